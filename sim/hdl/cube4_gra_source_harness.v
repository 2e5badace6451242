`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_gra_source_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of GRA's source, which both forms share: cube4_gra_lines
//   (tb/cube4_gra_lines) or cube4_gra_walk (tb/cube4_gra_walk). A Verilog
//   clock, the view registers as individual ports packed into the cfg bus
//   (CUBE4_VIEW_PACK), the sample input with a cube4_stream_check, the output
//   FIFO's credit as one port (every copy the same, as in cube4_gra) and the
//   source's interface as top-level ports.
//
// Parameters: as cube4_gra_lines and cube4_gra_walk (P 1..64, VOXEL_W 1..16,
//   WEIGHT_W 4..12, MAX_DIM 2..2048, MAX_SS_LOG2 0..3; CUBE4_UNIT_PARAMS);
//   WALK 0..1: 0 tests cube4_gra_lines, 1 cube4_gra_walk.
//
// Latency: that of the source (the ports connect straight to it).
//
// Ports
//   clk      out  the harness's clock (cube4_sim_clock, 10 ns)
//   rst      in   synchronous reset
//   cfg_*    in   view registers (golden/cube4/memory.py top_regs)
//   in_*     in   sample stream (cube4_tri's format; with WALK = 1 the walk's
//                 sample beats)
//   credit   in   the output FIFO's credit (all GRA_STEPS copies)
//   step .. c_edge, fend  out  as the source (CUBE4_GRA_STEP_PORTS)
// =============================================================================
module cube4_gra_source_harness #(
    `CUBE4_UNIT_PARAMS
    parameter integer VOXEL_W = 8,
    parameter integer WALK    = 0,
    `CUBE4_GRA_LAYOUT
) (
    `CUBE4_HARNESS_PORTS
    `CUBE4_GRA_STEP_PORTS(output)
    input  wire                  in_valid,
    output wire                  in_ready,
    input  wire [HDR_W-1:0]      in_hdr,
    input  wire [P*VOXEL_W-1:0]  in_sample,
    input  wire                  credit,
    output wire                  fend
);
    `CUBE4_HARNESS_VIEW

    generate
        `CUBE4_RANGE(g_bad_walk, "cube4_gra_source_harness", "WALK", WALK, 0, 1)
        if (WALK != 0) begin : g_walk
            cube4_gra_walk #(`CUBE4_GRA_PASS) u_src (.credit ({GRA_STEPS{credit}}), .in_eoss (1'b0), .*);
        end else begin : g_lines
            cube4_gra_lines #(`CUBE4_GRA_PASS) u_src (.credit ({GRA_STEPS{credit}}), .in_eoss (1'b0), .*);
        end
    endgenerate

    cube4_stream_check #(
        .NAME   ("gra source.in (sample beats)"),
        .DATA_W (HDR_W + P * VOXEL_W)
    ) u_chk_in (
        .clk (clk), .rst (rst), .valid (in_valid), .ready (in_ready), .data ({in_hdr, in_sample})
    );

endmodule
`default_nettype wire

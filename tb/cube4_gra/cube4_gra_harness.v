`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_gra_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_gra (tb/cube4_gra): a Verilog clock, the view
//   registers as individual ports packed into GRA's cfg bus (CUBE4_VIEW_PACK),
//   GRA's sample input and gradient output as top-level ports, which the
//   testbench drives and reads every cycle (golden sample beats in, random
//   gaps in valid; random ready out), and a cube4_stream_check on each of
//   the two streams.
//
// Parameters: as cube4_gra (P 1..64, VOXEL_W 1..16, WEIGHT_W 4..12,
//   MAX_DIM 2..2048, MAX_SS_LOG2 0..3, RECTS 0..1, BEATS 0..1, LABELS 0..1;
//   CUBE4_UNIT_PARAMS).
//
// Latency: that of cube4_gra (the ports connect straight to it).
//
// Ports
//   clk       out  the harness's clock (cube4_sim_clock, 10 ns)
//   rst       in   synchronous reset
//   cfg_*     in   view registers (golden/cube4/memory.py top_regs)
//   in_*      in   sample stream (cube4_tri's format, cube4_defs.vh)
//   out_*     out  gradient stream (cube4_gra's format, CUBE4_GRA_BEAT_PORTS)
// =============================================================================
module cube4_gra_harness #(
    `CUBE4_UNIT_PARAMS
    parameter integer VOXEL_W = 8,
    parameter integer RECTS   = 0,
    parameter integer BEATS   = 0,
    parameter integer LABELS  = 0,
    localparam integer GRAD_W = VOXEL_W + 5,
    localparam integer SMP_W  = VOXEL_W + ((LABELS != 0) ? 4 : 0)
) (
    `CUBE4_HARNESS_PORTS
    `CUBE4_GRA_BEAT_PORTS(output, out)
    input  wire                  in_valid,
    output wire                  in_ready,
    input  wire [HDR_W-1:0]      in_hdr,
    input  wire [P*SMP_W-1:0]    in_sample,
    input  wire                  in_eoss,
    output wire                  out_valid,
    input  wire                  out_ready
);
    `CUBE4_HARNESS_VIEW

    cube4_gra #(`CUBE4_GRA_PASS, .RECTS (RECTS), .BEATS (BEATS), .LABELS (LABELS)) u_gra (.*);

    cube4_stream_check #(
        .NAME   ("gra.in (samples)"),
        .DATA_W (HDR_W + P * SMP_W + 1)
    ) u_chk_in (
        .clk   (clk),
        .rst   (rst),
        .valid (in_valid),
        .ready (in_ready),
        .data  ({in_hdr, in_sample, in_eoss})
    );

    cube4_stream_check #(
        .NAME   ("gra.out (gradients)"),
        .DATA_W (HDR_W + P * SMP_W + 3 * P * GRAD_W)
    ) u_chk_out (
        .clk   (clk),
        .rst   (rst),
        .valid (out_valid),
        .ready (out_ready),
        .data  ({out_hdr, out_sample, out_gi, out_gj, out_gk})
    );

endmodule
`default_nettype wire

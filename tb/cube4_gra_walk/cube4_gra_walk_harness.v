`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_gra_walk_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_gra_walk (tb/cube4_gra_walk): a Verilog
//   clock, the view registers as individual ports packed into the cfg bus
//   (CUBE4_VIEW_PACK), the sample input with a cube4_stream_check, the
//   output FIFO's credit as one port (every copy the same, as in cube4_gra)
//   and the source's interface as top-level ports.
//
// Parameters: as cube4_gra_walk (P 1..64, VOXEL_W 1..16, WEIGHT_W 4..12,
//   MAX_DIM 2..2048, MAX_SS_LOG2 0..3).
//
// Latency: that of cube4_gra_walk (the ports connect straight to it).
//
// Ports
//   clk      out  the harness's clock (cube4_sim_clock, 10 ns)
//   rst      in   synchronous reset
//   cfg_*    in   view registers (golden/cube4/memory.py top_regs)
//   in_*     in   the walk's sample beats (cube4_tri's format)
//   credit   in   the output FIFO's credit (all GRA_STEPS copies)
//   step .. c_edge  out  as cube4_gra_walk
// =============================================================================
module cube4_gra_walk_harness #(
    parameter integer P           = 8,
    parameter integer VOXEL_W     = 8,
    parameter integer WEIGHT_W    = 8,
    parameter integer MAX_DIM     = 32,
    parameter integer MAX_SS_LOG2 = 0,
    `CUBE4_GEOMETRY,
    `CUBE4_VIEW_LAYOUT,
    `CUBE4_GRA_LAYOUT
) (
    output wire                  clk,
    input  wire                  rst,
    `CUBE4_VIEW_PORTS
    input  wire                  in_valid,
    output wire                  in_ready,
    input  wire [HDR_W-1:0]      in_hdr,
    input  wire [P*VOXEL_W-1:0]  in_sample,
    input  wire                  credit,
    output wire                  step,
    output wire                  sop,
    output wire                  fend,
    output wire [P*VOXEL_W-1:0]  x,
    output wire [P*VOXEL_W-1:0]  b1,
    output wire [P*VOXEL_W-1:0]  p1,
    output wire [P*VOXEL_W-1:0]  c,
    output wire [P*VOXEL_W-1:0]  p1b2,
    output wire [P*VOXEL_W-1:0]  p2b1,
    output wire [P*VOXEL_W-1:0]  p2b2,
    output wire [GRA_META_W-1:0] c_meta,
    output wire [P*GRA_NSEL-1:0] c_sel,
    output wire [1:0]            c_edge
);
    cube4_sim_clock u_clock (.clk (clk));

    wire [VIEW_W-1:0] cfg = `CUBE4_VIEW_PACK;

    cube4_gra_walk #(
        .P (P), .VOXEL_W (VOXEL_W), .WEIGHT_W (WEIGHT_W), .MAX_DIM (MAX_DIM), .MAX_SS_LOG2 (MAX_SS_LOG2)
    ) u_walk (
        .clk (clk), .rst (rst), .cfg (cfg),
        .in_valid (in_valid), .in_ready (in_ready), .in_hdr (in_hdr), .in_sample (in_sample),
        .credit ({GRA_STEPS{credit}}), .step (step), .sop (sop), .fend (fend),
        .x (x), .b1 (b1), .p1 (p1), .c (c), .p1b2 (p1b2), .p2b1 (p2b1), .p2b2 (p2b2),
        .c_meta (c_meta), .c_sel (c_sel), .c_edge (c_edge)
    );

    cube4_stream_check #(
        .NAME   ("gra_walk.in (walk beats)"),
        .DATA_W (HDR_W + P * VOXEL_W)
    ) u_chk_in (
        .clk (clk), .rst (rst), .valid (in_valid), .ready (in_ready), .data ({in_hdr, in_sample})
    );

endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_com_bpb_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_com_bpb (tb/cube4_com_bpb): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus
//   (CUBE4_VIEW_PACK), every other port of the unit as a top-level port.
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W (CUBE4_UNIT_PARAMS), AC_W,
//   RECTS as cube4_com_bpb; the slot width and the slice buffer's depth as
//   cube4_com derives them.
//
// Latency: that of cube4_com_bpb (the ports connect straight to it).
//
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports.
// =============================================================================
module cube4_com_bpb_harness #(
    `CUBE4_UNIT_PARAMS
    parameter integer AC_W  = 40,
    parameter integer RECTS = 0,
    localparam integer RW       = (MAX_DIM > 1) ? $clog2(MAX_DIM) : 1,
    localparam integer SP_W     = (RECTS != 0) ? RW + PB_W : ((MAX_DIM * NBMAX > 1) ? $clog2(MAX_DIM * NBMAX) : 1),
    localparam integer SB_DEPTH = (RECTS != 0) ? (1 << SP_W) : MAX_DIM * NBMAX,
    localparam integer PA       = P * AC_W
) (
    `CUBE4_HARNESS_PORTS
    input  wire [SP_W-1:0] rd_sp,
    input  wire [PB_W-1:0] pb_rd,
    input  wire [PB_W-1:0] pb_wr,
    input  wire            v2,
    input  wire            wr_en,
    input  wire [SP_W-1:0] wr_sp,
    input  wire [PA-1:0]   acc_q,
    input  wire            dyb4,
    input  wire            dkb4,
    input  wire            col1_4,
    output wire [PA-1:0]   s5_back,
    output wire [PA-1:0]   back_sh,
    output wire [PA-1:0]   prevb_sh
);
    `CUBE4_HARNESS_VIEW
    cube4_com_bpb #(
        `CUBE4_SLICE_PASS, .AC_W(AC_W), .SP_W(SP_W), .SB_DEPTH(SB_DEPTH), .RECTS(RECTS)
    ) u_bpb (.*);
endmodule
`default_nettype wire

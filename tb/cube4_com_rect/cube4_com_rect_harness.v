`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_rect_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_com_rect (tb/cube4_com_rect): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus
//   (CUBE4_VIEW_PACK), every other port of the unit as a top-level port (the
//   table entry rect_data as one word, CUBE4_RECT_LAYOUT).
//
// Parameters: P, MAX_DIM, ADDR_W as cube4_com_rect (MAX_SS_LOG2 = 0); the slot
//   width as cube4_com derives it.
//
// Latency: that of cube4_com_rect (the ports connect straight to it).
//
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports.
// =============================================================================
module cube4_com_rect_harness #(
    parameter integer P           = 5,
    parameter integer MAX_DIM     = 32,
    parameter integer MAX_SS_LOG2 = 0,
    parameter integer WEIGHT_W    = 8,
    parameter integer ADDR_W      = 16,
    `CUBE4_GEOMETRY,
    `CUBE4_VIEW_LAYOUT,
    `CUBE4_RECT_LAYOUT,
    localparam integer RW    = (MAX_DIM > 1) ? $clog2(MAX_DIM) : 1,
    localparam integer SP_W  = RW + PB_W,
    localparam integer SPF_W = 9 * SP_W,
    localparam integer PI_W  = P * IW
) (
    output wire              clk,
    input  wire              rst,
    `CUBE4_VIEW_PORTS
    input  wire              rect_we,
    input  wire [M_W-1:0]    rect_addr,
    input  wire [RECT_W-1:0] rect_data,
    input  wire              take,
    input  wire [HDR_W-1:0]  in_hdr,
    input  wire              step,
    input  wire [9:1]        v_fly,
    input  wire [SPF_W-1:0]  sp_fly,
    input  wire [M_W-1:0]    r0_m,
    input  wire [DIM_W-1:0]  r0_j,
    input  wire [PB_W-1:0]   r0_pb,
    input  wire              dxb,
    input  wire              dyb,
    input  wire [PI_W-1:0]   ipos,
    input  wire [PI_W-1:0]   f1_ipos,
    input  wire [IW-1:0]     f1_j,
    input  wire              f1_dxf,
    input  wire              f1_dyf,
    output wire [SP_W-1:0]   pos_sp,
    output wire [PB_W-1:0]   pos_pb,
    output wire              hazard,
    output wire [P-1:0]      fresh,
    output wire [P-1:0]      nx_in,
    output wire [DIM_W-1:0]  stx,
    output wire [DIM_W-1:0]  sty,
    output wire              col1_4
);
    cube4_sim_clock u_clock (.clk (clk));
    wire [VIEW_W-1:0] cfg = `CUBE4_VIEW_PACK;
    cube4_com_rect #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2),
        .ADDR_W(ADDR_W), .SP_W(SP_W)
    ) u_rect (
        .clk(clk), .rst(rst), .cfg(cfg),
        .rect_we(rect_we), .rect_addr(rect_addr), .rect_data(rect_data),
        .take(take), .in_hdr(in_hdr), .step(step), .v_fly(v_fly), .sp_fly(sp_fly),
        .r0_m(r0_m), .r0_j(r0_j), .r0_pb(r0_pb), .dxb(dxb), .dyb(dyb), .ipos(ipos),
        .f1_ipos(f1_ipos), .f1_j(f1_j), .f1_dxf(f1_dxf), .f1_dyf(f1_dyf),
        .pos_sp(pos_sp), .pos_pb(pos_pb), .hazard(hazard), .fresh(fresh), .nx_in(nx_in),
        .stx(stx), .sty(sty), .col1_4(col1_4));
endmodule
`default_nettype wire

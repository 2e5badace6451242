`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_walk_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_com_walk (tb/cube4_com_walk): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus
//   (CUBE4_VIEW_PACK), every other port of the unit as a top-level port.
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W as cube4_com_walk; the slot
//   width as cube4_com derives it.
//
// Latency: that of cube4_com_walk (the ports connect straight to it).
//
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports.
// =============================================================================
module cube4_com_walk_harness #(
    parameter integer P           = 5,
    parameter integer MAX_DIM     = 32,
    parameter integer MAX_SS_LOG2 = 0,
    parameter integer WEIGHT_W    = 8,
    `CUBE4_GEOMETRY,
    `CUBE4_VIEW_LAYOUT,
    localparam integer SP_W = (MAX_DIM * NBMAX > 1) ? $clog2(MAX_DIM * NBMAX) : 1,
    localparam integer PI_W = P * IW,
    localparam integer PH_W = PHASE_W
) (
    output wire             clk,
    input  wire             rst,
    `CUBE4_VIEW_PORTS
    input  wire [1:0]       step_c,
    input  wire             take,
    input  wire             step,
    input  wire [8:1]       v_fly,
    input  wire             sop,
    input  wire             first,
    input  wire [M_W-1:0]   r0_m,
    input  wire [DIM_W-1:0] r0_j,
    input  wire             dxb,
    input  wire             dyb,
    input  wire [PI_W-1:0]  ipos,
    input  wire [PI_W-1:0]  f1_ipos,
    input  wire [IW-1:0]    f1_j,
    input  wire             f1_dxf,
    input  wire             f1_dyf,
    output wire [SP_W-1:0]  pos_sp,
    output wire [PB_W-1:0]  pos_pb,
    output wire             hazard,
    output wire [P-1:0]     fresh,
    output wire [P-1:0]     nx_in,
    output wire [DIM_W-1:0] stx,
    output wire [DIM_W-1:0] sty,
    output wire [PH_W-1:0]  ph_x,
    output wire [PH_W-1:0]  ph_y,
    output wire [PH_W-1:0]  phn_x,
    output wire [PH_W-1:0]  phn_y,
    output wire             f1_last,
    output wire             f1_wxn,
    output wire             f1_wyn
);
    cube4_sim_clock u_clock (.clk (clk));
    wire [VIEW_W-1:0] cfg = `CUBE4_VIEW_PACK;
    cube4_com_walk #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .SP_W(SP_W)
    ) u_walk (
        .clk(clk), .rst(rst), .cfg(cfg),
        .step_c(step_c), .take(take), .step(step), .v_fly(v_fly),
        .sop(sop), .first(first), .r0_m(r0_m), .r0_j(r0_j), .dxb(dxb), .dyb(dyb), .ipos(ipos),
        .f1_ipos(f1_ipos), .f1_j(f1_j), .f1_dxf(f1_dxf), .f1_dyf(f1_dyf),
        .pos_sp(pos_sp), .pos_pb(pos_pb), .hazard(hazard), .fresh(fresh), .nx_in(nx_in),
        .stx(stx), .sty(sty), .ph_x(ph_x), .ph_y(ph_y), .phn_x(phn_x), .phn_y(phn_y),
        .f1_last(f1_last), .f1_wxn(f1_wxn), .f1_wyn(f1_wyn));
endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_plw_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_com_plw (tb/cube4_com_plw): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus
//   (CUBE4_VIEW_PACK), every other port of the unit as a top-level port.
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W, VOXEL_W, ALPHA_W as cube4_com_plw.
//
// Latency: that of cube4_com_plw (the ports connect straight to it).
//
// Ports: clk out (cube4_sim_clock, 10 ns); rst (unused by the unit), cfg_*
//   and the unit's ports.
// =============================================================================
module cube4_com_plw_harness #(
    parameter integer P           = 5,
    parameter integer MAX_DIM     = 32,
    parameter integer MAX_SS_LOG2 = 0,
    parameter integer WEIGHT_W    = 8,
    parameter integer VOXEL_W     = 8,
    parameter integer ALPHA_W     = 12,
    `CUBE4_GEOMETRY,
    `CUBE4_VIEW_LAYOUT,
    localparam integer PI_W  = P * IW,
    localparam integer PH_W  = PHASE_W,
    localparam integer COL_W = 4 * ALPHA_W,
    localparam integer PV_W  = P * VOXEL_W,
    localparam integer PA_W  = P * ALPHA_W
) (
    output wire             clk,
    input  wire             rst,
    `CUBE4_VIEW_PORTS
    input  wire             step,
    input  wire             first,
    input  wire [PH_W-1:0]  ph_x,
    input  wire [PH_W-1:0]  ph_y,
    input  wire [PH_W-1:0]  phn_x,
    input  wire [PH_W-1:0]  phn_y,
    input  wire [M_W-1:0]   r0_m,
    input  wire [DIM_W-1:0] r0_j,
    input  wire             dxb,
    input  wire             dyb,
    input  wire [PI_W-1:0]  ipos,
    input  wire [PI_W-1:0]  f1_ipos,
    input  wire [IW-1:0]    f1_j,
    input  wire             f1_dxf,
    input  wire             f1_dyf,
    input  wire             f1_last,
    input  wire             f1_wxn,
    input  wire             f1_wyn,
    input  wire             lut_we,
    input  wire [VOXEL_W-1:0] lut_addr,
    input  wire [COL_W-1:0] lut_data,
    input  wire [PV_W-1:0]  smp,
    input  wire             mode_ext,
    input  wire [PA_W-1:0]  a3,
    output wire [PA_W-1:0]  a_w
);
    cube4_sim_clock u_clock (.clk (clk));
    wire [VIEW_W-1:0] cfg = `CUBE4_VIEW_PACK;
    wire unused_rst = rst;
    cube4_com_plw #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2),
        .VOXEL_W(VOXEL_W), .ALPHA_W(ALPHA_W)
    ) u_plw (
        .clk(clk), .cfg(cfg), .step(step), .first(first),
        .ph_x(ph_x), .ph_y(ph_y), .phn_x(phn_x), .phn_y(phn_y),
        .r0_m(r0_m), .r0_j(r0_j), .dxb(dxb), .dyb(dyb), .ipos(ipos),
        .f1_ipos(f1_ipos), .f1_j(f1_j), .f1_dxf(f1_dxf), .f1_dyf(f1_dyf),
        .f1_last(f1_last), .f1_wxn(f1_wxn), .f1_wyn(f1_wyn),
        .lut_we(lut_we), .lut_addr(lut_addr), .lut_data(lut_data),
        .smp(smp), .mode_ext(mode_ext), .a3(a3), .a_w(a_w));
endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_ctl_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_cfb_ctl (tb/cube4_cfb_ctl): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus (CUBE4_VIEW_PACK), every other port of the unit as a top-level port (the entries as words,
//   CUBE4_RECT_LAYOUT).
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W (cube4_unit_params.vh), ADDR_W
//   as cube4_cfb_ctl.
// Latency: that of cube4_cfb_ctl (the ports connect straight to it).
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports.
// =============================================================================
module cube4_cfb_ctl_harness #(
    `include "cube4_unit_params.vh"
    parameter integer ADDR_W = 16,
    `CUBE4_CFB_LAYOUT
) (
    output wire clk, input wire rst,
    `CUBE4_VIEW_PORTS
    input  wire start, input wire busy, input wire advance,
    input  wire [RECT_W-1:0] rt_cur, input wire [RECT_W-1:0] rt_nxt,
    input  wire [M_W-1:0] m, input wire k0_odd, input wire [CFB_R_W-1:0] r,
    input  wire [DIM_W-1:0] j, input wire [PB_W-1:0] pb, input wire [SB_W-1:0] sb,
    input  wire last_pb, input wire last_j, input wire lower_mem, input wire upper_mem,
    input  wire [LANE_W-1:0] skew_pas, input wire [LANE_W-1:0] skew_vrt,
    input  wire [WEIGHT_W-1:0] wx, input wire [WEIGHT_W-1:0] wy, input wire [WEIGHT_W-1:0] wz,
    input  wire [3:0] steps,
    output wire idle, output wire go, output wire next_pass, output wire pass_done,
    output wire beat, output wire row, output wire flush_row,
    output wire issue, output wire [CFB_F1_W-1:0] fields,
    output wire use_prev, output wire [LANE_W-1:0] skew_out,
    output wire [DIM_W-1:0] p_ilo, output wire [DIM_W-1:0] p_iin, output wire [DIM_W-1:0] p_ihi,
    output wire rowv, output wire rowin, output wire rd
);
    cube4_sim_clock u_clock (.clk (clk));
    wire [VIEW_W-1:0] cfg = `CUBE4_VIEW_PACK;
    cube4_cfb_ctl #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W)
    ) u_ctl (.*);
endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_box_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_cfb_box (tb/cube4_cfb_box): a Verilog clock,
//   the view and address registers as ports packed into the unit's buses
//   (CUBE4_VIEW_PACK, CUBE4_ADDR_PACK), every other port of the unit as a top-level port (the entries as words,
//   CUBE4_RECT_LAYOUT).
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W (cube4_unit_params.vh), ADDR_W
//   as cube4_cfb_box.
// Latency: that of cube4_cfb_box (the ports connect straight to it).
// Ports: clk out (cube4_sim_clock, 10 ns); cfg_* and the unit's ports (the clock only paces the
//   testbench: the unit is combinational).
// =============================================================================
module cube4_cfb_box_harness #(
    `include "cube4_unit_params.vh"
    parameter integer ADDR_W = 16,
    `CUBE4_CFB_LAYOUT
) (
    output wire clk,
    `CUBE4_VIEW_PORTS
    `CUBE4_ADDR_PORTS
    input  wire last_pass,
    output wire [RECT_W-1:0] rt_cur, output wire [RECT_W-1:0] rt_nxt
);
    cube4_sim_clock u_clock (.clk (clk));
    wire [VIEW_W-1:0]    cfg      = `CUBE4_VIEW_PACK;
    wire [ADR_W_ALL-1:0] cfg_addr = `CUBE4_ADDR_PACK;
    cube4_cfb_box #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W)
    ) u_box (.*);
endmodule
`default_nettype wire

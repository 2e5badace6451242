`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_cfb_box_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_cfb_box (tb/cube4_cfb_box): a Verilog clock,
//   the view and address registers as ports packed into the unit's buses
//   (CUBE4_VIEW_PACK, CUBE4_ADDR_PACK), every other port of the unit as a top-level port (the entries as words,
//   CUBE4_RECT_LAYOUT).
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W, ADDR_W, RECTS (0)
//   as cube4_cfb_box (CUBE4_CFB_UNIT_PARAMS, cube4_unit_ports.vh).
// Latency: that of cube4_cfb_box (the ports connect straight to it).
// Ports: clk out (cube4_sim_clock, 10 ns); cfg_* and the unit's ports (the clock only paces the
//   testbench: the unit is combinational).
// =============================================================================
module cube4_cfb_box_harness #(
    `CUBE4_CFB_UNIT_PARAMS(0)
) (
    output wire clk,
    `CUBE4_VIEW_PORTS
    `CUBE4_ADDR_PORTS
    input  wire last_pass,
    output wire [RECT_W-1:0] rt_cur, output wire [RECT_W-1:0] rt_nxt
);
    `CUBE4_HARNESS_VIEW
    `CUBE4_HARNESS_ADDR
    cube4_cfb_box #(`CUBE4_CFB_PASS) u_box (.*);
endmodule
`default_nettype wire

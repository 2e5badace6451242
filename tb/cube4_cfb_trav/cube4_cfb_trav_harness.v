`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_cfb_trav_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_cfb_trav (tb/cube4_cfb_trav): a Verilog clock,
//   the view and address registers as ports packed into the unit's buses
//   (CUBE4_VIEW_PACK, CUBE4_ADDR_PACK), every other port of the unit as a
//   top-level port (the rectangle entries as words, CUBE4_RECT_LAYOUT).
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W, ADDR_W, RECTS (1)
//   as cube4_cfb_trav (RECTS = 0: the box's entry only; CUBE4_CFB_UNIT_PARAMS).
// Latency: that of cube4_cfb_trav (the ports connect straight to it).
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports.
// =============================================================================
module cube4_cfb_trav_harness #(
    `CUBE4_CFB_UNIT_PARAMS(1)
) (
    `CUBE4_HARNESS_PORTS
    `CUBE4_ADDR_PORTS
    `CUBE4_CFB_TRAV_PORTS
);
    `CUBE4_HARNESS_VIEW
    `CUBE4_HARNESS_ADDR
    cube4_cfb_trav #(`CUBE4_CFB_PASS) u_trav (.*);
endmodule
`default_nettype wire

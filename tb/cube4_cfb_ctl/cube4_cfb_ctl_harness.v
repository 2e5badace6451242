`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_cfb_ctl_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_cfb_ctl (tb/cube4_cfb_ctl): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus (CUBE4_VIEW_PACK), every other port of the unit as a top-level port (the entries as words,
//   CUBE4_RECT_LAYOUT).
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W, ADDR_W, RECTS (1)
//   as cube4_cfb_ctl (RECTS = 0: the box's entry only; CUBE4_CFB_UNIT_PARAMS).
// Latency: that of cube4_cfb_ctl (the ports connect straight to it).
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports.
// =============================================================================
module cube4_cfb_ctl_harness #(
    `CUBE4_CFB_UNIT_PARAMS(1)
) (
    `CUBE4_HARNESS_PORTS
    `CUBE4_CFB_CTL_PORTS
);
    `CUBE4_HARNESS_VIEW
    cube4_cfb_ctl #(`CUBE4_CFB_PASS) u_ctl (.*);
endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_cfb_tmpl_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_cfb_tmpl (tb/cube4_cfb_tmpl): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus (CUBE4_VIEW_PACK), every other port of the unit as a top-level port.
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W, ADDR_W, RECTS (0)
//   as cube4_cfb_tmpl (CUBE4_CFB_UNIT_PARAMS, cube4_unit_ports.vh).
// Latency: that of cube4_cfb_tmpl (the ports connect straight to it).
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports.
// =============================================================================
module cube4_cfb_tmpl_harness #(
    `CUBE4_CFB_UNIT_PARAMS(0)
) (
    `CUBE4_HARNESS_PORTS
    input  wire idle, input wire next_pass, input wire [CFB_R_W-1:0] r,
    output wire [WEIGHT_W-1:0] wx, output wire [WEIGHT_W-1:0] wy, output wire [WEIGHT_W-1:0] wz,
    output wire [3:0] steps
);
    `CUBE4_HARNESS_VIEW
    cube4_cfb_tmpl #(`CUBE4_CFB_PASS) u_tmpl (.*);
endmodule
`default_nettype wire

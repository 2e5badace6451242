`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_cfb_addr_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_cfb_addr (tb/cube4_cfb_addr): a Verilog clock,
//   the view and address registers as ports packed into the unit's buses
//   (CUBE4_VIEW_PACK, CUBE4_ADDR_PACK), every other port of the unit as a top-level port.
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W, ADDR_W, RECTS (0)
//   as cube4_cfb_addr (CUBE4_CFB_UNIT_PARAMS, cube4_unit_ports.vh).
// Latency: that of cube4_cfb_addr (the ports connect straight to it).
// Ports: clk out (cube4_sim_clock, 10 ns); cfg_* and the unit's ports.
// =============================================================================
module cube4_cfb_addr_harness #(
    `CUBE4_CFB_UNIT_PARAMS(0)
) (
    output wire clk,
    `CUBE4_VIEW_PORTS
    `CUBE4_ADDR_PORTS
    input  wire advance, input wire [LANE_W-1:0] skew_rd,
    input  wire [ADDR_W-1:0] aj, input wire [ADDR_W-1:0] ak, input wire [ADDR_W-1:0] pbx,
    output wire [P*LANE_W-1:0] t1, output wire [P*ADDR_W-1:0] addr
);
    `CUBE4_HARNESS_VIEW
    `CUBE4_HARNESS_ADDR
    cube4_cfb_addr #(`CUBE4_CFB_PASS) u_addr (.*);
endmodule
`default_nettype wire

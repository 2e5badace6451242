`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_cfb_rect_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_cfb_rect (tb/cube4_cfb_rect): a Verilog clock,
//   the table's write port with one port per field (rt_*, packed as
//   CUBE4_RECT_PACK), every other port of the unit as a top-level port (the entries read as
//   words, CUBE4_RECT_LAYOUT).
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W, ADDR_W, RECTS (0)
//   as cube4_cfb_rect (CUBE4_CFB_UNIT_PARAMS, cube4_unit_ports.vh).
// Latency: that of cube4_cfb_rect (the ports connect straight to it).
// Ports: clk out (cube4_sim_clock, 10 ns); rt_* and the unit's ports.
// =============================================================================
module cube4_cfb_rect_harness #(
    `CUBE4_CFB_UNIT_PARAMS(0)
) (
    output wire clk,
    `CUBE4_RECT_PORTS
    input  wire rect_we, input wire [M_W-1:0] rect_addr,
    input  wire idle, input wire go, input wire pass_done, input wire [M_W-1:0] m,
    output wire [RECT_W-1:0] rt_cur, output wire [RECT_W-1:0] rt_nxt
);
    cube4_sim_clock u_clock (.clk (clk));
    wire [RECT_W-1:0] rect_data = `CUBE4_RECT_PACK;
    cube4_cfb_rect #(`CUBE4_CFB_PASS) u_rect (.*);
endmodule
`default_nettype wire

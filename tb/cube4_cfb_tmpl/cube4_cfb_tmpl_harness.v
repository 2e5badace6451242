`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_tmpl_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_cfb_tmpl (tb/cube4_cfb_tmpl): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus (CUBE4_VIEW_PACK), every other port of the unit as a top-level port.
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W (cube4_unit_params.vh), ADDR_W
//   as cube4_cfb_tmpl.
// Latency: that of cube4_cfb_tmpl (the ports connect straight to it).
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports.
// =============================================================================
module cube4_cfb_tmpl_harness #(
    `include "cube4_unit_params.vh"
    parameter integer ADDR_W = 16,
    `CUBE4_CFB_LAYOUT
) (
    output wire clk, input wire rst,
    `CUBE4_VIEW_PORTS
    input  wire idle, input wire next_pass, input wire [CFB_R_W-1:0] r,
    output wire [WEIGHT_W-1:0] wx, output wire [WEIGHT_W-1:0] wy, output wire [WEIGHT_W-1:0] wz,
    output wire [3:0] steps
);
    cube4_sim_clock u_clock (.clk (clk));
    wire [VIEW_W-1:0] cfg = `CUBE4_VIEW_PACK;
    cube4_cfb_tmpl #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W)
    ) u_tmpl (.*);
endmodule
`default_nettype wire

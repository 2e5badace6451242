`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_trav_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_cfb_trav (tb/cube4_cfb_trav): a Verilog clock,
//   the view and address registers as ports packed into the unit's buses
//   (CUBE4_VIEW_PACK, CUBE4_ADDR_PACK), every other port of the unit as a
//   top-level port (the rectangle entries as words, CUBE4_RECT_LAYOUT).
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W (cube4_unit_params.vh), ADDR_W,
//   RECTS as cube4_cfb_trav (RECTS = 0: the box's entry only).
// Latency: that of cube4_cfb_trav (the ports connect straight to it).
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports.
// =============================================================================
module cube4_cfb_trav_harness #(
    `include "cube4_unit_params.vh"
    parameter integer ADDR_W = 16,
    parameter integer RECTS  = 1,
    `CUBE4_CFB_LAYOUT
) (
    output wire clk, input wire rst,
    `CUBE4_VIEW_PORTS
    `CUBE4_ADDR_PORTS
    `CUBE4_CFB_TRAV_PORTS
);
    cube4_sim_clock u_clock (.clk (clk));
    wire [VIEW_W-1:0]    cfg      = `CUBE4_VIEW_PACK;
    wire [ADR_W_ALL-1:0] cfg_addr = `CUBE4_ADDR_PACK;
    cube4_cfb_trav #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W),
        .RECTS(RECTS)
    ) u_trav (.*);
endmodule
`default_nettype wire

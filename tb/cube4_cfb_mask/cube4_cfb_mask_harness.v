`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_mask_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_cfb_mask (tb/cube4_cfb_mask): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus (CUBE4_VIEW_PACK);
//   cube4_stream_check watches the request stream, every other port of the unit as a top-level port (rt_cur as a word,
//   CUBE4_RECT_LAYOUT).
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W (cube4_unit_params.vh), ADDR_W,
//   RECTS as cube4_cfb_mask (RECTS = 0: the box's entry only).
// Latency: that of cube4_cfb_mask (the ports connect straight to it).
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports.
// =============================================================================
module cube4_cfb_mask_harness #(
    `include "cube4_unit_params.vh"
    parameter integer ADDR_W = 16,
    parameter integer RECTS  = 1,
    `CUBE4_CFB_LAYOUT
) (
    output wire clk, input wire rst,
    `CUBE4_VIEW_PORTS
    `CUBE4_CFB_MASK_PORTS
);
    cube4_sim_clock u_clock (.clk (clk));
    wire [VIEW_W-1:0] cfg = `CUBE4_VIEW_PACK;
    cube4_stream_check #(.NAME ("cfb_mask.req"), .DATA_W (P + TAG_W)) u_chk_req (
        .clk (clk), .rst (rst), .valid (req_valid), .ready (req_ready), .data ({req_rden, req_tag}));
    cube4_cfb_mask #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W),
        .RECTS(RECTS)
    ) u_mask (.*);
endmodule
`default_nettype wire

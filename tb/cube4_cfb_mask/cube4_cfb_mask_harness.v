`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_cfb_mask_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_cfb_mask (tb/cube4_cfb_mask): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus (CUBE4_VIEW_PACK);
//   cube4_stream_check watches the request stream, every other port of the unit as a top-level port (rt_cur as a word,
//   CUBE4_RECT_LAYOUT).
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W, ADDR_W, RECTS (1)
//   as cube4_cfb_mask (RECTS = 0: the box's entry only; CUBE4_CFB_UNIT_PARAMS).
// Latency: that of cube4_cfb_mask (the ports connect straight to it).
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports.
// =============================================================================
module cube4_cfb_mask_harness #(
    `CUBE4_CFB_UNIT_PARAMS(1)
) (
    `CUBE4_HARNESS_PORTS
    `CUBE4_CFB_MASK_PORTS
);
    `CUBE4_HARNESS_VIEW
    cube4_stream_check #(.NAME ("cfb_mask.req"), .DATA_W (P + TAG_W)) u_chk_req (
        .clk (clk), .rst (rst), .valid (req_valid), .ready (&req_ready), .data ({req_rden, req_tag}));
    cube4_cfb_mask #(`CUBE4_CFB_PASS) u_mask (.*);
endmodule
`default_nettype wire

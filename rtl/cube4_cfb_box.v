`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_box
// -----------------------------------------------------------------------------
// Purpose
//   The pass's rectangle of cube4_cfb without slice rectangles (RECTS = 0):
//   every pass walks the whole box (rows 0 .. NJ-1, partial beams 0 .. NB-1,
//   positions 0 .. NI-1, all inside), as an entry of CUBE4_RECT_LAYOUT built
//   from the view and address registers, so that the control and traversal
//   units read one layout in both builds. Only the box's last pass flushes and
//   ends the frame (FLUSH = LAST = last_pass); no pass is EMPTY. The next pass's
//   entry is the same box (rt_nxt = rt_cur; its FLUSH and LAST are not read).
//   COM's fields (INS, J_HI, I_HIN, STX, STY) are zero.
//
// Parameters (CUBE4_CFB_PARAMS; ranges as cube4_cfb)
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2, ADDR_W.
//
// Latency: combinational.
//
// Ports
//   cfg, cfg_addr  in  view and address registers (NI, NJ, NB, I flip, J_R0,
//                  J_A0, I_A0)
//   last_pass    in   pass m is the last (cube4_cfb_trav)
//   rt_cur, rt_nxt  out  [RECT_W] the box, as pass m's and the next pass's entry
//
// Bit growth and rounding: none.
// =============================================================================
module cube4_cfb_box #(`CUBE4_CFB_PARAMS) (
    input  wire [VIEW_W-1:0] cfg, input wire [ADR_W_ALL-1:0] cfg_addr,
    input  wire last_pass,
    output wire [RECT_W-1:0] rt_cur, output wire [RECT_W-1:0] rt_nxt
);
    `CUBE4_VIEW_FIELDS(cfg);
    `CUBE4_ADDR_FIELDS(cfg_addr);
    wire [ADDR_W-1:0] pbx_box = cfg_flip_i ? cfg_i_a0 : '0;
    assign rt_cur = {1'b0, {4{DIM_W'(0)}},   // COM's fields
                     cfg_nj - 1'b1, DIM_W'(0), SB_W'(1), SB_W'(0), IW'(0), pbx_box, cfg_j_r0,
                     cfg_j_a0,
                     cfg_ni, DIM_W'(0), DIM_W'(0),
                     PB_W'(cfg_nb - 1'b1), PB_W'(0),
                     DIM_W'(0), cfg_nj - 1'b1, DIM_W'(0), last_pass, last_pass, 1'b0};
    assign rt_nxt = rt_cur;
endmodule
`default_nettype wire

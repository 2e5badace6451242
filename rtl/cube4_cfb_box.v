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
    // the constant fields (CFB_BOX_CONST, cube4_defs.vh) and those from the registers
    wire [DIM_W-1:0] jl = cfg_nj - 1'b1;
    assign rt_cur = CFB_BOX_CONST | ((RECT_W)'(last_pass) << RT_FLUSH) | ((RECT_W)'(last_pass) << RT_LAST)
                  | ((RECT_W)'(jl) << RT_JL) | ((RECT_W)'(jl) << RT_TJL) | ((RECT_W)'(cfg_ni) << RT_IHI)
                  | ((RECT_W)'(PB_W'(cfg_nb - 1'b1)) << RT_PBL) | ((RECT_W)'(cfg_j_a0) << RT_AJ0)
                  | ((RECT_W)'(cfg_j_r0) << RT_RJ0) | ((RECT_W)'(pbx_box) << RT_PBX0);
    assign rt_nxt = rt_cur;
endmodule
`default_nettype wire

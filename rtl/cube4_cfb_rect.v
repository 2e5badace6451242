`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_rect
// -----------------------------------------------------------------------------
// Purpose
//   The rectangle-table reader of cube4_cfb (RECTS = 1; numerics.md section
//   18): the host writes one entry per sample slice (CUBE4_RECT_LAYOUT) while
//   idle; the unit gives the entry of pass m (rt_cur) and of the pass that
//   follows it (rt_nxt). The table is read one pass ahead: the RAM's address
//   is the index of the pass that holds after the next edge, plus one, so the
//   next entry is always in its output register (while idle: entry 0, and
//   entry 1 in the cycle that starts the frame).
//
// Parameters (CUBE4_CFB_PARAMS; ranges as cube4_cfb)
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2 (a frame with rectangles has S = 1),
//   ADDR_W (the layout's address fields).
//   The table has MAX_DIM entries: with S = 1, M <= MAX_DIM (the reads past
//   the last pass's entry wrap, and are never used).
//
// Latency
//   rt_nxt: the RAM's registered output (cube4_sdp_ram, one cycle from the
//   address); rt_cur: a register that takes rt_nxt while idle and at
//   pass_done.
//
// Ports
//   clk          clock (no reset: the table and rt_cur hold data only)
//   rect_we, rect_addr [M_W], rect_data [RECT_W]   in  the table's write port
//   idle, go, pass_done   in  the control unit's (cube4_cfb_ctl)
//   m            in   [M_W] the pass (cube4_cfb_trav)
//   rt_cur, rt_nxt  out  [RECT_W] the entries of pass m and of the next pass
//
// Bit growth and rounding: none (a table).
// =============================================================================
module cube4_cfb_rect #(`CUBE4_CFB_PARAMS) (
    input  wire clk,
    input  wire rect_we, input wire [M_W-1:0] rect_addr, input wire [RECT_W-1:0] rect_data,
    input  wire idle, input wire go, input wire pass_done, input wire [M_W-1:0] m,
    output wire [RECT_W-1:0] rt_cur, output wire [RECT_W-1:0] rt_nxt
);
    localparam integer TAW = (MAX_DIM > 1) ? $clog2(MAX_DIM) : 1;
    wire [M_W-1:0] m_after = idle ? '0 : (pass_done ? m + 1'b1 : m);
    wire [M_W-1:0] rd_addr = (idle && !go) ? '0 : m_after + 1'b1;
    cube4_sdp_ram #(.DATA_W (RECT_W), .DEPTH (MAX_DIM)) u_table (
        .clk     (clk),
        .rd_en   (1'b1), .out_en (1'b0),
        .rd_addr (TAW'(rd_addr)),
        .rd_data (rt_nxt),
        .wr_en   (rect_we),
        .wr_addr (TAW'(rect_addr)),
        .wr_data (rect_data)
    );
    wire unused_tbl_addr = ^{rd_addr, rect_addr};   // the bits above TAW (M_W >= TAW)

    reg [RECT_W-1:0] rt_q;
    always @(posedge clk) begin
        if (idle || pass_done) rt_q <= rt_nxt;
    end
    assign rt_cur = rt_q;
endmodule
`default_nettype wire

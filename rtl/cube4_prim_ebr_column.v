`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_prim_ebr_column
// -----------------------------------------------------------------------------
// Purpose
//   A column of BANKS block RAMs of one shape (cube4_prim_ebr) stacked in
//   depth: word a lives in block a >> BLK_AW at address a mod 2^BLK_AW. The
//   write goes to its block only; every block reads, and the word of the
//   block the read addressed is picked after the blocks' output registers by
//   the read address's top bits, registered beside the block's two read
//   registers. With BANKS = 1 it is one cube4_prim_ebr, no multiplexer. The
//   vendor layer's RAM forms (rtl/ecp5/cube4_sdp_ram.v,
//   rtl/ecp5/cube4_dual_read_ram.v) build their words from such columns
//   (rtl/ecp5/cube4_ebr_plan.vh chooses the shapes and depths).
//
// Parameters
//   SHAPE_W the blocks' port width: 1, 2, 4, 9 or 18.  Default 18.
//   W       bits used of the port: 1..SHAPE_W.       Default 18.
//   AW      the column's address bits: 1..BLK_AW + 2. Default 10.
//   BLK_AW  a block's address bits in its shape: 14, 13, 12, 11, 10 for
//           SHAPE_W 1, 2, 4, 9, 18.                   Default 10.
//   BANKS   blocks in depth: 1 when AW <= BLK_AW, else
//           2..2^(AW - BLK_AW) (the words above BANKS 2^BLK_AW unused).
//                                                    1..4.  Default 1.
//   READ_A  1: port A reads too (as cube4_prim_ebr).  0..1.  Default 0.
//
// Latency
//   As cube4_prim_ebr: a read is 2 cycles on either port (both registers
//   and the bank choice advance with the port's enables: port B's output
//   register and the choice beside it with b_oe); a write is seen by
//   a read one edge after it; port A in a cycle with a_we reads in no block
//   (every block's registers, and the choice, keep their words).
//
// Ports: as cube4_prim_ebr (a_addr, b_addr [AW]).
//
// Bit growth and rounding: none. No reset: the contents are data.
// =============================================================================
module cube4_prim_ebr_column #(
    parameter integer SHAPE_W = 18,
    parameter integer W       = 18,
    parameter integer AW      = 10,
    parameter integer BLK_AW  = 10,
    parameter integer BANKS   = 1,
    parameter integer READ_A  = 0
) (
    input  wire          clk,
    input  wire          a_en,
    input  wire          a_we,
    input  wire [AW-1:0] a_addr,
    input  wire [W-1:0]  a_wd,
    output wire [W-1:0]  a_rd,
    input  wire          b_en,
    input  wire          b_oe,
    input  wire [AW-1:0] b_addr,
    output wire [W-1:0]  b_rd
);
    localparam integer BAW = (AW < BLK_AW) ? AW : BLK_AW;    // a block's address bits in use
    generate
        `CUBE4_RANGE(g_bad_banks, "cube4_prim_ebr_column", "BANKS", BANKS, 1, 4)
        if ((BANKS == 1) != (AW <= BLK_AW) || (AW > BLK_AW && BANKS > (1 << (AW - BLK_AW)))) begin : g_bad_depth
            $error("cube4_prim_ebr_column: BANKS = %0d does not match AW = %0d, BLK_AW = %0d", BANKS, AW, BLK_AW);
        end
        if (BANKS == 1) begin : g_one
            cube4_prim_ebr #(.SHAPE_W(SHAPE_W), .W(W), .AW(BAW), .READ_A(READ_A)) u_ebr (
                .clk(clk), .a_en(a_en), .a_we(a_we), .a_addr(a_addr[BAW-1:0]), .a_wd(a_wd), .a_rd(a_rd),
                .b_en(b_en), .b_oe(b_oe), .b_addr(b_addr[BAW-1:0]), .b_rd(b_rd));
        end else begin : g_stack
            localparam integer SEL_W = AW - BLK_AW;
            wire [SEL_W-1:0] a_top = a_addr[AW-1:BLK_AW];
            wire [SEL_W-1:0] b_top = b_addr[AW-1:BLK_AW];
            wire             a_rd_en = a_en && !a_we;
            wire [BANKS*W-1:0] a_q, b_q;       // bank d at [d*W +: W]
            genvar d;
            for (d = 0; d < BANKS; d = d + 1) begin : g_bank
                cube4_prim_ebr #(.SHAPE_W(SHAPE_W), .W(W), .AW(BAW), .READ_A(READ_A)) u_ebr (
                    .clk(clk), .a_en(a_rd_en), .a_we(a_we && (a_top == SEL_W'(d))),
                    .a_addr(a_addr[BAW-1:0]), .a_wd(a_wd), .a_rd(a_q[d*W +: W]),
                    .b_en(b_en), .b_oe(b_oe), .b_addr(b_addr[BAW-1:0]), .b_rd(b_q[d*W +: W]));
            end
            // the bank of each port's read, beside the block's latch and output register
            reg [SEL_W-1:0] b_sel1, b_sel2;
            always @(posedge clk) begin
                if (b_en) b_sel1 <= b_top;
                if (b_oe) b_sel2 <= b_sel1;
            end
            cube4_mux #(.N(BANKS), .W(W)) u_b (.words(b_q), .sel(b_sel2), .word(b_rd));
            if (READ_A == 1) begin : g_read_a
                reg [SEL_W-1:0] a_sel1, a_sel2;
                always @(posedge clk) begin
                    if (a_rd_en) a_sel1 <= a_top;
                    if (a_rd_en) a_sel2 <= a_sel1;
                end
                cube4_mux #(.N(BANKS), .W(W)) u_a (.words(a_q), .sel(a_sel2), .word(a_rd));
            end else begin : g_write_a
                wire unused_a = ^a_q;
                assign a_rd = '0;
            end
        end
    endgenerate
endmodule
`default_nettype wire

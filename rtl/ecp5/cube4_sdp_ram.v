`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_sdp_ram  (ECP5 form; the generic form is rtl/cube4_sdp_ram.v)
// -----------------------------------------------------------------------------
// Purpose
//   The simple dual-port RAM of rtl/cube4_sdp_ram.v (same ports, parameters
//   and timing), shaped for the ECP5's DP16KD block RAMs. rtl/sources.f
//   names the generic form; synthesis for the ECP5 takes this one instead
//   (a file of the same name in rtl/ecp5/ replaces the generic one).
//   * A RAM deeper than 2048 words (more than one block RAM deep in its
//     2048 x 9 shape) stores its word as slices of 4, 2 or 1 bits (4096,
//     8192, 16384+ words), one memory each: each slice maps to block RAMs in
//     their 4K x 4, 8K x 2 or 16K x 1 shape, so that up to 16384 words the
//     read data needs no multiplexer between the block RAMs and the next
//     register; with OUT_REG > 0 (and IN_REG = 0) the slices take deeper shapes stacked in
//     depth where that takes fewer block RAMs (rtl/ecp5/cube4_ebr_plan.vh:
//     4096 x 9 in two 2048 x 9 blocks, not three 4096 x 4), a multiplexer
//     of up to 4 words behind the output registers (cube4_prim_ebr_column).
//   * With IN_REG = 1 every two slices get their own copies of the address
//     and enable registers (cube4_prim_copies; RAMs up to 2048 words deep are
//     then sliced into 18-bit words, two 2048 x 9 block RAMs), so no single
//     flip-flop drives the address of every block RAM: a RAM spread over
//     dozens of block RAMs across the die otherwise spends most of a cycle
//     routing one address net.
//   * With WR_REG = 1 the same copies hold the write's enable and address
//     (the read's are not registered), and the word written passes a
//     register of its own (each bit goes to one block RAM).
//   * With OUT_REG = 1 or 2 and at least 128 words (EBR_MIN_AW), each slice is a
//     DP16KD (rtl/ecp5/cube4_prim_ebr.v) with its output register (REGMODE_B = "OUTREG", loaded with the read enable,
//     or with out_en for OUT_REG = 2):
//     nextpnr times the block from clock to data in 0.7 ns instead of 4.1 ns
//     (speed grade 8), and Yosys infers no block RAM with that register. The
//     slice is the block's shape for the depth: 1024 x 18 up to 1024 words,
//     2048 x 9, 4096 x 4, 8192 x 2, 16384 x 1. Shallower RAMs are distributed
//     RAM (ram_style "distributed": left to itself, Yosys makes a 64-word RAM
//     a DP16KD, whose 4.3 ns from clock to data then ends at the fabric's
//     read register across the die), their read and output registers in the
//     fabric: a block RAM each would waste the part's EBRs. Deeper ones are
//     left to Yosys (the output register in the fabric after its bank
//     multiplexer).
//     sim/hdl/ecp5/DP16KD.v models the primitive for simulation. A read
//     of the word written at the same edge is undefined on the device (the
//     model returns the old word); cube4_sdp_ram's callers make none.
//   * With DIST = 1 the RAM is distributed RAM (ram_style "distributed":
//     TRELLIS_DPR16X4, read asynchronously into the read register, a
//     flip-flop of the fabric), for a small RAM whose word feeds logic in
//     the cycle after the read.
//   tb/cube4_top test_synthesis_form simulates this form, and
//   tb/cube4_sdp_ram runs both forms against a model of the RAM.
//
// Parameters, latency, ports, bit growth: as rtl/cube4_sdp_ram.v.
// =============================================================================
module cube4_sdp_ram
`include "cube4_sdp_ram_if.vh"

    localparam integer EBR_MIN_AW = 7;                  // block RAM from 128 words (OUT_REG > 0) ...
    localparam integer EBR_MAX_AW = 14;                 // ... to 16384 (one DP16KD deep)
    localparam integer USE_EBR = (OUT_REG != 0 && AW >= EBR_MIN_AW && AW <= EBR_MAX_AW) ? 1 : 0;
    // with OUT_REG, shallower than a block RAM: distributed RAM, as DIST = 1
    localparam integer USE_DIST = (DIST == 1 || (OUT_REG != 0 && AW < EBR_MIN_AW)) ? 1 : 0;
    localparam RAM_STYLE = (USE_DIST == 1) ? "distributed" : "auto";     // Yosys's ram_style
    // DIST = 1: distributed RAM (TRELLIS_DPR16X4, asynchronous read), its read register in the fabric
    // slice width: 4, 2, 1 bits from 4096, 8192, 16384 words on; else the
    // word (18 bits with IN_REG, so that the register copies have slices;
    // with OUT_REG the block's own shape: 18 bits to 1024 words, 9 to 2048)
    localparam integer SL_SHALLOW = (USE_EBR == 1) ? ((AW <= 10) ? 18 : 9)
                                  : (((IN_REG == 1 || WR_REG == 1) && DATA_W > 18) ? 18 : DATA_W);
    localparam integer SL_W = (AW >= 14) ? 1 : ((AW == 13) ? 2 : ((AW == 12) ? 4 : SL_SHALLOW));
    `include "ecp5/cube4_ebr_plan.vh"
    // the block RAMs' shapes (USE_EBR); with IN_REG one block deep (COM's slice and
    // beam buffers: a multiplexer behind their output registers would sit on COM's path)
    localparam integer PLAN = (IN_REG == 1) ? ebr_natural(DEPTH) * 9 : ebr_plan(DATA_W, DEPTH);
    localparam integer SPC  = 2;                        // slices per register copy
    localparam integer N_SL = (USE_EBR == 1)
                            ? ebr_n_main(DATA_W, PLAN / 8, PLAN % 8) + ebr_n_rest(DATA_W, PLAN / 8, PLAN % 8)
                            : (DATA_W + SL_W - 1) / SL_W;
    localparam integer N_CP = (N_SL + SPC - 1) / SPC;   // register copies (IN_REG = 1)
    localparam integer CW   = 2 * AW + 2;               // a copy: {re, we, ra, wa}

    wire [N_CP*CW-1:0] in_cp;           // the access's inputs, one set per copy
    wire [DATA_W-1:0]  wd;              // the word written
    generate
        if (IN_REG == 1) begin : g_in_reg
            cube4_prim_copies #(.N(N_CP), .W(CW), .RESET(0)) u_in (
                .clk(clk), .rst(1'b0), .d({rd_en, wr_en, rd_addr, wr_addr}), .q(in_cp));
            assign wd = wr_data;
        end else if (WR_REG == 1) begin : g_wr_reg
            wire [N_CP*(AW+1)-1:0] wr_cp;       // {we, wa} per copy
            cube4_prim_copies #(.N(N_CP), .W(AW + 1), .RESET(0)) u_wr (
                .clk(clk), .rst(1'b0), .d({wr_en, wr_addr}), .q(wr_cp));
            genvar c;
            for (c = 0; c < N_CP; c = c + 1) begin : g_cp
                wire [AW:0] w = wr_cp[c * (AW + 1) +: AW + 1];
                assign in_cp[c * CW +: CW] = {rd_en, w[AW], rd_addr, w[AW-1:0]};
            end
            reg [DATA_W-1:0] wd_q;
            always @(posedge clk) wd_q <= wr_data;
            assign wd = wd_q;
        end else begin : g_direct
            assign in_cp = {N_CP{rd_en, wr_en, rd_addr, wr_addr}};
            assign wd = wr_data;
        end
    endgenerate

    genvar sl;
    generate
        for (sl = 0; sl < N_SL; sl = sl + 1) begin : g_slice
            localparam integer LO = (USE_EBR == 1) ? ebr_sl_lo(DATA_W, PLAN, sl) : sl * SL_W;
            localparam integer W  = (USE_EBR == 1) ? ebr_sl_w(DATA_W, PLAN, sl)
                                  : ((DATA_W - LO < SL_W) ? DATA_W - LO : SL_W);
            wire [CW-1:0] cp = in_cp[(sl / SPC) * CW +: CW];
            wire          re = cp[CW-1];
            wire          we = cp[CW-2];
            wire [AW-1:0] ra = cp[AW +: AW];
            wire [AW-1:0] wa = cp[0 +: AW];
            if (USE_EBR == 1) begin : g_ebr
                // port A writes, port B reads through its output register
                localparam integer SH = ebr_sl_shape(DATA_W, PLAN, sl);
                wire oe = (OUT_REG == 2) ? out_en : re;    // the output register's enable
                wire [W-1:0] unused_a_rd;
                cube4_prim_ebr_column #(.SHAPE_W(ebr_w(SH)), .W(W), .AW(AW), .BLK_AW(10 + SH),
                                        .BANKS(ebr_banks(SH, DEPTH)), .READ_A(0)) u_ebr (
                    .clk(clk), .a_en(1'b0), .a_we(we), .a_addr(wa), .a_wd(wd[LO +: W]), .a_rd(unused_a_rd),
                    .b_en(re), .b_oe(oe), .b_addr(ra), .b_rd(rd_data[LO +: W]));
                wire unused_a = ^unused_a_rd;
            end else begin : g_fabric
                // distributed RAM (USE_DIST) or Yosys's choice ("auto": a DP16KD
                // without its output register, or distributed RAM)
                (* ram_style = RAM_STYLE *) reg [W-1:0] mem [0:(1 << AW)-1];
                reg [W-1:0] rd_q;
                always @(posedge clk) begin
                    if (we) mem[wa] <= wd[LO +: W];
                    if (re) rd_q <= mem[ra];
                end
                if (OUT_REG != 0) begin : g_out_reg
                    wire oe = (OUT_REG == 2) ? out_en : re;
                    reg [W-1:0] out_q;
                    always @(posedge clk) begin
                        if (oe) out_q <= rd_q;
                    end
                    assign rd_data[LO +: W] = out_q;
                end else begin : g_no_out_reg
                    assign rd_data[LO +: W] = rd_q;
                end
            end
        end
        if (OUT_REG != 2) begin : g_no_out_en
            wire unused_out_en = out_en;   // (the output register, if any, loads with the read)
        end
    endgenerate

endmodule
`default_nettype wire

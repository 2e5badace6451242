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
//     register (about as many block RAMs as the 2048 x 9 shape plus a
//     multiplexer).
//   * With IN_REG = 1 every two slices get their own copies of the address
//     and enable registers (cube4_prim_copies; RAMs up to 2048 words deep are
//     then sliced into 18-bit words, two 2048 x 9 block RAMs), so no single
//     flip-flop drives the address of every block RAM: a RAM spread over
//     dozens of block RAMs across the die otherwise spends most of a cycle
//     routing one address net.
//   * With WR_REG = 1 the same copies hold the write's enable and address
//     (the read's are not registered), and the word written passes a
//     register of its own (each bit goes to one block RAM).
//   * With OUT_REG = 1 and at least 128 words (EBR_MIN_AW), each slice is a
//     DP16KD instantiated here with its output register (REGMODE_B = "OUTREG", loaded with the read enable):
//     nextpnr times the block from clock to data in 0.7 ns instead of 4.1 ns
//     (speed grade 8), and Yosys infers no block RAM with that register. The
//     slice is the block's shape for the depth: 1024 x 18 up to 1024 words,
//     2048 x 9, 4096 x 4, 8192 x 2, 16384 x 1. Shallower RAMs are left to
//     Yosys (distributed RAM), their output register in the fabric: a block
//     RAM each would waste the part's EBRs; so are deeper ones (the output
//     register in the fabric after Yosys's bank multiplexer).
//     sim/hdl/ecp5/DP16KD.v models the primitive for simulation. A read
//     of the word written at the same edge is undefined on the device (the
//     model returns the old word); cube4_sdp_ram's callers make none.
//   tb/cube4_top test_synthesis_ram_form_p1 simulates this form, and
//   tb/cube4_sdp_ram runs both forms against a model of the RAM.
//
// Parameters, latency, ports, bit growth: as rtl/cube4_sdp_ram.v.
// =============================================================================
module cube4_sdp_ram #(
    parameter  integer DATA_W = 8,
    parameter  integer DEPTH  = 16,
    parameter  integer IN_REG = 0,
    parameter  integer WR_REG = 0,
    parameter  integer OUT_REG = 0,
    localparam integer AW     = (DEPTH > 1) ? $clog2(DEPTH) : 1
) (
    input  wire              clk,
    input  wire              rd_en,
    input  wire [AW-1:0]     rd_addr,
    output wire [DATA_W-1:0] rd_data,
    input  wire              wr_en,
    input  wire [AW-1:0]     wr_addr,
    input  wire [DATA_W-1:0] wr_data
);
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_sdp_ram", "DATA_W", DATA_W, 1, 4096)
        if (DEPTH < 1 || DEPTH > (1 << 24)) begin : g_bad_depth
            $error("cube4_sdp_ram: DEPTH = %0d is out of range 1..2^24", DEPTH);
        end
        `CUBE4_RANGE(g_bad_in_reg, "cube4_sdp_ram", "IN_REG", IN_REG, 0, 1)
        `CUBE4_RANGE(g_bad_wr_reg, "cube4_sdp_ram", "WR_REG", WR_REG, 0, 1)
        `CUBE4_RANGE(g_bad_out_reg, "cube4_sdp_ram", "OUT_REG", OUT_REG, 0, 1)
        if (IN_REG == 1 && WR_REG == 1) begin : g_bad_regs
            $error("cube4_sdp_ram: IN_REG = 1 with WR_REG = 1 (IN_REG registers the write's enable and address already)");
        end
    endgenerate

    localparam integer EBR_MIN_AW = 7;                  // block RAM from 128 words (OUT_REG = 1) ...
    localparam integer EBR_MAX_AW = 14;                 // ... to 16384 (one DP16KD deep)
    localparam integer USE_EBR = (OUT_REG == 1 && AW >= EBR_MIN_AW && AW <= EBR_MAX_AW) ? 1 : 0;
    // slice width: 4, 2, 1 bits from 4096, 8192, 16384 words on; else the
    // word (18 bits with IN_REG, so that the register copies have slices;
    // with OUT_REG the block's own shape: 18 bits to 1024 words, 9 to 2048)
    localparam integer SL_SHALLOW = (USE_EBR == 1) ? ((AW <= 10) ? 18 : 9)
                                  : (((IN_REG == 1 || WR_REG == 1) && DATA_W > 18) ? 18 : DATA_W);
    localparam integer SL_W = (AW >= 14) ? 1 : ((AW == 13) ? 2 : ((AW == 12) ? 4 : SL_SHALLOW));
    // a DP16KD port of SL_W bits addresses AD13..AD(LOW)
    localparam integer LOW  = (SL_W == 18) ? 4 : ((SL_W == 9) ? 3 : ((SL_W == 4) ? 2 : ((SL_W == 2) ? 1 : 0)));
    localparam integer SPC  = 2;                        // slices per register copy
    localparam integer N_SL = (DATA_W + SL_W - 1) / SL_W;
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
            localparam integer LO = sl * SL_W;
            localparam integer W  = (DATA_W - LO < SL_W) ? DATA_W - LO : SL_W;
            wire [CW-1:0] cp = in_cp[(sl / SPC) * CW +: CW];
            wire          re = cp[CW-1];
            wire          we = cp[CW-2];
            wire [AW-1:0] ra = cp[AW +: AW];
            wire [AW-1:0] wa = cp[0 +: AW];
            if (USE_EBR == 1) begin : g_ebr
                // port A writes, port B reads through its output register;
                // the 18-bit shape's byte enables (AD1..AD0 of port A) are 1
                wire [13:0] ada = 14'({(14 - LOW)'(wa), (LOW == 4) ? 4'b0011 : 4'b0000} >> (4 - LOW));
                wire [13:0] adb = 14'({(14 - LOW)'(ra), 4'b0000} >> (4 - LOW));
                wire [17:0] di  = 18'(wd[LO +: W]);
                wire [17:0] dob;
                wire [17:0] doa;                    // port A only writes
                wire unused_doa = ^doa;
                DP16KD #(
                    .DATA_WIDTH_A (SL_W), .DATA_WIDTH_B (SL_W),
                    .REGMODE_A ("NOREG"), .REGMODE_B ("OUTREG"),
                    .RESETMODE ("SYNC"), .ASYNC_RESET_RELEASE ("SYNC"),
                    .CSDECODE_A ("0b000"), .CSDECODE_B ("0b000"),
                    .WRITEMODE_A ("NORMAL"), .WRITEMODE_B ("NORMAL"),
                    .GSR ("DISABLED")
                ) u_ebr (
                    .DIA17(di[17]), .DIA16(di[16]), .DIA15(di[15]), .DIA14(di[14]), .DIA13(di[13]),
                    .DIA12(di[12]), .DIA11(di[11]), .DIA10(di[10]), .DIA9(di[9]), .DIA8(di[8]),
                    .DIA7(di[7]), .DIA6(di[6]), .DIA5(di[5]), .DIA4(di[4]), .DIA3(di[3]),
                    .DIA2(di[2]), .DIA1(di[1]), .DIA0(di[0]),
                    .ADA13(ada[13]), .ADA12(ada[12]), .ADA11(ada[11]), .ADA10(ada[10]), .ADA9(ada[9]),
                    .ADA8(ada[8]), .ADA7(ada[7]), .ADA6(ada[6]), .ADA5(ada[5]), .ADA4(ada[4]),
                    .ADA3(ada[3]), .ADA2(ada[2]), .ADA1(ada[1]), .ADA0(ada[0]),
                    .CEA(1'b1), .OCEA(1'b1), .CLKA(clk), .WEA(we), .RSTA(1'b0),
                    .CSA2(1'b0), .CSA1(1'b0), .CSA0(1'b0),
                    .DOA17(doa[17]), .DOA16(doa[16]), .DOA15(doa[15]), .DOA14(doa[14]), .DOA13(doa[13]),
                    .DOA12(doa[12]), .DOA11(doa[11]), .DOA10(doa[10]), .DOA9(doa[9]), .DOA8(doa[8]),
                    .DOA7(doa[7]), .DOA6(doa[6]), .DOA5(doa[5]), .DOA4(doa[4]), .DOA3(doa[3]),
                    .DOA2(doa[2]), .DOA1(doa[1]), .DOA0(doa[0]),
                    .DIB17(1'b0), .DIB16(1'b0), .DIB15(1'b0), .DIB14(1'b0), .DIB13(1'b0),
                    .DIB12(1'b0), .DIB11(1'b0), .DIB10(1'b0), .DIB9(1'b0), .DIB8(1'b0),
                    .DIB7(1'b0), .DIB6(1'b0), .DIB5(1'b0), .DIB4(1'b0), .DIB3(1'b0),
                    .DIB2(1'b0), .DIB1(1'b0), .DIB0(1'b0),
                    .ADB13(adb[13]), .ADB12(adb[12]), .ADB11(adb[11]), .ADB10(adb[10]), .ADB9(adb[9]),
                    .ADB8(adb[8]), .ADB7(adb[7]), .ADB6(adb[6]), .ADB5(adb[5]), .ADB4(adb[4]),
                    .ADB3(adb[3]), .ADB2(adb[2]), .ADB1(adb[1]), .ADB0(adb[0]),
                    .CEB(re), .OCEB(re), .CLKB(clk), .WEB(1'b0), .RSTB(1'b0),
                    .CSB2(1'b0), .CSB1(1'b0), .CSB0(1'b0),
                    .DOB17(dob[17]), .DOB16(dob[16]), .DOB15(dob[15]), .DOB14(dob[14]), .DOB13(dob[13]),
                    .DOB12(dob[12]), .DOB11(dob[11]), .DOB10(dob[10]), .DOB9(dob[9]), .DOB8(dob[8]),
                    .DOB7(dob[7]), .DOB6(dob[6]), .DOB5(dob[5]), .DOB4(dob[4]), .DOB3(dob[3]),
                    .DOB2(dob[2]), .DOB1(dob[1]), .DOB0(dob[0])
                );
                assign rd_data[LO +: W] = dob[W-1:0];
                if (W < 18) begin : g_unused
                    wire unused_dob = ^dob[17:W];   // the slice's port is wider than its bits
                end
            end else begin : g_infer
                reg [W-1:0] mem [0:(1 << AW)-1];
                reg [W-1:0] rd_q;
                always @(posedge clk) begin
                    if (we) mem[wa] <= wd[LO +: W];
                    if (re) rd_q <= mem[ra];
                end
                if (OUT_REG == 1) begin : g_out_reg
                    reg [W-1:0] out_q;
                    always @(posedge clk) begin
                        if (re) out_q <= rd_q;
                    end
                    assign rd_data[LO +: W] = out_q;
                end else begin : g_no_out_reg
                    assign rd_data[LO +: W] = rd_q;
                end
            end
        end
    endgenerate

endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_prim_ebr  (ECP5 form; the generic form is rtl/cube4_prim_ebr.v)
// -----------------------------------------------------------------------------
// Purpose
//   One DP16KD block RAM with the output registers of the ports that read
//   (REGMODE "OUTREG", loaded with port A's read enable, port B's b_oe): nextpnr times
//   the block from clock to data in 0.7 ns instead of 4.1 ns (speed grade
//   8), and Yosys infers no block RAM with that register. Port A writes
//   (WRITEMODE "NORMAL": its latch keeps its word in a write cycle) and,
//   with READ_A = 1, reads; port B reads. The one place the vendor layer
//   instantiates the primitive (rtl/ecp5/cube4_sdp_ram.v and
//   rtl/ecp5/cube4_dual_read_ram.v slice their words over it).
//   sim/hdl/ecp5/DP16KD.v models the primitive for simulation.
//
// Parameters, latency, ports: as rtl/cube4_prim_ebr.v.
// =============================================================================
module cube4_prim_ebr
`include "cube4_prim_ebr_if.vh"

    // the 18-bit shape's byte enables (AD1..AD0 of port A) are 1
    wire [13:0] ada = 14'({(14 - LOW)'(a_addr), (LOW == 4) ? 4'b0011 : 4'b0000} >> (4 - LOW));
    wire [13:0] adb = 14'({(14 - LOW)'(b_addr), 4'b0000} >> (4 - LOW));
    wire [17:0] di  = 18'(a_wd);
    wire [17:0] doa, dob;
    // port A's clock enable: its write, and its read with READ_A
    wire cea  = (READ_A == 1) ? (a_en || a_we) : 1'b1;
    wire ocea = (READ_A == 1) ? (a_en && !a_we) : 1'b1;
    DP16KD #(
        .DATA_WIDTH_A (SHAPE_W), .DATA_WIDTH_B (SHAPE_W),
        .REGMODE_A ((READ_A == 1) ? "OUTREG" : "NOREG"), .REGMODE_B ("OUTREG"),
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
        .CEA(cea), .OCEA(ocea), .CLKA(clk), .WEA(a_we), .RSTA(1'b0),
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
        .CEB(b_en), .OCEB(b_oe), .CLKB(clk), .WEB(1'b0), .RSTB(1'b0),
        .CSB2(1'b0), .CSB1(1'b0), .CSB0(1'b0),
        .DOB17(dob[17]), .DOB16(dob[16]), .DOB15(dob[15]), .DOB14(dob[14]), .DOB13(dob[13]),
        .DOB12(dob[12]), .DOB11(dob[11]), .DOB10(dob[10]), .DOB9(dob[9]), .DOB8(dob[8]),
        .DOB7(dob[7]), .DOB6(dob[6]), .DOB5(dob[5]), .DOB4(dob[4]), .DOB3(dob[3]),
        .DOB2(dob[2]), .DOB1(dob[1]), .DOB0(dob[0])
    );
    assign b_rd = dob[W-1:0];
    generate
        if (READ_A == 1) begin : g_read_a
            assign a_rd = doa[W-1:0];
        end else begin : g_write_a
            assign a_rd = '0;
        end
        if (W < 18) begin : g_unused
            wire unused_do = ^{doa[17:W], dob[17:W]};   // the port is wider than its bits
        end
        if (READ_A == 0) begin : g_unused_a
            wire unused_doa = ^{doa[W-1:0], a_en};
        end
    endgenerate

endmodule
`default_nettype wire

`default_nettype none
// =============================================================================
// DP16KD  (behavioural simulation model of the Lattice ECP5 block RAM)
// -----------------------------------------------------------------------------
// Purpose
//   Simulates the subset of the ECP5 16 kbit dual-port block RAM that the
//   vendor layer (rtl/ecp5/cube4_prim_ebr.v) uses, so that the RTL as
//   synthesis reads it can be simulated: port A writes and may read, port B
//   reads, one clock, port widths 1, 2, 4, 9 or 18 bits (16384 x 1 ..
//   1024 x 18), each read side with or without its output register
//   (REGMODE = "OUTREG" or "NOREG"). Port A in a write cycle does not read
//   (WRITEMODE "NORMAL": the data output is not updated by a write). Not
//   modelled, and refused at elaboration: writes on port B, chip selects
//   other than "0b000", WRITEMODE other than NORMAL. The resets and the
//   byte enables of the 18-bit shape are not modelled (RSTA/RSTB must stay
//   0; the vendor layer ties the 18-bit write port's byte enables AD1..AD0
//   to 1). Never read by synthesis (Yosys has its own black box of the
//   primitive).
//
// Addressing (as the primitive): a port of width W uses AD13..ADk with
//   k = 0, 1, 2, 3, 4 for W = 1, 2, 4, 9, 18; data on DI/DO[W-1:0].
//
// Latency (either port; port A's with CEA = 1 and WEA = 0)
//   NOREG: 1 (DO is the word of the last edge with CE = 1).
//   OUTREG: 2 (the latched word passes a register loaded on edges with
//   OCE = 1). A port B read of the address written at the same edge returns
//   the old word (the vendor layer's callers never depend on it).
// =============================================================================
/* verilator lint_off DECLFILENAME */
module DP16KD #(
    parameter integer DATA_WIDTH_A = 18, parameter integer DATA_WIDTH_B = 18,
    parameter REGMODE_A = "NOREG", parameter REGMODE_B = "NOREG",
    parameter RESETMODE = "SYNC", parameter ASYNC_RESET_RELEASE = "SYNC",
    parameter CSDECODE_A = "0b000", parameter CSDECODE_B = "0b000",
    parameter WRITEMODE_A = "NORMAL", parameter WRITEMODE_B = "NORMAL",
    parameter GSR = "ENABLED"
) (
    input  wire DIA17, DIA16, DIA15, DIA14, DIA13, DIA12, DIA11, DIA10, DIA9,
    input  wire DIA8, DIA7, DIA6, DIA5, DIA4, DIA3, DIA2, DIA1, DIA0,
    input  wire ADA13, ADA12, ADA11, ADA10, ADA9, ADA8, ADA7, ADA6, ADA5, ADA4, ADA3, ADA2, ADA1, ADA0,
    input  wire CEA, OCEA, CLKA, WEA, RSTA, CSA2, CSA1, CSA0,
    output wire DOA17, DOA16, DOA15, DOA14, DOA13, DOA12, DOA11, DOA10, DOA9,
    output wire DOA8, DOA7, DOA6, DOA5, DOA4, DOA3, DOA2, DOA1, DOA0,
    input  wire DIB17, DIB16, DIB15, DIB14, DIB13, DIB12, DIB11, DIB10, DIB9,
    input  wire DIB8, DIB7, DIB6, DIB5, DIB4, DIB3, DIB2, DIB1, DIB0,
    input  wire ADB13, ADB12, ADB11, ADB10, ADB9, ADB8, ADB7, ADB6, ADB5, ADB4, ADB3, ADB2, ADB1, ADB0,
    input  wire CEB, OCEB, CLKB, WEB, RSTB, CSB2, CSB1, CSB0,
    output wire DOB17, DOB16, DOB15, DOB14, DOB13, DOB12, DOB11, DOB10, DOB9,
    output wire DOB8, DOB7, DOB6, DOB5, DOB4, DOB3, DOB2, DOB1, DOB0
);
    // address bits below the word: 0, 1, 2, 3, 4 for widths 1, 2, 4, 9, 18
    function automatic integer low_bits(input integer w);
        low_bits = (w == 18) ? 4 : (w == 9) ? 3 : (w == 4) ? 2 : (w == 2) ? 1 : 0;
    endfunction
    localparam integer LA = low_bits(DATA_WIDTH_A);
    localparam integer LB = low_bits(DATA_WIDTH_B);
    localparam integer WORDS = 16384 >> LA;
    localparam OUTR = (REGMODE_B == "OUTREG");
    localparam OUTA = (REGMODE_A == "OUTREG");
    generate
        if (DATA_WIDTH_A != DATA_WIDTH_B || low_bits(DATA_WIDTH_A) == 0 && DATA_WIDTH_A != 1
            || !(REGMODE_A == "NOREG" || OUTA) || !(REGMODE_B == "NOREG" || OUTR)
            || CSDECODE_A != "0b000" || CSDECODE_B != "0b000"
            || WRITEMODE_A != "NORMAL" || WRITEMODE_B != "NORMAL"
            || RESETMODE != "SYNC" || ASYNC_RESET_RELEASE != "SYNC" || GSR == "") begin : g_unsupported
            $error("DP16KD model: only equal port widths of 1, 2, 4, 9 or 18, port A writing and reading, port B reading (NOREG or OUTREG), NORMAL write mode, synchronous reset mode (reset unused) and no chip-select decode are modelled");
        end
    endgenerate

    wire [17:0] dia = {DIA17, DIA16, DIA15, DIA14, DIA13, DIA12, DIA11, DIA10, DIA9,
                       DIA8, DIA7, DIA6, DIA5, DIA4, DIA3, DIA2, DIA1, DIA0};
    wire [13:0] ada = {ADA13, ADA12, ADA11, ADA10, ADA9, ADA8, ADA7, ADA6, ADA5, ADA4, ADA3, ADA2, ADA1, ADA0};
    wire [13:0] adb = {ADB13, ADB12, ADB11, ADB10, ADB9, ADB8, ADB7, ADB6, ADB5, ADB4, ADB3, ADB2, ADB1, ADB0};
    wire unused = ^{DIB17, DIB16, DIB15, DIB14, DIB13, DIB12, DIB11, DIB10, DIB9,
                    DIB8, DIB7, DIB6, DIB5, DIB4, DIB3, DIB2, DIB1, DIB0,
                    RSTA, RSTB, WEB, CSA2, CSA1, CSA0, CSB2, CSB1, CSB0, CLKB,
                    ada, adb, dia};   // (bits below the word are no address; above the width, no data)

    reg [DATA_WIDTH_A-1:0] mem [0:WORDS-1];
    reg [DATA_WIDTH_B-1:0] lat_q, out_q;
    reg [DATA_WIDTH_A-1:0] lat_a_q, out_a_q;
    // port A writes or reads, port B reads, on one clock (the vendor layer's use)
    always @(posedge CLKA) begin
        if (CEA && WEA) mem[ada[13:LA]] <= dia[DATA_WIDTH_A-1:0];
        if (CEA && !WEA) lat_a_q <= mem[ada[13:LA]];
        if (OCEA) out_a_q <= lat_a_q;
        if (CEB) lat_q <= mem[adb[13:LB]];
        if (OCEB) out_q <= lat_q;
    end
    wire [17:0] dob = 18'(OUTR ? out_q : lat_q);
    wire [17:0] doa = 18'(OUTA ? out_a_q : lat_a_q);
    assign {DOB17, DOB16, DOB15, DOB14, DOB13, DOB12, DOB11, DOB10, DOB9,
            DOB8, DOB7, DOB6, DOB5, DOB4, DOB3, DOB2, DOB1, DOB0} = dob;
    assign {DOA17, DOA16, DOA15, DOA14, DOA13, DOA12, DOA11, DOA10, DOA9,
            DOA8, DOA7, DOA6, DOA5, DOA4, DOA3, DOA2, DOA1, DOA0} = doa;
endmodule
/* verilator lint_on DECLFILENAME */
`default_nettype wire

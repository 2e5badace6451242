`default_nettype none
// =============================================================================
// MULT18X18D  (behavioural simulation model of the Lattice ECP5 primitive)
// -----------------------------------------------------------------------------
// Purpose
//   Simulates the subset of the ECP5 18 x 18 multiplier that the vendor
//   layer (rtl/ecp5/) uses, so that the RTL as synthesis reads it can be
//   simulated: P = A * B, signed or unsigned per SIGNEDA/SIGNEDB (held
//   constant), with each of the input (A, B), pipeline and output registers
//   on CLK0 / CE0 or bypassed (REG_*_CLK = "CLK0" or "NONE"). Not modelled,
//   and refused at elaboration: other clocks or clock enables, the C input's
//   register, dynamic B/C source selection, cascades, the reset of the
//   registers (RST0 must be tied 0). Never read by synthesis (Yosys has its
//   own black box of the primitive).
//
// Latency
//   The number of registers enabled (0..3) on CLK0 edges with CE0 = 1.
//
// Ports (the ones the vendor layer connects; names as the primitive's)
//   A17..A0, B17..B0   operands, two's complement when SIGNEDA / SIGNEDB = 1
//   C17..C0            unused (tied 0)
//   P35..P0            product, 36 bits
// =============================================================================
/* verilator lint_off DECLFILENAME */
module MULT18X18D #(
    parameter REG_INPUTA_CLK = "NONE", parameter REG_INPUTA_CE = "CE0", parameter REG_INPUTA_RST = "RST0",
    parameter REG_INPUTB_CLK = "NONE", parameter REG_INPUTB_CE = "CE0", parameter REG_INPUTB_RST = "RST0",
    parameter REG_PIPELINE_CLK = "NONE", parameter REG_PIPELINE_CE = "CE0", parameter REG_PIPELINE_RST = "RST0",
    parameter REG_OUTPUT_CLK = "NONE", parameter REG_OUTPUT_CE = "CE0", parameter REG_OUTPUT_RST = "RST0",
    parameter GSR = "ENABLED", parameter RESETMODE = "SYNC", parameter SOURCEB_MODE = "B_SHIFT"
) (
    input  wire A17, A16, A15, A14, A13, A12, A11, A10, A9, A8, A7, A6, A5, A4, A3, A2, A1, A0,
    input  wire B17, B16, B15, B14, B13, B12, B11, B10, B9, B8, B7, B6, B5, B4, B3, B2, B1, B0,
    input  wire C17, C16, C15, C14, C13, C12, C11, C10, C9, C8, C7, C6, C5, C4, C3, C2, C1, C0,
    input  wire SIGNEDA, SIGNEDB, SOURCEA, SOURCEB,
    input  wire CLK0, CLK1, CLK2, CLK3,
    input  wire CE0, CE1, CE2, CE3,
    input  wire RST0, RST1, RST2, RST3,
    output wire P35, P34, P33, P32, P31, P30, P29, P28, P27, P26, P25, P24, P23, P22, P21, P20, P19, P18, P17, P16, P15, P14, P13, P12, P11, P10, P9, P8, P7, P6, P5, P4, P3, P2, P1, P0
);
    localparam IN_A = (REG_INPUTA_CLK == "CLK0");
    localparam IN_B = (REG_INPUTB_CLK == "CLK0");
    localparam PIPE = (REG_PIPELINE_CLK == "CLK0");
    localparam OUTR = (REG_OUTPUT_CLK == "CLK0");
    generate
        if (!(REG_INPUTA_CLK == "NONE" || IN_A) || !(REG_INPUTB_CLK == "NONE" || IN_B)
            || !(REG_PIPELINE_CLK == "NONE" || PIPE) || !(REG_OUTPUT_CLK == "NONE" || OUTR)
            || REG_INPUTA_CE != "CE0" || REG_INPUTB_CE != "CE0" || REG_PIPELINE_CE != "CE0"
            || REG_OUTPUT_CE != "CE0" || SOURCEB_MODE != "B_SHIFT"
            || REG_INPUTA_RST != "RST0" || REG_INPUTB_RST != "RST0" || REG_PIPELINE_RST != "RST0"
            || REG_OUTPUT_RST != "RST0" || RESETMODE != "SYNC" || GSR == "") begin : g_unsupported
            $error("MULT18X18D model: only registers on CLK0/CE0/RST0 (or none), RESETMODE SYNC and SOURCEB_MODE B_SHIFT are modelled");
        end
    endgenerate

    wire [17:0] a = {A17, A16, A15, A14, A13, A12, A11, A10, A9, A8, A7, A6, A5, A4, A3, A2, A1, A0};
    wire [17:0] b = {B17, B16, B15, B14, B13, B12, B11, B10, B9, B8, B7, B6, B5, B4, B3, B2, B1, B0};
    wire unused = ^{C17, C16, C15, C14, C13, C12, C11, C10, C9, C8, C7, C6, C5, C4, C3, C2, C1, C0, SOURCEA, SOURCEB,
                    CLK1, CLK2, CLK3, CE1, CE2, CE3, RST1, RST2, RST3};

    reg  [17:0] a_q, b_q;
    reg  [35:0] m_q, p_q;
    wire [17:0] a_s = IN_A ? a_q : a;
    wire [17:0] b_s = IN_B ? b_q : b;
    // 36 bits hold the product exactly both ways (18 x 18 signed or unsigned)
    wire [35:0] a_x = SIGNEDA ? 36'(signed'(a_s)) : 36'(a_s);
    wire [35:0] b_x = SIGNEDB ? 36'(signed'(b_s)) : 36'(b_s);
    wire [35:0] prod = a_x * b_x;
    wire [35:0] m_s = PIPE ? m_q : prod;
    wire [35:0] p   = OUTR ? p_q : m_s;
    always @(posedge CLK0) begin
        if (RST0) begin
            a_q <= '0; b_q <= '0; m_q <= '0; p_q <= '0;   // (asserting RST0 is not supported; see above)
        end else if (CE0) begin
            a_q <= a;
            b_q <= b;
            m_q <= prod;
            p_q <= m_s;
        end
    end
    assign {P35, P34, P33, P32, P31, P30, P29, P28, P27, P26, P25, P24, P23, P22, P21, P20, P19, P18, P17, P16, P15, P14, P13, P12, P11, P10, P9, P8, P7, P6, P5, P4, P3, P2, P1, P0} = p;
endmodule
/* verilator lint_on DECLFILENAME */
`default_nettype wire

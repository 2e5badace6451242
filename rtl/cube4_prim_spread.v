`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_prim_spread
// -----------------------------------------------------------------------------
// Purpose
//   A control register for a wide word, in COPIES kept copies spread over the
//   word: bit b of the D-bit word is driven by copy floor(b / ceil(D / COPIES))
//   (cube4_prim_copies), so that no flip-flop drives more than one group of
//   about D / COPIES selects. For the selects of a datapath word whose control
//   would otherwise be one net to 2 * D multiplexers spread over a lane (COM's
//   fresh-or-previous select, its buffer-word selects: the P = 8 build's
//   critical nets before they were copied). The function stays in the unit:
//   it reads one control bit per word bit (bitwise logic on q).
//
// Parameters
//   W        control bits.                             1..64.   Default 1.
//   D        bits of the word they control.            1..4096. Default 1.
//   COPIES   register copies (the last groups may be
//            empty when D is small: their copy stays). 1..512.  Default 4.
//   RESET    1: synchronous reset to 0; 0: no reset.    0..1.    Default 0.
//
// Latency: 1 cycle (q is d of the last clock edge, every bit of it).
//
// Ports
//   d   in   [W]     the control bits (any format)
//   q   out  [W*D]   control bit c for word bit b at q[c*D + b]
//
// Bit growth and rounding: none.
// =============================================================================
module cube4_prim_spread #(
    parameter integer W      = 1,
    parameter integer D      = 1,
    parameter integer COPIES = 4,
    parameter integer RESET  = 0
) (
    input  wire           clk,
    input  wire           rst,
    input  wire [W-1:0]   d,
    output wire [W*D-1:0] q
);
    generate
        `CUBE4_RANGE(g_bad_w, "cube4_prim_spread", "W", W, 1, 64)
        `CUBE4_RANGE(g_bad_d, "cube4_prim_spread", "D", D, 1, 4096)
    endgenerate
    localparam integer GW = (D + COPIES - 1) / COPIES;   // word bits per copy

    wire [COPIES*W-1:0] c_q;                              // copy g at [g*W +: W]
    cube4_prim_copies #(.N(COPIES), .W(W), .RESET(RESET)) u_c (
        .clk(clk), .rst(rst), .d(d), .q(c_q));
    genvar c, b;
    generate
        for (c = 0; c < COPIES; c = c + 1) begin : g_copy
            if (c * GW >= D) begin : g_empty
                wire unused_c = ^c_q[c*W +: W];
            end
        end
        for (c = 0; c < W; c = c + 1) begin : g_bit
            for (b = 0; b < D; b = b + 1) begin : g_word
                assign q[c*D + b] = c_q[(b / GW) * W + c];
            end
        end
    endgenerate
endmodule
`default_nettype wire

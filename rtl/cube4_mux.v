`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_mux
// -----------------------------------------------------------------------------
// Purpose
//   Word sel of N packed words, as a tree of 2:1 multiplexers (level b picks
//   by bit b of sel). A part-select at a variable index, words[sel * W +: W],
//   with W not a power of two has synthesis compute the index sel * W, and
//   Yosys maps that product to a MULT18X18D: the word then waits for a
//   multiplier before its multiplexer. This form has no index arithmetic.
//
// Parameters
//   N      words.                       1..4096.  Default 2.
//   W      bits a word.                 1..4096.  Default 1.
//   SEL_W  select bits (derived: clog2(N), at least 1).
//
// Latency
//   Combinational.
//
// Ports
//   words  in   [N*W]  word k at [k*W +: W] (any format)
//   sel    in   [SEL_W] 0 .. N - 1 (a select of N or more gives zero)
//   word   out  [W]
//
// Bit growth and rounding: none (a select).
// =============================================================================
module cube4_mux #(
    parameter  integer N     = 2,
    parameter  integer W     = 1,
    localparam integer SEL_W = (N > 1) ? $clog2(N) : 1
) (
    input  wire [N*W-1:0]   words,
    input  wire [SEL_W-1:0] sel,
    output wire [W-1:0]     word
);
    generate
        `CUBE4_RANGE(g_bad_n, "cube4_mux", "N", N, 1, 4096)
        `CUBE4_RANGE(g_bad_w, "cube4_mux", "W", W, 1, 4096)
    endgenerate
    localparam integer NP = 1 << SEL_W;          // words padded to a power of two
    genvar b, k;
    generate
        // level b: NP >> b words; level b + 1 picks by bit b of sel
        for (b = 0; b <= SEL_W; b = b + 1) begin : g_lvl
            wire [(NP >> b)*W-1:0] v;
            if (b == 0) begin : g_in
                assign v = (NP * W)'(words);
            end else begin : g_pick
                for (k = 0; k < (NP >> b); k = k + 1) begin : g_word
                    assign v[k*W +: W] = sel[b-1] ? g_lvl[b-1].v[(2*k+1)*W +: W] : g_lvl[b-1].v[2*k*W +: W];
                end
            end
        end
    endgenerate
    assign word = g_lvl[SEL_W].v;
endmodule
`default_nettype wire

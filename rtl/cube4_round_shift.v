`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_round_shift
// -----------------------------------------------------------------------------
// Purpose
//   Divide a signed fixed-point value by 2^SHIFT, rounding half up:
//     y = floor((x + 2^(SHIFT-1)) / 2^SHIFT)   for SHIFT > 0
//     y = x                                    for SHIFT = 0
//   This is round_shift() of golden/cube4/fixed.py, bit for bit. The division
//   is an arithmetic shift (floor), so ties go towards +infinity for both signs:
//   +2.5 -> +3, -2.5 -> -2, -2.75 -> -3.
//
// Parameters
//   IN_W   width of x, two's complement signed.  Range 2..64.
//   SHIFT  number of fraction bits to drop.      Range 0..IN_W-1.
//
// Latency
//   0 cycles (purely combinational; no clock, no reset).
//
// Ports (fixed-point formats; sQm.f = signed two's complement with m integer
// bits, sign included, and f fraction bits)
//   x  in   signed [IN_W-1:0]          sQm.f with m + f = IN_W (any split)
//   y  out  signed [IN_W-SHIFT:0]      sQ(m+1).(f-SHIFT): the real value of x
//                                      rounded to f-SHIFT fraction bits, with one
//                                      more integer bit (see bit growth below)
//
// Bit growth and rounding (why the output is IN_W-SHIFT+1 bits wide)
//   The rounding constant 2^(SHIFT-1) is added BEFORE the shift, and that sum
//   can carry out of IN_W bits (x = 2^(IN_W-1)-1 plus the constant overflows).
//   The sum is therefore formed in IN_W+1 bits; shifting it right by SHIFT
//   leaves IN_W+1-SHIFT significant bits, all of which are needed in general
//   (e.g. IN_W = 4, SHIFT = 1: x = 7 -> y = 4 needs 4 signed bits, not 3).
//   With SHIFT = 0 the output is x sign-extended by one bit, so that the
//   output width formula holds for every SHIFT. Callers that know a tighter
//   range drop the surplus high bits themselves (cube4_lerp folds the rounding
//   into its own add: its header). Nothing is
//   saturated.
// =============================================================================
module cube4_round_shift #(
    parameter integer IN_W  = 16,
    parameter integer SHIFT = 8
) (
    input  wire signed [IN_W-1:0]  x,
    output wire signed [IN_W-SHIFT:0] y
);

    // ---- parameter checks (stop elaboration on illegal values) ----
    generate
        `CUBE4_RANGE(g_bad_in_w, "cube4_round_shift", "IN_W", IN_W, 2, 64)
        if (SHIFT < 0 || SHIFT > IN_W - 1) begin : g_bad_shift
            $error("cube4_round_shift: SHIFT = %0d is out of range 0..IN_W-1 (IN_W = %0d)",
                   SHIFT, IN_W);
        end
    endgenerate

    // x sign-extended by one bit: room for the carry of the rounding add.
    wire signed [IN_W:0] x_ext = {x[IN_W-1], x};

    generate
        if (SHIFT == 0) begin : g_no_shift
            assign y = x_ext;
        end else begin : g_shift
            // 2^(SHIFT-1): one half of the output LSB.
            localparam signed [IN_W:0] HALF = {{IN_W{1'b0}}, 1'b1} << (SHIFT - 1);
            wire signed [IN_W:0] sum = x_ext + HALF;
            // Arithmetic shift right by SHIFT = drop the low SHIFT bits (floor).
            assign y = sum[IN_W:SHIFT];
        end
    endgenerate

endmodule
`default_nettype wire

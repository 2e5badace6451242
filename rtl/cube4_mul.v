`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_mul  (generic form; the ECP5 form is rtl/ecp5/cube4_mul.v)
// -----------------------------------------------------------------------------
// Purpose
//   The one registered multiplier of Cube-4: p = a * b with a register on
//   each side and no other logic in series, the shape of a hard multiplier
//   that uses its own input and output registers. A caller that wrote
//       x_q <= x_d;  y_q <= y_d;  p_q <= x_q * y_q;
//   instantiates this with a = x_d, b = y_d and gets p = p_q in the same
//   cycle: the operand registers are the multiplier's own (a caller that
//   also needs x_q elsewhere keeps its own copy, which helps fan-out too).
//   This form registers in the fabric; synthesis for the ECP5 takes the
//   vendor form (MULT18X18D with its input and output registers), which
//   nextpnr times from clock to P in 0.5 ns instead of 2.3 to 3.1 ns from
//   A/B to P without them.
//
// Parameters
//   A_W  width of a, two's complement signed.   Range 2..32.  Default 18.
//   B_W  width of b, two's complement signed.   Range 2..32.  Default 18.
//   (The ECP5 form uses one MULT18X18D for A_W, B_W <= 18; wider products
//   fall back to this form there.) Unsigned operands are passed with a zero
//   bit on top.
//   OUT_FF  1: one more register after the product, a flip-flop in the fabric
//           (both forms; rtl/cube4_mul_if.vh): a hard multiplier placed far
//           from its consumers (the DSP sites are few and fixed) then ends its
//           route at a flip-flop the placer can put anywhere on the way, and
//           the consumer's logic starts at that flip-flop, not at the DSP.
//           0..1.  Default 0.
//
// Latency
//   2 + OUT_FF cycles from a, b to p; every stage advances only when en = 1
//   (stall enable; tie to 1 in a free-running pipeline). No reset: data
//   registers.
//
// Ports (any fixed-point split: sQm.f times sQn.g is sQ(m+n).(f+g))
//   clk  in   1 bit
//   en   in   1 bit            stall enable of every stage
//   a    in   signed [A_W-1:0]
//   b    in   signed [B_W-1:0]
//   p    out  signed [A_W+B_W-1:0]   a * b 2 + OUT_FF cycles earlier (en cycles)
//
// Bit growth and rounding
//   |a * b| <= 2^(A_W-1) * 2^(B_W-1) = 2^(A_W+B_W-2), so the product fits
//   A_W + B_W signed bits exactly: no rounding, no saturation, no wrap.
// =============================================================================
module cube4_mul
`include "cube4_mul_if.vh"

    reg signed [A_W-1:0] a_q;
    reg signed [B_W-1:0] b_q;
    reg signed [P_W-1:0] p_q;
    wire signed [P_W-1:0] a_e = P_W'(a_q);   // sign-extended: the product at full width
    wire signed [P_W-1:0] b_e = P_W'(b_q);
    always @(posedge clk) begin
        if (en) begin
            a_q <= a;
            b_q <= b;
            p_q <= a_e * b_e;
        end
    end
    assign p_core = p_q;

endmodule
`default_nettype wire

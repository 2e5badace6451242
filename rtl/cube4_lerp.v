`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_lerp
// -----------------------------------------------------------------------------
// Purpose
//   The one shared linear-interpolation primitive of Cube-4 (trilinear sample
//   interpolation and every other lerp use this module):
//     y = a + round_shift((b - a) * w, WEIGHT_W)
//   with round_shift() = divide by 2^WEIGHT_W rounding half up (see
//   cube4_round_shift). Bit-exact with lerp() of golden/cube4/fixed.py.
//
// Parameters
//   DATA_W    width of the samples a, b, y.          Range 1..19.  Default 8.
//   WEIGHT_W  width of the weight w.                  Range 1..12.  Default 8.
//   LATENCY   clock cycles from inputs to y.          Range 0..4.   Default 0.
//               0: combinational (clk and en unused).
//               1: y registered.
//               2: (b - a) * w and a registered, then y registered.
//               3: b - a, w and a registered, then (b - a) * w and a, then
//                  y: the multiplier is a cube4_mul (a DSP with its own
//                  registers on an FPGA), a register on each side and no
//                  other logic in series.
//               4: as 3, with the product and a registered once more in
//                  the fabric: the route out of the hard multiplier is a
//                  cycle of its own, not in series with the add (and a
//                  caller's logic on y_next, cube4_tri_lane's differences).
//   DIFF_IN   1: the caller gives b - a (d), formed before the register a
//             comes from (so with LATENCY 3, 4 the multiplier's operand
//             register loads from a register, no subtractor in between);
//             b is not used. 0: b - a is formed here, d is not used.
//                                                    Range 0..1.   Default 0.
//
// Latency
//   LATENCY cycles. Registers advance only on a rising clk edge with en = 1
//   (stall enable); with en = 0 every stage, and therefore y, holds. There is
//   no valid/ready here: the enclosing pipeline carries the valid bits and
//   drives en. No reset: the module has datapath registers only (rst is for
//   control state, of which it has none).
//
// Ports (fixed-point formats as in docs/numerics.md: QI.F = unsigned, I integer
// and F fraction bits; sQ = signed two's complement)
//   clk  in   1 bit                 clock (used when LATENCY > 0)
//   en   in   1 bit                 stall enable (used when LATENCY > 0)
//   a    in   [DATA_W-1:0]          sample at w = 0: Q0.DATA_W (e.g. Q0.8; the same
//                                   bits read as integers 0..2^DATA_W-1 work alike,
//                                   the lerp is linear)
//   b    in   [DATA_W-1:0]          sample at w -> 1: same format as a (DIFF_IN = 0)
//   d    in   [DATA_W:0]            b - a, sQ DATA_W + 1 bits, in the cycle of a
//                                   (DIFF_IN = 1)
//   w    in   [WEIGHT_W-1:0]        weight Q0.WEIGHT_W in [0, 1 - 2^-WEIGHT_W]
//                                   (e.g. Q0.8); 1.0 is not representable, and
//                                   y = a exactly when w = 0
//   y    out  [DATA_W-1:0]          interpolated sample: same format as a
//   y_next out [DATA_W-1:0]         the value y takes at the next clock edge with
//                                   en = 1 (LATENCY >= 1; y itself with LATENCY 0):
//                                   a caller that needs a function of y one cycle
//                                   after it (cube4_tri_lane: two lerps' difference,
//                                   the next lerp's operand) registers it from here
//
// Bit growth and rounding
//   b - a              : sQ, DATA_W + 1 bits (exact).
//   (b - a) * w        : sQ, DATA_W + 1 + WEIGHT_W bits (exact: magnitude
//                        < 2^(DATA_W + WEIGHT_W)).
//   round_shift(., W)  : rounds half up (ties towards +infinity), as
//                        cube4_round_shift; the loss is at most 1/2 LSB of y,
//                        the only loss of the lerp.
//   a + rounded        : the result always lies between a and b inclusive
//                        (|rounded| <= |b - a|), so it is taken modulo
//                        2^DATA_W without loss: NO bit growth, no saturation.
//   The two adds are one: a + round_shift(p, W) = floor((p + a * 2^W +
//   2^(W-1)) / 2^W), formed as p + {a, 1, 0 ... 0} in DATA_W + WEIGHT_W bits
//   (exact modulo 2^(DATA_W + WEIGHT_W): the true sum lies in [0, that)), y
//   its bits from WEIGHT_W up: one carry chain after the product.
// =============================================================================
module cube4_lerp #(
    parameter integer DATA_W   = 8,
    parameter integer WEIGHT_W = 8,
    parameter integer LATENCY  = 0,
    parameter integer DIFF_IN  = 0
) (
    input  wire                clk,
    input  wire                en,
    input  wire [DATA_W-1:0]   a,
    input  wire [DATA_W-1:0]   b,
    input  wire [DATA_W:0]     d,
    input  wire [WEIGHT_W-1:0] w,
    output wire [DATA_W-1:0]   y,
    output wire [DATA_W-1:0]   y_next
);

    // ---- parameter checks (stop elaboration on illegal values) ----
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_lerp", "DATA_W", DATA_W, 1, 19)
        `CUBE4_RANGE(g_bad_weight_w, "cube4_lerp", "WEIGHT_W", WEIGHT_W, 1, 12)
        `CUBE4_RANGE(g_bad_latency, "cube4_lerp", "LATENCY", LATENCY, 0, 4)
        `CUBE4_RANGE(g_bad_diff_in, "cube4_lerp", "DIFF_IN", DIFF_IN, 0, 1)
    endgenerate

    localparam integer DIFF_W = DATA_W + 1;             // b - a, signed
    localparam integer PROD_W = DIFF_W + WEIGHT_W;      // (b - a) * w, signed

    // ---- difference and product ----
    // LATENCY 3: the product is a cube4_mul (b - a and w into its operand
    // registers, its product register is the stage-1 register): on an FPGA a
    // hard multiplier with its own registers; LATENCY 4 registers that
    // product (and a) once more in the fabric. LATENCY 0..2: inferred here,
    // with the product register for LATENCY 2. Both operands are extended to
    // PROD_W bits so the product is formed at the width it needs; the true
    // product fits PROD_W signed bits, so the modulo-2^PROD_W multiply is exact.
    wire signed [DIFF_W-1:0] diff_c;
    generate
        if (DIFF_IN != 0) begin : g_diff_in
            assign diff_c = $signed(d);
            wire unused_b = ^b;
        end else begin : g_diff
            assign diff_c = $signed({1'b0, b}) - $signed({1'b0, a});
            wire unused_d = ^d;
        end
    endgenerate
    wire        [DATA_W-1:0] a_m;        // the product and its a, before the product register
    wire signed [PROD_W-1:0] prod_m;
    wire        [DATA_W-1:0] a_s1;
    wire signed [PROD_W-1:0] prod_s1;

    generate
        if (LATENCY >= 3) begin : g_mul3
            reg [DATA_W-1:0] a_q0, a_q1;
            always @(posedge clk) begin
                if (en) begin
                    a_q0 <= a;
                    a_q1 <= a_q0;
                end
            end
            wire signed [PROD_W:0] p_full;     // one bit more than the product needs
            cube4_mul #(.A_W(DIFF_W), .B_W(WEIGHT_W + 1)) u_mul (
                .clk (clk), .en (en), .a (diff_c), .b ($signed({1'b0, w})), .p (p_full));
            assign a_m    = a_q1;
            assign prod_m = p_full[PROD_W-1:0];
            wire unused_p = p_full[PROD_W];
        end else begin : g_mul_inferred
            wire signed [PROD_W-1:0] diff_ext = {{WEIGHT_W{diff_c[DIFF_W-1]}}, diff_c};
            wire signed [PROD_W-1:0] w_ext    = $signed({{DIFF_W{1'b0}}, w});
            assign a_m    = a;
            assign prod_m = diff_ext * w_ext;
        end
        // LATENCY 2: the inferred product's register; 4: the hard multiplier's
        // product registered again in the fabric
        if (LATENCY == 2 || LATENCY == 4) begin : g_stage1_reg
            reg        [DATA_W-1:0] a_q;
            reg signed [PROD_W-1:0] prod_q;
            always @(posedge clk) begin
                if (en) begin
                    a_q    <= a_m;
                    prod_q <= prod_m;
                end
            end
            assign a_s1    = a_q;
            assign prod_s1 = prod_q;
        end else begin : g_stage1_comb
            assign a_s1    = a_m;
            assign prod_s1 = prod_m;
        end
    endgenerate

    // ---- rounding and final add: one adder ----
    // a + round_shift(p, W) = round_shift(a * 2^W + p, W) (a * 2^W is a
    // multiple of 2^W), and a * 2^W plus round_shift's half, 2^(W-1), is a's
    // bits beside a one: so the add of the half and the add of a are one
    // adder, p + {a, 1, 0 ... 0}, whose bits from W up are y (the floor of
    // cube4_round_shift's shift). One carry chain after the product, not two
    // (the rounding's, then a's) in series. a + rnd lies in [0, 2^DATA_W - 1]
    // (see the header), so the sum's true value lies in [0, 2^(DATA_W + W))
    // and its low DATA_W + W bits, taken modulo, are exact.
    localparam integer SUM_W = DATA_W + WEIGHT_W;
    wire [SUM_W-1:0]  a_half = (SUM_W'(a_s1) << WEIGHT_W) | (SUM_W'(1) << (WEIGHT_W - 1));
    wire [SUM_W-1:0]  sum    = prod_s1[SUM_W-1:0] + a_half;
    wire unused_sign = prod_s1[PROD_W-1];   // (PROD_W = SUM_W + 1: the sum is exact modulo 2^SUM_W)
    wire [DATA_W-1:0] y_comb = sum[WEIGHT_W +: DATA_W];
    assign y_next = y_comb;

    // ---- optional output register (LATENCY >= 1) ----
    generate
        if (LATENCY >= 1) begin : g_out_reg
            reg [DATA_W-1:0] y_q;
            always @(posedge clk) begin
                if (en) begin
                    y_q <= y_comb;
                end
            end
            assign y = y_q;
        end else begin : g_out_comb
            assign y = y_comb;
        end
    endgenerate

endmodule
`default_nettype wire

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
//   LATENCY   clock cycles from inputs to y.          Range 0..3.   Default 0.
//               0: combinational (clk and en unused).
//               1: y registered.
//               2: (b - a) * w and a registered, then y registered.
//               3: b - a, w and a registered, then (b - a) * w and a, then
//                  y: the multiplier (a DSP on an FPGA) has a register on
//                  each side and no other logic in series.
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
//   b    in   [DATA_W-1:0]          sample at w -> 1: same format as a
//   w    in   [WEIGHT_W-1:0]        weight Q0.WEIGHT_W in [0, 1 - 2^-WEIGHT_W]
//                                   (e.g. Q0.8); 1.0 is not representable, and
//                                   y = a exactly when w = 0
//   y    out  [DATA_W-1:0]          interpolated sample: same format as a
//
// Bit growth and rounding
//   b - a              : sQ, DATA_W + 1 bits (exact).
//   (b - a) * w        : sQ, DATA_W + 1 + WEIGHT_W bits (exact: magnitude
//                        < 2^(DATA_W + WEIGHT_W)).
//   round_shift(., W)  : rounds half up (ties towards +infinity), sQ with
//                        DATA_W + 2 bits out of cube4_round_shift; the loss is
//                        at most 1/2 LSB of y, the only loss of the lerp.
//   a + rounded        : the result always lies between a and b inclusive
//                        (|rounded| <= |b - a|), so it is taken modulo
//                        2^DATA_W without loss: NO bit growth, no saturation.
// =============================================================================
module cube4_lerp #(
    parameter integer DATA_W   = 8,
    parameter integer WEIGHT_W = 8,
    parameter integer LATENCY  = 0
) (
    input  wire                clk,
    input  wire                en,
    input  wire [DATA_W-1:0]   a,
    input  wire [DATA_W-1:0]   b,
    input  wire [WEIGHT_W-1:0] w,
    output wire [DATA_W-1:0]   y
);

    // ---- parameter checks (stop elaboration on illegal values) ----
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_lerp", "DATA_W", DATA_W, 1, 19)
        `CUBE4_RANGE(g_bad_weight_w, "cube4_lerp", "WEIGHT_W", WEIGHT_W, 1, 12)
        `CUBE4_RANGE(g_bad_latency, "cube4_lerp", "LATENCY", LATENCY, 0, 3)
    endgenerate

    localparam integer DIFF_W = DATA_W + 1;             // b - a, signed
    localparam integer PROD_W = DIFF_W + WEIGHT_W;      // (b - a) * w, signed
    localparam integer RND_W  = PROD_W - WEIGHT_W + 1;  // round_shift output = DATA_W + 2

    // ---- difference (combinational, or registered with LATENCY == 3) ----
    wire signed [DIFF_W-1:0] diff_c = $signed({1'b0, b}) - $signed({1'b0, a});
    wire signed [DIFF_W-1:0] diff;
    wire        [WEIGHT_W-1:0] w_s0;
    wire        [DATA_W-1:0] a_s0;

    generate
        if (LATENCY == 3) begin : g_stage0_reg
            reg signed [DIFF_W-1:0]   diff_q;
            reg        [WEIGHT_W-1:0] w_q;
            reg        [DATA_W-1:0]   a_q;
            always @(posedge clk) begin
                if (en) begin
                    diff_q <= diff_c;
                    a_q    <= a;
                end
            end
            // every lerp keeps its own weight register next to its multiplier
            // (lerps that share a weight would otherwise share one flip-flop
            // whose net spans the chip)
            (* keep *)
            always @(posedge clk) begin
                if (en) w_q <= w;
            end
            assign diff = diff_q;
            assign w_s0 = w_q;
            assign a_s0 = a_q;
        end else begin : g_stage0_comb
            assign diff = diff_c;
            assign w_s0 = w;
            assign a_s0 = a;
        end
    endgenerate

    // ---- product ----
    // Both operands extended to PROD_W bits so the product is formed at the
    // width it needs; the true product fits in PROD_W signed bits, so the
    // modulo-2^PROD_W multiply is exact.
    wire signed [PROD_W-1:0] diff_ext = {{WEIGHT_W{diff[DIFF_W-1]}}, diff};
    wire signed [PROD_W-1:0] w_ext    = $signed({{DIFF_W{1'b0}}, w_s0});
    wire signed [PROD_W-1:0] prod     = diff_ext * w_ext;

    // ---- optional product register (LATENCY >= 2): split at the multiplier ----
    wire        [DATA_W-1:0] a_s1;
    wire signed [PROD_W-1:0] prod_s1;

    generate
        if (LATENCY >= 2) begin : g_stage1_reg
            reg        [DATA_W-1:0] a_q;
            reg signed [PROD_W-1:0] prod_q;
            always @(posedge clk) begin
                if (en) begin
                    a_q    <= a_s0;
                    prod_q <= prod;
                end
            end
            assign a_s1    = a_q;
            assign prod_s1 = prod_q;
        end else begin : g_stage1_comb
            assign a_s1    = a_s0;
            assign prod_s1 = prod;
        end
    endgenerate

    // ---- rounding and final add ----
    wire signed [RND_W-1:0] rnd;

    cube4_round_shift #(
        .IN_W  (PROD_W),
        .SHIFT (WEIGHT_W)
    ) u_round_shift (
        .x (prod_s1),
        .y (rnd)
    );

    // a + rnd lies in [0, 2^DATA_W - 1], so the top two bits of sum are always
    // zero and y is its low DATA_W bits.
    wire [RND_W-1:0]  sum    = {2'b00, a_s1} + rnd;
    wire [DATA_W-1:0] y_comb = sum[DATA_W-1:0];

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

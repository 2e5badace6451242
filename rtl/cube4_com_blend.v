`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_blend
// -----------------------------------------------------------------------------
// Purpose
//   One lane of COM's blending datapath (COMPOSITING = 1; numerics.md
//   sections 7, 13): a ray's step at one sample that counts (cnt), from its
//   partial result {C_R, C_G, C_B, T} and the sample's {R', G', B', A}:
//     composite  w = round_shift(T * A, ALPHA_W);   C += round_shift(w * C', 8);  T -= w
//     X-ray      w = round_shift(2^ACC_W * A, ALPHA_W);
//                C = min(2^ACC_W, C + round_shift(w * C', 8));   T = max(0, T - w)
//   w = 0 for a sample that does not count. The finished ray's pixel is
//   {R, G, B, A} = {C_R, C_G, C_B, 2^ACC_W - T}.
//
// Parameters
//   ALPHA_W  opacity width AW.                  8..16.  Default 12.
//   ACC_W    accumulator fraction bits F.       8..24.  Default 16.
//
// Latency
//   5 + 1 cycles, no stall: acc5 and a5 (S5) are registered at the edge into
//   S6 (acc5 in a kept register of its own, cube4_prim_copies; a5 in the
//   T * A multiplier's operand register); S7 T * A, S8 w (one
//   kept copy per w * C' multiplier and one for T - w), S9 w * C', S10 the
//   sums; acc_q is the S11 register (loads on every cycle) and pix is formed
//   from it. c7 and cnt7 are S7's (c7: cube4_com_lane's register, shared with
//   the extremum lane).
//
// Ports
//   acc5       in   S5: {C_R, C_G, C_B, T}, ACC_W + 1 bits each, Q0.ACC_W
//                   (0 .. 2^ACC_W; T starts at 2^ACC_W)
//   a5         in   S5: the sample's A, Q0.ALPHA_W
//   t5         in   S5: T's factor in T * A: ONE in X-ray, else acc5's T (the
//                   caller forms it from selects of its own, so that the
//                   multiplier's operand has logic and control registers of
//                   its own, placed by it alone)
//   c7         in   S7: the sample's {R', G', B'}, Q0.8 each
//   cnt7       in   S7: the sample counts
//   mode_xray  in   X-ray (else composite); static within a frame
//   acc_q      out  S11: the new {C_R, C_G, C_B, T}, as acc5
//   pix        out  S11: {R, G, B, A}, ACC_W + 1 bits each, Q0.ACC_W
//   depth_t    in   the depth-out threshold on T (DEPTH_T), static
//   added_q    out  S11: the sample added something (w > 0)
//   passed_q   out  S11: the new T <= depth_t
//   tau        in   termination's threshold on T (static)
//   done       out  S11: the new word is done by the mode's termination rule:
//                   composite T <= tau; X-ray T = 0 and every channel ONE. One
//                   LUT after S11 registers of its own (the T compare, and per
//                   channel "is ONE" at the end of its add's carry chain)
//
// Bit growth and rounding
//   T * A: (F+1) x AW bits; round_shift by AW (half up) gives w <= T (F+1 bits).
//   w * C': (F+1) x 8 bits; round_shift by 8 (half up) gives at most w, and
//   C + that <= 2^F - T. Composite: nothing wraps, nothing saturates. X-ray:
//   C + round_shift(w * C', 8) is formed in F+2 bits and saturates at 2^F;
//   T - w saturates at 0.
// =============================================================================
module cube4_com_blend #(
    parameter integer ALPHA_W = 12, parameter integer ACC_W = 16,
    localparam integer CW    = ACC_W + 1,     // one channel
    localparam integer CMP_W = 4 * CW
) (
    input  wire clk,
    input  wire [CMP_W-1:0] acc5, input wire [ALPHA_W-1:0] a5, input wire [CW-1:0] t5,
    input  wire [23:0] c7,
    input  wire cnt7, input wire mode_xray, input wire [CW-1:0] depth_t, input wire [CW-1:0] tau,
    output reg  [CMP_W-1:0] acc_q, output wire [CMP_W-1:0] pix,
    output reg  added_q, output reg passed_q,
    output wire done
);
    generate
        `CUBE4_RANGE(g_bad_alpha_w, "cube4_com_blend", "ALPHA_W", ALPHA_W, 8, 16)
        `CUBE4_RANGE(g_bad_acc_w, "cube4_com_blend", "ACC_W", ACC_W, 8, 24)
    endgenerate
    localparam integer TA_W = CW + ALPHA_W;     // T * A
    localparam integer WC_W = CW + 8;           // w * C'
    localparam [CW-1:0] ONE = {1'b1, {ACC_W{1'b0}}};  // T = 1.0

    // S6: the partial result in a register of its own (kept apart from the
    // extremum lane's, which shares its low bits: each placed by its own logic)
    wire [CMP_W-1:0] s6_acc;
    cube4_prim_copies #(.N(1), .W(CMP_W), .RESET(0)) u_s6_acc (
        .clk(clk), .rst(1'b0), .d(acc5), .q(s6_acc));
    reg  [CMP_W-1:0] s7_acc, s8_acc;    // {C_R, C_G, C_B, T}
    reg  [3*CW-1:0]  s9_cc;             // {C_R, C_G, C_B} (T: s9_t)
    reg  [23:0]      s8_c;              // the sample's {R', G', B'}
    always @(posedge clk) begin
        {s7_acc, s8_acc, s9_cc} <= {s6_acc, s7_acc, s8_acc[CW +: 3*CW]};
        s8_c                    <= c7;
    end

    // S6: T * A (X-ray: 2^F * A); cube4_mul's operand registers take S5's
    // values, its product register is S7's
    wire [CW-1:0] t_mul_d = t5;
`ifndef SYNTHESIS
    // (t5 is the caller's: ONE in X-ray, else acc5's T; the caller registers the
    // mode with S5's selects, so in every cycle it is the mode of the cycle
    // before, which is the mode whenever S5 holds a beat: the mode changes
    // between frames only)
    reg xray_q;
    always @(posedge clk) begin
        xray_q <= mode_xray;
        if (t5 !== (xray_q ? ONE : acc5[0 +: CW]) && !$isunknown({xray_q, acc5[0 +: CW]}))
            $fatal(1, "cube4_com_blend: t5 %h is not T's factor %h", t5, xray_q ? ONE : acc5[0 +: CW]);
    end
`endif
    wire signed [TA_W+1:0] ta_p;
    cube4_mul #(.A_W(CW + 1), .B_W(ALPHA_W + 1)) u_ta (
        .clk (clk), .en (1'b1), .a ($signed({1'b0, t_mul_d})), .b ($signed({1'b0, a5})), .p (ta_p));
    wire [TA_W-1:0] s7_ta = ta_p[TA_W-1:0];   // 0 <= T * A < 2^TA_W
    wire unused_ta = ^ta_p[TA_W +: 2];

    // S7: w = round_shift(T * A, AW), 0 <= w <= T (X-ray: <= 2^F); 0 for a
    // sample that does not count
    wire signed [CW+1:0] w_rs;
    cube4_round_shift #(.IN_W(TA_W + 1), .SHIFT(ALPHA_W)) u_w (
        .x($signed({1'b0, s7_ta})), .y(w_rs));
    wire [CW-1:0] w_d = cnt7 ? w_rs[CW-1:0] : {CW{1'b0}};
    // S8: w in fabric registers between the two multipliers (the T * A
    // product register through the rounding straight into the w * C'
    // multipliers' operand registers was a DSP -> fabric -> DSP path of
    // 7 ns of routing): one copy per w * C' multiplier and one for T - w
    wire [4*CW-1:0] s8_w;       // copy ch: channel ch's multiplier; copy 3: T - w
    cube4_prim_copies #(.N(4), .W(CW), .RESET(0)) u_w8 (
        .clk(clk), .rst(1'b0), .d(w_d), .q(s8_w));

    // S8: T - w (X-ray: at least 0)
    wire [CW-1:0] w8_t = s8_w[3*CW +: CW];
    wire [CW-1:0] t8   = s8_acc[0 +: CW];
    reg  [CW-1:0] s9_t, s10_t;
    always @(posedge clk) begin
        s9_t  <= (mode_xray && w8_t > t8) ? {CW{1'b0}} : t8 - w8_t;
        s10_t <= s9_t;
    end
    // depth out: the sample added something (w > 0, S8) and the new T is at most
    // DEPTH_T (S9), carried to S11 beside acc_q
    reg s9_add, s10_add, s10_pass;
    always @(posedge clk) begin
        s9_add   <= w8_t != '0;
        s10_add  <= s9_add;
        s10_pass <= s9_t <= depth_t;
        added_q  <= s10_add;
        passed_q <= s10_pass;
    end

    // S9: w * C' per channel (cube4_mul: its operand registers take S8's w
    // and C', its product register is S10's)
    wire [3*WC_W-1:0] s10_wc;
    reg  [3*CW-1:0]   s10_c;      // C per channel
    genvar ch;
    generate
        for (ch = 0; ch < 3; ch = ch + 1) begin : g_mul   // channel ch = B, G, R for 0, 1, 2
            wire signed [WC_W+1:0] wc_p;
            cube4_mul #(.A_W(CW + 1), .B_W(9)) u_wc (
                .clk (clk), .en (1'b1), .a ($signed({1'b0, s8_w[ch*CW +: CW]})),
                .b ($signed({1'b0, s8_c[8 * ch +: 8]})), .p (wc_p));
            assign s10_wc[ch*WC_W +: WC_W] = wc_p[WC_W-1:0];   // 0 <= w * C' < 2^WC_W
            wire unused_wc = ^wc_p[WC_W +: 2];
            always @(posedge clk) s10_c[ch*CW +: CW] <= s9_cc[ch*CW +: CW];
        end
    endgenerate

    // S10: C += round_shift(w * C', 8) (X-ray: at most 2^F), in one add:
    // C + floor((wc + 2^7) / 2^8) = C + wc[WC_W-1:8] + wc[7] (wc[7] the adder's
    // carry in). C <= ONE = 2^F and wc < 2^(F+9) give sum < 2^(F+2): it fits
    // CW + 1 bits, and sum >= ONE is its top two bits (ONE is bit F), one LUT
    // after the add. The X-ray's channel is then ONE (a sum of exactly ONE is
    // ONE either way), and "the channel is ONE" is that compare, for
    // termination (one_q)
    wire [3*CW-1:0] c_out;
    wire [2:0]      c_one;          // termination's part per channel (below)
    generate
        for (ch = 0; ch < 3; ch = ch + 1) begin : g_ch
            wire [WC_W-1:0] wc  = s10_wc[ch*WC_W +: WC_W];
            wire [CW:0]     sum = {1'b0, s10_c[ch*CW +: CW]} + {1'b0, wc[WC_W-1:8]} + (CW+1)'(wc[7]);
            wire unused_frac = ^wc[6:0];
            wire over = sum[CW] || sum[CW-1];    // sum >= ONE
            assign c_out[ch*CW +: CW] = (mode_xray && over) ? ONE : sum[CW-1:0];
            assign c_one[ch] = over || !mode_xray;
        end
    endgenerate

    // S11: the new partial result (the slice buffer's write word, beside the
    // sums), and the pixel {R, G, B, A = 1 - T} from it
    always @(posedge clk) acc_q <= {c_out, s10_t};
    // termination's rule on the S11 word, in registers beside the ones it reads
    // (the word's compares would sit between acc_q and the slice buffer's write
    // otherwise): t_q the mode's compare on T (composite T <= tau, X-ray T = 0),
    // one_q[ch] "channel ch is ONE" (always 1 in composite), each at the end of
    // its own carry chain: one flip-flop taking the three chains' ends was this
    // unit's longest route (a DSP's product, the add, across to the other
    // channels). done is their AND, one LUT after S11.
    reg       t_q;
    reg [2:0] one_q;
    always @(posedge clk) begin
        t_q   <= mode_xray ? (s10_t == '0) : (s10_t <= tau);
        one_q <= c_one;
    end
    assign done = t_q && (&one_q);
    assign pix = {acc_q[CW +: 3*CW], ONE - acc_q[0 +: CW]};
endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_lane
// -----------------------------------------------------------------------------
// Purpose
//   One of COM's P lanes around its datapaths (docs/architecture.md "COM"):
//   registers the lane's shaded sample {R', G', B', A} (and its v) at R0 and
//   carries it to the datapaths; at S5 takes the ray's previous partial result
//     prev = dxb ? (t0 ? prevb_sh : back_sh) : back5     (cube4_com_bpb)
//     acc  = fresh ? the fresh word : prev
//   with the fresh word {C = 0, T = 2^ACC_W} (blending), v = 0 (MIP) or
//   2^VOXEL_W - 1 (MinIP) with RGBA = 0; steps the ray in the blending lane
//   (cube4_com_blend) and / or the extremum lane (cube4_com_ext), and at S11
//   chooses the mode's word for the slice buffer and its pixel for the FIFO.
//   The S5 selects and the write word's select take their controls from a
//   register spread over the word (cube4_prim_spread, COPIES copies).
//
// Parameters
//   ALPHA_W, ACC_W, VOXEL_W, COMPOSITING, EXTREMUM: as cube4_com.
//   AC_W     the buffer word: max of the build's modes' words
//            (blending 4 * (ACC_W + 1), extremum VOXEL_W + 24 + ALPHA_W).
//   SAMPLE   1: R0 registers the sample v (extremum, path weights).  0..1.
//   COPIES   control copies over the word.                 1..64.  Default 4.
//   ZOUT     1: depth out: the buffer word's top 2 (ZM_W + 1) bits (below
//            the countdown with TERM = 1) hold the ray's slice numbers
//            {passed, first}, each {valid, m} (AC_W includes them).
//                                                            0..1.  Default 0.
//   ZM_W     the slice number's width (COM's M_W).            1..16. Default 14.
//   FALL     1: the slab's falloff: the blending datapath's A is
//            round_shift(A * f, 8) (numerics.md section 12).  0..1.  Default 0.
//   LIVE     1: live out (the beat schedule).                0..1.  Default 0.
//
// Latency
//   R0 registers in_rgba and in_sample; the sample's word is carried R0 ->
//   S5 (S3's A goes out as a3 and comes back as a3_w into S4: the path
//   weights), S6 and S7; the S5 controls are registered here once more (their
//   copies) with the buffers' S5 words; the datapaths end in S11 registers,
//   from which acc_q and pix are combinational. 12 cycles from in_* to pix.
//
// Ports
//   in_rgba    in   {R', G', B' (Q0.8), A (Q0.ALPHA_W)} of the lane's sample
//   in_sample  in   its v (unsigned VOXEL_W)
//   in_fall    in   its falloff weight f, 0 .. 256 (Q1.8; FALL = 1, else unused)
//   smp0       out  R0's v (0 when SAMPLE = 0)
//   a3, a3_w   out / in   S3's A, and the A that goes on to S4 (Q0.ALPHA_W)
//   back5, back_sh, prevb_sh   in   S5: the buffer words (cube4_com_bpb)
//   dxb4, t0_4, fresh_4, mode_ext, mode_min   in   S4: X back step, lane at
//              t = 0, fresh ray; the mode (static within a frame)
//   mode_xray, cnt_6, cnt_7   in   the blending mode; S6's, S7's "counts"
//   depth_t    in   DEPTH_T (the blending lane's threshold on T), static
//   m11        in   S11: the beat's slice m (depth out)
//   pix_z      out  S11: {passed, first}, each {valid, m} (ZOUT = 1; else 0)
//   acc_q      out  S11: the word for the slice buffer [AC_W]
//   pix        out  S11: {R, G, B, A}, ACC_W + 1 bits each, Q0.ACC_W
//   live       out  S11: the mode's word is not the fresh one (LIVE = 1;
//              else 1): a finished ray leaves a pixel only then
//
// Bit growth and rounding: none here (see cube4_com_blend, cube4_com_ext).
// =============================================================================
module cube4_com_lane #(
    parameter integer ALPHA_W = 12, parameter integer ACC_W = 16, parameter integer VOXEL_W = 8,
    parameter integer COMPOSITING = 1, parameter integer EXTREMUM = 1,
    parameter integer AC_W   = 68, parameter integer SAMPLE = 1, parameter integer COPIES = 4,
    parameter integer FALL   = 0,
    parameter integer ZOUT   = 0, parameter integer ZM_W = 14,
    parameter integer LIVE   = 0,
    parameter integer TERM   = 0, parameter integer LAG = `CUBE4_BEAT_LAG,
    localparam integer CNT_W = `CUBE4_TERM_CNT_W(LAG),  // the termination state (TERM = 1)
    localparam integer FALL_W = 9,
    localparam integer ZF_W  = ZM_W + 1,            // a depth field {valid, m}
    localparam integer ZW    = 2 * ZF_W,            // {passed, first}
    localparam integer CW    = ACC_W + 1,
    localparam integer CMP_W = 4 * CW,
    localparam integer LUT_W = 24 + ALPHA_W,
    localparam integer EXT_W = VOXEL_W + LUT_W
) (
    input  wire clk,
    input  wire [LUT_W-1:0] in_rgba, input wire [VOXEL_W-1:0] in_sample,
    input  wire [FALL_W-1:0] in_fall,
    output wire [VOXEL_W-1:0] smp0,
    output wire [ALPHA_W-1:0] a3, input wire [ALPHA_W-1:0] a3_w,
    input  wire [AC_W-1:0] back5, input wire [AC_W-1:0] back_sh, input wire [AC_W-1:0] prevb_sh,
    input  wire dxb4, input wire t0_4, input wire fresh_4,
    input  wire mode_xray, input wire mode_ext, input wire mode_min,
    input  wire cnt_6, input wire cnt_7,
    input  wire [CW-1:0] depth_t, input wire [ZM_W-1:0] m11,
    output wire [AC_W-1:0] acc_q, output wire [CMP_W-1:0] pix, output wire [ZW-1:0] pix_z,
    output wire live,
    // termination (TERM = 1; numerics.md section 19): the rule's registers (static),
    // S11: the lane may report (its ray runs, its stop is not soon); S5: the ray
    // ends here (its countdown); S11: it reports the ray done
    input  wire term_en, input wire [CW-1:0] term_tau,
    input  wire [VOXEL_W-1:0] term_vmin, input wire [VOXEL_W-1:0] term_vmax,
    input  wire rok11, output wire fin_t5, output wire rep
);
    generate
        if (AC_W < ((COMPOSITING != 0) ? CMP_W : 1) || AC_W < ((EXTREMUM != 0) ? EXT_W : 1)) begin : g_bad_ac_w
            $error("cube4_com_lane: AC_W is narrower than a datapath's word");
        end
    endgenerate
    localparam [CW-1:0]   ONE       = {1'b1, {ACC_W{1'b0}}};
    localparam [AC_W-1:0] FRESH_CMP = AC_W'({{(3*CW){1'b0}}, ONE});                 // C = 0, T = 1
    localparam [AC_W-1:0] FRESH_MIN = AC_W'({{VOXEL_W{1'b1}}, {LUT_W{1'b0}}});     // MinIP; MIP: 0

    // ---- R0 .. S6: the sample's word ----
    reg  [LUT_W-1:0]   r0_rgba;
    reg  [5*LUT_W-1:0] rgba_l;           // stage k (S1 .. S5) at [(k-1)*LUT_W +: LUT_W]
    reg  [LUT_W-1:0]   s6_rgba, s7_rgba; // S7: one register for both datapaths
    assign a3 = rgba_l[2*LUT_W +: ALPHA_W];
    wire [LUT_W-1:0] rgba5 = rgba_l[4*LUT_W +: LUT_W];
    always @(posedge clk) begin
        r0_rgba <= in_rgba;
        rgba_l  <= {rgba_l[4*LUT_W-1:3*LUT_W], rgba_l[2*LUT_W+ALPHA_W +: 24], a3_w,
                    rgba_l[0 +: 2*LUT_W], r0_rgba};
        s6_rgba <= rgba5;
        s7_rgba <= s6_rgba;
    end
    generate
        if (SAMPLE != 0) begin : g_smp
            reg [VOXEL_W-1:0] r0_smp;
            always @(posedge clk) r0_smp <= in_sample;
            assign smp0 = r0_smp;
        end else begin : g_no_smp
            wire unused_in_smp = ^in_sample;
            assign smp0 = '0;
        end
    endgenerate

    // ---- S3 .. S5: the slab's falloff (FALL = 1): the blending A at S5 is
    // round_shift(A_w * f, 8), A_w the A that goes on to S4 (a3_w, after the
    // path weights), f the sample's falloff weight carried R0 .. S3; a
    // cube4_mul whose operand registers are S4's and product register S5's ----
    wire [ALPHA_W-1:0] a5_blend;
    generate
        if (FALL != 0) begin : g_fall
            reg  [FALL_W-1:0] r0_f, s1_f, s2_f, s3_f;
            always @(posedge clk) {s3_f, s2_f, s1_f, r0_f} <= {s2_f, s1_f, r0_f, in_fall};
            localparam integer FP_W = ALPHA_W + FALL_W + 2;
            wire signed [FP_W-1:0] s5_p;
            cube4_mul #(.A_W(ALPHA_W + 1), .B_W(FALL_W + 1)) u_fall (
                .clk(clk), .en(1'b1), .a($signed({1'b0, a3_w})), .b($signed({1'b0, s3_f})), .p(s5_p));
            // A_w * f <= A_w * 2^8: the rounded product fits ALPHA_W bits
            wire [FP_W-1:0] s5_r = $unsigned(s5_p) + FP_W'(128);
            assign a5_blend = s5_r[8 +: ALPHA_W];
            wire unused_r = ^{s5_r[FP_W-1:8+ALPHA_W], s5_r[7:0], rgba5[0 +: ALPHA_W]};
        end else begin : g_no_fall
            assign a5_blend = rgba5[0 +: ALPHA_W];
            wire unused_fall = ^in_fall;
        end
    endgenerate

    // ---- S5: the previous partial result, or a fresh ray ----
    // (one flip-flop for all lanes, or one per lane, drove 2 * AC_W multiplexers
    // spread over the lane and was the P = 8 build's critical net)
    wire [5*AC_W-1:0] ctl;              // {dxb, t0, fresh, ext, min} over the word
    cube4_prim_spread #(.W(5), .D(AC_W), .COPIES(COPIES)) u_ctl (
        .clk(clk), .rst(1'b0), .d({dxb4, t0_4, fresh_4, mode_ext, mode_min}), .q(ctl));
    wire [AC_W-1:0] min_v   = ctl[0 +: AC_W],      ext_v = ctl[AC_W +: AC_W];
    wire [AC_W-1:0] fresh_v = ctl[2*AC_W +: AC_W], t0_v  = ctl[3*AC_W +: AC_W];
    wire [AC_W-1:0] dxb_v   = ctl[4*AC_W +: AC_W];
    // prev = dxb ? (t0 ? prevb_sh : back_sh) : back5, bit by bit with each bit's selects
    function automatic [AC_W-1:0] prev_of(input [AC_W-1:0] dxb, input [AC_W-1:0] t0);
        prev_of = (dxb & ((t0 & prevb_sh) | (~t0 & back_sh))) | (~dxb & back5);
    endfunction
    wire [AC_W-1:0] prev    = prev_of(dxb_v, t0_v);
    wire [AC_W-1:0] fresh_w = (ext_v & min_v & FRESH_MIN) | (~ext_v & FRESH_CMP);
    wire [AC_W-1:0] acc_in  = (fresh_v & fresh_w) | (~fresh_v & prev);
    // T's factor in T * A (cube4_com_blend t5): ONE in X-ray and for a fresh
    // composite ray, zero for a fresh extremum ray (fresh_w's T bits), else
    // prev's T; from control registers of its own (t_one, t_keep and the X-step
    // selects), so the multiplier's operand is logic of its own beside it,
    // not acc_in's (which the lane's S6 registers also take)
    wire [4*CW-1:0] tctl;
    cube4_prim_spread #(.W(4), .D(CW), .COPIES(1)) u_tctl (
        .clk(clk), .rst(1'b0),
        .d({dxb4, t0_4, mode_xray || (fresh_4 && !mode_ext), !mode_xray && !fresh_4}), .q(tctl));
    wire [CW-1:0] t_keep = tctl[0 +: CW], t_one = tctl[CW +: CW];
    wire [CW-1:0] t_t0   = tctl[2*CW +: CW], t_dxb = tctl[3*CW +: CW];
    wire [AC_W-1:0] t_prev_w = prev_of(AC_W'(t_dxb), AC_W'(t_t0));   // (its T bits are used)
    wire [CW-1:0] t_prev = t_prev_w[0 +: CW];
    wire unused_t_prev = ^t_prev_w[AC_W-1:CW];   // (the word above T: acc_in's)
    wire [CW-1:0] t5     = (t_keep & t_prev) | (t_one & ONE);

    // ---- S6 .. S11: the datapaths (their S11 registers) ----
    wire cnt6_t, cnt7_t;                // the counts, without a ray done before (TERM)
    wire added_c, passed_c, take_e;     // S11: the datapaths' depth-out flags
    wire done_c, done_e;                // S11: termination's rule on their words
    wire [AC_W-1:0]  acc_c, acc_e;       // S11: the blending, the extremum word
    wire [CMP_W-1:0] pix_c, pix_e;
    generate
        if (COMPOSITING != 0) begin : g_blend
            wire [CMP_W-1:0] acc_c_q;
            cube4_com_blend #(.ALPHA_W(ALPHA_W), .ACC_W(ACC_W)) u_blend (
                .clk(clk), .acc5(acc_in[CMP_W-1:0]), .a5(a5_blend), .t5(t5),
                .c7(s7_rgba[ALPHA_W +: 24]), .cnt7(cnt7_t), .mode_xray(mode_xray), .depth_t(depth_t),
                .tau(term_tau), .acc_q(acc_c_q), .pix(pix_c), .added_q(added_c), .passed_q(passed_c),
                .done(done_c));
            assign acc_c = AC_W'(acc_c_q);
        end else begin : g_no_blend
            wire unused_blend = ^{mode_xray, cnt7_t, a5_blend, depth_t, t5};
            assign acc_c = '0;
            assign pix_c = '0;
            assign {added_c, passed_c, done_c} = 3'b000;
        end
        if (EXTREMUM != 0) begin : g_ext
            wire [EXT_W-1:0] acc_e_q;
            cube4_com_ext #(.ALPHA_W(ALPHA_W), .ACC_W(ACC_W), .VOXEL_W(VOXEL_W)) u_ext (
                .clk(clk), .v0(smp0), .acc5(acc_in[EXT_W-1:0]), .rgba7(s7_rgba), .cnt6(cnt6_t),
                .mode_min(mode_min), .vmin(term_vmin), .vmax(term_vmax),
                .acc_q(acc_e_q), .pix(pix_e), .take_q(take_e), .done_q(done_e));
            assign acc_e = AC_W'(acc_e_q);
        end else begin : g_no_ext
            wire unused_ext = ^{cnt6_t, s7_rgba[0 +: ALPHA_W]};
            assign acc_e = '0;
            assign pix_e = '0;
            assign take_e = 1'b0;
            assign done_e = 1'b0;
        end
        // the pixel for the FIFO: the mode's
        if (COMPOSITING != 0 && EXTREMUM != 0) begin : g_pix_both
            assign pix = mode_ext ? pix_e : pix_c;
        end else if (COMPOSITING != 0) begin : g_pix_blend
            wire unused_pix_e = ^pix_e;
            assign pix = pix_c;
        end else begin : g_pix_ext
            wire unused_pix_c = ^pix_c;
            assign pix = pix_e;
        end
    endgenerate
    // the slice buffer's write word: the mode's, chosen with the ext copies
    // (on the route to its block RAMs, which are spread over the die)
    wire [AC_W-1:0] acc_m = (ext_v & acc_e) | (~ext_v & acc_c);
    // LIVE = 1: S11's word is not the fresh one (a sample added to the ray)
    generate
        if (LIVE != 0) begin : g_live
            assign live = (acc_m != fresh_w);
        end else begin : g_no_live
            assign live = 1'b1;
        end
    endgenerate

    // ---- termination (TERM = 1): a ray is done when no later sample may
    // change it (golden/cube4/beats.py TerminationRule.dead): composite T <= tau;
    // X-ray T = 0 and every colour at 1; MIP / MinIP its v at the volume's
    // largest / smallest value. Done before its sample (S5), the sample does not
    // count; done after it (S11) and not before (or fresh), it reports, and its
    // countdown starts at LAG: the ray ends LAG slices later (fin_t5 where the
    // count it brings is 1). The state rides in the buffer word above the mode's
    // (CUBE4_TERM_CNT_W): 0 live, LAG .. 1 the countdown, LAG + 1 done without
    // one (not reported: its stop was near). So a word is done exactly when its
    // state is not 0 (a done ray stays done: its samples no longer count), and
    // "done before the sample" at S5 is that, or for a fresh ray the rule on
    // the fresh word (static in a frame, a register): no compare of the word at
    // S5. At S11 the rule is the datapaths' registered flags. ----
    localparam integer DW = (AC_W > CMP_W) ? ((AC_W > EXT_W) ? AC_W : EXT_W) : ((CMP_W > EXT_W) ? CMP_W : EXT_W);
    function automatic is_dead(input [DW-1:0] w, input ext, input mn, input xr);
        begin
            if (ext) is_dead = w[EXT_W-1 -: VOXEL_W] == (mn ? term_vmin : term_vmax);
            else if (xr) is_dead = (w[0 +: CW] == '0) && (w[CW +: CW] == ONE) && (w[2*CW +: CW] == ONE)
                                   && (w[3*CW +: CW] == ONE);
            else is_dead = (w[0 +: CW] <= term_tau);
        end
    endfunction
    wire [AC_W-1:0] acc_n;                // the word the slice buffer takes (with the state)
    generate
        if (TERM != 0) begin : g_term
            localparam integer AM_W = AC_W - CNT_W;
            localparam [CNT_W-1:0] DONE = CNT_W'(LAG + 1);   // done without a countdown
            wire ext = ext_v[AC_W-1], mn = min_v[AC_W-1], fr = fresh_v[AC_W-1];
            wire [CNT_W-1:0] cnt5 = acc_in[AM_W +: CNT_W];
            // the rule on the fresh word: the mode and the rule's registers are static
            reg fresh_dead_q;
            always @(posedge clk) fresh_dead_q <= is_dead(DW'(fresh_w), ext, mn, mode_xray);
            wire dead5 = term_en && (fr ? fresh_dead_q : (cnt5 != '0));
            assign fin_t5 = term_en && !fr && (cnt5 == CNT_W'(1));
            reg  [5:0] dead_s, fresh_s;      // S6 .. S11
            reg  [CNT_W-1:0] c6, c7, c8, c9, c10, c11;
            always @(posedge clk) begin
                dead_s  <= {dead_s[4:0], dead5};
                fresh_s <= {fresh_s[4:0], fr};
                {c11, c10, c9, c8, c7, c6} <= {c10, c9, c8, c7, c6, cnt5};
            end
            assign cnt6_t = cnt_6 && !dead_s[0];
            assign cnt7_t = cnt_7 && !dead_s[1];
            // the rule on the S11 word, from the datapaths' registered flags
            wire dead11 = term_en && (ext ? done_e : done_c);
            assign rep = rok11 && dead11 && (fresh_s[5] || !dead_s[5]);
            // (a fresh word's state is 0; c11 = 1 ends the ray here)
            wire counting = (c11 > CNT_W'(1)) && (c11 <= CNT_W'(LAG));
            wire [CNT_W-1:0] c_n = rep ? CNT_W'(LAG) : (counting ? c11 - 1'b1 : (dead11 ? DONE : '0));
            assign acc_n = {c_n, acc_m[AM_W-1:0]};
            wire unused_top = ^acc_m[AC_W-1:AM_W];
        end else begin : g_no_term
            assign fin_t5 = 1'b0;
            assign rep = 1'b0;
            assign cnt6_t = cnt_6;
            assign cnt7_t = cnt_7;
            assign acc_n = acc_m;
            wire unused_term = ^{term_en, term_tau, term_vmin, term_vmax, rok11, done_c, done_e};
        end
    endgenerate
    // ---- depth out (ZOUT = 1; numerics.md section 21): the ray's two slice
    // numbers {valid, m} ride above the mode's word, S5 -> S11, and are set at
    // S11 with the beat's slice m11 when not yet valid: passed when the blending
    // lane's T <= DEPTH_T (the extremum lane: at every take), first when the
    // sample added something (the extremum lane: was taken) ----
    generate
        if (ZOUT != 0) begin : g_depth
            // the fields sit below the countdown (TERM = 1: {count, passed, first, mode's word})
            localparam integer ZT   = AC_W - ((TERM != 0) ? CNT_W : 0);
            localparam integer AM_W = ZT - ZW;          // the mode's word
            reg [ZW-1:0] z6, z7, z8, z9, z10, z11;
            always @(posedge clk) {z11, z10, z9, z8, z7, z6} <= {z10, z9, z8, z7, z6, acc_in[AM_W +: ZW]};
            wire ext = ext_v[AC_W-1];
            wire [ZF_W-1:0] zp = z11[ZF_W +: ZF_W], zf = z11[0 +: ZF_W];
            wire [ZF_W-1:0] now = {1'b1, m11};
            wire added = ext ? take_e : added_c;
            wire [ZF_W-1:0] zp_n = ext ? (take_e ? now : zp) : ((!zp[ZM_W] && passed_c) ? now : zp);
            wire [ZF_W-1:0] zf_n = (!zf[ZM_W] && added) ? now : zf;
            assign pix_z = {zp_n, zf_n};
            if (TERM != 0) begin : g_with_count
                assign acc_q = {acc_n[AC_W-1:ZT], zp_n, zf_n, acc_m[AM_W-1:0]};
                wire unused_top = ^{acc_m[AC_W-1:AM_W], acc_n[ZT-1:0]};
            end else begin : g_no_count
                assign acc_q = {zp_n, zf_n, acc_m[AM_W-1:0]};
                wire unused_top = ^{acc_m[AC_W-1:AM_W], acc_n};
            end
        end else begin : g_no_depth
            assign pix_z = '0;
            assign acc_q = acc_n;
            wire unused_depth = ^{added_c, passed_c, take_e, m11, depth_t};
        end
    endgenerate
endmodule
`default_nettype wire

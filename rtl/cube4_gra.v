`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_gra
// -----------------------------------------------------------------------------
// Purpose
//   The GRA units of all P pipelines (Teramac paper, section 5): central
//   differences on interpolated samples over three sample slices, with the
//   shear correction, exactly as docs/numerics.md section 5:
//     gi = s[m, j, i+1] - s[m, j, i-1]
//     gj = s[m, j+1, i] - s[m, j-1, i]
//     gr = s[m+1, j+dyf, i+dxf] - s[m-1, j-dyb, i-dxb]   (X/Y-step, old X/Y-step)
//     gk = S * gr - round_shift(VIEW_X * gi + VIEW_Y * gj, W)
//   with zero outside the volume (rows -1 and NJ, columns -1 and NI, slices -1
//   and M). Four units in a row:
//     u_src     the neighbourhood source: each incoming sample beat
//               X = (m+1, j+1) with six earlier beats around the centre
//               c' = (m, j): cube4_gra_lines (delay lines of the fixed
//               schedule, and the flush steps after a frame), or with
//               RECTS = 1 cube4_gra_walk (position buffers of the slice
//               rectangles' walk), or with BEATS = 1 cube4_gra_beats (position
//               buffers of the beat schedule, with the steps its centres
//               need); one interface, chosen by RECTS and BEATS
//     u_window  cube4_gra_window: alignment, zero rows and slices, the
//               three-beat window, i +/- 1 and the ray's rows: the operands
//     u_arith   cube4_gra_arith: the differences, the products and gk
//     u_fifo    the output FIFO (cube4_credit_fifo, 16 entries); with
//               RECTS = 1 each beat first waits in a hold register until the
//               next one comes or the walk ends, so that the last carries EOP
//               (the input's last beat may lie outside the rectangles)
//
// Parameters
//   P        pipelines.                            1..64.     Default 8.
//   VOXEL_W  sample bits.                          1..16.     Default 8.
//   WEIGHT_W view weight bits W.                   4..12.     Default 8.
//   MAX_DIM, MAX_SS_LOG2  as cube4_tri (derived widths: cube4_defs.vh).
//                                                  Defaults 256, 0.
//   RECTS    1: slice rectangles (cube4_gra_walk). 0..1.      Default 0.
//   BEATS    1: the beat schedule (cube4_gra_beats; every input beat leaves
//            as a centre, in order, with its header). Needs RECTS = 0.
//                                                  0..1.      Default 0.
//   LABELS   1: each sample carries its label (LABEL_W bits above the value,
//            numerics.md section 24): the source's lines hold whole samples,
//            the window and the arithmetic read the values, and the centre's
//            label follows the window's and the arithmetic's registers to
//            out_sample. Needs RECTS = 0.            0..1.      Default 0.
//   GRAD_W   gradient width = VOXEL_W + 5 (derived; signed)
//
// Latency
//   A sample beat leaves NJ*NB + NB + 2 beats after it entered (the plane and
//   beam delays and the window), plus the source's input register, the
//   arithmetic's four register stages (the last the view products in fabric
//   flip-flops after their multipliers', cube4_mul OUT_FF = 1) and the
//   output FIFO's memory, which stores gk's two subtractions after them
//   (with RECTS = 1 the hold register and one more before it). The source
//   and the window move on GRA's step (a beat is taken or a flush step
//   runs), which needs a credit of the output FIFO (an entry reserved for
//   the gradient beat the step may produce); the credit comes as GRA_STEPS
//   register copies (u_credit), one per group of step registers in the
//   source. The arithmetic moves on every cycle with valid bits; out_ready
//   reaches only the step and the FIFO's read pointers.
//
// Ports
//   in_*   the sample stream of cube4_tri (same fields and formats; a lane is
//          SMP_W bits, {label, value} with LABELS); in_eoss with BEATS = 1:
//          the beat is the last of its slice (cube4_frontend smp_eoss)
//   out_sample  [P*SMP_W]    the sample s[m, j, i] (unsigned, Q0.VOXEL_W; with
//                            LABELS its label above it)
//   out_gi/gj/gk [P*GRAD_W]  gradient per lane, signed integers, 2x the central
//                            differences in traversal axes (numerics.md 5)
//   out_hdr                  the sample beat's header, unchanged (cube4_defs.vh)
//   cfg                      view registers (cube4_defs.vh)
//
// Bit growth and rounding
//   As cube4_gra_arith: gi, gj, gr exact in VOXEL_W + 1 bits; the one
//   rounding is round_shift by W (half up) of VIEW_X*gi + VIEW_Y*gj; gk is
//   exact in GRAD_W = VOXEL_W + 5 bits. No saturation.
// =============================================================================
module cube4_gra #(
    `CUBE4_GRA_PARAMS, parameter integer RECTS = 0, parameter integer BEATS = 0, parameter integer LABELS = 0,
    localparam integer GRAD_W  = VOXEL_W + 5,
    localparam integer LBL_W   = (LABELS != 0) ? 4 : 0,    // (CUBE4_WORD_LAYOUT's)
    localparam integer SMP_W   = VOXEL_W + LBL_W
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    // sample stream in
    input  wire in_valid,  output wire in_ready,  input  wire [HDR_W-1:0] in_hdr,
    input  wire [P*SMP_W-1:0] in_sample,
    input  wire in_eoss,          // BEATS = 1: the input beat is the last of its slice (0 otherwise)
    // gradient stream out: the sample and its gradient (gi, gj, gk)
    output wire out_valid, input  wire out_ready, output wire [HDR_W-1:0] out_hdr,
    output wire [P*SMP_W-1:0] out_sample,
    output wire [P*GRAD_W-1:0]  out_gi, output wire [P*GRAD_W-1:0] out_gj, output wire [P*GRAD_W-1:0] out_gk
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_gra", "P", P, 1, 64)
        `CUBE4_RANGE(g_bad_voxel_w, "cube4_gra", "VOXEL_W", VOXEL_W, 1, 16)
        `CUBE4_RANGE(g_bad_rects, "cube4_gra", "RECTS", RECTS, 0, 1)
        `CUBE4_RANGE(g_bad_labels, "cube4_gra", "LABELS", LABELS, 0, 1)
        `CUBE4_RANGE(g_bad_beats, "cube4_gra", "BEATS", BEATS, 0, 1)
        if (LABELS != 0 && RECTS != 0) begin : g_labels_rects
            $error("cube4_gra: LABELS = 1 needs RECTS = 0");
        end
        if (BEATS != 0 && RECTS != 0) begin : g_beats_alone
            $error("cube4_gra: BEATS = 1 needs RECTS = 0");
        end
    endgenerate

    localparam integer PV         = P * VOXEL_W;
    localparam integer PS         = P * SMP_W;
    localparam integer FIFO_DEPTH = 16;   // >= 6 cycles from a step to the FIFO's read (8 with RECTS)

    // ------------------------------------------------------------ neighbourhood source
    wire [GRA_STEPS-1:0]  credit;         // copies of the output FIFO's credit
    wire                  step, sop, fend;
    wire [PS-1:0]         xs, b1s, p1s, cs, p1b2s, p2b1s, p2b2s;   // whole samples
    wire [PV-1:0]         x, b1, p1, c, p1b2, p2b1, p2b2;          // their values
    wire [GRA_META_W-1:0] c_meta;
    wire [P*GRA_NSEL-1:0] c_sel;
    wire [1:0]            c_edge;
    // the source, by one port map (cube4_gra_source_if.vh): delay lines or the walk
`define CUBE4_GRA_SOURCE(MODULE) \
            MODULE #( \
                .P(P), .MAX_DIM(MAX_DIM), .VOXEL_W(SMP_W), .MAX_SS_LOG2(MAX_SS_LOG2), .WEIGHT_W(WEIGHT_W) \
            ) u_src ( \
                .clk(clk), .rst(rst), .cfg(cfg), \
                .in_valid(in_valid), .in_ready(in_ready), .in_hdr(in_hdr), .in_sample(in_sample), .in_eoss(in_eoss), \
                .credit(credit), .step(step), .sop(sop), .fend(fend), \
                .x(xs), .b1(b1s), .p1(p1s), .c(cs), .p1b2(p1b2s), .p2b1(p2b1s), .p2b2(p2b2s), \
                .c_meta(c_meta), .c_sel(c_sel), .c_edge(c_edge));
    generate
        if (BEATS != 0) begin : g_beats
            `CUBE4_GRA_SOURCE(cube4_gra_beats)
        end else if (RECTS == 0) begin : g_lines
            `CUBE4_GRA_SOURCE(cube4_gra_lines)
        end else begin : g_walk
            `CUBE4_GRA_SOURCE(cube4_gra_walk)
        end
    endgenerate
`undef CUBE4_GRA_SOURCE

    // the values of the source's samples (the window and the arithmetic read
    // them), and the centre's labels (LABELS), which follow the centre through
    // the window's two step registers (h1, h2: its s) and the arithmetic's four
    genvar q;
    wire [P*LBL_W+(1-LABELS)-1:0] c_lbl;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_val
            assign x[q*VOXEL_W +: VOXEL_W]    = xs[q*SMP_W +: VOXEL_W];
            assign b1[q*VOXEL_W +: VOXEL_W]   = b1s[q*SMP_W +: VOXEL_W];
            assign p1[q*VOXEL_W +: VOXEL_W]   = p1s[q*SMP_W +: VOXEL_W];
            assign c[q*VOXEL_W +: VOXEL_W]    = cs[q*SMP_W +: VOXEL_W];
            assign p1b2[q*VOXEL_W +: VOXEL_W] = p1b2s[q*SMP_W +: VOXEL_W];
            assign p2b1[q*VOXEL_W +: VOXEL_W] = p2b1s[q*SMP_W +: VOXEL_W];
            assign p2b2[q*VOXEL_W +: VOXEL_W] = p2b2s[q*SMP_W +: VOXEL_W];
            if (LABELS != 0) begin : g_lbl
                assign c_lbl[q*LBL_W +: LBL_W] = cs[q*SMP_W + VOXEL_W +: LBL_W];
                wire unused_lbl = ^{xs[q*SMP_W + VOXEL_W +: LBL_W], b1s[q*SMP_W + VOXEL_W +: LBL_W],
                                    p1s[q*SMP_W + VOXEL_W +: LBL_W], p1b2s[q*SMP_W + VOXEL_W +: LBL_W],
                                    p2b1s[q*SMP_W + VOXEL_W +: LBL_W], p2b2s[q*SMP_W + VOXEL_W +: LBL_W]};
            end
        end
        if (LABELS == 0) begin : g_no_lbl
            assign c_lbl = 1'b0;
        end
    endgenerate

    // ------------------------------------------------------------ window
    wire                     take;        // a real centre steps: its FIFO entry is taken
    wire [HDR_W-1:0]         w_hdr;
    wire [PV-1:0]            w_s, w_hi, w_lo, w_fwd, w_back;
    wire [P*(VOXEL_W+1)-1:0] w_gj;
    cube4_gra_window #(
        .P(P), .MAX_DIM(MAX_DIM), .VOXEL_W(VOXEL_W), .MAX_SS_LOG2(MAX_SS_LOG2), .WEIGHT_W(WEIGHT_W),
        .RECTS(RECTS), .BEATS(BEATS)
    ) u_window (
        .clk(clk), .rst(rst), .cfg(cfg), .step(step), .sop(sop),
        .x(x), .b1(b1), .p1(p1), .c(c), .p1b2(p1b2), .p2b1(p2b1), .p2b2(p2b2),
        .c_meta(c_meta), .c_sel(c_sel), .c_edge(c_edge),
        .take(take), .c_hdr(w_hdr), .s(w_s), .hi(w_hi), .lo(w_lo), .fwd(w_fwd), .back(w_back), .gj(w_gj));

    // ------------------------------------------------------------ arithmetic
    wire                push_v;           // the arithmetic's output holds a beat next cycle
    wire [HDR_W-1:0]    a_hdr;
    wire [PV-1:0]       a_s;
    wire [PS-1:0]       a_smp;            // a_s with the centre's labels (LABELS)
    wire [P*GRAD_W-1:0] a_gi, a_gj, a_gk;
    cube4_gra_arith #(
        .P(P), .MAX_DIM(MAX_DIM), .VOXEL_W(VOXEL_W), .MAX_SS_LOG2(MAX_SS_LOG2), .WEIGHT_W(WEIGHT_W)
    ) u_arith (
        .clk(clk), .rst(rst), .cfg(cfg),
        .in_v(take), .in_hdr(w_hdr), .in_s(w_s), .in_hi(w_hi), .in_lo(w_lo), .in_fwd(w_fwd), .in_back(w_back),
        .in_gj(w_gj),
        .out_v_d(push_v), .out_hdr(a_hdr), .out_sample(a_s), .out_gi(a_gi), .out_gj(a_gj), .out_gk(a_gk));

    generate
        if (LABELS != 0) begin : g_label
            // h1, h2 as the window's centre registers (on step), then g1 .. g4 as
            // the arithmetic's (every cycle): the labels of the sample in a_s
            reg [P*LBL_W-1:0] l_h1, l_h2, l_g1, l_g2, l_g3, l_g4;
            always @(posedge clk) begin
                if (step) begin
                    l_h1 <= c_lbl;
                    l_h2 <= l_h1;
                end
                l_g1 <= l_h2;
                l_g2 <= l_g1;
                l_g3 <= l_g2;
                l_g4 <= l_g3;
            end
            for (q = 0; q < P; q = q + 1) begin : g_lane
                assign a_smp[q*SMP_W +: SMP_W] = {l_g4[q*LBL_W +: LBL_W], a_s[q*VOXEL_W +: VOXEL_W]};
            end
        end else begin : g_no_label
            assign a_smp = a_s;
            wire unused_c_lbl = c_lbl;
        end
    endgenerate

    // ------------------------------------------------------------ output
    // the FIFO's memory (gk's subtractions after the arithmetic's g4, whose
    // products are fabric flip-flops: cube4_gra_arith): push_d one cycle
    // before the FIFO stores the item
    localparam integer OUT_W = HDR_W + PS + 3 * P * GRAD_W;
    localparam integer EOP_BIT = OUT_W - HDR_W + HDR_CTRL + CTRL_EOP;   // the header's EOP in an item
    wire [OUT_W-1:0] fifo_out;
    wire [OUT_W-1:0] item = {a_hdr, a_smp, a_gi, a_gj, a_gk};
    wire unused_credit;                 // (the source's step nets take their own copies)
    wire credit_d;
    wire push_d;
    wire [OUT_W-1:0] fifo_in;
    generate
        if (RECTS == 0) begin : g_push
            assign push_d  = push_v;
            assign fifo_in = item;
            wire unused_g = fend;   // (the lines never end a frame early; the beats' last centre carries EOP)
        end else begin : g_hold
            // The frame's last beat is known only when GRA's walk ends (the input's
            // last beat may be one outside the rectangles): each beat waits in
            // hold_q until the next one comes (then it is pushed) or the frame
            // ends (then it is pushed with EOP). push_d says so one cycle before
            // g5_q holds the beat, which the FIFO stores.
            reg               g4_v, g1_end, g2_end, g3_end, g4_end, hold_v;
            reg [OUT_W-1:0]   hold_q, g5_q;
            always @(posedge clk) begin
                if (rst) begin
                    g4_v   <= 1'b0;
                    g1_end <= 1'b0;
                    g2_end <= 1'b0;
                    g3_end <= 1'b0;
                    g4_end <= 1'b0;
                    hold_v <= 1'b0;
                end else begin
                    g4_v   <= push_v;
                    g1_end <= step && fend;
                    g2_end <= g1_end;
                    g3_end <= g2_end;
                    g4_end <= g3_end;
                    if (g4_v)        hold_v <= 1'b1;
                    else if (g4_end) hold_v <= 1'b0;
                end
            end
            always @(posedge clk) begin
                if (g4_v) begin
                    hold_q          <= item;
                    hold_q[EOP_BIT] <= 1'b0;
                end
                if (g4_v || g4_end) begin
                    g5_q          <= hold_q;
                    g5_q[EOP_BIT] <= g4_end;
                end
            end
            assign push_d  = (g4_v || g4_end) && hold_v;
            assign fifo_in = g5_q;
        end
    endgenerate
    cube4_prim_copies #(.N(GRA_STEPS), .RST_VAL(64'd1)) u_credit (
        .clk(clk), .rst(rst), .d(credit_d), .q(credit));
    wire unused_valid_cp;
    cube4_credit_fifo #(.DATA_W(OUT_W), .DEPTH(FIFO_DEPTH), .IN_REG(0)) u_fifo (
        .clk(clk), .rst(rst), .take(take), .give(1'b0),
        .credit(unused_credit), .credit_d(credit_d),
        .push_d(push_d), .in_data(fifo_in),
        .out_valid(out_valid), .out_ready(out_ready), .out_data(fifo_out), .out_valid_cp(unused_valid_cp));
    assign {out_hdr, out_sample, out_gi, out_gj, out_gk} = fifo_out;

endmodule
`default_nettype wire

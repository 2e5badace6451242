`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_gra_lines
// -----------------------------------------------------------------------------
// Purpose
//   GRA's neighbourhood source for the fixed schedule (RECTS = 0): plane and
//   beam delay lines (cube4_delay_line, in beats) that bring each incoming
//   sample beat X = (m+1, j+1, pb) together with six earlier beats:
//     B1 = (m+1, j)   one beam back            P1   = (m, j+1)   one plane back
//     C  = (m, j)     the centre c'            P1b2 = (m, j-1)   a beam behind C
//     P2b1 = (m-1, j) a plane behind C         P2b2 = (m-1, j-1) a beam behind P2b1
//   (positions in beats of the stream m, j, pb: a beam is NB beats, a plane
//   NJ*NB, so row j + 1 = NJ is row 0 of the next slice, whose samples the
//   window zeroes). A beat before the frame's first reads as zero (the lines
//   are cleared at the frame start). After the frame's last beat the source
//   runs NJ*NB + NB + 2 zero "flush" steps (the samples of slice M and
//   beyond) to finish the last slice; then it takes the next frame.
//   The centre's select flags are computed from P1 (the beat one beam
//   before C) and travel with it through the last beam line, one copy per
//   lane, so each lane's selects in the window are registers of its own.
//
// Parameters
//   P, VOXEL_W, WEIGHT_W, MAX_DIM, MAX_SS_LOG2 as cube4_gra (derived widths:
//   cube4_defs.vh CUBE4_GEOMETRY, CUBE4_GRA_LAYOUT)
//
// Latency
//   The input register i0 (a stream register: loaded whenever it is empty or
//   its beat steps, one beat per cycle; in_ready depends on registers only),
//   then the interface shows i0's beat as X, combinationally; the other six
//   beats are the delay lines' registered outputs. Everything moves on step
//   (a beat of i0 steps, or a flush step runs), which needs a credit of the
//   output FIFO. The credit comes as GRA_STEPS register copies, and each
//   group of registers (each delay line; copy GRA_STEPS-1: the counters and
//   the window) has its own step, flush and frame-start nets, each from its
//   own copies (cube4_prim_reg_copies): no single net reaches every clock
//   enable.
//
// Ports (samples unsigned Q0.VOXEL_W, P lanes of VOXEL_W bits, lane q at
// [q*VOXEL_W +: VOXEL_W], in the lane alignment of their own beat)
//   in_*      the sample stream of cube4_tri (cube4_defs.vh header)
//   credit    [GRA_STEPS]   copies of the output FIFO's credit
//   step      out  the source and the window move this cycle
//   sop       out  the step's beat X starts a frame (the window's frame start)
//   fend      out  0 (slice rectangles only)
//   x, b1, p1, c, p1b2, p2b1, p2b2  [P*VOXEL_W]  the seven beats above; lanes
//             without a valid position (and flush steps) are zero
//   c_meta    [GRA_META_W]  {real, header} of C (real: not a flush step)
//   c_sel     [P*GRA_NSEL]  C's select flags, copy q for lane q (GSEL_*)
//   c_edge    out  0 (slice rectangles only)
//
// Bit growth and rounding: none (samples are passed, not computed).
// =============================================================================
module cube4_gra_lines
`include "cube4_gra_source_if.vh"

    localparam integer VW     = VOXEL_W;
    localparam integer PV     = P * VW;
    localparam integer NSTEP  = GRA_STEPS;      // 0..5 the delay lines, 6 window and counters
    localparam integer META_W = GRA_META_W;
    localparam integer NSEL   = GRA_NSEL;

    `CUBE4_VIEW_FIELDS(cfg);

    // ------------------------------------------------------------ input register
    reg               i0_v;
    reg [PV-1:0]      i0_sample;
    reg [HDR_W-1:0]   i0_hdr;
    wire [P-1:0]      i0_lane_valid = i0_hdr[HDR_LVALID +: P];
    wire              flush_q;                  // running the flush steps (its last copy)
    wire [NSTEP-1:0]  flush_rep;                // its copies, one per step net
    wire              i0_take = !i0_v || (credit[NSTEP-1] && !flush_rep[NSTEP-1]);   // free, or its beat steps now
    assign in_ready = i0_take;
    always @(posedge clk) begin
        if (rst)          i0_v <= 1'b0;
        else if (i0_take) i0_v <= in_valid;
    end
    always @(posedge clk) begin
        if (i0_take) begin
            i0_sample <= in_sample;
            i0_hdr    <= in_hdr;
        end
    end
    // i0's frame-start bit again, one copy per step net (a delay line's clear
    // comes from a flip-flop of its own, not from the one header bit)
    wire [NSTEP-1:0] sop_cp;
    cube4_prim_reg_copies #(.COPIES(NSTEP), .RESET(0)) u_sop (
        .clk(clk), .rst(rst), .en({NSTEP{i0_take}}), .d({NSTEP{in_hdr[HDR_CTRL + CTRL_SOP]}}), .q(sop_cp));

    // per step net: step = credit && (flush || a beat in i0); the frame starts
    // with a real beat whose SOP is set
    wire [NSTEP-1:0] step_rep = credit & (flush_rep | {NSTEP{i0_v}});
    wire [NSTEP-1:0] sop_rep  = ~flush_rep & sop_cp;
    assign step = step_rep[NSTEP-1];
    assign sop  = sop_rep[NSTEP-1];
    wire real_beat = !flush_q;
    wire i0_eop    = i0_hdr[HDR_CTRL + CTRL_EOP];
    wire eop       = real_beat && i0_eop;

    // ------------------------------------------------------------ flush
    // flush_q and its copies (one more than the step nets: flush_q, for the
    // counters). Each copy's next value comes from its own value and its own
    // credit copy (with i0_v, i0's EOP and f_tail_q):
    //   flushing:  !(step && f_tail_q)   (ends after the second step of row NJ + 1)
    //   else:      step && EOP           (a frame's last beat steps)
    // with this copy's step = credit && (flush || i0_v).
    reg              f_tail_q;                  // the previous flush step was in row NJ + 1
    wire [NSTEP:0]   fl_q;                      // {flush_q, flush_rep}
    wire [NSTEP:0]   fl_en = {credit[NSTEP-1], credit};
    wire [NSTEP:0]   fl_st = fl_en & (fl_q | {(NSTEP + 1){i0_v}});
    wire [NSTEP:0]   fl_d  = (fl_q & ~(fl_st & {(NSTEP + 1){f_tail_q}}))
                           | (~fl_q & fl_st & {(NSTEP + 1){i0_eop}});
    cube4_prim_reg_copies #(.COPIES(NSTEP + 1)) u_flush (
        .clk(clk), .rst(rst), .en({(NSTEP + 1){1'b1}}), .d(fl_d), .q(fl_q));
    assign {flush_q, flush_rep} = fl_q;

    // ------------------------------------------------------------ position counters
    // the beat index within a beam / slice; lb_q / ls_q: the position is the
    // last beam / the last beat of a slice (kept with the counters, so that
    // the delay lines' last inputs are a multiplexer on registers)
    reg  [PB_W-1:0]  pb_q;
    reg  [DIM_W-1:0] row_q;
    reg              lb_q, ls_q;
    reg  [DIM_W:0]   f_row_q;                   // flush: beam 0 .. NJ, then two beats (row NJ + 1)
    reg  [PB_W-1:0]  f_pb_q;
    // NB = 1, NJ = 1, NJ + 1: GRA's own registers (cube4_prim_copies keeps
    // them apart from COM's copies of the same compares)
    wire             nb1_q, nj1_q;
    wire [DIM_W:0]   nj_p1_q;
    cube4_prim_copies #(.N(1), .W(DIM_W + 3), .RESET(0)) u_view (
        .clk(clk), .rst(rst), .d({cfg_nb == NB_W'(1), cfg_nj == DIM_W'(1), {1'b0, cfg_nj} + 1'b1}),
        .q({nb1_q, nj1_q, nj_p1_q}));
    wire [PB_W-1:0]  pos_pb     = sop ? {PB_W{1'b0}} : pb_q;
    wire [DIM_W-1:0] pos_row    = sop ? {DIM_W{1'b0}} : row_q;
    wire             last_beam  = sop ? nb1_q : lb_q;
    wire             last_slice = sop ? (nb1_q && nj1_q) : ls_q;
    wire [PB_W-1:0]  pb_n  = last_beam ? {PB_W{1'b0}} : pos_pb + 1'b1;
    wire [DIM_W-1:0] row_n = !last_beam ? pos_row : (last_slice ? {DIM_W{1'b0}} : pos_row + 1'b1);
    wire             lb_n  = (NB_W'(pb_n) == cfg_nb - 1'b1);
    always @(posedge clk) begin
        if (rst) begin
            pb_q     <= {PB_W{1'b0}};
            row_q    <= {DIM_W{1'b0}};
            lb_q     <= 1'b0;
            ls_q     <= 1'b0;
            f_row_q  <= {(DIM_W + 1){1'b0}};
            f_pb_q   <= {PB_W{1'b0}};
            f_tail_q <= 1'b0;
        end else if (step) begin
            pb_q  <= pb_n;
            row_q <= row_n;
            lb_q  <= lb_n;
            ls_q  <= lb_n && (row_n == cfg_nj - 1'b1);
            if (flush_q) begin
                f_tail_q <= (f_row_q == nj_p1_q);
                if (NB_W'(f_pb_q) == cfg_nb - 1'b1) begin
                    f_pb_q  <= {PB_W{1'b0}};
                    f_row_q <= f_row_q + 1'b1;
                end else begin
                    f_pb_q <= f_pb_q + 1'b1;
                end
            end else if (eop) begin
                f_row_q  <= {(DIM_W + 1){1'b0}};
                f_pb_q   <= {PB_W{1'b0}};
                f_tail_q <= 1'b0;
            end
        end
    end

    // ------------------------------------------------------------ delay lines
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_mask
            assign x[q*VW +: VW] = (real_beat && i0_lane_valid[q]) ? i0_sample[q*VW +: VW] : {VW{1'b0}};
        end
    endgenerate
    wire [META_W-1:0] x_meta = {real_beat, i0_hdr};
    wire [META_W-1:0] p1_meta;

    // period of each line: NB (beam) and NJ*NB (plane), constant in a frame
    localparam integer BL_W = ((NBMAX > 1) ? $clog2(NBMAX) : 1) + 1;
    localparam integer PL_W = ((MAX_DIM * NBMAX > 1) ? $clog2(MAX_DIM * NBMAX) : 1) + 1;
    wire [BL_W-1:0] beam_len = BL_W'(cfg_nb);
    reg  [PL_W-1:0] plane_len;
    always @(posedge clk) begin
        plane_len <= PL_W'(PL_W'(cfg_nj) * PL_W'(cfg_nb));
    end
    cube4_delay_line #(.DATA_W(PV), .DEPTH(NBMAX)) u_x_b1 (
        .clk(clk), .rst(rst), .clear(sop_rep[0]), .step(step_rep[0]), .last(last_beam), .len(beam_len),
        .din(x), .dout(b1));
    cube4_delay_line #(.DATA_W(META_W + PV), .DEPTH(MAX_DIM * NBMAX)) u_x_p1 (
        .clk(clk), .rst(rst), .clear(sop_rep[1]), .step(step_rep[1]), .last(last_slice), .len(plane_len),
        .din({x_meta, x}), .dout({p1_meta, p1}));
    // C's flags from P1 (one beam before C), P copies, each a word of its own in the line
    wire [M_W-1:0]   p1_m    = p1_meta[HDR_M +: M_W];
    wire [DIM_W-1:0] p1_j    = p1_meta[HDR_J +: DIM_W];
    wire [M_W-1:0]   ss_mask = M_W'((1 << cfg_ss_log2) - 1);
    wire [NSEL-1:0]  p1_sel;
    assign p1_sel[GSEL_DKF]    = ((p1_m + 1'b1) & ss_mask) == '0;   // voxel slice changes m -> m+1
    assign p1_sel[GSEL_DKB]    = (p1_m & ss_mask) == '0;            // voxel slice changes m-1 -> m
    assign p1_sel[GSEL_JFIRST] = p1_j == '0;
    assign p1_sel[GSEL_MFIRST] = p1_m == '0;
    assign p1_sel[GSEL_YLAST]  = p1_meta[HDR_CTRL + CTRL_YLAST];
    assign p1_sel[GSEL_DYF]    = p1_meta[HDR_CTRL + CTRL_SY];
    assign p1_sel[GSEL_DYB]    = p1_meta[HDR_CTRL + CTRL_OSY];
    cube4_delay_line #(.DATA_W(P * NSEL + META_W + PV), .DEPTH(NBMAX)) u_p1_c (
        .clk(clk), .rst(rst), .clear(sop_rep[2]), .step(step_rep[2]), .last(last_beam), .len(beam_len),
        .din({{P{p1_sel}}, p1_meta, p1}), .dout({c_sel, c_meta, c}));
    cube4_delay_line #(.DATA_W(PV), .DEPTH(NBMAX)) u_c_p1b2 (
        .clk(clk), .rst(rst), .clear(sop_rep[3]), .step(step_rep[3]), .last(last_beam), .len(beam_len),
        .din(c), .dout(p1b2));
    cube4_delay_line #(.DATA_W(PV), .DEPTH(MAX_DIM * NBMAX)) u_c_p2b1 (
        .clk(clk), .rst(rst), .clear(sop_rep[4]), .step(step_rep[4]), .last(last_slice), .len(plane_len),
        .din(c), .dout(p2b1));
    cube4_delay_line #(.DATA_W(PV), .DEPTH(NBMAX)) u_p2b1_p2b2 (
        .clk(clk), .rst(rst), .clear(sop_rep[5]), .step(step_rep[5]), .last(last_beam), .len(beam_len),
        .din(p2b1), .dout(p2b2));

    assign c_edge = 2'b00;                      // i - 1 and i + 1 lie in the frame's beams
    assign fend   = 1'b0;

    wire unused_eoss = in_eoss;   // (the beat schedule's: cube4_gra_beats)

endmodule
`default_nettype wire

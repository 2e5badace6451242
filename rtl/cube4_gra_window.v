`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_gra_window
// -----------------------------------------------------------------------------
// Purpose
//   GRA's window: from the neighbourhood source's beats (cube4_gra_lines or
//   cube4_gra_walk: X, B1, P1, C, P1b2, P2b1, P2b2 around the incoming
//   centre c' = (m, j, pb)) to the operands of docs/numerics.md section 5 for
//   the centre c = (m, j, i), lane by lane:
//     hi  = s[m, j, i+1]               lo   = s[m, j, i-1]
//     gj  = s[m, j+1, i] - s[m, j-1, i]                      (the only difference here)
//     fwd = s[m+1, j+dyf, i+dxf]       back = s[m-1, j-dyb, i-dxb]
//   with zero outside the volume (rows -1 and NJ, slices -1 and M, columns
//   -1 and NI) and, with slice rectangles, beyond the walk's edge beams.
//   First the alignment hops: each beat's lane skew differs from c's by the
//   j step and, where the voxel slice changes, the k step, one ring hop each
//   (cube4_ring_shift); then per lane, with the lane's own copy of c's
//   flags, the zero rows and the ray's rows (j + dyf, j - dyb). gj is taken
//   here, as c' enters the window, so the window carries one difference
//   instead of two rows. The window is three registered beats, h1 = c + 1
//   (c' of the last step), the centre h2 = c and h3 = c - 1, each with its
//   forward and backward rows; i + 1 and i - 1 come from the ring
//   neighbours with beam extension in both directions (the lane at t = P-1
//   takes beat c + 1, the lane at t = 0 beat c - 1), selected by registered
//   one-hot selects per lane (the X-steps folded into the ray's rows'), so
//   every output is a 4-input function of registers.
//
// Parameters
//   P, VOXEL_W, WEIGHT_W, MAX_DIM, MAX_SS_LOG2 as cube4_gra (derived widths:
//   cube4_defs.vh CUBE4_GEOMETRY, CUBE4_GRA_LAYOUT)
//   RECTS   1: the source is cube4_gra_walk (c_edge counts; every centre it
//           brings is of the current frame); 0: cube4_gra_lines (centres
//           count from the frame's first beat on: after a reset the lines
//           still hold words of an interrupted frame).  0..1.  Default 0.
//   BEATS   1: the source is cube4_gra_beats (as RECTS, but c_edge is
//           {gap, gap}: the incoming beat is not the partial beam after the
//           last one in its row, so the beat before it has no neighbour
//           there, nor has it one before it).  0..1.  Default 0.
//
// Latency
//   A centre's operands appear two steps after the step that brought it as
//   c' (the step that brings c' + 2), from registers through one
//   multiplexer level; all registers move on step. take = 1 in that step
//   when the centre is a real beat of the current frame.
//
// Ports (samples unsigned Q0.VOXEL_W, P lanes at [q*VOXEL_W +: VOXEL_W])
//   step, sop, x .. p2b2, c_meta, c_sel, c_edge   from the source (cube4_gra_lines)
//   take      out  the centre below is a real beat and the window steps
//   c_hdr     out  [HDR_W]       the centre's header
//   s         out  [P*VOXEL_W]   the centre's samples s[m, j, i]
//   hi, lo, fwd, back  out [P*VOXEL_W]   the neighbours above, in c's lanes
//   gj        out  [P*(VOXEL_W+1)]  signed, lane q at [q*(VOXEL_W+1) +: VOXEL_W+1]
//
// Bit growth and rounding: gj = up - down of two unsigned VOXEL_W-bit
//   samples, VOXEL_W + 1 bits signed, exact.
// =============================================================================
module cube4_gra_window #(
    `CUBE4_GRA_PARAMS, parameter integer RECTS = 0, parameter integer BEATS = 0
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    input  wire step, input wire sop,
    input  wire [P*VOXEL_W-1:0] x, input wire [P*VOXEL_W-1:0] b1, input wire [P*VOXEL_W-1:0] p1,
    input  wire [P*VOXEL_W-1:0] c, input wire [P*VOXEL_W-1:0] p1b2,
    input  wire [P*VOXEL_W-1:0] p2b1, input wire [P*VOXEL_W-1:0] p2b2,
    input  wire [GRA_META_W-1:0] c_meta,
    input  wire [P*GRA_NSEL-1:0] c_sel,
    input  wire [1:0] c_edge,
    output wire take,
    output wire [HDR_W-1:0] c_hdr,
    output wire [P*VOXEL_W-1:0] s,
    output wire [P*VOXEL_W-1:0] hi, output wire [P*VOXEL_W-1:0] lo,
    output wire [P*VOXEL_W-1:0] fwd, output wire [P*VOXEL_W-1:0] back,
    output wire [P*(VOXEL_W+1)-1:0] gj
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_gra_window", "P", P, 1, 64)
        `CUBE4_RANGE(g_bad_voxel_w, "cube4_gra_window", "VOXEL_W", VOXEL_W, 1, 16)
        `CUBE4_RANGE(g_bad_rects, "cube4_gra_window", "RECTS", RECTS, 0, 1)
        `CUBE4_RANGE(g_bad_beats, "cube4_gra_window", "BEATS", BEATS, 0, 1)
    endgenerate

    localparam integer VW     = VOXEL_W;
    localparam integer PV     = P * VW;
    localparam integer DW     = VW + 1;                     // differences, signed
    localparam integer META_W = GRA_META_W;
    localparam integer NSEL   = GRA_NSEL;
    localparam [LANE_W:0] PL  = P[LANE_W:0];

    `CUBE4_VIEW_FIELDS(cfg);
    `CUBE4_LANE_FUNCTIONS
    genvar q;

    // ------------------------------------------------------------ alignment hops
    // source skew - centre skew: P1 +s_j, P1b2 -s_j, X +s_j (+s_k), B1 (+s_k),
    // P2b1 (-s_k), P2b2 -s_j (-s_k); a +1 difference means y[q] = x[q + 1].
    wire [PV-1:0] p1_a, p1b2_a, x_j, p2b2_j;
    wire [PV-1:0] x_jk, b1_k, p2b1_k, p2b2_jk;
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_al_p1   (.down(!cfg_flip_j), .x(p1),     .y(p1_a));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_al_p1b2 (.down(cfg_flip_j),  .x(p1b2),   .y(p1b2_a));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_al_xj   (.down(!cfg_flip_j), .x(x), .y(x_j));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_al_xk   (.down(!cfg_flip_k), .x(x_j),    .y(x_jk));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_al_b1k  (.down(!cfg_flip_k), .x(b1),     .y(b1_k));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_al_p2k  (.down(cfg_flip_k),  .x(p2b1),   .y(p2b1_k));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_al_p22j (.down(cfg_flip_j),  .x(p2b2),   .y(p2b2_j));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_al_p22k (.down(cfg_flip_k),  .x(p2b2_j), .y(p2b2_jk));
    // then, per lane with the lane's copy of the flags: the slice hops, zero
    // rows and slices outside the volume, pick the ray neighbours
    wire [PV-1:0] row_up, row_dn, fwd_row, back_row;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_rows
            wire [NSEL-1:0] f = c_sel[q*NSEL +: NSEL];
            wire dk_f = f[GSEL_DKF], dk_b = f[GSEL_DKB], j_first = f[GSEL_JFIRST], m_first = f[GSEL_MFIRST];
            wire y_last = f[GSEL_YLAST], c_dyf = f[GSEL_DYF], c_dyb = f[GSEL_DYB];
            localparam integer LO = q * VW;
            wire [VW-1:0] x_a    = dk_f ? x_jk[LO +: VW] : x_j[LO +: VW];
            wire [VW-1:0] b1_a   = dk_f ? b1_k[LO +: VW] : b1[LO +: VW];
            wire [VW-1:0] p2b1_a = dk_b ? p2b1_k[LO +: VW] : p2b1[LO +: VW];
            wire [VW-1:0] p2b2_a = dk_b ? p2b2_jk[LO +: VW] : p2b2_j[LO +: VW];
            assign row_up[LO +: VW]   = y_last  ? {VW{1'b0}} : p1_a[LO +: VW];          // (m, j+1)
            assign row_dn[LO +: VW]   = j_first ? {VW{1'b0}} : p1b2_a[LO +: VW];        // (m, j-1)
            assign fwd_row[LO +: VW]  = c_dyf ? (y_last ? {VW{1'b0}} : x_a) : b1_a;    // (m+1, j+dyf)
            assign back_row[LO +: VW] = m_first ? {VW{1'b0}}
                                     : (c_dyb ? (j_first ? {VW{1'b0}} : p2b2_a) : p2b1_a);   // (m-1, j-dyb)
        end
    endgenerate

    // gj of c' per lane
    wire [P*DW-1:0] gj_in;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_gj
            assign gj_in[q*DW +: DW] = $signed({1'b0, row_up[q*VW +: VW]}) - $signed({1'b0, row_dn[q*VW +: VW]});
        end
    endgenerate

    // ------------------------------------------------------------ window hold
    // h1 = beat c + 1 (the incoming c' of the last step), h2 = beat c (the
    // centre of the output), h3 = beat c - 1. All window inputs are registers:
    // the incoming beat only reaches h1.
    reg               h1_v, h2_v;
    reg               h1_live, h2_live;   // a beat of the current frame (not a stale RAM word)
    reg               live_q;    // the current frame's first beat has reached the centre
    wire              c_sop  = c_meta[HDR_CTRL + CTRL_SOP];
    wire              c_live = (RECTS != 0 || BEATS != 0) || c_sop || live_q;   // (the walks gate stale words)
    wire [1:0]        edge_in = (RECTS != 0 || BEATS != 0) ? c_edge : 2'b00;  // (lines: i +/- 1 lie in the frame's beams)
    wire              unused_edge = ^c_edge;                       // (lines: constant zero)
    reg [META_W-1:0]  h1_meta, h2_meta;
    reg [META_W-1:0]  h1_mx;     // h1_meta with the flags' fields from their second kept copy (below)
    reg [PV-1:0]      h1_c, h2_c, h3_c, h1_f, h2_f, h1_b, h2_b, h3_b;
    reg [P*DW-1:0]    h1_gj, h2_gj;

    always @(posedge clk) begin
        if (rst) begin
            h1_v    <= 1'b0;
            h2_v    <= 1'b0;
            h1_live <= 1'b0;
            h2_live <= 1'b0;
            live_q  <= 1'b0;
        end else if (step) begin
            h1_v    <= 1'b1;
            h2_v    <= h1_v;
            h1_live <= c_live;
            h2_live <= h1_live;
            // after a reset the plane buffers still hold beats of an interrupted
            // frame; centres count only from the current frame's first beat on
            if (sop)        live_q <= 1'b0;
            else if (c_sop) live_q <= 1'b1;
        end
    end
    always @(posedge clk) begin
        if (step) begin
            h1_meta <= c_meta;
            h2_meta <= h1_mx;
            h1_c    <= c;
            h2_c    <= h1_c;
            h3_c    <= h2_c;
            h1_f    <= fwd_row;
            h2_f    <= h1_f;
            h1_b    <= back_row;
            h2_b    <= h1_b;
            h3_b    <= h2_b;
            h1_gj   <= gj_in;
            h2_gj   <= h1_gj;
        end
    end

    wire              h_real = h2_meta[META_W-1] && h2_live;

    // Per lane of h1 (the next centre), where its i - 1 and i + 1 are: inside
    // the volume (hi_ok, lo_ok) and in the next / previous beat (hi_new,
    // lo_old). Registered with h1 into h2 (the window of h2 uses them) as
    // each neighbour's two selects (i+1 from the next beat / from this beat,
    // i-1 from the previous beat / from this beat; both 0: zero), with the
    // walk's edge beams already applied (beyond them the neighbour is zero),
    // so each bit of a neighbour is one 4-input function of its selects and
    // its two candidates. The forward and backward rows have their own
    // registers, with the X-steps folded in (i + dxf: from the next beat,
    // from this beat's neighbour, or the lane itself; i - dxb likewise), so
    // no single X-step flip-flop drives the selects of every lane.
    // With i = pb * P + t: i + 1 < NI holds in every partial beam but the last,
    // L, and in L where t < r = row_last_rem - 1 (CUBE4_LAST_BEAM_FUNCTIONS;
    // 0 <= r < P); i > 0 where pb > 0 or t > 0. So the
    // flags are h1's fields against registered view constants, with no sum of
    // the position on the path.
    // The flags read h1's fields from kept copies of their own, one per lane,
    // loaded with h1_meta: the header's register serves the centre's outputs,
    // and a route from it across GRA to the flags' compares limited the beat
    // build, as did one copy's route to the selects of every lane. A lane's
    // copy holds the partial beam as its two compares (pb == L, pb == 0, taken
    // as it loads) and the skew, which picks the lane's position flags from a
    // table of view constants (t < r, t == P - 1, t == 0 for each skew), so
    // no lane position is computed between the copy and the selects. The
    // header's fields on their way to h2_meta are a copy of their own (a plain
    // register of the same input would be merged into a lane's copy, which
    // then drove both ends again).
    `CUBE4_LAST_BEAM_FUNCTIONS
    reg  [NB_W-1:0]   nbm1_q;             // L
    always @(posedge clk) nbm1_q <= row_last_pb(cfg_nb);
    localparam integer FK_W = PB_W + LANE_W + 2;     // {pb, skew, dxf, dxb}: h2_meta's
    localparam integer FL_W = 2 + LANE_W + 2;        // {pb == L, pb == 0, skew, dxf, dxb}: a lane's
    wire [PB_W-1:0]   pb_d = c_meta[HDR_PB +: PB_W];
    wire [FK_W-1:0]   fk_d = {pb_d, c_meta[HDR_SKEW +: LANE_W], c_meta[HDR_CTRL + CTRL_SX],
                              c_meta[HDR_CTRL + CTRL_OSX]};
    wire [FL_W-1:0]   fl_d = {NB_W'(pb_d) == nbm1_q, pb_d == '0, fk_d[LANE_W+1:0]};
    wire [P*FL_W-1:0] h1_flc;
    wire [FK_W-1:0]   h1_fkm;
    cube4_prim_reg_copies #(.COPIES(P), .W(FL_W), .RESET(0)) u_h1_fk (
        .clk(clk), .rst(rst), .en({P{step}}), .d({P{fl_d}}), .q(h1_flc));
    cube4_prim_reg_copies #(.COPIES(1), .W(FK_W), .RESET(0)) u_h1_fkm (
        .clk(clk), .rst(rst), .en(step), .d(fk_d), .q(h1_fkm));
    always @(*) begin
        h1_mx = h1_meta;
        h1_mx[HDR_PB +: PB_W]       = h1_fkm[FK_W-1 -: PB_W];
        h1_mx[HDR_SKEW +: LANE_W]   = h1_fkm[2 +: LANE_W];
        h1_mx[HDR_CTRL + CTRL_SX]   = h1_fkm[1];
        h1_mx[HDR_CTRL + CTRL_OSX]  = h1_fkm[0];
    end
    wire [LANE_W:0]   ni_rem = row_last_rem(cfg_ni, cfg_nb) - 1'b1;   // r: L's last lane position, 0 .. P - 1
    wire [LANE_W-1:0] ni_r   = ni_rem[LANE_W-1:0];
    wire              unused_ni_rem = ni_rem[LANE_W];
    localparam integer NSK = 1 << LANE_W;            // every skew the field holds
    wire [P-1:0]      hi_ok_d, lo_ok_d, hi_new_d, lo_old_d;
    wire [P-1:0]      h1_dxf, h1_dxb;     // X-step of slice m (h1's), old X-step, each lane's copy
    reg  [1:0]        h1_edge;            // {last, first} partial beam of the walk (c_edge)
    genvar sk;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_pos
            wire [FL_W-1:0]   fl      = h1_flc[q*FL_W +: FL_W];   // the lane's copy of h1's fields
            wire              h1_pb_last = fl[FL_W-1];
            wire              h1_pb_zero = fl[FL_W-2];
            wire [LANE_W-1:0] h1_skew = fl[2 +: LANE_W];
            // the lane's position t = lane_pos(q, skew) as flags, for each skew (view
            // constants, a register behind the view as nbm1_q)
            reg  [NSK-1:0]    tab_lt, tab_last, tab_zero;   // t < r, t == P - 1, t == 0
            for (sk = 0; sk < NSK; sk = sk + 1) begin : g_sk
                wire [LANE_W-1:0] ts = lane_pos(q, LANE_W'(sk), cfg_flip_i, cfg_i_r1);
                always @(posedge clk) begin
                    tab_lt[sk]   <= (ts < ni_r);
                    tab_last[sk] <= ({1'b0, ts} == PL - 1'b1);
                    tab_zero[sk] <= (ts == '0);
                end
            end
            assign h1_dxf[q] = fl[1];
            assign h1_dxb[q] = fl[0];
            assign hi_ok_d[q]  = !h1_pb_last || tab_lt[h1_skew];
            assign lo_ok_d[q]  = !h1_pb_zero || !tab_zero[h1_skew];
            assign hi_new_d[q] = tab_last[h1_skew];          // i + 1 is in the next beat
            assign lo_old_d[q] = tab_zero[h1_skew];          // i - 1 is in the previous beat
        end
    endgenerate
    always @(posedge clk) begin
        if (step) begin
            h1_edge   <= edge_in;
        end
    end
    localparam integer CSEL_W = 4 * P;    // {lo_same, lo_old, hi_same, hi_new} per lane
    localparam integer RSEL_W = 6 * P;    // {b_self, b_same, b_old, f_self, f_same, f_new} per lane
`ifndef SYNTHESIS
    wire [PB_W-1:0]   h1_pb = h1_meta[HDR_PB +: PB_W];
    wire [FK_W-1:0]   h1_fk = {h1_pb, h1_meta[HDR_SKEW +: LANE_W], h1_meta[HDR_CTRL + CTRL_SX],
                               h1_meta[HDR_CTRL + CTRL_OSX]};
    // (the flags' compares and table, taken at a load and a view register behind,
    // are checked where they count: a step with a centre of this frame in h1)
    wire              h1_cur = h1_v && h1_live && h1_meta[META_W-1] && step;
    always @(posedge clk) begin
        if (!rst && h1_v && h1_fkm != h1_fk)
            $fatal(1, "cube4_gra_window: the header's copy of h1's fields %0h differs from h1_meta's", h1_fkm);
        if (!rst && h1_cur && h1_flc != {P{NB_W'(h1_pb) == nbm1_q, h1_pb == '0, h1_fk[LANE_W+1:0]}})
            $fatal(1, "cube4_gra_window: the lanes' partial beam flags %0h are not h1's (pb %0d)", h1_flc, h1_pb);
    end
    for (q = 0; q < P; q = q + 1) begin : g_tab_check
        wire [LANE_W-1:0] t = lane_pos(q, h1_fk[2 +: LANE_W], cfg_flip_i, cfg_i_r1);
        always @(posedge clk) begin
            if (!rst && h1_v && h1_flc[q*FL_W +: LANE_W + 2] != h1_fk[LANE_W+1:0])
                $fatal(1, "cube4_gra_window: lane %0d's copy of h1's fields %0h differs from h1_meta's", q,
                       h1_flc[q*FL_W +: FL_W]);
            if (!rst && h1_cur && {g_pos[q].tab_lt[h1_fk[2 +: LANE_W]], hi_new_d[q], lo_old_d[q]}
                                  != {t < ni_r, {1'b0, t} == PL - 1'b1, t == '0})
                $fatal(1, "cube4_gra_window: lane %0d's position flags at skew %0d are not lane_pos %0d's",
                       q, h1_fk[2 +: LANE_W], t);
        end
    end
`endif
    // h1's last partial beam: its own flag (RECTS), or a gap before the incoming beat (BEATS)
    wire              h1_last = (BEATS != 0) ? edge_in[1] : h1_edge[1];
    wire [P-1:0]      hi_okx = hi_ok_d & ~(hi_new_d & {P{h1_last}});
    wire [P-1:0]      lo_okx = lo_ok_d & ~(lo_old_d & {P{h1_edge[0]}});
    wire [P-1:0]      hi_n = hi_okx & hi_new_d, hi_s = hi_okx & ~hi_new_d;
    wire [P-1:0]      lo_o = lo_okx & lo_old_d, lo_s = lo_okx & ~lo_old_d;
    wire [CSEL_W-1:0] csel_d = {lo_s, lo_o, hi_s, hi_n};
    wire [RSEL_W-1:0] rsel_d = {~h1_dxb, lo_s & h1_dxb, lo_o & h1_dxb,
                                ~h1_dxf, hi_s & h1_dxf, hi_n & h1_dxf};
    wire [CSEL_W-1:0] csel_q;             // the centre's row
    wire [RSEL_W-1:0] rsel_q;             // the forward and backward rows
    // (kept registers: the P equal X-step bits of rsel stay P registers)
    cube4_prim_reg_copies #(.W(CSEL_W), .RESET(0)) u_csel (
        .clk(clk), .rst(rst), .en(step), .d(csel_d), .q(csel_q));
    cube4_prim_reg_copies #(.W(RSEL_W), .RESET(0)) u_rsel (
        .clk(clk), .rst(rst), .en(step), .d(rsel_d), .q(rsel_q));

    // neighbours i+1 (from lane q + s_i; the lane at t = P-1 from beat c + 1) and
    // i-1 (from lane q - s_i; the lane at t = 0 from beat c - 1)
    wire [PV-1:0] c_next_same, c_next_new, c_prev_same, c_prev_old;
    wire [PV-1:0] f_next_same, f_next_new, b_prev_same, b_prev_old;
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_cn_s (.down(!cfg_flip_i), .x(h2_c), .y(c_next_same));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_cn_n (.down(!cfg_flip_i), .x(h1_c), .y(c_next_new));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_cp_s (.down(cfg_flip_i),  .x(h2_c), .y(c_prev_same));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_cp_o (.down(cfg_flip_i),  .x(h3_c), .y(c_prev_old));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_fn_s (.down(!cfg_flip_i), .x(h2_f), .y(f_next_same));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_fn_n (.down(!cfg_flip_i), .x(h1_f), .y(f_next_new));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_bp_s (.down(cfg_flip_i),  .x(h2_b), .y(b_prev_same));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_bp_o (.down(cfg_flip_i),  .x(h3_b), .y(b_prev_old));

    generate
        for (q = 0; q < P; q = q + 1) begin : g_win
            // centre row: [0] i+1 from the next beat, [1] from this one, [2] i-1
            // from the previous beat, [3] from this one; forward row i + dxf:
            // [0] from the next beat, [1] this beat's neighbour, [2] the lane;
            // backward row i - dxb: [3] from the previous beat, [4] this
            // beat's neighbour, [5] the lane (all 0: zero)
            wire [3:0] sc = {csel_q[3*P + q], csel_q[2*P + q], csel_q[P + q], csel_q[q]};
            wire [5:0] sr = {rsel_q[5*P + q], rsel_q[4*P + q], rsel_q[3*P + q],
                             rsel_q[2*P + q], rsel_q[P + q], rsel_q[q]};
            localparam integer LO = q * VW;
            assign hi[LO +: VW]   = ({VW{sc[0]}} & c_next_new[LO +: VW]) | ({VW{sc[1]}} & c_next_same[LO +: VW]);
            assign lo[LO +: VW]   = ({VW{sc[2]}} & c_prev_old[LO +: VW]) | ({VW{sc[3]}} & c_prev_same[LO +: VW]);
            assign fwd[LO +: VW]  = ({VW{sr[0]}} & f_next_new[LO +: VW]) | ({VW{sr[1]}} & f_next_same[LO +: VW])
                                  | ({VW{sr[2]}} & h2_f[LO +: VW]);                   // i + dxf
            assign back[LO +: VW] = ({VW{sr[3]}} & b_prev_old[LO +: VW]) | ({VW{sr[4]}} & b_prev_same[LO +: VW])
                                  | ({VW{sr[5]}} & h2_b[LO +: VW]);                   // i - dxb
        end
    endgenerate

    assign take  = step && h2_v && h_real;
    assign c_hdr = h2_meta[META_W-2:0];
    assign s     = h2_c;
    assign gj    = h2_gj;

endmodule
`default_nettype wire

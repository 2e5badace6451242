`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_tri
// -----------------------------------------------------------------------------
// Purpose
//   The TRI units of all P pipelines (Teramac paper, section 5, eq. 4): turns
//   the voxel beats read by cube4_cfb into tri-linear samples, one sample per
//   lane per beat, with seven lerps per lane (four in x, two in y, one in z;
//   docs/numerics.md section 4), all of them the shared cube4_lerp.
//
//   Buffers (each voxel is read from memory once per frame):
//   * slice buffers (only when MAX_SS_LOG2 > 0): two slices of raw voxels per
//     lane, by slice parity, replayed for the S sample slices between two
//     voxel slices;
//   * beam buffers: the previous row (beam) of the lower and upper slice per
//     lane, NB entries, so the 2 x 2 neighbourhood in (i, j) is complete when
//     row j + 1 arrives.
//   Ring traffic (cube4_ring_shift / cube4_beam_ext, one hop, fixed width):
//   * the upper slice is one lane off (its skew differs by the k step);
//   * the beam buffer is written one lane over (the skew changes by the j step
//     from one beam to the next), so its output is aligned with the new row;
//   * beam extension: position i + 1 from the neighbour lane, for the last
//     lane of a partial beam from the next beat (Fig. 6).
//
// Parameters
//   P            pipelines.                           1..64.   Default 8.
//   VOXEL_W      voxel / sample width.                1..16.   Default 8.
//   WEIGHT_W     weight width W.                      4..12.   Default 8.
//   MAX_DIM      largest volume dimension.            2..2048. Default 256.
//   MAX_SS_LOG2  log2 of the largest supersampling.   0..3.    Default 0.
//   CLIP         1: the window and the cut plane (cube4_clip) set the
//                header's KEEP; 0: KEEP = LVALID.     0..1.    Default 1.
//   VGRAD        1: a memory word is the voxel and its gradient's three
//                components (CUBE4_WORD_LAYOUT); every buffer holds whole
//                words and each of the four channels has its seven lerps
//                (numerics.md section 5b). 0: the voxel alone. 0..1. Default 0.
//   Derived widths and the layouts of cfg, in_tag and out_hdr: cube4_defs.vh.
//
// Latency
//   Fixed 14-stage pipeline (s0 .. s13) that moves on every cycle and carries a valid bit
//   per stage (no stall enable): s0 input, s1 slice-buffer select, s2 beam
//   buffer, s3 beam-extension hold (a beat waits there for the next beat, so
//   the drain beat pushes out the last one), s4, then x-lerps, y-lerps and
//   the z-lerp, LERP_LAT = 3 stages each (b - a, the multiply (b - a) * w,
//   then the rounding add). The results are written into the output FIFO
//   (cube4_credit_fifo, 32 entries), which is on out_* one cycle after the
//   z-lerp's register. A beat enters s0 only when the FIFO has an entry
//   reserved for it (in_ready = the FIFO's credit), so out_ready reaches
//   in_ready and the FIFO's pointers only; a beat that s3 does not emit
//   returns its entry.
//
// Ports
//   cfg     view registers (cube4_defs.vh); TRI reads the three flips, and
//           its cube4_clip WIN_*, CUT_*, SS_LOG2 and I_R1.
//   in_*    beats from memory: in_data lane q = bank q's word (WORD_W bits: the
//           voxel Q0.VOXEL_W as an unsigned integer, with VGRAD the gradient's
//           components, signed VG_W bits each; 0 for lanes not read);
//           in_tag = cube4_cfb's tag.
//   out_*   sample beats: out_sample lane q (WORD_W bits: the sample, unsigned
//           VOXEL_W, Q0.VOXEL_W; with VGRAD the interpolated components, signed);
//           out_hdr the stream header (CUBE4_GEOMETRY): lane valid (position
//           < NI; with slice rectangles the traversed positions), lane inside
//           (the sample is inside the volume box, numerics.md section 4, and not
//           below its slice rectangle's low sides, tag LINL, section 18), lane keep (valid and counts: window and cut plane,
//           section 12), m, j, pb, skew (lane q holds i = pb*P + t, lane_pos)
//           and the control bits.
//
// Bit growth and rounding
//   Each lerp rounds half up once (cube4_lerp); samples stay VOXEL_W bits, the
//   gradient components VG_W bits (a lerp's result lies between its inputs).
//   A component enters its lerps with the sign bit flipped (offset binary) and
//   leaves with it flipped back: the unsigned lerp of a + B and b + B is the
//   signed lerp of a and b plus B, bit for bit.
//   Order of the seven lerps as in the golden model: x in rows j and j + 1 of
//   both slices, then y, then z.
// =============================================================================
module cube4_tri #(
    parameter integer P       = 8, parameter integer MAX_DIM     = 256,
    parameter integer VOXEL_W = 8, parameter integer MAX_SS_LOG2 = 0,
    parameter integer WEIGHT_W = 8, parameter integer CLIP = 1,
    parameter integer VGRAD   = 0,
    `CUBE4_GEOMETRY, `CUBE4_VIEW_LAYOUT, `CUBE4_TAG_LAYOUT, `CUBE4_WORD_LAYOUT
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    // input beats: the memory's response (lane q = bank q) with the CFB tag
    input  wire in_valid,  output wire in_ready,  input  wire [TAG_W-1:0] in_tag,
    input  wire [P*WORD_W-1:0] in_data,
    // output: sample beats
    output wire out_valid, input  wire out_ready, output wire [HDR_W-1:0] out_hdr,
    output wire [P*WORD_W-1:0] out_sample
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_tri", "P", P, 1, 64)
        `CUBE4_RANGE(g_bad_voxel_w, "cube4_tri", "VOXEL_W", VOXEL_W, 1, 16)
        `CUBE4_RANGE(g_bad_ss, "cube4_tri", "MAX_SS_LOG2", MAX_SS_LOG2, 0, 3)
        `CUBE4_RANGE(g_bad_clip, "cube4_tri", "CLIP", CLIP, 0, 1)
        `CUBE4_RANGE(g_bad_vgrad, "cube4_tri", "VGRAD", VGRAD, 0, 1)
    endgenerate

    `CUBE4_VIEW_FIELDS(cfg);
    // the tag's fields (CUBE4_TAG_LAYOUT)
    wire                in_t_emit      = in_tag[TAG_EMIT];
    wire                in_t_sop       = in_tag[TAG_SOP];
    wire                in_t_eop       = in_tag[TAG_EOP];
    wire                in_t_ywrap     = in_tag[TAG_YWRAP];
    wire                in_t_bb_we     = in_tag[TAG_BBWE];
    wire                in_t_lower_mem = in_tag[TAG_LMEM];
    wire                in_t_upper_mem = in_tag[TAG_UMEM];
    wire                in_t_upper_use = in_tag[TAG_UUSE];
    wire                in_t_k0_odd    = in_tag[TAG_K0ODD];
    wire [SB_W-1:0]     in_t_sb_addr   = in_tag[TAG_SB +: SB_W];
    wire [PB_W-1:0]     in_t_pb        = in_tag[TAG_PB +: PB_W];
    wire [WEIGHT_W-1:0] in_t_wx        = in_tag[TAG_WX +: WEIGHT_W];
    wire [WEIGHT_W-1:0] in_t_wy        = in_tag[TAG_WY +: WEIGHT_W];
    wire [WEIGHT_W-1:0] in_t_wz        = in_tag[TAG_WZ +: WEIGHT_W];
    wire [M_W-1:0]      in_t_m         = in_tag[TAG_M +: M_W];
    wire [DIM_W-1:0]    in_t_j         = in_tag[TAG_J +: DIM_W];
    wire [LANE_W-1:0]   in_t_skew      = in_tag[TAG_SKEW +: LANE_W];
    wire                in_t_y_last    = in_tag[TAG_YLAST];
    wire [3:0]          in_t_steps     = in_tag[TAG_STEPS +: 4];
    wire [P-1:0]        in_t_lane_valid = in_tag[TAG_LVAL +: P];
    wire [P-1:0]        in_t_lane_nbr  = in_tag[TAG_LNBR +: P];
    wire [P-1:0]        in_t_lane_wrap = in_tag[TAG_LWRAP +: P];
    wire [P-1:0]        in_t_lane_inl  = in_tag[TAG_LINL +: P];

    localparam integer VW    = WORD_W;      // a memory word: every buffer holds whole words
    localparam integer PV    = P * VW;
    localparam integer BBMAX = 1 << PB_W;   // beam-buffer entries (>= NBMAX)
    // the stream header, formed at s0, rides along unchanged to the output
    localparam integer META_W = HDR_W;

    // Credit-based flow control (see Latency): the output FIFO's credit.
    localparam integer FIFO_DEPTH = 32;     // >= 18 cycles from s0 to the FIFO's read
    wire credit;
    assign in_ready = credit;
    wire take = in_valid && credit;         // a beat enters s0

    // ------------------------------------------------------------- s0: input
    reg               s0_v;
    reg [PV-1:0]      s0_data;
    reg               s0_emit, s0_ywrap, s0_bbwe, s0_lmem, s0_umem, s0_uuse, s0_k0odd;
    reg [SB_W-1:0]    s0_sb;
    reg [PB_W-1:0]    s0_pb;
    reg [WEIGHT_W-1:0] s0_wx, s0_wy, s0_wz;
    reg [P-1:0]       s0_nbr, s0_wrap;
    reg [META_W-1:0]  s0_meta;

    // inside = valid, not below the rectangle's low sides (LINL; all ones without
    // slice rectangles), and not in the last column when wx > 0, nor the last row when wy > 0
    wire [P-1:0] in_inside = in_t_lane_valid & in_t_lane_inl
                           & ~(in_t_lane_valid & ~in_t_lane_nbr & {P{in_t_wx != '0}})
                           & ~{P{in_t_y_last && in_t_wy != '0}};

    always @(posedge clk) begin
        if (rst) s0_v <= 1'b0;
        else     s0_v <= take;
    end
    always @(posedge clk) begin
        s0_data  <= in_data;
        s0_emit  <= in_t_emit;
        s0_ywrap <= in_t_ywrap;
        s0_bbwe  <= in_t_bb_we;
        s0_lmem  <= in_t_lower_mem;
        s0_umem  <= in_t_upper_mem;
        s0_uuse  <= in_t_upper_use;
        s0_k0odd <= in_t_k0_odd;
        s0_sb    <= in_t_sb_addr;
        s0_pb    <= in_t_pb;
        s0_wx    <= in_t_wx;
        s0_wy    <= in_t_wy;
        s0_wz    <= in_t_wz;
        s0_nbr   <= in_t_lane_nbr;
        s0_wrap  <= in_t_lane_wrap;
        // CUBE4_GEOMETRY's header, MSB first (KEEP = LVALID until cube4_clip's
        // result replaces it after s4)
        s0_meta  <= {in_t_m, in_t_j, in_t_pb, in_t_skew,
                     in_t_y_last, in_t_eop, in_t_sop, in_t_steps,
                     in_t_lane_valid, in_t_lane_valid, in_inside};
    end

    // ------------------------------------- s1: slice buffers and source select
    reg               s1_v;
    reg [PV-1:0]      s1_data;
    reg               s1_emit, s1_ywrap, s1_bbwe, s1_lmem, s1_umem, s1_uuse, s1_k0odd;
    reg [PB_W-1:0]    s1_pb;
    reg [WEIGHT_W-1:0] s1_wx, s1_wy, s1_wz;
    reg [P-1:0]       s1_nbr, s1_wrap;
    reg [META_W-1:0]  s1_meta;
    wire [PV-1:0]     s1_sb_lower, s1_sb_upper;  // slice-buffer words for the s1 beat

    always @(posedge clk) begin
        if (rst) s1_v <= 1'b0;
        else     s1_v <= s0_v;
    end
    always @(posedge clk) begin
        s1_data  <= s0_data;
        s1_emit  <= s0_emit;
        s1_ywrap <= s0_ywrap;
        s1_bbwe  <= s0_bbwe;
        s1_lmem  <= s0_lmem;
        s1_umem  <= s0_umem;
        s1_uuse  <= s0_uuse;
        s1_k0odd <= s0_k0odd;
        s1_pb    <= s0_pb;
        s1_wx    <= s0_wx;
        s1_wy    <= s0_wy;
        s1_wz    <= s0_wz;
        s1_nbr   <= s0_nbr;
        s1_wrap  <= s0_wrap;
        s1_meta  <= s0_meta;
    end

    genvar q, c;
    generate
        if (MAX_SS_LOG2 > 0) begin : g_slice_buf
            // Two slices per lane, by parity. Written at s0 by the beat that
            // reads the slice from memory; read at s0 (data at s1) by later passes.
            for (q = 0; q < P; q = q + 1) begin : g_lane
                reg [VW-1:0] sbuf0 [0:(1 << SB_W)-1];
                reg [VW-1:0] sbuf1 [0:(1 << SB_W)-1];
                reg [VW-1:0] rd0_q, rd1_q;
                wire [VW-1:0] d = s0_data[q*VW +: VW];
                wire wr_lo = s0_v && s0_lmem;   // lower slice, parity k0
                wire wr_up = s0_v && s0_umem;   // upper slice, parity k0 + 1
                always @(posedge clk) begin
                    if ((wr_lo && !s0_k0odd) || (wr_up && s0_k0odd)) sbuf0[s0_sb] <= d;
                    if ((wr_lo && s0_k0odd) || (wr_up && !s0_k0odd)) sbuf1[s0_sb] <= d;
                end
                always @(posedge clk) begin
                    rd0_q <= sbuf0[s0_sb];
                    rd1_q <= sbuf1[s0_sb];
                end
                assign s1_sb_lower[q*VW +: VW] = s1_k0odd ? rd1_q : rd0_q;
                assign s1_sb_upper[q*VW +: VW] = s1_k0odd ? rd0_q : rd1_q;
            end
        end else begin : g_no_slice_buf
            // S = 1 only: every pass reads its own slice, the upper slice is unused.
            assign s1_sb_lower = '0;
            assign s1_sb_upper = '0;
            wire unused_sb = ^{s0_sb, s1_k0odd};
        end
    endgenerate

    wire [PV-1:0] s1_lower   = s1_lmem ? s1_data : s1_sb_lower;
    wire [PV-1:0] s1_upper_r = s1_umem ? s1_data : s1_sb_upper;
    wire [PV-1:0] s1_upper_a;   // realigned to the lower slice's lanes
    cube4_ring_shift #(
        .P      (P),
        .DATA_W (VW)
    ) u_upper_align (
        .down (!cfg_flip_k),
        .x    (s1_upper_r),
        .y    (s1_upper_a)
    );
    wire [PV-1:0] s1_upper = s1_uuse ? s1_upper_a : '0;

    // ------------------------------------------------------ s2: beam buffers
    // Lane q's beam buffer holds, per partial beam, the previous row's voxels
    // of the position lane q holds now: it is written from lane q - s_j.
    wire [2*PV-1:0] s1_pair;     // {upper, lower} per lane
    wire [2*PV-1:0] s1_pair_sh;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_pair
            assign s1_pair[q*2*VW +: 2*VW] = {s1_upper[q*VW +: VW], s1_lower[q*VW +: VW]};
        end
    endgenerate
    cube4_ring_shift #(
        .P      (P),
        .DATA_W (2 * VW)
    ) u_bb_shift (
        .down (cfg_flip_j),
        .x    (s1_pair),
        .y    (s1_pair_sh)
    );

    reg               s2_v;
    reg [2*PV-1:0]    s2_cur;    // current row (zero on Y-wrap)
    reg               s2_emit;
    reg [WEIGHT_W-1:0] s2_wx, s2_wy, s2_wz;
    reg [P-1:0]       s2_nbr, s2_wrap;
    reg [META_W-1:0]  s2_meta;
    wire [2*PV-1:0]   s2_prev;   // previous row, from the beam buffers

    generate
        for (q = 0; q < P; q = q + 1) begin : g_beam_buf
            reg [2*VW-1:0] bbuf [0:BBMAX-1];
            reg [2*VW-1:0] rd_q;
            always @(posedge clk) begin
                rd_q <= bbuf[s1_pb];   // read first: the row before this one
                if (s1_v && s1_bbwe) bbuf[s1_pb] <= s1_pair_sh[q*2*VW +: 2*VW];
            end
            assign s2_prev[q*2*VW +: 2*VW] = rd_q;
        end
    endgenerate

    always @(posedge clk) begin
        if (rst) s2_v <= 1'b0;
        else     s2_v <= s1_v;
    end
    integer ks;
    always @(posedge clk) begin
        // (lane by lane: one zero constant of 2*PV bits would be thousands of bits wide)
        for (ks = 0; ks < P; ks = ks + 1)
            s2_cur[ks*2*VW +: 2*VW] <= s1_ywrap ? '0 : s1_pair[ks*2*VW +: 2*VW];
        s2_emit <= s1_emit;
        s2_wx   <= s1_wx;
        s2_wy   <= s1_wy;
        s2_wz   <= s1_wz;
        s2_nbr  <= s1_nbr;
        s2_wrap <= s1_wrap;
        s2_meta <= s1_meta;
    end

    // ---------------------------------------- s3: hold for beam extension
    // Per lane, 4 values: {prev upper, prev lower, cur upper, cur lower}.
    wire [4*PV-1:0] s2_vals;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_vals
            assign s2_vals[q*4*VW +: 4*VW] = {s2_prev[q*2*VW +: 2*VW], s2_cur[q*2*VW +: 2*VW]};
        end
    endgenerate

    reg               s3_v;
    reg [4*PV-1:0]    s3_vals;
    reg               s3_emit;
    reg [WEIGHT_W-1:0] s3_wx, s3_wy, s3_wz;
    reg [P-1:0]       s3_nbr, s3_wrap;
    reg [META_W-1:0]  s3_meta;
    wire              s3_take = s2_v;   // a new beat completes the held one

    always @(posedge clk) begin
        if (rst) s3_v <= 1'b0;
        else if (s3_take) s3_v <= 1'b1;
    end
    always @(posedge clk) begin
        if (s3_take) begin
            s3_vals <= s2_vals;
            s3_emit <= s2_emit;
            s3_wx   <= s2_wx;
            s3_wy   <= s2_wy;
            s3_wz   <= s2_wz;
            s3_nbr  <= s2_nbr;
            s3_wrap <= s2_wrap;
            s3_meta <= s2_meta;
        end
    end

    wire [4*PV-1:0] s3_nvals;   // the four values at position i + 1
    cube4_beam_ext #(
        .P      (P),
        .DATA_W (4 * VW)
    ) u_beam_ext (
        .down   (cfg_flip_i),
        .prev   (s3_vals),
        .cur    (s2_vals),
        .wrap   (s3_wrap),
        .nbr_ok (s3_nbr),
        .nbr    (s3_nvals)
    );

    // ------------------------------------------------ s4: the 2x2x2 cell
    reg               s4_v;
    reg [4*PV-1:0]    s4_vals, s4_nvals;
    reg [WEIGHT_W-1:0] s4_wy, s4_wz;   // (wx: each lane's copy, g_lerp)
    reg [WEIGHT_W-1:0] s4_wx_clip;     // wx for cube4_clip
    reg [META_W-1:0]  s4_meta;

    always @(posedge clk) begin
        if (rst) s4_v <= 1'b0;
        else     s4_v <= s3_take && s3_v && s3_emit;
    end
    always @(posedge clk) begin
        s4_vals  <= s3_vals;
        s4_nvals <= s3_nvals;
        s4_wy    <= s3_wy;
        s4_wx_clip <= s3_wx;
        s4_wz    <= s3_wz;
        s4_meta  <= s3_meta;
    end

    // ------------------------- after s4: seven lerps per lane, LERP_LAT each
    // Stage n after s4 holds lv_q[n] / lmeta_q[n]; the y-lerps take the weight
    // LERP_LAT stages after s4, the z-lerp 2 * LERP_LAT stages after.
    localparam integer LERP_LAT = 3;
    localparam integer NL       = 3 * LERP_LAT;
    reg [NL-1:1]                     lv_q;     // (stage NL: the FIFO's push copies)
    reg [META_W-1:0]   lmeta_q [1:NL];
    // which samples count (window, cut plane): CLIP_LAT cycles from s4's fields
    localparam integer CLIP_LAT = 5;
    wire [P-1:0] clip_keep;
    generate
        if (CLIP != 0) begin : g_clip
            cube4_clip #(
                .P           (P),
                .MAX_DIM     (MAX_DIM),
                .WEIGHT_W    (WEIGHT_W),
                .MAX_SS_LOG2 (MAX_SS_LOG2)
            ) u_clip (
                .clk     (clk),
                .cfg     (cfg),
                .in_m    (s4_meta[HDR_M +: M_W]),
                .in_j    (s4_meta[HDR_J +: DIM_W]),
                .in_pb   (s4_meta[HDR_PB +: PB_W]),
                .in_skew (s4_meta[HDR_SKEW +: LANE_W]),
                .in_wx   (s4_wx_clip),
                .in_wy   (s4_wy),
                .keep    (clip_keep)
            );
        end else begin : g_no_clip
            assign clip_keep = {P{1'b1}};
            wire unused_wx_clip = ^s4_wx_clip;
        end
    endgenerate
    reg [WEIGHT_W-1:0] lwy_q [1:LERP_LAT-1];     // (the last stage: each lane's wy_l)
    reg [WEIGHT_W-1:0] lwz_q [1:2*LERP_LAT-1];   // (the last stage: each lane's wz_l)
    wire [PV-1:0]      l_sample;

    always @(posedge clk) begin
        if (rst) lv_q <= '0;
        else     lv_q <= {lv_q[NL-2:1], s4_v};
    end
    integer kl;
    always @(posedge clk) begin
        lmeta_q[1] <= s4_meta;
        for (kl = 2; kl <= NL; kl = kl + 1) lmeta_q[kl] <= lmeta_q[kl - 1];
        // cube4_clip's KEEP (CLIP_LAT cycles after s4) replaces the placeholder
        lmeta_q[CLIP_LAT + 1][HDR_KEEP +: P] <= lmeta_q[CLIP_LAT][HDR_LVALID +: P] & clip_keep;
        lwy_q[1] <= s4_wy;
        for (kl = 2; kl <= LERP_LAT - 1; kl = kl + 1) lwy_q[kl] <= lwy_q[kl - 1];
        lwz_q[1] <= s4_wz;
        for (kl = 2; kl <= 2 * LERP_LAT - 1; kl = kl + 1) lwz_q[kl] <= lwz_q[kl - 1];
    end

    generate
        for (q = 0; q < P; q = q + 1) begin : g_lerp
            // the lane's own copies of the weights, wx at s4, wy / wz when the
            // y / z lerps start: one shared register would drive the
            // multipliers of every lane (and every channel of the lane)
            reg [WEIGHT_W-1:0] wx_l, wy_l, wz_l;
            (* keep *)
            always @(posedge clk) begin
                wx_l <= s3_wx;
                wy_l <= lwy_q[LERP_LAT - 1];
                wz_l <= lwz_q[2 * LERP_LAT - 1];
            end
            for (c = 0; c < NCH; c = c + 1) begin : g_ch
                // channel c of the word: the voxel, then the gradient components
                localparam integer CW  = (c == 0) ? VOXEL_W : VG_W;
                localparam integer OFF = (c == 0) ? 0 : VOXEL_W + (c - 1) * VG_W;
                // values of this lane: index 0 cur lower (row j+1), 1 cur upper,
                // 2 prev lower (row j), 3 prev upper; n* = the same at i + 1
                // (a gradient component is two's complement in the word: its sign
                // bit flipped makes it offset binary for the unsigned lerps, and
                // flipped back after the z-lerp; the voxel is unsigned as it is)
                localparam [CW-1:0] FLIP = (c == 0) ? '0 : (CW'(1) << (CW - 1));
                wire [CW-1:0] cl  = FLIP ^ s4_vals[q*4*VW + 0*VW + OFF +: CW];
                wire [CW-1:0] cu  = FLIP ^ s4_vals[q*4*VW + 1*VW + OFF +: CW];
                wire [CW-1:0] pl  = FLIP ^ s4_vals[q*4*VW + 2*VW + OFF +: CW];
                wire [CW-1:0] pu  = FLIP ^ s4_vals[q*4*VW + 3*VW + OFF +: CW];
                wire [CW-1:0] ncl = FLIP ^ s4_nvals[q*4*VW + 0*VW + OFF +: CW];
                wire [CW-1:0] ncu = FLIP ^ s4_nvals[q*4*VW + 1*VW + OFF +: CW];
                wire [CW-1:0] npl = FLIP ^ s4_nvals[q*4*VW + 2*VW + OFF +: CW];
                wire [CW-1:0] npu = FLIP ^ s4_nvals[q*4*VW + 3*VW + OFF +: CW];
                wire [CW-1:0] x_l0, x_l1, x_u0, x_u1, y_l, y_u, z;

                // x: rows j (prev) and j + 1 (cur) of the lower and upper slice
                cube4_lerp #(.DATA_W(CW), .WEIGHT_W(WEIGHT_W), .LATENCY(LERP_LAT)) u_x_l0 (
                    .clk(clk), .en(1'b1), .a(pl), .b(npl), .w(wx_l), .y(x_l0));
                cube4_lerp #(.DATA_W(CW), .WEIGHT_W(WEIGHT_W), .LATENCY(LERP_LAT)) u_x_l1 (
                    .clk(clk), .en(1'b1), .a(cl), .b(ncl), .w(wx_l), .y(x_l1));
                cube4_lerp #(.DATA_W(CW), .WEIGHT_W(WEIGHT_W), .LATENCY(LERP_LAT)) u_x_u0 (
                    .clk(clk), .en(1'b1), .a(pu), .b(npu), .w(wx_l), .y(x_u0));
                cube4_lerp #(.DATA_W(CW), .WEIGHT_W(WEIGHT_W), .LATENCY(LERP_LAT)) u_x_u1 (
                    .clk(clk), .en(1'b1), .a(cu), .b(ncu), .w(wx_l), .y(x_u1));
                // y
                cube4_lerp #(.DATA_W(CW), .WEIGHT_W(WEIGHT_W), .LATENCY(LERP_LAT)) u_y_l (
                    .clk(clk), .en(1'b1), .a(x_l0), .b(x_l1), .w(wy_l), .y(y_l));
                cube4_lerp #(.DATA_W(CW), .WEIGHT_W(WEIGHT_W), .LATENCY(LERP_LAT)) u_y_u (
                    .clk(clk), .en(1'b1), .a(x_u0), .b(x_u1), .w(wy_l), .y(y_u));
                // z
                cube4_lerp #(.DATA_W(CW), .WEIGHT_W(WEIGHT_W), .LATENCY(LERP_LAT)) u_z (
                    .clk(clk), .en(1'b1), .a(y_l), .b(y_u), .w(wz_l), .y(z));
                assign l_sample[q*VW + OFF +: CW] = FLIP ^ z;
            end
        end
    endgenerate

    // ------------------------------------------------------ output FIFO
    // lv_q[NL-1] says the z-lerp's result is an item at the next cycle; an s3
    // beat that leaves without being emitted gives its entry back.
    localparam integer OUT_W = PV + META_W;
    reg give_q;
    always @(posedge clk) begin
        if (rst) give_q <= 1'b0;
        else     give_q <= s3_take && s3_v && !s3_emit;
    end
    wire [OUT_W-1:0] fifo_out;
    wire unused_credit_d;
    cube4_credit_fifo #(.DATA_W(OUT_W), .DEPTH(FIFO_DEPTH)) u_fifo (
        .clk(clk), .rst(rst), .take(take), .give(give_q),
        .credit(credit), .credit_d(unused_credit_d),
        .push_d(lv_q[NL-1]), .in_data({lmeta_q[NL], l_sample}),
        .out_valid(out_valid), .out_ready(out_ready), .out_data(fifo_out));

    assign out_sample = fifo_out[PV-1:0];
    assign out_hdr    = fifo_out[OUT_W-1:PV];

endmodule
`default_nettype wire

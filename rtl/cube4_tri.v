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
//   A thin top of units (docs/architecture.md "TRI"):
//     u_src    cube4_tri_src: s0, s1: the tag's fields, the slice buffers, each
//              lane's lower and upper slice word, the upper one realigned
//     u_beam   cube4_tri_beam: s2 .. s4: the beam buffers, the hold for beam
//              extension (cube4_beam_ext), the 2 x 2 x 2 cell
//     u_clip   cube4_clip (CLIP = 1): window and cut plane, the header's KEEP
//     u_meta   cube4_tri_meta: the header, valid bit and y / z weights beside
//              the lerps; KEEP inserted
//     g_lane   cube4_tri_lane per lane: the seven lerps per channel
//     u_fifo   cube4_credit_fifo: the sample beats
//
// Parameters
//   P            pipelines.                           1..64.   Default 8.
//   VOXEL_W      voxel / sample width.                1..16.   Default 8.
//   WEIGHT_W     weight width W.                      4..12.   Default 8.
//   MAX_DIM      largest volume dimension.            2..2048. Default 256.
//   MAX_SS_LOG2  log2 of the largest supersampling.   0..3.    Default 0.
//   CLIP         1: the window and the cut plane (cube4_clip) set the
//                header's KEEP; 0: KEEP = LVALID.     0..1.    Default 1.
//   SLAB         1: cube4_clip's slab far face too.  0..CLIP. Default 0.
//   VGRAD        1: a memory word is the voxel and its gradient's three
//                components (CUBE4_WORD_LAYOUT); every buffer holds whole
//                words and each of the four channels has its seven lerps
//                (numerics.md section 5b). 0: the voxel alone. 0..1. Default 0.
//   LABELS       1: the word carries the voxel's label above it; each lane
//                picks the nearest corner's (cube4_tri_lane, numerics.md
//                section 24). Needs VGRAD = 0. 0..1. Default 0.
//   Derived widths and the layouts of cfg, in_tag and out_hdr: cube4_defs.vh.
//
// Latency
//   Fixed 17-stage pipeline (s0 .. s16) that moves on every cycle and carries a valid bit
//   per stage (no stall enable): s0 input, s1 slice-buffer select, s2 beam
//   buffer, s3 beam-extension hold (a beat waits there for the next beat, so
//   the drain beat pushes out the last one), s4, then x-lerps, y-lerps and
//   the z-lerp, TRI_LERP_LAT = 4 stages each (b - a, the multiply (b - a) * w,
//   the product again in the fabric, then the rounding add; the x-lerps' b - a is formed in the lanes from
//   s3's cell and registered with s4: cube4_tri_lane). The results are written into the output FIFO
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
//           VOXEL_W, Q0.VOXEL_W; with VGRAD the interpolated components, signed;
//           with LABELS the nearest corner's label above it);
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
    parameter integer CLIP = 1, parameter integer SLAB = 0,
    `CUBE4_TRI_PARAMS, `CUBE4_VIEW_LAYOUT
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
    // (P, MAX_SS_LOG2: checked by the units; VOXEL_W, VGRAD: by cube4_tri_lane)
    generate
        `CUBE4_RANGE(g_bad_clip, "cube4_tri", "CLIP", CLIP, 0, 1)
        `CUBE4_RANGE(g_bad_slab, "cube4_tri", "SLAB", SLAB, 0, CLIP)
    endgenerate

    localparam integer VW = WORD_W;
    localparam integer PV = P * VW;
    localparam integer FIFO_DEPTH = 32;     // >= 21 cycles from s0 to the FIFO's read

    // Credit-based flow control (see Latency): the output FIFO's credit.
    wire credit;
    assign in_ready = credit;
    wire take = in_valid && credit;         // a beat enters s0

    // ==== s0, s1: the beat, the slice buffers, the lower and upper slice ====
    wire               s1_v, s1_ywrap, s1_bbwe;
    wire [2*PV-1:0]    s1_pair;
    wire [PB_W-1:0]    s1_pb;
    wire [TRI_C_W-1:0] s1_ctl;
    cube4_tri_src #(
        .P(P), .MAX_DIM(MAX_DIM), .VOXEL_W(VOXEL_W), .MAX_SS_LOG2(MAX_SS_LOG2), .WEIGHT_W(WEIGHT_W), .VGRAD(VGRAD),
        .LABELS(LABELS)
    ) u_src (
        .clk(clk), .rst(rst), .take(take), .in_tag(in_tag), .in_data(in_data), .flip_k(cfg[VIEW_FLIP_K]),
        .s1_v(s1_v), .s1_pair(s1_pair), .s1_ywrap(s1_ywrap), .s1_bbwe(s1_bbwe), .s1_pb(s1_pb), .s1_ctl(s1_ctl));

    // ==== s2 .. s4: the beam buffers, beam extension, the cell ====
    wire                give, s4_v;
    wire [WEIGHT_W-1:0] s3_wx, s4_wx, s4_wy, s4_wz;
    wire [4*PV-1:0]     s4_vals, s4_nvals, s3_cell, s3_ncell;
    wire [HDR_W-1:0]    s4_meta;
    cube4_tri_beam #(
        .P(P), .MAX_DIM(MAX_DIM), .VOXEL_W(VOXEL_W), .MAX_SS_LOG2(MAX_SS_LOG2), .WEIGHT_W(WEIGHT_W), .VGRAD(VGRAD),
        .LABELS(LABELS)
    ) u_beam (
        .clk(clk), .rst(rst), .flip_j(cfg[VIEW_FLIP_J]), .flip_i(cfg[VIEW_FLIP_I]),
        .s1_v(s1_v), .s1_pair(s1_pair), .s1_ywrap(s1_ywrap), .s1_bbwe(s1_bbwe), .s1_pb(s1_pb), .s1_ctl(s1_ctl),
        .s3_wx(s3_wx), .give(give), .s4_v(s4_v), .s4_vals(s4_vals), .s4_nvals(s4_nvals),
        .s3_cell(s3_cell), .s3_ncell(s3_ncell), .s4_wx(s4_wx), .s4_wy(s4_wy), .s4_wz(s4_wz), .s4_meta(s4_meta));

    // ==== which samples count (window, cut plane): TRI_CLIP_LAT cycles from s4 ====
    wire [P-1:0] clip_keep;
    generate
        if (CLIP != 0) begin : g_clip
            cube4_clip #(
                .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .SLAB(SLAB)
            ) u_clip (
                .clk(clk), .cfg(cfg),
                .in_m(s4_meta[HDR_M +: M_W]), .in_j(s4_meta[HDR_J +: DIM_W]),
                .in_pb(s4_meta[HDR_PB +: PB_W]), .in_skew(s4_meta[HDR_SKEW +: LANE_W]),
                .in_wx(s4_wx), .in_wy(s4_wy), .keep(clip_keep));
        end else begin : g_no_clip
            assign clip_keep = {P{1'b1}};
            wire unused_wx_clip = ^{s4_wx, cfg};
        end
    endgenerate

    // ==== beside the lerps: valid, header (KEEP inserted), y / z weights ====
    wire                push_d;
    wire [HDR_W-1:0]    l_hdr;
    wire [WEIGHT_W-1:0] l_wy, l_wz;
    cube4_tri_meta #(
        .P(P), .MAX_DIM(MAX_DIM), .MAX_SS_LOG2(MAX_SS_LOG2), .WEIGHT_W(WEIGHT_W)
    ) u_meta (
        .clk(clk), .rst(rst), .s4_v(s4_v), .s4_meta(s4_meta), .s4_wy(s4_wy), .s4_wz(s4_wz),
        .keep(clip_keep), .wy(l_wy), .wz(l_wz), .push_d(push_d), .hdr(l_hdr));

    // ==== the lanes: seven lerps per channel ====
    wire [PV-1:0] l_sample;
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            cube4_tri_lane #(.VOXEL_W(VOXEL_W), .WEIGHT_W(WEIGHT_W), .VGRAD(VGRAD), .LABELS(LABELS)) u_lane (
                .clk(clk), .wx(s3_wx), .wy(l_wy), .wz(l_wz),
                .vals(s4_vals[q*4*VW +: 4*VW]), .nvals(s4_nvals[q*4*VW +: 4*VW]),
                .pre_vals(s3_cell[q*4*VW +: 4*VW]), .pre_nvals(s3_ncell[q*4*VW +: 4*VW]),
                .sample(l_sample[q*VW +: VW]));
        end
    endgenerate

    // ==== the output FIFO ====
    // push_d says the z-lerp's result is an item at the next cycle; an s3
    // beat that leaves without being emitted gives its entry back.
    localparam integer OUT_W = PV + HDR_W;
    wire [OUT_W-1:0] fifo_out;
    wire unused_credit_d, unused_valid_cp;
    cube4_credit_fifo #(.DATA_W(OUT_W), .DEPTH(FIFO_DEPTH)) u_fifo (
        .clk(clk), .rst(rst), .take(take), .give(give),
        .credit(credit), .credit_d(unused_credit_d),
        .push_d(push_d), .in_data({l_hdr, l_sample}),
        .out_valid(out_valid), .out_ready(out_ready), .out_data(fifo_out), .out_valid_cp(unused_valid_cp));
    assign {out_hdr, out_sample} = fifo_out;
endmodule
`default_nettype wire

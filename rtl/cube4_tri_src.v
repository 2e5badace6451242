`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_tri_src
// -----------------------------------------------------------------------------
// Purpose
//   TRI's first two stages (cube4_tri): takes a memory beat and its cube4_cfb
//   tag (s0), and chooses each lane's lower and upper slice word (s1):
//   * the tag's fields: the header (CUBE4_GEOMETRY; KEEP = LVALID for now,
//     INSIDE = valid, not below the rectangle's low sides (LINL), not in the
//     last column when wx > 0 nor in the last row when wy > 0) and the fields
//     later stages need, as one word (CUBE4_TRI_LAYOUT, TRI_C_*);
//   * slice buffers (only when MAX_SS_LOG2 > 0): two slices of raw words per
//     lane, by slice parity, written by the beat that reads the slice from
//     memory, replayed for the S sample slices between two voxel slices.
//     Each is a block RAM read through its output register
//     (cube4_sdp_ram OUT_REG = 2): the read is addressed by the input's tag
//     as the beat is taken (a register of the voxel memory's), its word is
//     in the read register at s0 and in the output register at s1, so no
//     block RAM's clock-to-data lies in s1's selects. A beat read at the
//     edge that writes its slot (the beat before it, in s0, wrote that
//     slot: a slice of one beat) takes the word written (a bypass; on a
//     block RAM the read of a word written at the same edge is undefined);
//   * each slice from memory (tag LMEM / UMEM) or from its slice buffer; the
//     upper slice realigned to the lower slice's lanes (its skew differs by
//     the k step: cube4_ring_shift, one hop, down unless FLIP_K), and zero
//     unless the tag's UUSE.
//
// Parameters (CUBE4_TRI_PARAMS)
//   P            pipelines.                           1..64.   Default 8.
//   MAX_DIM      largest volume dimension.            2..2048. Default 256.
//   VOXEL_W      voxel width.                         1..16.   Default 8.
//   MAX_SS_LOG2  log2 of the largest supersampling.   0..3.    Default 0.
//   WEIGHT_W     weight width.                        4..12.   Default 8.
//   VGRAD        1: a word is the voxel and its gradient (CUBE4_WORD_LAYOUT).
//                                                     0..1.    Default 0.
//
// Latency
//   Two register stages that move on every cycle (no stall enable): a beat
//   taken at an edge is in s0 after it, its s1_* outputs one cycle later.
//   s0_v and s1_v are the stages' valid bits (reset); nothing else is reset.
//
// Ports
//   take       in   a beat enters s0 (in_valid && TRI's credit)
//   in_tag     in   cube4_cfb's tag (CUBE4_TAG_LAYOUT)
//   in_data    in   lane q = bank q's word (WORD_W bits, raw; 0 for lanes not read)
//   flip_k     in   view register FLIP_K (static within a frame)
//   s1_v       out  s1 holds a beat
//   s1_pair    out  lane q = {upper, lower} word (2 * WORD_W bits, raw)
//   s1_ywrap, s1_bbwe, s1_pb   out  the tag's YWRAP, BBWE and PB, at s1
//   s1_ctl     out  the fields that ride along (TRI_C_W bits, TRI_C_*)
//
// Bit growth and rounding: none (registers, buffers and selects only).
// =============================================================================
module cube4_tri_src #(
    `CUBE4_TRI_PARAMS
) (
    input  wire clk, input wire rst,
    input  wire take, input wire [TAG_W-1:0] in_tag, input wire [P*WORD_W-1:0] in_data,
    input  wire flip_k,
    output reg  s1_v, output wire [2*P*WORD_W-1:0] s1_pair,
    output wire s1_ywrap, output wire s1_bbwe, output reg [PB_W-1:0] s1_pb,
    output reg  [TRI_C_W-1:0] s1_ctl
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_tri_src", "P", P, 1, 64)
        `CUBE4_RANGE(g_bad_ss, "cube4_tri_src", "MAX_SS_LOG2", MAX_SS_LOG2, 0, 3)
    endgenerate

    localparam integer VW = WORD_W;      // a memory word: every buffer holds whole words
    localparam integer PV = P * VW;

    // ------------------------------------------------------------- s0: input
    wire [P-1:0] t_lval = in_tag[TAG_LVAL +: P];
    wire [P-1:0] t_nbr  = in_tag[TAG_LNBR +: P];
    wire [WEIGHT_W-1:0] t_wx = in_tag[TAG_WX +: WEIGHT_W];
    wire [WEIGHT_W-1:0] t_wy = in_tag[TAG_WY +: WEIGHT_W];
    // inside = valid, not below the rectangle's low sides (LINL; all ones without
    // slice rectangles), and not in the last column when wx > 0, nor the last row when wy > 0
    wire [P-1:0] t_inside = t_lval & in_tag[TAG_LINL +: P]
                          & ~(t_lval & ~t_nbr & {P{t_wx != '0}})
                          & ~{P{in_tag[TAG_YLAST] && t_wy != '0}};

    reg               s0_v;
    reg [PV-1:0]      s0_data;
    // the tag's buffer controls, TAG_K0ODD .. TAG_YWRAP in order:
    // {ywrap, bbwe, lmem, umem, uuse, k0odd}
    reg [5:0]         s0_f, s1_f;
    wire              s0_k0odd = s0_f[0], s0_umem = s0_f[2], s0_lmem = s0_f[3];
    reg [SB_W-1:0]    s0_sb;
    reg [PB_W-1:0]    s0_pb;
    reg [TRI_C_W-1:0] s0_ctl;

    reg [PV-1:0]      s1_data;
    // both stages: the valid bits, then the fields
    always @(posedge clk) begin
        if (rst) {s1_v, s0_v} <= 2'b00;
        else     {s1_v, s0_v} <= {s0_v, take};
    end
    always @(posedge clk) begin
        s1_data  <= s0_data;
        s1_f     <= s0_f;
        s1_pb    <= s0_pb;
        s1_ctl   <= s0_ctl;
        s0_data  <= in_data;
        s0_f     <= in_tag[TAG_K0ODD +: 6];
        s0_sb    <= in_tag[TAG_SB +: SB_W];
        s0_pb    <= in_tag[TAG_PB +: PB_W];
        // TRI_C_*: emit, wx, wy, wz, the lanes' neighbour and wrap flags, and
        // CUBE4_GEOMETRY's header, MSB first (KEEP = LVALID until cube4_clip's
        // result replaces it, cube4_tri_meta)
        s0_ctl   <= {in_tag[TAG_EMIT], t_wx, t_wy, in_tag[TAG_WZ +: WEIGHT_W], t_nbr, in_tag[TAG_LWRAP +: P],
                     in_tag[TAG_M +: M_W], in_tag[TAG_J +: DIM_W], in_tag[TAG_PB +: PB_W],
                     in_tag[TAG_SKEW +: LANE_W], in_tag[TAG_YLAST], in_tag[TAG_EOP], in_tag[TAG_SOP],
                     in_tag[TAG_STEPS +: 4], t_lval, t_lval, t_inside};
    end

    // ------------------------------------- s1: slice buffers and source select
    wire [PV-1:0]     s1_sb_lower, s1_sb_upper;  // slice-buffer words for the s1 beat
    wire [SB_W-1:0]   in_sb = in_tag[TAG_SB +: SB_W];
    wire              s1_k0odd = s1_f[0], s1_uuse = s1_f[1], s1_umem = s1_f[2], s1_lmem = s1_f[3];
    assign {s1_ywrap, s1_bbwe} = s1_f[5:4];

    genvar q;
    generate
        if (MAX_SS_LOG2 > 0) begin : g_slice_buf
            // Two slices per lane, by parity. Written at s0 by the beat that
            // reads the slice from memory; read as a beat is taken (the word
            // at s1, through the read and output registers) by later passes.
            wire wr_lo = s0_v && s0_lmem;   // lower slice, parity k0
            wire wr_up = s0_v && s0_umem;   // upper slice, parity k0 + 1
            wire wr0 = (wr_lo && !s0_k0odd) || (wr_up && s0_k0odd);
            wire wr1 = (wr_lo && s0_k0odd) || (wr_up && !s0_k0odd);
            // the bypass: the read at this edge meets s0's write of the same slot
            // (the same for every lane); s0's words are s1_data a cycle later
            reg  [1:0]  byp0_q, byp1_q;     // {s1, s0} of each buffer's flag
            reg  [PV-1:0] byp_d;            // the words written, at s1
            wire same = (in_sb == s0_sb);
            always @(posedge clk) begin
                byp0_q <= {byp0_q[0], wr0 && same};
                byp1_q <= {byp1_q[0], wr1 && same};
                byp_d  <= s1_data;
            end
            for (q = 0; q < P; q = q + 1) begin : g_lane
                wire [VW-1:0] d = s0_data[q*VW +: VW];
                wire [VW-1:0] out0, out1;
                cube4_sdp_ram #(.DATA_W (VW), .DEPTH (1 << SB_W), .OUT_REG (2)) u_sbuf0 (
                    .clk (clk), .rd_en (1'b1), .out_en (1'b1), .rd_addr (in_sb), .rd_data (out0),
                    .wr_en (wr0), .wr_addr (s0_sb), .wr_data (d));
                cube4_sdp_ram #(.DATA_W (VW), .DEPTH (1 << SB_W), .OUT_REG (2)) u_sbuf1 (
                    .clk (clk), .rd_en (1'b1), .out_en (1'b1), .rd_addr (in_sb), .rd_data (out1),
                    .wr_en (wr1), .wr_addr (s0_sb), .wr_data (d));
                wire [VW-1:0] w0 = byp0_q[1] ? byp_d[q*VW +: VW] : out0;
                wire [VW-1:0] w1 = byp1_q[1] ? byp_d[q*VW +: VW] : out1;
                assign s1_sb_lower[q*VW +: VW] = s1_k0odd ? w1 : w0;
                assign s1_sb_upper[q*VW +: VW] = s1_k0odd ? w0 : w1;
            end
        end else begin : g_no_slice_buf
            // S = 1 only: every pass reads its own slice, the upper slice is unused.
            assign s1_sb_lower = '0;
            assign s1_sb_upper = '0;
            wire unused_sb = ^{in_sb, s0_sb, s0_k0odd, s0_umem, s0_lmem, s1_k0odd};
        end
    endgenerate

    wire [PV-1:0] s1_lower   = s1_lmem ? s1_data : s1_sb_lower;
    wire [PV-1:0] s1_upper_r = s1_umem ? s1_data : s1_sb_upper;
    wire [PV-1:0] s1_upper_a;   // realigned to the lower slice's lanes
    cube4_ring_shift #(
        .P      (P),
        .DATA_W (VW)
    ) u_upper_align (
        .down (!flip_k),
        .x    (s1_upper_r),
        .y    (s1_upper_a)
    );
    wire [PV-1:0] s1_upper = s1_uuse ? s1_upper_a : '0;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_pair
            assign s1_pair[q*2*VW +: 2*VW] = {s1_upper[q*VW +: VW], s1_lower[q*VW +: VW]};
        end
    endgenerate
endmodule
`default_nettype wire

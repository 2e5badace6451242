`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_tri_beam
// -----------------------------------------------------------------------------
// Purpose
//   TRI's stages s2 .. s4 (cube4_tri): completes each lane's 2 x 2 x 2 cell.
//   * s2, beam buffers: per lane the previous row (beam) of the lower and
//     upper slice, one entry per partial beam, so the 2 x 2 neighbourhood in
//     (i, j) is complete when row j + 1 arrives. Lane q's buffer is written
//     from lane q - s_j (cube4_ring_shift, one hop, down when FLIP_J: the
//     skew changes by the j step from one beam to the next), so its output is
//     aligned with the new row. A Y-wrap beat's current row is zero.
//   * s3, hold for beam extension: a beat waits here for the next beat;
//     cube4_beam_ext gives position i + 1 from the neighbour lane, for the
//     last lane of a partial beam from the next beat (Fig. 6).
//   * s4: the cell (s3's four values and their i + 1 neighbours), the beat's
//     weights and header, valid only for a beat the tag emits.
//
// Parameters (CUBE4_TRI_PARAMS): as cube4_tri_src.
//
// Latency
//   s2 and s4 move on every cycle; s3 loads when s2 holds a beat (the drain
//   beat pushes out the last one). s1 -> s2 -> s3 -> s4: a beat reaches s4
//   three cycles after s1 once the next beat has reached s2. give is
//   registered with s4: the beat that left s3 was not emitted. Valid bits and
//   give are reset; nothing else.
//
// Ports
//   s1_*       in   cube4_tri_src's s1 outputs (s1_pair lane q = {upper, lower})
//   flip_j, flip_i  in  view registers FLIP_J, FLIP_I (static within a frame)
//   s3_wx      out  s3's wx (the lanes' own copies are loaded from it into s4)
//   give       out  an s3 beat left without being emitted (returns its FIFO entry)
//   s4_v       out  s4 holds an emitted beat
//   s4_vals    out  lane q = 4 words {prev upper, prev lower, cur upper, cur lower}
//                   (row j = prev, j + 1 = cur), raw WORD_W bits each
//   s4_nvals   out  the same at position i + 1
//   s3_cell, s3_ncell  out  s4_vals and s4_nvals one cycle early (the s3
//                   register and the beam extension's choice): the lanes form
//                   their x-lerps' differences from them (cube4_tri_lane)
//   s4_wx, s4_wy, s4_wz  out  the beat's weights (unsigned WEIGHT_W, Q0.WEIGHT_W)
//   s4_meta    out  the beat's header (CUBE4_GEOMETRY; KEEP = LVALID)
//
// Bit growth and rounding: none (buffers, registers and ring hops only).
// =============================================================================
module cube4_tri_beam #(
    `CUBE4_TRI_PARAMS
) (
    input  wire clk, input wire rst,
    input  wire flip_j, input wire flip_i,
    input  wire s1_v, input wire [2*P*WORD_W-1:0] s1_pair,
    input  wire s1_ywrap, input wire s1_bbwe, input wire [PB_W-1:0] s1_pb,
    input  wire [TRI_C_W-1:0] s1_ctl,
    output wire [WEIGHT_W-1:0] s3_wx, output reg give,
    output reg  s4_v, output reg [4*P*WORD_W-1:0] s4_vals, output reg [4*P*WORD_W-1:0] s4_nvals,
    output wire [4*P*WORD_W-1:0] s3_cell, output wire [4*P*WORD_W-1:0] s3_ncell,
    output reg  [WEIGHT_W-1:0] s4_wx, output reg [WEIGHT_W-1:0] s4_wy, output reg [WEIGHT_W-1:0] s4_wz,
    output reg  [HDR_W-1:0] s4_meta
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_tri_beam", "P", P, 1, 64)
    endgenerate

    localparam integer VW    = WORD_W;
    localparam integer PV    = P * VW;
    localparam integer BBMAX = 1 << PB_W;   // beam-buffer entries (>= NBMAX)

    // ------------------------------------------------------ s2: beam buffers
    // Lane q's beam buffer holds, per partial beam, the previous row's voxels
    // of the position lane q holds now: it is written from lane q - s_j.
    wire [2*PV-1:0] s1_pair_sh;
    cube4_ring_shift #(
        .P      (P),
        .DATA_W (2 * VW)
    ) u_bb_shift (
        .down (flip_j),
        .x    (s1_pair),
        .y    (s1_pair_sh)
    );

    reg               s2_v;
    reg [2*PV-1:0]    s2_cur;    // current row (zero on Y-wrap)
    reg [TRI_C_W-1:0] s2_ctl;
    wire [2*PV-1:0]   s2_prev;   // previous row, from the beam buffers

    // (distributed RAM, its read register in the fabric: the word feeds s3's
    // multiplexers and the lanes' x-lerps in the next cycle, and at P = 1, where
    // a lane's buffer is MAX_DIM words deep, a block RAM's clock-to-data would
    // take most of that cycle; the read of the word written at the same edge
    // returns the old word, the row before this one, on every form of DIST)
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_beam_buf
            cube4_sdp_ram #(.DATA_W (2 * VW), .DEPTH (BBMAX), .DIST (1)) u_bbuf (
                .clk (clk), .rd_en (1'b1), .out_en (1'b0), .rd_addr (s1_pb),
                .rd_data (s2_prev[q*2*VW +: 2*VW]),
                .wr_en (s1_v && s1_bbwe), .wr_addr (s1_pb), .wr_data (s1_pair_sh[q*2*VW +: 2*VW]));
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
        s2_ctl <= s1_ctl;
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
    reg [TRI_C_W-1:0] s3_ctl;
    wire              s3_take = s2_v;   // a new beat completes the held one
    wire              s3_emit = s3_ctl[TRI_C_EMIT];
    assign s3_wx = s3_ctl[TRI_C_WX +: WEIGHT_W];

    always @(posedge clk) begin
        if (rst) s3_v <= 1'b0;
        else if (s3_take) s3_v <= 1'b1;
    end
    always @(posedge clk) begin
        if (s3_take) begin
            s3_vals <= s2_vals;
            s3_ctl  <= s2_ctl;
        end
    end

    wire [4*PV-1:0] s3_nvals;   // the four values at position i + 1
    cube4_beam_ext #(
        .P      (P),
        .DATA_W (4 * VW)
    ) u_beam_ext (
        .down   (flip_i),
        .prev   (s3_vals),
        .cur    (s2_vals),
        .wrap   (s3_ctl[TRI_C_WRAP +: P]),
        .nbr_ok (s3_ctl[TRI_C_NBR +: P]),
        .nbr    (s3_nvals)
    );

    assign s3_cell  = s3_vals;
    assign s3_ncell = s3_nvals;

    // ------------------------------------------------ s4: the 2x2x2 cell
    always @(posedge clk) begin
        if (rst) begin
            s4_v <= 1'b0;
            give <= 1'b0;
        end else begin
            s4_v <= s3_take && s3_v && s3_emit;
            give <= s3_take && s3_v && !s3_emit;
        end
    end
    always @(posedge clk) begin
        s4_vals  <= s3_vals;
        s4_nvals <= s3_nvals;
        s4_wx    <= s3_wx;
        s4_wy    <= s3_ctl[TRI_C_WY +: WEIGHT_W];
        s4_wz    <= s3_ctl[TRI_C_WZ +: WEIGHT_W];
        // KEEP = LVALID (a copy of the same register: the ctl word's KEEP bits go unused)
        s4_meta  <= {s3_ctl[HDR_KEEP + P +: HDR_W - HDR_KEEP - P], s3_ctl[HDR_LVALID +: P],
                     s3_ctl[HDR_LVALID +: P], s3_ctl[HDR_INSIDE +: P]};
    end
endmodule
`default_nettype wire

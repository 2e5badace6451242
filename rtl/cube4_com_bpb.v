`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_bpb
// -----------------------------------------------------------------------------
// Purpose
//   COM's base-plane buffers (docs/architecture.md "COM"; the paper's
//   "base-plane buffer for one slice of intermediate compositing results"):
//   the partial result of every ray lives in the lane and slot of its latest
//   sample. For the beat of sample (m, j, i) they return the ray's partial
//   result at its previous sample (m-1, j - dyb, i - dxb):
//     slice buffer (NJ * NB beats): the word a1 of slot (j, pb) of slice m-1
//     beam buffer (NB beats): a2, the slice word of the beat one row above
//             (NB = 1, or a rectangle one partial beam wide: the previous beat)
//     back    = dyb ? a2 : a1, hopped one lane along the ring for the k step
//             (dkb: the voxel slice changed) and for the j step
//     the X-step (dxb): back hopped one lane along i; the lane at t = 0
//             takes the previous beat's back (prevb)
//   The words are opaque here (AC_W bits per lane, cube4_com's layout).
//
// Parameters
//   P, MAX_DIM, MAX_SS_LOG2: as cube4_com (1..64, 2..2048, 0..3).
//   WEIGHT_W  as cube4_com (the view layout).                    4..12.
//   AC_W      a lane's word.                                     1..4096.
//   SP_W      the slot's width (1..22, default 13); SB_DEPTH the slice buffer's
//             words, MAX_DIM * NBMAX or 2^SP_W with rectangles (default 8192)
//             (cube4_com derives both).
//   RECTS     0: the row above is the previous beat when NB = 1 (cfg, a
//             copied register); 1: when col1_4 says so.           0..1.
//   COPIES    enable and select copies per lane word.            1..64.  Default 4.
//
// Latency
//   Slice buffer: read at S1 (rd_sp, given at S0: the RAM registers its
//   address), word a1 at S3 (the RAM's output register); written at the end of
//   S11 (wr_en, wr_sp, given at S10; wr_data acc_q is S11's register). Beam
//   buffer: read at S2 (pb_rd), written with a1 at the end of S3 (v2, pb_wr
//   given at S2); a2 at S4. S4: a1 registered, back selected; S5: s5_back
//   and back_sh, a registered word and its ring hop (combinational); prevb_sh
//   the previous beat's back hopped as it is registered (the hop from the
//   neighbour lane's register ahead of S5's, not on the route from S5 into
//   the lane's blend and its T·A multiplier).
//   The last beat's words load under the copies of v2 (prim copies: v3 per
//   lane, then COPIES per register), so they hold across bubbles.
//
// Ports
//   rd_sp, pb_rd, pb_wr, v2, wr_en, wr_sp   (cube4_com_seq)
//   acc_q      in   S11: the lanes' new partial results (lane q at q*AC_W)
//   dyb4, dkb4, col1_4   in   S4: the beat's back step along y, a voxel
//              slice change, the previous beat is the row above (RECTS = 1)
//   s5_back    out  S5: (m-1, j-dyb, i) in the beat's skew, per lane
//   back_sh, prevb_sh   out  S5: this beat's and the previous beat's back,
//              hopped one lane along i (cfg_flip_i)
//
// Bit growth and rounding: none (words move, nothing is computed).
// =============================================================================
module cube4_com_bpb #(
    `CUBE4_SLICE_PARAMS,
    parameter integer AC_W     = 68,
    parameter integer SP_W     = 13, parameter integer SB_DEPTH   = 8192,
    parameter integer RECTS    = 0,  parameter integer COPIES     = 4,
    localparam integer PA = P * AC_W
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    input  wire [SP_W-1:0] rd_sp, input wire [PB_W-1:0] pb_rd, input wire [PB_W-1:0] pb_wr,
    input  wire v2, input wire wr_en, input wire [SP_W-1:0] wr_sp,
    input  wire [PA-1:0] acc_q,
    input  wire dyb4, input wire dkb4, input wire col1_4,
    output wire [PA-1:0] s5_back, output wire [PA-1:0] back_sh, output wire [PA-1:0] prevb_sh
);
    `CUBE4_VIEW_FIELDS(cfg);

    // ---- the slice buffer (S1 -> S3) and the beam buffer (S2 -> S4) ----
    // Both register their addresses and write enables themselves (with
    // copies for their block RAMs, IN_REG) and end in their output register
    // (OUT_REG: the block RAM's own, whose clock-to-out is most of a cycle
    // without it). The beam buffer holds one beam of slice words (a2 of a
    // beat = a1 of the beat NB steps earlier, same partial beam); for NB >= 2
    // its write comes first.
    wire [PA-1:0] a1_ram, a2_ram;       // S3, S4
    cube4_sdp_ram #(.DATA_W(PA), .DEPTH(SB_DEPTH), .IN_REG(1), .OUT_REG(1)) u_slice (
        .clk(clk), .rd_en(1'b1), .out_en(1'b0), .rd_addr(rd_sp), .rd_data(a1_ram),
        .wr_en(wr_en), .wr_addr(wr_sp), .wr_data(acc_q));
    cube4_sdp_ram #(.DATA_W(PA), .DEPTH(NBMAX), .IN_REG(1), .OUT_REG(1)) u_beam (
        .clk(clk), .rd_en(1'b1), .out_en(1'b0), .rd_addr(pb_rd), .rd_data(a2_ram),
        .wr_en(v2), .wr_addr(pb_wr), .wr_data(a1_ram));

    // ---- S4: a1, the previous beat's a1, and a2, per lane ----
    // The last beat's words load under v_s[4] as a tree of copies: v3 (one per
    // lane), then COPIES per register (cube4_prim_reg_en).
    wire [PA-1:0] a1, a2, back, lastb_all, lastb_sh, s5_prevb;
    wire [P-1:0]  v3;
    cube4_prim_copies #(.N(P)) u_v3 (.clk(clk), .rst(rst), .d(v2), .q(v3));
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            localparam integer LO = q * AC_W;
            reg  [AC_W-1:0] s4_a1_q, s5_back_q, s5_prevb_q;
            wire [AC_W-1:0] prev_a1, lastb;
            always @(posedge clk) begin
                s4_a1_q    <= a1_ram[LO +: AC_W];
                s5_back_q  <= back[LO +: AC_W];
                s5_prevb_q <= lastb_sh[LO +: AC_W];   // the back of the last beat before this one, hopped
            end
            cube4_prim_reg_en #(.W(AC_W), .COPIES(COPIES)) u_prev_a1 (
                .clk(clk), .rst(rst), .en_d(v3[q]), .d(s4_a1_q), .q(prev_a1));
            cube4_prim_reg_en #(.W(AC_W), .COPIES(COPIES)) u_lastb (
                .clk(clk), .rst(rst), .en_d(v3[q]), .d(back[LO +: AC_W]), .q(lastb));
            assign lastb_all[LO +: AC_W] = lastb;
            // the row above at the same partial beam is the previous beat (NB = 1,
            // or a rectangle one partial beam wide): its beam-buffer write comes too late
            if (RECTS != 0) begin : g_col1
                assign a2[LO +: AC_W] = col1_4 ? prev_a1 : a2_ram[LO +: AC_W];
            end else begin : g_nb1
                wire [AC_W-1:0] nb1;        // NB = 1, spread over the word (its selects
                                            // feed the ring hops to the neighbouring lanes)
                cube4_prim_spread #(.W(1), .D(AC_W), .COPIES(COPIES)) u_nb1 (
                    .clk(clk), .rst(1'b0), .d(cfg_nb == NB_W'(1)), .q(nb1));
                assign a2[LO +: AC_W] = (nb1 & prev_a1) | (~nb1 & a2_ram[LO +: AC_W]);
            end
            assign a1[LO +: AC_W]       = s4_a1_q;
            assign s5_back[LO +: AC_W]  = s5_back_q;
            assign s5_prevb[LO +: AC_W] = s5_prevb_q;
        end
        if (RECTS == 0) begin : g_no_col1
            wire unused_col1 = col1_4;
        end
    endgenerate

    // ---- S4: (m-1, j-dyb, i) in this beat's skew: the k and j ring hops ----
    wire [PA-1:0] a1_k, a2_j, a2_jk;
    cube4_ring_shift #(.P(P), .DATA_W(AC_W)) u_a1k  (.down(cfg_flip_k), .x(a1),   .y(a1_k));
    cube4_ring_shift #(.P(P), .DATA_W(AC_W)) u_a2j  (.down(cfg_flip_j), .x(a2),   .y(a2_j));
    cube4_ring_shift #(.P(P), .DATA_W(AC_W)) u_a2jk (.down(cfg_flip_k), .x(a2_j), .y(a2_jk));
    assign back = dyb4 ? (dkb4 ? a2_jk : a2_j) : (dkb4 ? a1_k : a1);

    // ---- S5: the X-step hop (the lane at t = 0 takes the previous beat) ----
    cube4_ring_shift #(.P(P), .DATA_W(AC_W)) u_bsh (.down(cfg_flip_i), .x(s5_back),    .y(back_sh));
    // (the previous beat's back: hopped at S4, from its registers, into S5's; cfg_flip_i
    // holds through a frame)
    cube4_ring_shift #(.P(P), .DATA_W(AC_W)) u_psh (.down(cfg_flip_i), .x(lastb_all),  .y(lastb_sh));
    assign prevb_sh = s5_prevb;
endmodule
`default_nettype wire

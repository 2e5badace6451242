`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_gra_pos
// -----------------------------------------------------------------------------
// Purpose
//   GRA's position buffers, shared by the walks that step by position
//   (cube4_gra_walk: slice rectangles; cube4_gra_beats: the beat schedule).
//   A step at walk position (w, r, pb) brings X = (w, r, pb) and the centre
//   C = (w - 1, r - 1, pb) with the six neighbours of cube4_gra_lines:
//     plane A {r, pb}      X of the step at (w - 1, r, pb): P1 = (w - 1, r)
//     plane B {r, pb}      C of that step (its centre, row r - 1): P2b1 =
//                          (w - 2, r - 1), at the step's row as plane A (a
//                          row's address is r mod 2^RW for both: r - 1 would
//                          map the rows one to one alike, with a subtractor
//                          in front of the read and of the bypass compare)
//     beam {pb}            X, P1, C, P2b1 of the step at (w, r - 1, pb):
//                          B1, C, P1b2, P2b2
//   Each is read in the cycle the step's position loads (ld: a block RAM's
//   registered read) and written when it steps; a read of the word written
//   in that cycle takes the new word (bypass). With OUT_STAGE = 1 the words
//   read pass one more register, the RAMs' output registers (cube4_sdp_ram
//   OUT_REG = 2, the block RAMs' own), loaded as the step's position moves
//   on from the read to the step (mv); the write of the step before it, if
//   it came after the read (a second bypass), is kept in a register beside
//   them and chosen after them: the block RAMs' clock-to-data ends at their
//   output register (0.7 ns on the ECP5), not in the caller's arithmetic. The caller says, registered
//   with its step, which words are this frame's neighbours (pg, pgb, bg);
//   the others read as zero. Plane A holds rows 0 .. NJ - 1 (row NJ is
//   outside the volume), plane B rows 1 .. NJ (the centre's row + 1), a
//   dead step (one that only moves the window) writes nothing. The buffers
//   keep a beat's header without its position (PB, J, M: the top fields),
//   which C's header takes from the step's own, (w - 1, r - 1, pb), where a
//   beat came in (a bit kept with it; elsewhere the header is zero).
//
// Parameters
//   OUT_STAGE  0: the words read are the outputs from the edge after ld
//              (cube4_gra_walk); 1: from the edge after mv (cube4_gra_beats,
//              whose step register follows its read register).  0..1.
//              Default 0.
//   P, VOXEL_W, WEIGHT_W, MAX_DIM, MAX_SS_LOG2 as cube4_gra (derived widths:
//   cube4_defs.vh CUBE4_GEOMETRY, CUBE4_GRA_LAYOUT)
//
// Latency
//   OUT_STAGE = 0: the words for a position loaded at an edge (ld) are on
//   the outputs after it, until the next load. OUT_STAGE = 1: they are on
//   the outputs after the next edge with mv (at which or before which the
//   step before it has stepped; the caller moves a read on at mv, and loads
//   the next read at the same edge or later), until the next mv; a step
//   after a read comes at the read's mv edge, not between (cube4_gra_beats:
//   a step moves its read register on; a simulation check). A step's write
//   lands at its edge.
//
// Ports (samples unsigned Q0.VOXEL_W, P lanes of VOXEL_W bits)
//   ld [GRA_POS_G], ld_r [DIM_W], ld_pb [PB_W]   the next step's position
//                                    loads (read)
//   mv [GRA_POS_G]                   (OUT_STAGE = 1) the position read moves
//                                    on to the step: its words load
//   step [GRA_POS_G], dead, i0_w, i0_r, i0_pb, row_ok [2]   the loaded step
//                                    steps (write), its position (slice
//                                    [M_W], row, partial beam), whether it
//                                    writes (!dead), and its row's bounds
//                                    {i0_r != 0, i0_r < NJ} (plane B's write,
//                                    plane A's), formed by the caller (beat
//                                    source: registers, ahead of the step)
//     ld, mv and step come as GRA_POS_G equal copies, one per group of
//     registers (cube4_defs.vh CUBE4_GRA_LAYOUT: plane A; plane B; the beam
//     buffer's X, P1 with its meta, C, P2b1): each copy's load enables and
//     bypass choice reach its group's words only (the caller forms each
//     from its own register copy, or gives one signal GRA_POS_G times; a
//     simulation check compares them)
//   in_beat, sample, lane_valid [P]  the step brings an input beat, its
//                                    samples and valid lanes
//   x                          out   X: the samples of the valid lanes of an
//                                    input beat, zero elsewhere
//   x_meta [GRA_META_W]              X's {real, header}
//   pg, pgb, bg                      the plane A, plane B and beam words read
//                                    for the step are this frame's neighbours
//   p1, p2b1, b1, c_meta, c, p1b2, p2b2   the neighbours (zero where their
//                                    word does not count), C with its {real,
//                                    header} (P1's, kept in the beam buffer)
//
// Bit growth and rounding: none (storage only).
// =============================================================================
module cube4_gra_pos #(
    parameter integer OUT_STAGE = 0,
    `CUBE4_GRA_PARAMS
) (
    input  wire clk,
    input  wire [GRA_POS_G-1:0] ld, input wire [DIM_W-1:0] ld_r, input wire [PB_W-1:0] ld_pb,
    input  wire [GRA_POS_G-1:0] mv,
    input  wire [GRA_POS_G-1:0] step, input wire dead, input wire [M_W-1:0] i0_w, input wire [DIM_W-1:0] i0_r,
    input  wire [PB_W-1:0] i0_pb,
    input  wire [1:0] row_ok,
    input  wire in_beat, input wire [P*VOXEL_W-1:0] sample, input wire [P-1:0] lane_valid,
    output wire [P*VOXEL_W-1:0] x, input wire [GRA_META_W-1:0] x_meta,
    input  wire pg, input wire pgb, input wire bg,
    output wire [P*VOXEL_W-1:0] p1, output wire [P*VOXEL_W-1:0] p2b1,
    output wire [P*VOXEL_W-1:0] b1, output wire [GRA_META_W-1:0] c_meta, output wire [P*VOXEL_W-1:0] c,
    output wire [P*VOXEL_W-1:0] p1b2, output wire [P*VOXEL_W-1:0] p2b2
);
    localparam integer PV     = P * VOXEL_W;
    localparam integer META_W = GRA_META_W;
    localparam integer RW  = (MAX_DIM > 1) ? $clog2(MAX_DIM) : 1;   // row bits of a plane address
    localparam integer PAW = RW + PB_W;                            // plane address {row, pb}
    localparam integer SM_W = 2 + HDR_PB;                          // a meta kept: {beat, real, header below PB}
    localparam integer AWD = SM_W + PV;                            // plane A: X with its meta
    localparam integer BMW = 4 * PV + SM_W;                        // beam: X, P1 (meta), C, P2b1

    wire [SM_W-1:0] p1_meta;                       // P1's kept meta (into the beam buffer)
    wire [SM_W-1:0] x_sm = {in_beat, x_meta[META_W-1], x_meta[HDR_PB-1:0]};   // (beat: it came in)
    wire unused_pos = ^x_meta[META_W-2:HDR_PB];    // (a beat's position: the step's)
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_mask
            assign x[q*VOXEL_W +: VOXEL_W] = (in_beat && lane_valid[q]) ? sample[q*VOXEL_W +: VOXEL_W]
                                                                         : {VOXEL_W{1'b0}};
        end
    endgenerate
    wire [PAW-1:0]  ra_a = {ld_r[RW-1:0], ld_pb}, wa_a = {i0_r[RW-1:0], i0_pb};
    wire [PAW-1:0]  ra_b = ra_a,                  wa_b = wa_a;   // (plane B: at the step's row too)
    // the groups' writes: plane A (X at its own position), plane B (C, at the
    // step's row as plane A), the beam buffer's four fields; a dead step writes nothing
    wire wa_ok = !dead && row_ok[0];              // (registers: each copy of step ANDs them)
    wire wb_ok = !dead && row_ok[1];
    wire [GRA_POS_G-1:0] we = step & {{(GRA_POS_G - 2){!dead}}, wb_ok, wa_ok};
    wire [AWD-1:0] a_w;                           // the words read, with the writes since
    wire [PV-1:0]  b_w;
    wire [BMW-1:0] m_w;
    cube4_gra_pos_buf #(.DATA_W (AWD), .AW (PAW), .OUT_STAGE (OUT_STAGE)) u_plane_a (
        .clk (clk), .ld (ld[0]), .rd_addr (ra_a), .mv (mv[0]),
        .we (we[0]), .wr_addr (wa_a), .wr_data ({x_sm, x}), .rd_word (a_w));
    cube4_gra_pos_buf #(.DATA_W (PV), .AW (PAW), .OUT_STAGE (OUT_STAGE)) u_plane_b (
        .clk (clk), .ld (ld[1]), .rd_addr (ra_b), .mv (mv[1]),
        .we (we[1]), .wr_addr (wa_b), .wr_data (c), .rd_word (b_w));
    // the beam buffer {pb}: X, P1 with its meta, C, P2b1, a buffer each
    localparam integer BMF = GRA_POS_G - 2;      // its fields
    localparam integer MLO0 = 3 * PV + SM_W, MLO1 = 2 * PV, MLO2 = PV, MLO3 = 0;
    localparam integer MW0 = PV, MW1 = PV + SM_W, MW2 = PV, MW3 = PV;
    wire [BMW-1:0] wd_m = {x, p1_meta, p1, c, p2b1};
    genvar f;
    generate
        for (f = 0; f < BMF; f = f + 1) begin : g_beam
            localparam integer LO = (f == 0) ? MLO0 : (f == 1) ? MLO1 : (f == 2) ? MLO2 : MLO3;
            localparam integer FW = (f == 0) ? MW0 : (f == 1) ? MW1 : (f == 2) ? MW2 : MW3;
            cube4_gra_pos_buf #(.DATA_W (FW), .AW (PB_W), .OUT_STAGE (OUT_STAGE)) u_field (
                .clk (clk), .ld (ld[2 + f]), .rd_addr (ld_pb), .mv (mv[2 + f]),
                .we (we[2 + f]), .wr_addr (i0_pb), .wr_data (wd_m[LO +: FW]), .rd_word (m_w[LO +: FW]));
        end
    endgenerate
`ifndef SYNTHESIS
    // the copies are equal, and (OUT_STAGE = 1) the caller's order holds: a step
    // after a read and before its mv comes at mv (no reset here: a reset in
    // mid-frame may leave pend set, and a read after it replaces one that never
    // moved on; no step comes before an mv)
    reg pend;                                     // a read waits for its mv (set before any step)
    always @(posedge clk) begin
        if (ld != {GRA_POS_G{ld[0]}} || mv != {GRA_POS_G{mv[0]}} || step != {GRA_POS_G{step[0]}})
            $fatal(1, "cube4_gra_pos: the copies of ld (%b), mv (%b) or step (%b) differ", ld, mv, step);
        if (OUT_STAGE != 0 && pend && step[0] && !dead && !mv[0])
            $fatal(1, "cube4_gra_pos: a step between a read and its mv (OUT_STAGE = 1 takes writes at mv only)");
        if (ld[0]) pend <= 1'b1;
        else if (mv[0]) pend <= 1'b0;
    end
`endif
    generate
        `CUBE4_RANGE(g_bad_groups, "cube4_gra_pos", "GRA_POS_G", GRA_POS_G, 6, 6)   // (the six buffers above)
    endgenerate
    assign p1_meta = pg  ? a_w[PV +: SM_W] : {SM_W{1'b0}};
    assign p1      = pg  ? a_w[PV-1:0] : {PV{1'b0}};
    assign p2b1    = pgb ? b_w : {PV{1'b0}};
    // C's {real, header}: its kept fields and its position (w - 1, r - 1, pb)
    wire [SM_W-1:0] c_sm = m_w[3*PV +: SM_W];
    wire [M_W-1:0]   c_m = i0_w - 1'b1;
    wire [DIM_W-1:0] c_j = i0_r - 1'b1;
    assign b1      = bg  ? m_w[3*PV + SM_W +: PV] : {PV{1'b0}};
    wire c_beat = c_sm[SM_W-1];                    // a beat came in there: its header has its position
    assign c_meta  = bg  ? {c_sm[SM_W-2], c_beat ? {c_m, c_j, i0_pb} : {(M_W + DIM_W + PB_W){1'b0}},
                            c_sm[HDR_PB-1:0]} : {META_W{1'b0}};
    assign c       = bg  ? m_w[2*PV +: PV] : {PV{1'b0}};
    assign p1b2    = bg  ? m_w[PV +: PV] : {PV{1'b0}};
    assign p2b2    = bg  ? m_w[0 +: PV] : {PV{1'b0}};
    generate
        if (DIM_W > RW) begin : g_row_top
            wire unused_r = ^{ld_r[DIM_W-1:RW], i0_r[DIM_W-1:RW]};   // (rows below MAX_DIM address the planes)
        end
    endgenerate

endmodule
`default_nettype wire

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
//     plane B {r - 1, pb}  C of that step: P2b1 = (w - 2, r - 1)
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
//   outside the volume), plane B rows 0 .. NJ - 1 (the centre's row), a
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
//   ld, ld_r [DIM_W], ld_pb [PB_W]   the next step's position loads (read)
//   mv                               (OUT_STAGE = 1) the position read moves
//                                    on to the step: its words load
//   step, dead, i0_w, i0_r, i0_pb, nj   the loaded step steps (write), its
//                                    position (slice [M_W], row, partial
//                                    beam), whether it writes (!dead), NJ
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
    input  wire ld, input wire [DIM_W-1:0] ld_r, input wire [PB_W-1:0] ld_pb,
    input  wire mv,
    input  wire step, input wire dead, input wire [M_W-1:0] i0_w, input wire [DIM_W-1:0] i0_r,
    input  wire [PB_W-1:0] i0_pb,
    input  wire [DIM_W-1:0] nj,
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
    localparam integer PBN = 1 << PB_W;                            // beam buffer entries

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
    wire [RW-1:0]   ld_r1 = ld_r[RW-1:0] - 1'b1;   // the centre's row (plane B)
    wire [RW-1:0]   i0_r1 = i0_r[RW-1:0] - 1'b1;
    wire [PAW-1:0]  ra_a = {ld_r[RW-1:0], ld_pb}, wa_a = {i0_r[RW-1:0], i0_pb};
    wire [PAW-1:0]  ra_b = {ld_r1, ld_pb},        wa_b = {i0_r1, i0_pb};
    wire we_a = step && !dead && (i0_r < nj);     // plane A: X at its own position
    wire we_b = step && !dead && (i0_r != '0);    // plane B: C at the centre's position
    wire we_m = step && !dead;                    // the beam buffer
    wire [AWD-1:0] wd_a = {x_sm, x};
    wire [PV-1:0]  wd_b = c;
    wire [BMW-1:0] wd_m = {x, p1_meta, p1, c, p2b1};
    wire [AWD-1:0] rd_a;
    wire [PV-1:0]  rd_b;
    wire [BMW-1:0] rd_m;
    // OUT_STAGE = 1: the RAMs' output registers (OUT_REG = 2, loaded at mv) are the stage
    localparam integer ORG = (OUT_STAGE != 0) ? 2 : 0;
    wire oe = (OUT_STAGE != 0) && mv;
    cube4_sdp_ram #(.DATA_W (AWD), .DEPTH (1 << PAW), .OUT_REG (ORG)) u_plane_a (
        .clk (clk), .rd_en (ld), .out_en (oe), .rd_addr (ra_a), .rd_data (rd_a),
        .wr_en (we_a), .wr_addr (wa_a), .wr_data (wd_a));
    cube4_sdp_ram #(.DATA_W (PV), .DEPTH (1 << PAW), .OUT_REG (ORG)) u_plane_b (
        .clk (clk), .rd_en (ld), .out_en (oe), .rd_addr (ra_b), .rd_data (rd_b),
        .wr_en (we_b), .wr_addr (wa_b), .wr_data (wd_b));
    cube4_sdp_ram #(.DATA_W (BMW), .DEPTH (PBN), .OUT_REG (ORG)) u_beam (
        .clk (clk), .rd_en (ld), .out_en (oe), .rd_addr (ld_pb), .rd_data (rd_m),
        .wr_en (we_m), .wr_addr (i0_pb), .wr_data (wd_m));
    // the word read for a position, with the writes since its read (bypass: the
    // RAM returns the old word for a read in the cycle of the write)
    reg            by_a, by_b, by_m;
    reg [AWD-1:0]  bd_a;
    reg [PV-1:0]   bd_b;
    reg [BMW-1:0]  bd_m;
    wire [AWD-1:0] a_w;
    wire [PV-1:0]  b_w;
    wire [BMW-1:0] m_w;
    // the read's addresses, kept for a write that lands at its mv
    reg [PAW-1:0]  ra_a1, ra_b1;
    reg [PB_W-1:0] ra_m1;
    wire hit_a = (OUT_STAGE != 0) && we_a && (wa_a == ra_a1);
    wire hit_b = (OUT_STAGE != 0) && we_b && (wa_b == ra_b1);
    wire hit_m = (OUT_STAGE != 0) && we_m && (i0_pb == ra_m1);
    // (loaded at ld only: with OUT_STAGE = 1 a write after the read comes at mv's
    // edge, where the stage below takes it; checked in simulation)
    always @(posedge clk) begin
        if (ld) begin                                // a write in the read's own cycle
            ra_a1 <= ra_a;
            ra_b1 <= ra_b;
            ra_m1 <= ld_pb;
            by_a  <= we_a && (wa_a == ra_a);
            by_b  <= we_b && (wa_b == ra_b);
            by_m  <= we_m && (i0_pb == ld_pb);
            bd_a  <= wd_a;
            bd_b  <= wd_b;
            bd_m  <= wd_m;
        end
    end
    generate
        if (OUT_STAGE == 0) begin : g_direct
            assign a_w = by_a ? bd_a : rd_a;         // the word with every write since
            assign b_w = by_b ? bd_b : rd_b;
            assign m_w = by_m ? bd_m : rd_m;
            wire unused_mv = ^{mv, ra_a1, ra_b1, ra_m1, hit_a, hit_b, hit_m};   // (read for the step itself)
        end else begin : g_stage
            // the RAMs' words pass their output registers at mv; the bypass's
            // choice and word (with a write at mv's own edge) beside them, the
            // choice applied after the registers
            reg            s_a, s_b, s_m;
            reg [AWD-1:0]  sd_a;
            reg [PV-1:0]   sd_b;
            reg [BMW-1:0]  sd_m;
            always @(posedge clk) begin
                if (mv) begin
                    s_a  <= hit_a || by_a;
                    s_b  <= hit_b || by_b;
                    s_m  <= hit_m || by_m;
                    sd_a <= hit_a ? wd_a : bd_a;
                    sd_b <= hit_b ? wd_b : bd_b;
                    sd_m <= hit_m ? wd_m : bd_m;
                end
            end
            assign a_w = s_a ? sd_a : rd_a;
            assign b_w = s_b ? sd_b : rd_b;
            assign m_w = s_m ? sd_m : rd_m;
`ifndef SYNTHESIS
            // the caller's order: a step after a read and before its mv comes at mv
            // (no reset here: a reset in mid-frame may leave pend set, and a read
            // after it replaces one that never moved on; no step comes before an mv)
            reg pend;                                // a read waits for its mv (set before any step)
            always @(posedge clk) begin
                if (pend && step && !dead && !mv)
                    $fatal(1, "cube4_gra_pos: a step between a read and its mv (OUT_STAGE = 1 takes writes at mv only)");
                if (ld) pend <= 1'b1;
                else if (mv) pend <= 1'b0;
            end
`endif
        end
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

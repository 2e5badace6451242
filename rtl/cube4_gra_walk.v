`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_gra_walk
// -----------------------------------------------------------------------------
// Purpose
//   GRA's neighbourhood source for slice rectangles (RECTS = 1; numerics.md
//   section 18, docs/architecture.md "GRA"), with the interface of
//   cube4_gra_lines. The beats arrive as the front end's walk
//   (golden/cube4/slices.py SliceRects.walk: each slice's rectangle and the
//   rows and partial beams needed to finish the slice before; beats with no
//   lane valid carry no sample). A step at walk position (w, r, pb) brings
//   X = (w, r, pb) and the centre C = (w - 1, r - 1, pb) with the same six
//   neighbours as cube4_gra_lines, from position buffers instead of delay
//   lines: plane A {row, pb} holds X (its old word is P1 = (w-1, r)), plane
//   B holds C at the centre's position (old word P2b1 = (w-2, r-1)), and a
//   beam buffer by pb holds X, P1, C, P2b1 of the row before (B1, C, P1b2,
//   P2b2). Each is read in the cycle a step's position loads into the input
//   register (a block RAM's registered read) and written when it steps (a
//   read of the word written in that cycle takes the new word); a plane word
//   counts only where the previous walk covered the position, a beam word
//   only after the walk's first row, otherwise it is zero. After the frame's
//   last beat the source walks the rest of the last slice itself (the rows
//   of its walk and one more, then three steps; fend marks the last).
//
// Parameters
//   P, VOXEL_W, WEIGHT_W, MAX_DIM, MAX_SS_LOG2 as cube4_gra (derived widths:
//   cube4_defs.vh CUBE4_GEOMETRY, CUBE4_GRA_LAYOUT)
//
// Latency
//   The input register i0 holds the next step's position with its sample
//   beat (an input beat, or none: a step of the source's own walk); the
//   interface shows it as X, combinationally, and the buffers' words read
//   for it. A step happens when i0 holds a position and the output FIFO's
//   credit (copy GRA_STEPS-1; the other copies are unused here) is there.
//
// Ports (as cube4_gra_lines; samples unsigned Q0.VOXEL_W, lanes in the
// alignment of their own beat)
//   in_*      the walk's sample stream (cube4_tri's format)
//   credit    [GRA_STEPS]   copies of the output FIFO's credit
//   step      out  the source and the window move this cycle
//   sop       out  0 (the walk gates stale words itself)
//   fend      out  the step is the last of the frame (the last centre may leave)
//   x, b1, p1, c, p1b2, p2b1, p2b2  [P*VOXEL_W]  X and its six neighbours;
//             zero outside the previous walk / before the walk's second row
//   c_meta    [GRA_META_W]  {real, header} of C (real: an input beat with a lane valid)
//   c_sel     [P*GRA_NSEL]  C's select flags from the walk (GSEL_*), the same for every lane
//   c_edge    [2]  {last, first}: C is at its walk's last / first partial beam
//
// Bit growth and rounding: none (samples are passed, not computed).
// =============================================================================
module cube4_gra_walk
`include "cube4_gra_source_if.vh"

    localparam integer VW     = VOXEL_W;
    localparam integer PV     = P * VW;
    localparam integer META_W = GRA_META_W;

    `CUBE4_VIEW_FIELDS(cfg);

    // i0: the position of the next step, with its sample beat (an input
    // beat) or none (a step of GRA's own walk at the end of a frame)
    reg               i0_v, i0_in, i0_dead, i0_fend;
    reg [PV-1:0]      i0_sample;
    reg [HDR_W-1:0]   i0_hdr;
    reg [M_W-1:0]     i0_w;          // walk slice w = the centre's slice + 1
    reg [DIM_W-1:0]   i0_r;          // walk row r = the centre's row + 1
    reg [PB_W-1:0]    i0_pb;
    reg               i0_pg, i0_bg;  // the plane / beam words read for it are this walk's neighbours
    reg               i0_pgb;        // plane B's (the centre's row is a row: r > 0)
    reg [1:0]         i0_edge;
    reg [3:0]         i0_flags;      // {dk_f, dk_b, j_first, m_first} of the centre
    reg               i0_ylast;
    reg               i0_dyf, i0_dyb;
    wire [P-1:0]      i0_lane_valid = i0_hdr[HDR_LVALID +: P];
    assign step = i0_v && credit[GRA_STEPS-1];
    assign sop  = 1'b0;
    assign fend = i0_fend;
    wire i0_take = !i0_v || step;

    // the input's walks: the current one (wk) and the one before (pv)
    reg               wk_v, pv_ok;
    // the Y-steps of a walk's slice (every beat of a pass has its steps):
    // SY and OSY of wk, OSY of pv; a centre of slice w - 1 takes them from
    // these, not from its own header (which a centre outside the
    // rectangles does not have, and its neighbours need)
    reg               wk_sy, wk_osy, pv_osy;
    reg [M_W-1:0]     wk_m;
    reg [DIM_W-1:0]   wk_j0, wk_jl, pv_j0, pv_jl;
    reg [PB_W-1:0]    wk_pb0, wk_pbl, pv_pb0, pv_pbl;
    // GRA's own walk after a frame's last beat: the rows wk_j0 .. wk_jl + 1
    // (at most NJ) over wk's partial beams, then three trailing steps
    reg               gen_q, g_rows_done;
    reg [DIM_W-1:0]   g_r, g_j0;
    reg [PB_W-1:0]    g_pb;
    reg [1:0]         g_tail;

    wire [M_W-1:0]    in_m   = in_hdr[HDR_M +: M_W];
    wire [DIM_W-1:0]  in_j   = in_hdr[HDR_J +: DIM_W];
    wire [PB_W-1:0]   in_pb  = in_hdr[HDR_PB +: PB_W];
    wire              in_sop = in_hdr[HDR_CTRL + CTRL_SOP];
    wire              in_eop = in_hdr[HDR_CTRL + CTRL_EOP];
    wire              in_sy  = in_hdr[HDR_CTRL + CTRL_SY];
    wire              in_osy = in_hdr[HDR_CTRL + CTRL_OSY];
    assign in_ready = i0_take && !gen_q;
    wire ld_in  = i0_take && !gen_q && in_valid;
    wire ld_gen = i0_take && gen_q;
    wire ld     = ld_in || ld_gen;

    wire new_walk = in_sop || !wk_v || (in_m != wk_m);
    wire prev_ok  = new_walk ? (wk_v && !in_sop && (in_m == wk_m + 1'b1)) : pv_ok;
    wire [DIM_W-1:0] pj0  = new_walk ? wk_j0 : pv_j0;
    wire [DIM_W-1:0] pjl  = new_walk ? wk_jl : pv_jl;
    wire [PB_W-1:0]  ppb0 = new_walk ? wk_pb0 : pv_pb0;
    wire [PB_W-1:0]  ppbl = new_walk ? wk_pbl : pv_pbl;
    wire [DIM_W-1:0] g_last = (wk_jl >= cfg_nj) ? cfg_nj : wk_jl + 1'b1;
    wire             g_dead = g_rows_done;

    // the step being loaded: walk slice w, row r, partial beam pb
    wire [M_W-1:0]   ld_w  = gen_q ? wk_m + 1'b1 : in_m;
    wire [DIM_W-1:0] ld_r  = gen_q ? g_r : in_j;
    wire [PB_W-1:0]  ld_pb = gen_q ? g_pb : in_pb;
    wire ld_pg = gen_q ? (!g_dead && g_r >= wk_j0 && g_r <= wk_jl && g_pb >= wk_pb0 && g_pb <= wk_pbl)
                       : (prev_ok && in_j >= pj0 && in_j <= pjl && in_pb >= ppb0 && in_pb <= ppbl);
    wire ld_bg = gen_q ? (!g_dead && g_r != g_j0) : (!new_walk && in_j != wk_j0);
    wire ld_e0 = gen_q ? (g_pb == wk_pb0) : (new_walk || in_pb == wk_pb0);
    wire ld_e1 = gen_q ? (g_pb == wk_pbl) : (!new_walk && in_pb == wk_pbl);
    wire [M_W-1:0] ss_mask = M_W'((1 << cfg_ss_log2) - 1);
    wire [3:0] ld_flags = {(ld_w & ss_mask) == '0,                  // dk_f of centre slice w - 1
                           ((ld_w - 1'b1) & ss_mask) == '0,         // dk_b
                           ld_r == DIM_W'(1),                       // j_first (centre row 0)
                           ld_w == M_W'(1)};                        // m_first (centre slice 0)

    always @(posedge clk) begin
        if (rst) begin
            i0_v  <= 1'b0;
            gen_q <= 1'b0;
            wk_v  <= 1'b0;
            pv_ok <= 1'b0;
        end else begin
            if (ld)        i0_v <= 1'b1;
            else if (step) i0_v <= 1'b0;
            if (ld_in) begin
                if (new_walk) begin
                    wk_v   <= 1'b1;
                    wk_m   <= in_m;
                    wk_j0  <= in_j;
                    wk_jl  <= in_j;
                    wk_pb0 <= in_pb;
                    wk_pbl <= in_pb;
                    pv_ok  <= prev_ok;
                    pv_j0  <= wk_j0;
                    pv_jl  <= wk_jl;
                    pv_pb0 <= wk_pb0;
                    pv_pbl <= wk_pbl;
                    wk_sy  <= in_sy;
                    wk_osy <= in_osy;
                    pv_osy <= wk_osy;
                end else begin
                    wk_jl <= in_j;
                    if (in_pb > wk_pbl) wk_pbl <= in_pb;
                end
                if (in_eop) begin
                    gen_q       <= 1'b1;
                    g_rows_done <= 1'b0;
                    g_tail      <= 2'd0;
                    g_r         <= new_walk ? in_j : wk_j0;
                    g_j0        <= new_walk ? in_j : wk_j0;
                    g_pb        <= new_walk ? in_pb : wk_pb0;
                end
            end
            if (ld_gen) begin
                if (!g_rows_done) begin
                    if (g_pb == wk_pbl) begin
                        g_pb <= wk_pb0;
                        if (g_r == g_last) g_rows_done <= 1'b1;
                        else               g_r <= g_r + 1'b1;
                    end else begin
                        g_pb <= g_pb + 1'b1;
                    end
                end else begin
                    g_tail <= g_tail + 1'b1;
                    if (g_tail == 2'd2) begin
                        gen_q <= 1'b0;
                        wk_v  <= 1'b0;   // the frame is over
                    end
                end
            end
        end
    end
    always @(posedge clk) begin
        if (ld) begin
            i0_sample <= gen_q ? {PV{1'b0}} : in_sample;
            i0_hdr    <= gen_q ? {HDR_W{1'b0}} : in_hdr;
            i0_in     <= !gen_q;
            i0_dead   <= gen_q && g_dead;
            i0_fend   <= gen_q && g_dead && (g_tail == 2'd2);
            i0_w      <= ld_w;
            i0_r      <= ld_r;
            i0_pb     <= ld_pb;
            i0_pg     <= ld_pg;
            i0_pgb    <= ld_pg && (ld_r != '0);
            i0_bg     <= ld_bg;
            i0_edge   <= {ld_e1, ld_e0};
            i0_flags  <= ld_flags;
            i0_ylast  <= (ld_r == cfg_nj);
            i0_dyf    <= gen_q ? wk_sy : in_osy;                      // SY(w - 1) = OSY(w)
            i0_dyb    <= gen_q ? wk_osy : (new_walk ? wk_osy : pv_osy); // OSY(w - 1)
        end
    end

    wire [META_W-1:0] x_meta = {i0_in && (|i0_lane_valid), i0_hdr};

    // ---- position buffers (cube4_gra_pos): read when a step's position loads
    // into i0, written when it steps ----
    cube4_gra_pos #(`CUBE4_GRA_PASS) u_pos (
        .clk (clk), .ld ({GRA_POS_G{ld}}), .ld_r (ld_r), .ld_pb (ld_pb), .mv ({GRA_POS_G{1'b0}}),
        .step ({GRA_POS_G{step}}), .dead (i0_dead), .i0_w (i0_w), .i0_r (i0_r), .i0_pb (i0_pb),
        .row_ok ({i0_r != '0, i0_r < cfg_nj}),
        .in_beat (i0_in), .sample (i0_sample), .lane_valid (i0_lane_valid), .x (x), .x_meta (x_meta), .pg (i0_pg), .pgb (i0_pgb), .bg (i0_bg),
        .p1 (p1), .p2b1 (p2b1), .b1 (b1), .c_meta (c_meta), .c (c),
        .p1b2 (p1b2), .p2b2 (p2b2));
    assign c_sel  = {P{i0_flags, i0_ylast, i0_dyf, i0_dyb}};   // bits GSEL_DKF .. GSEL_DYB
    assign c_edge = i0_edge;
    wire unused_credit = ^credit[GRA_STEPS-2:0];   // (the lines' step nets)

    wire unused_eoss = in_eoss;   // (the beat schedule's: cube4_gra_beats)

endmodule
`default_nettype wire

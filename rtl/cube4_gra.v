`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_gra
// -----------------------------------------------------------------------------
// Purpose
//   The GRA units of all P pipelines (Teramac paper, section 5): central
//   differences on interpolated samples over three sample slices, with the
//   shear correction, exactly as docs/numerics.md section 5:
//     gi = s[m, j, i+1] - s[m, j, i-1]
//     gj = s[m, j+1, i] - s[m, j-1, i]
//     gr = s[m+1, j+dyf, i+dxf] - s[m-1, j-dyb, i-dxb]   (X/Y-step, old X/Y-step)
//     gk = S * gr - round_shift(VIEW_X * gi + VIEW_Y * gj, W)
//   with zero outside the volume (rows -1 and NJ, columns -1 and NI, slices -1
//   and M).
//
//   Plane and beam buffers (cube4_delay_line, in beats): the incoming sample
//   beat X = (m+1, j+1) meets B1 = (m+1, j), P1 = (m, j+1), C = (m, j),
//   P1b2 = (m, j-1), P2b1 = (m-1, j), P2b2 = (m-1, j-1). Their lane skews differ
//   from C's by the j step and (when the voxel slice changes) the k step, one
//   ring hop each (cube4_ring_shift); i +/- 1 come from the ring neighbours with
//   beam extension in both directions (the lane at t = P-1 takes the next beat,
//   the lane at t = 0 the previous one). The window is three registered beats
//   (c + 1, the centre c, c - 1), so a beat's gradient is computed in the step
//   that brings in beat c + 2. After the last beat of a frame GRA runs
//   NJ*NB + NB + 2 zero "flush" steps, the samples of slice M and beyond, to
//   finish the last slice; then it accepts the next frame.
//
//   Slice rectangles (RECTS = 1; docs/architecture.md "GRA", numerics.md
//   section 18): the beats arrive as the front end's walk (golden/cube4/slices.py
//   SliceRects.walk: each slice's rectangle and the rows and partial beams
//   needed to finish the slice before; beats with no lane valid carry no
//   sample). The delay lines become position buffers: plane A {row, pb} holds X
//   (its old word is P1 = (m, j+1)), plane B holds C at the centre's position
//   (old word P2b1 = (m-1, j)), and a beam buffer by pb holds X, P1, C, P2b1 of
//   the row before (B1, C, P1b2, P2b2). Each is read in the cycle a step's
//   position loads into the input register and written when it steps (a read
//   of the word written in that cycle takes the new word); a plane word counts
//   only where the previous walk covered the position, a beam word only after
//   the walk's first row, otherwise it is zero. After the frame's last beat GRA
//   walks the rest of the last slice itself (the rows of its walk and one more,
//   then three steps). Only beats with a lane valid leave; the last waits in a
//   register for the walk's end to carry EOP.
//
// Parameters
//   P, VOXEL_W, WEIGHT_W, MAX_DIM, MAX_SS_LOG2 as cube4_tri (derived widths too)
//   RECTS   1: slice rectangles (position buffers, above).  0..1.  Default 0.
//   GRAD_W  gradient width = VOXEL_W + 5 (derived; signed)
//
// Latency
//   A sample beat leaves NJ*NB + NB + 2 beats after it entered (the plane and
//   beam delays and the window), plus the input register, 4 register stages
//   (the differences; the multipliers' operand registers, fed from the
//   differences' flip-flops, not from their carry chains; the products; the
//   output FIFO's input register, IN_REG = 1: the two subtractions of gk end
//   at a flip-flop beside them, not at the FIFO's distributed memory) and
//   the FIFO's memory (cube4_credit_fifo, 16 entries), which stands in for a
//   fifth. The delay lines and the window move on GRA's step
//   (a beat is taken or a flush step runs), which needs a credit of the
//   output FIFO (an entry reserved for the gradient beat the step may
//   produce); the credit comes as seven flip-flop copies, one per group of
//   registers (each delay line, the window and counters), so that no single
//   net reaches every clock enable. The arithmetic after the window moves on
//   every cycle with valid bits (no clock enable); out_ready reaches only the
//   step and the FIFO's read pointers.
//
// Ports
//   in_*   the sample stream of cube4_tri (same fields and formats)
//   out_sample  [P*VOXEL_W]  the sample s[m, j, i] (unsigned, Q0.VOXEL_W)
//   out_gi/gj/gk [P*GRAD_W]  gradient per lane, signed integers, 2x the central
//                            differences in traversal axes (numerics.md 5)
//   out_hdr                  the sample beat's header, unchanged (cube4_defs.vh)
//   cfg                      view registers (cube4_defs.vh)
//
// Bit growth and rounding
//   gi, gj, gr: VOXEL_W + 1 bits signed, exact. VIEW_X * gi, VIEW_Y * gj:
//   W + VOXEL_W + 3 bits signed each (cube4_mul), exact; their sum rounded
//   by W (half up, the only rounding; folded into one subtraction, see
//   "arithmetic" below) gives VOXEL_W + 5 bits; |gk| < 2^(VOXEL_W+3) +
//   2^(VOXEL_W+1), so GRAD_W = VOXEL_W + 5 holds every result exactly. No
//   saturation.
// =============================================================================
module cube4_gra #(
    parameter integer P       = 8, parameter integer MAX_DIM     = 256,
    parameter integer VOXEL_W = 8, parameter integer MAX_SS_LOG2 = 0,
    parameter integer WEIGHT_W = 8, parameter integer RECTS       = 0,
    `CUBE4_GEOMETRY, `CUBE4_VIEW_LAYOUT,
    localparam integer GRAD_W = VOXEL_W + 5
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    // sample stream in
    input  wire in_valid,  output wire in_ready,  input  wire [HDR_W-1:0] in_hdr,
    input  wire [P*VOXEL_W-1:0] in_sample,
    // gradient stream out: the sample and its gradient (gi, gj, gk)
    output wire out_valid, input  wire out_ready, output wire [HDR_W-1:0] out_hdr,
    output wire [P*VOXEL_W-1:0] out_sample,
    output wire [P*GRAD_W-1:0]  out_gi, output wire [P*GRAD_W-1:0] out_gj, output wire [P*GRAD_W-1:0] out_gk
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_gra", "P", P, 1, 64)
        `CUBE4_RANGE(g_bad_voxel_w, "cube4_gra", "VOXEL_W", VOXEL_W, 1, 16)
        `CUBE4_RANGE(g_bad_rects, "cube4_gra", "RECTS", RECTS, 0, 1)
    endgenerate

    localparam integer VW     = VOXEL_W;
    localparam integer PV     = P * VW;
    localparam integer DW     = VW + 1;                     // differences, signed
    localparam integer META_W = 1 + HDR_W;                  // {real, header}
    localparam [LANE_W:0] PL  = P[LANE_W:0];

    `CUBE4_VIEW_FIELDS(cfg);
    `CUBE4_LANE_FUNCTIONS

    // ------------------------------------------------------------ stepping
    // The output FIFO's credit has NSTEP register copies (cube4_prim_copies),
    // so each group of registers (each delay line, the window and counters)
    // gets its own step net: no single net drives every clock enable of the
    // unit.
    localparam integer NSTEP = 7;    // 0..5 the delay lines, 6 window and counters
    localparam integer FIFO_DEPTH = 16;   // >= 6 cycles from a step to the FIFO's read (8 with RECTS)
    wire [NSTEP-1:0] en_rep;         // copies of the output FIFO's credit
    genvar q;

    // The source of the window: for the incoming centre c' = (m, j, pb) (the
    // step's beat X = (m + 1, j + 1, pb)), its neighbourhood and flags.
    wire              step;          // GRA steps: the source and the window move
    wire              sop;           // the step's beat starts a frame (delay lines)
    wire              fend;          // the step ends a frame (RECTS: the last centre may leave)
    wire [PV-1:0]     x_data, b1, p1, c_d, p1b2, p2b1, p2b2;
    wire [META_W-1:0] c_meta;        // {real, header} of c'
    // c's select flags, one copy per lane (each lane's row selects below take
    // their own copy: no single flag register drives the selects of all P
    // lanes): bits {dk_f, dk_b, j_first, m_first, y_last, dyf, dyb} of copy q =
    // the voxel slice changes m -> m+1 / m-1 -> m, c' is in row 0 / slice 0 /
    // row NJ - 1, the Y-step and old Y-step of c's slice
    localparam integer NSEL = 7;
    wire [P*NSEL-1:0] sel_c;
    wire [1:0]        c_edge;        // {last, first}: c' is at its walk's last / first partial beam (RECTS)

    generate
        if (RECTS == 0) begin : g_lines
            wire             flush_q;        // running the zero steps after a frame (its last copy)
            wire [NSTEP-1:0] flush_rep;      // copies of flush_q
            wire [NSTEP-1:0] sop_cp;         // copies of i0's frame-start bit, one per step net
            reg  [DIM_W:0]   f_row_q;        // flush: beam 0 .. NJ, then two beats (row NJ + 1)
            reg  [PB_W-1:0]  f_pb_q;
            reg              f_tail_q;       // the previous flush step was in row NJ + 1
            reg  [DIM_W:0]   nj_p1_q;        // NJ + 1

            // ------------------------------------------------------------ input register
            // The incoming beat is registered (i0) before anything uses it: a stream
            // register, loaded whenever it is empty or its beat is taken by a step, so
            // it passes one beat per cycle. in_ready depends on registers only.
            reg               i0_v;
            reg [P*VOXEL_W-1:0] i0_sample;
            reg [HDR_W-1:0]   i0_hdr;
            wire [P-1:0]      i0_lane_valid = i0_hdr[HDR_LVALID +: P];
            wire i0_take = !i0_v || (en_rep[6] && !flush_rep[6]);   // i0 is free, or its beat steps now
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
            // i0's SOP bit again, one kept copy per step net (a delay line's
            // clear reaches its write-address copies and its output groups
            // from a flip-flop of its own, not from the one header bit)
            for (q = 0; q < NSTEP; q = q + 1) begin : g_sop
                reg sop_q;
                (* keep *)
                always @(posedge clk) begin
                    if (i0_take) sop_q <= in_hdr[HDR_CTRL + CTRL_SOP];
                end
                assign sop_cp[q] = sop_q;
            end

            wire [NSTEP-1:0] step_rep = en_rep[NSTEP-1:0] & (flush_rep | {NSTEP{i0_v}});
            wire [NSTEP-1:0] sop_rep  = ~flush_rep & sop_cp;   // frame start, per copy
            assign step = step_rep[6];

            wire real_beat = !flush_q;
            assign sop     = sop_rep[6];
            wire eop       = real_beat && i0_hdr[HDR_CTRL + CTRL_EOP];

            // position counters of the delay lines (beat index within a beam / slice);
            // lb_q / ls_q: the position in pb_q / row_q is the last beam / the last
            // beat of a slice (kept with the counters, so that the delay lines' last
            // inputs are a multiplexer on registers)
            reg  [PB_W-1:0]  pb_q;
            reg  [DIM_W-1:0] row_q;
            reg              lb_q, ls_q;
            reg              nb1_q, nj1_q;   // NB = 1, NJ = 1
            // "keep": GRA's own (synthesis would share one flip-flop with COM's
            // copies of the same compare, placed among COM's hundreds of loads)
            (* keep *)
            always @(posedge clk) begin
                nb1_q   <= (cfg_nb == NB_W'(1));
                nj1_q   <= (cfg_nj == DIM_W'(1));
                nj_p1_q <= {1'b0, cfg_nj} + 1'b1;
            end
            wire [PB_W-1:0]  pos_pb  = sop ? {PB_W{1'b0}} : pb_q;
            wire [DIM_W-1:0] pos_row = sop ? {DIM_W{1'b0}} : row_q;
            wire last_beam  = sop ? nb1_q : lb_q;
            wire last_slice = sop ? (nb1_q && nj1_q) : ls_q;
            wire [PB_W-1:0]  pb_n  = last_beam ? {PB_W{1'b0}} : pos_pb + 1'b1;
            wire [DIM_W-1:0] row_n = !last_beam ? pos_row : (last_slice ? {DIM_W{1'b0}} : pos_row + 1'b1);
            wire             lb_n  = (NB_W'(pb_n) == cfg_nb - 1'b1);

            // flush_q and its copies. Each copy computes its own next value from
            // its own value and its own credit copy (with i0_v, i0's EOP bit and
            // f_tail_q): no step net and no shared next value lies between one
            // copy and the others. All copies hold the same value, so each
            // copy's next value is
            //   flush:  step ? !f_tail_q : 1   (ends after the second step of row NJ + 1)
            //   else:   step && eop            (a frame's last beat steps)
            // with this copy's step = en && (flush || i0_v), eop = EOP && !flush.
            wire [NSTEP:0] fl_en = {en_rep[6], en_rep};      // the credit copy of each flush copy
            wire [NSTEP:0] fl_q;                             // {flush_q, flush_rep}
            wire           i0_eop = i0_hdr[HDR_CTRL + CTRL_EOP];
            for (q = 0; q <= NSTEP; q = q + 1) begin : g_flush
                wire st = fl_en[q] && (fl_q[q] || i0_v);
                wire d  = fl_q[q] ? (!st || !f_tail_q) : (st && i0_eop);
                cube4_prim_copies #(.N(1), .RESET(1)) u_copy (
                    .clk(clk), .rst(rst), .d(d), .q(fl_q[q]));
            end
            assign {flush_q, flush_rep} = fl_q;

            always @(posedge clk) begin
                if (rst) begin
                    pb_q    <= {PB_W{1'b0}};
                    row_q   <= {DIM_W{1'b0}};
                    lb_q    <= 1'b0;
                    ls_q    <= 1'b0;
                    f_row_q <= {(DIM_W + 1){1'b0}};
                    f_pb_q  <= {PB_W{1'b0}};
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
            for (q = 0; q < P; q = q + 1) begin : g_mask
                assign x_data[q*VW +: VW] = (real_beat && i0_lane_valid[q]) ? i0_sample[q*VW +: VW] : {VW{1'b0}};
            end
            wire [META_W-1:0] x_meta = {real_beat, i0_hdr};

            wire [META_W-1:0]    p1_meta;
            wire [3:0]           p1_flags;   // {dk_f, dk_b, j_first, m_first} of the beat

            // period of each delay line: NB (beam) and NJ*NB (plane), constant in a frame
            localparam integer BL_W = ((NBMAX > 1) ? $clog2(NBMAX) : 1) + 1;
            localparam integer PL_W = ((MAX_DIM * NBMAX > 1) ? $clog2(MAX_DIM * NBMAX) : 1) + 1;
            wire [BL_W-1:0] beam_len = BL_W'(cfg_nb);
            reg  [PL_W-1:0] plane_len;
            always @(posedge clk) begin
                plane_len <= PL_W'(PL_W'(cfg_nj) * PL_W'(cfg_nb));
            end
            cube4_delay_line #(.DATA_W(PV), .DEPTH(NBMAX)) u_x_b1 (
                .clk(clk), .rst(rst), .clear(sop_rep[0]), .step(step_rep[0]), .last(last_beam), .len(beam_len),
                .din(x_data), .dout(b1));
            cube4_delay_line #(.DATA_W(META_W + PV), .DEPTH(MAX_DIM * NBMAX)) u_x_p1 (
                .clk(clk), .rst(rst), .clear(sop_rep[1]), .step(step_rep[1]), .last(last_slice), .len(plane_len),
                .din({x_meta, x_data}), .dout({p1_meta, p1}));
            // The centre's slice and row flags are computed from the beat one beam
            // earlier (p1, a register) and travel with it, so they are registers at c.
            wire [M_W-1:0]    p1_m    = p1_meta[HDR_M +: M_W];
            wire [DIM_W-1:0]  p1_j    = p1_meta[HDR_J +: DIM_W];
            wire [M_W-1:0]    ss_mask = M_W'((1 << cfg_ss_log2) - 1);
            assign p1_flags = {((p1_m + 1'b1) & ss_mask) == '0,   // dk_f: voxel slice changes m -> m+1
                               (p1_m & ss_mask) == '0,            // dk_b: voxel slice changes m-1 -> m
                               p1_j == '0,                        // j_first
                               p1_m == '0};                       // m_first
            // (the P copies of the flags are words of their own in the line: each
            // copy's output register is its own)
            wire [NSEL-1:0] p1_sel = {p1_flags, p1_meta[HDR_CTRL + CTRL_YLAST],
                                      p1_meta[HDR_CTRL + CTRL_SY], p1_meta[HDR_CTRL + CTRL_OSY]};
            cube4_delay_line #(.DATA_W(P * NSEL + META_W + PV), .DEPTH(NBMAX)) u_p1_c (
                .clk(clk), .rst(rst), .clear(sop_rep[2]), .step(step_rep[2]), .last(last_beam), .len(beam_len),
                .din({{P{p1_sel}}, p1_meta, p1}), .dout({sel_c, c_meta, c_d}));
            cube4_delay_line #(.DATA_W(PV), .DEPTH(NBMAX)) u_c_p1b2 (
                .clk(clk), .rst(rst), .clear(sop_rep[3]), .step(step_rep[3]), .last(last_beam), .len(beam_len),
                .din(c_d), .dout(p1b2));
            cube4_delay_line #(.DATA_W(PV), .DEPTH(MAX_DIM * NBMAX)) u_c_p2b1 (
                .clk(clk), .rst(rst), .clear(sop_rep[4]), .step(step_rep[4]), .last(last_slice), .len(plane_len),
                .din(c_d), .dout(p2b1));
            cube4_delay_line #(.DATA_W(PV), .DEPTH(NBMAX)) u_p2b1_p2b2 (
                .clk(clk), .rst(rst), .clear(sop_rep[5]), .step(step_rep[5]), .last(last_beam), .len(beam_len),
                .din(p2b1), .dout(p2b2));

            assign c_edge = 2'b00;                            // i - 1 and i + 1 lie in the frame's beams
            assign fend   = 1'b0;

        end else begin : g_walk
            // ---- slice rectangles: GRA's walk and position buffers (header) ----
            localparam integer RW  = (MAX_DIM > 1) ? $clog2(MAX_DIM) : 1;   // row bits of a plane address
            localparam integer PAW = RW + PB_W;                            // plane address {row, pb}
            localparam integer AWD = META_W + PV;                          // plane A: X with its meta
            localparam integer BMW = 4 * PV + META_W;                      // beam: X, P1 (meta), C, P2b1
            localparam integer PBN = 1 << PB_W;                            // beam buffer entries

            // i0: the position of the next step, with its sample beat (an input
            // beat) or none (a step of GRA's own walk at the end of a frame)
            reg               i0_v, i0_in, i0_dead, i0_fend;
            reg [PV-1:0]      i0_sample;
            reg [HDR_W-1:0]   i0_hdr;
            reg [DIM_W-1:0]   i0_r;          // walk row r = the centre's row + 1
            reg [PB_W-1:0]    i0_pb;
            reg               i0_pg, i0_bg;  // the plane / beam words read for it are this walk's neighbours
            reg               i0_pgb;        // plane B's (the centre's row is a row: r > 0)
            reg [1:0]         i0_edge;
            reg [3:0]         i0_flags;      // {dk_f, dk_b, j_first, m_first} of the centre
            reg               i0_ylast;
            reg               i0_dyf, i0_dyb;
            wire [P-1:0]      i0_lane_valid = i0_hdr[HDR_LVALID +: P];
            wire [META_W-1:0] p1_meta;       // P1's {real, header} (gated)
            assign step = i0_v && en_rep[6];
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

            for (q = 0; q < P; q = q + 1) begin : g_mask
                assign x_data[q*VW +: VW] = (i0_in && i0_lane_valid[q]) ? i0_sample[q*VW +: VW] : {VW{1'b0}};
            end
            wire [META_W-1:0] x_meta = {i0_in && (|i0_lane_valid), i0_hdr};

            // ---- position buffers: read when a step's position loads into i0
            // (a block RAM's registered read), written when it steps; a read of
            // the word written in the same cycle takes the new word (bypass) ----
            wire [RW-1:0]    ld_r1 = ld_r[RW-1:0] - 1'b1;   // the centre's row (plane B)
            wire [RW-1:0]    i0_r1 = i0_r[RW-1:0] - 1'b1;
            wire [PAW-1:0]   ra_a = {ld_r[RW-1:0], ld_pb}, wa_a = {i0_r[RW-1:0], i0_pb};
            wire [PAW-1:0]   ra_b = {ld_r1, ld_pb},        wa_b = {i0_r1, i0_pb};
            wire we_a = step && !i0_dead && (i0_r < cfg_nj);   // plane A: X at its own position
            wire we_b = step && !i0_dead && (i0_r != '0);      // plane B: C at the centre's position
            wire we_m = step && !i0_dead;                      // beam buffer
            wire [AWD-1:0] wd_a = {x_meta, x_data};
            wire [PV-1:0]  wd_b = c_d;
            wire [BMW-1:0] wd_m = {x_data, p1_meta, p1, c_d, p2b1};
            wire [AWD-1:0] rd_a;
            wire [PV-1:0]  rd_b;
            wire [BMW-1:0] rd_m;
            cube4_sdp_ram #(.DATA_W (AWD), .DEPTH (1 << PAW)) u_plane_a (
                .clk (clk), .rd_en (ld), .rd_addr (ra_a), .rd_data (rd_a),
                .wr_en (we_a), .wr_addr (wa_a), .wr_data (wd_a));
            cube4_sdp_ram #(.DATA_W (PV), .DEPTH (1 << PAW)) u_plane_b (
                .clk (clk), .rd_en (ld), .rd_addr (ra_b), .rd_data (rd_b),
                .wr_en (we_b), .wr_addr (wa_b), .wr_data (wd_b));
            cube4_sdp_ram #(.DATA_W (BMW), .DEPTH (PBN)) u_beam (
                .clk (clk), .rd_en (ld), .rd_addr (ld_pb), .rd_data (rd_m),
                .wr_en (we_m), .wr_addr (i0_pb), .wr_data (wd_m));
            reg            by_a, by_b, by_m;
            reg [AWD-1:0]  bd_a;
            reg [PV-1:0]   bd_b;
            reg [BMW-1:0]  bd_m;
            always @(posedge clk) begin
                if (ld) begin
                    by_a <= we_a && (wa_a == ra_a);
                    by_b <= we_b && (wa_b == ra_b);
                    by_m <= we_m && (i0_pb == ld_pb);
                    bd_a <= wd_a;
                    bd_b <= wd_b;
                    bd_m <= wd_m;
                end
            end
            wire [AWD-1:0] a_w = by_a ? bd_a : rd_a;
            wire [PV-1:0]  b_w = by_b ? bd_b : rd_b;
            wire [BMW-1:0] m_w = by_m ? bd_m : rd_m;
            assign p1_meta = i0_pg ? a_w[PV +: META_W] : {META_W{1'b0}};
            assign p1   = i0_pg ? a_w[PV-1:0] : {PV{1'b0}};
            assign p2b1 = i0_pgb ? b_w : {PV{1'b0}};
            assign b1     = i0_bg ? m_w[3*PV + META_W +: PV] : {PV{1'b0}};
            assign c_meta = i0_bg ? m_w[3*PV +: META_W] : {META_W{1'b0}};
            assign c_d    = i0_bg ? m_w[2*PV +: PV] : {PV{1'b0}};
            assign p1b2   = i0_bg ? m_w[PV +: PV] : {PV{1'b0}};
            assign p2b2   = i0_bg ? m_w[0 +: PV] : {PV{1'b0}};
            assign sel_c = {P{i0_flags, i0_ylast, i0_dyf, i0_dyb}};
            assign c_edge = i0_edge;
            wire unused_walk = ^{en_rep[5:0]};
        end
    endgenerate


    // ------------------------------------------------------------ alignment hops
    // source skew - centre skew: P1 +s_j, P1b2 -s_j, X +s_j (+s_k), B1 (+s_k),
    // P2b1 (-s_k), P2b2 -s_j (-s_k); a +1 difference means y[q] = x[q + 1].
    wire [PV-1:0] p1_a, p1b2_a, x_j, p2b2_j;
    wire [PV-1:0] x_jk, b1_k, p2b1_k, p2b2_jk;
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_al_p1   (.down(!cfg_flip_j), .x(p1),     .y(p1_a));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_al_p1b2 (.down(cfg_flip_j),  .x(p1b2),   .y(p1b2_a));
    cube4_ring_shift #(.P(P), .DATA_W(VW)) u_al_xj   (.down(!cfg_flip_j), .x(x_data), .y(x_j));
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
            wire dk_f, dk_b, j_first, m_first, y_last, c_dyf, c_dyb;
            assign {dk_f, dk_b, j_first, m_first, y_last, c_dyf, c_dyb} = sel_c[q*NSEL +: NSEL];
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
    wire              c_live = (RECTS != 0) || c_sop || live_q;   // (RECTS: the walk gates stale words)
    reg [META_W-1:0]  h1_meta, h2_meta;
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
            h2_meta <= h1_meta;
            h1_c    <= c_d;
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
    // With i = pb * P + t and NB = ceil(NI / P): i + 1 < NI holds in every
    // partial beam but the last, and in the last where t < r = NI - 1 - (NB - 1) * P
    // (0 <= r < P, exact modulo 2^LANE_W); i > 0 where pb > 0 or t > 0. So the
    // flags are compares of h1's fields with registered view constants, with
    // no sum of the position on the path.
    wire [PB_W-1:0]   h1_pb   = h1_meta[HDR_PB +: PB_W];
    wire [LANE_W-1:0] h1_skew = h1_meta[HDR_SKEW +: LANE_W];
    reg  [NB_W-1:0]   nbm1_q;             // NB - 1
    reg  [LANE_W-1:0] ni_r_q;             // r: the last partial beam's last lane position
    always @(posedge clk) begin
        nbm1_q <= cfg_nb - 1'b1;
        ni_r_q <= LANE_W'(IW'(cfg_ni) + IW'(P - 1) - IW'(cfg_nb) * IW'(P));
    end
    wire              h1_pb_last = (NB_W'(h1_pb) == nbm1_q);
    wire              h1_pb_zero = (h1_pb == '0);
    wire [P-1:0]      hi_ok_d, lo_ok_d, hi_new_d, lo_old_d;
    reg  [1:0]        h1_edge;            // {last, first} partial beam of the walk (c_edge)
    generate
        for (q = 0; q < P; q = q + 1) begin : g_pos
            wire [LANE_W-1:0] t = lane_pos(q, h1_skew, cfg_flip_i, cfg_i_r1);
            assign hi_ok_d[q]  = !h1_pb_last || (t < ni_r_q);
            assign lo_ok_d[q]  = !h1_pb_zero || (t != '0);
            assign hi_new_d[q] = ({1'b0, t} == PL - 1'b1);   // i + 1 is in the next beat
            assign lo_old_d[q] = (t == '0);                  // i - 1 is in the previous beat
        end
    endgenerate
    always @(posedge clk) begin
        if (step) begin
            h1_edge   <= c_edge;
        end
    end
    localparam integer CSEL_W = 4 * P;    // {lo_same, lo_old, hi_same, hi_new} per lane
    localparam integer RSEL_W = 6 * P;    // {b_self, b_same, b_old, f_self, f_same, f_new} per lane
    wire              h1_dxf = h1_meta[HDR_CTRL + CTRL_SX];    // X-step of slice m (h1's)
    wire              h1_dxb = h1_meta[HDR_CTRL + CTRL_OSX];   // old X-step
    wire [P-1:0]      hi_okx = hi_ok_d & ~(hi_new_d & {P{h1_edge[1]}});
    wire [P-1:0]      lo_okx = lo_ok_d & ~(lo_old_d & {P{h1_edge[0]}});
    wire [P-1:0]      hi_n = hi_okx & hi_new_d, hi_s = hi_okx & ~hi_new_d;
    wire [P-1:0]      lo_o = lo_okx & lo_old_d, lo_s = lo_okx & ~lo_old_d;
    wire [CSEL_W-1:0] csel_d = {lo_s, lo_o, hi_s, hi_n};
    wire [RSEL_W-1:0] rsel_d = {{P{!h1_dxb}}, lo_s & {P{h1_dxb}}, lo_o & {P{h1_dxb}},
                                {P{!h1_dxf}}, hi_s & {P{h1_dxf}}, hi_n & {P{h1_dxf}}};
    wire [CSEL_W-1:0] csel_q;             // the centre's row
    wire [RSEL_W-1:0] rsel_q;             // the forward and backward rows
    cube4_prim_copies #(.N(1), .W(CSEL_W), .RESET(0)) u_csel (
        .clk(clk), .rst(rst), .d(step ? csel_d : csel_q), .q(csel_q));
    cube4_prim_copies #(.N(1), .W(RSEL_W), .RESET(0)) u_rsel (
        .clk(clk), .rst(rst), .d(step ? rsel_d : rsel_q), .q(rsel_q));

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

    wire [P*DW-1:0] gi_d, gr_d;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_win
            // beyond the walk's partial beams the neighbours are zero (outside the rectangles)
            // centre row: [0] i+1 from the next beat, [1] from this one, [2] i-1
            // from the previous beat, [3] from this one; forward row i + dxf:
            // [0] from the next beat, [1] this beat's neighbour, [2] the lane;
            // backward row i - dxb: [3] from the previous beat, [4] this
            // beat's neighbour, [5] the lane (all 0: zero)
            wire [3:0] sc = {csel_q[3*P + q], csel_q[2*P + q], csel_q[P + q], csel_q[q]};
            wire [5:0] sr = {rsel_q[5*P + q], rsel_q[4*P + q], rsel_q[3*P + q],
                             rsel_q[2*P + q], rsel_q[P + q], rsel_q[q]};
            wire [VW-1:0] c_hi = ({VW{sc[0]}} & c_next_new[q*VW +: VW]) | ({VW{sc[1]}} & c_next_same[q*VW +: VW]);
            wire [VW-1:0] c_lo = ({VW{sc[2]}} & c_prev_old[q*VW +: VW]) | ({VW{sc[3]}} & c_prev_same[q*VW +: VW]);
            wire [VW-1:0] fwd  = ({VW{sr[0]}} & f_next_new[q*VW +: VW]) | ({VW{sr[1]}} & f_next_same[q*VW +: VW])
                               | ({VW{sr[2]}} & h2_f[q*VW +: VW]);                        // i + dxf
            wire [VW-1:0] back = ({VW{sr[3]}} & b_prev_old[q*VW +: VW]) | ({VW{sr[4]}} & b_prev_same[q*VW +: VW])
                               | ({VW{sr[5]}} & h2_b[q*VW +: VW]);                        // i - dxb
            assign gi_d[q*DW +: DW] = $signed({1'b0, c_hi}) - $signed({1'b0, c_lo});
            assign gr_d[q*DW +: DW] = $signed({1'b0, fwd}) - $signed({1'b0, back});
        end
    endgenerate

    // ------------------------------------------------------------ arithmetic
    // g1: differences (the carry chains end at g1's flip-flops); g2, g3:
    // VIEW_X*gi and VIEW_Y*gj, each a cube4_mul whose operand registers are
    // g2's (they take g1_gi and g1_gj) and whose product register is g3's,
    // so that the route from the fabric to the multiplier's pins starts at
    // a flip-flop (the 9-bit difference's sign drove ten operand pins);
    // g4: gk, in the output FIFO's input register (IN_REG = 1), then its
    // memory.
    // g1 .. g3 load on every cycle; g1_v marks a step whose centre is a real
    // beat (the take of its FIFO entry).
    //   gk = (gr << ss) - round_shift(VIEW_X*gi + VIEW_Y*gj, WEIGHT_W) is formed
    //   as floor((G' - VIEW_X*gi - VIEW_Y*gj) / 2^WEIGHT_W) with
    //   G' = (gr << ss) * 2^WEIGHT_W + 2^(WEIGHT_W-1) - 1 (registered at g3;
    //   its low bits are the constant, so no adder): the same integer, since
    //   c - floor((x + h) / 2^W) = floor((c * 2^W - x - h + 2^W - 1) / 2^W).
    //   Two subtractions in g4, as the rounding add and subtraction were.
    //   Formed modulo 2^(GRAD_W + WEIGHT_W); the top GRAD_W bits are gk
    //   modulo 2^GRAD_W, as before (gk fits GRAD_W bits: nothing wraps).
    localparam integer MB_W  = WEIGHT_W + 2;                // a view weight (0 .. 2^W), signed
    localparam integer MP_W  = DW + MB_W;                   // a product
    localparam integer GX_W  = GRAD_W + WEIGHT_W;           // G' and the difference
    localparam [WEIGHT_W-1:0] GK_LOW = WEIGHT_W'((1 << (WEIGHT_W - 1)) - 1);
    reg               g1_v, g2_v, g3_v;
    reg [META_W-2:0]  g1_meta, g2_meta, g3_meta;
    reg [PV-1:0]      g1_s, g2_s, g3_s;
    reg [P*DW-1:0]    g1_gi, g1_gj, g1_gr, g2_gi, g2_gj, g2_gr, g3_gi, g3_gj;
    reg [P*GX_W-1:0]  g3_gpre;
    wire              take = step && h2_v && h_real;

    always @(posedge clk) begin
        if (rst) begin
            g1_v <= 1'b0;
            g2_v <= 1'b0;
            g3_v <= 1'b0;
        end else begin
            g1_v <= take;
            g2_v <= g1_v;
            g3_v <= g2_v;
        end
    end

    wire [P*GX_W-1:0]   gpre_d;
    wire [P*GRAD_W-1:0] gk_d, gi_x, gj_x;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_arith
            wire signed [MP_W-1:0] px, py;     // at g3: VIEW_X * gi, VIEW_Y * gj
            wire signed [DW-1:0]   gi_a = g1_gi[q*DW +: DW];
            wire signed [DW-1:0]   gj_a = g1_gj[q*DW +: DW];
            wire signed [MB_W-1:0] vx_b = {1'b0, cfg_view_x};
            wire signed [MB_W-1:0] vy_b = {1'b0, cfg_view_y};
            cube4_mul #(.A_W(DW), .B_W(MB_W)) u_px (
                .clk (clk), .en (1'b1), .a (gi_a), .b (vx_b), .p (px));
            cube4_mul #(.A_W(DW), .B_W(MB_W)) u_py (
                .clk (clk), .en (1'b1), .a (gj_a), .b (vy_b), .p (py));
            // g2 -> g3: G' (a shift and a constant)
            wire signed [DW-1:0]     gr1  = g2_gr[q*DW +: DW];
            wire signed [GRAD_W-1:0] gr_e = {{(GRAD_W - DW){gr1[DW-1]}}, gr1};
            wire signed [GRAD_W-1:0] gr_s = gr_e <<< cfg_ss_log2;
            assign gpre_d[q*GX_W +: GX_W] = {gr_s, GK_LOW};
            // g4: gk
            wire signed [GX_W-1:0] px_e = GX_W'(px);
            wire signed [GX_W-1:0] py_e = GX_W'(py);
            wire signed [GX_W-1:0] dif  = $signed(g3_gpre[q*GX_W +: GX_W]) - px_e - py_e;
            assign gk_d[q*GRAD_W +: GRAD_W] = dif[GX_W-1 -: GRAD_W];
            wire unused_dif = ^dif[WEIGHT_W-1:0];   // the fraction the floor drops
            wire signed [DW-1:0] gi2 = g3_gi[q*DW +: DW];
            wire signed [DW-1:0] gj2 = g3_gj[q*DW +: DW];
            assign gi_x[q*GRAD_W +: GRAD_W] = {{(GRAD_W - DW){gi2[DW-1]}}, gi2};
            assign gj_x[q*GRAD_W +: GRAD_W] = {{(GRAD_W - DW){gj2[DW-1]}}, gj2};
        end
    endgenerate

    always @(posedge clk) begin
        g1_meta <= h2_meta[META_W-2:0];
        g1_s    <= h2_c;
        g1_gi   <= gi_d;
        g1_gj   <= h2_gj;
        g1_gr   <= gr_d;
        g2_meta <= g1_meta;
        g2_s    <= g1_s;
        g2_gi   <= g1_gi;
        g2_gj   <= g1_gj;
        g2_gr   <= g1_gr;
        g3_meta <= g2_meta;
        g3_s    <= g2_s;
        g3_gi   <= g2_gi;
        g3_gj   <= g2_gj;
        g3_gpre <= gpre_d;
    end

    // ---- g4: the output FIFO's input register, then its memory; g2 holds a
    // beat: push at g4 (the FIFO stores it one cycle later) ----
    localparam integer OUT_W = META_W - 1 + PV + 3 * P * GRAD_W;
    localparam integer EOP_BIT = OUT_W - HDR_W + HDR_CTRL + CTRL_EOP;   // the header's EOP in an item
    wire [OUT_W-1:0] fifo_out;
    wire [OUT_W-1:0] item = {g3_meta, g3_s, gi_x, gj_x, gk_d};   // g3 holds a beat when g3_v
    wire unused_credit;                 // (en_rep: the step nets' own copies)
    wire credit_d;
    wire push_d;
    wire [OUT_W-1:0] fifo_in;
    generate
        if (RECTS == 0) begin : g_push
            assign push_d  = g2_v;
            assign fifo_in = item;
            wire unused_g = ^{g3_v, fend};   // the FIFO's push copies are its copies
        end else begin : g_hold
            // The frame's last beat is known only when GRA's walk ends (the input's
            // last beat may be one outside the rectangles): each beat waits in
            // hold_q until the next one comes (then it is pushed) or the frame
            // ends (then it is pushed with EOP). push_d says so one cycle before
            // g4_q holds the beat, which the FIFO stores.
            reg               g1_end, g2_end, g3_end, hold_v;
            reg [OUT_W-1:0]   hold_q, g4_q;
            always @(posedge clk) begin
                if (rst) begin
                    g1_end <= 1'b0;
                    g2_end <= 1'b0;
                    g3_end <= 1'b0;
                    hold_v <= 1'b0;
                end else begin
                    g1_end <= step && fend;
                    g2_end <= g1_end;
                    g3_end <= g2_end;
                    if (g3_v)        hold_v <= 1'b1;
                    else if (g3_end) hold_v <= 1'b0;
                end
            end
            always @(posedge clk) begin
                if (g3_v) begin
                    hold_q          <= item;
                    hold_q[EOP_BIT] <= 1'b0;
                end
                if (g3_v || g3_end) begin
                    g4_q          <= hold_q;
                    g4_q[EOP_BIT] <= g3_end;
                end
            end
            assign push_d  = (g3_v || g3_end) && hold_v;
            assign fifo_in = g4_q;
        end
    endgenerate
    cube4_prim_copies #(.N(NSTEP), .RST_VAL(64'd1)) u_credit (
        .clk(clk), .rst(rst), .d(credit_d), .q(en_rep));
    cube4_credit_fifo #(.DATA_W(OUT_W), .DEPTH(FIFO_DEPTH), .IN_REG(1)) u_fifo (
        .clk(clk), .rst(rst), .take(take), .give(1'b0),
        .credit(unused_credit), .credit_d(credit_d),
        .push_d(push_d), .in_data(fifo_in),
        .out_valid(out_valid), .out_ready(out_ready), .out_data(fifo_out));
    assign {out_hdr, out_sample, out_gi, out_gj, out_gk} = fifo_out;

endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_gra_beats
// -----------------------------------------------------------------------------
// Purpose
//   GRA's neighbourhood source on the beat schedule (BEATS = 1; numerics.md
//   section 19, docs/architecture.md "Beat skipping and ray termination"),
//   with the interface of cube4_gra_lines. The input is the front end's
//   sample beats: every beat it emits, in order of slice, row and partial
//   beam (lanes valid where the beat runs, none elsewhere), each of them a
//   centre that leaves GRA once, in the same order, with its header. Samples
//   of beats that do not come, or come with no lane valid, are zero.
//
//   A step at position (w, r, pb) brings X = (w, r, pb) and the centre
//   C = (w - 1, r - 1, pb) with the six neighbours of cube4_gra_lines, from
//   position buffers: plane A {r, pb} holds X of the step at (w - 1, r, pb)
//   (P1 = (w - 1, r)), plane B {r - 1, pb} its C (P2b1 = (w - 2, r - 1)),
//   the beam buffer {pb} X, P1, C, P2b1 of the step at (w, r - 1, pb) (B1,
//   C, P1b2, P2b2). The steps of slice w, row by row (r = 0 .. NJ) and rising
//   partial beams within a row, are the input beats of (w, r) merged with
//   the steps that the centres of slice w - 1 need:
//     G(w, r) = C(w - 1, r - 1) | C(w - 1, r)
//   (C(w, r): the input beats of row r of slice w; a centre's X-step and the
//   step of its row that fills the beam buffer). The window reads the beats
//   beside a centre for i +/- 1: the walk emits the partial beams beside
//   every running beat (numerics.md section 19: the footprint's pb + 1, the
//   cover's pb - 1), so they are centres too, and beyond a gap in a row's
//   steps the window takes zero (c_edge). Every
//   sample that is not zero came in, and is a centre, so each word a centre
//   reads was written by a step of this frame: a plane word counts where
//   the step at (w - 1, r, pb) ran (S(w - 1, r), the stepped bits), a beam
//   word where the step at (w, r - 1, pb) ran, otherwise it is zero.
//   C and S of each row are written, one word per row, into a table of two
//   slices (slice mod 2) as the row ends, and read one row ahead (row NJ,
//   which has no input and whose S does not fit the table, in a register
//   per slice). A row ends when its steps are loaded and the input has
//   passed it: a beat of a later row has come, or the last beat of its
//   slice (in_eoss) or of the frame (EOP) has been loaded. Each slice's
//   rows end with two steps that only move the window, so that the slice's
//   last centres leave without waiting for the next slice's beats (the
//   decisions wait for COM's reports of them: numerics.md section 19, lag).
//   After the frame's last beat the source steps the rest: the rows of the
//   last slice and of slice M, each with its two window steps.
//
// Parameters
//   P, VOXEL_W, WEIGHT_W, MAX_DIM, MAX_SS_LOG2 as cube4_gra (derived widths:
//   cube4_defs.vh CUBE4_GEOMETRY, CUBE4_GRA_LAYOUT). Any S: the steps run
//   over sample slices; where S > 1 the window's k neighbours are chosen by
//   whether a voxel slice lies between (dk_f, dk_b, as cube4_gra_walk).
//
// Latency
//   An input beat passes a skid buffer (cube4_gra_beats_in: one cycle;
//   in_ready is its register; the head's place against the row, its slice
//   against the row's, its slice and partial beam, and its EOSS, EOP, SY
//   and OSY bits come with it, in registers of a head slot, not behind a
//   read pointer; its sample and header wait in a queue of their own that
//   pops as i0 moves on to ia), so the choice of the next step
//   and the slice flags w_in and w_last start at registers; the
//   choice computes what each candidate position decides (its plane and beam
//   words' bits, its gap, the row bits it passes) beside the choice itself.
//   The input register i0 holds the next step's position with its sample
//   beat (an input beat) or none (a step the centres need, or a trailing
//   step); it moves on to ia when ia is free or moves on, and ia to i1 when
//   i1 is free or moves on: that move reads the position buffers at ia's
//   position (from registers; i0's lie beside the choice, ia's beside the
//   buffers, so no route from the choice runs to the buffers' addresses
//   across the die). i1 moves
//   on to i2 when i2 is free or steps, and the words read for it load into
//   registers with it (cube4_gra_pos OUT_STAGE = 1: the block RAMs'
//   clock-to-data ends at a flip-flop). The interface shows i2 as X,
//   combinationally, with its words. A step happens when i2 holds a position
//   and the output FIFO's credit (copy GRA_STEPS-1) is there; a read meets
//   the writes of the two steps before it, in the cycle of the read or at
//   the edge it moves on to i2 (the buffers' bypasses). A row's steps load one
//   a cycle while the credit lasts; a row ends in a cycle of its own (its
//   table word written, the next row's taken), which loads the next row's
//   first step (or a slice's first window step) when the row has lasted two
//   cycles (the next row's steps, registered, nx_*): a row of n >= 2 steps
//   takes n cycles, a row of one step or none two and one. A centre leaves
//   at its X-step: one slice and one row after it came.
//
// Ports (as cube4_gra_lines; samples unsigned Q0.VOXEL_W, lanes in the
// alignment of their own beat)
//   in_*      the beat schedule's sample stream (cube4_tri's format); in_eoss
//             the beat is the last of its slice
//   credit    [GRA_STEPS]   copies of the output FIFO's credit (GRA_STEPS-1:
//                           the step; 0 .. GRA_POS_G-1: the position
//                           buffers' groups, the same step)
//   step      out  the source and the window move this cycle
//   sop       out  0 (the source gates stale words itself)
//   fend      out  the step is the frame's last (a window step)
//   x, b1, p1, c, p1b2, p2b1, p2b2  [P*VOXEL_W]  X and its six neighbours;
//             zero where their step did not run
//   c_meta    [GRA_META_W]  {real, header} of C (real: an input beat)
//   c_sel     [P*GRA_NSEL]  C's select flags (GSEL_*), the same for every lane
//   c_edge    [2]  {gap, gap}: the step is not the one after the step of
//             the partial beam before in its row (cube4_gra_window BEATS:
//             beyond a gap the neighbour beat is zero)
//
// Bit growth and rounding: none (samples are passed, not computed).
// =============================================================================
module cube4_gra_beats
`include "cube4_gra_source_if.vh"

    localparam integer VW     = VOXEL_W;
    localparam integer PV     = P * VW;
    localparam integer META_W = GRA_META_W;
    localparam integer NBX    = NBMAX;                                 // bits of a row word
    localparam integer RW  = (MAX_DIM > 1) ? $clog2(MAX_DIM) : 1;     // row bits of a plane address

    `CUBE4_VIEW_FIELDS(cfg);
    genvar q;

    // ------------------------------------------------------------ the frame
    reg               act;           // a frame is under way
    reg               ended;         // its last input beat (EOP) is loaded
    reg               tail;          // the window steps after a slice's last row
    reg               tail_n;        // window steps loaded: 0, 1
    reg               fin;           // the frame is over after them
    reg [M_W-1:0]     cmp_m;         // the input of slices below cmp_m is in (in_eoss)
    reg               w_in;          // w < cmp_m (a register: loaded with w and cmp_m's next values)
    reg [M_W-1:0]     w;             // the slice being stepped
    reg [M_W-1:0]     w_last1;       // the last input beat's slice + 1 (with ended)
    reg               w_last;        // w == w_last1 (with ended; a register: loaded with w and w_last1's next values)
    reg [DIM_W-1:0]   r;             // its row, 0 .. NJ
    reg [DIM_W-1:0]   r1_q, r2_q;    // r + 1, r + 2 (DIM_W bits; registers, loaded with r)
    reg [M_W-1:0]     w1_q;          // w + 1 (loaded with w)
    reg [M_W-1:0]     wm1_q;         // w - 1 (M_W bits; loaded with w)
    wire [DIM_W-1:0]  r1 = r1_q;     // r + 1
    reg               r_nj;          // r == NJ (a register: r moves at start and at row_mv)
    reg               r1_nj;         // r + 1 == NJ
    reg               r_zero, r_one; // r == 0, r == 1
    reg               w_zero, w_one; // w == 0, w == 1
    wire              r_ones = (r == {DIM_W{1'b1}});   // r + 1 == 0 (the row after wraps)
    reg [NBX-1:0]     gm;            // G(w, r) not yet passed
    reg [NBX-1:0]     c_cur;         // C(w - 1, r)
    reg [NBX-1:0]     s_cur;         // S(w - 1, r): the plane words of this row count
    reg [NBX-1:0]     acc_c, acc_s;  // C(w, r), S(w, r) so far
    reg [NBX-1:0]     prev_s;        // S(w, r - 1): the beam words count
    reg [NBX-1:0]     prev_c;        // C(w, r - 1) (0 in row 0)
    reg               row_any;       // a step of this row is loaded
    reg [PB_W-1:0]    row_pb;        // its partial beam (the last)
    reg               sy_q [0:1], osy_q [0:1];   // SY, OSY of slice w by w's parity
    reg [NBX-1:0]     s_nj [0:1];    // S(w, NJ) by w's parity
    reg [NBX-1:0]     l_nj [0:1];    // L(w, NJ) by w's parity (L: the row table)
    reg [NBX-1:0]     nb_mask;       // bits below NB
    reg               nx_ok;         // nx_gm, nx_s hold the next row's (its second cycle on)
    reg [NBX-1:0]     nx_gm, nx_s;   // G(w, r + 1), S(w - 1, r + 1)

    // the input passes a skid buffer first (cube4_gra_beats_in): the choice of the
    // next step starts at registers (the head beat's place against the row, decided
    // a cycle ahead, its partial beam as bit words, decoded as it entered, its slice,
    // partial beam and EOSS, EOP, SY, OSY bits: the head slot's registers, which no
    // read pointer selects), and in_ready is a register (not the choice's result)
    wire              s_valid, s_ready, s_eoss;
    wire [HDR_W-1:0]  s_hdr;
    wire [PV-1:0]     s_sample;
    wire              s_eq0, s_gt0, s_eq1, s_gt1;    // the head against {w, r}, {w, r + 1}
    wire              s_mge, s_mgt, s_meq, s_meq1;   // its slice m: m >= w, m > w, m == w, m + 1 == w
    wire [NBX-1:0]    in_oh, in_below;               // the head's partial beam: bit pb, bits below it
    wire              row_mv;                        // the row moves on to {nx_w, nx_r}
    wire [M_W-1:0]    nx_w, nx_wm1;
    wire [DIM_W-1:0]  nx_r, nx_r1;
    wire              s_eop;                         // the head is the frame's last beat
    wire              in_sy, in_osy;                 // its SY, OSY
    wire [M_W-1:0]    in_m;                          // its slice
    wire [PB_W-1:0]   in_pb;                         // its partial beam
    wire              d_pop;                         // the data of the beat in i0 move on with it
    cube4_gra_beats_in #(.DATA_W (HDR_W + PV), .M_W (M_W), .DIM_W (DIM_W), .PB_W (PB_W), .NBX (NBX), .CW (4)) u_in (
        .clk (clk), .rst (rst),
        .in_valid (in_valid), .in_ready (in_ready), .in_data ({in_hdr, in_sample}),
        .out_valid (s_valid), .out_ready (s_ready), .d_pop (d_pop), .d_data ({s_hdr, s_sample}),
        .in_m (in_hdr[HDR_M +: M_W]), .in_j (in_hdr[HDR_J +: DIM_W]),
        .w (w), .r (r), .r1 (r1), .wm1 (wm1_q), .mv (row_mv), .nx_w (nx_w), .nx_r (nx_r), .nx_r1 (nx_r1),
        .nx_wm1 (nx_wm1), .home (start),
        .in_pb (in_hdr[HDR_PB +: PB_W]),
        .eq0 (s_eq0), .gt0 (s_gt0), .eq1 (s_eq1), .gt1 (s_gt1),
        .m_ge (s_mge), .m_gt (s_mgt), .m_eq (s_meq), .m_eq1 (s_meq1), .oh (in_oh), .below (in_below),
        .in_ctl ({in_eoss, in_hdr[HDR_CTRL + CTRL_EOP], in_hdr[HDR_CTRL + CTRL_SY], in_hdr[HDR_CTRL + CTRL_OSY]}),
        .ctl ({s_eoss, s_eop, in_sy, in_osy}), .m (in_m), .pb (in_pb));
    wire              in_eop = s_eop;              // (kept in the input's head slot: a register)

    // i0: the next step
    reg               i0_v, i0_in, i0_dead, i0_fend, i0_gap;
    reg [M_W-1:0]     i0_w;
    reg [DIM_W-1:0]   i0_r;
    reg [PB_W-1:0]    i0_pb;
    reg               i0_pg, i0_bg;  // the plane / beam words read for it count
    reg               i0_pgb;        // plane B's (the centre's row is a row)
    reg [3:0]         i0_flags;      // {dk_f, dk_b, j_first, m_first} of the centre
    reg               i0_ylast, i0_dyf, i0_dyb;
    // the step's fields as one word, which moves on i0 -> ia -> i1 -> i2; a generated
    // step's sample and header are zero (the samples of beats that do not run),
    // formed here from the register i0_in; an input beat's sample and header are
    // the input's data queue's oldest (u_in), which pops as i0 moves on (d_pop), so
    // the choice that loads i0 drives no data register
    // (i0_rok: the row's bounds {r != 0, r < NJ} the position buffers' writes
    // take, formed here from registers, so that the step's write enables are
    // registers ANDed with step's copies, no compare between)
    localparam integer SW = 16 + PV + HDR_W + M_W + DIM_W + PB_W;
    wire [PV-1:0]    i0_smp_in = {PV{i0_in}} & s_sample;
    wire [HDR_W-1:0] i0_hdr_in = {HDR_W{i0_in}} & s_hdr;
    wire [1:0]       i0_rok = {i0_r != '0, i0_r < cfg_nj};
    wire [SW-1:0] i0_word = {i0_rok, i0_in, i0_dead, i0_fend, i0_gap, i0_smp_in, i0_hdr_in, i0_w, i0_r, i0_pb,
                             i0_pg, i0_bg, i0_pgb, i0_flags, i0_ylast, i0_dyf, i0_dyb};
    // ia: one register stage after i0, whose position reads the position buffers
    // as it moves on (from registers: neither the choice nor its fan-out reaches
    // the block RAMs' addresses and the bypass registers' enables, and i0, which
    // the choice loads, feeds only ia, so it lies beside the choice)
    reg               ia_v;
    reg [SW-1:0]      ia_word;
    localparam integer W_PB = 10;                       // ia_word's pb, r (i0_word's order)
    localparam integer W_R  = W_PB + PB_W;
    wire [PB_W-1:0]   ia_pb = ia_word[W_PB +: PB_W];
    wire [DIM_W-1:0]  ia_r  = ia_word[W_R +: DIM_W];
    // i1: one register stage after ia, the step whose words are being read
    reg               i1_v;
    reg [SW-1:0]      i1_word;
    // i2: the step, one register stage after i1, with the words i1 read (their
    // block RAMs' clock-to-data ends at a register: cube4_gra_pos OUT_STAGE)
    reg               i2_v;
    reg [SW-1:0]      i2_word;
    wire [1:0]        i2_rok;
    wire              i2_in, i2_dead, i2_fend, i2_gap;
    wire [PV-1:0]     i2_sample;
    wire [HDR_W-1:0]  i2_hdr;
    wire [M_W-1:0]    i2_w;
    wire [DIM_W-1:0]  i2_r;
    wire [PB_W-1:0]   i2_pb;
    wire              i2_pg, i2_bg, i2_pgb;
    wire [3:0]        i2_flags;
    wire              i2_ylast, i2_dyf, i2_dyb;
    assign {i2_rok, i2_in, i2_dead, i2_fend, i2_gap, i2_sample, i2_hdr, i2_w, i2_r, i2_pb,
            i2_pg, i2_bg, i2_pgb, i2_flags, i2_ylast, i2_dyf, i2_dyb} = i2_word;
    wire [P-1:0]      i2_lane_valid = i2_hdr[HDR_LVALID +: P];
    assign step = i2_v && credit[GRA_STEPS-1];
    assign sop  = 1'b0;
    assign fend = i2_fend;
    wire i1_mv   = i1_v && (!i2_v || step);               // i1 moves on to i2 (its words load)
    wire ia_mv   = ia_v && (!i1_v || i1_mv);              // ia moves on to i1 (its buffers' read)
    wire i0_mv   = i0_v && (!ia_v || ia_mv);              // i0 moves on to ia
    wire i0_take = !i0_v || i0_mv;
    assign d_pop = i0_mv && i0_in;                        // i0's input beat's data move on with it

    // ------------------------------------------------------------ the next step
    // the input's beat is in this row, or beyond it
    wire in_v     = s_valid && act && !ended && !tail;
    wire in_row   = in_v && s_eq0;
    wire in_after = in_v && s_gt0;
    // the next row's beat of the input, or beyond it (for a row end that loads)
    wire in_nx    = in_v && s_eq1;
    wire in_aft1  = in_v && s_gt1;
    // partial beams as bit words: the choice works on them (AND-OR terms of
    // registers; the carry chains that find lowest bits feed registers only),
    // the binary partial beam is encoded beside it for the buffers
    function automatic [NBX-1:0] low_oh(input [NBX-1:0] v);       // v's lowest set bit (0: none)
        low_oh = v & ~(v - 1'b1);
    endfunction
    function automatic [PB_W-1:0] enc(input [NBX-1:0] oh);        // a one-hot word's bit index
        integer b;
        enc = '0;
        for (b = 0; b < NBX; b = b + 1) begin
            if (oh[b]) enc = enc | PB_W'(b);
        end
    endfunction
    // gm's and nx_gm's lowest bits are registers kept with them (g_oh, x_oh), so
    // the choice and what it decides start at flip-flops, not at a carry chain
    // over gm; the second lowest bits (g2_oh, x2_oh) are what g_oh takes when a
    // step passes the lowest (formed from registers, chosen at g_oh's input)
    reg  [NBX-1:0]  g_oh;                                        // low_oh(gm)
    reg  [NBX-1:0]  x_oh;                                        // low_oh(nx_gm)
    wire [NBX-1:0]  g2_oh = low_oh(gm & ~g_oh);
    wire [NBX-1:0]  x2_oh = low_oh(nx_gm & ~x_oh);
    // whether gm and nx_gm hold a step are registers too (g_nz, x_nz), loaded with
    // g_oh and x_oh: the row end (no step of the row left) is decided from a
    // flip-flop, not from an OR over gm's NBX bits in front of the choice; the
    // values they take are ORs of registers beside it (g2_nz, x2_nz)
    reg             g_nz;                                        // gm != 0
    reg             x_nz;                                        // nx_gm != 0
    wire            g2_nz = |(gm & ~g_oh);                       // g2_oh != 0
    wire            x2_nz = |(nx_gm & ~x_oh);                    // x2_oh != 0
    wire [PB_W-1:0] g_pb = enc(g_oh);
    wire [PB_W-1:0] x_pb = enc(x_oh);
    wire [NBX-1:0]  in_upto = in_oh | in_below;             // bits 0 .. in_pb
    wire g_any   = act && !tail && g_nz;
    wire g_first = g_any && (!in_row || |(gm & in_below));  // a generated step comes first (g_pb < in_pb)
    wire start   = !act && s_valid;                         // a frame's first beat waits
    wire pass    = act && !tail && (in_after || ended || w_in);   // the input has passed this row
    // The choice is formed without i0_take (t_*: what loads if i0 takes a step), and
    // the loads (ld_*) are t_* with i0_take. What a load writes (the i0 fields, the
    // row's words) is formed from t_*: under a load i0_take is 1 and t_* are ld_*, so
    // the step's fields do not wait for i0_take (i0_v .. i2_v and the credit), and
    // they load on i0_take alone, not on the choice; only i0_v, the row's registers'
    // enables and the row end's choices (ld_nx, ld_in_x) take both.
    wire t_in    = in_row && !g_first;
    wire t_gen   = g_first && (in_row || pass);
    wire t_tl    = tail;
    wire row_end = pass && !g_any;                           // the row ends (no step of it this cycle)
    // a row end that loads: the next row's first step, or a slice's first window step
    wire t_mg    = row_end && nx_ok && !r_nj;
    wire x_first = x_nz && (!in_nx || |(nx_gm & in_below));
    wire t_in_x  = t_mg && in_nx && !x_first;
    wire t_gen_x = t_mg && x_first && (in_nx || in_aft1 || ended || w_in);
    wire t_tl_x  = row_end && r_nj;
    wire t_nx    = t_in_x || t_gen_x;                        // a step of the next row
    wire t_i     = t_in || t_in_x;                           // an input beat
    wire t_tail  = t_tl || t_tl_x;                           // a window step
    wire ld_in    = i0_take && t_in;
    wire ld_gen   = i0_take && t_gen;
    wire ld_tl    = i0_take && t_tl;
    wire mg       = i0_take && t_mg;
    wire ld_in_x  = i0_take && t_in_x;
    wire ld_gen_x = i0_take && t_gen_x;
    wire ld_tl_x  = i0_take && t_tl_x;
    wire ld_nx   = ld_in_x || ld_gen_x;                      // a step of the next row
    wire ld_i    = ld_in || ld_in_x;                         // an input beat
    wire ld_s    = ld_i || ld_gen || ld_gen_x;               // a step of a row
    wire ld_tail = ld_tl || ld_tl_x;                         // a window step
    wire last_row = w_last && r_nj;
    wire ld      = ld_s || ld_tail;
    assign s_ready = ld_i;

    // the step being loaded: slice ld_w, row ld_r, partial beam ld_pb (t_*: as loaded)
    wire [M_W-1:0]   ld_w  = w;
    wire [DIM_W-1:0] ld_r  = t_nx ? r1 : r;
    wire [PB_W-1:0]  ld_pb = t_i ? in_pb : (t_nx ? x_pb : g_pb);
    wire             w_pos = (ld_w != '0);
    wire [NBX-1:0]   ld_bit = t_i ? in_oh : (t_nx ? x_oh : g_oh);       // 1 << ld_pb
    // what the step's partial beam decides, for each place it may come from (the
    // input's beat, the row's generated step, the next row's input or generated step),
    // side by side with the choice, which then picks one
    wire [PB_W-1:0]  row_pb1 = row_pb + 1'b1;
    wire pg_in  = |(s_cur & in_oh),  pg_gen = |(s_cur & g_oh),  pg_inx = |(nx_s & in_oh),  pg_genx = |(nx_s & x_oh);
    wire bg_in  = |(prev_s & in_oh), bg_gen = |(prev_s & g_oh), bg_inx = |(acc_s & in_oh), bg_genx = |(acc_s & x_oh);
    wire ld_pg = !t_tail && w_pos && ((t_in && pg_in) || (t_gen && pg_gen) || (t_in_x && pg_inx)
                                      || (t_gen_x && pg_genx));
    wire ld_bg = !t_tail && (t_nx ? !r_ones && ((t_in_x && bg_inx) || (t_gen_x && bg_genx))
                                  : !r_zero && ((t_in && bg_in) || (t_gen && bg_gen)));
    wire ld_gap = t_tail || t_nx || !row_any || (t_i ? (in_pb != row_pb1) : (g_pb != row_pb1));
    // the steps of a row the step passes: the bits up to its partial beam (an
    // input beat: none of gm / nx_gm lie below it), or its own bit (a generated
    // step: the lowest)
    wire [NBX-1:0] ld_upto = t_i ? in_upto : (t_nx ? x_oh : g_oh);
    // gm's lowest bit after the step: the second lowest where the step passed the lowest
    wire           g_pass  = t_gen || (g_oh & in_oh) != '0;
    wire           x_pass  = t_gen_x || (x_oh & in_oh) != '0;
    wire [NBX-1:0] g_oh_ld = g_pass ? g2_oh : g_oh;
    wire [NBX-1:0] x_oh_ld = x_pass ? x2_oh : x_oh;
    wire           g_nz_ld = g_pass ? g2_nz : g_nz;             // g_oh_ld != 0
    wire           x_nz_ld = x_pass ? x2_nz : x_nz;             // x_oh_ld != 0
    // dk_f, dk_b: the centre slice w - 1 and the slice after / before it lie between
    // other voxel slices (as cube4_gra_walk; always with S = 1)
    `CUBE4_VIEW_SLICES;
    wire [M_W-1:0] ss_mask = M_W'((1 << view_ssl) - 1);
    wire unused_m_last = ^view_m_last;
    wire [3:0] ld_flags = {(ld_w & ss_mask) == '0,           // dk_f of centre slice w - 1
                           (wm1_q & ss_mask) == '0,          // dk_b (ld_w - 1)
                           t_nx ? r_zero : r_one,          // j_first (centre row 0): ld_r == 1
                           w_one};                         // m_first (centre slice 0): ld_w == 1
    wire           wm1_odd = ~ld_w[0];                // (w - 1) mod 2

    // ------------------------------------------------------------ the row table
    // word {S, C, L} of row r of slice w at {w mod 2, r}; read one row ahead.
    // L = low_oh((C(w, r - 1) | C(w, r)) & nb_mask) (C(w, -1) = 0) is the
    // lowest step of row_gm below while the word is n_c's (c_cur then holds
    // C(w, r - 1), or r_nj masks it for r = 0), formed as the word is written,
    // so that a row that ends in its first cycle takes the next row's lowest
    // step g_oh from the word read, not through a carry chain over it (a
    // simulation check holds it to low_oh(row_gm)).
    // A row's word is written one edge after its row end, from registers
    // (t_we_q, t_wa_q, t_wd_q), so the row end (a decision over gm) reaches a
    // flip-flop, not the distributed RAM's write enable; a read at the row end's
    // edge or at the next one takes the word through the bypass (t_by, t_bd).
    localparam integer TW = 3 * NBX;
    wire [RW:0]     t_ra;            // {parity, row} read
    wire [TW-1:0]   t_rd;
    wire            t_re;
    wire            t_we = row_end && act && !r_nj;
    wire [RW:0]     t_wa = {w[0], r[RW-1:0]};
    wire [TW-1:0]   t_wd = {acc_s, acc_c, low_oh((prev_c | acc_c) & nb_mask)};
    reg             t_we_q;          // the write, one edge late
    reg [RW:0]      t_wa_q;
    reg [TW-1:0]    t_wd_q;
    always @(posedge clk) begin
        t_we_q <= !rst && t_we;
        t_wa_q <= t_wa;
        t_wd_q <= t_wd;
    end
    // (distributed RAM: the word read goes into the row's next steps, gm, in the cycle after)
    cube4_sdp_ram #(.DATA_W (TW), .DEPTH (2 << RW), .DIST (1)) u_rows (
        .clk (clk), .rd_en (t_re), .out_en (1'b0), .rd_addr (t_ra), .rd_data (t_rd),
        .wr_en (t_we_q), .wr_addr (t_wa_q), .wr_data (t_wd_q));
    // the row after the next one: rows 0 .. NJ of slice w read slice w - 1's
    // rows; the word of row NJ and of slice -1 is zero (n_zero)
    assign nx_r  = r_nj ? '0 : r1;                             // the next row
    assign nx_r1 = r_nj ? DIM_W'(1) : r2_q;                    // nx_r + 1
    assign nx_w  = r_nj ? w1_q : w;                            // and its slice
    assign nx_wm1 = r_nj ? w : wm1_q;                          // nx_w - 1
    wire   nx_nj = r_nj ? (cfg_nj == '0) : r1_nj;              // nx_r == NJ
    assign row_mv = row_end && !(ended && last_row);         // (as the row end below)
    // the row after the next one, (nn_w, nn_r), in registers that move with the row (so
    // the table's read address is a register: the distributed RAM reads in the cycle)
    reg [DIM_W-1:0]  nn_r;
    reg [M_W-1:0]    nn_w;
    reg              nn_nj;          // nn_r == NJ
    always @(posedge clk) begin
        if (start) begin             // after row 0: row 1 (NJ >= 1), after it row 2 or slice 1's 0
            nn_r  <= (cfg_nj <= DIM_W'(1)) ? '0 : DIM_W'(2);
            nn_w  <= (cfg_nj == '0) ? M_W'(2) : ((cfg_nj == DIM_W'(1)) ? M_W'(1) : '0);
            nn_nj <= (cfg_nj == '0) || (cfg_nj == DIM_W'(2));
        end else if (row_mv) begin
            nn_r  <= nn_nj ? '0 : nn_r + 1'b1;
            nn_w  <= nn_nj ? nn_w + 1'b1 : nn_w;
            nn_nj <= nn_nj ? (cfg_nj == '0) : (nn_r + 1'b1 == cfg_nj);
        end
    end
    // a frame starts at row 0 of slice 0, and reads row 1's (zero: slice -1)
    assign t_re = row_end || start;
    // (the read at start is of slice -1, whose word is zero by t_zero: the RAM's
    // address is (nn_w, nn_r) in every cycle, flip-flops, and only the registers
    // beside it take start)
    wire [M_W-1:0]   rd_w   = start ? '0 : nn_w;
    assign t_ra = {~nn_w[0], nn_r[RW-1:0]};                   // slice nn_w - 1's parity (rows below MAX_DIM)
    reg             t_zero;          // the word read is zero (slice -1)
    reg             t_by;            // it is t_bd: a word the RAM does not hold yet, or row NJ's
    reg [TW-1:0]    t_bd;
    wire            rd_nj = start ? (cfg_nj == DIM_W'(1)) : nn_nj;
    // the words not in the RAM at the read: the row end's of this edge (t_wd), the
    // write of this edge (t_wd_q); the choice between them is by address alone
    // (registers), not by the row end (a simulation check below holds that the
    // two never both match with only the older one written)
    wire            by_new = (t_wa == t_ra);
    wire            by_old = (t_wa_q == t_ra);
    // row NJ's word {S, C, L} as its row ends (its C is zero): kept in s_nj / l_nj by
    // the slice's parity; with NJ = 1 the read at that row end is of this very word
    // (the row after the next one is row NJ of the next slice, whose rows read this
    // slice's), so it is taken from here, not from the register it is written to
    wire [TW-1:0]   nj_wd  = {acc_s, {NBX{1'b0}}, low_oh(prev_c & nb_mask)};
    always @(posedge clk) begin
        if (t_re) begin
            t_zero <= (rd_w == '0);
            t_by   <= rd_nj || (t_we && by_new) || (t_we_q && by_old);
            t_bd   <= rd_nj ? (r_nj ? nj_wd : {s_nj[~rd_w[0]], {NBX{1'b0}}, l_nj[~rd_w[0]]})
                            : (by_new ? t_wd : t_wd_q);
        end
        if (row_end && act && r_nj) begin
            s_nj[w[0]] <= nj_wd[2*NBX +: NBX];
            l_nj[w[0]] <= nj_wd[0 +: NBX];
        end
    end
    wire [TW-1:0]  t_word = t_zero ? '0 : (t_by ? t_bd : t_rd);
    wire [NBX-1:0] n_l = t_word[0 +: NBX];                     // low_oh(row_gm)
    wire [NBX-1:0] n_c = t_word[NBX +: NBX];                   // C(w', r' + 1) of the row after
    wire [NBX-1:0] n_s = t_word[2*NBX +: NBX];
    wire [NBX-1:0] row_gm = ((r_nj ? '0 : c_cur) | n_c) & nb_mask;   // G of the next row, as it ends
    generate
        for (q = 0; q < NBX; q = q + 1) begin : g_nb
            always @(posedge clk) nb_mask[q] <= (NB_W'(q) < cfg_nb);
        end
    endgenerate

    always @(posedge clk) begin
        if (rst) begin
            act    <= 1'b0;
            ended  <= 1'b0;
            tail   <= 1'b0;
            i0_v   <= 1'b0;
            ia_v   <= 1'b0;
            i1_v   <= 1'b0;
            i2_v   <= 1'b0;
        end else begin
            if (ld)         i0_v <= 1'b1;
            else if (i0_mv) i0_v <= 1'b0;
            if (i0_mv)      ia_v <= 1'b1;
            else if (ia_mv) ia_v <= 1'b0;
            if (ia_mv)      i1_v <= 1'b1;
            else if (i1_mv) i1_v <= 1'b0;
            if (i1_mv)      i2_v <= 1'b1;
            else if (step)  i2_v <= 1'b0;
            if (start) begin
                // slice 0, row 0 (slice -1 gives nothing); its beat loads as the row's
                act     <= 1'b1;
                ended   <= 1'b0;
                tail    <= 1'b0;
                cmp_m   <= '0;
                w       <= '0;
                w1_q    <= M_W'(1);
                wm1_q   <= {M_W{1'b1}};
                r       <= '0;
                r1_q    <= DIM_W'(1);
                r2_q    <= DIM_W'(2);
                r_nj    <= (cfg_nj == '0);
                r1_nj   <= (cfg_nj == DIM_W'(1));
                r_zero  <= 1'b1;
                r_one   <= 1'b0;
                w_zero  <= 1'b1;
                w_one   <= 1'b0;
                gm      <= '0;
                g_oh    <= '0;
                g_nz    <= 1'b0;
                c_cur   <= '0;
                s_cur   <= '0;
                prev_s  <= '0;
                prev_c  <= '0;
                acc_c   <= '0;
                acc_s   <= '0;
                row_any <= 1'b0;
            end
            if (ld_in || ld_gen) begin
                row_any <= 1'b1;
                row_pb  <= ld_pb;
                acc_s   <= acc_s | ld_bit;
                if (ld_in) acc_c <= acc_c | ld_bit;
                // the steps of this row up to ld_pb are passed
                gm   <= gm & ~ld_upto;
                g_oh <= g_oh_ld;
                g_nz <= g_nz_ld;
            end
            nx_ok <= !(start || row_end);
            if (ld_i) begin
                if (s_eoss) cmp_m <= in_m + 1'b1;
                if (in_eop) begin
                    ended  <= 1'b1;
                    w_last1 <= in_m + 1'b1;
                end
            end
            if (row_end) begin
                // the next row, with its first step when one loads (ld_nx)
                row_any <= ld_nx;
                row_pb  <= ld_pb;
                acc_c   <= ld_in_x ? ld_bit : '0;
                acc_s   <= ld_nx ? ld_bit : '0;
                if (r_nj) begin
                    tail   <= 1'b1;
                    tail_n <= ld_tl_x;
                    fin    <= ended && last_row;
                end
                if (ended && last_row) begin
                    gm     <= '0;
                    g_oh   <= '0;
                    g_nz   <= 1'b0;
                end else begin
                    r       <= nx_r;
                    r1_q    <= nx_r1;
                    r2_q    <= r_nj ? DIM_W'(2) : r2_q + 1'b1;
                    w1_q    <= r_nj ? w1_q + 1'b1 : w1_q;
                    wm1_q   <= nx_wm1;
                    r_nj    <= nx_nj;
                    r1_nj   <= r_nj ? (cfg_nj == DIM_W'(1)) : (r + DIM_W'(2) == cfg_nj);   // nx_r + 1 == NJ
                    r_zero  <= r_nj || r_ones;                                         // nx_r == 0
                    r_one   <= !r_nj && r_zero;                                        // nx_r == 1
                    w_zero  <= r_nj ? (w == {M_W{1'b1}}) : w_zero;                      // nx_w == 0
                    w_one   <= r_nj ? w_zero : w_one;                                  // nx_w == 1
                    w       <= nx_w;
                    prev_s  <= r_nj ? '0 : acc_s;
                    prev_c  <= r_nj ? '0 : acc_c;
                    c_cur   <= n_c;
                    s_cur   <= n_s;
                    gm      <= row_gm & ~(ld_nx ? ld_upto : '0);
                    g_oh    <= ld_nx ? x_oh_ld : n_l;   // (ld_nx: row_gm = nx_gm; n_l = low_oh(row_gm))
                    g_nz    <= ld_nx ? x_nz_ld : |n_l;
                end
            end
            if (ld_tl) begin
                tail_n <= 1'b1;
                if (tail_n) begin
                    tail <= 1'b0;
                    if (fin) act <= 1'b0;    // the frame is over
                end
            end
        end
    end
    // w < cmp_m for the next cycle: the four compares of w or w + 1 (the row moves on to
    // the next slice) with cmp_m or in_m + 1 (the slice's EOSS beat loads), and the two
    // choices select one. Against in_m + 1 they are the head's slice flags, kept in the
    // skid's entries (w + 1 < in_m + 1: m > w; w < in_m + 1: m >= w, in M_W + 1 bits),
    // so neither the skid's multiplexer nor an adder lies before the choice.
    wire [M_W:0] w_x = {1'b0, w}, w1_x = w_x + 1'b1, cm_x = {1'b0, cmp_m};
    wire         w_mv  = row_mv && r_nj;                     // w moves on to w + 1
    wire         cm_ld = ld_i && s_eoss;                     // cmp_m loads in_m + 1
    always @(posedge clk) begin
        if (start) w_in <= 1'b0;
        else       w_in <= w_mv ? (cm_ld ? s_mgt : (w1_x < cm_x))
                                : (cm_ld ? s_mge : (w_x < cm_x));
    end
    // w == w_last1 for the next cycle alike: w or w + 1 against w_last1 or in_m + 1 (the
    // frame's EOP beat loads), in M_W bits as w_last1 is (w + 1 == in_m + 1: m == w;
    // w == in_m + 1: m + 1 == w, the head's flags); read only with ended, which
    // start clears and the EOP beat sets (so start's w = 0 needs no compare of its own).
    // It keeps the compare out of row_mv, in front of w_in and the row's registers.
    wire           wl_ld = ld_i && in_eop;                   // w_last1 loads in_m + 1
    always @(posedge clk) begin
        if (start) w_last <= 1'b0;
        else       w_last <= w_mv ? (wl_ld ? s_meq : (w1_q == w_last1))
                                  : (wl_ld ? s_meq1 : (w == w_last1));
    end
`ifndef SYNTHESIS
    // the head's slice flags are the compares they stand for
    wire [M_W:0] im1_x = {1'b0, in_m} + 1'b1;
    always @(posedge clk) begin
        if (!rst && s_valid && act
            && {s_mgt, s_mge, s_meq, s_meq1} != {w1_x < im1_x, w_x < im1_x, w1_q == im1_x[M_W-1:0], w == im1_x[M_W-1:0]})
            $fatal(1, "cube4_gra_beats: the head's slice flags %b are not its slice %0d against w %0d",
                   {s_mgt, s_mge, s_meq, s_meq1}, in_m, w);
    end
`endif
`ifndef SYNTHESIS
    always @(posedge clk) begin
        if (!rst && act && wm1_q != w - 1'b1)
            $fatal(1, "cube4_gra_beats: wm1_q %0d is not w - 1 (w %0d)", wm1_q, w);
        if (!rst && act && ended && (w_last != (w == w_last1)))
            $fatal(1, "cube4_gra_beats: w_last %0d differs from w == w_last1 (w %0d, w_last1 %0d)", w_last, w, w_last1);
    end
`endif
    always @(posedge clk) begin
        // the next row's steps, for a row end that loads (valid in a row's second cycle on)
        nx_gm <= (c_cur | n_c) & nb_mask;
        x_oh  <= low_oh((c_cur | n_c) & nb_mask);
        x_nz  <= |((c_cur | n_c) & nb_mask);
        nx_s  <= n_s;
        if (ld_i) begin
            sy_q[in_m[0]]  <= in_sy;
            osy_q[in_m[0]] <= in_osy;
        end
        // the step's fields load whenever i0 takes a step (a load enable of i0's
        // registers, not the choice of step: where the choice loads no step, i0_v
        // falls and the fields are not read)
        if (i0_take) begin
            i0_in     <= t_i;
            i0_dead   <= t_tail;
            i0_fend   <= t_tl && tail_n && fin;
            i0_gap    <= ld_gap;
            i0_w      <= ld_w;
            i0_r      <= ld_r;
            i0_pb     <= ld_pb;
            i0_pg     <= ld_pg;
            i0_bg     <= ld_bg;
            i0_pgb    <= ld_pg && (t_nx ? !r_ones : !r_zero);    // ld_r != 0
            i0_flags  <= ld_flags;
            i0_ylast  <= t_nx ? r1_nj : r_nj;                     // ld_r == NJ
            i0_dyf    <= sy_q[wm1_odd];                          // SY(w - 1): the centre's slice
            i0_dyb    <= osy_q[wm1_odd];                         // OSY(w - 1)
        end
    end

    always @(posedge clk) begin
        if (i0_mv) ia_word <= i0_word;
        if (ia_mv) i1_word <= ia_word;
        if (i1_mv) i2_word <= i1_word;
    end
    wire [META_W-1:0] x_meta = {i2_in, i2_hdr};

    // ---- position buffers (cube4_gra_pos): read as a step's position moves on
    // from ia to i1, their words registered as it moves on to i2, written when
    // it steps from i2 ----
    // Each group of its registers takes its read, load and step from a credit
    // copy of its own (copies 0 .. GRA_POS_G-1: the delay lines' in the other
    // builds, unused by this source otherwise; not step's), so no one net
    // reaches the hundreds of enables and bypass choices (as ia_mv, i1_mv, step)
    wire [GRA_POS_G-1:0] pos_cr = credit[GRA_POS_G-1:0];
    wire [GRA_POS_G-1:0] pos_step = {GRA_POS_G{i2_v}} & pos_cr;
    wire [GRA_POS_G-1:0] pos_mv   = {GRA_POS_G{i1_v}} & ({GRA_POS_G{!i2_v}} | pos_cr);
    wire [GRA_POS_G-1:0] pos_ld   = {GRA_POS_G{ia_v}} & ({GRA_POS_G{!i1_v || !i2_v}} | pos_cr);
    cube4_gra_pos #(.OUT_STAGE (1), `CUBE4_GRA_PASS) u_pos (
        .clk (clk), .ld (pos_ld), .ld_r (ia_r), .ld_pb (ia_pb), .mv (pos_mv),
        .step (pos_step), .dead (i2_dead), .i0_w (i2_w), .i0_r (i2_r), .i0_pb (i2_pb), .row_ok (i2_rok),
        .in_beat (i2_in), .sample (i2_sample), .lane_valid (i2_lane_valid), .x (x), .x_meta (x_meta), .pg (i2_pg), .pgb (i2_pgb), .bg (i2_bg),
        .p1 (p1), .p2b1 (p2b1), .b1 (b1), .c_meta (c_meta), .c (c),
        .p1b2 (p1b2), .p2b2 (p2b2));
    assign c_sel   = {P{i2_flags, i2_ylast, i2_dyf, i2_dyb}};   // bits GSEL_DKF .. GSEL_DYB
    assign c_edge  = {i2_gap, i2_gap};
`ifndef SYNTHESIS
    always @(posedge clk) begin
        if (!rst && act && g_oh != low_oh(gm))
            $fatal(1, "cube4_gra_beats: g_oh %0h is not gm's lowest bit (gm %0h)", g_oh, gm);
        if (!rst && act && (g_nz != (gm != '0) || x_nz != (nx_gm != '0)))
            $fatal(1, "cube4_gra_beats: g_nz %0d, x_nz %0d are not gm != 0, nx_gm != 0 (gm %0h, nx_gm %0h)",
                   g_nz, x_nz, gm, nx_gm);
        if (pos_ld[0] != ia_mv || pos_mv[0] != i1_mv || pos_step[0] != step)
            $fatal(1, "cube4_gra_beats: the position buffers' read/load/step (%b%b%b) are not ia_mv, i1_mv, step (%b%b%b)",
                   pos_ld[0], pos_mv[0], pos_step[0], ia_mv, i1_mv, step);
        if (!rst && i2_v && i2_rok != {i2_r != '0, i2_r < cfg_nj})
            $fatal(1, "cube4_gra_beats: i2's row bounds %b are not row %0d's (NJ %0d)", i2_rok, i2_r, cfg_nj);
        if (!rst && i0_v && (i0_word[W_PB +: PB_W] != i0_pb || i0_word[W_R +: DIM_W] != i0_r))
            $fatal(1, "cube4_gra_beats: the word's fields at W_PB, W_R are not i0's pb %0d and r %0d", i0_pb, i0_r);
        if (!rst && act && n_l != low_oh(row_gm))
            $fatal(1, "cube4_gra_beats: the row table's L %0h is not the next row's lowest step (row_gm %0h)", n_l, row_gm);
        if (!rst && t_re && !rd_nj && rd_w != '0 && by_new && !t_we && by_old && t_we_q)
            $fatal(1, "cube4_gra_beats: the row table's read at %0h takes the row end's word, not the write before it", t_ra);
        if (!rst && mg && row_gm != nx_gm)   // (what g_oh's load from x_oh at a row end relies on)
            $fatal(1, "cube4_gra_beats: the next row's steps %0h at a loading row end are not nx_gm %0h", row_gm, nx_gm);
    end
`endif
    generate
        if (GRA_POS_G > GRA_STEPS - 1) begin : g_bad_pos_g
            $error("cube4_gra_beats: GRA_POS_G = %0d groups need as many credit copies besides step's (GRA_STEPS = %0d)",
                   GRA_POS_G, GRA_STEPS);
        end else if (GRA_POS_G < GRA_STEPS - 1) begin : g_spare_credit
            wire unused_credit = ^credit[GRA_STEPS-2:GRA_POS_G];   // (more copies than groups)
        end
    endgenerate

endmodule
`default_nettype wire

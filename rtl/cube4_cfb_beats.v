`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_beats
// -----------------------------------------------------------------------------
// Purpose
//   The walk of the beat schedule (docs/numerics.md section 19, "The walk";
//   docs/architecture.md "The front end's plan"; golden/cube4/beats.py
//   walk_rows): from each sample slice's bitmaps, one NB-bit word per row of
//     A    the running beats (a lane holds a running ray)
//     OCC  the beats that may count
//   it forms each row's running beats
//     E(m, j) = A(m, j) | (nbr_en & OCC(m, j) & grow(OR of A(m + dm, j + dj),
//               dm, dj in -1 .. 1))        grow(x) = x | x << 1 | x >> 1
//   (nbr_en: termination in a frame shaded by GRA; rows and slices outside the
//   frame are zero), and walks the voxel beats they read, row by row, with
//   the cover COM's X-step hop needs (the partial beam before a running
//   beat, walked without reads where the row reads nothing there):
//     reads(k) = up(E(k - 1) | E(k)),    up(x) = x | x << 1   (pb and pb + 1)
//     walks(k) = reads(k) | ((E(k - 1) | E(k)) >> 1)
//   where k runs over the frame's rows (m, j) in order and then one flush row
//   (m = M, j = 0, E = 0): the previous row in this order is row j - 1, or
//   the previous slice's last row, whose reads complete it (Y-wrap, as the
//   fixed schedule). Each set bit of walks(k) is one voxel beat, lowest pb
//   first, with its bit of reads(k) and the bit of E(k - 1) at its pb (the
//   sample beat that leaves with it runs). A row that walks nothing takes
//   one cycle and gives one beat that reads nothing: a slice's last row,
//   row 0 of every slice but the first and the flush row a marker (every
//   slice leaves at least one beat, and so does every sample slice's last
//   row, which leaves with row 0 of the slice after it: the units behind
//   see each slice end without waiting for the next beat, and COM can
//   report it), any other row a token that only moves the address unit's
//   row on (cube4_cfb_bctl: every row ends with a beat that carries EOR).
//   The last beat carries LAST.
//   With S > 1 a pass that reads a voxel slice for the slice buffers (pass 0
//   and each pass k0 S + 1: beats.BeatSchedule.reads_slice) reads every beat
//   of its rows, reads(k) = NB ones for k = (m, j) of such a pass: the passes
//   that replay the slice may run any of its beats.
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2: the geometry (cube4_defs.vh; 1..64,
//   2..2048, 4..12, 0..3). NBMAX = ceil(MAX_DIM / P) bits per bitmap row.
//
// Latency
//   Bitmaps: a row is taken when bm_valid && bm_ready and written into its
//   slot at the edge after; slice m's rows may be taken once the walk
//   fetches slice m - 2 (four slots, slice mod 4), and the walk fetches slice
//   m's rows once slice m + 1 is written whole (or is past the frame). The
//   walk: a row is fetched (its words of slices m - 1, m, m + 1 read at one
//   row, one from each copy of the slots, through the RAMs' read and output
//   registers: two fetches), enters a window of three rows, its E is
//   registered, and its reads are formed from two registered E words, and
//   the row waits in a queue of two rows for the emitter: a row fetched at
//   an edge is in the emitter six edges later (its first beat offered in
//   the cycle after).
//   The pipeline moves one row per edge while the queue has room (its
//   registered count: the emitter's last bit does not reach the pipeline's
//   enable). The emitter takes one cycle per
//   beat and one per row that walks nothing, so with its rows ready a frame
//   takes sum over rows of max(1, beats) cycles (beats.walker_cycles).
//   out_valid does not depend on out_ready; a beat is held while stalled.
//
// Ports
//   start    in   pulse: a frame starts (nj, nb, nm, nbr_en stable until done)
//   busy     out  a frame is under way (from start to its LAST beat's transfer)
//   nj, nb, nm    rows NJ [DIM_W] 1..MAX_DIM, partial beams NB [NB_W]
//             1..NBMAX, sample slices M [M_W] >= 1
//   ss_log2  log2 S [2], 0 .. MAX_SS_LOG2
//   nbr_en   in   E with the neighbour term
//   bm_valid, bm_ready, bm_a, bm_occ   the next row's bitmaps [NBMAX] (bit pb,
//             zero at pb >= NB), rows j = 0 .. NJ - 1 of slices 0 .. M - 1 in order
//   out_valid, out_ready   the walk's beats
//   out_m, out_j, out_pb   the voxel beat: sample slice [M_W] (M: the flush
//             row), row [DIM_W], partial beam [PB_W]
//   out_read  the beat reads (0: a beat of the cover, or the token or
//             marker of a row that walks nothing; a marker carries EOS or
//             LAST)
//   out_tok   the beat is a token (a row that walks nothing, not a marker)
//   out_leave the sample beat that leaves with it runs
//   out_in_a  that beat holds a running ray (A; else it runs as GRA's
//             neighbour only)
//   out_eor   the row's last beat (of its reads, or its token or marker)
//   out_eos   the slice's last beat (of its last row, or its marker)
//   out_last  the frame's last beat
//
// Bit growth and rounding: none (bit words and counters).
// =============================================================================
module cube4_cfb_beats #(
    `CUBE4_SLICE_PARAMS
) (
    input  wire clk, input wire rst,
    input  wire start, output wire busy,
    input  wire [DIM_W-1:0] nj, input wire [NB_W-1:0] nb, input wire [M_W-1:0] nm,
    input  wire [1:0] ss_log2,
    input  wire nbr_en,
    input  wire bm_valid, output wire bm_ready,
    input  wire [NBMAX-1:0] bm_a, input wire [NBMAX-1:0] bm_occ,
    output wire out_valid, input wire out_ready,
    output wire [M_W-1:0] out_m, output wire [DIM_W-1:0] out_j, output wire [PB_W-1:0] out_pb,
    output wire out_read, output wire out_leave, output wire out_in_a, output wire out_tok,
    output wire out_eor, output wire out_eos, output wire out_last
);
    localparam integer NW = NBMAX;
    localparam integer RW = (MAX_DIM > 1) ? $clog2(MAX_DIM) : 1;     // a row address
    // the kinds of a fetched row: none (the pipeline's fill or its tail), a row of
    // the frame, the flush row
    localparam [1:0] K_NONE = 2'd0, K_ROW = 2'd1, K_FLUSH = 2'd2;

    reg active;                            // between start and the flush row's last beat
    assign busy = active;

    // ==== the bitmaps: four slots, slice mod 4, one {A, OCC} word per row, kept in
    // three copies, one for each slice a fetch reads (slice m - 1: A; m: {OCC, A};
    // m + 1: A), each a RAM of the four slots' rows (word {slot, row}) read at one
    // word per fetch, so no multiplexer among slots lies behind the RAMs. A row's
    // write lands one edge after its take (cube4_sdp_ram WR_REG: the write enable,
    // address and word pass registers, copies of them per 36 bits, so the take's
    // compares reach a few flip-flops, not every cell of the copies). The read
    // passes the RAM's read register and its output register (OUT_REG = 1: on the
    // ECP5 a block RAM with its output register from 128 words on, distributed RAM
    // with fabric registers below), so the copies (4 MAX_DIM words of NBMAX, 2 NBMAX
    // and NBMAX bits) cost block RAMs, not distributed RAM and its read multiplexers,
    // and a fetched row's words come out one fetch after its place (f_*, then f2_*) ====
    reg [M_W-1:0]   wm;                    // the slice being written
    reg [DIM_W-1:0] wj;
    reg [M_W-1:0]   g;                     // the slice being fetched (nm: past the frame)
    reg [DIM_W-1:0] gj;
    // beside g, registers of what the fetch and the writes compare with it (loaded as
    // g moves on), so no adder of g lies before a compare
    reg [M_W:0]     g2;                    // g + 2
    reg             g_in;                  // g < nm: a slice of the frame
    reg             g_last;                // g + 1 >= nm: no slice after it
    reg [M_W-1:0]   need;                  // slice g's rows need slice need written whole:
                                           // g + 1, the last slice itself
    // bm_ready = active && wm < nm && wm <= g2, a register (the FIFO in front
    // takes it into its read pointers and reservations): loaded with its next
    // value, the moves of wm, g2 and active choosing among compares of the
    // registers (wm + 1 <= g2 + 1 is wm <= g2)
    reg  rdy_q;
    assign bm_ready = rdy_q;
    wire bm_take = bm_valid && bm_ready;
    wire wm_mv = bm_take && (wj == nj - 1'b1);   // slice wm is written whole
    wire g_mv;                                   // g (and g2) move on
    wire act_off;                                // the flush row's last beat leaves
    wire [M_W:0] wm_x = {1'b0, wm};
    wire lt0  = (wm_x < {1'b0, nm}),  lt1  = (wm_x + 1'b1 < {1'b0, nm});
    wire le00 = (wm_x <= g2), le10 = (wm_x + 1'b1 <= g2), le01 = (wm_x <= g2 + 1'b1);
    always @(posedge clk) begin
        if (rst)        rdy_q <= 1'b0;
        else if (start) rdy_q <= (nm != '0);
        else            rdy_q <= active && !act_off && (wm_mv ? lt1 : lt0)
                                 && (wm_mv ? (g_mv ? le00 : le10) : (g_mv ? le01 : le00));
    end
`ifndef SYNTHESIS
    always @(posedge clk) begin
        if (!rst && !start && rdy_q != (active && (wm < nm) && ({1'b0, wm} <= g2)))
            $fatal(1, "cube4_cfb_beats: bm_ready %b is not active && wm < nm && wm <= g2 (wm %0d, nm %0d, g2 %0d)",
                   rdy_q, wm, nm, g2);
    end
`endif
    always @(posedge clk) begin
        if (rst || start) begin
            wm <= '0;
            wj <= '0;
        end else if (bm_take) begin
            wj <= (wj == nj - 1'b1) ? '0 : wj + 1'b1;
            if (wm_mv) wm <= wm + 1'b1;
        end
    end
    wire [NW-1:0]   slot_p, slot_n;        // A of slices g - 1, g + 1 (two fetches after the read)
    wire [2*NW-1:0] slot_c;                // {OCC, A} of slice g
    wire            adv;                   // the walk's pipeline moves
    wire [RW+1:0]   slot_wa = {wm[1:0], RW'(wj)};
    cube4_sdp_ram #(.DATA_W(NW), .DEPTH(4 << RW), .WR_REG(1), .OUT_REG(1)) u_slot_p (
        .clk(clk), .rd_en(adv), .out_en(1'b0), .rd_addr({g[1:0] - 2'd1, RW'(gj)}), .rd_data(slot_p),
        .wr_en(bm_take), .wr_addr(slot_wa), .wr_data(bm_a));
    cube4_sdp_ram #(.DATA_W(2 * NW), .DEPTH(4 << RW), .WR_REG(1), .OUT_REG(1)) u_slot_c (
        .clk(clk), .rd_en(adv), .out_en(1'b0), .rd_addr({g[1:0], RW'(gj)}), .rd_data(slot_c),
        .wr_en(bm_take), .wr_addr(slot_wa), .wr_data({bm_occ, bm_a}));
    cube4_sdp_ram #(.DATA_W(NW), .DEPTH(4 << RW), .WR_REG(1), .OUT_REG(1)) u_slot_n (
        .clk(clk), .rd_en(adv), .out_en(1'b0), .rd_addr({g[1:0] + 2'd1, RW'(gj)}), .rd_data(slot_n),
        .wr_en(bm_take), .wr_addr(slot_wa), .wr_data(bm_a));
    genvar s;

    // ==== the fetch: rows of the frame, then the flush row and the tail ====
    wire in_frame = g_in;
    // wm > need as a register (wm_gt), from both next values: the walk's advance
    // (adv, fanned out to every register of the fetch) starts at flip-flops
    reg  wm_gt;
    wire fetch_ok = !in_frame || wm_gt;
    reg  tail;                             // the flush row is fetched: rows past it are none
    reg  flushed;                          // the emitter took the flush row: the fetch stops
    wire take_ok;
    assign adv = active && !flushed && fetch_ok && take_ok;
    assign g_mv = adv && in_frame && (gj == nj - 1'b1);   // g moves on to g + 1
    // need_n: what need becomes when g moves on (g + 2, the last slice g + 1), a
    // register kept one move ahead, so no adder of g lies before wm_gt's compare
    reg  [M_W-1:0] need_n;
    wire [M_W-1:0] need_g = need_n;
    wire [M_W-1:0] need0  = (nm > M_W'(1)) ? M_W'(1) : '0;
    always @(posedge clk) begin
        if (rst || start) need_n <= ((M_W + 1)'(2) < {1'b0, nm}) ? M_W'(2) : M_W'(1);
        else if (g_mv)    need_n <= ({1'b0, g} + (M_W + 1)'(3) < {1'b0, nm}) ? M_W'(g + 2'd3) : M_W'(g + 2'd2);
    end
    always @(posedge clk) begin
        if (rst || start) begin
            g      <= '0;
            g2     <= (M_W + 1)'(2);
            g_in   <= (nm != '0);
            g_last <= (nm <= M_W'(1));
            need   <= need0;
            gj     <= '0;
            tail   <= 1'b0;
        end else if (adv) begin
            if (in_frame) begin
                gj <= (gj == nj - 1'b1) ? '0 : gj + 1'b1;
                if (g_mv) begin
                    g      <= g + 1'b1;
                    g2     <= g2 + 1'b1;
                    g_in   <= !g_last;
                    g_last <= ({1'b0, g} + (M_W + 1)'(2) >= {1'b0, nm});
                    need   <= need_g;
                end
            end else begin
                tail <= 1'b1;
            end
        end
    end
    // wm_gt: the next wm against the next need. A slice's last row lands in its
    // slot an edge after wm counts it, at the edge of the walk's first read of
    // the slice before it: that read is of row 0, and the row landing is row
    // NJ - 1, written, with every row before it, before any read of it, unless
    // NJ = 1; then the slices counted are those landed (wm of now), so the
    // read never meets the write of its own word
    // (wm or wm + 1 against need or need_g: four compares of registers, and the walk's
    // advance (g_mv) and the bitmaps' take (wm_mv), the late ones, choose at the last
    // multiplexer, as for bm_ready; wm < nm, so wm + 1 fits M_W bits)
    reg            nj_one;
    always @(posedge clk) nj_one <= (nj == DIM_W'(1));
    wire           wm_up = wm_mv && !nj_one;
    wire [M_W:0]   wm1_x = wm_x + 1'b1;
    wire gt_n0 = (wm_x > {1'b0, need}),   gt_n1 = (wm1_x > {1'b0, need});
    wire gt_g0 = (wm_x > {1'b0, need_g}), gt_g1 = (wm1_x > {1'b0, need_g});
    always @(posedge clk) begin
        if (rst || start) wm_gt <= 1'b0;                       // wm = 0 is not above need0
        else              wm_gt <= g_mv ? (wm_up ? gt_g1 : gt_g0) : (wm_up ? gt_n1 : gt_n0);
    end
`ifndef SYNTHESIS
    always @(posedge clk) begin
        if (!rst && !start && !nj_one && wm_gt != (wm > need))   // (NJ = 1: the wm before)
            $fatal(1, "cube4_cfb_beats: wm_gt %b is not wm > need (wm %0d, need %0d)", wm_gt, wm, need);
    end
`endif
`ifndef SYNTHESIS
    // no fetch (of slice g: the slots of g - 1, g, g + 1) reads a row in the edge
    // that row's bitmaps land in its slot
    reg             land_we;
    reg [M_W-1:0]   land_m;
    reg [DIM_W-1:0] land_j;
    always @(posedge clk) begin
        land_we <= bm_take && !rst && !start;
        land_m  <= wm;
        land_j  <= wj;
        if (!rst && adv && in_frame && land_we && land_j == gj
                && {1'b0, land_m} + 1'b1 >= {1'b0, g} && land_m <= g + 1'b1) begin
            $error("cube4_cfb_beats: slice %0d row %0d fetched in the edge slice %0d's row lands", g, gj, land_m);
            $fatal(1, "cube4_cfb_beats: a slot read meets its write");
        end
    end
`endif
    // the fetched row's place, beside the slots' read register
    reg [1:0]       f_kind;
    reg [M_W-1:0]   f_m;
    reg [DIM_W-1:0] f_j;
    reg             f_first, f_lastm;  // slice 0 (no slice before), the last slice (none after)
    reg             f_full;            // a pass that reads a voxel slice for the slice buffers (S > 1)
    wire [2:0]      s_m1 = 3'((1 << ss_log2) - 1);     // S - 1
    always @(posedge clk) begin
        if (rst || start) begin
            f_kind <= K_NONE;
        end else if (adv) begin
            f_kind  <= in_frame ? K_ROW : (tail ? K_NONE : K_FLUSH);
            f_m     <= g;
            f_j     <= in_frame ? gj : '0;
            f_first <= (g == '0);
            f_lastm <= g_last;
            f_full  <= (ss_log2 != 2'd0) && ((g == '0) || ((3'(g) & s_m1) == 3'd1));
        end
    end
    // the place one fetch on, beside the slots' output registers
    reg [1:0]       f2_kind;
    reg [M_W-1:0]   f2_m;
    reg [DIM_W-1:0] f2_j;
    reg             f2_first, f2_lastm, f2_full;
    always @(posedge clk) begin
        if (rst || start) f2_kind <= K_NONE;
        else if (adv)     f2_kind <= f_kind;
        if (adv) {f2_m, f2_j, f2_first, f2_lastm, f2_full} <= {f_m, f_j, f_first, f_lastm, f_full};
    end
    // the slots of slices m - 1, m, m + 1 (zero outside the frame)
    wire [NW-1:0] r_p = (f2_kind != K_ROW || f2_first) ? '0 : slot_p;
    wire [NW-1:0] r_c = (f2_kind != K_ROW) ? '0 : slot_c[NW-1:0];
    wire [NW-1:0] r_n = (f2_kind != K_ROW || f2_lastm) ? '0 : slot_n;
    wire [NW-1:0] r_o = (f2_kind != K_ROW) ? '0 : slot_c[2*NW-1:NW];

    // ==== the window: rows k + 1 (0), k (1), k - 1 (2); E of row k ====
    reg [1:0]       w_kind [0:2];
    reg [M_W-1:0]   w_m    [0:2];
    reg [DIM_W-1:0] w_j    [0:2];
    reg [NW-1:0]    w_any  [0:2];          // A of slices m - 1, m, m + 1, ORed
    reg [NW-1:0]    w_a    [0:2];          // A of slice m
    reg [NW-1:0]    w_o    [0:2];          // OCC of slice m
    reg [1:0]       w_full;                // rows k + 1, k: their pass reads whole rows (f_full)
    integer k;
    always @(posedge clk) begin
        if (rst || start) begin
            for (k = 0; k < 3; k = k + 1) w_kind[k] <= K_NONE;
        end else if (adv) begin
            w_kind[0] <= f2_kind;
            for (k = 1; k < 3; k = k + 1) w_kind[k] <= w_kind[k-1];
        end
        if (adv) begin
            w_full <= {w_full[0], f2_full};
            w_m[0] <= f2_m;  w_j[0] <= f2_j;
            w_any[0] <= r_p | r_c | r_n;  w_a[0] <= r_c;  w_o[0] <= r_o;
            for (k = 1; k < 3; k = k + 1) begin
                w_m[k] <= w_m[k-1];  w_j[k] <= w_j[k-1];
                w_any[k] <= w_any[k-1];  w_a[k] <= w_a[k-1];  w_o[k] <= w_o[k-1];
            end
        end
    end
    wire [NW-1:0] nbmask;
    generate
        for (s = 0; s < NW; s = s + 1) begin : g_nbmask
            assign nbmask[s] = (NB_W'(s) < nb);
        end
    endgenerate
    // rows j - 1 and j + 1 count only within row k's slice
    wire same_up = (w_kind[0] == K_ROW) && (w_m[0] == w_m[1]);
    wire same_dn = (w_kind[2] == K_ROW) && (w_m[2] == w_m[1]);
    wire [NW-1:0] near_rows = w_any[1] | (same_up ? w_any[0] : '0) | (same_dn ? w_any[2] : '0);
    wire [NW-1:0] grown = (near_rows | (near_rows << 1) | (near_rows >> 1)) & nbmask;
    wire [NW-1:0] e_k = w_a[1] | ((nbr_en && (w_kind[1] == K_ROW)) ? (w_o[1] & grown) : '0);

    // ==== E of rows k and k - 1, and the reads of row k ====
    reg [1:0]       e_kind;
    reg [M_W-1:0]   e_m;
    reg [DIM_W-1:0] e_j;
    reg [NW-1:0]    e1, e2;                // E(k), E(k - 1)
    reg [NW-1:0]    a1, a2;                // A(k), A(k - 1)
    reg             e_full;                // row k reads all its beats
    always @(posedge clk) begin
        if (rst || start) begin
            e_kind <= K_NONE;
            e1 <= '0;
            e2 <= '0;
            a1 <= '0;
            a2 <= '0;
        end else if (adv) begin
            e_kind <= w_kind[1];
            e1 <= e_k;
            e2 <= e1;
            a1 <= w_a[1];
            a2 <= a1;
        end
        if (adv) begin
            e_m <= (w_kind[1] == K_FLUSH) ? nm : w_m[1];
            e_j <= w_j[1];
            e_full <= (w_kind[1] == K_ROW) && w_full[1];
        end
    end
    wire [NW-1:0] either = e1 | e2;
    wire [NW-1:0] reads  = (e_full ? '1 : (either | (either << 1))) & nbmask;
    wire [NW-1:0] walks  = reads | ((either >> 1) & nbmask);   // and the cover (pb - 1), no reads

    // ==== a queue of two rows between the pipeline and the emitter (the pipeline's
    // enable comes from its registered count, not from the emitter's last bit) ====
    localparam integer RQ_W = 4 * NW + M_W + DIM_W + 4;   // {walks, reads, leave, in_a, m, j, flush, mark, row0, empty}
    reg  [RQ_W-1:0] rq0, rq1;              // rq0 the head
    reg  [1:0]      rq_n;
    assign take_ok = (rq_n != 2'd2);
    wire            rq_push = adv && (e_kind != K_NONE);
    wire [RQ_W-1:0] rq_in = {walks, reads, e2, a2, e_m, e_j, (e_kind == K_FLUSH),
                             (e_kind == K_FLUSH) || (e_j == nj - 1'b1),
                             (e_kind == K_ROW) && (e_j == '0) && (e_m != '0), (walks == '0)};
    wire            rq_pop;
    always @(posedge clk) begin
        if (rst || start) begin
            rq_n    <= 2'd0;
            flushed <= 1'b0;
        end else begin
            rq_n <= rq_n + 2'(rq_push) - 2'(rq_pop);
            if (rq_push && e_kind == K_FLUSH) flushed <= 1'b1;
        end
        // the head: the next row when popped, else the pushed row into the first free place
        if (rq_pop) rq0 <= (rq_n == 2'd2) ? rq1 : rq_in;
        else if (rq_push && rq_n == 2'd0) rq0 <= rq_in;
        if (rq_push && (rq_n - 2'(rq_pop)) == 2'd1) rq1 <= rq_in;
    end

    // ==== the emitter: one beat a cycle, one cycle for a row without reads ====
    // Every output of a beat is a register, formed as the row or the beat before it
    // leaves (from the queue's head at a pop, from the bits left at a transfer): from
    // the emitter into the skid after it (cube4_cfb_skip's u_eskid, placed toward the
    // join) only a route remains, no lowest-bit isolation, reduction or encoder (the
    // crop beat build's path on one placement: the bits left through those LUTs
    // across the die into the skid's entries, 1.5 ns of logic, 6.6 ns of route).
    reg             x_busy;
    reg [NW-1:0]    x_rd, x_leave, x_in_a;
    reg [M_W-1:0]   x_m;
    reg [DIM_W-1:0] x_j;
    reg             x_flush, x_empty;      // the flush row; a row that walks nothing
    reg             x_mark;                // a slice's last row or the flush row: emits when empty
    reg             x_row0;                // row 0 of a slice but the first: emits when empty
    reg [NW-1:0]    x_nx;                  // the bits left after this beat: the row after it
    reg             x_one;                 // x_nx = 0: one bit left (the row's last beat), a register
    function automatic [NW-1:0] strip(input [NW-1:0] w);      // w without its lowest set bit
        strip = w & (w - 1'b1);
    endfunction
    function automatic [PB_W-1:0] index_of(input [NW-1:0] onehot);   // the set bit's index
        integer ib;
        index_of = '0;
        for (ib = 0; ib < NW; ib = ib + 1) begin
            if (onehot[ib]) index_of = index_of | PB_W'(ib);
        end
    endfunction
    // the row at the queue's head, and the next beat of this row: its bits, the bits
    // after it, its lowest set bit (the beat)
    wire [NW-1:0]   h_walks, h_rd, h_leave, h_in_a;
    wire [M_W-1:0]  h_m;
    wire [DIM_W-1:0] h_j;
    wire            h_flush, h_mark, h_row0, h_empty;
    assign {h_walks, h_rd, h_leave, h_in_a, h_m, h_j, h_flush, h_mark, h_row0, h_empty} = rq0;
    wire [NW-1:0]   rq_nx  = strip(h_walks);
    wire [NW-1:0]   x_nx2  = strip(x_nx);
    // the beat this cycle: a walked beat, or the token or marker of a row that walks nothing
    assign out_valid = x_busy;
    wire   x_fire = out_valid && out_ready;
    wire   x_done = x_fire && (x_empty || x_one);
    assign rq_pop = (rq_n != 2'd0) && (!x_busy || x_done);
    // the beat loaded at this edge: the head row's first (rq_pop) or this row's next
    wire [NW-1:0]   n_rd    = rq_pop ? h_rd    : x_rd;
    wire [NW-1:0]   n_leave = rq_pop ? h_leave : x_leave;
    wire [NW-1:0]   n_in_a  = rq_pop ? h_in_a  : x_in_a;
    wire [NW-1:0]   n_low   = rq_pop ? (h_walks & ~rq_nx) : (x_nx & ~x_nx2);
    wire            n_empty = rq_pop ? h_empty : x_empty;
    wire            n_one   = rq_pop ? (rq_nx == '0) : (x_nx2 == '0);
    wire            n_flush = rq_pop ? h_flush : x_flush;
    wire            n_mark  = rq_pop ? h_mark  : x_mark;
    wire            n_row0  = rq_pop ? h_row0  : x_row0;
    reg  [PB_W-1:0] o_pb;
    reg             o_read, o_leave, o_in_a, o_tok, o_eor, o_last, o_eos;
    always @(posedge clk) begin
        if (rst || start) begin
            x_busy <= 1'b0;
        end else begin
            if (rq_pop) begin
                x_busy <= 1'b1;
                {x_rd, x_leave, x_in_a, x_m, x_j, x_flush, x_mark, x_row0, x_empty} <=
                    {h_rd, h_leave, h_in_a, h_m, h_j, h_flush, h_mark, h_row0, h_empty};
                x_nx   <= rq_nx;
            end else if (x_done) begin
                x_busy <= 1'b0;
            end else if (x_fire) begin
                x_nx  <= x_nx2;
            end
            if (rq_pop || (x_fire && !x_done)) begin
                x_one    <= n_one;
                o_pb     <= index_of(n_low);
                o_read   <= !n_empty && ((n_rd & n_low) != '0);
                o_leave  <= !n_empty && ((n_leave & n_low) != '0);
                o_in_a   <= !n_empty && ((n_in_a & n_low) != '0);
                o_tok    <= n_empty && !n_mark && !n_row0;
                o_eor    <= n_empty || n_one;
                o_last   <= n_flush && (n_empty || n_one);
                o_eos    <= n_mark && !n_flush && (n_empty || n_one);
            end
        end
    end
    always @(posedge clk) begin
        if (rst) active <= 1'b0;
        else if (start) active <= 1'b1;
        else if (act_off) active <= 1'b0;
    end
    assign act_off = x_done && x_flush;
    assign out_m     = x_m;
    assign out_j     = x_j;
    assign out_pb    = o_pb;
    assign out_read  = o_read;
    assign out_tok   = o_tok;
    assign out_leave = o_leave;
    assign out_in_a  = o_in_a;
    assign out_eor   = o_eor;
    assign out_last  = o_last;
    assign out_eos   = o_eos;
endmodule
`default_nettype wire

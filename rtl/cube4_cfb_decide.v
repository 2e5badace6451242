`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_decide
// -----------------------------------------------------------------------------
// Purpose
//   The decisions of the beat schedule (docs/numerics.md section 19, "Runs";
//   docs/architecture.md "The front end's plan"), RATE beats a cycle: for
//   every beat (m, j, pb) of the frame, in order, and each position t of it
//   (i = pb P + t < NI), the ray (by, bx) = (j - sty(m) + SY, i - stx(m) + SX)
//     occ    its sample may count: the block table's bit of the sample's
//            first voxel (voxel slice floor(m / S), S = 2^ss_log2), in the
//            volume's blocks of 2^BLOCK_LOG2 voxels
//     run    first <= m < end: (started or occ) and m < end
//     fresh  run and not started (m is the ray's first slice)
//     last   run and m + 1 >= stop (the ray's last slice by its stop)
//     soon   run and m + LAG + 1 >= stop (a report of slice m would not end
//            the ray before its stop: COM writes none for it); COM reads it
//            up to the ray's done slice only (after it, it depends on when
//            the report came)
//   where the ray table's word {tdone, end} holds {0, stop} from the host or
//   {1, d + LAG + 1} from COM's report of slice d (written only where the
//   stop lies beyond it, so end = min(stop, d + LAG + 1)), and started is a
//   bit per ray this unit sets where occ. last and soon look at host words
//   only: they do not depend on when a report arrives. Out: each row's
//   words of A (a position runs) and OCC (a position may count) for
//   cube4_cfb_beats, and, for each group of RATE beats with a running ray
//   (A), each beat's flag and position bits {a, soon, last, fresh, run} for
//   the header (a beat without a running ray has a = 0 and zero bits).
//   A beat of slice m is decided only once COM has written its reports of
//   slices up to m - LAG - 1 (com_m >= m - LAG): a report of a later slice d
//   moves an end to d + LAG + 1 > m and decides slice m alike.
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2: the geometry (cube4_defs.vh; 1..64,
//   2..2048, 4..12, 0..3).
//   BLOCK_LOG2  log2 of the block edge B.        1..4.   Default 2 (B = 4).
//   RATE        beats decided a cycle (pb, pb + 1: cube4_ray_table's RATE).
//                                                1..2.   Default 1.
//   LAG         slices from a report to its use. 2..7.   Default
//               CUBE4_BEAT_LAG (4: the front end with GRA between it and COM
//               needs 4, cube4_defs.vh).
//   Derived: NBK = ceil(MAX_DIM / B) blocks per axis; BK_W its index width.
//
// Latency
//   A beat issued at an edge (its fields into the tables' reads) has its
//   decisions at the sixth edge after (cube4_ray_table's read with
//   OUT_STAGE: its block RAMs' words go into flip-flops before the lanes'
//   picks), registered at the seventh (S7; what needs no ray table word,
//   each position's column and block bit, m + 1 and m + LAG + 1, is
//   registered at S6 beside the word), and its group and row words written
//   into the output FIFOs at the eighth (cube4_credit_fifo, credit-based: a
//   beat is issued only with an entry reserved in each). RATE beats a cycle
//   (a row's last group may hold one). A ray's next beat comes a slice
//   (NJ NB beats) or more after its last (the steps only grow), and its
//   started bit's write is issued six cycles after that beat's issue, so a
//   read issued seven or more cycles after it sees the bit; a slice of fewer
//   than 8 RATE + 2 beats (fewer than nine cycles) waits for the pipeline to
//   drain before its next slice.
//
// Ports
//   start, busy   a frame (its registers stable from start until busy falls)
//   ni, nj, nb, nm   NI, NJ [DIM_W], NB [NB_W], M [M_W] (sample slices)
//   ss_log2       log2 S [2], 0 .. MAX_SS_LOG2
//   sx, sy        SX, SY [DIM_W]
//   bi_base, bi_flip, bj_base, bj_flip, bk_base, bk_flip   the frame's axes
//                 i, j, k in the volume: voxel c = base + x (flip 0) or
//                 base - x (flip 1) [DIM_W]
//   st_valid, st_ready, st_x, st_y   stepx(m), stepy(m) [DIM_W], a slice each
//   blk_we, blk_addr, blk_data   the block table: word {kb, jb} holds the bits
//                 of the blocks along the frame's i axis [NBK] (host, per view)
//   tab_we, tab_addr, tab_data   the ray table's host word (P stops [M_W],
//                 cube4_ray_table's layout); clears the started bits alike
//   rep_*         a report (COM): rep_valid, rep_j, rep_pb, rep_stx, rep_sty,
//                 rep_en [P] per position, rep_end [P*M_W] per position: the
//                 end d + LAG + 1 of a ray done after slice d, not soon
//   com_m         slices whose reports COM has written whole [M_W]; it may count
//                 a slice in the cycle of its last write (the unit registers it,
//                 so its reads come at least a cycle after that write)
//   bm_valid, bm_ready, bm_a, bm_occ    rows of A and OCC [NBMAX]
//   ln_valid, ln_ready, ln_bits   per group of RATE beats with one of A:
//                 beat r at [r*(4P+1) +: 4P+1] = {a, soon, last, fresh, run},
//                 bit t of each the position t
//
// Bit growth and rounding: none (compares, counters, bit words).
// =============================================================================
module cube4_cfb_decide #(
    `CUBE4_SLICE_PARAMS,
    parameter integer BLOCK_LOG2 = 2,
    parameter integer LAG        = `CUBE4_BEAT_LAG,
    parameter integer RATE       = 1,
    `CUBE4_STOP_LAYOUT,
    `CUBE4_BLOCK_LAYOUT
) (
    input  wire clk, input wire rst,
    `CUBE4_DECIDE_IN_PORTS,
    output wire bm_valid, input wire bm_ready, output wire [NBMAX-1:0] bm_a, output wire [NBMAX-1:0] bm_occ,
    output wire ln_valid, input wire ln_ready, output wire [RATE*(4*P+1)-1:0] ln_bits
);
    generate
        `CUBE4_RANGE(g_bad_block, "cube4_cfb_decide", "BLOCK_LOG2", BLOCK_LOG2, 1, 4)
        `CUBE4_RANGE(g_bad_lag, "cube4_cfb_decide", "LAG", LAG, 2, 7)
        `CUBE4_RANGE(g_bad_rate, "cube4_cfb_decide", "RATE", RATE, 1, 2)
    endgenerate
    localparam integer ND = 6;               // stages from issue to the decisions (the tables' read)
    localparam integer NW = NBMAX;
    localparam integer LN = 4 * P + 1;       // a beat's {a, soon, last, fresh, run}
    genvar q, r;
    integer k;

    // ==== issue: (m, j, pb) in order, a slice's steps, the reports it needs ====
    reg              active, issuing;
    reg [M_W-1:0]    m;
    reg [DIM_W-1:0]  kv;                   // m's voxel slice, floor(m / S)
    reg [2:0]        kr;                   // m mod S (S <= 8)
    reg              k_adv;                // the last edge issued a slice's last beat: kv, kr move on
    reg [DIM_W-1:0]  j;
    reg [PB_W-1:0]   pb;
    reg [DIM_W-1:0]  stx, sty;
    reg              have_st;              // this slice's steps are taken
    reg [ND:1]       v;                    // the decision pipeline's valid bits
    reg              v7;                   // S7's valid bit (the decisions registered)
    reg              tiny;                 // NJ NB < 8 RATE + 2: drain between slices
    wire             credit_ln, credit_bm;
    // Where the beat stands in its slice, as registers kept with j and pb (set
    // at start for (0, 0), stepped at an issue from compares of the registers
    // as they stand), so that the issue and the counters' enables start at
    // flops, not behind pb's carry chain
    reg              first_beat;           // j = 0 and pb = 0
    reg              last_pb;              // pb + RATE >= NB: the row's last group
    reg              last_j;               // j = NJ - 1
    reg              last_beat;            // last_pb and last_j: the slice's last group
    wire [NB_W:0]    pb_r  = {1'b0, NB_W'(pb)} + (NB_W + 1)'(RATE);
    wire             lpb_0 = (NB_W + 1)'(RATE) >= {1'b0, nb};            // pb = 0
    wire             lpb_n = pb_r + (NB_W + 1)'(RATE) >= {1'b0, nb};    // pb + RATE
    wire             lj_0  = (nj == DIM_W'(1));                          // j = 0
    wire             lj_n  = (j + 1'b1 == nj - 1'b1);                    // j + 1
    // the flags' next values at an issue
    wire             lpb_nx = last_pb ? lpb_0 : lpb_n;
    wire             lj_nx  = last_pb ? (last_j ? lj_0 : lj_n) : last_j;
    // reports_ok: m <= com_q + LAG, com_q being com_m a cycle late (a read a cycle
    // after the last write): a register, set from com_m's compares with m as it
    // stands and with m + 1, chosen by whether m moves on at this edge (a
    // slice's last issue), so the issue starts at registers, not at a carry chain
    reg              reports_ok;
    wire [M_W:0]     com_lag = {1'b0, com_m} + (M_W + 1)'(LAG);
    wire             m_adv   = issue && last_beat;                    // m moves on at this edge
    // v == 0 (no beat in the decisions' pipeline), a register: v's next value is
    // {v[ND-1:1], issue}
    reg              v_none;
    wire             drained    = !tiny || !first_beat || v_none;
    wire             steps_ok   = !first_beat || have_st;
    // (issuing implies active: set together at start, active cleared only after it)
    wire             issue = issuing && credit_ln && credit_bm && reports_ok && drained && steps_ok;
    assign st_ready = issuing && first_beat && !have_st;
    always @(posedge clk) begin
        if (rst) begin
            active  <= 1'b0;
            issuing <= 1'b0;
            have_st <= 1'b0;
        end else if (start) begin
            active  <= 1'b1;
            issuing <= 1'b1;
            have_st <= 1'b0;
            m <= '0;
            kv <= '0;
            kr <= '0;
            j <= '0;
            pb <= '0;
            first_beat <= 1'b1;
            last_pb <= lpb_0;
            last_j <= lj_0;
            last_beat <= lpb_0 && lj_0;
        end else begin
            if (st_valid && st_ready) begin
                have_st <= 1'b1;
                stx <= st_x;
                sty <= st_y;
            end
            if (issue) begin
                pb <= last_pb ? '0 : pb + PB_W'(RATE);
                last_pb <= lpb_nx;
                last_j <= lj_nx;
                last_beat <= lpb_nx && lj_nx;
                first_beat <= last_beat;
                if (last_pb) j <= last_j ? '0 : j + 1'b1;
                if (last_beat) begin
                    m <= m + 1'b1;
                    have_st <= 1'b0;
                    if (m + 1'b1 == nm) issuing <= 1'b0;
                end
            end
            // the voxel slice moves on after S sample slices, at the edge after the
            // slice's last issue (k_adv): the next slice's first issue waits a cycle
            // for its steps anyway (have_st is cleared with the last issue), so kv
            // is read no earlier, and the issue's AND reaches only k_adv, beside it,
            // not kv's and kr's enables (across the die: a crop beat build's longest
            // path on one placement)
            if (k_adv) begin
                if (kr == 3'((1 << ss_log2) - 1)) begin
                    kr <= '0;
                    kv <= kv + 1'b1;
                end else begin
                    kr <= kr + 1'b1;
                end
            end
            if (!issuing && v == '0 && !v7 && !bm_valid && !ln_valid) active <= 1'b0;
        end
    end
    always @(posedge clk) k_adv <= !(rst || start) && issue && last_beat;
    assign busy = active;
    always @(posedge clk) begin
        // (at start: m = 0, com_q = 0)
        reports_ok <= (rst || start) || (m_adv ? ({1'b0, M_W'(m + 1'b1)} <= com_lag) : ({1'b0, m} <= com_lag));
        v_none     <= (rst || start) || ((v[ND-1:1] == '0) && !issue);
    end
`ifndef SYNTHESIS
    always @(posedge clk) begin
        if (!rst && !start && active && issuing
            && ({first_beat, last_pb, last_j, last_beat}
                != {(j == '0) && (pb == '0), pb_r >= {1'b0, nb}, j == nj - 1'b1, (pb_r >= {1'b0, nb}) && (j == nj - 1'b1)}))
            $fatal(1, "cube4_cfb_decide: the flags {first, last pb, last j, last beat} %b differ from j %0d, pb %0d (NJ %0d, NB %0d)",
                   {first_beat, last_pb, last_j, last_beat}, j, pb, nj, nb);
        if (!rst && issuing && !active)
            $fatal(1, "cube4_cfb_decide: issuing without active");
        if (!rst && !start && issue && k_adv)
            $fatal(1, "cube4_cfb_decide: an issue in the cycle after a slice's last (kv is not yet moved on)");
        if (!rst && !start && active && v_none != (v == '0))
            $fatal(1, "cube4_cfb_decide: v_none %0d with v %b", v_none, v);
    end
    reg [M_W-1:0] com_q;                   // the compare the registers stand for
    always @(posedge clk) com_q <= (rst || start) ? '0 : com_m;
    always @(posedge clk) begin
        if (!rst && active && reports_ok != ({1'b0, m} <= {1'b0, com_q} + (M_W + 1)'(LAG)))
            $fatal(1, "cube4_cfb_decide: reports_ok %0d differs from m <= com_q + LAG (m %0d, com_q %0d)",
                   reports_ok, m, com_q);
    end
`endif
    always @(posedge clk) begin
        tiny <= 32'(nj) * 32'(nb) < 8 * RATE + 2;
    end

    // ==== the beat's fields along the pipeline ====
    reg [M_W-1:0]   m_s   [1:ND];
    reg [PB_W-1:0]  pb_s  [1:ND];
    reg [DIM_W-1:0] j_s   [1:ND];
    reg [DIM_W-1:0] stx_s [1:ND], sty_s [1:ND];
    reg [ND:1]      row_end;               // the row's last beat
    always @(posedge clk) begin
        if (rst || start) v <= '0;
        else v <= {v[ND-1:1], issue};
        m_s[1] <= m;  pb_s[1] <= pb;  j_s[1] <= j;  stx_s[1] <= stx;  sty_s[1] <= sty;
        row_end <= {row_end[ND-1:1], last_pb};
        for (k = 2; k <= ND; k = k + 1) begin
            m_s[k] <= m_s[k-1];  pb_s[k] <= pb_s[k-1];  j_s[k] <= j_s[k-1];
            stx_s[k] <= stx_s[k-1];  sty_s[k] <= sty_s[k-1];
        end
    end

    // ==== the ray table (ends) and the started bits, read at each position ====
    wire [P*LANE_W-1:0] ident;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_ident
            assign ident[q*LANE_W +: LANE_W] = LANE_W'(q);
        end
    endgenerate
    localparam integer EW = M_W + 1;       // {tdone, end}
    wire [P*EW-1:0]      tab_word;
    wire [RATE*P*EW-1:0] rep_word, end_d;
    wire [RATE*P-1:0]    started_d, set_started, rep_en_r;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_words
            assign tab_word[q*EW +: EW] = {1'b0, tab_data[q*M_W +: M_W]};
        end
        for (q = 0; q < RATE * P; q = q + 1) begin : g_rep
            // COM's report is one beat: the first of the write port's RATE
            assign rep_word[q*EW +: EW] = {1'b1, (q < P) ? rep_end[(q % P)*M_W +: M_W] : M_W'(0)};
            assign rep_en_r[q] = (q < P) && rep_en[q % P];
        end
    endgenerate
    // (OUT_STAGE: each block RAM's word into a flip-flop before the lanes' picks;
    // the words at S6 = ND)
    cube4_ray_table #(`CUBE4_SLICE_PASS, .DATA_W(EW), .RATE(RATE), .OUT_STAGE(1)) u_end (
        .clk(clk), .sx(sx), .sy(sy),
        .tab_we(tab_we), .tab_addr(tab_addr), .tab_data(tab_word),
        .rd_j(j), .rd_pb(pb), .rd_tpos(ident), .rd_stx(stx), .rd_sty(sty), .rd_data(end_d),
        .wr_valid(rep_valid), .wr_j(rep_j), .wr_pb(rep_pb), .wr_stx(rep_stx), .wr_sty(rep_sty),
        .wr_en(rep_en_r), .wr_data(rep_word));
    cube4_ray_table #(`CUBE4_SLICE_PASS, .DATA_W(1), .RATE(RATE), .OUT_STAGE(1)) u_started (
        .clk(clk), .sx(sx), .sy(sy),
        .tab_we(tab_we), .tab_addr(tab_addr), .tab_data('0),
        .rd_j(j), .rd_pb(pb), .rd_tpos(ident), .rd_stx(stx), .rd_sty(sty), .rd_data(started_d),
        .wr_valid(v[ND]), .wr_j(j_s[ND]), .wr_pb(pb_s[ND]), .wr_stx(stx_s[ND]), .wr_sty(sty_s[ND]),
        .wr_en(set_started), .wr_data('1));

    // ==== the block table: the word of (m, j)'s blocks along i, and each position's block ====
    function automatic [DIM_W-1:0] vol_coord(input [DIM_W-1:0] base, input flip, input [DIM_W-1:0] x);
        vol_coord = flip ? base - x : base + x;
    endfunction
    wire [DIM_W-1:0] vk = vol_coord(bk_base, bk_flip, kv);
    wire [DIM_W-1:0] vj = vol_coord(bj_base, bj_flip, j);
    reg  [2*BK_W-1:0] blk_ra;
    always @(posedge clk) blk_ra <= {BK_W'(vk >> BLOCK_LOG2), BK_W'(vj >> BLOCK_LOG2)};
    wire [NBK-1:0] blk_q;                  // S2
    cube4_sdp_ram #(.DATA_W(NBK), .DEPTH(1 << (2 * BK_W))) u_blk (
        .clk(clk), .rd_en(1'b1), .out_en(1'b0), .rd_addr(blk_ra), .rd_data(blk_q),
        .wr_en(blk_we), .wr_addr(blk_addr), .wr_data(blk_data));
    reg [NBK-1:0] blk_s3, blk_s4, blk_s5;
    always @(posedge clk) {blk_s5, blk_s4, blk_s3} <= {blk_s4, blk_s3, blk_q};
    wire unused_vk = ^{vk[BLOCK_LOG2-1:0], vj[BLOCK_LOG2-1:0]};

    // ==== S4 -> S6: what does not need the ray table: each position's column
    // (inside the row and its block at S5, from S4's beat), whether its sample
    // may count (the block table's bit), and m + 1, m + LAG + 1 ====
    wire [IW-1:0]      pbp4 = IW'(pb_s[ND-2]) * IW'(P);
    reg  [RATE*P-1:0]  val6, occ6;
    reg  [M_W:0]       m1_6, ml_6;         // m + 1, m + LAG + 1 of S6's beat
    always @(posedge clk) begin
        m1_6 <= {1'b0, m_s[ND-1]} + 1'b1;
        ml_6 <= {1'b0, m_s[ND-1]} + (M_W + 1)'(LAG + 1);
    end
    // Each position's column i = (pb + r) P + t is inside (i < NI) where its
    // partial beam lies below the last one, L, or is L with t below the
    // remainder (CUBE4_LAST_BEAM_FUNCTIONS). L and the remainder
    // are kept registers of the unit's own (view constants, loaded on every
    // edge: stable from a cycle after start, the first beat at S4 five or more
    // edges later), so the test is a compare of pb with L, not of i with NI on
    // a carry chain synthesis may share with another unit's compares of NI
    // (COM's).
    `CUBE4_LAST_BEAM_FUNCTIONS
    wire [NB_W-1:0]   lpb_q;
    wire [LANE_W:0]   lrem_q;
    cube4_prim_reg_copies #(.W(NB_W + LANE_W + 1), .RESET(0), .ENABLE(0)) u_last (
        .clk(clk), .rst(rst), .en(1'b1),
        .d({row_last_pb(nb), row_last_rem(ni, nb)}), .q({lpb_q, lrem_q}));
    generate
        for (q = 0; q < RATE * P; q = q + 1) begin : g_col
            // the position's inside bit and its block along i, from S4's beat
            // into S5 registers (the compare with L and the column's two adds
            // ahead of the block bit's multiplexer)
            wire [NB_W:0]    pbr4 = {1'b0, NB_W'(pb_s[ND-2])} + (NB_W + 1)'(q / P);
            wire             val4 = (pbr4 < {1'b0, lpb_q})
                                 || ((pbr4 == {1'b0, lpb_q}) && ((LANE_W + 1)'(q % P) < lrem_q));
            wire [IW-1:0]    i4  = pbp4 + IW'(q);
            wire [DIM_W-1:0] vi  = vol_coord(bi_base, bi_flip, DIM_W'(i4));
            reg  [BK_W-1:0]  ib5;
            reg              val5;
            always @(posedge clk) begin
                ib5     <= BK_W'(vi >> BLOCK_LOG2);
                val5    <= val4;
                val6[q] <= val5;
                occ6[q] <= val5 && blk_s5[ib5];
            end
`ifndef SYNTHESIS
            wire [NB_W:0] pbr = {1'b0, NB_W'(pb_s[ND-1])} + (NB_W + 1)'(q / P);
            wire [IW-1:0] i   = IW'(pb_s[ND-1]) * IW'(P) + IW'(q);
            always @(posedge clk) begin
                if (!rst && v[ND-1] && val5 != ((i < IW'(ni)) && ((q / P == 0) || (pbr < {1'b0, nb}))))
                    $fatal(1, "cube4_cfb_decide: position %0d's inside bit %0d differs from i < NI (pb %0d, NI %0d)",
                           q, val5, pb_s[ND-1], ni);
            end
`endif
            wire unused_vi = ^{vi[BLOCK_LOG2-1:0], i4};   // (i4's bits above DIM_W: positions past the row)
        end
    endgenerate

    // ==== S6: each beat's positions' decisions (beat r: partial beam pb + r) ====
    wire [RATE*P-1:0]  run6, fresh6, last6, soon6;
    generate
        for (q = 0; q < RATE * P; q = q + 1) begin : g_pos
            wire [M_W-1:0]   e   = end_d[q*EW +: M_W];
            wire             td  = end_d[q*EW + M_W];
            assign run6[q]   = val6[q] && (started_d[q] || occ6[q]) && (m_s[ND] < e);
            assign fresh6[q] = run6[q] && !started_d[q];
            assign last6[q]  = run6[q] && !td && (m1_6 >= {1'b0, e});
            assign soon6[q]  = run6[q] && !td && (ml_6 >= {1'b0, e});
            assign set_started[q] = v[ND] && occ6[q] && !started_d[q];
        end
    endgenerate

    // ==== S7: the decisions registered; each beat of the group in A, may count ====
    reg                row_end7;
    reg  [PB_W-1:0]    pb7;
    reg  [RATE*P-1:0]  run7, occ7, fresh7, last7, soon7;
    always @(posedge clk) begin
        if (rst || start) v7 <= 1'b0;
        else              v7 <= v[ND];
        row_end7 <= row_end[ND];
        pb7      <= pb_s[ND];
        {run7, occ7, fresh7, last7, soon7} <= {run6, occ6, fresh6, last6, soon6};
    end
    wire [RATE-1:0] a7, o7;
    generate
        for (r = 0; r < RATE; r = r + 1) begin : g_beat
            assign a7[r] = run7[r*P +: P] != '0;
            assign o7[r] = occ7[r*P +: P] != '0;
        end
    endgenerate

    // ==== the outputs: a group's bits, a row's words (credit FIFOs, written at S8) ====
    reg  [NW-1:0] row_a, row_o;            // the row so far (S7's beats not yet in)
    wire [NW-1:0] a_add = NW'({{(NW > RATE ? NW - RATE : 0){1'b0}}, a7}) << pb7;
    wire [NW-1:0] o_add = NW'({{(NW > RATE ? NW - RATE : 0){1'b0}}, o7}) << pb7;
    wire [NW-1:0] a_now = row_a | a_add;
    wire [NW-1:0] o_now = row_o | o_add;
    always @(posedge clk) begin
        if (rst || start || (v7 && row_end7)) begin
            row_a <= '0;
            row_o <= '0;
        end else if (v7) begin
            row_a <= a_now;
            row_o <= o_now;
        end
    end
    reg  [NW-1:0]      bm_a8, bm_o8;
    wire [RATE*LN-1:0] ln_w;
    reg  [RATE*LN-1:0] ln8;
    generate
        for (r = 0; r < RATE; r = r + 1) begin : g_ln
            assign ln_w[r*LN +: LN] = {a7[r], soon7[r*P +: P], last7[r*P +: P], fresh7[r*P +: P], run7[r*P +: P]};
        end
    endgenerate
    always @(posedge clk) begin
        bm_a8 <= a_now;
        bm_o8 <= o_now;
        ln8   <= ln_w;
    end
    wire unused_cr_ln, unused_cr_bm, unused_vcp_ln, unused_vcp_bm;
    cube4_credit_fifo #(.DATA_W(RATE * LN), .DEPTH(16)) u_ln (
        .clk(clk), .rst(rst || start), .take(issue), .give(v7 && (a7 == '0)), .credit(credit_ln),
        .credit_d(unused_cr_ln), .push_d(v7 && (a7 != '0)), .in_data(ln8), .out_valid(ln_valid),
        .out_ready(ln_ready), .out_data(ln_bits), .out_valid_cp(unused_vcp_ln));
    cube4_credit_fifo #(.DATA_W(2 * NW), .DEPTH(16)) u_bm (
        .clk(clk), .rst(rst || start), .take(issue), .give(v7 && !row_end7), .credit(credit_bm),
        .credit_d(unused_cr_bm), .push_d(v7 && row_end7), .in_data({bm_o8, bm_a8}),
        .out_valid(bm_valid), .out_ready(bm_ready), .out_data({bm_occ, bm_a}), .out_valid_cp(unused_vcp_bm));
endmodule
`default_nettype wire

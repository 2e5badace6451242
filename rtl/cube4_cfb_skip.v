`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_skip
// -----------------------------------------------------------------------------
// Purpose
//   The beat schedule's front end without its reads (docs/architecture.md
//   "The front end's plan"; S = 2^ss_log2): cube4_cfb_decide decides every beat a
//   slice or two ahead, cube4_cfb_beats walks the voxel beats of each slice
//   from the decisions' bitmaps, and the position bits of the beats that
//   hold a running ray wait between the two in a cube4_ram_fifo (3P + 1 bits a
//   beat: the packed bits, CUBE4_RAY_BITS_FUNCTIONS, and a = run != 0). Each walk
//   beat leaves with the position bits {soon, last, fresh, run} of the
//   sample beat that leaves with it (zero when none leaves, or when it runs
//   as GRA's neighbour only).
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2: the geometry (cube4_defs.vh).
//   BLOCK_LOG2, LAG, RATE: as cube4_cfb_decide (LAG default 3; RATE beats
//             decided a cycle, 1..2, default 1).
//   LN_DEPTH  the position bits' queue (groups of RATE beats), a power of two
//             >= 4 NJ NB / RATE of the largest frame: the decisions run less
//             than four slices ahead of the walk's last beat (bitmaps of slices
//             up to g + 2 while the walk fetches slice g, whose emitter is at
//             most a few rows behind). Default: 4 MAX_DIM NBMAX / RATE rounded up.
//
// Latency
//   As its units, and one cycle: the walk's beats pass a skid buffer (u_eskid,
//   a cube4_skid_peek), the queue's items one too (u_qskid), then one register-free
//   join (out_valid is the walk skid's valid and, where the leaving beat holds
//   a running ray, the queue skid's valid: both registers).
//
// Ports
//   As cube4_cfb_decide's inputs (the frame, the steps, the tables, COM's
//   reports), and the walk: out_valid, out_ready, out_m, out_j, out_pb,
//   out_read, out_leave, out_tok, out_eor, out_eos, out_last (cube4_cfb_beats) and out_bits
//   {soon, last, fresh, run} [4*P] of the leaving beat.
//   out_ready_q  a register copy of out_ready (equal to it) for the queue's
//            side of the join (out_ready drives the walk skid's pop)
//   nbr_en   E with GRA's neighbours (termination in a GRA frame)
//
// Bit growth and rounding: none.
// =============================================================================
module cube4_cfb_skip #(
    `CUBE4_SLICE_PARAMS,
    parameter integer BLOCK_LOG2 = 2,
    parameter integer LAG        = `CUBE4_BEAT_LAG,
    parameter integer RATE       = 1,
    parameter integer LN_DEPTH   = 1 << $clog2((4 * MAX_DIM * ((MAX_DIM + P - 1) / P) + RATE - 1) / RATE),
    `CUBE4_STOP_LAYOUT,
    `CUBE4_BLOCK_LAYOUT
) (
    input  wire clk, input wire rst,
    `CUBE4_DECIDE_IN_PORTS,
    input  wire nbr_en,
    output wire out_valid, input wire out_ready, input wire out_ready_q,
    output wire [M_W-1:0] out_m, output wire [DIM_W-1:0] out_j, output wire [PB_W-1:0] out_pb,
    output wire out_read, output wire out_leave, output wire out_tok, output wire out_eor,
    output wire out_eos, output wire out_last,
    output wire [4*P-1:0] out_bits
);
    wire            busy_d, busy_w;
    wire            bm_valid, bm_ready;
    wire [NBMAX-1:0] bm_a, bm_occ;
    localparam integer LN = 4 * P + 1;     // a beat's {a, soon, last, fresh, run}
    // a beat in the queue: {a, its packed bits}; a (= run != 0) is carried as a bit of
    // its own, so that the queue's head says which beats it holds from a register,
    // not from an OR of the unpacked run bits
    localparam integer QN = 3 * P + 1;
    `CUBE4_RAY_BITS_FUNCTIONS
    wire            ln_valid, ln_ready, q_valid, q_ready;
    wire [RATE*LN-1:0] ln_bits, q_bits;
    wire [RATE*QN-1:0] ln_packed, q_packed;
    genvar r;
    generate
        for (r = 0; r < RATE; r = r + 1) begin : g_pack
            assign ln_packed[r*QN +: QN] = {ln_bits[r*LN + 4*P], ray_bits_pack(ln_bits[r*LN +: 4*P])};
            assign q_bits[r*LN +: LN]    = {q_packed[r*QN + QN - 1], ray_bits_unpack(q_packed[r*QN +: QN - 1])};
        end
    endgenerate
    cube4_cfb_decide #(`CUBE4_SLICE_PASS, .BLOCK_LOG2(BLOCK_LOG2), .LAG(LAG), .RATE(RATE)) u_decide (
        .clk(clk), .rst(rst), .start(start), .busy(busy_d),
        .ni(ni), .nj(nj), .nb(nb), .nm(nm), .ss_log2(ss_log2), .sx(sx), .sy(sy),
        .bi_base(bi_base), .bi_flip(bi_flip), .bj_base(bj_base), .bj_flip(bj_flip),
        .bk_base(bk_base), .bk_flip(bk_flip),
        .st_valid(st_valid), .st_ready(st_ready), .st_x(st_x), .st_y(st_y),
        .blk_we(blk_we), .blk_addr(blk_addr), .blk_data(blk_data),
        .tab_we(tab_we), .tab_addr(tab_addr), .tab_data(tab_data),
        .rep_valid(rep_valid), .rep_j(rep_j), .rep_pb(rep_pb), .rep_stx(rep_stx), .rep_sty(rep_sty),
        .rep_en(rep_en), .rep_end(rep_end), .com_m(com_m),
        .bm_valid(bm_valid), .bm_ready(bm_ready), .bm_a(bm_a), .bm_occ(bm_occ),
        .ln_valid(ln_valid), .ln_ready(ln_ready), .ln_bits(ln_bits));
    // (the block RAMs' word through their output registers: OUT_REG)
    // (its items pass a skid buffer beside the join: the join's pop, logic of the
    // walk skid's head, reaches the skid's few state flip-flops, not the enables of
    // the queue's register queue (4 RATE QN flip-flops) across the die, the default
    // beat build's longest path on one placement; the queue's pop is the skid's
    // ready, a register)
    wire            r_valid, r_ready;
    wire [RATE*QN-1:0] r_packed;
    cube4_ram_fifo #(.DATA_W(RATE * QN), .DEPTH(LN_DEPTH), .OUT_REG(1)) u_queue (
        .clk(clk), .rst(rst || start),
        .in_valid(ln_valid), .in_ready(ln_ready), .in_data(ln_packed),
        .out_valid(r_valid), .out_ready(r_ready), .out_data(r_packed));
    // (its valid in three copies, one per side of the join: q_vc)
    wire [2:0] q_vc;
    wire [RATE*QN-1:0] unused_q_nx;
    wire unused_q_nv, unused_q_rc, unused_q_rn;
    cube4_skid_peek #(.DATA_W(RATE * QN), .VALID_N(3)) u_qskid (
        .clk(clk), .rst(rst || start),
        .in_valid(r_valid), .in_ready(r_ready), .in_data(r_packed),
        .out_valid(q_valid), .out_ready(q_ready), .out_data(q_packed),
        .nx_valid(unused_q_nv), .nx_data(unused_q_nx), .in_ready_cp(unused_q_rc),
        .in_ready_nx(unused_q_rn), .out_valid_cp(q_vc));
    wire e_valid, e_ready, e_leave, e_in_a, e_read, e_tok, e_eor, e_eos, e_last;
    wire [M_W-1:0]   e_m;
    wire [DIM_W-1:0] e_j;
    wire [PB_W-1:0]  e_pb;
    cube4_cfb_beats #(`CUBE4_SLICE_PASS) u_walk (
        .clk(clk), .rst(rst), .start(start), .busy(busy_w),
        .nj(nj), .nb(nb), .nm(nm), .ss_log2(ss_log2), .nbr_en(nbr_en),
        .bm_valid(bm_valid), .bm_ready(bm_ready), .bm_a(bm_a), .bm_occ(bm_occ),
        .out_valid(e_valid), .out_ready(e_ready), .out_m(e_m), .out_j(e_j), .out_pb(e_pb),
        .out_read(e_read), .out_leave(e_leave), .out_in_a(e_in_a), .out_tok(e_tok), .out_eor(e_eor), .out_eos(e_eos),
        .out_last(e_last));
    // the walk's beats pass a skid buffer before they meet the queue: the
    // emitter's ready is a register, and whether a beat takes the queue's bits
    // (need) is a register bit beside it, not logic of the emitter's state
    localparam integer WK_W = M_W + DIM_W + PB_W + 7;
    // (its valid in three copies, one per side of the join: w_vc)
    wire w_valid, w_ready, w_leave, need;
    wire [2:0] w_vc;
    wire [WK_W-1:0] unused_w_nx;
    wire unused_w_nv, unused_w_rc, unused_w_rn;
    cube4_skid_peek #(.DATA_W(WK_W), .VALID_N(3)) u_eskid (
        .clk(clk), .rst(rst || start),
        .in_valid(e_valid), .in_ready(e_ready),
        .in_data({e_m, e_j, e_pb, e_read, e_leave, e_leave && e_in_a, e_tok, e_eor, e_eos, e_last}),
        .out_valid(w_valid), .out_ready(w_ready),
        .out_data({out_m, out_j, out_pb, out_read, w_leave, need, out_tok, out_eor, out_eos, out_last}),
        .nx_valid(unused_w_nv), .nx_data(unused_w_nx), .in_ready_cp(unused_w_rc),
        .in_ready_nx(unused_w_rn), .out_valid_cp(w_vc));
    wire unused_nx = ^{unused_q_nx, unused_q_nv, unused_q_rc, unused_q_rn, q_vc[0],
                       unused_w_nx, unused_w_nv, unused_w_rc, unused_w_rn, w_vc[0]};   // (= q_valid, w_valid)
    // a walk beat whose leaving beat holds a running ray (need) takes that beat's
    // bits: the next beat with a = 1 of the queue's head group (from beat `half` on)
    reg  half;                             // RATE = 2: the head's first beat is taken
    wire a0   = q_bits[LN-1] && !half;
    wire [0:0] pick = (RATE > 1 && !a0) ? 1'b1 : 1'b0;
    wire [LN-1:0] beat = q_bits[32'(pick)*LN +: LN];
    wire unused_a = beat[LN-1];            // a = 1 here: the queue holds groups with one of A
    // the group is used up after this beat: its last one, or the first with no a = 1 after it
    wire more = (RATE > 1) && !pick && q_bits[(RATE - 1)*LN + LN - 1];
    // The join reads the two skids' valid and the consumer's ready (out_ready,
    // out_ready_q: copies of one register) from a copy per side: the walk skid's
    // pop (w_ready), the queue skid's pop (take) and the consumer's push
    // (out_valid) each end in LUTs of their own, placed beside their skid, so
    // a path runs from a register copy across to one side, not from three
    // registers to a LUT between the skids and back (the crop beat build's path
    // on one placement, from the walk skid's read pointer: 0.7 ns of logic,
    // 7.8 ns of route).
    wire take = out_ready_q && w_vc[1] && need && q_valid;
    assign out_valid = w_vc[2] && (!need || q_vc[2]);
    assign w_ready   = out_ready && (!need || q_vc[1]);
    assign q_ready   = take && !more;
    always @(posedge clk) begin
        if (rst || start) half <= 1'b0;
        else if (take)    half <= more;
    end
    assign out_leave = w_leave;
    assign out_bits  = need ? beat[4*P-1:0] : '0;
    assign busy      = busy_d || busy_w || w_valid;
endmodule
`default_nettype wire

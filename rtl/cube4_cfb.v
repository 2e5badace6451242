`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb
// -----------------------------------------------------------------------------
// Purpose
//   The CFB of Cube-4 (Teramac paper, section 5, Fig. 12): the traversal unit
//   (pass / beam / partial-beam counters), the template unit (incremental
//   resampling weights, X/Y steps from the carry), the address unit (one
//   address per bank for the partial beam being read, any of the six major
//   viewing directions and any slope signs, from the one skewed memory image)
//   and the control unit (the bits that travel with the data to TRI and on).
//   It issues one memory request beat per partial beam; the memory returns the
//   voxels with the beat's tag, and cube4_tri turns beats into samples.
//
//   Schedule (docs/architecture.md, "Front end"): passes m = 0 .. M-1, one per
//   sample slice, M = (NK - 1) * S + 1, pass m = k0 * S + r. Each pass walks
//   beams j = 0 .. NJ-1 and partial beams pb = 0 .. NB-1. Voxel slice k is
//   read from memory exactly once: by pass 0 (k = 0, as the lower slice) or by
//   the pass k0 * S + 1 with k0 = k - 1 (as the upper slice); with S = 1 every
//   pass reads its own slice. Sample row j of pass m leaves with beam j + 1, and
//   row NJ-1 with beam 0 of the next pass (Y-wrap: the row above is zero); a
//   last "flush" beam (NB beats, no reads) emits the last row of the frame and
//   one "drain" beat pushes the beam-extension delay of cube4_tri empty.
//   Beats per frame: (M * NJ + 1) * NB + 1.
//
//   Slice rectangles (RECTS = 1, S = 1 only; numerics.md section 18): pass m
//   walks only rows J0 .. JL of its entry in the rectangle table (written by
//   the host through rect_we / rect_addr / rect_data, layout CUBE4_RECT_LAYOUT)
//   and partial beams PB0 .. PBL, reads the positions I_LO <= i < I_HI of rows
//   TJ0 .. TJL (the other rows are walked for GRA, with no read and no lane
//   valid; JL may be NJ), and marks the lanes below I_IN, the rows below J_IN
//   and the row TJL when wy > 0 as not inside (tag LINL).
//   Its last row leaves with the next pass's first beam when that pass walks
//   the same partial beams; otherwise (entry FLUSH) a flush beam of its own
//   emits it before the next pass. An EMPTY pass takes one cycle and issues
//   nothing; the flush beam of the LAST pass ends the frame. Beats per frame:
//   golden/cube4/slices.py SliceRects.beats.
//   The table is read one pass ahead (the next entry is always ready).
//
//   Beat skipping and ray termination (BEATS = 1; numerics.md section 19):
//   cube4_cfb_skip decides every beat (the block table, the ray
//   table's stops and COM's reports) and walks the voxel beats the running
//   sample beats read; cube4_cfb_bctl turns its beats into requests in place
//   of the control and traversal units, with the box as every pass's
//   rectangle, and cube4_cfb_steps gives the decisions each slice's steps;
//   with S > 1 the passes that read a voxel slice walk all their rows (the
//   others replay the slices from TRI's slice buffers, as the fixed schedule).
//   Request beats per frame: the walk's beats but its tokens, and the drain
//   beat, a push beat after each slice's last beat and after each sample
//   slice's last; each carries its emitted beat's position bits, EOS and
//   EOSS (req_bits, req_eos, req_eoss).
//
//   Lane q reads bank q, at the address of the position t of the partial beam
//   that it holds (eq. 1; cube4_cfb_addr, golden/cube4/memory.py).
//
//   A thin top of units (docs/architecture.md "Front end"):
//     u_ctl    cube4_cfb_ctl: the state, its moves, the fields of the beat it
//              describes (the emitted row: the row below or a pass's last)
//     u_trav   cube4_cfb_trav: pass, row and partial-beam counters, the
//              per-axis address terms and the lanes' skews
//     u_tmpl   cube4_cfb_tmpl: the template (phases, weights, X/Y steps)
//     u_steps, u_skip, u_bctl  (BEATS = 1) in place of u_ctl and u_trav: the
//              slices' steps (through u_sskid, a cube4_skid: the decisions'
//              take of a slice's steps reaches a register, not the steps'
//              counters), the decisions and walk, the walk's beats as the
//              state (through u_wskid, a cube4_skid: one cycle); u_steps
//              and u_skip start an edge after u_bctl takes the frame (two
//              register copies of go)
//     u_rect   cube4_cfb_rect (RECTS = 1): the rectangle table, one pass ahead
//     u_box    cube4_cfb_box (RECTS = 0): the whole box as the pass's entry
//     u_addr   cube4_cfb_addr: lane positions t and one address per bank
//     u_mask   cube4_cfb_mask: the beat pipeline, lane masks and read enables
//
// Parameters (derived widths and layouts: cube4_defs.vh)
//   P            pipelines = memory banks.                 1..64.  Default 8.
//   MAX_DIM      largest volume dimension on any axis.      2..2048. Default 256.
//   ADDR_W       memory address width (words per bank).     1..30.  Default 16.
//   WEIGHT_W     resampling weight width W (Q0.W).          4..12.  Default 8.
//   MAX_SS_LOG2  log2 of the largest supersampling S.       0..3.   Default 0.
//   RECTS        1: slice rectangles (a frame needs S = 1). 0..1.   Default 0.
//   BEATS        1: the beat schedule (RECTS = 0).               0..1.
//                Default 0.
//   RATE         BEATS = 1: beats decided a cycle (cube4_cfb_decide). 1..2.
//                Default 2.
//   The block table's blocks are 4 voxels on a side (BLOCK_LOG2 = 2,
//   golden/cube4/beats.py BLOCK).
//
// Latency
//   Three register stages: a beat leaves (req_valid) three cycles after the
//   state that describes it. s1 registers the beat's fields, each lane's
//   position t and A_j + A_k; s2 adds the partial-beam term (base address);
//   the output register adds the lane's +/-(t*I_LIN + [t > I_RT]) from a
//   table of P entries (cube4_cfb_addr); the lane masks are compared at s2
//   (cube4_cfb_mask). All three stages and the
//   state move under one enable (the output register free or accepted by
//   req_ready); req_valid never depends on req_ready.
//
// Ports (formats as in docs/numerics.md; cfg and cfg_addr are the host's
// view and address registers, laid out in cube4_defs.vh, see
// golden/cube4/memory.py frontend_regs; stable from start until done)
//   clk, rst         clock, synchronous active-high reset (control state only)
//   start            in   pulse: start a frame (ignored while busy)
//   busy             out  a frame is being issued (state or s1, s2 hold a beat)
//   cfg              in   [VIEW_W]  NI, NJ, NK, NB, flips, log2 S, VIEW_X/Y
//                                   (Q1.W), lane residues J_R0, K_R0, I_R1, I_RT,
//                                   the starting phases PH0_X/Y (W + log2 S bits)
//   cfg_addr         in   [9*ADDR_W] address start values and strides
//   req_valid/ready                 memory request handshake; req_ready
//                                   [CFB_ADV_N] equal copies, one per group
//                                   of the stall enable's loads (cube4_cfb_mask)
//   req_addr         out  [P*ADDR_W] word address per bank (lane q at q*ADDR_W)
//   req_rden         out  [P]       read bank q (0: padding or no read this beat)
//   req_tag          out  [TAG_W]   the beat's control bits (CUBE4_TAG_LAYOUT)
//   rect_we, rect_addr [M_W], rect_data [RECT_W]
//                    in   the rectangle table (RECTS = 1): entry rect_addr =
//                         sample slice; written while idle (unused when RECTS = 0)
//   blk_*, tab_*, rep_*, com_m, blk_base, nbr_en
//                    in   BEATS = 1: the decisions' tables, COM's reports and
//                         the frame's axes (CUBE4_BEATS_IN_PORTS; cube4_cfb_decide)
//   req_bits [4P], req_eos, req_eoss  out  BEATS = 1: with each request, the
//                         position bits {soon, last, fresh, run} of the sample
//                         beat it emits (cube4_cfb_skip), its walk beat's EOS,
//                         and EOSS: that sample beat is its slice's last
//
// Bit growth and rounding
//   None: counters and modular address arithmetic (ADDR_W bits, exact for
//   every enabled lane; disabled lanes may wrap and are never read). The phase
//   accumulators are W + log2 S bits and wrap by design (the carry is the step).
// =============================================================================
module cube4_cfb #(
    `CUBE4_CFB_PARAMS,
    parameter integer BEATS = 0,
    parameter integer RATE  = 2,
    localparam integer BLOCK_LOG2 = 2,
    `CUBE4_STOP_LAYOUT,
    `CUBE4_BLOCK_LAYOUT
) (
    input  wire clk, input wire rst,
    input  wire start, output wire busy,
    input  wire [VIEW_W-1:0]    cfg,        // view registers (cube4_defs.vh)
    input  wire [ADR_W_ALL-1:0] cfg_addr,   // address registers (cube4_defs.vh)
    input  wire rect_we, input wire [M_W-1:0] rect_addr, input wire [RECT_W-1:0] rect_data,
    `CUBE4_BEATS_IN_PORTS,
    output wire [4*P-1:0] req_bits, output wire req_eos, output wire req_eoss,   // BEATS = 1: with each request
    // memory request stream; the tag travels with the beat to cube4_tri
    output wire req_valid, input wire [CFB_ADV_N-1:0] req_ready, output wire [TAG_W-1:0] req_tag,
    output wire [P*ADDR_W-1:0] req_addr,
    output wire [P-1:0] req_rden
);
    // ---- parameter checks ----
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_cfb", "P", P, 1, 64)
        `CUBE4_RANGE(g_bad_max_dim, "cube4_cfb", "MAX_DIM", MAX_DIM, 2, 2048)
        `CUBE4_RANGE(g_bad_addr_w, "cube4_cfb", "ADDR_W", ADDR_W, 1, 30)
        `CUBE4_RANGE(g_bad_weight_w, "cube4_cfb", "WEIGHT_W", WEIGHT_W, 4, 12)
        `CUBE4_RANGE(g_bad_ss, "cube4_cfb", "MAX_SS_LOG2", MAX_SS_LOG2, 0, 3)
        `CUBE4_RANGE(g_bad_rects, "cube4_cfb", "RECTS", RECTS, 0, 1)
        `CUBE4_RANGE(g_bad_beats, "cube4_cfb", "BEATS", BEATS, 0, 1)
        if (BEATS != 0 && RECTS != 0) begin : g_beats_rects
            $error("cube4_cfb: BEATS = 1 needs RECTS = 0 (two schedules)");
        end
    endgenerate
    `CUBE4_VIEW_FIELDS(cfg);

    // ==== what the control gives the template, the address unit and the lane masks ====
    wire              idle, next_pass, issue;
    wire [CFB_ADV_N-1:0] advance;       // copies: CFB_ADV_CTL, _BITS, _ADDR, _MASK, _STEP (CUBE4_CFB_LAYOUT)
    wire [CFB_F1_W-1:0] fields;
    wire              use_prev, rowv, rowin, rd;
    wire [LANE_W-1:0] skew_out, skew_rd;
    wire [DIM_W-1:0]  p_ilo, p_iin, p_ihi;
    wire [RECT_W-1:0] rt_cur, rt_nxt;
    wire [CFB_R_W-1:0] r;
    wire [IW-1:0]     pbp;
    wire [ADDR_W-1:0] pbx, aj, ak;
    wire [WEIGHT_W-1:0] wx, wy, wz;
    wire [3:0]        steps;
    wire              mask_busy;

    generate
        if (BEATS != 0) begin : g_beats
            // ==== the beat schedule: steps, decisions and walk, the walk's beats ====
            wire go, busy_s;
            // the steps and the skipping unit start an edge after the control takes the
            // frame (go, logic of every unit's busy): their start resets the decisions,
            // the position bits' queue, the walk and its skid, so it reaches them from
            // flip-flops (a copy each), not through the busy logic across the units
            wire [1:0] go_q;
            cube4_prim_copies #(.N(2), .W(1)) u_go (.clk(clk), .rst(rst), .d(go), .q(go_q));
            wire s0_valid, s0_ready;
            wire [DIM_W-1:0] s0_x, s0_y;
            cube4_cfb_steps #(
                .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W)
            ) u_steps (
                .clk(clk), .rst(rst), .cfg(cfg), .start(go_q[0]),
                .st_valid(s0_valid), .st_ready(s0_ready), .st_x(s0_x), .st_y(s0_y));
            // the steps a slice ahead of the decisions, which take one a slice: the
            // skid's ready is a register (the steps hold two items there from the
            // frame's second cycle on, so the decisions never wait for one); a
            // frame's start empties it with the steps (go_q[0])
            wire st_valid, st_ready;
            wire [DIM_W-1:0] st_x, st_y;
            cube4_skid #(.DATA_W(2 * DIM_W)) u_sskid (
                .clk(clk), .rst(rst || go_q[0]),
                .in_valid(s0_valid), .in_ready(s0_ready), .in_data({s0_x, s0_y}),
                .out_valid(st_valid), .out_ready(st_ready), .out_data({st_x, st_y}));
            wire w_valid, w_ready, w_read, w_leave, w_tok, w_eor, w_eos, w_last;
            wire [M_W-1:0]   w_m;
            wire [DIM_W-1:0] w_j;
            wire [PB_W-1:0]  w_pb;
            wire [4*P-1:0]   w_bits;
            // the frame's sample slices M = (NK - 1) S + 1 and log2 S
            `CUBE4_VIEW_SLICES;
            cube4_cfb_skip #(
                .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2),
                .BLOCK_LOG2(BLOCK_LOG2), .RATE(RATE)
            ) u_skip (
                .clk(clk), .rst(rst), .start(go_q[1]), .busy(busy_s),
                .ni(cfg_ni), .nj(cfg_nj), .nb(cfg_nb), .nm(view_m_last + 1'b1), .ss_log2(view_ssl), .sx(cfg_sx), .sy(cfg_sy),
                .bi_base(blk_base[0 +: DIM_W]), .bi_flip(cfg_flip_i),
                .bj_base(blk_base[DIM_W +: DIM_W]), .bj_flip(cfg_flip_j),
                .bk_base(blk_base[2*DIM_W +: DIM_W]), .bk_flip(cfg_flip_k),
                .st_valid(st_valid), .st_ready(st_ready), .st_x(st_x), .st_y(st_y),
                .blk_we(blk_we), .blk_addr(blk_addr), .blk_data(blk_data),
                .tab_we(tab_we), .tab_addr(tab_addr), .tab_data(tab_data),
                .rep_valid(rep_valid), .rep_j(rep_j), .rep_pb(rep_pb), .rep_stx(rep_stx), .rep_sty(rep_sty),
                .rep_en(rep_en), .rep_end(rep_end), .com_m(com_m),
                .nbr_en(nbr_en),
                .out_valid(w_valid), .out_ready(w_ready), .out_ready_q(w_ready_q), .out_m(w_m), .out_j(w_j), .out_pb(w_pb),
                .out_read(w_read), .out_leave(w_leave), .out_tok(w_tok), .out_eor(w_eor), .out_eos(w_eos),
                .out_last(w_last),
                .out_bits(w_bits));
            wire unused_walk = ^{w_m, w_j};   // the control keeps its own slice and row
            // the walk's beats reach the control through a skid buffer: its ready (the
            // state's stall enable) and the walk's valid (the decisions' queue) meet
            // at registers, not in one path across both units
            localparam integer WB_W = PB_W + 6 + 4 * P;
            wire b_valid, b_ready, b_read, b_leave, b_tok, b_eor, b_eos, b_last;
            wire [PB_W-1:0] b_pb;
            wire [4*P-1:0]  b_bits;
            // (its ready in two copies: w_ready to the walk skid's side of u_skip's
            // join, w_ready_q to the queue's)
            wire             w_ready_q, unused_w_r0, unused_w_nv, unused_w_rn, unused_w_vc;
            wire [WB_W-1:0]  unused_w_nx;
            cube4_skid_peek #(.DATA_W(WB_W), .READY_N(2)) u_wskid (
                .clk(clk), .rst(rst),
                .in_valid(w_valid), .in_ready(w_ready),
                .in_data({w_pb, w_read, w_leave, w_tok, w_eor, w_eos, w_last, w_bits}),
                .out_valid(b_valid), .out_ready(b_ready),
                .out_data({b_pb, b_read, b_leave, b_tok, b_eor, b_eos, b_last, b_bits}),
                .nx_valid(unused_w_nv), .nx_data(unused_w_nx), .in_ready_cp({w_ready_q, unused_w_r0}),
                .in_ready_nx(unused_w_rn), .out_valid_cp(unused_w_vc));
            wire unused_wskid = ^{unused_w_r0, unused_w_nv, unused_w_nx, unused_w_rn, unused_w_vc};
            wire [4*P-1:0] x_bits;
            wire           x_eos, x_eoss;
            cube4_cfb_bctl #(
                .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W)
            ) u_bctl (
                .clk(clk), .rst(rst), .cfg(cfg), .cfg_addr(cfg_addr),
                .start(start), .busy(busy), .go(go),
                .in_valid(b_valid), .in_ready(b_ready), .in_pb(b_pb), .in_read(b_read), .in_leave(b_leave),
                .in_tok(b_tok),
                .in_eor(b_eor), .in_eos(b_eos), .in_last(b_last), .in_bits(b_bits),
                .advance(advance[CFB_ADV_CTL]), .advance_step(advance[CFB_ADV_STEP]),
                .wx(wx), .wy(wy), .wz(wz), .steps(steps),
                .idle(idle), .next_pass(next_pass), .r(r),
                .issue(issue), .fields(fields), .use_prev(use_prev), .skew_out(skew_out),
                .p_ilo(p_ilo), .p_iin(p_iin), .p_ihi(p_ihi), .rowv(rowv), .rowin(rowin), .rd(rd),
                .pbp(pbp), .skew_rd(skew_rd), .aj(aj), .ak(ak), .pbx(pbx),
                .x_bits(x_bits), .x_eos(x_eos), .x_eoss(x_eoss));
            cube4_cfb_box #(
                .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W)
            ) u_box (
                .cfg(cfg), .cfg_addr(cfg_addr), .last_pass(1'b0), .rt_cur(rt_cur), .rt_nxt(rt_nxt));
            wire unused_beats = ^{rt_nxt, rect_we, rect_addr, rect_data};
            // the beat's bits, EOS and EOSS pass the mask's three stages beside it
            reg [4*P+1:0] x1_q, x2_q, x_q;
            always @(posedge clk) begin
                if (advance[CFB_ADV_BITS]) begin
                    x1_q <= {x_eoss, x_eos, x_bits};
                    x2_q <= x1_q;
                    x_q  <= x2_q;
                end
            end
            assign {req_eoss, req_eos, req_bits} = x_q;
            assign busy = mask_busy || busy_s || b_valid;
        end else begin : g_fixed
            wire unused_adv_bits = ^{advance[CFB_ADV_BITS], advance[CFB_ADV_STEP]};   // (BEATS = 1 only)
            // ==== control and traversal of the fixed, box and rectangle schedules ====
            wire              go, pass_done, pass_next, row, flush_row;
            wire [M_W-1:0]    m;
            wire [DIM_W-1:0]  j;
            wire [PB_W-1:0]   pb;
            wire [SB_W-1:0]   sb;
            wire              k0_odd, last_pb, last_j, last_pass, lower_mem, upper_mem;
            wire [LANE_W-1:0] skew_pas, skew_vrt;
            cube4_cfb_ctl #(
                .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W),
                .RECTS(RECTS)
            ) u_ctl (
                .clk(clk), .rst(rst), .cfg(cfg), .start(start), .busy(busy), .advance(advance[CFB_ADV_CTL]),
                .rt_cur(rt_cur), .rt_nxt(rt_nxt),
                .m(m), .k0_odd(k0_odd), .r(r), .j(j), .pb(pb), .sb(sb), .last_pb(last_pb), .last_j(last_j),
                .lower_mem(lower_mem), .upper_mem(upper_mem), .skew_pas(skew_pas), .skew_vrt(skew_vrt),
                .wx(wx), .wy(wy), .wz(wz), .steps(steps),
                .idle(idle), .go(go), .next_pass(next_pass), .pass_done(pass_done),
                .pass_next(pass_next), .row(row), .flush_row(flush_row), .issue(issue), .fields(fields),
                .use_prev(use_prev), .skew_out(skew_out), .p_ilo(p_ilo), .p_iin(p_iin), .p_ihi(p_ihi),
                .rowv(rowv), .rowin(rowin), .rd(rd));
            cube4_cfb_trav #(
                .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W),
                .RECTS(RECTS)
            ) u_trav (
                .clk(clk), .rst(rst), .cfg(cfg), .cfg_addr(cfg_addr), .rt_cur(rt_cur), .rt_nxt(rt_nxt),
                .idle(idle), .advance(advance[CFB_ADV_CTL]), .pass_next(pass_next), .row(row), .flush_row(flush_row),
                .m(m), .k0_odd(k0_odd), .r(r), .j(j), .pb(pb), .sb(sb), .pbp(pbp), .pbx(pbx), .aj(aj), .ak(ak),
                .last_pb(last_pb), .last_j(last_j), .last_pass(last_pass),
                .lower_mem(lower_mem), .upper_mem(upper_mem),
                .skew_rd(skew_rd), .skew_pas(skew_pas), .skew_vrt(skew_vrt));
            // ==== the pass's rectangle: the table (RECTS = 1) or the box ====
            if (RECTS != 0) begin : g_rects
                cube4_cfb_rect #(
                    .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W)
                ) u_rect (
                    .clk(clk), .rect_we(rect_we), .rect_addr(rect_addr), .rect_data(rect_data),
                    .idle(idle), .go(go), .pass_done(pass_done), .m(m), .rt_cur(rt_cur), .rt_nxt(rt_nxt));
                wire unused_rects = last_pass;   // the table's LAST ends the frame
            end else begin : g_box
                cube4_cfb_box #(
                    .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W)
                ) u_box (
                    .cfg(cfg), .cfg_addr(cfg_addr), .last_pass(last_pass), .rt_cur(rt_cur), .rt_nxt(rt_nxt));
                wire unused_box = ^{rect_we, rect_addr, rect_data, go, pass_done};
            end
            assign {req_eoss, req_eos, req_bits} = '0;
            assign busy = mask_busy;
            wire unused_fixed = ^{blk_base, nbr_en, blk_we, blk_addr, blk_data, tab_we, tab_addr, tab_data,
                                  rep_valid, rep_j, rep_pb, rep_stx, rep_sty, rep_en, rep_end, com_m};
        end
    endgenerate

    // ==== the template ====
    cube4_cfb_tmpl #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W)
    ) u_tmpl (
        .clk(clk), .rst(rst), .cfg(cfg), .idle(idle), .next_pass(next_pass), .r(r),
        .wx(wx), .wy(wy), .wz(wz), .steps(steps));

    // ==== addresses, lane masks, the request stream ====
    wire [P*LANE_W-1:0] t1;
    cube4_cfb_addr #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W)
    ) u_addr (
        .clk(clk), .cfg(cfg), .cfg_addr(cfg_addr), .advance(advance[CFB_ADV_ADDR]), .skew_rd(skew_rd),
        .aj(aj), .ak(ak), .pbx(pbx), .t1(t1), .addr(req_addr));
    cube4_cfb_mask #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .ADDR_W(ADDR_W),
        .RECTS(RECTS)
    ) u_mask (
        .clk(clk), .rst(rst), .cfg(cfg), .idle(idle), .issue(issue), .fields(fields),
        .use_prev(use_prev), .skew_out(skew_out), .p_ilo(p_ilo), .p_iin(p_iin), .p_ihi(p_ihi),
        .rowv(rowv), .rowin(rowin), .rd(rd), .rt_cur(rt_cur), .pbp(pbp), .t1(t1),
        .advance(advance), .busy(mask_busy),
        .req_valid(req_valid), .req_ready(req_ready), .req_rden(req_rden), .req_tag(req_tag));
endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_mask
// -----------------------------------------------------------------------------
// Purpose
//   The beat pipeline of cube4_cfb and its lane masks: the beat's fields
//   (cube4_cfb_ctl) travel s1 -> s2 -> output register with their valid bits;
//   s2 adds the per-lane bits of the tag (CUBE4_TAG_LAYOUT) and the bank read
//   enables. A lane's position i = pb*P + t is in [lo, hi) exactly when
//   lo - pb*P <= t < hi - pb*P: the differences are registered at s1 (clamped
//   to 0 .. P + 1: t + 1 <= P), with the lanes' positions t of both rows, and
//   the compares run at s2 on registers only. The read row takes pass m's
//   positions (I_LO .. I_HI of rt_cur); the emitted row its own pass's
//   (use_prev: the kept p_*). Per lane:
//     rden   the read row's lane reads (rd and I_LO <= i < I_HI)
//     LVAL   the emitted row's lane holds a sample (rowv and I_LO <= i < I_HI)
//     LNBR   position i + 1 is below I_HI;  LWRAP  t = P - 1
//     LINL   the sample is not below the low sides (rowin and i >= I_IN)
//
// Parameters (CUBE4_CFB_PARAMS; ranges as cube4_cfb)
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2, ADDR_W.
//
// Latency
//   Three register stages; a beat is on req_* three edges after the state
//   that describes it. All stages move under advance = the output register
//   is free or taken by req_ready; req_valid never depends on req_ready.
//   advance comes as CFB_ADV_N equal copies, each from its own copy of the
//   output register's valid bit and its own copy of req_ready, one per group
//   of its loads (CUBE4_CFB_LAYOUT), so no one net reaches the stages, the
//   address unit and the control's counters; each valid copy's next value
//   is logic of its own, not its advance net (cube4_prim_valid_copies).
//
// Ports (past clk, rst and the register buses: CUBE4_CFB_MASK_PORTS)
//   clk, rst     clock, synchronous active-high reset (the valid bits only)
//   cfg          in   [VIEW_W] view registers (I flip, I_R1)
//   idle, issue  in   the control unit is idle; its state describes a beat
//   fields       in   [TAG_W - 4P] the beat's tag fields (cube4_cfb_ctl)
//   use_prev, skew_out, p_ilo, p_iin, p_ihi, rowv, rowin, rd   in  the
//                emitted row's and the read row's (cube4_cfb_ctl)
//   rt_cur       in   [RECT_W] pass m's rectangle (I_LO, I_IN, I_HI; with
//                RECTS = 0 the box, whose I_HI = NI the unit reads through
//                registers loaded on every edge: stable from a cycle before
//                the frame's first beat, as cfg's NB)
//   pbp          in   [IW] pb * P (cube4_cfb_trav)
//   t1           in   [P*LANE_W] s1: the read row's lane positions (cube4_cfb_addr)
//   advance      out  [CFB_ADV_N] the stages move (copies);  busy  out  idle is
//                low or s1, s2 hold a beat
//   req_valid / req_ready   the request handshake; req_ready [CFB_ADV_N]
//                equal copies, copy c into advance c (the front end's are
//                register copies of its skids' ready)
//   req_rden     out  [P] bank q reads;  req_tag  out  [TAG_W] the tag
//
// Bit growth and rounding: none (compares in IW bits, clamped remainders).
// =============================================================================
module cube4_cfb_mask #(`CUBE4_CFB_PARAMS) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    `CUBE4_CFB_MASK_PORTS
);
    // the entries (the box's constant fields as constants: CUBE4_CFB_ENTRY)
    wire [RECT_W-1:0] cur = `CUBE4_CFB_ENTRY(rt_cur);
    `CUBE4_VIEW_FIELDS(cfg);
    `CUBE4_LANE_FUNCTIONS
    `CUBE4_LAST_BEAM_FUNCTIONS
    localparam integer REM_W = $clog2(P + 2);               // 0 .. P + 1
    localparam integer F_W   = P + TAG_W;
    wire unused_rt = ^cur;   // the fields besides I_LO, I_IN, I_HI

    function automatic [REM_W-1:0] rem_of(input [DIM_W-1:0] bound, input [IW-1:0] pbp_v);
        reg [IW-1:0] b, diff;            // IW >= DIM_W: the bound zero-extended
        begin
            b = IW'(bound);
            diff = b - pbp_v;
            rem_of = (b <= pbp_v) ? {REM_W{1'b0}} : (diff > IW'(P + 1)) ? REM_W'(P + 1) : REM_W'(diff);
        end
    endfunction
    // I_HI's remainders. Without rectangles (RECTS = 0) every pass's I_HI is NI
    // (cube4_cfb_box), a view constant, and pbp = pb P: with L the last partial
    // beam (CUBE4_LAST_BEAM_FUNCTIONS) the remainder is P + 1 below L P
    // (NI - pbp >= NI - L P + P > P), row_last_rem in it (1 .. P) and 0 past it
    // (pbp >= L P + P >= NI). L P and row_last_rem are kept registers of the
    // unit's own (loaded on every edge: stable from a cycle before the frame's
    // first beat; a simulation check holds them to I_HI's), so one compare
    // of pbp with L takes the place of a subtraction and its compares, and
    // synthesis merges none of them with another unit's of NI (COM's).
    wire [REM_W-1:0] hi_rd_d, hi_prev_d;
    generate
    if (RECTS != 0) begin : g_ihi_rects
        assign hi_rd_d   = rem_of(cur[RT_IHI +: DIM_W], pbp);
        assign hi_prev_d = rem_of(p_ihi, pbp);
    end else begin : g_ihi_box
        wire [IW-1:0]    last_d = IW'(row_last_pb(cfg_nb)) * IW'(P);
        wire [IW-1:0]    last_q;
        wire [REM_W-1:0] rlast_q;
        cube4_prim_reg_copies #(.W(IW + REM_W), .RESET(0), .ENABLE(0)) u_last (
            .clk(clk), .rst(rst), .en(1'b1),
            .d({last_d, REM_W'(row_last_rem(cfg_ni, cfg_nb))}), .q({last_q, rlast_q}));
        assign hi_rd_d   = (pbp == last_q) ? rlast_q : (pbp < last_q) ? REM_W'(P + 1) : {REM_W{1'b0}};
        assign hi_prev_d = hi_rd_d;
        wire unused_ihi = ^p_ihi;
`ifndef SYNTHESIS
        always @(posedge clk) begin
            if (!rst && issue && hi_rd_d != rem_of(cur[RT_IHI +: DIM_W], pbp))
                $fatal(1, "cube4_cfb_mask: the box's I_HI remainder %0d differs from rem_of %0d (pbp %0d)",
                       hi_rd_d, rem_of(cur[RT_IHI +: DIM_W], pbp), pbp);
        end
`endif
    end
    endgenerate
    wire [REM_W-1:0] lo_rd_d  = rem_of(cur[RT_ILO +: DIM_W], pbp);
    // (the emitted row's: both candidates' remainders, selected after them, so
    // that the state's use_prev is not in series with the subtraction)
    wire [REM_W-1:0] hi_out_d = use_prev ? hi_prev_d : hi_rd_d;
    wire [REM_W-1:0] lo_out_d = use_prev ? rem_of(p_ilo, pbp) : lo_rd_d;
    wire [REM_W-1:0] in_out_d = use_prev ? rem_of(p_iin, pbp) : rem_of(cur[RT_IIN +: DIM_W], pbp);
    wire [P*LANE_W-1:0] tout_d;       // lane positions t of the emitted row

    reg [CFB_F1_W-1:0]     f1_q;
    reg [P*LANE_W-1:0] tout1_q;
    reg [REM_W-1:0]    hi_rd1_q, lo_rd1_q, hi_out1_q, lo_out1_q, in_out1_q;
    reg                rowin1_q, rowv1_q, rd1_q;
    wire [P-1:0]       rden_2, lval_2, lnbr_2, lwrap_2, linl_2;
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            assign tout_d[q*LANE_W +: LANE_W] = lane_pos(q, skew_out, cfg_flip_i, cfg_i_r1);
            wire [REM_W-1:0] tr = REM_W'(t1[q*LANE_W +: LANE_W]);
            wire [REM_W-1:0] to = REM_W'(tout1_q[q*LANE_W +: LANE_W]);
            assign rden_2[q]  = rd1_q && (tr < hi_rd1_q) && (tr >= lo_rd1_q);
            assign lval_2[q]  = rowv1_q && (to < hi_out1_q) && (to >= lo_out1_q);
            assign lnbr_2[q]  = (to + 1'b1 < hi_out1_q);
            assign lwrap_2[q] = (to == REM_W'(P - 1));
            assign linl_2[q]  = rowin1_q && (to >= in_out1_q);
        end
    endgenerate

    reg           v1_q, v2_q;
    wire [CFB_ADV_N-1:0] v_cp;            // the output register's valid bit, a copy per advance
    reg [F_W-1:0] f2_q, f_q;
`ifndef SYNTHESIS
    always @(posedge clk) begin
        if (!rst && req_ready != '0 && req_ready != '1)
            $fatal(1, "cube4_cfb_mask: the copies of req_ready differ (%b)", req_ready);
    end
`endif
    wire   adv     = advance[CFB_ADV_MASK];
    // advance[c] = ~v_cp[c] | req_ready[c]; each copy's own next value is logic
    // beside it, not the advance net that reaches copy c's loads
    cube4_prim_valid_copies #(.COPIES(CFB_ADV_N)) u_v (
        .clk(clk), .rst(rst), .d(v2_q), .ready(req_ready), .q(v_cp), .adv(advance));
    always @(posedge clk) begin
        if (rst) begin
            v1_q <= 1'b0;
            v2_q <= 1'b0;
        end else if (adv) begin
            v1_q <= issue;
            v2_q <= v1_q;
        end
    end
    always @(posedge clk) begin
        if (adv) begin
            // s1
            f1_q      <= fields;
            tout1_q   <= tout_d;
            hi_rd1_q  <= hi_rd_d;
            lo_rd1_q  <= lo_rd_d;
            hi_out1_q <= hi_out_d;
            lo_out1_q <= lo_out_d;
            in_out1_q <= in_out_d;
            rowin1_q  <= rowin;
            rowv1_q   <= rowv;
            rd1_q     <= rd;
            // s2
            f2_q <= {rden_2, linl_2, lval_2, lnbr_2, lwrap_2, f1_q};
            // output register
            f_q  <= f2_q;
        end
    end

    assign busy      = !idle || v1_q || v2_q;
    assign req_valid = v_cp[CFB_ADV_MASK];
    assign {req_rden, req_tag} = f_q;   // f2: {rden, LINL, LVAL, LNBR, LWRAP, f1}
endmodule
`default_nettype wire

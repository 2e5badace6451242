`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_ctl
// -----------------------------------------------------------------------------
// Purpose
//   The control unit of cube4_cfb: the state (idle, run, flush beam, drain
//   beat; docs/architecture.md "Front end"), what a state advance does to the
//   traversal counters (cube4_cfb_trav) and the template (cube4_cfb_tmpl), and
//   the fields of the beat the state describes, in the tag's order
//   (CUBE4_TAG_LAYOUT, MSB first, without the lane masks). The row a beat
//   emits is the row below (j - 1) or, at a pass's first beam and in the
//   flush beam, the last row of the pass before (use_prev): its fields,
//   weights, steps, skew and rectangle are kept from that pass's last beat.
//   The pass's rectangle is rt_cur (cube4_cfb_rect or cube4_cfb_box): RUN
//   ends after its last partial beam of its last row (or at once when EMPTY);
//   a FLUSH pass adds a flush beam, the LAST pass the drain beat.
//
// Parameters (CUBE4_CFB_PARAMS; ranges as cube4_cfb)
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2, ADDR_W.
//
// Latency
//   The state and the kept fields are registers that move under advance (the
//   state's beat leaves); everything else is combinational from registers
//   (here, in cube4_cfb_trav and cube4_cfb_tmpl, rt_cur) and start / busy.
//
// Ports (past clk, rst and the register buses: CUBE4_CFB_CTL_PORTS)
//   clk, rst     clock, synchronous active-high reset (resets the state only)
//   cfg          in   [VIEW_W] view registers (NJ)
//   start, busy  in   start a frame (taken while not busy); cube4_cfb's busy
//   advance      in   the state's beat leaves (cube4_cfb_mask)
//   rt_cur, rt_nxt  in  [RECT_W] the rectangles of pass m and of the next pass
//   m, k0_odd, r, j, pb, sb, last_pb, last_j, lower_mem, upper_mem,
//   skew_pas, skew_vrt   in  the traversal unit's (cube4_cfb_trav)
//   wx, wy, wz [W] (Q0.W), steps [4]   in  the template's (cube4_cfb_tmpl)
//   idle, go, next_pass, pass_done, row, flush_row   out  the state's
//                moves (cube4_cfb_trav, _tmpl, _rect)
//   pass_next    out  the state's beat ends its pass and a next pass follows:
//                next_pass without advance, for the traversal's row
//                registers, whose next value it selects while advance is only
//                their enable (so advance, which comes from the request
//                stream's ready, does not pass through their next-value logic)
//   issue        out  the state describes a beat
//   fields       out  [TAG_W - 4P] the beat's tag fields (CUBE4_TAG_LAYOUT)
//   use_prev     out  the emitted row is the last row of a pass before
//   skew_out     out  [LANE_W] the emitted row's skew
//   p_ilo, p_iin, p_ihi  out  [DIM_W] that pass's I_LO, I_IN, I_HI
//   rowv, rowin  out  the emitted row holds samples / is inside (rows)
//   rd           out  the beat reads memory (RUN, a read pass, a sample row)
//
// Bit growth and rounding: none (compares and counters).
// =============================================================================
module cube4_cfb_ctl #(`CUBE4_CFB_PARAMS) (
    input  wire clk, input wire rst, input wire [VIEW_W-1:0] cfg,
    `CUBE4_CFB_CTL_PORTS
);
    // the entries (the box's constant fields as constants: CUBE4_CFB_ENTRY)
    wire [RECT_W-1:0] cur = `CUBE4_CFB_ENTRY(rt_cur);
    wire [RECT_W-1:0] nxt = `CUBE4_CFB_ENTRY(rt_nxt);
    `CUBE4_VIEW_FIELDS(cfg);

    localparam [1:0] ST_IDLE = 2'd0, ST_RUN = 2'd1, ST_FLUSH = 2'd2, ST_DRAIN = 2'd3;
    reg [1:0]          state_q;
    reg                fr_q;       // j is the pass's first row
    reg                pend_q;     // the previous pass's last row waits for this pass's first beam
    reg                sopp_q;     // no row emitted yet in this frame
    // the previous pass, for the row emitted at beam 0 and in the flush beam
    reg [WEIGHT_W-1:0] pwx_q, pwy_q, pwz_q;
    reg [3:0]          psteps_q;
    reg [LANE_W-1:0]   pskew_q;
    // and its rectangle's rows and positions: {JL, J_IN, TJ0, TJL, I_LO, I_IN, I_HI}
    function automatic [7*DIM_W-1:0] rows_of(input [RECT_W-1:0] e);
        rows_of = {e[RT_JL +: DIM_W], e[RT_JIN +: DIM_W], e[RT_TJ0 +: DIM_W], e[RT_TJL +: DIM_W],
                   e[RT_ILO +: DIM_W], e[RT_IIN +: DIM_W], e[RT_IHI +: DIM_W]};
    endfunction
    reg [7*DIM_W-1:0]  prow_q;
    wire [DIM_W-1:0]   p_jl, p_jin, p_tj0, p_tjl;
    assign {p_jl, p_jin, p_tj0, p_tjl, p_ilo, p_iin, p_ihi} = prow_q;

    wire             e_empty = cur[RT_EMPTY];
    wire             e_last  = cur[RT_LAST];
    wire [DIM_W-1:0] e_tj0   = cur[RT_TJ0 +: DIM_W];
    wire [DIM_W-1:0] e_tjl   = cur[RT_TJL +: DIM_W];
    wire unused_ctl = ^{cur, nxt};   // the fields cube4_cfb_trav reads

    // ---- the state's moves ----
    wire in_run   = (state_q == ST_RUN);
    wire in_flush = (state_q == ST_FLUSH);
    wire run_end  = in_run && (e_empty || (last_pb && last_j));   // pass m's last beat
    wire run_out  = run_end && !e_empty;                          // ... that emits a row
    assign idle      = (state_q == ST_IDLE);
    assign go        = start && !busy;
    wire   pass_end  = (run_end && (e_empty || !cur[RT_FLUSH])) || (in_flush && last_pb);
    assign pass_done = advance && pass_end;
    assign pass_next = pass_end && !e_last;
    assign next_pass = advance && pass_next;
    assign row       = in_run && last_pb && !last_j && !e_empty;
    assign flush_row = run_out;

    // ---- the beat described by the state ----
    assign issue    = !idle && !(in_run && e_empty);
    assign use_prev = fr_q || in_flush;            // emitted row is the last of a pass before
    assign skew_out = use_prev ? pskew_q : skew_pas;
    wire              emit_d = in_run ? (!fr_q || pend_q) : in_flush;
    wire [M_W-1:0]    mout_d = (in_run && fr_q) ? m - 1'b1 : m;   // flush: m stays
    wire [DIM_W-1:0]  jout_c = j - 1'b1;                  // the row below this pass's beam
    wire [DIM_W-1:0]  jout_d = use_prev ? p_jl : jout_c;
    // the emitted row holds samples (TJ0 .. TJL); inside: not below J_IN, and not
    // the last sample row when wy > 0 (the box's high-face rule, numerics.md 4)
    // (each candidate's compares, selected after them, so that the state's
    // use_prev is not in series with the compares)
    wire [WEIGHT_W-1:0] wy_out  = use_prev ? pwy_q : wy;
    wire rowv_p  = (p_jl >= p_tj0) && (p_jl <= p_tjl);
    wire rowv_c  = (jout_c >= e_tj0) && (jout_c <= e_tjl);
    wire rowin_p = (p_jl >= p_jin) && !((p_jl == p_tjl) && (pwy_q != '0));
    wire rowin_c = (jout_c >= cur[RT_JIN +: DIM_W]) && !((jout_c == e_tjl) && (wy != '0));
    assign rowv  = use_prev ? rowv_p : rowv_c;
    assign rowin = use_prev ? rowin_p : rowin_c;
    assign rd    = in_run && (lower_mem || upper_mem) && (j >= e_tj0) && (j <= e_tjl);
    assign fields = {emit_d, emit_d && sopp_q, in_flush && last_pb && e_last, use_prev,
                     in_run, in_run && lower_mem, in_run && upper_mem, in_run && (r != '0),
                     k0_odd, sb, pb,
                     use_prev ? pwx_q : wx, wy_out, use_prev ? pwz_q : wz,
                     mout_d, jout_d, skew_out, (jout_d == cfg_nj - 1'b1),   // row NJ - 1
                     use_prev ? psteps_q : steps};

    // ---- state update ----
    always @(posedge clk) begin
        if (rst) begin
            state_q <= ST_IDLE;
        end else if (idle) begin
            // Idle: the counters hold their first values all the time, so
            // start only moves the state (start and busy reach no counter).
            if (go) state_q <= ST_RUN;
            fr_q    <= 1'b1;
            pend_q  <= 1'b0;
            sopp_q  <= 1'b1;
            prow_q  <= rows_of(nxt);
        end else if (advance) begin
            if (issue && emit_d) sopp_q <= 1'b0;
            if (row) fr_q <= 1'b0;   // the next row
            if (run_out) begin
                // pass m's last beat: remember its emitted row's fields
                pwx_q    <= wx;
                pwy_q    <= wy;
                pwz_q    <= wz;
                psteps_q <= steps;
                pskew_q  <= skew_vrt;
                prow_q   <= rows_of(cur);
                fr_q     <= 1'b0;
                if (cur[RT_FLUSH]) state_q <= ST_FLUSH;
            end
            if (pass_end) begin                  // pass_done (under advance)
                pend_q  <= in_run && !e_empty;   // no flush: the next pass's first beam emits it
                fr_q    <= 1'b1;
                state_q <= e_last ? ST_DRAIN : ST_RUN;
            end
            if (state_q == ST_DRAIN) state_q <= ST_IDLE;   // one beat
        end
    end
endmodule
`default_nettype wire

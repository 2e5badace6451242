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
//   The table is read one pass ahead (the RAM's address is the next pass's
//   index + 1, so the next entry is always in its output register).
//
//   Lane q reads bank q. With c_i, c_j, c_k the volume coordinates along the
//   traversal axes, lane q holds the position t of the partial beam with
//   (c_i + c_j + c_k) mod P = q (eq. 1):
//     t = (q - skew) mod P              (i not flipped)
//     t = (I_R1 + skew - q) mod P       (i flipped), skew = (c_j + c_k) mod P
//   and reads address  A_j(c_j) + A_k(c_k) + I_A0 +/- (pb*I_PB + t*I_LIN + [t > I_RT])
//   with the per-axis terms kept incrementally (golden/cube4/memory.py); the
//   partial-beam term is kept with its sign and I_A0 folded in (pbx_q).
//
// Parameters (derived widths and layouts: cube4_defs.vh)
//   P            pipelines = memory banks.                 1..64.  Default 8.
//   MAX_DIM      largest volume dimension on any axis.      2..2048. Default 256.
//   ADDR_W       memory address width (words per bank).     1..30.  Default 16.
//   WEIGHT_W     resampling weight width W (Q0.W).          4..12.  Default 8.
//   MAX_SS_LOG2  log2 of the largest supersampling S.       0..3.   Default 0.
//   RECTS        1: slice rectangles (a frame needs S = 1). 0..1.   Default 0.
//
// Latency
//   Three register stages: a beat leaves (req_valid) three cycles after the
//   state that describes it. s1 registers the beat's fields, each lane's
//   position t and A_j + A_k; s2 adds the partial-beam term (base address);
//   the output register adds the lane's +/-(t*I_LIN + [t > I_RT]) from a
//   table of P entries (lin_tab_q, recomputed every cycle from cfg_i_lin and
//   cfg_i_rt, which are stable during a frame). All three stages and the
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
//   req_valid/ready                 memory request handshake
//   req_addr         out  [P*ADDR_W] word address per bank (lane q at q*ADDR_W)
//   req_rden         out  [P]       read bank q (0: padding or no read this beat)
//   req_tag          out  [TAG_W]   the beat's control bits (CUBE4_TAG_LAYOUT)
//   rect_we, rect_addr [M_W], rect_data [RECT_W]
//                    in   the rectangle table (RECTS = 1): entry rect_addr =
//                         sample slice; written while idle (unused when RECTS = 0)
//
// Bit growth and rounding
//   None: counters and modular address arithmetic (ADDR_W bits, exact for
//   every enabled lane; disabled lanes may wrap and are never read). The phase
//   accumulators are W + log2 S bits and wrap by design (the carry is the step).
// =============================================================================
module cube4_cfb #(
    parameter integer P        = 8, parameter integer MAX_DIM     = 256,
    parameter integer WEIGHT_W = 8, parameter integer MAX_SS_LOG2 = 0,
    parameter integer ADDR_W   = 16, parameter integer RECTS       = 0,
    `CUBE4_GEOMETRY, `CUBE4_VIEW_LAYOUT, `CUBE4_ADDR_LAYOUT, `CUBE4_TAG_LAYOUT,
    `CUBE4_RECT_LAYOUT
) (
    input  wire clk, input wire rst,
    input  wire start, output wire busy,
    input  wire [VIEW_W-1:0]    cfg,        // view registers (cube4_defs.vh)
    input  wire [ADR_W_ALL-1:0] cfg_addr,   // address registers (cube4_defs.vh)
    input  wire rect_we, input wire [M_W-1:0] rect_addr, input wire [RECT_W-1:0] rect_data,
    // memory request stream; the tag travels with the beat to cube4_tri
    output wire req_valid, input wire req_ready, output wire [TAG_W-1:0] req_tag,
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
    endgenerate

    localparam integer PH_W = PHASE_W;                  // phase accumulator (cube4_defs.vh)
    localparam integer R_W  = (MAX_SS_LOG2 > 0) ? MAX_SS_LOG2 : 1;
    localparam integer REM_W = $clog2(P + 2);               // 0 .. P + 1
    localparam [LANE_W:0] PL = P[LANE_W:0];

    `CUBE4_VIEW_FIELDS(cfg);
    wire [ADDR_W-1:0] cfg_j_a0  = cfg_addr[ADR_J_A0 +: ADDR_W];
    wire [ADDR_W-1:0] cfg_j_lin = cfg_addr[ADR_J_LIN +: ADDR_W];
    wire [ADDR_W-1:0] cfg_j_blk = cfg_addr[ADR_J_BLK +: ADDR_W];
    wire [ADDR_W-1:0] cfg_k_a0  = cfg_addr[ADR_K_A0 +: ADDR_W];
    wire [ADDR_W-1:0] cfg_k_lin = cfg_addr[ADR_K_LIN +: ADDR_W];
    wire [ADDR_W-1:0] cfg_k_blk = cfg_addr[ADR_K_BLK +: ADDR_W];
    wire [ADDR_W-1:0] cfg_i_a0  = cfg_addr[ADR_I_A0 +: ADDR_W];
    wire [ADDR_W-1:0] cfg_i_pb  = cfg_addr[ADR_I_PB +: ADDR_W];
    wire [ADDR_W-1:0] cfg_i_lin = cfg_addr[ADR_I_LIN +: ADDR_W];
    `CUBE4_LANE_FUNCTIONS

    // step a coordinate by +/-1: (c mod P, address term)
    function automatic [LANE_W-1:0] r_step(input [LANE_W-1:0] r, input down);
        begin
            if (down) r_step = (r == '0) ? PL[LANE_W-1:0] - 1'b1 : r - 1'b1;
            else      r_step = ({1'b0, r} == PL - 1'b1) ? '0 : r + 1'b1;
        end
    endfunction
    function automatic [ADDR_W-1:0] a_step(input [ADDR_W-1:0] a, input [LANE_W-1:0] r,
                                           input down, input [ADDR_W-1:0] lin,
                                           input [ADDR_W-1:0] blk);
        begin
            if (down) a_step = a - ((r == '0) ? blk : lin);
            else      a_step = a + (({1'b0, r} == PL - 1'b1) ? blk : lin);
        end
    endfunction
    function automatic [LANE_W-1:0] add_p(input [LANE_W-1:0] a, input [LANE_W-1:0] b);
        add_p = mod_p($signed({3'b000, a}) + $signed({3'b000, b}));
    endfunction

    // resampling weight = phase bits g .. g+W-1 (the g guard bits are below)
    function automatic [WEIGHT_W-1:0] phase_weight(input [PH_W-1:0] ph, input [1:0] gg);
        reg [PH_W-1:0] sh;
        begin
            sh = ph >> gg;
            phase_weight = sh[WEIGHT_W-1:0];
        end
    endfunction

    // ------------------------------------------------------------------ state
    localparam [1:0] ST_IDLE = 2'd0, ST_RUN = 2'd1, ST_FLUSH = 2'd2, ST_DRAIN = 2'd3;
    reg [1:0]          state_q;
    reg [M_W-1:0]      m_q;        // pass (sample slice)
    reg [DIM_W-1:0]    k0_q;       // lower voxel slice of the pass
    reg [R_W-1:0]      r_q;        // m mod S
    reg [DIM_W-1:0]    j_q;        // beam
    reg [PB_W-1:0]     pb_q;       // partial beam
    reg                lpb_q;      // pb_q is the last partial beam (NB - 1)
    reg                lj_q;       // j_q is the last beam (NJ - 1)
    reg [SB_W-1:0]     sb_q;       // j * NB + pb
    reg [IW-1:0]       pbp_q;      // pb * P
    reg [ADDR_W-1:0]   pbx_q;      // I_A0 - pb * I_PB (i flipped), pb * I_PB (not)
    reg [LANE_W-1:0]   rj_q;       // c_j mod P
    reg [ADDR_W-1:0]   aj_q;       // A_j(c_j)
    reg [LANE_W-1:0]   rk_q;       // c_k mod P of the next slice to read
    reg [ADDR_W-1:0]   ak_q;       // A_k(c_k) of the next slice to read
    reg [LANE_W-1:0]   rk0_q;      // c_k mod P of the pass's lower slice
    reg [PH_W-1:0]     phx_q, phy_q;  // template phases of pass m
    reg                old_sx_q, old_sy_q;
    // the previous pass, for the row emitted at beam 0 and in the flush beam
    reg [WEIGHT_W-1:0] pwx_q, pwy_q, pwz_q;
    reg [3:0]          psteps_q;
    reg [LANE_W-1:0]   pskew_q;

    // ---- template unit (combinational from the phases) ----
    wire [2:0]          g = {1'b0, cfg_ss_log2};
    wire [PH_W:0]       phx_sum = {1'b0, phx_q} + {{(PH_W - WEIGHT_W){1'b0}}, cfg_view_x};
    wire [PH_W:0]       phy_sum = {1'b0, phy_q} + {{(PH_W - WEIGHT_W){1'b0}}, cfg_view_y};
    wire [PH_W:0]       ph_one  = {{PH_W{1'b0}}, 1'b1} << (WEIGHT_W[3:0] + {1'b0, g});
    wire                sx_step = (phx_sum >= ph_one);   // X-step of pass m
    wire                sy_step = (phy_sum >= ph_one);   // Y-step of pass m
    wire [PH_W-1:0]     phx_next = sx_step ? phx_sum[PH_W-1:0] - ph_one[PH_W-1:0] : phx_sum[PH_W-1:0];
    wire [PH_W-1:0]     phy_next = sy_step ? phy_sum[PH_W-1:0] - ph_one[PH_W-1:0] : phy_sum[PH_W-1:0];
    wire [WEIGHT_W-1:0] wx = phase_weight(phx_q, cfg_ss_log2);
    wire [WEIGHT_W-1:0] wy = phase_weight(phy_q, cfg_ss_log2);
    // wz = r / S in Q0.W: r < 2^g, so the shift loses nothing
    wire [WEIGHT_W-1:0] r_ext = {{(WEIGHT_W - R_W){1'b0}}, r_q};
    wire [WEIGHT_W-1:0] wz = r_ext << (WEIGHT_W[3:0] - {1'b0, g});
    wire [3:0]          steps = {old_sy_q, old_sx_q, sy_step, sx_step};

    // ---- the pass's rectangle: an entry of the table (RECTS = 1) or the box ----
    // rt_cur: pass m's entry; rt_nxt: the entry the next pass (and, while idle,
    // pass 0) takes. Without rectangles both are the whole box, from the view
    // registers, and only the last pass flushes.
    wire [RECT_W-1:0] rt_cur, rt_nxt;
    wire              pass_done;               // pass m ends at this advance (below)
    wire              go = start && !busy;
    generate
        if (RECTS != 0) begin : g_rects
            reg  [RECT_W-1:0] rt_q;
            // the RAM's output is always the entry of the pass after the one that
            // holds at the next edge: read (m after this edge) + 1; while idle,
            // entry 0, and entry 1 in the cycle that starts the frame
            // MAX_DIM entries: a frame with rectangles has S = 1, so M <= MAX_DIM (the
            // reads past the last pass's entry wrap, and are never used)
            localparam integer TAW = (MAX_DIM > 1) ? $clog2(MAX_DIM) : 1;
            wire [M_W-1:0] m_after = (state_q == ST_IDLE) ? '0 : (pass_done ? m_q + 1'b1 : m_q);
            wire [M_W-1:0] rd_addr = (state_q == ST_IDLE && !go) ? '0 : m_after + 1'b1;
            cube4_sdp_ram #(.DATA_W (RECT_W), .DEPTH (MAX_DIM)) u_table (
                .clk     (clk),
                .rd_en   (1'b1),
                .rd_addr (TAW'(rd_addr)),
                .rd_data (rt_nxt),
                .wr_en   (rect_we),
                .wr_addr (TAW'(rect_addr)),
                .wr_data (rect_data)
            );
            wire unused_tbl_addr = ^{rd_addr, rect_addr};   // the bits above TAW (M_W >= TAW)
            always @(posedge clk) begin
                if (state_q == ST_IDLE || pass_done) rt_q <= rt_nxt;
            end
            assign rt_cur = rt_q;
        end else begin : g_box
            wire [ADDR_W-1:0] pbx_box = cfg_flip_i ? cfg_i_a0 : '0;
            assign rt_cur = {1'b0, {4{DIM_W'(0)}},   // COM's fields (unused here)
                             cfg_nj - 1'b1, DIM_W'(0), SB_W'(1), SB_W'(0), IW'(0), pbx_box, cfg_j_r0, cfg_j_a0,
                             cfg_ni, DIM_W'(0), DIM_W'(0),
                             PB_W'(cfg_nb - 1'b1), PB_W'(0),
                             DIM_W'(0), cfg_nj - 1'b1, DIM_W'(0), 1'b0, 1'b0, 1'b0};
            assign rt_nxt = rt_cur;
            // the next entry is the box again: its flags and SBROW are read from rt_cur
            wire unused_rect = ^{rect_we, rect_addr, rect_data, rt_nxt[RT_SBROW +: SB_W],
                                 rt_nxt[RT_LAST], rt_nxt[RT_FLUSH], rt_nxt[RT_EMPTY],
                                 rt_cur[RT_LAST]};
        end
    endgenerate
    wire              e_empty = rt_cur[RT_EMPTY];
    wire              e_flush = rt_cur[RT_FLUSH];
    wire [DIM_W-1:0]  e_jl    = rt_cur[RT_JL +: DIM_W];
    wire [DIM_W-1:0]  e_jin   = rt_cur[RT_JIN +: DIM_W];
    wire [PB_W-1:0]   e_pb0   = rt_cur[RT_PB0 +: PB_W];
    wire [PB_W-1:0]   e_pbl   = rt_cur[RT_PBL +: PB_W];
    wire [DIM_W-1:0]  e_ilo   = rt_cur[RT_ILO +: DIM_W];
    wire [DIM_W-1:0]  e_iin   = rt_cur[RT_IIN +: DIM_W];
    wire [DIM_W-1:0]  e_ihi   = rt_cur[RT_IHI +: DIM_W];
    wire [ADDR_W-1:0] e_pbx0  = rt_cur[RT_PBX0 +: ADDR_W];
    wire [IW-1:0]     e_pbp0  = rt_cur[RT_PBP0 +: IW];
    wire [SB_W-1:0]   e_sbrow = rt_cur[RT_SBROW +: SB_W];
    wire [DIM_W-1:0]  e_tj0   = rt_cur[RT_TJ0 +: DIM_W];
    wire [DIM_W-1:0]  e_tjl   = rt_cur[RT_TJL +: DIM_W];
    wire [DIM_W-1:0]  n_j0    = rt_nxt[RT_J0 +: DIM_W];
    wire [DIM_W-1:0]  n_jl    = rt_nxt[RT_JL +: DIM_W];
    wire [PB_W-1:0]   n_pb0   = rt_nxt[RT_PB0 +: PB_W];
    wire [PB_W-1:0]   n_pbl   = rt_nxt[RT_PBL +: PB_W];
    wire [ADDR_W-1:0] n_aj0   = rt_nxt[RT_AJ0 +: ADDR_W];
    wire [LANE_W-1:0] n_rj0   = rt_nxt[RT_RJ0 +: LANE_W];
    wire [ADDR_W-1:0] n_pbx0  = rt_nxt[RT_PBX0 +: ADDR_W];
    wire [IW-1:0]     n_pbp0  = rt_nxt[RT_PBP0 +: IW];
    wire [SB_W-1:0]   n_sb0   = rt_nxt[RT_SB0 +: SB_W];

    // ---- traversal unit: where the counters go next ----
    wire [R_W-1:0] ss_m1 = R_W'((1 << g) - 1);
    wire last_pb    = lpb_q;       // (pb_q == PBL), kept with the counter
    wire last_j     = lj_q;        // (j_q == JL)
    wire last_r     = (r_q == ss_m1);
    wire last_pass  = (k0_q == cfg_nk - 1'b1) && (r_q == '0);
    wire flush_pass = (RECTS != 0) ? e_flush : last_pass;   // a flush beam follows the pass
    wire end_pass   = (RECTS != 0) ? rt_cur[RT_LAST] : last_pass;   // the frame ends after it
    wire lower_mem  = (g == 3'd0) || (m_q == '0);
    wire upper_mem  = (g != 3'd0) && (r_q == R_W'(1));
    wire any_read   = lower_mem || upper_mem;
    wire s_j_down   = cfg_flip_j;
    wire s_k_down   = cfg_flip_k;
    wire in_run     = (state_q == ST_RUN);
    wire in_flush   = (state_q == ST_FLUSH);
    wire run_end    = in_run && (e_empty || (last_pb && last_j));   // pass m's last beat
    assign pass_done = advance && ((run_end && (e_empty || !flush_pass)) || (in_flush && last_pb));

    reg               fr_q;        // j_q is the pass's first row
    reg               pend_q;      // the previous pass's last row waits for this pass's first beam
    reg               sopp_q;      // no row emitted yet in this frame
    reg [DIM_W-1:0]   p_jl_q, p_jin_q, p_ilo_q, p_iin_q, p_ihi_q;   // the pass of the row emitted at a first beam
    reg [DIM_W-1:0]   p_tj0_q, p_tjl_q;

    wire [LANE_W-1:0] rk_rd    = rk_q;                         // read slice
    wire [LANE_W-1:0] skew_rd  = add_p(rj_q, rk_rd);
    wire [LANE_W-1:0] skew_pas = add_p(rj_q, rk0_q);
    wire [LANE_W-1:0] skew_vrt = r_step(skew_pas, s_j_down);   // virtual row JL + 1
    wire              use_prev = fr_q || in_flush;              // emitted row is the last of a pass before
    wire [LANE_W-1:0] skew_out = use_prev ? pskew_q : skew_pas;

    // ---- address unit and lane masks (one per lane) ----
    // t*I_LIN + [t > I_RT] for t = 0 .. P-1, by shifts and adds of the constant t
    function automatic [ADDR_W-1:0] lin_of(input integer t);
        integer b;
        begin
            lin_of = {{(ADDR_W - 1){1'b0}}, (LANE_W'(t) > cfg_i_rt)};
            for (b = 0; b < LANE_W; b = b + 1) begin
                if (((t >> b) & 1) == 1) lin_of = lin_of + (cfg_i_lin << b);
            end
        end
    endfunction
    // a packed vector (entry t at t*ADDR_W): a table of registers, not a RAM
    reg [P*ADDR_W-1:0] lin_tab_q;
    genvar tl;
    generate
        for (tl = 0; tl < P; tl = tl + 1) begin : g_lin_tab
            always @(posedge clk) lin_tab_q[tl*ADDR_W +: ADDR_W] <= lin_of(tl);
        end
    endgenerate
    // Lane masks: i = pb*P + t in [lo, hi)  <=>  lo - pb*P <= t < hi - pb*P. The
    // differences are registered at s1 (clamped to 0 .. P + 1: t + 1 <= P), t of
    // both rows too; the compares run at s2 on registers only. The read row
    // takes pass m's positions; the emitted row its own pass's (use_prev).
    function automatic [REM_W-1:0] rem_of(input [DIM_W-1:0] bound, input [IW-1:0] pbp);
        reg [IW-1:0] b, diff;            // IW >= DIM_W: the bound zero-extended
        begin
            b = IW'(bound);
            diff = b - pbp;
            rem_of = (b <= pbp) ? {REM_W{1'b0}} : (diff > IW'(P + 1)) ? REM_W'(P + 1) : REM_W'(diff);
        end
    endfunction
    wire [P*LANE_W-1:0] t_d, tout_d;
    wire [REM_W-1:0]    hi_rd_d  = rem_of(e_ihi, pbp_q);
    wire [REM_W-1:0]    lo_rd_d  = rem_of(e_ilo, pbp_q);
    // (the emitted row's: both candidates' remainders, selected after them, so
    // that the state's use_prev is not in series with the subtraction)
    wire [REM_W-1:0]    hi_out_d = use_prev ? rem_of(p_ihi_q, pbp_q) : hi_rd_d;
    wire [REM_W-1:0]    lo_out_d = use_prev ? rem_of(p_ilo_q, pbp_q) : lo_rd_d;
    wire [REM_W-1:0]    in_out_d = use_prev ? rem_of(p_iin_q, pbp_q) : rem_of(e_iin, pbp_q);
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            // position held by this lane for the read and for the emitted row
            wire [LANE_W-1:0] t_rd  = lane_pos(q, skew_rd, cfg_flip_i, cfg_i_r1);
            wire [LANE_W-1:0] t_out = lane_pos(q, skew_out, cfg_flip_i, cfg_i_r1);
            assign t_d[q*LANE_W +: LANE_W]    = t_rd;
            assign tout_d[q*LANE_W +: LANE_W] = t_out;
        end
    endgenerate

    // ---- the beat described by the state ----
    wire              issue   = (state_q != ST_IDLE) && !(in_run && e_empty);
    wire              emit_d  = in_run ? (!fr_q || pend_q) : in_flush;
    wire [M_W-1:0]    mout_d  = (in_run && fr_q) ? m_q - 1'b1 : m_q;  // flush: m stays
    wire [DIM_W-1:0]  jout_d  = use_prev ? p_jl_q : j_q - 1'b1;
    wire              sop_d   = emit_d && sopp_q;
    wire              eop_d   = in_flush && last_pb && end_pass;
    // the emitted row holds samples (TJ0 .. TJL); inside: not below J_IN, and not
    // the last sample row when wy > 0 (the box's high-face rule, numerics.md 4)
    wire [DIM_W-1:0]    tj0_out = use_prev ? p_tj0_q : e_tj0;
    wire [DIM_W-1:0]    tjl_out = use_prev ? p_tjl_q : e_tjl;
    wire [WEIGHT_W-1:0] wy_out  = use_prev ? pwy_q : wy;
    wire              rowv_d  = (jout_d >= tj0_out) && (jout_d <= tjl_out);
    wire              rowin_d = (jout_d >= (use_prev ? p_jin_q : e_jin))
                                && !((jout_d == tjl_out) && (wy_out != '0));
    wire              rdrow_d = (j_q >= e_tj0) && (j_q <= e_tjl);   // the read row holds samples
    wire              ylast_d = (jout_d == cfg_nj - 1'b1);          // the emitted row is row NJ - 1

    // ---- the beat's fields, as they travel s1 -> s2 -> output register ----
    // s1 holds the fields but the lane masks (F1_W bits); s2 adds the masks.
    // The order is the tag's (cube4_defs.vh, CUBE4_TAG_LAYOUT), MSB first.
    localparam integer F1_W = TAG_W - 4 * P;
    localparam integer F_W  = P + TAG_W;
    wire [F1_W-1:0] f_d = {emit_d, sop_d, eop_d, use_prev,
                           in_run, in_run && lower_mem,
                           in_run && upper_mem, in_run && (r_q != '0),
                           k0_q[0], sb_q, pb_q,
                           use_prev ? pwx_q : wx, wy_out, use_prev ? pwz_q : wz,
                           mout_d, jout_d, skew_out, ylast_d,
                           use_prev ? psteps_q : steps};

    reg [F1_W-1:0]      f1_q;
    reg [P*LANE_W-1:0]  tout1_q;           // lane positions t of the emitted row
    reg [REM_W-1:0]     hi_rd1_q, lo_rd1_q, hi_out1_q, lo_out1_q, in_out1_q;
    reg                 rowin1_q;          // the emitted row is inside (rowin_d)
    reg                 rowv1_q;           // the emitted row holds samples
    reg                 rd1_q;             // the beat reads memory (RUN and a read pass)
    reg [P*LANE_W-1:0]  t1_q, t2_q;        // lane positions t of the read
    wire [P-1:0]        rden_2, lval_2, lnbr_2, lwrap_2, linl_2;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_mask
            wire [REM_W-1:0] tr = REM_W'(t1_q[q*LANE_W +: LANE_W]);
            wire [REM_W-1:0] to = REM_W'(tout1_q[q*LANE_W +: LANE_W]);
            assign rden_2[q]  = rd1_q && (tr < hi_rd1_q) && (tr >= lo_rd1_q);
            assign lval_2[q]  = rowv1_q && (to < hi_out1_q) && (to >= lo_out1_q);
            assign lnbr_2[q]  = (to + 1'b1 < hi_out1_q);
            assign lwrap_2[q] = (to == REM_W'(P - 1));
            assign linl_2[q]  = rowin1_q && (to >= in_out1_q);
        end
    endgenerate

    reg                 v1_q, v2_q, v_q;
    reg [F_W-1:0]       f2_q, f_q;
    reg [ADDR_W-1:0]    ajk1_q;            // A_j + A_k
    reg [ADDR_W-1:0]    pbx1_q;
    reg [ADDR_W-1:0]    base2_q;           // A_j + A_k + I_A0 - pb*I_PB  or  A_j + A_k + pb*I_PB
    reg                 flip1_q, flip2_q;
    reg [P*ADDR_W-1:0]  addr_q;

    wire advance = !v_q || req_ready;

    always @(posedge clk) begin
        if (rst) begin
            v1_q <= 1'b0;
            v2_q <= 1'b0;
            v_q  <= 1'b0;
        end else if (advance) begin
            v1_q <= issue;
            v2_q <= v1_q;
            v_q  <= v2_q;
        end
    end

    integer ql;
    always @(posedge clk) begin
        if (advance) begin
            // s1
            f1_q      <= f_d;
            t1_q      <= t_d;
            tout1_q   <= tout_d;
            hi_rd1_q  <= hi_rd_d;
            lo_rd1_q  <= lo_rd_d;
            hi_out1_q <= hi_out_d;
            lo_out1_q <= lo_out_d;
            in_out1_q <= in_out_d;
            rowin1_q  <= rowin_d;
            rowv1_q   <= rowv_d;
            rd1_q     <= in_run && any_read && rdrow_d;
            ajk1_q    <= aj_q + ak_q;
            pbx1_q    <= pbx_q;
            flip1_q   <= cfg_flip_i;
            // s2
            f2_q    <= {rden_2, linl_2, lval_2, lnbr_2, lwrap_2, f1_q};
            t2_q    <= t1_q;
            base2_q <= ajk1_q + pbx1_q;
            flip2_q <= flip1_q;
            // output register
            f_q     <= f2_q;
            for (ql = 0; ql < P; ql = ql + 1) begin
                addr_q[ql*ADDR_W +: ADDR_W] <= flip2_q
                    ? base2_q - lin_tab_q[32'(t2_q[ql*LANE_W +: LANE_W]) * ADDR_W +: ADDR_W]
                    : base2_q + lin_tab_q[32'(t2_q[ql*LANE_W +: LANE_W]) * ADDR_W +: ADDR_W];
            end
        end
    end

    // ---- the pass's counters: row and partial beam, slot, address terms ----
    // A pass starts with them at its rectangle's first row and partial beam
    // (rt_nxt: while idle pass 0's, at pass_done the next pass's); each beat
    // steps them; a row's last partial beam goes back to the first.
    wire load_pass = (state_q == ST_IDLE) || (pass_done && !end_pass);
    always @(posedge clk) begin
        if (load_pass) begin
            j_q   <= n_j0;
            lj_q  <= (n_j0 == n_jl);
            pb_q  <= n_pb0;
            lpb_q <= (n_pb0 == n_pbl);
            sb_q  <= n_sb0;
            pbp_q <= n_pbp0;
            pbx_q <= n_pbx0;
            rj_q  <= n_rj0;
            aj_q  <= n_aj0;
        end else if (advance && state_q != ST_IDLE) begin
            if (!last_pb) begin
                pb_q  <= pb_q + 1'b1;
                lpb_q <= (pb_q + 1'b1 == e_pbl);
                pbp_q <= pbp_q + IW'(P);
                pbx_q <= cfg_flip_i ? pbx_q - cfg_i_pb : pbx_q + cfg_i_pb;
                sb_q  <= sb_q + 1'b1;
            end else begin
                pb_q  <= e_pb0;
                lpb_q <= (e_pb0 == e_pbl);
                pbp_q <= e_pbp0;
                pbx_q <= e_pbx0;
            end
            if (in_run && last_pb && !last_j && !e_empty) begin
                j_q  <= j_q + 1'b1;
                lj_q <= (j_q + 1'b1 == e_jl);
                sb_q <= sb_q + e_sbrow;
                rj_q <= r_step(rj_q, s_j_down);
                aj_q <= a_step(aj_q, rj_q, s_j_down, cfg_j_lin, cfg_j_blk);
            end
            if (run_end && !e_empty) sb_q <= rt_cur[RT_SB0 +: SB_W];   // the flush beam's slots
        end
    end

    // ---- state update ----
    always @(posedge clk) begin
        if (rst) begin
            state_q <= ST_IDLE;
        end else if (state_q == ST_IDLE) begin
            // Idle: the counters hold their first values all the time, so
            // start only moves the state (start and busy reach no counter).
            if (go) state_q <= ST_RUN;
            m_q      <= '0;
            k0_q     <= '0;
            r_q      <= '0;
            fr_q     <= 1'b1;
            pend_q   <= 1'b0;
            sopp_q   <= 1'b1;
            p_jl_q   <= n_jl;
            p_jin_q  <= rt_nxt[RT_JIN +: DIM_W];
            p_ilo_q  <= rt_nxt[RT_ILO +: DIM_W];
            p_iin_q  <= rt_nxt[RT_IIN +: DIM_W];
            p_ihi_q  <= rt_nxt[RT_IHI +: DIM_W];
            p_tj0_q  <= rt_nxt[RT_TJ0 +: DIM_W];
            p_tjl_q  <= rt_nxt[RT_TJL +: DIM_W];
            rk_q     <= cfg_k_r0;
            ak_q     <= cfg_k_a0;
            rk0_q    <= cfg_k_r0;
            // pass 0 starts at the phase PH0; its old step (slice -1 to 0) is
            // floor(PH0 / 2^(W+g)) - floor((PH0 - VIEW) / 2^(W+g)) = [PH0 < VIEW]
            phx_q    <= cfg_ph0_x;
            phy_q    <= cfg_ph0_y;
            old_sx_q <= ({1'b0, cfg_ph0_x} < (PH_W + 1)'(cfg_view_x));
            old_sy_q <= ({1'b0, cfg_ph0_y} < (PH_W + 1)'(cfg_view_y));
        end else if (advance) begin
            if (issue && emit_d) sopp_q <= 1'b0;
            if (in_run && last_pb && !last_j && !e_empty) fr_q <= 1'b0;   // the next row
            if (run_end && !e_empty) begin
                // pass m's last beat: remember its emitted row's fields
                pwx_q    <= wx;
                pwy_q    <= wy;
                pwz_q    <= wz;
                psteps_q <= steps;
                pskew_q  <= skew_vrt;
                p_jl_q   <= e_jl;
                p_jin_q  <= e_jin;
                p_ilo_q  <= e_ilo;
                p_iin_q  <= e_iin;
                p_ihi_q  <= e_ihi;
                p_tj0_q  <= e_tj0;
                p_tjl_q  <= e_tjl;
                fr_q     <= 1'b0;
                if (flush_pass) state_q <= ST_FLUSH;
            end
            if (pass_done) begin
                pend_q <= in_run && !e_empty;   // no flush: the next pass's first beam emits it
                fr_q   <= 1'b1;
                if (end_pass) begin
                    state_q <= ST_DRAIN;
                end else begin
                    // the next pass (its counters: below)
                    state_q  <= ST_RUN;
                    m_q      <= m_q + 1'b1;
                    phx_q    <= phx_next;
                    phy_q    <= phy_next;
                    old_sx_q <= sx_step;
                    old_sy_q <= sy_step;
                    if (any_read) begin
                        rk_q <= r_step(rk_q, s_k_down);
                        ak_q <= a_step(ak_q, rk_q, s_k_down, cfg_k_lin, cfg_k_blk);
                    end
                    if (last_r) begin
                        r_q   <= '0;
                        k0_q  <= k0_q + 1'b1;
                        rk0_q <= r_step(rk0_q, s_k_down);
                    end else begin
                        r_q <= r_q + 1'b1;
                    end
                end
            end
            if (state_q == ST_DRAIN) state_q <= ST_IDLE;   // one beat
        end
    end

    assign busy      = (state_q != ST_IDLE) || v1_q || v2_q;
    assign req_valid = v_q;
    assign req_addr  = addr_q;
    assign {req_rden, req_tag} = f_q;   // f2: {rden, LINL, LVAL, LNBR, LWRAP, f1}

endmodule
`default_nettype wire

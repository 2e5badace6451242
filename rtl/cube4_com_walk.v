`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_walk
// -----------------------------------------------------------------------------
// Purpose
//   COM's slice geometry without rectangles (RECTS = 0; docs/architecture.md
//   "COM"): every slice is the whole NJ x NB beats in order, so the beat's
//   slot, partial beam and row are counted (as cube4_gra's counters), and the
//   template of slice m + 1 (its phase) and the steps of slice m follow
//   from the view registers. Per lane (numerics.md section 8):
//     fresh   the ray's previous sample (m-1, j-dyb, i-dxb) is outside:
//             m = 0, or dyb and j = 0, or dxb and i = 0
//     nx_in   its next sample (m+1, j+dyf, i+dxf) is inside: m < M-1,
//             i+dxf < NI, j+dyf < NJ, and not the last column (row) of a
//             template whose weight wx(m+1) (wy(m+1)) is not 0
//   and the read-after-write rule on the slice buffer: a beat's slot repeats
//   every L = NJ * NB beats, so the beat it depends on is in R0 .. S9 exactly
//   when R0 .. S9 hold L or more beats (counted; L >= 11 never waits).
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2: as cube4_com (1..64, 2..2048, 4..12, 0..3).
//   SP_W   the slot's width, clog2(MAX_DIM * NBMAX) (cube4_com).  1..22.  Default 13.
//
// Latency
//   pos_*, fresh, stx, sty, phases: combinational from R0 (S0) and this
//   unit's registers; the counters load under step_c[0], the template under
//   step_c[1] (R0's valid-bit copies). nx_in and f1_*: from S1 registers
//   (one edge after S0; f1_wxn, f1_wyn from ph_x, ph_y by compares with
//   thresholds of the frame, CUBE4_PHASE_NEXT_NZ, registered from cfg every
//   clock). hazard: a register (the count for the next cycle).
//
// Ports
//   step_c    R0 holds a beat (copies for the counters, the template)
//   take, step, v_fly   a beat enters R0; R0, S1 .. S8 hold one
//   sop, first, r0_m, r0_j, dxb, dyb, ipos   R0's fields (cube4_com_seq)
//   f1_ipos, f1_j, f1_dxf, f1_dyf   S1's (cube4_com_seq)
//   pos_sp    out  the slot j * NB + pb [SP_W];  pos_pb  the partial beam
//   stx, sty  out  stepx(m), stepy(m) [DIM_W]
//   ph_x, ph_y     out  the phase of slice m when R0 holds the slice's first
//             beat (sop: PH0) [PHASE_W, W + g bits, Q.W+g of a voxel]
//   phn_x, phn_y   out  the phase of slice m + 1 [PHASE_W]
//   f1_last, f1_wxn, f1_wyn   out  S1: m = M - 1; wx(m+1) > 0; wy(m+1) > 0
//
// Bit growth and rounding: phases stay below 2^(W+g) (one subtraction of
//   2^(W+g) after each add of VIEW); positions in IW bits; no rounding.
// =============================================================================
module cube4_com_walk #(
    `CUBE4_SLICE_PARAMS,
    parameter integer SP_W     = 13,
    localparam integer PH_W = PHASE_W
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    input  wire [1:0] step_c, input wire take, input wire step, input wire [8:1] v_fly,
    input  wire sop, input wire first, input wire [M_W-1:0] r0_m, input wire [DIM_W-1:0] r0_j,
    input  wire dxb, input wire dyb, input wire [P*IW-1:0] ipos,
    input  wire [P*IW-1:0] f1_ipos, input wire [IW-1:0] f1_j, input wire f1_dxf, input wire f1_dyf,
    output wire [SP_W-1:0] pos_sp, output wire [PB_W-1:0] pos_pb, output wire hazard,
    output wire [P-1:0] fresh, output wire [P-1:0] nx_in,
    output wire [DIM_W-1:0] stx, output wire [DIM_W-1:0] sty,
    output wire [PH_W-1:0] ph_x, output wire [PH_W-1:0] ph_y,
    output wire [PH_W-1:0] phn_x, output wire [PH_W-1:0] phn_y,
    output reg  f1_last, output reg f1_wxn, output reg f1_wyn
);
    `CUBE4_VIEW_FIELDS(cfg);

    // ---- positions: partial beam, row and slot (as cube4_gra) ----
    // sop (a register) only selects between results computed from registers:
    // lb_q / ls_q say pb_q / row_q are at the last beam / the last slot of a
    // slice (kept with the counters), the increments run on pb_q, row_q,
    // sp_q, and the compares on registered view constants.
    reg  [PB_W-1:0]  pb_q;
    reg  [DIM_W-1:0] row_q;
    reg  [SP_W-1:0]  sp_q;
    assign pos_pb = sop ? {PB_W{1'b0}} : pb_q;
    assign pos_sp = sop ? {SP_W{1'b0}} : sp_q;
    wire [DIM_W-1:0] pos_row = sop ? {DIM_W{1'b0}} : row_q;
    reg              lb_q, ls_q;                 // pb_q = NB - 1; and row_q = NJ - 1
    reg              nb1_q, nb2_q, nj1_q, nj2_q; // NB = 1, NB = 2, NJ = 1, NJ = 2
    reg  [NB_W-1:0]  nbm2_q;                     // NB - 2
    reg  [DIM_W-1:0] njm1_q, njm2_q;             // NJ - 1, NJ - 2
    always @(posedge clk) begin
        nb1_q  <= (cfg_nb == NB_W'(1));
        nb2_q  <= (cfg_nb == NB_W'(2));
        nj1_q  <= (cfg_nj == DIM_W'(1));
        nj2_q  <= (cfg_nj == DIM_W'(2));
        nbm2_q <= cfg_nb - NB_W'(2);
        njm1_q <= cfg_nj - DIM_W'(1);
        njm2_q <= cfg_nj - DIM_W'(2);
    end
    wire last_beam  = sop ? nb1_q : lb_q;
    wire last_slice = sop ? (nb1_q && nj1_q) : ls_q;
    // pos_pb + 1 == NB - 1, pos_row == NJ - 1, pos_row + 1 == NJ - 1 (used where NB > 1 / NJ > 1)
    wire pb_e2  = sop ? nb2_q : (NB_W'(pb_q) == nbm2_q);
    wire row_e1 = sop ? nj1_q : (row_q == njm1_q);
    wire row_e2 = sop ? nj2_q : (row_q == njm2_q);
    wire [PB_W-1:0]  pb_inc  = sop ? PB_W'(1) : pb_q + 1'b1;
    wire [DIM_W-1:0] row_inc = sop ? DIM_W'(1) : row_q + 1'b1;
    wire [SP_W-1:0]  sp_inc  = sop ? SP_W'(1) : sp_q + 1'b1;
    wire lb_n = last_beam ? nb1_q : pb_e2;
    wire ls_n = lb_n && (!last_beam ? row_e1 : (last_slice ? nj1_q : row_e2));
    always @(posedge clk) begin
        if (rst) begin
            pb_q  <= {PB_W{1'b0}};
            row_q <= {DIM_W{1'b0}};
            sp_q  <= {SP_W{1'b0}};
            lb_q  <= 1'b0;
            ls_q  <= 1'b0;
        end else if (step_c[0]) begin
            pb_q  <= last_beam ? {PB_W{1'b0}} : pb_inc;
            row_q <= !last_beam ? pos_row : (last_slice ? {DIM_W{1'b0}} : row_inc);
            sp_q  <= last_slice ? {SP_W{1'b0}} : sp_inc;
            lb_q  <= lb_n;
            ls_q  <= ls_n;
        end
    end

    // ---- template of slice m+1 (for "next sample inside") and steps of slice m ----
    reg  [PH_W-1:0]  phx_q, phy_q;      // phase of slice m + 1
    reg  [DIM_W-1:0] stx_q, sty_q;      // stepx(m), stepy(m)
    assign ph_x = sop ? cfg_ph0_x : phx_q;
    assign ph_y = sop ? cfg_ph0_y : phy_q;
    `CUBE4_PHASE_FUNCTIONS
    `CUBE4_PHASE_NEXT_NZ
    wire [PH_W:0]    ph_one  = phase_one({1'b0, cfg_ss_log2});
    wire [PH_W:0]    phx_add = phase_advance(ph_x, cfg_view_x, ph_one);
    wire [PH_W:0]    phy_add = phase_advance(ph_y, cfg_view_y, ph_one);
    wire unused_carry = ^{phx_add[PH_W], phy_add[PH_W]};
    reg  [PH_W:0]    ph_g1;             // 2^g: a phase's weight is not 0
    always @(posedge clk) ph_g1 <= {{PH_W{1'b0}}, 1'b1} << cfg_ss_log2;
    assign phn_x = first ? phx_add[PH_W-1:0] : phx_q;
    assign phn_y = first ? phy_add[PH_W-1:0] : phy_q;
    // wx(m+1) > 0: the weight is the phase >> g, so phn_x >= 2^g; at a
    // slice's first beat from ph_x (a register: PH0 at sop, else phx_q) by
    // CUBE4_PHASE_NEXT_NZ's compares, without the adder
    wire wxn_nz = !first ? ({1'b0, phx_q} >= ph_g1)
                         : (sop ? phase_next_nz(cfg_ph0_x, ph_thr_x) : phase_next_nz(phx_q, ph_thr_x));
    wire wyn_nz = !first ? ({1'b0, phy_q} >= ph_g1)
                         : (sop ? phase_next_nz(cfg_ph0_y, ph_thr_y) : phase_next_nz(phy_q, ph_thr_y));
    assign stx = !first ? stx_q : (sop ? {DIM_W{1'b0}} : stx_q + DIM_W'(dxb));
    assign sty = !first ? sty_q : (sop ? {DIM_W{1'b0}} : sty_q + DIM_W'(dyb));
    wire [M_W-1:0] m_last = M_W'(cfg_nk - 1'b1) << cfg_ss_log2;
    always @(posedge clk) begin
        if (step_c[1]) begin
            phx_q <= phn_x;
            phy_q <= phn_y;
            stx_q <= stx;
            sty_q <= sty;
        end
    end

    // ---- per lane: fresh ray (S0) and next sample inside (S1) ----
    // (CUBE4_NEXT_INSIDE: compares with NI, NJ and their n - 1, n - 2 registers,
    // no adder before them)
    // (the row's compares with NJ, NJ - 1, NJ - 2 are registers made from R0's
    // row, as cube4_com_beats' (f1_j is R0's row a cycle later): from S1's
    // registers to the sequencer's finished rays, across COM, only the rule's
    // LUTs, no carry chain: f1_j's compares into `fin_s` were a full build's
    // longest path on one placement)
    `CUBE4_NEXT_INSIDE
    reg f1_jlt0, f1_jlt1, f1_jeq1, f1_jeq2;
    wire [IW-1:0] r0_jx = IW'(r0_j);
    always @(posedge clk) begin
        f1_last <= (r0_m == m_last);
        f1_wxn  <= wxn_nz;
        f1_wyn  <= wyn_nz;
        f1_jlt0 <= r0_jx < nj_0;
        f1_jlt1 <= r0_jx < nj_1;
        f1_jeq1 <= r0_jx == nj_1;
        f1_jeq2 <= r0_jx == nj_2;
    end
    wire j_ok = !f1_last && next_inside_of(f1_dyf, f1_wyn, f1_jlt0, f1_jlt1, f1_jeq1, f1_jeq2);
`ifndef SYNTHESIS
    reg [IW-1:0] r0_jx_q;
    reg [1:0]    f1_wn_ref;             // the weights' flags from phn_x, phn_y themselves
    always @(posedge clk) begin
        r0_jx_q <= r0_jx;
        if (!rst && (f1_j != r0_jx_q))
            $fatal(1, "cube4_com_walk: S1's row %0d is not R0's %0d a cycle later", f1_j, r0_jx_q);
        f1_wn_ref <= {(phn_x >> cfg_ss_log2) != '0, (phn_y >> cfg_ss_log2) != '0};
        if (!rst && v_fly[1] && {f1_wxn, f1_wyn} != f1_wn_ref)
            $fatal(1, "cube4_com_walk: S1's weight flags %b differ from the phases' %b", {f1_wxn, f1_wyn}, f1_wn_ref);
    end
`else
    wire unused_f1_j = ^f1_j;
`endif
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            wire [IW-1:0] i_pos = ipos[q*IW +: IW];
            assign fresh[q] = (r0_m == '0) || (dyb && r0_j == '0) || (dxb && i_pos == '0);
            assign nx_in[q] = j_ok && next_inside(f1_ipos[q*IW +: IW], f1_dxf, f1_wxn, ni_0, ni_1, ni_2);
        end
    endgenerate

    // ---- read after write: valid beats in R0 .. S9 in the next cycle ----
    // (take, step, S1 .. S8 now), against min(NJ * NB, 11): 11 never stalls
    reg  [3:0] lim_q;
    always @(posedge clk) begin
        lim_q <= (32'(cfg_nj) * 32'(cfg_nb) >= 32'd11) ? 4'd11 : 4'(32'(cfg_nj) * 32'(cfg_nb));
    end
    reg [3:0] n_fly_d;                  // at most 10
    integer kh;
    always @* begin
        n_fly_d = {3'b000, take} + {3'b000, step};
        for (kh = 1; kh <= 8; kh = kh + 1) n_fly_d = n_fly_d + {3'b000, v_fly[kh]};
    end
    reg hazard_q;
    always @(posedge clk) begin
        if (rst) hazard_q <= 1'b0;
        else     hazard_q <= (n_fly_d >= lim_q);
    end
    assign hazard = hazard_q;
endmodule
`default_nettype wire

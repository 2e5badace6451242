`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_beats
// -----------------------------------------------------------------------------
// Purpose
//   COM's slice geometry on the beat schedule (BEATS = 1; numerics.md section
//   19, docs/architecture.md "COM"): the beats of a slice are those of its
//   running sample beats (and its markers), so the beat's slot is {j, pb}
//   from its header, as cube4_com_rect's; the rays' intervals come with each
//   beat from the front end's decisions (in_bits, cube4_cfb_skip's position
//   bits {soon, last, fresh, run}, P bits each). Per lane:
//     fresh   the ray's first slice is this one (bit fresh)
//     nx_in   the ray runs the next slice too (not bit last) and its next
//             sample (m+1, j+dyf, i+dxf) is inside the box (cube4_com_walk's
//             rule: the last column / row is outside when wx / wy > 0)
//   Whether a lane's ray runs is the caller's (cube4_com registers bit run
//   at R0 and ANDs each lane's into inside at S0, cube4_com_seq run0). The steps and phases of the beat's slice m come with it
//   (c_geo: cube4_com_steps, where the beats leave SHA in cube4_top) through
//   the skid buffers, and R0 registers them on every cycle: neither the take
//   nor the hazard reaches them, and no logic of them lies on the route from
//   SHA to COM. The slot and "the previous beat is the row above":
//   cube4_com_slot, as cube4_com_rect's; the read-after-write rule by
//   position as a register decided a cycle ahead from COM's input skid
//   (cube4_com_ahead), held equal to cube4_com_slot's compare in simulation.
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2.
//   SP_W   the slot's width, clog2(MAX_DIM) + PB_W (cube4_com).  2..22.
//
// Latency
//   The bits and the steps: registered as the header enters R0 (fresh, stx,
//   sty: combinational from R0 registers at S0; R0 loads on every cycle);
//   nx_in from an S1
//   register.
//   hazard: a register (cube4_com_ahead), the rule for the beat offered in
//   its cycle. col1_4: S4.
//
// Ports
//   in_bits   in   [4P] the offered beat's {soon, last, fresh, run}, P bits
//                  each by position t in the partial beam
//   tpos      in   [P*LANE_W] S0: lane q's position t (cube4_com_seq)
//   c_geo     in   [GEO_W] the offered beat's {stx, sty, ph_x, ph_y}
//                  (cube4_com_steps' q_geo, come with the beat)
//   in_valid, in_hdr   in   COM's input skid offers a beat; its header
//   nx_valid  in   the skid holds a second beat
//   sk_hdr    in   the header at the skid's input
//   take      in   the offered beat enters R0 at this edge
//   step, v_fly, sp_fly   R0, S1 .. S9 hold a beat; S1 .. S9's slots
//   r0_m, r0_j, r0_pb   R0's fields (cube4_com_seq)
//   pos_sp, pos_pb, hazard, fresh, nx_in, stx, sty, col1_4: as cube4_com_rect
//   soon_0    out  S0: the lanes' soon bits (the ray's stop comes within the
//                  lag: COM reports nothing for it)
//   ph_x, ph_y, phn_x, phn_y   out  S0: the phases of R0's slice m and of
//                  slice m + 1 [PHASE_W] (the path weights, cube4_com_plw)
//   f1_klast, f1_wxn, f1_wyn   out  S1: m = M - 1; wx(m+1) > 0; wy(m+1) > 0
//
// Bit growth and rounding: none (compares, counters; the phases wrap by
//   design, their carry is the step).
// =============================================================================
module cube4_com_beats #(
    `CUBE4_SLICE_PARAMS,
    parameter integer SP_W = 13,
    localparam integer GEO_W = `CUBE4_GEO_W    // a beat's {stx, sty, ph_x, ph_y}
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    input  wire [4*P-1:0] in_bits, input wire [P*LANE_W-1:0] tpos,
    input  wire [GEO_W-1:0] c_geo, input wire in_valid, input wire [HDR_W-1:0] in_hdr,
    input  wire nx_valid, input wire [HDR_W-1:0] sk_hdr, input wire take,
    input  wire step, input wire [9:1] v_fly, input wire [9*SP_W-1:0] sp_fly,
    input  wire [M_W-1:0] r0_m, input wire [DIM_W-1:0] r0_j, input wire [PB_W-1:0] r0_pb,
    input  wire [P*IW-1:0] f1_ipos, input wire [IW-1:0] f1_j, input wire f1_dxf, input wire f1_dyf,
    output wire [SP_W-1:0] pos_sp, output wire [PB_W-1:0] pos_pb, output wire hazard,
    output wire [P-1:0] fresh, output wire [P-1:0] nx_in,
    output wire [DIM_W-1:0] stx, output wire [DIM_W-1:0] sty,
    output wire col1_4, output wire [P-1:0] soon_0,
    output wire [PHASE_W-1:0] ph_x, output wire [PHASE_W-1:0] ph_y,
    output wire [PHASE_W-1:0] phn_x, output wire [PHASE_W-1:0] phn_y,
    output reg  f1_klast, output reg f1_wxn, output reg f1_wyn
);
    `CUBE4_VIEW_FIELDS(cfg);
    localparam integer PH_W = PHASE_W;

    // ---- the bits, registered with R0's header (loaded on every cycle); they
    // come by position t in the partial beam, lane q holds t = tpos[q] (S0) ----
    reg [P-1:0] r0_fresh, r0_last, r0_soon, s1_last;
    always @(posedge clk) begin
        r0_soon  <= in_bits[3*P +: P];
        r0_last  <= in_bits[2*P +: P];
        r0_fresh <= in_bits[P +: P];
    end
    wire [P-1:0] last_0;
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            wire [LANE_W-1:0] t = tpos[q*LANE_W +: LANE_W];
            assign fresh[q]  = r0_fresh[32'(t)];
            assign last_0[q] = r0_last[32'(t)];
            assign soon_0[q] = r0_soon[32'(t)];
        end
    endgenerate
    always @(posedge clk) s1_last <= last_0;
    wire unused_run = ^in_bits[0 +: P];   // (ANDed into inside at S0 by cube4_com)

    // ---- the steps and phases of the beat's slice: decided where the beat left
    // SHA (cube4_com_steps), they come with it through the skid buffers (c_geo);
    // R0 registers them on every cycle ----
    `CUBE4_PHASE_FUNCTIONS
    wire [2:0]       g      = {1'b0, cfg_ss_log2};
    wire [PH_W:0]    ph_one = phase_one(g);
    reg  [GEO_W-1:0] r0_geo;
    always @(posedge clk) r0_geo <= c_geo;
    wire [PH_W:0]    nx = phase_advance(ph_x, cfg_view_x, ph_one), ny = phase_advance(ph_y, cfg_view_y, ph_one);
    assign {stx, sty, ph_x, ph_y} = r0_geo;
    // the next slice's weights (S1): its last column / row is outside when wx / wy > 0
    assign phn_x = nx[PH_W-1:0];
    assign phn_y = ny[PH_W-1:0];
    wire unused_carry = ^{nx[PH_W], ny[PH_W]};      // (the next slice's steps are its own beats')
    `CUBE4_VIEW_SLICES;
    wire [M_W-1:0] m_last = view_m_last;
    // (wx(m+1) > 0, phn_x >= 2^g, by CUBE4_PHASE_NEXT_NZ's compares of ph_x, without the adder)
    `CUBE4_PHASE_NEXT_NZ
    always @(posedge clk) begin
        f1_klast <= (r0_m == m_last);
        f1_wxn   <= phase_next_nz(ph_x, ph_thr_x);
        f1_wyn   <= phase_next_nz(ph_y, ph_thr_y);
    end
`ifndef SYNTHESIS
    reg [1:0] f1_wn_ref;                // the flags from phn_x, phn_y themselves
    always @(posedge clk) begin
        f1_wn_ref <= {(phn_x >> cfg_ss_log2) != '0, (phn_y >> cfg_ss_log2) != '0};
        if (!rst && v_fly[1] && {f1_wxn, f1_wyn} != f1_wn_ref)
            $fatal(1, "cube4_com_beats: S1's weight flags %b differ from the phases' %b", {f1_wxn, f1_wyn}, f1_wn_ref);
    end
`endif

    // ---- per lane: the ray runs the next slice and its next sample is inside
    // the box (as cube4_com_walk, numerics.md 4), S1 ----
    // (CUBE4_NEXT_INSIDE: compares with NI, NJ and their n - 1, n - 2 registers)
    `CUBE4_NEXT_INSIDE
    // (j's compares with NJ, NJ - 1, NJ - 2 are made at R0, from r0_j, into S1
    // registers of the unit's own: S1's j register serves other units, and a
    // route from it across COM into the compares limited the beat build)
    wire [IW-1:0] r0_jx = IW'(r0_j);
    reg           f1_jlt0, f1_jlt1, f1_jeq1, f1_jeq2;
    always @(posedge clk) begin
        f1_jlt0 <= r0_jx < nj_0;
        f1_jlt1 <= r0_jx < nj_1;
        f1_jeq1 <= r0_jx == nj_1;
        f1_jeq2 <= r0_jx == nj_2;
    end
    wire j_ok = next_inside_of(f1_dyf, f1_wyn, f1_jlt0, f1_jlt1, f1_jeq1, f1_jeq2);
`ifndef SYNTHESIS
    always @(posedge clk) begin
        if (!rst && v_fly[1] && j_ok != next_inside(f1_j, f1_dyf, f1_wyn, nj_0, nj_1, nj_2))
            $fatal(1, "cube4_com_beats: j_ok %0d differs from next_inside of f1_j %0d", j_ok, f1_j);
    end
`endif
    generate
        for (q = 0; q < P; q = q + 1) begin : g_next
            assign nx_in[q] = !s1_last[q] && j_ok
                            && next_inside(f1_ipos[q*IW +: IW], f1_dxf, f1_wxn, ni_0, ni_1, ni_2);
        end
    endgenerate

    // ---- the slot {j, pb}, "the row above"; the read-after-write rule a cycle ahead ----
    wire hz_now;                         // cube4_com_slot's compare of the offered beat
    cube4_com_slot #(`CUBE4_SLICE_PASS, .SP_W(SP_W)) u_slot (
        .clk(clk), .rst(rst), .in_hdr(in_hdr), .step(step), .v_fly(v_fly), .sp_fly(sp_fly),
        .r0_m(r0_m), .r0_j(r0_j), .r0_pb(r0_pb),
        .pos_sp(pos_sp), .pos_pb(pos_pb), .hazard(hz_now), .col1_4(col1_4));
    cube4_com_ahead #(`CUBE4_SLICE_PASS, .SP_W(SP_W)) u_ahead (
        .clk(clk), .rst(rst), .hd_valid(in_valid), .hd_hdr(in_hdr), .nx_valid(nx_valid),
        .in_hdr(sk_hdr), .take(take), .step(step), .pos_sp(pos_sp),
        .v_fly(v_fly[8:1]), .sp_fly(sp_fly[0 +: 8*SP_W]), .hazard(hazard));
    wire unused_hz = hz_now;             // (synthesis: the check's only)
`ifndef SYNTHESIS
    always @(posedge clk) begin
        if (!rst && in_valid && hazard != hz_now) begin
            $error("cube4_com_beats: the registered hazard %0d differs from the slot compare %0d", hazard, hz_now);
            $fatal(1, "cube4_com_beats: hazard out of step");
        end
    end
`endif
endmodule
`default_nettype wire

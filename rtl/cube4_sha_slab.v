`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_sha_slab
// -----------------------------------------------------------------------------
// Purpose
//   The slab's falloff weight of every sample of a beat (SHA with SLAB = 1;
//   docs/numerics.md section 12, golden twin golden/cube4/clip.py
//   Clip.falloff):
//     f = min(max(min(E, E_H), 0) >> FALL_SH, 256)     (FALL_ON = 1)
//     f = 256                                          (FALL_ON = 0)
//   E and E_H the plane's and the far face's values at the sample
//   (cube4_plane), at the sample's position (i + wx / 2^W, j + wy / 2^W, m / S)
//   with the slice's resampling weights formed here from m:
//     wx(m) = ((PH0_X + m * VIEW_X) mod 2^(W + g)) >> g     (wy alike)
//   (golden/cube4/view.py Traversal.weights). COM multiplies the blending
//   modes' opacity by f (cube4_com_lane).
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2 as cube4_sha (derived widths and the view
//   layout: cube4_defs.vh).
//
// Latency
//   `CUBE4_SLAB_LAT = 9 register stages from the fields to f, no enable (SHA's
//   pipeline moves on every cycle):
//     p1, p2  m * VIEW_X and m * VIEW_Y (cube4_mul's operand and product
//             registers); the beat's fields ride along
//     p3      wx, wy
//     p4 .. p7  cube4_plane's c0 .. c3
//     p8      each lane's max(min(E, E_H), 0) (the min chosen by cube4_plane's
//             e_near, formed beside E and E_H)
//     p9      f (the low 8 bits of the shift, or 256 where a mask of the
//             bits at 8 + FALL_SH and above finds one set)
//
// Ports
//   cfg                           view registers (PH0_*, VIEW_*, SS_LOG2, CUT_*, FALL_*)
//   in_m, in_j, in_pb, in_skew    the beat's header fields
//   fall  [P*FALL_W]              lane q's f, 0 .. 256 (Q1.8), 9 cycles later
//
// Bit growth and rounding
//   The phase products are exact (M_W + W + 2 bits), of which the low
//   W + g bits are the phase; E, E_H exact (cube4_plane); f truncates
//   (a shift right) and saturates at 256, one rule with the golden model.
// =============================================================================
module cube4_sha_slab #(
    parameter integer P        = 8, parameter integer MAX_DIM     = 256,
    parameter integer WEIGHT_W = 8, parameter integer MAX_SS_LOG2 = 0,
    `CUBE4_GEOMETRY, `CUBE4_VIEW_LAYOUT
) (
    input  wire clk,
    input  wire [VIEW_W-1:0] cfg,
    input  wire [M_W-1:0] in_m, input wire [DIM_W-1:0] in_j, input wire [PB_W-1:0] in_pb,
    input  wire [LANE_W-1:0] in_skew,
    output wire [P*FALL_W-1:0] fall
);
    `CUBE4_VIEW_FIELDS(cfg);

    localparam integer EW  = CUT_E_W;
    localparam integer PW  = PHASE_W;
    localparam integer FLD_W = M_W + DIM_W + PB_W + LANE_W;
    localparam integer PR_W = M_W + WEIGHT_W + 3;     // {0, m} * {0, VIEW}, signed

    // ---- p1, p2: the phase products; the fields ride along ----
    wire signed [PR_W-1:0] p2_px, p2_py;
    cube4_mul #(.A_W(M_W + 1), .B_W(WEIGHT_W + 2)) u_mul_x (
        .clk(clk), .en(1'b1), .a($signed({1'b0, in_m})), .b($signed({1'b0, cfg_view_x})), .p(p2_px));
    cube4_mul #(.A_W(M_W + 1), .B_W(WEIGHT_W + 2)) u_mul_y (
        .clk(clk), .en(1'b1), .a($signed({1'b0, in_m})), .b($signed({1'b0, cfg_view_y})), .p(p2_py));
    reg [FLD_W-1:0] p1_f, p2_f, p3_f;
    always @(posedge clk) begin
        p1_f <= {in_m, in_j, in_pb, in_skew};
        p2_f <= p1_f;
        p3_f <= p2_f;
    end
    wire unused_p = ^{p2_px[PR_W-1:PW], p2_py[PR_W-1:PW]};

    // ---- p3: the slice's weights, ((PH0 + m * VIEW) mod 2^(W + g)) >> g ----
    wire [3:0]    wg   = WEIGHT_W[3:0] + {2'b00, cfg_ss_log2};
    wire [PW-1:0] mask = ~({PW{1'b1}} << wg);
    wire [PW-1:0] phx  = (cfg_ph0_x + p2_px[PW-1:0]) & mask;
    wire [PW-1:0] phy  = (cfg_ph0_y + p2_py[PW-1:0]) & mask;
    reg  [WEIGHT_W-1:0] p3_wx, p3_wy;
    always @(posedge clk) begin
        p3_wx <= WEIGHT_W'(phx >> cfg_ss_log2);
        p3_wy <= WEIGHT_W'(phy >> cfg_ss_log2);
    end

    // ---- p4 .. p7: E and E_H (cube4_plane) ----
    wire [M_W-1:0]    f_m;
    wire [DIM_W-1:0]  f_j;
    wire [PB_W-1:0]   f_pb;
    wire [LANE_W-1:0] f_skew;
    assign {f_m, f_j, f_pb, f_skew} = p3_f;
    wire [P*LANE_W-1:0] unused_t;
    wire [P*EW-1:0]     e, e_h;
    wire [P-1:0]        e_near;               // E < E_H
    cube4_plane #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .FAR(1)
    ) u_plane (
        .clk(clk), .cfg(cfg), .in_m(f_m), .in_j(f_j), .in_pb(f_pb), .in_skew(f_skew),
        .in_wx(p3_wx), .in_wy(p3_wy), .c0_t(unused_t), .e(e), .e_h(e_h), .e_near(e_near));

    // ---- p8: max(min(E, E_H), 0); p9: f ----
    // f saturates where d >> FALL_SH >= 256, that is where d has a bit at
    // 8 + FALL_SH or above: an AND with a mask of those bits and an OR of the
    // result, beside the shift (whose low 8 bits alone are f otherwise), not a
    // compare of the shifted word on a carry chain after the shifter (47 bits:
    // the SLAB build's critical path). The mask and the shifts' FALL_SH are
    // registers of the unit's own, loaded on every edge (a view constant:
    // stable long before a frame's first beat reaches p8). FALL_SH selects in
    // every stage of every lane's shifter: one kept copy per lane
    // (cube4_prim_copies), so that no one register drives all P shifters
    // across the unit (a placed SLAB build's path, 0.9 ns of logic and 5.8 ns
    // of route from one FALL_SH register).
    localparam integer DW = EW - 1;                 // d >= 0: EW - 1 bits
    reg  [DW-1:0]  sat_mask;                        // the bits of d at 8 + FALL_SH and above
    wire [P*6-1:0] fall_sh;                         // FALL_SH, lane q's copy at [q*6 +: 6]
    always @(posedge clk)
        sat_mask <= {DW{1'b1}} << (7'd8 + {1'b0, cfg_fall_sh});
    cube4_prim_copies #(.N(P), .W(6), .RESET(0)) u_fall_sh (
        .clk(clk), .rst(1'b0), .d(cfg_fall_sh), .q(fall_sh));
    genvar ln;
    generate
        for (ln = 0; ln < P; ln = ln + 1) begin : g_lane
            wire signed [EW-1:0] el = e[ln*EW +: EW];
            wire signed [EW-1:0] eh = e_h[ln*EW +: EW];
            wire signed [EW-1:0] mn = e_near[ln] ? el : eh;   // min(E, E_H)
            reg  [DW-1:0]        p8_d;          // >= 0
            reg  [FALL_W-1:0]    p9_f;
            wire [DW-1:0]        sh  = p8_d >> fall_sh[ln*6 +: 6];
            wire                 sat = |(p8_d & sat_mask);
            always @(posedge clk) begin
                p8_d <= mn[EW-1] ? '0 : mn[EW-2:0];
                p9_f <= !cfg_fall_on ? FALL_W'(256)
                      : sat ? FALL_W'(256) : {1'b0, sh[FALL_W-2:0]};
            end
`ifndef SYNTHESIS
            always @(posedge clk) begin
                if (sat != (sh >= DW'(256)))
                    $fatal(1, "cube4_sha_slab: lane %0d's saturation %0d differs from d >> FALL_SH >= 256 (d %0d, FALL_SH %0d)",
                           ln, sat, p8_d, fall_sh[ln*6 +: 6]);
            end
`endif
            wire unused_sh = ^sh[DW-1:FALL_W-1];
            assign fall[ln*FALL_W +: FALL_W] = p9_f;
        end
    endgenerate
    wire unused_cfg = ^{unused_t, cfg};

endmodule
`default_nettype wire

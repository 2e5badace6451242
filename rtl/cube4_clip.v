`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_clip
// -----------------------------------------------------------------------------
// Purpose
//   Which samples of a beat count (docs/numerics.md section 12): the window
//     WIN_I0 <= i < WIN_I1,  WIN_J0 <= j < WIN_J1,  WIN_M0 <= m < WIN_M1
//   the crop regions: along i a sample is below (0) when i < CR_I0, above (2)
//   when i > CR_I1 or i = CR_I1 and wx > 0, else within (1); j alike with wy;
//   m below when m < CR_M0, above when m > CR_M1; it counts unless bit
//   ri + 3 rj + 9 rm of CR_HIDE is set;
//   and the kept side of the cut plane, E >= 0 (cube4_plane), with SLAB = 1
//   also the slab's far face, E <= CUT_T (E_H >= 0),
//   evaluated exactly at every sample (m, j, i) of the beat, lane q holding
//   i = pb * P + t, t = lane_pos(q, skew). The result is the header's KEEP
//   mask (cube4_tri writes it); a sample outside the box is dealt with by
//   INSIDE, not here. Golden twin: golden/cube4/clip.py.
//
// Parameters
//   P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W as cube4_tri (derived widths and the
//   view layout: cube4_defs.vh).
//   SLAB   1: the slab's far face too. 0..1. Default 0.
//
// Latency
//   5 register stages, no enable (the caller's pipeline moves on every cycle):
//   keep belongs to the inputs of 5 cycles earlier.
//     c0  window compares along j and m; the beat's regions along j and m
//         and the three CR_HIDE bits of its row of regions along i; (in
//         cube4_plane) each lane's position t, the beat products' operands
//     c1  window compares along i; each lane's region along i and its
//         CR_HIDE bit; (cube4_plane) the products, each lane's CUT_A * t
//     c2, c3  (cube4_plane) the beat's sums
//     c4  each lane's E and its sign (and E_H's), with the window: keep
//
// Ports
//   cfg            view registers (WIN_*, CR_*, CUT_*, FLIP_I, I_R1, SS_LOG2)
//   in_m, in_j, in_pb, in_skew   the beat (as the header's fields)
//   in_wx, in_wy   the beat's resampling weights, Q0.W
//   keep [P]       lane q's sample counts (5 cycles later)
//
// Bit growth and rounding
//   None: exact integers (cube4_plane).
// =============================================================================
module cube4_clip #(
    parameter integer P        = 8, parameter integer MAX_DIM     = 256,
    parameter integer WEIGHT_W = 8, parameter integer MAX_SS_LOG2 = 0,
    parameter integer SLAB     = 0,
    `CUBE4_GEOMETRY, `CUBE4_VIEW_LAYOUT
) (
    input  wire clk,
    input  wire [VIEW_W-1:0] cfg,
    input  wire [M_W-1:0] in_m, input wire [DIM_W-1:0] in_j, input wire [PB_W-1:0] in_pb,
    input  wire [LANE_W-1:0] in_skew,
    input  wire [WEIGHT_W-1:0] in_wx, input wire [WEIGHT_W-1:0] in_wy,
    output wire [P-1:0] keep
);
    generate
        `CUBE4_RANGE(g_bad_slab, "cube4_clip", "SLAB", SLAB, 0, 1)
    endgenerate
    `CUBE4_VIEW_FIELDS(cfg);

    localparam integer EW = CUT_E_W;

    // ---- c0 .. c3 (+ combinational): each lane's E and E_H ----
    wire [P*LANE_W-1:0] c0_t;
    wire [P*EW-1:0]     e, e_h;
    wire [P-1:0]        unused_near;      // (the slab's falloff alone needs it)
    cube4_plane #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .FAR(SLAB)
    ) u_plane (
        .clk(clk), .cfg(cfg), .in_m(in_m), .in_j(in_j), .in_pb(in_pb), .in_skew(in_skew),
        .in_wx(in_wx), .in_wy(in_wy), .c0_t(c0_t), .e(e), .e_h(e_h), .e_near(unused_near));

    // ---- c0: window along j and m; the beat's regions ----
    reg                   c0_wjm;                     // j and m inside the window
    reg [IW-1:0]          c0_pbp;                     // pb * P
    // the beat's crop regions along j and m (0 below, 1 within, 2 above), and
    // the CR_HIDE bits of its three regions along i
    wire [1:0] rj = (in_j < cfg_cr_j0) ? 2'd0
                  : ((in_j > cfg_cr_j1) || (in_j == cfg_cr_j1 && in_wy != '0)) ? 2'd2 : 2'd1;
    wire [1:0] rm = (in_m < cfg_cr_m0) ? 2'd0 : (in_m > cfg_cr_m1) ? 2'd2 : 2'd1;
    // CR_HIDE bits 3 rj + 9 rm .. + 2 (regions (0..2, rj, rm)): a 9-bit plane by rm, then
    // a 3-bit row by rj, each a multiplexer of constant slices (an index computed as
    // rj * 3 + rm * 9 made synthesis put two multipliers on this path)
    wire [8:0] plane = (rm == 2'd0) ? cfg_cr_hide[8:0] : (rm == 2'd1) ? cfg_cr_hide[17:9] : cfg_cr_hide[26:18];
    wire [2:0] row   = (rj == 2'd0) ? plane[2:0] : (rj == 2'd1) ? plane[5:3] : plane[8:6];
    reg [2:0]             c0_hide;                    // CR_HIDE of regions (ri, rj, rm), ri = 0, 1, 2
    reg                   c0_wx_nz;                   // wx > 0: a lane at i = CR_I1 lies past it
    always @(posedge clk) begin
        c0_wjm   <= (in_j >= cfg_win_j0) && (in_j < cfg_win_j1) && (in_m >= cfg_win_m0) && (in_m < cfg_win_m1);
        c0_pbp   <= IW'(in_pb) * IW'(P);
        c0_hide  <= row;
        c0_wx_nz <= in_wx != '0;
    end

    // ---- c1: window compares along i, each lane's region; c2, c3: carried ----
    reg         c1_wjm, c2_wjm, c3_wjm;
    reg [P-1:0] c1_wi, c2_wi, c3_wi;                  // lane's i inside the window, its region kept
    always @(posedge clk) begin
        {c3_wjm, c2_wjm, c1_wjm} <= {c2_wjm, c1_wjm, c0_wjm};
        {c3_wi, c2_wi}           <= {c2_wi, c1_wi};
    end
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            wire [IW-1:0] i = c0_pbp + IW'(c0_t[q*LANE_W +: LANE_W]);
            wire below = i < IW'(cfg_cr_i0);
            wire above = (i > IW'(cfg_cr_i1)) || (i == IW'(cfg_cr_i1) && c0_wx_nz);
            wire hide  = below ? c0_hide[0] : above ? c0_hide[2] : c0_hide[1];
            always @(posedge clk) c1_wi[q] <= (i >= IW'(cfg_win_i0)) && (i < IW'(cfg_win_i1)) && !hide;
        end
    endgenerate

    // ---- c4: each lane's E's sign (and E_H's), the window ----
    reg [P-1:0] c4_keep;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_c4
            wire far_ok = (SLAB == 0) || !e_h[q*EW + EW - 1];
            always @(posedge clk) c4_keep[q] <= c3_wjm && c3_wi[q] && !e[q*EW + EW - 1] && far_ok;
        end
        if (SLAB == 0) begin : g_no_far
            wire unused_e_h = ^e_h;
        end
    endgenerate
    assign keep = c4_keep;

    // the plane's value bits below the sign are the slab unit's, not KEEP's
    wire unused_e = ^e;

endmodule
`default_nettype wire

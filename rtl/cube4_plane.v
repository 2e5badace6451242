`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_plane
// -----------------------------------------------------------------------------
// Purpose
//   The cut plane's value at every sample of a beat (docs/numerics.md
//   section 12), and with FAR = 1 the slab's far face's:
//     E   = CUT_A * (i * 2^W + wx) + CUT_B * (j * 2^W + wy) + CUT_C * (m * 2^(W - g)) + CUT_D
//     E_H = CUT_T - E
//     e_near = E < E_H (FAR = 1; 2 E < CUT_T, that is E < H = ceil(CUT_T / 2))
//   (g = log2 S: every coordinate in units of 2^-W voxel), lane q holding
//   i = pb * P + t, t = lane_pos(q, skew). Golden twin: golden/cube4/clip.py
//   plane_value. One definition for the two places that need it: cube4_clip
//   (KEEP, in TRI) and cube4_sha_slab (the falloff weight, in SHA).
//
//   The beat terms are three products shared by the lanes:
//     E = CUT_A * (pb * P * 2^W + wx) + CUT_B * (j * 2^W + wy) + CUT_C * (m * 2^(W - g)) + CUT_D
//         + (CUT_A * t) * 2^W
//   and each lane adds its own CUT_A * t (t < P): a table of the P products
//   in registers, formed from the (static) coefficient a cycle before, so
//   the lane's position only selects (no multiplier after the position's
//   logic). E_H likewise from CUT_T - CUT_D, registered from the static
//   registers, and e_near as a compare of the lane's CUT_A * t * 2^W with the
//   beat's H - (E less it), formed likewise from H - CUT_D: so the caller's
//   min(E, E_H) selects by a bit made beside E's and E_H's sums, not by a
//   compare of them after the sums (the SLAB build's path).
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2 as cube4_tri (derived widths and the
//   view layout: cube4_defs.vh).
//   FAR   1: also E_H (the slab's far face). 0..1. Default 0.
//
// Latency
//   4 register stages, no enable (the caller's pipeline moves on every cycle);
//   e and e_h are combinational from the last (the caller registers them, or
//   what it makes of them, as its stage c4):
//     c0  each lane's position t; the operands of the three beat products
//         (cube4_mul's input registers)
//     c1  the three beat products (cube4_mul's output registers); each lane's
//         CUT_A * t (from the table, which follows cfg one cycle late: cfg is
//         written between frames, many cycles before a beat arrives)
//     c2  the beat's sum in two halves (CUT_A and CUT_B terms; CUT_C and
//         CUT_D, or CUT_T - CUT_D)
//     c3  the beat's sum (and the far face's)
//   c0_t: lane q's position t at c0 (for the caller's per-lane logic).
//
// Ports
//   cfg            view registers (CUT_*, FLIP_I, I_R1, SS_LOG2)
//   in_m, in_j, in_pb, in_skew   the beat (as the header's fields)
//   in_wx, in_wy   the beat's resampling weights, Q0.W
//   c0_t  [P*LANE_W]  each lane's t, registered at c0
//   e, e_h [P*CUT_E_W]  lane q's E and E_H, signed (combinational from c3)
//   e_near [P]       lane q's E < E_H (combinational from c3; 0 with FAR = 0)
//
// Bit growth and rounding
//   None: exact integers. i * 2^W + wx and m * 2^(W - g) are below
//   (MAX_DIM + 2P) * 2^W (IW + W bits), the coefficients are CUT_W = 18 bits
//   signed, and the host chooses them so that |E| < 2^(CUT_E_W - 1) = 2^47
//   over the box and CUT_T + |E| < 2^47 (golden/cube4/clip.py
//   cut_coefficients, slab_coefficients), so neither wraps in CUT_E_W bits.
//   c2's two halves are sums modulo 2^CUT_E_W, so their sum at c3 is exact
//   even where a half alone would not fit. e_near's terms are CUT_E_W + 2 bits
//   (|H - E| < 2^46 + 2^47 and CUT_A * t * 2^W below 2^(AT_W + W - 1)), so
//   its compare is exact wherever E and E_H are.
// =============================================================================
module cube4_plane #(
    parameter integer P        = 8, parameter integer MAX_DIM     = 256,
    parameter integer WEIGHT_W = 8, parameter integer MAX_SS_LOG2 = 0,
    parameter integer FAR      = 0,
    `CUBE4_GEOMETRY, `CUBE4_VIEW_LAYOUT
) (
    input  wire clk,
    input  wire [VIEW_W-1:0] cfg,
    input  wire [M_W-1:0] in_m, input wire [DIM_W-1:0] in_j, input wire [PB_W-1:0] in_pb,
    input  wire [LANE_W-1:0] in_skew,
    input  wire [WEIGHT_W-1:0] in_wx, input wire [WEIGHT_W-1:0] in_wy,
    output wire [P*LANE_W-1:0] c0_t,
    output wire [P*CUT_E_W-1:0] e, output wire [P*CUT_E_W-1:0] e_h,
    output wire [P-1:0] e_near
);
    generate
        `CUBE4_RANGE(g_bad_far, "cube4_plane", "FAR", FAR, 0, 1)
    endgenerate
    `CUBE4_VIEW_FIELDS(cfg);
    `CUBE4_LANE_FUNCTIONS

    localparam integer EW  = CUT_E_W;
    localparam integer X_W = IW + WEIGHT_W + 1;     // i * 2^W + wx, signed (>= 0)
    localparam integer AT_W = CUT_W + LANE_W + 2;   // CUT_A * t

    // ---- c0: the multipliers' operands; each lane's position ----
    wire [IW-1:0] pbp = IW'(in_pb) * IW'(P);
    wire signed [X_W-1:0] xi = $signed({1'b0, pbp, in_wx});                         // pb*P*2^W + wx
    wire signed [X_W-1:0] xj = $signed({1'b0, IW'(in_j), in_wy});                   // j*2^W + wy
    wire [X_W-2:0]        m_sh = (X_W - 1)'(in_m) << (WEIGHT_W[3:0] - {2'b00, cfg_ss_log2});
    wire signed [X_W-1:0] xm = $signed({1'b0, m_sh});                              // m * 2^(W - g)
    reg [LANE_W-1:0]      c0_tq [0:P-1];              // lane q's position t

    // ---- c0 .. c1: the three beat products (operand and product registers
    // are cube4_mul's own: the ECP5 form is a MULT18X18D with its registers) ----
    localparam integer PR_W = CUT_W + X_W;
    wire signed [PR_W-1:0] c1_a, c1_b, c1_c;
    cube4_mul #(.A_W(CUT_W), .B_W(X_W)) u_mul_a (.clk(clk), .en(1'b1), .a(cfg_cut_a), .b(xi), .p(c1_a));
    cube4_mul #(.A_W(CUT_W), .B_W(X_W)) u_mul_b (.clk(clk), .en(1'b1), .a(cfg_cut_b), .b(xj), .p(c1_b));
    cube4_mul #(.A_W(CUT_W), .B_W(X_W)) u_mul_c (.clk(clk), .en(1'b1), .a(cfg_cut_c), .b(xm), .p(c1_c));

    // ---- c1: each lane's CUT_A * t ----
    reg signed [AT_W-1:0] c1_at [0:P-1];      // CUT_A * t
    reg signed [AT_W-1:0] at_tab [0:P-1];     // CUT_A * k, k = 0 .. P - 1
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            always @(posedge clk) begin
                at_tab[q] <= cfg_cut_a * $signed({2'b00, LANE_W'(q)});
                c0_tq[q]  <= lane_pos(q, in_skew, cfg_flip_i, cfg_i_r1);
                c1_at[q]  <= at_tab[c0_tq[q]];
            end
            assign c0_t[q*LANE_W +: LANE_W] = c0_tq[q];
        end
    endgenerate

    // ---- c2: the beat's sum in two halves; c3: the sum ----
    // (two adders of two operands each, then one: a sum of four straight
    // after the multipliers' registers was the P = 4 build's path)
    reg signed [EW-1:0] c2_ab, c2_cd, c3_base;
    reg signed [AT_W-1:0] c2_at [0:P-1];
    reg signed [AT_W-1:0] c3_at [0:P-1];
    integer k;
    always @(posedge clk) begin
        c2_ab   <= EW'(c1_a) + EW'(c1_b);
        c2_cd   <= EW'(c1_c) + cfg_cut_d;
        c3_base <= c2_ab + c2_cd;
        for (k = 0; k < P; k = k + 1) begin
            c2_at[k] <= c1_at[k];
            c3_at[k] <= c2_at[k];
        end
    end

    // ---- after c3: each lane's E (and E_H) ----
    generate
        for (q = 0; q < P; q = q + 1) begin : g_e
            assign e[q*EW +: EW] = c3_base + (EW'(c3_at[q]) <<< WEIGHT_W);
        end
        if (FAR != 0) begin : g_far
            // E_H = CUT_T - E = (CUT_T - CUT_D - CUT_C term) - (CUT_A, CUT_B terms) - CUT_A * t * 2^W
            reg signed [EW-1:0] td_q, c2_tcd, c3_tbase;
            always @(posedge clk) begin
                td_q     <= cfg_cut_t - cfg_cut_d;
                c2_tcd   <= td_q - EW'(c1_c);
                c3_tbase <= c2_tcd - c2_ab;
            end
            for (q = 0; q < P; q = q + 1) begin : g_eh
                assign e_h[q*EW +: EW] = c3_tbase - (EW'(c3_at[q]) <<< WEIGHT_W);
            end
            // e_near: E < CUT_T - E <=> E < H = ceil(CUT_T / 2) = (CUT_T + 1) >>> 1
            // <=> CUT_A * t * 2^W < H - (E less it): H - CUT_D, less the CUT_C
            // term (c2), less the CUT_A and CUT_B terms (c3), in HW bits
            localparam integer HW = EW + 2;
            reg  signed [HW-1:0] hd_q, c2_hcd, c3_hbase;
            wire signed [HW-1:0] t_w = HW'($signed(cfg_cut_t));   // (the view fields are unsigned)
            wire signed [HW-1:0] d_w = HW'($signed(cfg_cut_d));
            always @(posedge clk) begin
                hd_q     <= ((t_w + HW'(1)) >>> 1) - d_w;
                c2_hcd   <= hd_q - HW'(c1_c);
                c3_hbase <= c2_hcd - HW'(c2_ab);
            end
            for (q = 0; q < P; q = q + 1) begin : g_near
                assign e_near[q] = (HW'(c3_at[q]) <<< WEIGHT_W) < c3_hbase;
            end
`ifndef SYNTHESIS
            // e_near is E < E_H wherever E_H is CUT_T - E without wrap, for the
            // CUT_T c3 was formed from: every sample of a slab (the host's
            // bounds). Skipped: the cycles around a view change, when the idle
            // pipeline mixes two views, and frames without a slab, whose CUT_T
            // (CUT_T_NONE, 2^47 - 1) wraps E_H only where E < 0 (samples the
            // cut plane drops) and whose falloff is off (FALL_ON = 0)
            reg [EW-1:0] t_s1, t_s2, t_s3;
            always @(posedge clk) {t_s3, t_s2, t_s1} <= {t_s2, t_s1, cfg_cut_t};
            for (q = 0; q < P; q = q + 1) begin : g_near_check
                wire signed [EW-1:0] eq = e[q*EW +: EW], ehq = e_h[q*EW +: EW];
                always @(posedge clk) begin
                    if ($signed({t_s3[EW-1], t_s3}) - $signed({eq[EW-1], eq}) == $signed({ehq[EW-1], ehq})
                        && e_near[q] != (eq < ehq))
                        $fatal(1, "cube4_plane: lane %0d's e_near %0d differs from E < E_H (E %0d, E_H %0d)",
                               q, e_near[q], eq, ehq);
                end
            end
`endif
        end else begin : g_no_far
            assign e_h  = '0;
            assign e_near = '0;
        end
    endgenerate

endmodule
`default_nettype wire

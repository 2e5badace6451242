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
//   and the kept side of the cut plane
//     E = CUT_A * (i * 2^W + wx) + CUT_B * (j * 2^W + wy) + CUT_C * (m * 2^(W - g)) + CUT_D >= 0
//   (g = log2 S: every coordinate in units of 2^-W voxel)
//   evaluated exactly at every sample (m, j, i) of the beat, lane q holding
//   i = pb * P + t, t = lane_pos(q, skew). The result is the header's KEEP
//   mask (cube4_tri writes it); a sample outside the box is dealt with by
//   INSIDE, not here. Golden twin: golden/cube4/clip.py.
//
//   The plane's beat terms are three products shared by the lanes:
//     E = CUT_A * (pb * P * 2^W + wx) + CUT_B * (j * 2^W + wy) + CUT_C * (m * 2^(W - g)) + CUT_D
//         + (CUT_A * t) * 2^W
//   and each lane adds its own CUT_A * t (t < P): a table of the P products
//   in registers, formed from the (static) coefficient a cycle before, so
//   the lane's position only selects (no multiplier after the position's
//   logic).
//
// Parameters
//   P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W as cube4_tri (derived widths and the
//   view layout: cube4_defs.vh).
//
// Latency
//   5 register stages, no enable (the caller's pipeline moves on every cycle):
//   keep belongs to the inputs of 5 cycles earlier.
//     c0  window compares along j and m; the beat's regions along j and m
//         and the three CR_HIDE bits of its row of regions along i; each
//         lane's position t; the operands of the three beat products
//         (cube4_mul's input registers)
//     c1  the three beat products (cube4_mul's output registers); window
//         compares along i; each lane's region along i and its CR_HIDE bit;
//         each lane's CUT_A * t (from the table, which
//         follows cfg one cycle late: cfg is written between frames, many
//         cycles before a beat arrives)
//     c2  the beat's sum in two halves (CUT_A and CUT_B terms; CUT_C and CUT_D)
//     c3  the beat's sum
//     c4  each lane's E and its sign, with the window: keep
//
// Ports
//   cfg            view registers (WIN_*, CR_*, CUT_*, FLIP_I, I_R1, SS_LOG2)
//   in_m, in_j, in_pb, in_skew   the beat (as the header's fields)
//   in_wx, in_wy   the beat's resampling weights, Q0.W
//   keep [P]       lane q's sample counts (5 cycles later)
//
// Bit growth and rounding
//   None: exact integers. i * 2^W + wx and m * 2^(W - g) are below
//   (MAX_DIM + 2P) * 2^W (IW + W bits), the
//   coefficients are CUT_W = 18 bits signed, and the host chooses them so that
//   |E| < 2^(CUT_E_W - 1) = 2^47 over the box (golden/cube4/clip.py
//   cut_coefficients), so E never wraps in CUT_E_W bits. c2's two halves are
//   sums modulo 2^CUT_E_W, so their sum at c3 is E exactly even where a half
//   alone would not fit.
// =============================================================================
module cube4_clip #(
    parameter integer P        = 8, parameter integer MAX_DIM     = 256,
    parameter integer WEIGHT_W = 8, parameter integer MAX_SS_LOG2 = 0,
    `CUBE4_GEOMETRY, `CUBE4_VIEW_LAYOUT
) (
    input  wire clk,
    input  wire [VIEW_W-1:0] cfg,
    input  wire [M_W-1:0] in_m, input wire [DIM_W-1:0] in_j, input wire [PB_W-1:0] in_pb,
    input  wire [LANE_W-1:0] in_skew,
    input  wire [WEIGHT_W-1:0] in_wx, input wire [WEIGHT_W-1:0] in_wy,
    output wire [P-1:0] keep
);
    `CUBE4_VIEW_FIELDS(cfg);
    `CUBE4_LANE_FUNCTIONS

    localparam integer EW  = CUT_E_W;
    localparam integer X_W = IW + WEIGHT_W + 1;     // i * 2^W + wx, signed (>= 0)

    // ---- c0: the multipliers' operands; each lane's position ----
    wire [IW-1:0] pbp = IW'(in_pb) * IW'(P);
    wire signed [X_W-1:0] xi = $signed({1'b0, pbp, in_wx});                         // pb*P*2^W + wx
    wire signed [X_W-1:0] xj = $signed({1'b0, IW'(in_j), in_wy});                   // j*2^W + wy
    wire [X_W-2:0]        m_sh = (X_W - 1)'(in_m) << (WEIGHT_W[3:0] - {2'b00, cfg_ss_log2});
    wire signed [X_W-1:0] xm = $signed({1'b0, m_sh});                              // m * 2^(W - g)
    reg                   c0_wjm;                     // j and m inside the window
    reg [IW-1:0]          c0_pbp;                     // pb * P
    reg [LANE_W-1:0]      c0_t [0:P-1];               // lane q's position t
    // the beat's crop regions along j and m (0 below, 1 within, 2 above), and
    // the CR_HIDE bits of its three regions along i
    wire [1:0] rj = (in_j < cfg_cr_j0) ? 2'd0
                  : ((in_j > cfg_cr_j1) || (in_j == cfg_cr_j1 && in_wy != '0)) ? 2'd2 : 2'd1;
    wire [1:0] rm = (in_m < cfg_cr_m0) ? 2'd0 : (in_m > cfg_cr_m1) ? 2'd2 : 2'd1;
    wire [4:0] row = 5'(rj) * 5'd3 + 5'(rm) * 5'd9;     // region (0, rj, rm)
    reg [2:0]             c0_hide;                    // CR_HIDE of regions (ri, rj, rm), ri = 0, 1, 2
    reg                   c0_wx_nz;                   // wx > 0: a lane at i = CR_I1 lies past it
    always @(posedge clk) begin
        c0_wjm   <= (in_j >= cfg_win_j0) && (in_j < cfg_win_j1) && (in_m >= cfg_win_m0) && (in_m < cfg_win_m1);
        c0_pbp   <= pbp;
        c0_hide  <= cfg_cr_hide[row +: 3];
        c0_wx_nz <= in_wx != '0;
    end

    // ---- c0 .. c1: the three beat products (operand and product registers
    // are cube4_mul's own: the ECP5 form is a MULT18X18D with its registers) ----
    localparam integer PR_W = CUT_W + X_W;
    wire signed [PR_W-1:0] c1_a, c1_b, c1_c;
    cube4_mul #(.A_W(CUT_W), .B_W(X_W)) u_mul_a (.clk(clk), .en(1'b1), .a(cfg_cut_a), .b(xi), .p(c1_a));
    cube4_mul #(.A_W(CUT_W), .B_W(X_W)) u_mul_b (.clk(clk), .en(1'b1), .a(cfg_cut_b), .b(xj), .p(c1_b));
    cube4_mul #(.A_W(CUT_W), .B_W(X_W)) u_mul_c (.clk(clk), .en(1'b1), .a(cfg_cut_c), .b(xm), .p(c1_c));

    // ---- c1: window compares along i; each lane's CUT_A * t ----
    reg                 c1_wjm;
    reg [P-1:0]         c1_wi;                        // lane's i inside the window, its region kept
    reg signed [CUT_W+LANE_W+1:0] c1_at [0:P-1];      // CUT_A * t
    reg signed [CUT_W+LANE_W+1:0] at_tab [0:P-1];     // CUT_A * k, k = 0 .. P - 1
    always @(posedge clk) c1_wjm <= c0_wjm;
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_tab
            always @(posedge clk) at_tab[q] <= cfg_cut_a * $signed({2'b00, LANE_W'(q)});
        end
        for (q = 0; q < P; q = q + 1) begin : g_lane
            always @(posedge clk) c0_t[q] <= lane_pos(q, in_skew, cfg_flip_i, cfg_i_r1);
            wire [IW-1:0] i = c0_pbp + IW'(c0_t[q]);
            wire below = i < IW'(cfg_cr_i0);
            wire above = (i > IW'(cfg_cr_i1)) || (i == IW'(cfg_cr_i1) && c0_wx_nz);
            wire hide  = below ? c0_hide[0] : above ? c0_hide[2] : c0_hide[1];
            always @(posedge clk) begin
                c1_wi[q] <= (i >= IW'(cfg_win_i0)) && (i < IW'(cfg_win_i1)) && !hide;
                c1_at[q] <= at_tab[c0_t[q]];
            end
        end
    endgenerate

    // ---- c2: the beat's sum in two halves; c3: the sum ----
    // (two adders of two operands each, then one: a sum of four straight
    // after the multipliers' registers was the P = 4 build's path)
    reg signed [EW-1:0] c2_ab, c2_cd, c3_base;
    reg                 c2_wjm, c3_wjm;
    reg [P-1:0]         c2_wi, c3_wi;
    reg signed [CUT_W+LANE_W+1:0] c2_at [0:P-1];
    reg signed [CUT_W+LANE_W+1:0] c3_at [0:P-1];
    integer k;
    always @(posedge clk) begin
        c2_ab   <= EW'(c1_a) + EW'(c1_b);
        c2_cd   <= EW'(c1_c) + cfg_cut_d;
        c3_base <= c2_ab + c2_cd;
        {c3_wjm, c2_wjm} <= {c2_wjm, c1_wjm};
        {c3_wi, c2_wi}   <= {c2_wi, c1_wi};
        for (k = 0; k < P; k = k + 1) begin
            c2_at[k] <= c1_at[k];
            c3_at[k] <= c2_at[k];
        end
    end

    // ---- c4: each lane's E, its sign, the window ----
    reg [P-1:0] c4_keep;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_c4
            wire signed [EW-1:0] e = c3_base + (EW'(c3_at[q]) <<< WEIGHT_W);
            always @(posedge clk) c4_keep[q] <= c3_wjm && c3_wi[q] && !e[EW-1];
        end
    endgenerate
    assign keep = c4_keep;

endmodule
`default_nettype wire

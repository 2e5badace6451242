`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_gra_arith
// -----------------------------------------------------------------------------
// Purpose
//   GRA's arithmetic, docs/numerics.md section 5, lane by lane, from the
//   window's operands (cube4_gra_window):
//     gi = hi - lo                      = s[m, j, i+1] - s[m, j, i-1]
//     gr = fwd - back                   = s[m+1, j+dyf, i+dxf] - s[m-1, j-dyb, i-dxb]
//     gk = S * gr - round_shift(VIEW_X * gi + VIEW_Y * gj, WEIGHT_W)
//   (gj arrives as a difference, taken in the window). gk is formed as
//     floor((G' - VIEW_X * gi - VIEW_Y * gj) / 2^WEIGHT_W),
//     G' = (gr << log2 S) * 2^WEIGHT_W + 2^(WEIGHT_W-1) - 1
//   (the same integer, since c - floor((x + h) / 2^W) =
//   floor((c * 2^W - x - h + 2^W - 1) / 2^W) with h = 2^(W-1); G''s low bits
//   are the constant, so it needs no adder): two subtractions, as the
//   rounding add and the subtraction were. Formed modulo 2^(GRAD_W + WEIGHT_W);
//   its top GRAD_W bits are gk (which fits: nothing wraps).
//
// Parameters
//   P, VOXEL_W, WEIGHT_W, MAX_DIM, MAX_SS_LOG2 as cube4_gra (MAX_DIM and
//   MAX_SS_LOG2 only size the header and the view bus)
//   GRAD_W  VOXEL_W + 5 (derived; signed)
//
// Latency
//   Four register stages with no clock enable, loaded on every cycle:
//   g1 the differences (their carry chains end at g1's flip-flops); g2 the
//   multipliers' operand registers (cube4_mul, fed from g1's flip-flops) and
//   G'; g3 the products (the multipliers' own output registers); g4 the
//   products again, in flip-flops in the fabric (cube4_mul OUT_FF = 1: the
//   route from a multiplier placed far away ends at a flip-flop, not at the
//   subtractions). out_* are g4 with gk's two subtractions after it (the
//   caller stores them: GRA's output FIFO's memory). A beat given with in_v
//   in cycle t is on out_* in cycle t + 4; out_v_d = 1 in cycle t + 3 says
//   so a cycle ahead (the FIFO's push_d).
//
// Ports (P lanes; lane q of a W-bit field at [q*W +: W])
//   in_v         in   a real centre (GRA's take)
//   in_hdr       in   [HDR_W]          its header, passed through
//   in_s         in   [P*VOXEL_W]      s[m, j, i], unsigned Q0.VOXEL_W, passed through
//   in_hi, in_lo, in_fwd, in_back  in  [P*VOXEL_W]  unsigned Q0.VOXEL_W samples
//   in_gj        in   [P*(VOXEL_W+1)]  signed integer
//   cfg          in   view registers: VIEW_X, VIEW_Y (Q1.W, 0 .. 2^W), SS_LOG2
//   out_v_d      out  out_* hold a beat in the next cycle
//   out_hdr, out_sample               the beat's header and samples
//   out_gi, out_gj, out_gk  [P*GRAD_W]  signed integers
//
// Bit growth and rounding
//   gi, gj, gr: VOXEL_W + 1 bits signed, exact. VIEW_X * gi, VIEW_Y * gj:
//   VOXEL_W + WEIGHT_W + 3 bits signed each (cube4_mul), exact; their sum
//   rounded by WEIGHT_W (half up, the only rounding) gives VOXEL_W + 5 bits;
//   |gk| < 2^(VOXEL_W+3) + 2^(VOXEL_W+1), so GRAD_W = VOXEL_W + 5 holds
//   every result exactly; gi and gj are sign-extended to GRAD_W. No
//   saturation.
// =============================================================================
module cube4_gra_arith #(
    `CUBE4_GRA_PARAMS,
    localparam integer GRAD_W = VOXEL_W + 5
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    input  wire in_v,
    input  wire [HDR_W-1:0] in_hdr,
    input  wire [P*VOXEL_W-1:0] in_s,
    input  wire [P*VOXEL_W-1:0] in_hi, input wire [P*VOXEL_W-1:0] in_lo,
    input  wire [P*VOXEL_W-1:0] in_fwd, input wire [P*VOXEL_W-1:0] in_back,
    input  wire [P*(VOXEL_W+1)-1:0] in_gj,
    output wire out_v_d,
    output wire [HDR_W-1:0] out_hdr,
    output wire [P*VOXEL_W-1:0] out_sample,
    output wire [P*GRAD_W-1:0] out_gi, output wire [P*GRAD_W-1:0] out_gj, output wire [P*GRAD_W-1:0] out_gk
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_gra_arith", "P", P, 1, 64)
        `CUBE4_RANGE(g_bad_voxel_w, "cube4_gra_arith", "VOXEL_W", VOXEL_W, 1, 16)
    endgenerate

    localparam integer VW    = VOXEL_W;
    localparam integer PV    = P * VW;
    localparam integer DW    = VW + 1;                      // differences, signed
    localparam integer MB_W  = WEIGHT_W + 2;                // a view weight (0 .. 2^W), signed
    localparam integer MP_W  = DW + MB_W;                   // a product
    localparam integer GX_W  = GRAD_W + WEIGHT_W;           // G' and the difference
    localparam [WEIGHT_W-1:0] GK_LOW = WEIGHT_W'((1 << (WEIGHT_W - 1)) - 1);

    `CUBE4_VIEW_FIELDS(cfg);
    genvar q;

    reg               g1_v, g2_v, g3_v;
    reg [HDR_W-1:0]   g1_hdr, g2_hdr, g3_hdr, g4_hdr;
    reg [PV-1:0]      g1_s, g2_s, g3_s, g4_s;
    reg [P*DW-1:0]    g1_gi, g1_gj, g1_gr, g2_gi, g2_gj, g2_gr, g3_gi, g3_gj, g4_gi, g4_gj;
    reg [P*GX_W-1:0]  g3_gpre, g4_gpre;
    always @(posedge clk) begin
        if (rst) begin
            g1_v <= 1'b0;
            g2_v <= 1'b0;
            g3_v <= 1'b0;
        end else begin
            g1_v <= in_v;
            g2_v <= g1_v;
            g3_v <= g2_v;
        end
    end
    assign out_v_d = g3_v;

    wire [P*DW-1:0]     gi_d, gr_d;
    wire [P*GX_W-1:0]   gpre_d;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            // g1: the differences
            assign gi_d[q*DW +: DW] = $signed({1'b0, in_hi[q*VW +: VW]})  - $signed({1'b0, in_lo[q*VW +: VW]});
            assign gr_d[q*DW +: DW] = $signed({1'b0, in_fwd[q*VW +: VW]}) - $signed({1'b0, in_back[q*VW +: VW]});
            // g2 -> g4: VIEW_X * gi, VIEW_Y * gj (operand registers at g2, products at
            // g3 in the multipliers and at g4 in the fabric)
            wire signed [MP_W-1:0] px, py;
            wire signed [DW-1:0]   gi_a = g1_gi[q*DW +: DW];
            wire signed [DW-1:0]   gj_a = g1_gj[q*DW +: DW];
            wire signed [MB_W-1:0] vx_b = {1'b0, cfg_view_x};
            wire signed [MB_W-1:0] vy_b = {1'b0, cfg_view_y};
            cube4_mul #(.A_W(DW), .B_W(MB_W), .OUT_FF(1)) u_px (
                .clk (clk), .en (1'b1), .a (gi_a), .b (vx_b), .p (px));
            cube4_mul #(.A_W(DW), .B_W(MB_W), .OUT_FF(1)) u_py (
                .clk (clk), .en (1'b1), .a (gj_a), .b (vy_b), .p (py));
            // g2 -> g3: G' (a shift and a constant)
            wire signed [DW-1:0]     gr1  = g2_gr[q*DW +: DW];
            wire signed [GRAD_W-1:0] gr_e = {{(GRAD_W - DW){gr1[DW-1]}}, gr1};
            wire signed [GRAD_W-1:0] gr_s = gr_e <<< cfg_ss_log2;
            assign gpre_d[q*GX_W +: GX_W] = {gr_s, GK_LOW};
            // after g4: gk = floor((G' - VIEW_X * gi - VIEW_Y * gj) / 2^W)
            wire signed [GX_W-1:0] px_e = GX_W'(px);
            wire signed [GX_W-1:0] py_e = GX_W'(py);
            wire signed [GX_W-1:0] dif  = $signed(g4_gpre[q*GX_W +: GX_W]) - px_e - py_e;
            assign out_gk[q*GRAD_W +: GRAD_W] = dif[GX_W-1 -: GRAD_W];
            wire unused_dif = ^dif[WEIGHT_W-1:0];   // the fraction the floor drops
            wire signed [DW-1:0] gi4 = g4_gi[q*DW +: DW];
            wire signed [DW-1:0] gj4 = g4_gj[q*DW +: DW];
            assign out_gi[q*GRAD_W +: GRAD_W] = {{(GRAD_W - DW){gi4[DW-1]}}, gi4};
            assign out_gj[q*GRAD_W +: GRAD_W] = {{(GRAD_W - DW){gj4[DW-1]}}, gj4};
        end
    endgenerate

    always @(posedge clk) begin
        g1_hdr  <= in_hdr;
        g1_s    <= in_s;
        g1_gi   <= gi_d;
        g1_gj   <= in_gj;
        g1_gr   <= gr_d;
        g2_hdr  <= g1_hdr;
        g2_s    <= g1_s;
        g2_gi   <= g1_gi;
        g2_gj   <= g1_gj;
        g2_gr   <= g1_gr;
        g3_hdr  <= g2_hdr;
        g3_s    <= g2_s;
        g3_gi   <= g2_gi;
        g3_gj   <= g2_gj;
        g3_gpre <= gpre_d;
        g4_hdr  <= g3_hdr;
        g4_s    <= g3_s;
        g4_gi   <= g3_gi;
        g4_gj   <= g3_gj;
        g4_gpre <= g3_gpre;
    end
    assign out_hdr    = g4_hdr;
    assign out_sample = g4_s;

endmodule
`default_nettype wire

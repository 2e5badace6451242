`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_sha
// -----------------------------------------------------------------------------
// Purpose
//   The SHA units of all P pipelines: classification by a lookup table and
//   shading by a reflectance map (docs/numerics.md section 6):
//     (R, G, B, A) = LUT[sample]                       (colours Q0.8, A Q0.ALPHA_W)
//     idx = cube-map cell of the gradient (face, v, u), 6 R^2 for g = 0
//     (D, P) = RMAP[idx]                               (Q2.8 each)
//     C' = min(255, round_shift(C * D, 8) + P) for C in R, G, B;  A' = A
//   Every two lanes share one copy of both tables (the paper has tables per
//   pipeline; a block RAM has two ports): cube4_dual_read_ram, lane 2k
//   reading through the port that also writes, lane 2k + 1 through the
//   other, an odd P's last lane a copy of its own. The host writes them
//   through the load ports, which broadcast to all copies, at run time (a
//   new transfer function or light needs no rebuild), between frames only:
//   a write takes lane 2k's read in that cycle (cube4_top's contract). The
//   host applies the opacity correction for the view's sample distance when
//   it writes the LUT (golden/cube4/tables.py).
//   A build with SHADING = 0 classifies only (C' = C): it has no reflectance
//   map, no face select, no division and no shading multipliers, and its
//   gradient inputs are not read (cube4_top then builds no GRA).
//   With CARRY_SAMPLE = 1 the sample itself leaves with the beat (out_sample)
//   for COM's MIP / MinIP; with 0, out_sample is 0 and nothing carries it.
//
// Parameters
//   P           pipelines.                          1..64.  Default 8.
//   VOXEL_W     sample width (LUT has 2^VOXEL_W entries). 1..16. Default 8.
//   LABELS      1: a sample carries its label above the value (SMP_W =
//               VOXEL_W + 4 bits) and the LUT has 2^SMP_W entries, a block
//               of 2^VOXEL_W per label, read at {label, value} (numerics.md
//               section 24). 0..1. Default 0.
//   ALPHA_W     LUT opacity width AW.               8..16.  Default 12.
//   RMAP_BITS   cube-map resolution R = 2^RMAP_BITS. 2..6.  Default 5.
//   SHADING     1: shading by the reflectance map; 0: classification only. 0..1. Default 1.
//   CARRY_SAMPLE 1: the sample rides along to out_sample; 0: out_sample = 0. 0..1. Default 1.
//   VALID_N     copies of out_valid (out_valid_cp: the output FIFO's, each a
//               flip-flop of its own, for a consumer far away).  1..4.  Default 1.
//   SLAB        1 (with COMPOSITING = 1, FALL): the slab's falloff weights
//               (cube4_sha_slab), out_fall carried beside the beat; SHA then
//               has at least SLAB_LAT + 1 = 10 stages. 0..1. Default 0.
//   GMOD        1 (with SHADING): gradient-magnitude modulation (numerics.md
//               section 23): cube4_sha_gm's factors fa, fs of each lane's |g|^2
//               from the table written through gm_*; two more stages (m1, m2)
//               after dr modulate D and P, and A' = round_shift(A fa, 8). 0..1. Default 0.
//   MAX_DIM, MAX_SS_LOG2 and the derived widths as cube4_gra; GRAD_W = VOXEL_W + 5.
//
// Latency
//   5 + (RMAP_BITS + 1) + 6 stages (input; LUT read and |g|; the three |g|
//   comparisons; face; numerators; one stage per quotient bit of the
//   division; reflectance-map read; its output register; its fabric
//   register; C * D's operands; C * D; the products in fabric flip-flops,
//   the shading after them into the output FIFO's memory), 17 at
//   RMAP_BITS = 5: a beat is on out_* 16 cycles after it entered the input
//   register when the output FIFO was empty; 2 more with GMOD (m1, m2). SHADING = 0: 4 stages
//   (input; LUT read; its register; the output FIFO), 11 with FALL. The stages move on every
//   cycle and carry a valid bit (no stall enable); the last one is the
//   memory of the output FIFO (cube4_credit_fifo), and a beat
//   enters the input register only when that FIFO has an entry reserved for
//   it (credit-based flow control), so out_ready reaches in_ready and the
//   FIFO's pointers only. Both tables' RAM outputs go straight into a
//   register (an FPGA block RAM's clock-to-output is long).
//
// Ports
//   lut_we/lut_addr/lut_data     LUT write: lut_data = {R, G, B (Q0.8), A (Q0.ALPHA_W)},
//                                lut_addr = {label, value} (SMP_W bits)
//   rmap_we/rmap_addr/rmap_data  reflectance-map write: rmap_data = {D, P} (Q2.8 each);
//                               entry 6 R^2 (the zero gradient's) is a register
//                               beside the tables (so each table is 6 R^2 words:
//                               6144 at RMAP_BITS = 5, 7 block RAMs on the ECP5
//                               where 6145 took 9)
//   gm_we/gm_addr/gm_data        modulation table write (GMOD): gm_data = {fa, fs},
//                                0 .. 256 each (Q0.8), GMF_W bits each
//   in_*    the gradient stream of cube4_gra (gi, gj, gk signed GRAD_W bits;
//           in_sample SMP_W bits per lane)
//   out_rgba  [P*(24+ALPHA_W)]  per lane {R', G', B' (Q0.8), A (Q0.ALPHA_W)}
//   out_idx   [P*RI_W]          reflectance-map entry used (for checking and waves;
//                               0 when SHADING = 0)
//   out_sample [P*VOXEL_W]      the beat's sample values, unchanged (CARRY_SAMPLE = 1; else 0)
//   out_hdr   [HDR_W]           the beat's header, unchanged (cube4_defs.vh)
//   out_fall  [P*FALL_W]        the slab's falloff weight f of each lane, 0 .. 256
//                               (cube4_sha_slab; FALL = 1, else 256)
//   out_valid_cp [VALID_N]      copies of out_valid (copy 0 is out_valid)
//   cfg                         view registers (read by cube4_sha_slab only)
//
// Bit growth and rounding
//   Face select: |g| is GRAD_W bits unsigned. u = min(R-1, floor((g_b + A) R / 2A))
//   is an exact restoring division with an RMAP_BITS+1-bit quotient (no
//   rounding). C * D is 8 x 10 = 18 bits; round_shift by 8 (half up) gives 11
//   bits; + P (10 bits) < 2^12; the min with 255 is the one saturation.
//   GMOD: (D - 256) fs is 11 x 10 bits signed, D' = 256 + round_shift(., 8)
//   in 0 .. 1023; P' = round_shift(P fs, 8) in 0 .. 1023; A fa is (ALPHA_W +
//   1) x 10 bits, A' = round_shift(A fa, 8) <= A: no saturation.
// =============================================================================
module cube4_sha #(
    `CUBE4_BUILD_PARAMS, parameter integer CARRY_SAMPLE = 1, parameter integer VALID_N = 1,
    `CUBE4_GM_LAYOUT,
    localparam integer LBL_W  = (LABELS != 0) ? 4 : 0,     // (CUBE4_WORD_LAYOUT's)
    localparam integer SMP_W  = VOXEL_W + LBL_W,           // a sample: {label, value}
    localparam integer GRAD_W = VOXEL_W + 5,
    localparam integer RI_W   = 2 * RMAP_BITS + 3
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,      // view registers (the slab's falloff, FALL = 1)
    // table load ports (broadcast to every lane's copy)
    input  wire lut_we,  input wire [SMP_W-1:0] lut_addr,   input wire [24+ALPHA_W-1:0] lut_data,
    input  wire rmap_we, input wire [RI_W-1:0] rmap_addr,   input wire [19:0] rmap_data,
    input  wire gm_we,   input wire [GMA_W-1:0] gm_addr,    input wire [2*GMF_W-1:0] gm_data,
    // gradient stream in
    input  wire in_valid,  output wire in_ready,  input  wire [HDR_W-1:0] in_hdr,
    input  wire [P*SMP_W-1:0]   in_sample,
    input  wire [P*GRAD_W-1:0]  in_gi, input wire [P*GRAD_W-1:0] in_gj, input wire [P*GRAD_W-1:0] in_gk,
    // shaded stream out: RGBA and the reflectance-map entry used
    output wire out_valid, input  wire out_ready, output wire [HDR_W-1:0] out_hdr,
    output wire [P*(24+ALPHA_W)-1:0] out_rgba,
    output wire [P*RI_W-1:0] out_idx,
    output wire [P*VOXEL_W-1:0] out_sample,
    output wire [P*FALL_W-1:0]  out_fall,
    output wire [VALID_N-1:0]   out_valid_cp      // copies of out_valid (copy 0 is out_valid)
);
    generate
        `CUBE4_BUILD_CHECKS("cube4_sha")
        `CUBE4_RANGE(g_bad_carry, "cube4_sha", "CARRY_SAMPLE", CARRY_SAMPLE, 0, 1)
        `CUBE4_RANGE(g_bad_valid_n, "cube4_sha", "VALID_N", VALID_N, 1, 4)
    endgenerate

    localparam integer VW     = VOXEL_W;
    localparam integer GW     = GRAD_W;
    localparam integer RB     = RMAP_BITS;
    localparam integer LUT_W  = 24 + ALPHA_W;
    localparam integer NUM_W  = GW + 1 + RB;     // (g_b + A) * R
    localparam integer META_W = HDR_W;
    localparam integer RMAP_N = 6 * (1 << (2 * RB));   // the tables' words: every entry but the zero gradient's
    localparam [RI_W-1:0] RMAP_ZERO = RI_W'(RMAP_N);    // the zero gradient's entry (a register, rmap_zero)

    // ---- pipeline ----
    //   a      input register
    //   b1     LUT read; |gi|, |gj|, |gk|
    //   bc     the comparisons |gi| >= |gj|, |gi| >= |gk|, |gj| >= |gk|;
    //          the LUT entry in the RAM's output register (OUT_REG)
    //   b2     cube-map face: the largest |g| (A), its sign, the other two (g_b, g_c)
    //   b3     numerators (g + A) * R, denominator 2A
    //   c0..cR restoring division, one quotient bit per stage, for u and v at once
    //   d      reflectance-map read (address: face and the quotients, min(R-1, q))
    //   d2     the read word in the RAM's output register (OUT_REG)
    //   dr     that word (or the zero gradient's entry) in fabric registers
    //          beside the RAM: the route to the multipliers, often across
    //          the die, starts at a flip-flop, not at the banks' select
    //   d3     the multipliers' operand registers (C, D)
    //   e1     C * D (the multipliers' product registers)
    //   e2     C * D in fabric flip-flops (cube4_mul OUT_FF = 1: the route from
    //          a multiplier placed far away ends at a flip-flop); then
    //          round_shift(C * D, 8) + P, min 255, into the output FIFO's memory
    // Every stage moves on every cycle and carries a valid bit; the beat's
    // fields ride along.
    localparam integer NDIV = RB + 1;            // quotient bits: q in 0 .. R
    // stages after a: b1, bc, b2, b3, c*, d, d2, dr, d3, e1, e2, then the FIFO's memory
    // (SHADING = 0: b1, e1, then the FIFO); with the slab's falloff (FALL) at least the
    // falloff unit's latency before the last stage (e1 without shading)
    localparam integer FALL     = (SLAB != 0 && COMPOSITING != 0) ? 1 : 0;
    localparam integer SLAB_LAT = `CUBE4_SLAB_LAT;   // cube4_sha_slab's latency
    localparam integer GM       = (GMOD != 0 && SHADING != 0) ? 1 : 0;   // the modulation's two stages m1, m2
    localparam integer GM_LAT   = `CUBE4_GM_LAT;
    localparam integer NST_SH   = (SHADING != 0) ? 4 + NDIV + 7 + 2 * GM : 3;
    localparam integer NST      = (FALL != 0 && NST_SH < SLAB_LAT + 1) ? SLAB_LAT + 1 : NST_SH;
    // FIFO entries: a reservation lasts NST + 2 cycles (a, the stages, the FIFO's read).
    localparam integer FIFO_DEPTH  = (NST + 2 <= 16) ? 16 : 32;

    wire credit;                        // the output FIFO has an entry for one more beat
    assign in_ready = credit;
    wire take = in_valid && credit;

    // ---- stage a: input register (loads on every cycle; a_v marks a beat) ----
    reg               a_v;
    reg [P*SMP_W-1:0] a_s;              // {label, value} per lane: the LUT's address
    wire [P*VW-1:0]   a_val;            // the values (carried to COM)
    reg [P*GW-1:0]    a_gi, a_gj, a_gk;
    reg [META_W-1:0]  a_meta;
    always @(posedge clk) begin
        if (rst) a_v <= 1'b0;
        else     a_v <= take;
    end
    always @(posedge clk) begin
        a_s    <= in_sample;
        a_gi   <= in_gi;
        a_gj   <= in_gj;
        a_gk   <= in_gk;
        a_meta <= in_hdr;
    end

    genvar ql;
    generate
        for (ql = 0; ql < P; ql = ql + 1) begin : g_val
            assign a_val[ql*VW +: VW] = a_s[ql*SMP_W +: VW];
        end
    endgenerate

    // ---- valid bits and the beat's fields, stages 1 .. NST - 1 ----
    reg [NST-1:1]    st_v;
    // st_meta_q: the fields at stage k in bits [(k-1)*META_W +: META_W] (one
    // packed shift register, not an array: Verilator copies it as words)
    reg [(NST-1)*META_W-1:0] st_meta_q;
    always @(posedge clk) begin
        if (rst) st_v <= '0;
        else     st_v <= {st_v[NST-2:1], a_v};
    end
    always @(posedge clk) begin
        st_meta_q <= {st_meta_q[(NST-2)*META_W-1:0], a_meta};
    end
    // the samples ride along with the fields (stage k in bits [(k-1)*P*VW +: P*VW])
    wire [P*VW-1:0]    e_s;                                              // with e_meta
    generate
        if (CARRY_SAMPLE != 0) begin : g_carry
            reg [(NST-1)*P*VW-1:0] st_s_q;
            always @(posedge clk) begin
                st_s_q <= {st_s_q[(NST-2)*P*VW-1:0], a_val};
            end
            assign e_s = st_s_q[(NST-2)*P*VW +: P*VW];
        end else begin : g_no_carry
            assign e_s = '0;
            wire unused_val = ^a_val;
        end
    endgenerate
    wire [META_W-1:0]  e_meta = st_meta_q[(NST-2)*META_W +: META_W];   // the last stage (e2; e1 unshaded)
    wire [P*LUT_W-1:0] e_rgba;          // the last stage's results, written into the FIFO
    wire [P*RI_W-1:0]  e_idx;

    // per lane: the classification table's word (stage 2), the reflectance
    // map's index (d) and word (d2), between the lanes and g_pair's tables
    wire [P*LUT_W-1:0] lut_2_all;
    wire [P*RI_W-1:0]  idx_all;
    wire [P*20-1:0]    dp_all;
    reg  [19:0]        rmap_zero;          // the map's entry of the zero gradient (SHADING)
    always @(posedge clk) begin
        if (rmap_we && rmap_addr == RMAP_ZERO) rmap_zero <= rmap_data;
    end

    // gradient-magnitude modulation's factors of each lane (GM = 1): fs at dr (the
    // modulation's operands at m1), fa at m2 (A's operand at d3)
    wire [P*GMF_W-1:0] gm_fs_dr, gm_fa_m2;

    genvar q, it;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            // the classification table's word of this lane (g_pair), read at
            // b1, from its output register at stage 2
            wire [LUT_W-1:0] lut_2 = lut_2_all[q*LUT_W +: LUT_W];

            if (SHADING == 0) begin : g_plain
                // classification only: the LUT entry read at b1; its output
                // register is e1's (with the falloff, stage 2's, carried to e1)
                if (NST > 3) begin : g_late
                    reg [(NST-3)*LUT_W-1:0] lut_sr;
                    wire [(NST-2)*LUT_W-1:0] lut_q = {lut_sr, lut_2};
                    always @(posedge clk) lut_sr <= lut_q[(NST-3)*LUT_W-1:0];
                    assign e_rgba[q*LUT_W +: LUT_W] = lut_q[(NST-3)*LUT_W +: LUT_W];
                end else begin : g_now
                    assign e_rgba[q*LUT_W +: LUT_W] = lut_2;
                end
                assign e_idx[q*RI_W +: RI_W]    = '0;
                assign idx_all[q*RI_W +: RI_W]  = '0;
                wire unused_grad = ^{a_gi[q*GW +: GW], a_gj[q*GW +: GW], a_gk[q*GW +: GW]};
            end else begin : g_shade
                localparam integer E1 = NST - 2;    // stage e1 (C * D in the multipliers)
                // b1: |g|; |g| < 2^(GW-1): no overflow
                wire signed [GW-1:0] gi = a_gi[q*GW +: GW];
                wire signed [GW-1:0] gj = a_gj[q*GW +: GW];
                wire signed [GW-1:0] gk = a_gk[q*GW +: GW];
                reg  signed [GW-1:0] b1_gi, b1_gj, b1_gk;
                reg         [GW-1:0] b1_ai, b1_aj, b1_ak;
                always @(posedge clk) begin
                    {b1_gi, b1_gj, b1_gk} <= {gi, gj, gk};
                    b1_ai <= gi[GW-1] ? -gi : gi;
                    b1_aj <= gj[GW-1] ? -gj : gj;
                    b1_ak <= gk[GW-1] ? -gk : gk;
                end

                // bc: the three comparisons (each a carry chain) in their own stage
                reg  signed [GW-1:0] bc_gi, bc_gj, bc_gk;
                reg         [GW-1:0] bc_ai, bc_aj, bc_ak;
                reg                  bc_ij, bc_ik, bc_jk;   // |gi| >= |gj|, |gi| >= |gk|, |gj| >= |gk|
                always @(posedge clk) begin
                    {bc_gi, bc_gj, bc_gk} <= {b1_gi, b1_gj, b1_gk};
                    {bc_ai, bc_aj, bc_ak} <= {b1_ai, b1_aj, b1_ak};
                    bc_ij <= (b1_ai >= b1_aj);
                    bc_ik <= (b1_ai >= b1_ak);
                    bc_jk <= (b1_aj >= b1_ak);
                end

                // b2: face
                wire [1:0] f = (bc_ij && bc_ik) ? 2'd0 : (bc_jk ? 2'd1 : 2'd2);
                reg  [2:0]           b2_face;   // {f, sign}
                reg  [GW-1:0]        b2_amax;
                reg  signed [GW-1:0] b2_gb, b2_gc;
                always @(posedge clk) begin
                    b2_face <= {f, (f == 2'd0) ? bc_gi[GW-1] : (f == 2'd1) ? bc_gj[GW-1] : bc_gk[GW-1]};
                    b2_amax <= (f == 2'd0) ? bc_ai : (f == 2'd1) ? bc_aj : bc_ak;
                    b2_gb   <= (f == 2'd0) ? bc_gj : bc_gi;
                    b2_gc   <= (f == 2'd2) ? bc_gj : bc_gk;
                end

                // b3: g_b + A and g_c + A in 0 .. 2A (GW + 1 bits unsigned), times R
                wire [GW:0] nb = $unsigned($signed({b2_gb[GW-1], b2_gb}) + $signed({1'b0, b2_amax}));
                wire [GW:0] nc = $unsigned($signed({b2_gc[GW-1], b2_gc}) + $signed({1'b0, b2_amax}));
                // The division's state after b3 (0) and after each quotient bit
                // (1 .. NDIV), one packed word per stage on one bus (per-stage
                // registers, not arrays: Verilator copies plain registers in place):
                //   {rb, rc: remainders, NUM_W each; qb, qc: quotient bits found so
                //    far, RB+1 each; den: 2A, GW+1; face: 3; zero: g = 0}
                localparam integer DV_W = 2 * NUM_W + 2 * (RB + 1) + (GW + 1) + 3 + 1;
                wire [(NDIV + 1)*DV_W-1:0] dv;
                reg  [DV_W-1:0]            dv0_q;   // b3: numerators (g + A) * R, 2A
                always @(posedge clk) begin
                    dv0_q <= {{{RB{1'b0}}, nb} << RB, {{RB{1'b0}}, nc} << RB,
                                        {(RB + 1){1'b0}}, {(RB + 1){1'b0}},
                                        {b2_amax, 1'b0}, b2_face, (b2_amax == {GW{1'b0}})};
                end
                assign dv[0 +: DV_W] = dv0_q;

                // c0 .. cR: quotient bit RB - it (exact restoring division, no rounding)
                for (it = 0; it < NDIV; it = it + 1) begin : g_div
                    localparam integer KB = RB - it;
                    wire [NUM_W-1:0] rb, rc;
                    wire [RB:0]      qb, qc;
                    wire [GW:0]      den;
                    wire [2:0]       face;
                    wire             zero;
                    assign {rb, rc, qb, qc, den, face, zero} = dv[it*DV_W +: DV_W];
                    wire [NUM_W-1:0] d  = {{(NUM_W - GW - 1){1'b0}}, den} << KB;
                    wire             ge_b = (rb >= d);
                    wire             ge_c = (rc >= d);
                    reg  [DV_W-1:0]  dv_q;
                    always @(posedge clk) begin
                        dv_q <= {ge_b ? rb - d : rb, ge_c ? rc - d : rc,
                                           qb | ((RB + 1)'(ge_b) << KB), qc | ((RB + 1)'(ge_c) << KB),
                                           den, face, zero};
                    end
                    assign dv[(it + 1)*DV_W +: DV_W] = dv_q;
                end
                wire [NUM_W-1:0] rb_n, rc_n;     // the last remainders (unused)
                wire [RB:0]      qb, qc;
                wire [GW:0]      den_n;          // (unused)
                wire [2:0]       face_n;
                wire             zero_n;
                assign {rb_n, rc_n, qb, qc, den_n, face_n, zero_n} = dv[NDIV*DV_W +: DV_W];
                wire unused_div = ^{rb_n, rc_n, den_n};
                wire [RB-1:0] ub = qb[RB] ? {RB{1'b1}} : qb[RB-1:0];   // min(R - 1, q)
                wire [RB-1:0] uc = qc[RB] ? {RB{1'b1}} : qc[RB-1:0];
                wire [RI_W-1:0] idx = zero_n ? RMAP_ZERO : {face_n, uc, ub};

                // d: reflectance-map read (g_pair); d2: the RAM's output register,
                // or the zero gradient's entry (rmap_zero)
                assign idx_all[q*RI_W +: RI_W] = {face_n, uc, ub};
                reg [RI_W-1:0]  d_idx;
                reg             d_zero, d2_zero;
                wire [19:0]     d2_dp = d2_zero ? rmap_zero : dp_all[q*20 +: 20];
                reg [RI_W-1:0]  d2_idx;
                reg [19:0]      dr_dp;             // dr: d2's word in fabric registers
                reg [RI_W-1:0]  dr_idx;
                always @(posedge clk) begin
                    d_idx   <= idx;
                    d2_idx  <= d_idx;
                    d_zero  <= zero_n;
                    d2_zero <= d_zero;
                    dr_dp   <= d2_dp;
                    dr_idx  <= d2_idx;
                end
                // GM = 1: m1, m2 modulate D and P by the lane's fs (cube4_sha_gm):
                //   D' = 256 + round_shift((D - 256) fs, 8),  P' = round_shift(P fs, 8)
                // (cube4_mul: operand registers m1, products m2); D' and P' then
                // take D's and P's places at d3. Without: dr's word goes on to d3.
                wire [9:0]      dd_d3, pp_d3;       // D and P, one stage before d3
                wire [RI_W-1:0] idx_d3;             // the index, one stage before d3
                if (GM != 0) begin : g_gm
                    wire [GMF_W-1:0] fs_dr = gm_fs_dr[q*GMF_W +: GMF_W];
                    wire signed [20:0] dm, pm;        // 11 x 10 bits
                    cube4_mul #(.A_W(11), .B_W(10)) u_dm (
                        .clk(clk), .en(1'b1), .a($signed({1'b0, dr_dp[19:10]}) - 11'sd256),
                        .b($signed({1'b0, fs_dr})), .p(dm));
                    cube4_mul #(.A_W(11), .B_W(10)) u_pm (
                        .clk(clk), .en(1'b1), .a($signed({1'b0, dr_dp[9:0]})),
                        .b($signed({1'b0, fs_dr})), .p(pm));
                    // -256 <= round_shift((D - 256) fs, 8) <= 767: D' in 0 .. 1023; P' in 0 .. 1023
                    wire signed [20:0] dr = (dm + 21'sd128) >>> 8;
                    wire signed [20:0] pr = (pm + 21'sd128) >>> 8;
                    assign dd_d3 = 10'(dr + 21'sd256);
                    assign pp_d3 = 10'(pr);
                    wire unused_r = ^{dr[20:10], pr[20:10]};
                    reg [RI_W-1:0] m1_idx, m2_idx;
                    always @(posedge clk) begin
                        m1_idx <= dr_idx;
                        m2_idx <= m1_idx;
                    end
                    assign idx_d3 = m2_idx;
                end else begin : g_no_gm
                    assign dd_d3  = dr_dp[19:10];
                    assign pp_d3  = dr_dp[9:0];
                    assign idx_d3 = dr_idx;
                end
                // d3: the multipliers' operand registers (D, C); P and the index ride along
                reg [RI_W-1:0]  d3_idx;
                reg [9:0]       d3_pp;
                always @(posedge clk) begin
                    d3_idx <= idx_d3;
                    d3_pp  <= pp_d3;
                end
                // the sample's LUT entry rides along from stage 2 to d3 (stage
                // k's entry in bits [(k-2)*LUT_W +: LUT_W]: the RAM's output
                // register, then a packed shift register)
                reg  [(E1-3)*LUT_W-1:0] lut_sr;
                wire [(E1-2)*LUT_W-1:0] lut_q = {lut_sr, lut_2};
                always @(posedge clk) begin
                    lut_sr <= lut_q[(E1-3)*LUT_W-1:0];
                end
                wire [ALPHA_W-1:0] d_alpha = lut_q[(E1-3)*LUT_W +: ALPHA_W];

                // e1: C * D, 8 x 10 bits, exact: a cube4_mul whose operand
                // registers are d3's (C from the shift register's stage before
                // d_alpha's, D from dr's word or D'): the block RAM's word
                // reaches the multiplier through d2, the RAM's output register,
                // and dr, a fabric register beside it; the product register is e1's,
                // and the product is then registered again at e2 in fabric
                // flip-flops (OUT_FF = 1), where the shading's add starts
                wire [23:0] d_col_d = lut_q[(E1-4)*LUT_W + ALPHA_W +: 24];   // C one stage early
                wire unused_col = ^lut_q[(E1-3)*LUT_W + ALPHA_W +: 24];       // (its copy at d3: not needed)
                wire [3*18-1:0]   e2_cd;
                reg  [17:0]       e1_ppx, e2_ppx;    // P * 2^8 + the rounding half 2^7
                wire [ALPHA_W-1:0] e2_a;     // A, or A' = round_shift(A fa, 8) with GM
                reg  [RI_W-1:0]   e1_idx, e2_idx;
                genvar ch;
                for (ch = 0; ch < 3; ch = ch + 1) begin : g_mul   // ch = 0, 1, 2: R, G, B
                    wire signed [19:0] cd_p;
                    cube4_mul #(.A_W(9), .B_W(11), .OUT_FF(1)) u_cd (
                        .clk (clk), .en (1'b1), .a ($signed({1'b0, d_col_d[8 * (2 - ch) +: 8]})),
                        .b ($signed({1'b0, dd_d3})), .p (cd_p));
                    assign e2_cd[18*ch +: 18] = cd_p[17:0];    // < 255 * 1023 < 2^18
                    wire unused_cd = ^cd_p[19:18];
                end
                always @(posedge clk) begin
                    e1_ppx <= {d3_pp, 8'h80};
                    e1_idx <= d3_idx;
                    e2_ppx <= e1_ppx;
                    e2_idx <= e1_idx;
                end
                if (GM != 0) begin : g_gm_a
                    // A' = round_shift(A fa, 8) <= A: operand registers d3 (A one stage
                    // early), product e1, and e2 in fabric flip-flops (OUT_FF = 1)
                    wire signed [ALPHA_W+10:0] am;
                    cube4_mul #(.A_W(ALPHA_W + 1), .B_W(10), .OUT_FF(1)) u_am (
                        .clk(clk), .en(1'b1), .a($signed({1'b0, lut_q[(E1-4)*LUT_W +: ALPHA_W]})),
                        .b($signed({1'b0, gm_fa_m2[q*GMF_W +: GMF_W]})), .p(am));
                    wire [ALPHA_W+10:0] ar = ($unsigned(am) + (ALPHA_W + 11)'(128)) >> 8;
                    assign e2_a = ar[ALPHA_W-1:0];
                    wire unused_ar = ^{ar[ALPHA_W+10:ALPHA_W], d_alpha};
                end else begin : g_no_gm_a
                    reg [ALPHA_W-1:0] e1_a_q, e2_a_q;
                    always @(posedge clk) begin
                        e1_a_q <= d_alpha;
                        e2_a_q <= e1_a_q;
                    end
                    assign e2_a = e2_a_q;
                end

                // after e2, into the FIFO's memory: shade, col = min(round_shift(C * D, 8)
                // + P, 255), the rounding in the one add: round_shift(x, 8) + P =
                // floor((x + P * 2^8 + 2^7) / 2^8)
                wire [23:0] col_d;
                for (ch = 0; ch < 3; ch = ch + 1) begin : g_ch
                    // < 2^18 + 2^18; the sum / 2^8 < 2^11 (rs < 2^10, P < 2^10)
                    wire [18:0] sum_x = {1'b0, e2_ppx} + {1'b0, e2_cd[18*ch +: 18]};
                    wire [10:0] sum   = sum_x[18:8];
                    wire unused_frac = ^sum_x[7:0];
                    assign col_d[8 * (2 - ch) +: 8] = (sum > 11'd255) ? 8'd255 : sum[7:0];
                end
                assign e_rgba[q*LUT_W +: LUT_W] = {col_d, e2_a};
                assign e_idx[q*RI_W +: RI_W]    = e2_idx;
            end
        end
        if (SHADING == 0) begin : g_no_rmap
            assign dp_all = '0;
            wire unused_rmap = ^{rmap_we, rmap_addr, rmap_data, idx_all, dp_all, rmap_zero};
        end
        // The tables, one copy per two lanes (cube4_dual_read_ram: lane 2k
        // reads through the write's port, lane 2k + 1 through the other;
        // they are written between frames only, cube4_top's contract, so
        // no read is lost to a write), each read ending in the RAM's output
        // register (the block RAM's own on an FPGA). An odd P's last lane
        // has a copy of its own (the second port unused).
        for (q = 0; q < P; q = q + 2) begin : g_pair
            localparam integer Q1 = (q + 1 < P) ? q + 1 : q;   // the second lane (q itself when none)
            wire [LUT_W-1:0] lut_1;
            cube4_dual_read_ram #(.DATA_W(LUT_W), .DEPTH(1 << SMP_W), .OUT_REG(1)) u_lut (
                .clk(clk), .rd_en(1'b1),
                .rd0_addr(a_s[q*SMP_W +: SMP_W]), .rd0_data(lut_2_all[q*LUT_W +: LUT_W]),
                .rd1_addr(a_s[Q1*SMP_W +: SMP_W]), .rd1_data(lut_1),
                .wr_en(lut_we), .wr_addr(lut_addr), .wr_data(lut_data));
            if (SHADING != 0) begin : g_rmap
                wire [19:0] dp_1;
                cube4_dual_read_ram #(.DATA_W(20), .DEPTH(RMAP_N), .OUT_REG(1)) u_rmap (
                    .clk(clk), .rd_en(1'b1),
                    .rd0_addr(idx_all[q*RI_W +: RI_W]), .rd0_data(dp_all[q*20 +: 20]),
                    .rd1_addr(idx_all[Q1*RI_W +: RI_W]), .rd1_data(dp_1),
                    .wr_en(rmap_we && (rmap_addr != RMAP_ZERO)), .wr_addr(rmap_addr), .wr_data(rmap_data));
                if (Q1 != q) begin : g_second
                    assign dp_all[Q1*20 +: 20] = dp_1;
                end else begin : g_none
                    wire unused_dp_1 = ^dp_1;
                end
            end
            if (Q1 != q) begin : g_second
                assign lut_2_all[Q1*LUT_W +: LUT_W] = lut_1;
            end else begin : g_none
                wire unused_lut_1 = ^lut_1;
            end
        end
    endgenerate

    // ---- gradient-magnitude modulation (GM = 1): cube4_sha_gm from stage a's gradient,
    // its factors (stage GM_LAT) carried to dr (fs) and m2 (fa) ----
    generate
        if (GM != 0) begin : g_gmod
            localparam integer FW2 = P * GMF_W;
            localparam integer DR  = 7 + NDIV;        // stage dr (a = 0)
            wire [FW2-1:0] fa7, fs7;
            cube4_sha_gm #(.P(P), .VOXEL_W(VOXEL_W)) u_gm (
                .clk(clk), .gm_we(gm_we), .gm_addr(gm_addr), .gm_data(gm_data),
                .in_gi(a_gi), .in_gj(a_gj), .in_gk(a_gk), .fa(fa7), .fs(fs7));
            if (DR < GM_LAT) begin : g_late
                $error("cube4_sha: the modulation's factors come at stage %0d, after dr (%0d)", GM_LAT, DR);
            end
            // fs: NSF = DR - GM_LAT (>= 3: NDIV >= 3) more stages; fa: two more (m1, m2)
            localparam integer NSF = DR - GM_LAT;
            localparam integer NSA = NSF + 2;
            reg  [NSF*FW2-1:0]     fs_sr;
            reg  [NSA*FW2-1:0]     fa_sr;
            wire [(NSF+1)*FW2-1:0] fs_q = {fs_sr, fs7};
            wire [(NSA+1)*FW2-1:0] fa_q = {fa_sr, fa7};
            always @(posedge clk) begin
                fs_sr <= fs_q[NSF*FW2-1:0];
                fa_sr <= fa_q[NSA*FW2-1:0];
            end
            assign gm_fs_dr = fs_q[NSF*FW2 +: FW2];
            assign gm_fa_m2 = fa_q[NSA*FW2 +: FW2];
        end else begin : g_no_gmod
            assign gm_fs_dr = '0;
            assign gm_fa_m2 = '0;
            wire unused_gm = ^{gm_we, gm_addr, gm_data, gm_fs_dr, gm_fa_m2};
        end
    endgenerate

    // ---- the slab's falloff weights (FALL = 1): from stage a's fields, carried to e1 ----
    localparam integer FW = (FALL != 0) ? P * FALL_W : 0;
    wire [P*FALL_W-1:0] e_fall;
    generate
        if (FALL != 0) begin : g_fall
            wire [P*FALL_W-1:0] f9;             // stage SLAB_LAT
            cube4_sha_slab #(
                .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2)
            ) u_slab (
                .clk(clk), .cfg(cfg),
                .in_m(a_meta[HDR_M +: M_W]), .in_j(a_meta[HDR_J +: DIM_W]),
                .in_pb(a_meta[HDR_PB +: PB_W]), .in_skew(a_meta[HDR_SKEW +: LANE_W]), .fall(f9));
            if (NST - 1 > SLAB_LAT) begin : g_delay
                reg [(NST-1-SLAB_LAT)*FW-1:0] f_sr;
                wire [(NST-SLAB_LAT)*FW-1:0] f_q = {f_sr, f9};
                always @(posedge clk) f_sr <= f_q[(NST-1-SLAB_LAT)*FW-1:0];
                assign e_fall = f_q[(NST-1-SLAB_LAT)*FW +: FW];
            end else begin : g_now
                assign e_fall = f9;
            end
        end else begin : g_no_fall
            assign e_fall = {P{FALL_W'(256)}};
            wire unused_view = ^cfg;
        end
    endgenerate

    // ---- the output FIFO's memory stores the last stage's results (NST - 1: e2
    //      shaded, e1 unshaded); push_d from the stage before it ----
    localparam integer OUT_W = META_W + P * LUT_W + P * RI_W + P * VW + FW;
    wire [OUT_W-1:0] fifo_out;
    wire unused_credit_d;
    generate
        if (FALL != 0) begin : g_fifo_fall
            cube4_credit_fifo #(.DATA_W(OUT_W), .DEPTH(FIFO_DEPTH), .VALID_N(VALID_N)) u_fifo (
                .clk(clk), .rst(rst), .take(take), .give(1'b0),
                .credit(credit), .credit_d(unused_credit_d),
                .push_d(st_v[NST-2]), .in_data({e_fall, e_meta, e_rgba, e_idx, e_s}),
                .out_valid(out_valid), .out_ready(out_ready), .out_data(fifo_out),
                .out_valid_cp(out_valid_cp));
            assign {out_fall, out_hdr, out_rgba, out_idx, out_sample} = fifo_out;
        end else begin : g_fifo
            cube4_credit_fifo #(.DATA_W(OUT_W), .DEPTH(FIFO_DEPTH), .VALID_N(VALID_N)) u_fifo (
                .clk(clk), .rst(rst), .take(take), .give(1'b0),
                .credit(credit), .credit_d(unused_credit_d),
                .push_d(st_v[NST-2]), .in_data({e_meta, e_rgba, e_idx, e_s}),
                .out_valid(out_valid), .out_ready(out_ready), .out_data(fifo_out),
                .out_valid_cp(out_valid_cp));
            assign {out_hdr, out_rgba, out_idx, out_sample} = fifo_out;
            assign out_fall = e_fall;
        end
    endgenerate
    wire unused_st_v = st_v[NST-1];     // the last stage's valid bit: the FIFO's push copies are its copies

endmodule
`default_nettype wire

`default_nettype none
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
//   Every lane has its own copy of both tables (as in the paper: tables per
//   pipeline); the host writes them through the load ports, which broadcast
//   to all lanes, at run time: a new transfer function or light needs no
//   rebuild. The host applies the opacity correction for the view's sample
//   distance when it writes the LUT (golden/cube4/tables.py).
//
// Parameters
//   P           pipelines.                          1..64.  Default 8.
//   VOXEL_W     sample width (LUT has 2^VOXEL_W entries). 1..16. Default 8.
//   ALPHA_W     LUT opacity width AW.               8..16.  Default 12.
//   RMAP_BITS   cube-map resolution R = 2^RMAP_BITS. 2..6.  Default 5.
//   MAX_DIM, MAX_SS_LOG2 and the derived widths as cube4_gra; GRAD_W = VOXEL_W + 5.
//
// Latency
//   5 register stages (input, LUT read + face select, division, reflectance-map
//   read, shading) under one stall enable, then the output skid buffer.
//
// Ports
//   lut_we/lut_addr/lut_data     LUT write: lut_data = {R, G, B (Q0.8), A (Q0.ALPHA_W)}
//   rmap_we/rmap_addr/rmap_data  reflectance-map write: rmap_data = {D, P} (Q2.8 each)
//   in_*    the gradient stream of cube4_gra (gi, gj, gk signed GRAD_W bits)
//   out_rgba  [P*(24+ALPHA_W)]  per lane {R', G', B' (Q0.8), A (Q0.ALPHA_W)}
//   out_idx   [P*RI_W]          reflectance-map entry used (for checking and waves)
//   out_lane_valid ... out_ctrl  the beat's fields, unchanged
//
// Bit growth and rounding
//   Face select: |g| is GRAD_W bits unsigned. u = min(R-1, floor((g_b + A) R / 2A))
//   is an exact restoring division with an RMAP_BITS+1-bit quotient (no
//   rounding). C * D is 8 x 10 = 18 bits; round_shift by 8 (half up) gives 11
//   bits; + P (10 bits) < 2^12; the min with 255 is the one saturation.
// =============================================================================
module cube4_sha #(
    parameter integer P           = 8,
    parameter integer VOXEL_W     = 8,
    parameter integer ALPHA_W     = 12,
    parameter integer RMAP_BITS   = 5,
    parameter integer MAX_DIM     = 256,
    parameter integer MAX_SS_LOG2 = 0,
    parameter integer DIM_W  = $clog2(MAX_DIM + 1),
    parameter integer PB_W   = ((MAX_DIM + P - 1) / P > 1) ? $clog2((MAX_DIM + P - 1) / P) : 1,
    parameter integer LANE_W = (P > 1) ? $clog2(P) : 1,
    parameter integer M_W    = $clog2((MAX_DIM - 1) * (1 << MAX_SS_LOG2) + 2),
    parameter integer GRAD_W = VOXEL_W + 5,
    parameter integer RI_W   = 2 * RMAP_BITS + 3
) (
    input  wire                    clk,
    input  wire                    rst,
    // table load ports (broadcast to every lane's copy)
    input  wire                    lut_we,
    input  wire [VOXEL_W-1:0]      lut_addr,
    input  wire [24+ALPHA_W-1:0]   lut_data,
    input  wire                    rmap_we,
    input  wire [RI_W-1:0]         rmap_addr,
    input  wire [19:0]             rmap_data,
    // gradient stream in
    input  wire                    in_valid,
    output wire                    in_ready,
    input  wire [P*VOXEL_W-1:0]    in_sample,
    input  wire [P*GRAD_W-1:0]     in_gi,
    input  wire [P*GRAD_W-1:0]     in_gj,
    input  wire [P*GRAD_W-1:0]     in_gk,
    input  wire [P-1:0]            in_lane_valid,
    input  wire [P-1:0]            in_lane_inside,
    input  wire [M_W-1:0]          in_m,
    input  wire [DIM_W-1:0]        in_j,
    input  wire [PB_W-1:0]         in_pb,
    input  wire [LANE_W-1:0]       in_skew,
    input  wire [6:0]              in_ctrl,
    // shaded stream out
    output wire                    out_valid,
    input  wire                    out_ready,
    output wire [P*(24+ALPHA_W)-1:0] out_rgba,
    output wire [P*RI_W-1:0]       out_idx,
    output wire [P-1:0]            out_lane_valid,
    output wire [P-1:0]            out_lane_inside,
    output wire [M_W-1:0]          out_m,
    output wire [DIM_W-1:0]        out_j,
    output wire [PB_W-1:0]         out_pb,
    output wire [LANE_W-1:0]       out_skew,
    output wire [6:0]              out_ctrl
);
    generate
        if (P < 1 || P > 64) begin : g_bad_p
            $error("cube4_sha: P = %0d is out of range 1..64", P);
        end
        if (ALPHA_W < 8 || ALPHA_W > 16) begin : g_bad_alpha_w
            $error("cube4_sha: ALPHA_W = %0d is out of range 8..16", ALPHA_W);
        end
        if (RMAP_BITS < 2 || RMAP_BITS > 6) begin : g_bad_rmap_bits
            $error("cube4_sha: RMAP_BITS = %0d is out of range 2..6", RMAP_BITS);
        end
        if (GRAD_W != VOXEL_W + 5 || RI_W != 2 * RMAP_BITS + 3) begin : g_bad_derived
            $error("cube4_sha: GRAD_W and RI_W are derived, do not set them");
        end
    endgenerate

    localparam integer VW     = VOXEL_W;
    localparam integer GW     = GRAD_W;
    localparam integer RB     = RMAP_BITS;
    localparam integer LUT_W  = 24 + ALPHA_W;
    localparam integer NUM_W  = GW + 1 + RB;     // (g_b + A) * R
    localparam integer META_W = M_W + DIM_W + PB_W + LANE_W + 7 + 2 * P;
    localparam integer RMAP_N = 6 * (1 << (2 * RB)) + 1;

    // restoring division, quotient in 0 .. R (RB + 1 bits), then min(R - 1, q)
    function automatic [RB-1:0] rmap_cell(input [NUM_W-1:0] num, input [GW:0] den);
        reg [NUM_W-1:0] rem;
        reg [NUM_W-1:0] d;
        reg [RB:0]      qq;
        integer         k;
        begin
            rem = num;
            qq  = {(RB + 1){1'b0}};
            for (k = RB; k >= 0; k = k - 1) begin
                d = {{(NUM_W - GW - 1){1'b0}}, den} << k;
                if (rem >= d) begin
                    rem   = rem - d;
                    qq[k] = 1'b1;
                end
            end
            rmap_cell = qq[RB] ? {RB{1'b1}} : qq[RB-1:0];
        end
    endfunction

    wire en;
    assign in_ready = en;

    // ---- stage a: input register ----
    reg               a_v;
    reg [P*VW-1:0]    a_s;
    reg [P*GW-1:0]    a_gi, a_gj, a_gk;
    reg [META_W-1:0]  a_meta;
    always @(posedge clk) begin
        if (rst) a_v <= 1'b0;
        else if (en) a_v <= in_valid;
    end
    always @(posedge clk) begin
        if (en) begin
            a_s    <= in_sample;
            a_gi   <= in_gi;
            a_gj   <= in_gj;
            a_gk   <= in_gk;
            a_meta <= {in_m, in_j, in_pb, in_skew, in_ctrl, in_lane_valid, in_lane_inside};
        end
    end

    // ---- stages b..e per lane ----
    reg               b_v, c_v, d_v, e_v;
    reg [META_W-1:0]  b_meta, c_meta, d_meta, e_meta;
    wire [P*LUT_W-1:0] e_rgba;
    wire [P*RI_W-1:0]  e_idx;
    always @(posedge clk) begin
        if (rst) begin
            b_v <= 1'b0;
            c_v <= 1'b0;
            d_v <= 1'b0;
            e_v <= 1'b0;
        end else if (en) begin
            b_v <= a_v;
            c_v <= b_v;
            d_v <= c_v;
            e_v <= d_v;
        end
    end
    always @(posedge clk) begin
        if (en) begin
            b_meta <= a_meta;
            c_meta <= b_meta;
            d_meta <= c_meta;
            e_meta <= d_meta;
        end
    end

    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            // tables (this lane's copies)
            reg [LUT_W-1:0] lut  [0:(1 << VW)-1];
            reg [19:0]      rmap [0:RMAP_N-1];
            always @(posedge clk) begin
                if (lut_we)  lut[lut_addr]   <= lut_data;
                if (rmap_we) rmap[rmap_addr] <= rmap_data;
            end

            // b: LUT read, cube-map face
            wire signed [GW-1:0] gi = a_gi[q*GW +: GW];
            wire signed [GW-1:0] gj = a_gj[q*GW +: GW];
            wire signed [GW-1:0] gk = a_gk[q*GW +: GW];
            wire [GW-1:0] ai = gi[GW-1] ? -gi : gi;   // |g| < 2^(GW-1): no overflow
            wire [GW-1:0] aj = gj[GW-1] ? -gj : gj;
            wire [GW-1:0] ak = gk[GW-1] ? -gk : gk;
            wire [1:0] f = (ai >= aj && ai >= ak) ? 2'd0 : (aj >= ak ? 2'd1 : 2'd2);
            wire [GW-1:0]        amax = (f == 2'd0) ? ai : (f == 2'd1) ? aj : ak;
            wire                 neg  = (f == 2'd0) ? gi[GW-1] : (f == 2'd1) ? gj[GW-1] : gk[GW-1];
            wire signed [GW-1:0] gb   = (f == 2'd0) ? gj : gi;
            wire signed [GW-1:0] gc   = (f == 2'd2) ? gj : gk;
            // g_b + A in 0 .. 2A: GW + 1 bits unsigned
            wire [GW:0] nb = $unsigned($signed({gb[GW-1], gb}) + $signed({1'b0, amax}));
            wire [GW:0] nc = $unsigned($signed({gc[GW-1], gc}) + $signed({1'b0, amax}));

            reg [LUT_W-1:0] b_lut;
            reg [2:0]       b_face;
            reg             b_zero;
            reg [GW:0]      b_den;
            reg [NUM_W-1:0] b_nb, b_nc;
            always @(posedge clk) begin
                if (en) begin
                    b_lut  <= lut[a_s[q*VW +: VW]];
                    b_face <= {f, neg};
                    b_zero <= (amax == {GW{1'b0}});
                    b_den  <= {amax, 1'b0};
                    b_nb   <= {{RB{1'b0}}, nb} << RB;
                    b_nc   <= {{RB{1'b0}}, nc} << RB;
                end
            end

            // c: division -> entry
            reg [LUT_W-1:0] c_lut;
            reg [RI_W-1:0]  c_idx;
            always @(posedge clk) begin
                if (en) begin
                    c_lut <= b_lut;
                    c_idx <= b_zero ? RI_W'(6 << (2 * RB))
                                    : {b_face, rmap_cell(b_nc, b_den), rmap_cell(b_nb, b_den)};
                end
            end

            // d: reflectance-map read
            reg [LUT_W-1:0] d_lut;
            reg [RI_W-1:0]  d_idx;
            reg [19:0]      d_dp;
            always @(posedge clk) begin
                if (en) begin
                    d_lut <= c_lut;
                    d_idx <= c_idx;
                    d_dp  <= rmap[c_idx];
                end
            end

            // e: shade
            wire [9:0] dd = d_dp[19:10];
            wire [9:0] pp = d_dp[9:0];
            wire [23:0] col_d;
            genvar ch;
            for (ch = 0; ch < 3; ch = ch + 1) begin : g_ch
                wire [7:0]         cc   = d_lut[ALPHA_W + 8 * (2 - ch) +: 8];   // R, G, B
                wire [17:0]        cd   = {10'd0, cc} * {8'd0, dd};   // 8 x 10 bits, exact
                wire signed [18:0] prod = $signed({1'b0, cd});
                wire signed [11:0] rs;
                cube4_round_shift #(
                    .IN_W  (19),
                    .SHIFT (8)
                ) u_rs (
                    .x (prod),
                    .y (rs)
                );
                // rs >= 0 and < 2^11; rs + P < 2^12
                wire [11:0] sum = rs + {2'b00, pp};
                assign col_d[8 * (2 - ch) +: 8] = (sum > 12'd255) ? 8'd255 : sum[7:0];
            end
            reg [LUT_W-1:0] e_q;
            reg [RI_W-1:0]  e_idx_q;
            always @(posedge clk) begin
                if (en) begin
                    e_q     <= {col_d, d_lut[ALPHA_W-1:0]};
                    e_idx_q <= d_idx;
                end
            end
            assign e_rgba[q*LUT_W +: LUT_W] = e_q;
            assign e_idx[q*RI_W +: RI_W]    = e_idx_q;
        end
    endgenerate

    localparam integer OUT_W = META_W + P * LUT_W + P * RI_W;
    wire [OUT_W-1:0] skid_out;
    cube4_skid #(
        .DATA_W (OUT_W)
    ) u_skid (
        .clk       (clk),
        .rst       (rst),
        .in_valid  (e_v),
        .in_ready  (en),
        .in_data   ({e_meta, e_rgba, e_idx}),
        .out_valid (out_valid),
        .out_ready (out_ready),
        .out_data  (skid_out)
    );
    assign {out_m, out_j, out_pb, out_skew, out_ctrl, out_lane_valid, out_lane_inside,
            out_rgba, out_idx} = skid_out;

endmodule
`default_nettype wire

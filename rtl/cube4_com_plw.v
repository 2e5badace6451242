`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_plw
// -----------------------------------------------------------------------------
// Purpose
//   COM's path-length weights (PLW = 1, numerics.md section 17): the first
//   sample of a ray that enters through a face in FACES, and the last of one
//   that leaves through one, take a weight wq in quarters (2 .. 6) from the
//   template's phase and the causes of a fresh or a finished ray, split by face:
//     rq(num, VIEW) = #{k in 1, 3, 5, 7 : 8 num >= k VIEW}   (quarter bins)
//     entry: num = ph(m)          (an old step has just wrapped it below VIEW)
//     exit:  num = VIEW - ph(m+1) (a step has just wrapped ph(m+1))
//     wq = clamp((entry ? rq_in : 2) + (exit ? rq_out : 2), 2, 6)
//   with rq of an end the minimum over its active causes (face k: m = 0 /
//   m = M-1; face y: j = 0 / the last rows; face x: i = 0 / the last columns).
//   A blending sample with wq != 4 takes its A from the LUT's path-weight
//   column for wq (a table of 2^VOXEL_W x 4 opacities per lane, read with the
//   sample) instead of the LUT's A.
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2: as cube4_com (1..64, 2..2048, 4..12, 0..3).
//   VOXEL_W  the sample width (the column tables' address).  1..16.
//   ALPHA_W  opacity width.                                   8..16.
//
// Latency
//   S0 -> S1 the entry bins, slice m+1's phases and the entry causes; S1 ->
//   S2 each lane's entry bin, the exit bins and causes; S2 -> S3 each lane's
//   weight class; the
//   columns: read with R0's sample (S1: the RAM's read register, S2: its
//   output register), carried to S3. a_w: combinational at S3 (the lane
//   registers it into S4).
//
// Ports
//   step, first, ph_x, ph_y, phn_x, phn_y   R0 holds a beat; the slice's
//             first beat; phases of slices m (at the first beat) and m + 1
//             (cube4_com_walk) [PHASE_W, unsigned, VIEW = one voxel step]
//   r0_m, r0_j, dxb, dyb, ipos, f1_*   R0's and S1's fields (cube4_com_seq,
//             cube4_com_walk: f1_last, f1_wxn, f1_wyn)
//   lut_we, lut_addr, lut_data   the columns: {A at w = 3/2, 5/4, 3/4, 1/2},
//             Q0.ALPHA_W each
//   smp       R0's samples, lane q at [q*VOXEL_W], unsigned
//   mode_ext  the frame is MIP / MinIP (no weights)
//   a3        S3's A of each lane [ALPHA_W, Q0.ALPHA_W]
//   a_w       out  the A that goes on to S4 (the column's, or a3)
//
// Bit growth and rounding: comparisons only (a column's opacity is the host's
//   1 - (1 - A)^w in Q0.ALPHA_W); 8 num in PHASE_W + 4 bits.
// =============================================================================
module cube4_com_plw #(
    `CUBE4_SLICE_PARAMS,
    parameter integer VOXEL_W  = 8, parameter integer ALPHA_W     = 12,
    localparam integer PH_W = PHASE_W
) (
    input  wire clk,
    input  wire [VIEW_W-1:0] cfg,
    input  wire step, input wire first,
    input  wire [PH_W-1:0] ph_x, input wire [PH_W-1:0] ph_y,
    input  wire [PH_W-1:0] phn_x, input wire [PH_W-1:0] phn_y,
    input  wire [M_W-1:0] r0_m, input wire [DIM_W-1:0] r0_j, input wire dxb, input wire dyb,
    input  wire [P*IW-1:0] ipos,
    input  wire [P*IW-1:0] f1_ipos, input wire [IW-1:0] f1_j, input wire f1_dxf, input wire f1_dyf,
    input  wire f1_last, input wire f1_wxn, input wire f1_wyn,
    input  wire lut_we, input wire [VOXEL_W-1:0] lut_addr, input wire [4*ALPHA_W-1:0] lut_data,
    input  wire [P*VOXEL_W-1:0] smp, input wire mode_ext,
    input  wire [P*ALPHA_W-1:0] a3, output wire [P*ALPHA_W-1:0] a_w
);
    `CUBE4_VIEW_FIELDS(cfg);
    localparam integer NW = PH_W + 4;

    reg  [PH_W-1:0] phx_m_q, phy_m_q;   // phase of slice m
    wire [PH_W-1:0] phx_m = first ? ph_x : phx_m_q;
    wire [PH_W-1:0] phy_m = first ? ph_y : phy_m_q;
    always @(posedge clk) begin
        if (step) begin
            phx_m_q <= phx_m;
            phy_m_q <= phy_m;
        end
    end
    function automatic [2:0] qbins(input [NW-1:0] num, input [NW-1:0] view);
        reg [NW-1:0] n8;
        begin
            n8   = num << 3;
            qbins = 3'(n8 >= view) + 3'(n8 >= 3 * view) + 3'(n8 >= 5 * view) + 3'(n8 >= 7 * view);
        end
    endfunction
    wire [NW-1:0] vx = NW'(cfg_view_x);
    wire [NW-1:0] vy = NW'(cfg_view_y);
    wire [5:0]    fc = cfg_faces;
    wire [IW-1:0] ni_ext = IW'(cfg_ni);
    wire [IW-1:0] nj_ext = IW'(cfg_nj);

    // ---- S0 -> S1: the entry bins (of slice m's phase), the phases of slice
    // m + 1, the entry causes ----
    reg  [2:0]      f1_rxi, f1_ryi;
    reg  [PH_W-1:0] f1_phxn, f1_phyn;
    reg             f1_kin, f1_yin;
    reg  [P-1:0]    f1_xin;
    integer         l;
    always @(posedge clk) begin
        f1_rxi  <= qbins(NW'(phx_m), vx);
        f1_ryi  <= qbins(NW'(phy_m), vy);
        f1_phxn <= phn_x;
        f1_phyn <= phn_y;
        f1_kin  <= fc[4] && (r0_m == '0);
        f1_yin  <= fc[2] && dyb && (r0_j == '0);
        for (l = 0; l < P; l = l + 1)
            f1_xin[l] <= fc[0] && dxb && (ipos[l*IW +: IW] == '0);
    end

    // ---- S1 -> S2: each lane's entry bin rq_in (the minimum over its
    // causes, NONE without one), the exit bins and causes ----
    localparam [3:0] NONE = 4'd9;
    wire [3:0]   in_yk = f1_kin ? 4'd0 : (f1_yin ? {1'b0, f1_ryi} : NONE);   // shared by the lanes
    reg  [2:0]   s2_rxo, s2_ryo;
    reg          s2_kout, s2_yout0, s2_yout1;
    reg  [P-1:0] s2_xout0, s2_xout1;
    reg  [3:0]   s2_rq_in [0:P-1];
    always @(posedge clk) begin
        s2_rxo   <= qbins(vx - NW'(f1_phxn), vx);
        s2_ryo   <= qbins(vy - NW'(f1_phyn), vy);
        s2_kout  <= fc[5] && f1_last;
        s2_yout0 <= fc[3] && (f1_j + IW'(1) == nj_ext) && (f1_dyf || f1_wyn);
        s2_yout1 <= fc[3] && (f1_j + IW'(2) == nj_ext) && f1_dyf && f1_wyn;
        for (l = 0; l < P; l = l + 1) begin
            s2_rq_in[l] <= (f1_xin[l] && {1'b0, f1_rxi} < in_yk) ? {1'b0, f1_rxi} : in_yk;
            s2_xout0[l] <= fc[1] && (f1_ipos[l*IW +: IW] + IW'(1) == ni_ext) && (f1_dxf || f1_wxn);
            s2_xout1[l] <= fc[1] && (f1_ipos[l*IW +: IW] + IW'(2) == ni_ext) && f1_dxf && f1_wxn;
        end
    end

    // ---- S2 -> S3, per lane: the weight class (the lane's own registers: the
    // causes shared by the lanes fan out to P of them, not to P * ALPHA_W
    // selects of the opacity), and the column read with the sample ----
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            wire [3:0] rq_in = s2_rq_in[q];
            wire [3:0] o_x   = s2_xout0[q] ? 4'd0 : (s2_xout1[q] ? {1'b0, s2_rxo} : NONE);
            wire [3:0] o_y   = s2_yout0 ? 4'd0 : (s2_yout1 ? {1'b0, s2_ryo} : NONE);
            wire [3:0] o_xy  = (o_x < o_y) ? o_x : o_y;
            wire [3:0] rq_out = s2_kout ? 4'd0 : o_xy;
            wire [3:0] wsum = ((rq_in == NONE) ? 4'd2 : rq_in) + ((rq_out == NONE) ? 4'd2 : rq_out);
            wire [2:0] wq   = (wsum < 4'd2) ? 3'd2 : (wsum > 4'd6) ? 3'd6 : wsum[2:0];
            reg       use_q;                 // S3: wq != 4
            reg [1:0] col_q;                 // S3: its column (wq = 2, 3, 5, 6)
            always @(posedge clk) begin
                use_q <= (wq != 3'd4);
                col_q <= (wq == 3'd2) ? 2'd0 : (wq == 3'd3) ? 2'd1 : (wq == 3'd5) ? 2'd2 : 2'd3;
            end
            // the lane's copy of the columns, read with R0's sample (S1: the
            // RAM's read register), its word registered once more (S2: the RAM's
            // output register, a block RAM's own, so no logic and no
            // clock-to-out of the block after it), then carried to S3
            wire [4*ALPHA_W-1:0] w2_cols;
            reg  [4*ALPHA_W-1:0] w3_cols;
            cube4_sdp_ram #(.DATA_W(4 * ALPHA_W), .DEPTH(1 << VOXEL_W), .OUT_REG(1)) u_wtab (
                .clk(clk), .rd_en(1'b1), .out_en(1'b0), .rd_addr(smp[q*VOXEL_W +: VOXEL_W]), .rd_data(w2_cols),
                .wr_en(lut_we), .wr_addr(lut_addr), .wr_data(lut_data));
            always @(posedge clk) w3_cols <= w2_cols;
            wire [ALPHA_W-1:0] a_col;
            cube4_mux #(.N(4), .W(ALPHA_W)) u_col (.words(w3_cols), .sel(col_q), .word(a_col));
            assign a_w[q*ALPHA_W +: ALPHA_W] = (use_q && !mode_ext) ? a_col : a3[q*ALPHA_W +: ALPHA_W];
        end
    endgenerate
endmodule
`default_nettype wire

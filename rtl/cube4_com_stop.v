`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_stop
// -----------------------------------------------------------------------------
// Purpose
//   Depth in (ZIN = 1, docs/numerics.md section 22): per lane, whether the
//   sample's slice m lies in front of the geometry of its ray's base-plane
//   pixel (by, bx):  ok = m < stop(by, bx). COM ANDs ok into the sample's
//   count (cube4_com_seq, S5 -> S6), so a ray counts no sample at or behind
//   the geometry and still finishes where it leaves the box.
//   The stop table (the host's, per frame: golden/cube4/memory.py stop_table)
//   lives in P banks skewed along bx, so that a beat's P rays, which lie on
//   P consecutive columns of one base-plane row, read one bank each:
//     bank  = bx mod P,   word = {by [ROWS_W], bx div P [COLS_W]}
//   For a beat of row j, partial beam pb in slice m, the lane at position t
//   holds bx = pb P + t + B with B = SX - stepx(m) >= 0, by = j - stepy(m) +
//   SY. With B = Q P + R (0 <= R < P) bank b is read at word
//     pb + Q + (b < R ? 1 : 0)          (mod 2^COLS_W)
//   and the lane at t takes bank (t + R) mod P. Q = floor(B * RECIP / 2^K),
//   RECIP = ceil(2^K / P), K = DIM_W + LANE_W: exact for every B < 2^DIM_W
//   (RECIP P - 2^K < P <= 2^(K - DIM_W)). A lane past the slice's last column
//   may read a word that wraps: its sample never counts.
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2: as cube4_com (1..64, 2..2048, 4..12, 0..3).
//   ROWS_W, COLS_W, STOP_AW: the table's layout (derived, CUBE4_STOP_LAYOUT).
//
// Latency
//   Stages move on every cycle (no enable, like COM's). R0's fields (S0)
//   are registered into S1; S1 -> S2 Q; S2: R, the banks' read addresses
//   (combinational into the RAMs, cube4_sdp_ram with OUT_REG: the word at
//   S4); S4 -> S5 each lane's stop. ok is combinational at S5 (from S5's
//   registers): COM registers it into its S6 counts.
//   The table is written between frames (stop_we), never read then.
//
// Ports
//   stop_we, stop_addr, stop_data  the table: one word of all P banks
//             (bank b at [b*M_W +: M_W], unsigned stop slices 0 .. M) at
//             address {by, word}
//   r0_m, r0_j, r0_pb, tpos, stx, sty   R0's slice, row, partial beam, the
//             lanes' positions t [LANE_W] and stepx(m), stepy(m) (S0)
//   ok        out  S5: the lane's sample is in front of the geometry
//
// Bit growth and rounding: B in DIM_W bits (0 .. SX), the product B RECIP in
//   DIM_W + K + 1 bits; the word sum wraps mod 2^COLS_W (see above); no
//   rounding.
// =============================================================================
module cube4_com_stop #(
    `CUBE4_SLICE_PARAMS,
    `CUBE4_STOP_LAYOUT
) (
    input  wire clk,
    input  wire [VIEW_W-1:0] cfg,
    input  wire stop_we, input wire [STOP_AW-1:0] stop_addr, input wire [P*M_W-1:0] stop_data,
    input  wire [M_W-1:0] r0_m, input wire [DIM_W-1:0] r0_j, input wire [PB_W-1:0] r0_pb,
    input  wire [P*LANE_W-1:0] tpos,
    input  wire [DIM_W-1:0] stx, input wire [DIM_W-1:0] sty,
    output wire [P-1:0] ok
);
    `CUBE4_VIEW_FIELDS(cfg);
    localparam integer LW    = (P > 1) ? $clog2(P) : 0;      // B = Q 2^LW + ... when P is a power of two
    localparam integer K     = DIM_W + LW;
    localparam integer PR_W  = DIM_W + K + 1;                // B * RECIP
    localparam [K:0]   RECIP = (K + 1)'(((64'd1 << K) + 64'(P) - 64'd1) / 64'(P));
    localparam integer BX_W  = DIM_W + 1;
    wire unused_cfg = ^{cfg_ni, cfg_nk};

    // ---- S0 -> S1: B, by, the beat's fields
    reg [DIM_W-1:0]    b1;
    reg [BX_W-1:0]     by1;
    reg [PB_W-1:0]     pb1;
    reg [P*LANE_W-1:0] t1;
    reg [M_W-1:0]      m_s [1:5];
    always @(posedge clk) begin
        b1  <= cfg_sx - stx;                                          // stx <= SX in every slice
        by1 <= BX_W'(r0_j) - BX_W'(sty) + BX_W'(cfg_sy);
        pb1 <= r0_pb;
        t1  <= tpos;
        m_s[1] <= r0_m;
    end
    wire unused_nj = ^cfg_nj;
    generate
        if (ROWS_W < BX_W) begin : g_by_top
            wire unused_by_top = ^by1[BX_W-1:ROWS_W];   // by < 2 MAX_DIM - 1
        end
    endgenerate

    // ---- S1 -> S2: Q = floor(B / P)
    reg [DIM_W-1:0]    b2, q2;
    reg [ROWS_W-1:0]   by2;
    reg [PB_W-1:0]     pb2;
    reg [P*LANE_W-1:0] t2;
    wire [PR_W-1:0]    prod = PR_W'(b1) * PR_W'(RECIP);
    always @(posedge clk) begin
        q2  <= DIM_W'(prod >> K);
        b2  <= b1;
        by2 <= by1[ROWS_W-1:0];
        pb2 <= pb1;
        t2  <= t1;
        m_s[2] <= m_s[1];
    end
    wire unused_prod = ^{prod[K-1:0], prod[PR_W-1:K+DIM_W]};

    // ---- S2: R, the banks' addresses; each lane's bank, carried to S4
    wire [DIM_W-1:0]  qp = DIM_W'(32'(q2) * P);
    wire [LANE_W-1:0] r2 = LANE_W'(b2 - qp);                         // 0 .. P-1
    wire [COLS_W-1:0] w2 = COLS_W'(pb2) + COLS_W'(q2);
    wire unused_b2 = ^{b2, qp};
    reg  [P*LANE_W-1:0] sel3, sel4;
    genvar b, q;
    integer k;
    wire [P*M_W-1:0] rd4;
    generate
        for (b = 0; b < P; b = b + 1) begin : g_bank
            wire [COLS_W-1:0] w = w2 + COLS_W'((32'(b) < 32'(r2)) ? 1 : 0);
            cube4_sdp_ram #(.DATA_W(M_W), .DEPTH(1 << STOP_AW), .OUT_REG(1)) u_bank (
                .clk(clk), .rd_en(1'b1), .rd_addr({by2, w}), .rd_data(rd4[b*M_W +: M_W]),
                .wr_en(stop_we), .wr_addr(stop_addr), .wr_data(stop_data[b*M_W +: M_W]));
        end
        for (q = 0; q < P; q = q + 1) begin : g_sel
            wire [LANE_W:0] s = {1'b0, t2[q*LANE_W +: LANE_W]} + {1'b0, r2};
            always @(posedge clk) begin
                sel3[q*LANE_W +: LANE_W] <= LANE_W'((32'(s) >= P) ? 32'(s) - P : 32'(s));
            end
        end
    endgenerate
    always @(posedge clk) begin
        sel4 <= sel3;
        for (k = 3; k <= 5; k = k + 1) m_s[k] <= m_s[k-1];
    end

    // ---- S4 -> S5: each lane's stop; S5: ok
    reg [M_W-1:0] stop5 [0:P-1];
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            wire [LANE_W-1:0] s4 = sel4[q*LANE_W +: LANE_W];
            always @(posedge clk) stop5[q] <= rd4[32'(s4)*M_W +: M_W];
            assign ok[q] = m_s[5] < stop5[q];
        end
    endgenerate
endmodule
`default_nettype wire

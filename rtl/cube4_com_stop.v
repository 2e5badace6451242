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
//   is a cube4_ray_table: P banks skewed along bx, so that a beat's P rays,
//   which lie on P consecutive columns of one base-plane row, read one bank
//   each (its header has the addressing).
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2: as cube4_com (1..64, 2..2048, 4..12, 0..3).
//   ROWS_W, COLS_W, STOP_AW: the table's layout (derived, CUBE4_STOP_LAYOUT).
//
// Latency
//   Stages move on every cycle (no enable, like COM's). R0's fields (S0) go
//   into the table's read (cube4_ray_table: each lane's stop at S5); ok is
//   combinational at S5 (from S5's registers): COM registers it into its S6
//   counts. The table is written between frames (stop_we), never read then.
//
// Ports
//   stop_we, stop_addr, stop_data  the table: one word of all P banks
//             (bank b at [b*M_W +: M_W], unsigned stop slices 0 .. M) at
//             address {by, word}
//   r0_m, r0_j, r0_pb, tpos, stx, sty   R0's slice, row, partial beam, the
//             lanes' positions t [LANE_W] and stepx(m), stepy(m) (S0)
//   ok        out  S5: the lane's sample is in front of the geometry
//
// Bit growth and rounding: none here (the table's addressing: cube4_ray_table).
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
    wire unused_cfg = ^{cfg_ni, cfg_nj, cfg_nk};

    wire [P*M_W-1:0] stop5;
    cube4_ray_table #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .DATA_W(M_W)
    ) u_table (
        .clk(clk), .sx(cfg_sx), .sy(cfg_sy),
        .tab_we(stop_we), .tab_addr(stop_addr), .tab_data(stop_data),
        .rd_j(r0_j), .rd_pb(r0_pb), .rd_tpos(tpos), .rd_stx(stx), .rd_sty(sty), .rd_data(stop5),
        .wr_valid(1'b0), .wr_j('0), .wr_pb('0), .wr_stx('0), .wr_sty('0), .wr_en('0), .wr_data('0));

    // ---- the slice alongside the table's five stages; S5: ok
    reg [M_W-1:0] m_s [1:5];
    integer k;
    always @(posedge clk) begin
        m_s[1] <= r0_m;
        for (k = 2; k <= 5; k = k + 1) m_s[k] <= m_s[k-1];
    end
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            assign ok[q] = m_s[5] < stop5[q*M_W +: M_W];
        end
    endgenerate
endmodule
`default_nettype wire

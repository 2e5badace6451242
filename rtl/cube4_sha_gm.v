`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_sha_gm
// -----------------------------------------------------------------------------
// Purpose
//   Gradient-magnitude modulation's factors (GMOD = 1, docs/numerics.md
//   section 23, golden/cube4/gmod.py), per lane:
//     s   = gi^2 + gj^2 + gk^2                          exact, 2 GW bits
//     idx = 0 for s = 0; else e = floor(log2 s), m = the GM_MB bits below the
//           leading one (s << GM_MB >> e, low bits), idx = e 2^GM_MB + m + 1
//     {fa, fs} = GMT[idx]                               0 .. 256 each (Q0.8)
//   No square root: the table is indexed by s in floating point (3 mantissa
//   bits), logarithmic bins of 1/16 of an octave of |g|. The host fills the
//   table from the scene's functions of |grad f| (cube4.gmod.gm_table); a
//   frame without modulation loads 256 everywhere (the identity).
//   The table is copied per two lanes (cube4_dual_read_ram, the LUT's
//   arrangement in cube4_sha), written between frames.
//
// Parameters
//   P        pipelines.                 1..64.  Default 8.
//   VOXEL_W  sample width; GW = VOXEL_W + 5 gradient bits. 1..16. Default 8.
//   GM_MB, GM_N, GMA_W, GMF_W: the table's layout (derived, CUBE4_GM_LAYOUT).
//
// Latency
//   CUBE4_GM_LAT = 7 stages from in_g* (stage a's registers) to fa, fs, no
//   enable: the squares' operand registers (1) and products (2, cube4_mul),
//   s (3), e and s (4), idx (5), the table's read register (6) and output
//   register (7).
//
// Ports
//   gm_we, gm_addr, gm_data   the table: gm_data = {fa, fs}, GMF_W bits each
//   in_gi, in_gj, in_gk       lane q at [q*GW], two's complement
//   fa, fs                    lane q at [q*GMF_W], unsigned 0 .. 256
//
// Bit growth and rounding: each square < 2^(2 GW - 2), s < 3 2^(2 GW - 2) <
//   2^(2 GW) (SW bits); e in clog2(SW) bits; no rounding (m truncates).
// =============================================================================
module cube4_sha_gm #(
    parameter integer P       = 8,
    parameter integer VOXEL_W = 8,
    `CUBE4_GM_LAYOUT,
    localparam integer GW = VOXEL_W + 5
) (
    input  wire clk,
    input  wire gm_we, input wire [GMA_W-1:0] gm_addr, input wire [2*GMF_W-1:0] gm_data,
    input  wire [P*GW-1:0] in_gi, input wire [P*GW-1:0] in_gj, input wire [P*GW-1:0] in_gk,
    output wire [P*GMF_W-1:0] fa, output wire [P*GMF_W-1:0] fs
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_sha_gm", "P", P, 1, 64)
        `CUBE4_RANGE(g_bad_voxel_w, "cube4_sha_gm", "VOXEL_W", VOXEL_W, 1, 16)
    endgenerate

    localparam integer SW = 2 * GW;                         // s
    localparam integer EW = $clog2(SW);                     // e = 0 .. SW - 1
    localparam integer TW = 2 * GMF_W;

    wire [P*GMA_W-1:0] idx_all;
    wire [P*TW-1:0]    word_all;
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            // 1, 2: the squares
            wire signed [2*GW-1:0] sq_i, sq_j, sq_k;
            wire signed [GW-1:0] gi = in_gi[q*GW +: GW];
            wire signed [GW-1:0] gj = in_gj[q*GW +: GW];
            wire signed [GW-1:0] gk = in_gk[q*GW +: GW];
            cube4_mul #(.A_W(GW), .B_W(GW)) u_sq_i (.clk(clk), .en(1'b1), .a(gi), .b(gi), .p(sq_i));
            cube4_mul #(.A_W(GW), .B_W(GW)) u_sq_j (.clk(clk), .en(1'b1), .a(gj), .b(gj), .p(sq_j));
            cube4_mul #(.A_W(GW), .B_W(GW)) u_sq_k (.clk(clk), .en(1'b1), .a(gk), .b(gk), .p(sq_k));
            // 3: s (each square is non-negative and below 2^(2 GW - 2))
            reg [SW-1:0] s3;
            always @(posedge clk) s3 <= $unsigned(sq_i) + $unsigned(sq_j) + $unsigned(sq_k);
            // 4: the leading one's position
            reg [EW-1:0] e_lead;
            integer b;
            always @(*) begin
                e_lead = '0;
                for (b = 0; b < SW; b = b + 1)
                    if (s3[b]) e_lead = EW'(b);
            end
            reg [SW-1:0] s4;
            reg [EW-1:0] e4;
            always @(posedge clk) begin
                s4 <= s3;
                e4 <= e_lead;
            end
            // 5: the entry, e 2^GM_MB + m + 1 (0 for s = 0)
            wire [SW+GM_MB-1:0] sh = {s4, {GM_MB{1'b0}}} >> e4;     // the leading one at bit GM_MB
            reg  [GMA_W-1:0]    idx5;
            always @(posedge clk) begin
                idx5 <= (s4 == '0) ? '0 : GMA_W'({e4, sh[GM_MB-1:0]}) + GMA_W'(1);
            end
            assign idx_all[q*GMA_W +: GMA_W] = idx5;
            wire unused_sh = ^sh[SW+GM_MB-1:GM_MB];
            // 6, 7: the table's read and output registers (g_pair)
            assign fa[q*GMF_W +: GMF_W] = word_all[q*TW + GMF_W +: GMF_W];
            assign fs[q*GMF_W +: GMF_W] = word_all[q*TW +: GMF_W];
        end
        for (q = 0; q < P; q = q + 2) begin : g_pair
            localparam integer Q1 = (q + 1 < P) ? q + 1 : q;
            wire [TW-1:0] word_1;
            cube4_dual_read_ram #(.DATA_W(TW), .DEPTH(GM_N), .OUT_REG(1)) u_gmt (
                .clk(clk), .rd_en(1'b1),
                .rd0_addr(idx_all[q*GMA_W +: GMA_W]), .rd0_data(word_all[q*TW +: TW]),
                .rd1_addr(idx_all[Q1*GMA_W +: GMA_W]), .rd1_data(word_1),
                .wr_en(gm_we), .wr_addr(gm_addr), .wr_data(gm_data));
            if (Q1 != q) begin : g_second
                assign word_all[Q1*TW +: TW] = word_1;
            end else begin : g_none
                wire unused_word_1 = ^word_1;
            end
        end
    endgenerate
endmodule
`default_nettype wire

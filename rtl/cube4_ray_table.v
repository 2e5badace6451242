`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_ray_table
// -----------------------------------------------------------------------------
// Purpose
//   One word per ray of the base plane (pixel (by, bx)), in P banks skewed
//   along bx, so that a beat's P rays, which lie on P consecutive columns of
//   one base-plane row, are one word of each bank:
//     bank = bx mod P,   word = {by [ROWS_W], bx div P [COLS_W]}
//   (golden/cube4/memory.py stop_table). Depth in's stop table (cube4_com_stop)
//   and the beat schedule's ray table (docs/architecture.md "Beat skipping and
//   ray termination") are this table: the host writes it between frames, a
//   beat reads the words of its lanes' rays, and a beat may write the words of
//   the rays at some of its positions.
//   For a beat of row j, partial beam pb in a slice whose steps are stx, sty,
//   the lane at position t holds bx = pb P + t + B with B = SX - stx >= 0 and
//   by = j - sty + SY. With B = Q P + R (0 <= R < P) bank b holds the word
//     pb + Q + (b < R ? 1 : 0)          (mod 2^COLS_W)
//   for position t = (b - R) mod P; the lane at t takes bank (t + R) mod P.
//   Q = floor(B * RECIP / 2^K), RECIP = ceil(2^K / P), K = DIM_W + clog2(P):
//   exact for every B < 2^DIM_W (RECIP P - 2^K < P <= 2^(K - DIM_W)); for P
//   a power of two Q and R are B's bits (no multiplier, no subtraction). A
//   position past the slice's last column may address a word that wraps; its
//   caller ignores what it reads and writes nothing there.
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2: the geometry (cube4_defs.vh; 1..64,
//           2..2048, 4..12, 0..3).
//   DATA_W  a ray's word.                          1..64.  Default 8.
//   RATE    beats read (and written) at once: beat pb and, with 2, beat
//           pb + 1 too, whose word in each bank is the next one. Each bank is
//           then RATE sub-banks of 1/RATE the depth, word w in sub-bank
//           w mod RATE: the same bits, any RATE consecutive words in one read.
//                                                  1..2.   Default 1.
//   OUT_STAGE  1: each sub-bank's word (past the bypass below) is registered
//           as it leaves its block RAM, and the lanes' picks run a stage
//           later: rd_data at S6, no logic between a block RAM and a
//           flip-flop but the bypass. 0: rd_data at S5.  0..1.  Default 0.
//   ROWS_W, COLS_W, STOP_AW: the layout (derived, CUBE4_STOP_LAYOUT).
//
// Latency
//   Read: stages move on every cycle. The beat's fields (S0) are registered
//   into S1; S1 -> S2 Q; S2: R and the banks' read addresses (into
//   cube4_sdp_ram with OUT_REG: the word at S4); S4 -> S5 each lane's word:
//   rd_data is a register, 5 edges after its fields (6 with OUT_STAGE: S5
//   holds each sub-bank's word, S5 -> S6 each lane's). With P a power of two
//   (Q and R are bits of B) each sub-bank's address is formed at S1 and
//   registered: the same access at S2, its address from a flip-flop, not
//   from a sum.
//   Write: the same arithmetic; the banks take the word at the third edge
//   after its fields (S3 -> the banks' write ports). A read issued one cycle
//   or more after a write returns the written word; one issued in the same
//   cycle returns the old word. (A read issued the cycle after meets the
//   write at the banks' edge, where block RAM promises neither word: a bypass
//   gives the new one.)
//   The host's writes (tab_we) go straight to the banks' write ports and
//   must not meet a beat's write (between frames only).
//
// Ports
//   sx, sy     SX = stepx(M-1), SY = stepy(M-1) (the view's, [DIM_W])
//   tab_we, tab_addr, tab_data   the host's write: one word of all P banks
//             (bank b at [b*DATA_W +: DATA_W]) at address {by, word}
//   rd_j, rd_pb, rd_tpos, rd_stx, rd_sty   S0: the reading beat's row, partial
//             beam, its lanes' positions t [LANE_W] and the slice's steps
//   rd_data   out  S5 (S6 with OUT_STAGE): beat r's lane q's ray's word at
//             [(r*P + q)*DATA_W +: DATA_W]
//   wr_valid, wr_j, wr_pb, wr_stx, wr_sty   S0: a writing beat's fields
//   wr_en, wr_data   S0: per beat r and position t (not lane) whether to write
//             its ray's word and the word, at bit r*P + t and word
//             [(r*P + t)*DATA_W +: DATA_W]
//
// Bit growth and rounding: B in DIM_W bits (0 .. SX), the product B RECIP in
//   DIM_W + K + 1 bits; the word sum wraps mod 2^COLS_W (see above); no
//   rounding.
// =============================================================================
module cube4_ray_table #(
    `CUBE4_SLICE_PARAMS,
    parameter integer DATA_W = 8,
    parameter integer RATE   = 1,
    parameter integer OUT_STAGE = 0,
    `CUBE4_STOP_LAYOUT
) (
    input  wire clk,
    input  wire [DIM_W-1:0] sx, input wire [DIM_W-1:0] sy,
    input  wire tab_we, input wire [STOP_AW-1:0] tab_addr, input wire [P*DATA_W-1:0] tab_data,
    input  wire [DIM_W-1:0] rd_j, input wire [PB_W-1:0] rd_pb, input wire [P*LANE_W-1:0] rd_tpos,
    input  wire [DIM_W-1:0] rd_stx, input wire [DIM_W-1:0] rd_sty,
    output wire [RATE*P*DATA_W-1:0] rd_data,
    input  wire wr_valid, input wire [DIM_W-1:0] wr_j, input wire [PB_W-1:0] wr_pb,
    input  wire [DIM_W-1:0] wr_stx, input wire [DIM_W-1:0] wr_sty,
    input  wire [RATE*P-1:0] wr_en, input wire [RATE*P*DATA_W-1:0] wr_data
);
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_ray_table", "DATA_W", DATA_W, 1, 64)
        `CUBE4_RANGE(g_bad_rate, "cube4_ray_table", "RATE", RATE, 1, 2)
        `CUBE4_RANGE(g_bad_out_stage, "cube4_ray_table", "OUT_STAGE", OUT_STAGE, 0, 1)
    endgenerate
    localparam integer LW    = (P > 1) ? $clog2(P) : 0;
    localparam integer K     = DIM_W + LW;
    localparam integer PR_W  = DIM_W + K + 1;                // B * RECIP
    localparam [K:0]   RECIP = (K + 1)'(((64'd1 << K) + 64'(P) - 64'd1) / 64'(P));
    localparam integer BX_W  = DIM_W + 1;
    localparam integer RL_W  = 1;                            // a beat or sub-bank index (RATE <= 2)
    localparam integer RL    = (RATE > 1) ? 1 : 0;           // log2 RATE
    localparam integer CS_W  = (COLS_W > RL) ? COLS_W - RL : 0;   // a sub-bank's column bits
    localparam integer SA_W  = ROWS_W + CS_W;                // a sub-bank's address
    localparam integer BI_W  = (RATE * P > 1) ? $clog2(RATE * P) : 1;   // a beat's position bit
    // a word's address in its sub-bank: {by, w div RATE}
    function automatic [SA_W-1:0] sub_addr(input [ROWS_W-1:0] by, input [COLS_W-1:0] w);
        sub_addr = SA_W'({by, w} >> (COLS_W - CS_W));
    endfunction
    genvar b, q;

    // ==== a beat's place in the table: {by, Q, R} two edges after its fields ====
    // (the read's and the write's, side by side: index 0 read, 1 write)
    reg [DIM_W-1:0]  b1 [0:1];
    reg [BX_W-1:0]   by1 [0:1];
    reg [PB_W-1:0]   pb1 [0:1];
    reg [DIM_W-1:0]  b2 [0:1], q2 [0:1];
    reg [ROWS_W-1:0] by2 [0:1];
    reg [PB_W-1:0]   pb2 [0:1];
    wire [DIM_W-1:0] stx0 [0:1], sty0 [0:1], j0 [0:1];
    wire [PB_W-1:0]  pb0 [0:1];
    assign {j0[0], pb0[0], stx0[0], sty0[0]} = {rd_j, rd_pb, rd_stx, rd_sty};
    assign {j0[1], pb0[1], stx0[1], sty0[1]} = {wr_j, wr_pb, wr_stx, wr_sty};
    wire [LANE_W-1:0] r2 [0:1];
    wire [COLS_W-1:0] w2 [0:1];
    // P a power of two (EARLY): the read's R and first word one stage sooner, from
    // S1's registers, so each sub-bank's address is a register and no sum reaches
    // a block RAM's address pins; otherwise (Q from a product at S1 -> S2) the
    // address is S2's sum
    localparam integer EARLY = ((P & (P - 1)) == 0) ? 1 : 0;
    wire [LANE_W-1:0] r1r;                 // the read's R at S1 (EARLY)
    wire [COLS_W-1:0] w1r;                 // pb + Q at S1 (a bank's first word: + (b < R))
    generate
        for (q = 0; q < 2; q = q + 1) begin : g_place
            always @(posedge clk) begin
                b1[q]  <= sx - stx0[q];                                 // stx <= SX in every slice
                by1[q] <= BX_W'(j0[q]) - BX_W'(sty0[q]) + BX_W'(sy);
                pb1[q] <= pb0[q];
                b2[q]  <= b1[q];
                by2[q] <= by1[q][ROWS_W-1:0];
                pb2[q] <= pb1[q];
            end
            if ((P & (P - 1)) == 0) begin : g_pow2
                // Q and R are B's bits: R the low LW, Q the rest
                always @(posedge clk) q2[q] <= b1[q] >> LW;
                if (P > 1) begin : g_r
                    assign r2[q] = b2[q][LANE_W-1:0];
                end else begin : g_r0
                    assign r2[q] = '0;
                end
                if (q == 0) begin : g_early
                    if (P > 1) begin : g_r
                        assign r1r = b1[q][LANE_W-1:0];
                    end else begin : g_r0
                        assign r1r = '0;
                    end
                    assign w1r = COLS_W'(pb1[q]) + COLS_W'(b1[q] >> LW);
                end
                wire unused_place = ^b2[q];
            end else begin : g_div
                wire [PR_W-1:0] prod = PR_W'(b1[q]) * PR_W'(RECIP);
                always @(posedge clk) q2[q] <= DIM_W'(prod >> K);
                wire [DIM_W-1:0] qp = DIM_W'(32'(q2[q]) * P);
                assign r2[q] = LANE_W'(b2[q] - qp);                        // 0 .. P-1
                wire unused_place = ^{prod[K-1:0], prod[PR_W-1:K+DIM_W], b2[q], qp};
                if (q == 0) begin : g_late
                    assign {r1r, w1r} = '0;        // (EARLY = 0: the address is S2's sum)
                    wire unused_early = ^{r1r, w1r};
                end
            end
            assign w2[q] = COLS_W'(pb2[q]) + COLS_W'(q2[q]);
            if (ROWS_W < BX_W) begin : g_by_top
                wire unused_by_top = ^by1[q][BX_W-1:ROWS_W];   // by < 2 MAX_DIM - 1
            end
        end
    endgenerate

    // ==== the write: each bank's position (b - R) mod P, registered into S3 ====
    reg [RATE*P-1:0]        we1, we2;
    reg                     wv1, wv2;
    reg [RATE*P*DATA_W-1:0] wd1, wd2;
    always @(posedge clk) begin
        {wv2, wv1} <= {wv1, wr_valid};
        {we2, we1} <= {we1, wr_en};
        {wd2, wd1} <= {wd1, wr_data};
    end
    // ==== the read: each lane's bank carried to S4 ====
    reg  [P*LANE_W-1:0] t1, t2, sel3, sel4, sel5;
    always @(posedge clk) begin
        t1 <= rd_tpos;
        t2 <= t1;
        sel4 <= sel3;
        sel5 <= sel4;
    end
    // the picks' stage: S4 -> S5, or (OUT_STAGE) S5 -> S6
    wire [P*LANE_W-1:0] sel_o = (OUT_STAGE != 0) ? sel5 : sel4;
    // per bank b and beat r of the read: the word, from sub-bank (its word mod RATE)
    wire [RATE*P*DATA_W-1:0] rd4;          // beat r, bank b at [(r*P + b)*DATA_W] (the picks' stage)
    genvar r, sb;
    generate
        for (b = 0; b < P; b = b + 1) begin : g_bank
            wire [LANE_W:0]   d  = (LANE_W + 1)'(b + P) - {1'b0, r2[1]};
            wire [LANE_W-1:0] tw = LANE_W'((32'(d) >= P) ? 32'(d) - P : 32'(d));   // (b - R) mod P
            // the first beat's word in this bank; beat r's is r words on
            wire [COLS_W-1:0] ww = w2[1] + COLS_W'((32'(b) < 32'(r2[1])) ? 1 : 0);
            wire [COLS_W-1:0] wr = w2[0] + COLS_W'((32'(b) < 32'(r2[0])) ? 1 : 0);
            reg  [RL_W-1:0]   par3, par4, par5;   // the read's first word mod RATE, to S4 (S5)
            always @(posedge clk) {par5, par4, par3} <= {par4, par3, RL_W'(32'(wr) & (RATE - 1))};
            wire [RL_W-1:0]   par_o = (OUT_STAGE != 0) ? par5 : par4;
            wire [DATA_W-1:0] sub_q [0:RATE-1];
            for (sb = 0; sb < RATE; sb = sb + 1) begin : g_sub
                // the beats whose words fall in this sub-bank, and those words
                wire [RL_W-1:0]   rw  = RL_W'((32'(sb) - 32'(ww)) & (RATE - 1));
                wire [COLS_W-1:0] wwd = ww + COLS_W'(rw);
                wire [BI_W-1:0]   bit_w = BI_W'(32'(rw) * P + 32'(tw));
                reg               bw3;
                reg  [SA_W-1:0]   ba3;
                reg  [DATA_W-1:0] bd3;
                wire [DATA_W-1:0] wd_pick;
                cube4_mux #(.N(RATE * P), .W(DATA_W)) u_wd (.words(wd2), .sel(bit_w), .word(wd_pick));
                always @(posedge clk) begin
                    bw3 <= wv2 && we2[bit_w];
                    ba3 <= sub_addr(by2[1], wwd);
                    bd3 <= wd_pick;
                end
                // the read's address at S2: a sum of S2's fields, or (EARLY) a register
                // loaded with the same sum formed from S1's
                wire [SA_W-1:0] ra_s2;
                if (EARLY != 0) begin : g_early
                    wire [COLS_W-1:0] wr1 = w1r + COLS_W'((32'(b) < 32'(r1r)) ? 1 : 0);
                    wire [RL_W-1:0]   rr1 = RL_W'((32'(sb) - 32'(wr1)) & (RATE - 1));
                    reg  [SA_W-1:0]   ra2_q;
                    always @(posedge clk) ra2_q <= sub_addr(by1[0][ROWS_W-1:0], wr1 + COLS_W'(rr1));
                    assign ra_s2 = ra2_q;
                end else begin : g_late
                    wire [RL_W-1:0]   rr  = RL_W'((32'(sb) - 32'(wr)) & (RATE - 1));
                    wire [COLS_W-1:0] wrd = wr + COLS_W'(rr);
                    assign ra_s2 = sub_addr(by2[0], wrd);
                end
                wire tab_here = tab_we && ((32'(tab_addr[COLS_W-1:0]) & (RATE - 1)) == sb);
                wire              we = tab_here || (!tab_we && bw3);
                wire [SA_W-1:0]   wa = tab_we ? sub_addr(tab_addr[STOP_AW-1:COLS_W], tab_addr[COLS_W-1:0]) : ba3;
                wire [DATA_W-1:0] wd = tab_we ? tab_data[b*DATA_W +: DATA_W] : bd3;
                wire [DATA_W-1:0] q4;
                cube4_sdp_ram #(.DATA_W(DATA_W), .DEPTH(1 << SA_W), .OUT_REG(1)) u_bank (
                    .clk(clk), .rd_en(1'b1), .out_en(1'b0), .rd_addr(ra_s2), .rd_data(q4),
                    .wr_en(we), .wr_addr(wa), .wr_data(wd));
                // a read at the edge of a beat's write to the same word takes the new word
                reg               hit3, hit4;
                reg  [DATA_W-1:0] hd3, hd4;
                always @(posedge clk) begin
                    hit3 <= bw3 && (ba3 == ra_s2);
                    hd3  <= bd3;
                    hit4 <= hit3;
                    hd4  <= hd3;
                end
                wire [DATA_W-1:0] word4 = hit4 ? hd4 : q4;
                if (OUT_STAGE != 0) begin : g_stage
                    reg [DATA_W-1:0] word5;
                    always @(posedge clk) word5 <= word4;
                    assign sub_q[sb] = word5;
                end else begin : g_direct
                    assign sub_q[sb] = word4;
                end
            end
            // beat r's word is in sub-bank (first word + r) mod RATE
            for (r = 0; r < RATE; r = r + 1) begin : g_out
                wire [RL_W-1:0] at = RL_W'((32'(par_o) + r) & (RATE - 1));
                assign rd4[(r*P + b)*DATA_W +: DATA_W] = sub_q[at];
            end
        end
        for (q = 0; q < P; q = q + 1) begin : g_sel
            wire [LANE_W:0] s = {1'b0, t2[q*LANE_W +: LANE_W]} + {1'b0, r2[0]};
            always @(posedge clk) begin
                sel3[q*LANE_W +: LANE_W] <= LANE_W'((32'(s) >= P) ? 32'(s) - P : 32'(s));
            end
        end
    endgenerate

    // ==== S4 -> S5 (OUT_STAGE: S5 -> S6): each beat's lanes' words ====
    reg [RATE*P*DATA_W-1:0] word_q;
    generate
        for (r = 0; r < RATE; r = r + 1) begin : g_beat5
            for (q = 0; q < P; q = q + 1) begin : g_lane
                wire [DATA_W-1:0] pick;
                cube4_mux #(.N(P), .W(DATA_W)) u_pick (
                    .words(rd4[r*P*DATA_W +: P*DATA_W]), .sel(sel_o[q*LANE_W +: LANE_W]), .word(pick));
                always @(posedge clk) begin
                    word_q[(r*P + q)*DATA_W +: DATA_W] <= pick;
                end
            end
        end
    endgenerate
    assign rd_data = word_q;
endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_tri_lane
// -----------------------------------------------------------------------------
// Purpose
//   One lane of TRI (cube4_tri): the tri-linear sample of the lane's 2 x 2 x 2
//   cell, seven lerps per channel (Teramac paper, eq. 4; docs/numerics.md
//   section 4), all of them the shared cube4_lerp, in the golden model's
//   order: x in rows j and j + 1 of both slices, then y, then z. With VGRAD
//   each of the word's four channels (the voxel, the gradient's components;
//   CUBE4_WORD_LAYOUT) has its own seven lerps (numerics.md section 5b).
//   The lane keeps its own copies of the weights (wx at s4, wy / wz when the
//   y / z lerps start): one shared register would drive the multipliers of
//   every lane and every channel. Likewise the x-lerps' differences b - a:
//   the lane forms them from the cell one cycle before s4 (pre_vals,
//   pre_nvals) and registers them with s4 (cube4_lerp DIFF_IN), so each
//   x-lerp's multiplier loads its operand from a register of its own lane,
//   not through a subtractor from the beam buffer's registers. The y- and
//   z-lerps' differences too: each is registered beside the two results it
//   is the difference of, from the earlier lerps' next values (cube4_lerp
//   y_next), so every multiplier of the lane loads a register, not the
//   output of a carry chain (a difference formed from the results' registers
//   in front of its MULT18X18D was a critical path of the beat build).
//
// Parameters
//   VOXEL_W   voxel / sample width.                1..16.  Default 8.
//   WEIGHT_W  weight width W.                      4..12.  Default 8.
//   VGRAD     1: four channels per word, 0: one.   0..1.   Default 0.
//   LABELS    1: the word's label channel (top LBL_W bits) takes the
//             nearest corner's label: seven cube4_pick in the lerps' places
//             (numerics.md section 24). Needs VGRAD = 0. 0..1. Default 0.
//   The lerp latency is CUBE4_TRI_LERP_LAT (cube4_defs.vh).
//
// Latency
//   Moves on every cycle (no enable). wx is registered with s4 (its input is
//   s3's), the x-lerps start from s4's cell and take TRI_LERP_LAT cycles,
//   then the y-lerps, then the z-lerp (wy / wz registered one cycle before
//   each starts): sample is valid 3 * TRI_LERP_LAT cycles after s4.
//
// Ports
//   wx, wy, wz   in   weights, unsigned Q0.WEIGHT_W (wx one cycle before s4,
//                     wy / wz one cycle before the y / z lerps start)
//   vals         in   s4: 4 words {prev upper, prev lower, cur upper, cur lower}
//                     (rows j, j + 1 of the lower and upper slice, position i)
//   nvals        in   s4: the same at position i + 1
//   pre_vals, pre_nvals   in   vals and nvals one cycle before s4 (s3)
//   sample       out  the sample word (WORD_W bits: the voxel channel unsigned
//                     Q0.VOXEL_W, with VGRAD the three components signed VG_W,
//                     with LABELS the label above the voxel, unsigned LABEL_W)
//
// Bit growth and rounding
//   Each lerp rounds half up once (cube4_lerp); a lerp's result lies between
//   its inputs, so every channel keeps its width. A gradient component enters
//   its lerps with the sign bit flipped (offset binary) and leaves with it
//   flipped back: the unsigned lerp of a + B and b + B is the signed lerp of
//   a and b plus B, bit for bit.
// =============================================================================
module cube4_tri_lane #(
    parameter integer VOXEL_W = 8, parameter integer WEIGHT_W = 8, parameter integer VGRAD = 0,
    parameter integer LABELS = 0,
    `CUBE4_WORD_LAYOUT
) (
    input  wire clk,
    input  wire [WEIGHT_W-1:0] wx, input wire [WEIGHT_W-1:0] wy, input wire [WEIGHT_W-1:0] wz,
    input  wire [4*WORD_W-1:0] vals, input wire [4*WORD_W-1:0] nvals,
    input  wire [4*WORD_W-1:0] pre_vals, input wire [4*WORD_W-1:0] pre_nvals,
    output wire [WORD_W-1:0] sample
);
    generate
        `CUBE4_RANGE(g_bad_voxel_w, "cube4_tri_lane", "VOXEL_W", VOXEL_W, 1, 16)
        `CUBE4_RANGE(g_bad_vgrad, "cube4_tri_lane", "VGRAD", VGRAD, 0, 1)
        `CUBE4_RANGE(g_bad_labels, "cube4_tri_lane", "LABELS", LABELS, 0, 1)
        if (LABELS != 0 && VGRAD != 0) begin : g_labels_vgrad
            $error("cube4_tri_lane: LABELS = 1 needs VGRAD = 0");
        end
    endgenerate

    localparam integer VW       = WORD_W;
    localparam integer LERP_LAT = `CUBE4_TRI_LERP_LAT;

    reg [WEIGHT_W-1:0] wx_l, wy_l, wz_l;
    (* keep *)
    always @(posedge clk) begin
        wx_l <= wx;
        wy_l <= wy;
        wz_l <= wz;
    end

    genvar c, n;
    generate
        for (c = 0; c < NCH + LABELS; c = c + 1) begin : g_ch
            // channel c of the word: the voxel, then the gradient components
            // (a gradient component is two's complement in the word: its sign
            // bit flipped makes it offset binary for the unsigned lerps); with
            // LABELS the last channel is the label (the word's top LBL_W bits),
            // whose seven steps are picks: the nearest corner's label
            localparam integer LBL  = (c == NCH) ? 1 : 0;
            localparam integer CW   = (LBL != 0) ? LBL_W : ((c == 0) ? VOXEL_W : VG_W);
            localparam integer OFF  = (LBL != 0) ? WORD_W - LBL_W : ((c == 0) ? 0 : VOXEL_W + (c - 1) * VG_W);
            localparam [CW-1:0] FLIP = (c == 0 || LBL != 0) ? '0 : (CW'(1) << (CW - 1));
            // step n: 0 .. 3 x in row j lower, j + 1 lower, j upper, j + 1 upper
            // (value index 2, 0, 3, 1 of vals, with nvals at i + 1); 4, 5 y of
            // the lower and the upper slice (x results 0, 1 and 2, 3); 6 z (4, 5)
            wire [7*CW-1:0] y;
            wire [7*CW-1:0] yn;          // each step's next y (cube4_lerp y_next)
            for (n = 0; n < 7; n = n + 1) begin : g_lerp
                localparam integer IX = (((n % 2) != 0) ? 0 : 2) + n / 2;
                wire [CW-1:0] a, b;
                wire [CW:0]   d;             // b - a, sQ CW + 1 (x-lerps: registered with s4)
                wire [WEIGHT_W-1:0] w = (n < 4) ? wx_l : ((n < 6) ? wy_l : wz_l);
                if (n < 4) begin : g_x
                    assign a = FLIP ^ vals[IX*VW + OFF +: CW];
                    assign b = FLIP ^ nvals[IX*VW + OFF +: CW];
                    wire [CW-1:0] pa = FLIP ^ pre_vals[IX*VW + OFF +: CW];
                    wire [CW-1:0] pb = FLIP ^ pre_nvals[IX*VW + OFF +: CW];
                    reg  [CW:0]   d_q;
                    always @(posedge clk) d_q <= {1'b0, pb} - {1'b0, pa};
                    assign d = d_q;
                end else begin : g_yz
                    assign a = y[(2*n-8)*CW +: CW];
                    assign b = y[(2*n-7)*CW +: CW];
                    if (LBL == 0) begin : g_d
                        // b - a of the results a and b as they are loaded (the
                        // lerps move every cycle: d_q is b - a in a and b's cycle)
                        reg [CW:0] d_q;
                        always @(posedge clk) d_q <= {1'b0, yn[(2*n-7)*CW +: CW]} - {1'b0, yn[(2*n-8)*CW +: CW]};
                        assign d = d_q;
                    end else begin : g_no_d
                        assign d = '0;
                    end
                end
                if (LBL != 0) begin : g_pick
                    cube4_pick #(.DATA_W(CW), .WEIGHT_W(WEIGHT_W), .LATENCY(LERP_LAT)) u_pick (
                        .clk(clk), .en(1'b1), .a(a), .b(b), .w(w), .y(y[n*CW +: CW]));
                    assign yn[n*CW +: CW] = '0;        // (no difference of picks is formed)
                    wire unused_d = ^d;
                end else begin : g_mix
                    cube4_lerp #(.DATA_W(CW), .WEIGHT_W(WEIGHT_W), .LATENCY(LERP_LAT),
                                 .DIFF_IN(1)) u_lerp (
                        .clk(clk), .en(1'b1), .a(a), .b(b), .d(d), .w(w), .y(y[n*CW +: CW]),
                        .y_next(yn[n*CW +: CW]));
                end
            end
            assign sample[OFF +: CW] = FLIP ^ y[6*CW +: CW];
            // (the z-lerp's next value: nothing follows it; a label channel's picks form no difference)
            wire unused_yn = (LBL != 0) ? ^yn : ^yn[6*CW +: CW];
        end
    endgenerate
endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_pick
// -----------------------------------------------------------------------------
// Purpose
//   The nearest of two: y = b when w >= 2^(WEIGHT_W-1), else a. The label
//   channel's step in TRI (docs/numerics.md section 24): where cube4_lerp
//   mixes the two values, this picks the label of the nearer voxel, with the
//   same ports and latency so that it runs beside the lerps. A tie (w exactly
//   one half) goes to b, as the lerp's rounding goes up. Golden twin:
//   nearest_pair in golden/cube4/labels.py.
//
// Parameters
//   DATA_W    width of a, b, y.                       1..16.  Default 4.
//   WEIGHT_W  width of the weight w.                  1..12.  Default 8.
//   LATENCY   clock cycles from inputs to y (as      0..4.   Default 0.
//             cube4_lerp's: a, b and w are taken together).
//
// Latency
//   LATENCY cycles; registers advance on clk with en = 1. No reset (datapath).
//
// Ports
//   a, b  in   [DATA_W-1:0]    the labels at w = 0 and w -> 1 (unsigned)
//   w     in   [WEIGHT_W-1:0]  weight Q0.WEIGHT_W, only its top bit is read
//   y     out  [DATA_W-1:0]    a or b
//
// Bit growth and rounding: none (a select).
// =============================================================================
module cube4_pick #(
    parameter integer DATA_W   = 4,
    parameter integer WEIGHT_W = 8,
    parameter integer LATENCY  = 0
) (
    input  wire                clk,
    input  wire                en,
    input  wire [DATA_W-1:0]   a,
    input  wire [DATA_W-1:0]   b,
    input  wire [WEIGHT_W-1:0] w,
    output wire [DATA_W-1:0]   y
);
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_pick", "DATA_W", DATA_W, 1, 16)
        `CUBE4_RANGE(g_bad_weight_w, "cube4_pick", "WEIGHT_W", WEIGHT_W, 1, 12)
        `CUBE4_RANGE(g_bad_latency, "cube4_pick", "LATENCY", LATENCY, 0, 4)
    endgenerate

    wire [DATA_W-1:0] y_comb = w[WEIGHT_W-1] ? b : a;
    wire unused_w = ^w[WEIGHT_W-1:0];     // (only the top bit decides)

    generate
        if (LATENCY == 0) begin : g_comb
            assign y = y_comb;
            wire unused_clk = clk ^ en;
        end else begin : g_reg
            genvar k;
            for (k = 0; k < LATENCY; k = k + 1) begin : g_stage
                reg [DATA_W-1:0] q;
                if (k == 0) begin : g_first
                    always @(posedge clk) if (en) q <= y_comb;
                end else begin : g_next
                    always @(posedge clk) if (en) q <= g_stage[k - 1].q;
                end
            end
            assign y = g_stage[LATENCY - 1].q;
        end
    endgenerate
endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_ring_shift
// -----------------------------------------------------------------------------
// Purpose
//   One hop on the pipeline ring: lane q receives lane q - 1 (down = 0) or
//   lane q + 1 (down = 1), modulo P. This is the only way data moves between
//   pipelines in Cube-4: each lane is wired to its two ring neighbours, with a
//   fixed width, never across the whole ring (no barrel shifter, no crossbar).
//   Used to realign data whose skew changed by one between beams or slices.
//
// Parameters
//   P       lanes (pipelines).     Range 1..64.    Default 8.
//   DATA_W  bits per lane.         Range 1..512.   Default 8.
//
// Latency
//   0 cycles (wiring and one 2:1 multiplexer per lane).
//
// Ports
//   down  in   1 bit          0: y[q] = x[q-1]; 1: y[q] = x[q+1] (indices mod P)
//   x     in   [P*DATA_W]     lane q at bits q*DATA_W +: DATA_W (any format)
//   y     out  [P*DATA_W]     same format
//
// Bit growth and rounding: none.
// =============================================================================
module cube4_ring_shift #(
    parameter integer P      = 8,
    parameter integer DATA_W = 8
) (
    input  wire                down,
    input  wire [P*DATA_W-1:0] x,
    output wire [P*DATA_W-1:0] y
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_ring_shift", "P", P, 1, 64)
        `CUBE4_RANGE(g_bad_data_w, "cube4_ring_shift", "DATA_W", DATA_W, 1, 512)
    endgenerate

    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            localparam integer LEFT  = (q + P - 1) % P;  // lane q - 1
            localparam integer RIGHT = (q + 1) % P;      // lane q + 1
            assign y[q*DATA_W +: DATA_W] = down ? x[RIGHT*DATA_W +: DATA_W]
                                                : x[LEFT*DATA_W +: DATA_W];
        end
    endgenerate

endmodule
`default_nettype wire

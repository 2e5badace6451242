`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_skid
// -----------------------------------------------------------------------------
// Purpose
//   Two-entry skid buffer for a valid/ready stream whose in_ready is a
//   register: cube4_skid_peek (which documents the buffer: its entries, the
//   free flags and read-pointer copies per 64 data bits, full throughput)
//   without the ports that show the entry behind the head and the copies of
//   in_ready and out_valid.
//
// Parameters
//   DATA_W        width of the payload.  Range 1..4096.  Default 8.
//
// Latency
//   1 cycle from an accepted input to out_valid (cube4_skid_peek).
//
// Ports
//   clk, rst                 clock, synchronous active-high reset (empties it)
//   in_valid/in_ready/in_data   input stream (in_data: any format, DATA_W
//                            bits); in_ready is a register
//   out_valid/out_ready/out_data output stream (same format)
//
// Bit growth and rounding: none (storage only).
// =============================================================================
module cube4_skid #(
    parameter integer DATA_W = 8
) (
    `CUBE4_STREAM_PORTS(DATA_W)
);
    wire              unused_nx_valid, unused_ready_cp, unused_ready_nx, unused_valid_cp;
    wire [DATA_W-1:0] unused_nx_data;
    cube4_skid_peek #(.DATA_W (DATA_W)) u_skid (
        .clk (clk), .rst (rst),
        .in_valid (in_valid), .in_ready (in_ready), .in_data (in_data),
        .out_valid (out_valid), .out_ready (out_ready), .out_data (out_data),
        .nx_valid (unused_nx_valid), .nx_data (unused_nx_data), .in_ready_cp (unused_ready_cp),
        .in_ready_nx (unused_ready_nx), .out_valid_cp (unused_valid_cp));
    wire unused_nx = ^{unused_nx_valid, unused_nx_data, unused_ready_cp, unused_ready_nx, unused_valid_cp};
endmodule
`default_nettype wire

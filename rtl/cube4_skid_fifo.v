`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_skid_fifo
// -----------------------------------------------------------------------------
// Purpose
//   A first-in first-out queue whose two ends lie far apart on the die: a skid
//   buffer (cube4_skid_peek, its ready in READY_N copies) beside the
//   producer, the queue, and a skid buffer (cube4_skid_peek, its valid in
//   VALID_N copies) beside the consumer. in_ready is the front skid's register and out_ready
//   moves only the back skid's pointers, so neither end's handshake reaches
//   the queue's count, its RAM's read enable or the other end in the same
//   cycle: each route across the die starts and ends at a register. The
//   queue is in block RAM behind a register queue (cube4_ram_fifo) or in
//   distributed RAM (cube4_sync_fifo). The beat schedule's position bits
//   wait in two of them (cube4_frontend: beside the memory and TRI;
//   cube4_top: beside GRA and SHA).
//
// Parameters
//   DATA_W   width of an item.                               1..4096.  Default 8.
//   DEPTH    the queue's entries; a power of two.  RAM = 1: 4..2^20;
//            RAM = 0: 2..1024.                                          Default 64.
//   RAM      1: the queue in block RAM (cube4_ram_fifo), 0: in distributed
//            RAM (cube4_sync_fifo).                         0..1.     Default 0.
//   OUT_REG  RAM = 1: the RAM's output register (cube4_ram_fifo OUT_REG).
//            0..1.                                                      Default 0.
//   READY_N  copies of in_ready (in_ready_cp; the front skid's,
//            cube4_skid_peek).                              1..16.    Default 1.
//   VALID_N  copies of out_valid (out_valid_cp; the back skid's,
//            cube4_skid_peek).                              1..16.    Default 1.
//
// Latency
//   Into an empty queue an item is on out_valid Q + 2 edges after the edge
//   that took it: one per skid buffer and the queue's Q (cube4_sync_fifo: 0,
//   it is on its output right after the edge that wrote it; cube4_ram_fifo:
//   L + 1, L = 1 + OUT_REG, its RAM's read and its register queue). Full
//   rate: one item in and one out per cycle. It holds DEPTH + 4 items
//   (RAM = 1: DEPTH + L + 6, the register queue's L + 2 as well).
//
// Ports
//   clk, rst                     clock, synchronous active-high reset (empties it)
//   in_valid/in_ready/in_data    items in (any format, DATA_W bits); in_ready a register
//   in_ready_cp  out  [READY_N]  copies of in_ready (copy 0 is in_ready)
//   in_ready_nx  out  in_ready after the next edge (the front skid's,
//                     combinational; cube4_skid_peek)
//   out_valid_cp out  [VALID_N]  copies of out_valid (copy 0 is out_valid)
//   out_valid/out_ready/out_data items out, in order; out_valid and out_data
//                                the back skid's (registers through its 2:1 select)
//
// Bit growth and rounding: none (storage only).
// =============================================================================
module cube4_skid_fifo #(
    parameter integer DATA_W  = 8,
    parameter integer DEPTH   = 64,
    parameter integer RAM     = 0,
    parameter integer OUT_REG = 0,
    parameter integer READY_N = 1,
    parameter integer VALID_N = 1
) (
    `CUBE4_STREAM_PORTS(DATA_W),
    output wire [READY_N-1:0] in_ready_cp,
    output wire in_ready_nx,
    output wire [VALID_N-1:0] out_valid_cp
);
    generate
        `CUBE4_RANGE(g_bad_ram, "cube4_skid_fifo", "RAM", RAM, 0, 1)
        if (RAM == 0 && OUT_REG != 0) begin : g_bad_out_reg
            $error("cube4_skid_fifo: OUT_REG = 1 needs RAM = 1 (the block RAM's output register)");
        end
    endgenerate
    wire              k_valid, k_ready, f_valid, f_ready;
    wire [DATA_W-1:0] k_data, f_data;
    // beside the producer
    wire              unused_nx_valid, unused_k_valid_cp;
    wire [DATA_W-1:0] unused_nx_data;
    cube4_skid_peek #(.DATA_W (DATA_W), .READY_N (READY_N)) u_in (
        .clk (clk), .rst (rst),
        .in_valid (in_valid), .in_ready (in_ready), .in_data (in_data),
        .out_valid (k_valid), .out_ready (k_ready), .out_data (k_data),
        .nx_valid (unused_nx_valid), .nx_data (unused_nx_data), .in_ready_cp (in_ready_cp),
        .in_ready_nx (in_ready_nx), .out_valid_cp (unused_k_valid_cp));
    wire unused_nx = ^{unused_nx_valid, unused_nx_data, unused_k_valid_cp};
    generate
        if (RAM != 0) begin : g_ram
            cube4_ram_fifo #(.DATA_W (DATA_W), .DEPTH (DEPTH), .OUT_REG (OUT_REG)) u_q (
                .clk (clk), .rst (rst),
                .in_valid (k_valid), .in_ready (k_ready), .in_data (k_data),
                .out_valid (f_valid), .out_ready (f_ready), .out_data (f_data));
        end else begin : g_regs
            cube4_sync_fifo #(.DATA_W (DATA_W), .DEPTH (DEPTH)) u_q (
                .clk (clk), .rst (rst),
                .in_valid (k_valid), .in_ready (k_ready), .in_data (k_data),
                .out_valid (f_valid), .out_ready (f_ready), .out_data (f_data));
        end
    endgenerate
    // beside the consumer
    wire              unused_o_nx_valid, unused_o_ready_cp, unused_o_ready_nx;
    wire [DATA_W-1:0] unused_o_nx_data;
    cube4_skid_peek #(.DATA_W (DATA_W), .VALID_N (VALID_N)) u_out (
        .clk (clk), .rst (rst),
        .in_valid (f_valid), .in_ready (f_ready), .in_data (f_data),
        .out_valid (out_valid), .out_ready (out_ready), .out_data (out_data),
        .nx_valid (unused_o_nx_valid), .nx_data (unused_o_nx_data), .in_ready_cp (unused_o_ready_cp),
        .in_ready_nx (unused_o_ready_nx), .out_valid_cp (out_valid_cp));
    wire unused_o_nx = ^{unused_o_nx_valid, unused_o_nx_data, unused_o_ready_cp, unused_o_ready_nx};
endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_prim_ebr  (generic form; the ECP5 form is rtl/ecp5/cube4_prim_ebr.v)
// -----------------------------------------------------------------------------
// Purpose
//   One block RAM with the output registers of both ports: the technology
//   cell below the vendor layer's RAM forms (rtl/ecp5/cube4_sdp_ram.v,
//   rtl/ecp5/cube4_dual_read_ram.v slice their words over it). Port A
//   writes and, with READ_A = 1, also reads (a block RAM's true dual-port
//   use); port B reads. The design's generic RAMs (cube4_sdp_ram,
//   cube4_dual_read_ram) do not use it: this form is the behavioural twin
//   of the ECP5 cell, for lint and for reading what the cell does.
//
// Parameters
//   SHAPE_W the block's port width: 1, 2, 4, 9 or 18 (the DP16KD shapes
//           16384 x 1 .. 1024 x 18).  Default 18.
//   W       bits used of the port: 1..SHAPE_W.  Default 18.
//   AW      address bits used: 1 .. 14 - k for SHAPE_W 1, 2, 4, 9, 18 and
//           k = 0 .. 4 (14, 13, 12, 11, 10 bits).  Default 10.
//   READ_A  1: port A reads too; 0: it only writes (a_rd = 0).  0..1.
//           Default 0.
//
// Latency
//   A read is 2 cycles on either port: a read register (the block's latch,
//   loaded on an edge with the port's enable) and the output register
//   (port A: loaded with the enable too; port B: with its own enable b_oe,
//   which a caller that reads on every step ties to b_en), so both hold
//   while the enables are 0. A
//   write is seen by a read one edge after it. Port A in a cycle with a_we
//   does not read: both its registers keep their words (the latch by the
//   block's NORMAL write mode, the output register by its enable).
//   Port B reading the word written at the same edge returns the old word
//   (undefined on the device; the callers make no such read).
//
// Ports
//   a_en  in   port A's read enable (READ_A = 1; no read while a_we = 1)
//   a_we  in   write enable
//   a_addr, b_addr  in  [AW]
//   a_wd  in   [W] the word written
//   a_rd, b_rd  out  [W] the words read (any format)
//   b_en  in   port B's read enable (its read register, the block's latch)
//   b_oe  in   port B's output register's enable (ECP5: OCEB)
//
// Bit growth and rounding: none. No reset: the contents are data.
// =============================================================================
module cube4_prim_ebr
`include "cube4_prim_ebr_if.vh"

    reg [W-1:0] mem [0:(1 << AW)-1];
    reg [W-1:0] b_lat_q, b_out_q;
    always @(posedge clk) begin
        if (a_we) mem[a_addr] <= a_wd;
        if (b_en) b_lat_q <= mem[b_addr];
        if (b_oe) b_out_q <= b_lat_q;
    end
    assign b_rd = b_out_q;
    generate
        if (READ_A == 1) begin : g_read_a
            reg [W-1:0] a_lat_q, a_out_q;
            always @(posedge clk) begin
                if (a_en && !a_we) a_lat_q <= mem[a_addr];
                if (a_en && !a_we) a_out_q <= a_lat_q;
            end
            assign a_rd = a_out_q;
        end else begin : g_write_a
            wire unused_a_en = a_en;
            assign a_rd = '0;
        end
    endgenerate

endmodule
`default_nettype wire

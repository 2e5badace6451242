`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_dual_read_ram
// -----------------------------------------------------------------------------
// Purpose
//   A table read by two lanes: one write port and two read ports on one
//   clock, where read port 0 shares its block RAM port with the write (a
//   block RAM's true dual-port use). Two lanes reading one copy of a table
//   need half the block RAMs of one copy per lane (cube4_sha's tables).
//   Port 0 does not read in a cycle with wr_en: its registers keep their
//   words, as if rd_en were 0 for it. The caller writes only while no read matters (the
//   tables are loaded between frames).
//   This is the generic, behavioural form (simulation, and synthesis for any
//   technology without a form of its own); rtl/ecp5/cube4_dual_read_ram.v
//   is the ECP5 form with the same ports, parameters and timing.
//
// Parameters
//   DATA_W  word width.                     1..4096.  Default 8.
//   DEPTH   words.                          1..2^24.  Default 16.
//   OUT_REG 0: rd*_data is the read register; 1: the read word passes a
//           second register, loaded with the read register's word with
//           its port's read enable (rd_en; port 0: rd_en && !wr_en), a
//           block RAM's output register, as cube4_sdp_ram's.
//           0..1.  Default 1.
//   AW      address width (derived; not to be set).
//
// Latency
//   Read: 1 + OUT_REG cycles on both ports, a port's registers advancing
//   with its read enable (rd_en for port 1, rd_en && !wr_en for port 0;
//   rd*_data holds while it is 0). Write: visible to a read one cycle
//   later; port 1 reading the word written in the same cycle returns the
//   old word here (undefined on a device; no caller does it).
//
// Ports
//   rd_en               in   read enable of both ports
//   rd0_addr, rd1_addr  in   [AW] read addresses
//   rd0_data, rd1_data  out  [DATA_W] any format
//   wr_en, wr_addr      in   write enable, address [AW]
//   wr_data             in   [DATA_W] the word
//
// Bit growth and rounding: none. No reset: the contents are data.
// =============================================================================
module cube4_dual_read_ram
`include "cube4_dual_read_ram_if.vh"

    wire             rd0_en = rd_en && !wr_en;   // port 0 shares the write's port
    reg [DATA_W-1:0] mem [0:DEPTH-1];    // DEPTH words (reads at DEPTH and above: none in use)
    reg [DATA_W-1:0] rd0_q, rd1_q;
    always @(posedge clk) begin
        if (wr_en)  mem[wr_addr] <= wr_data;
        if (rd0_en) rd0_q <= mem[rd0_addr];
        if (rd_en)  rd1_q <= mem[rd1_addr];
    end
    generate
        if (OUT_REG == 1) begin : g_out_reg
            reg [DATA_W-1:0] out0_q, out1_q;
            always @(posedge clk) begin
                if (rd0_en) out0_q <= rd0_q;
                if (rd_en)  out1_q <= rd1_q;
            end
            assign rd0_data = out0_q;
            assign rd1_data = out1_q;
        end else begin : g_no_out_reg
            assign rd0_data = rd0_q;
            assign rd1_data = rd1_q;
        end
    endgenerate

endmodule
`default_nettype wire

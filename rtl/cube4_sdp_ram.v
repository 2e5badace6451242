`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_sdp_ram
// -----------------------------------------------------------------------------
// Purpose
//   Simple dual-port RAM: one write port, one registered read port, one clock.
//   It maps to block RAM (an FPGA's BRAM, an ASIC's SRAM macro) with the read
//   register inside the macro. Used where the caller computes both addresses
//   itself, e.g. cube4_com's base-plane buffers, whose write lands several
//   pipeline stages after the read of the same position.
//   This is the generic, behavioural form (simulation, and synthesis for any
//   technology without a form of its own). Technology forms with the same
//   ports, parameters and timing live in the vendor folders (rtl/ecp5/
//   cube4_sdp_ram.v: block-RAM shaping and register copies); the source list
//   (rtl/sources.f) chooses one.
//
// Parameters
//   DATA_W  word width.                     1..4096.  Default 8.
//   DEPTH   words.                          1..2^24.  Default 16.
//   IN_REG  0: rd_en, rd_addr, wr_en and wr_addr act this cycle; 1: the RAM
//           registers them itself (the caller gives them one cycle early),
//           and the access uses the registered values.  0..1.  Default 0.
//   WR_REG  0: the write acts this cycle; 1: wr_en, wr_addr and wr_data pass
//           a register in the RAM, and the write lands one cycle after its
//           inputs (a write port spread over many block RAMs gets a cycle of
//           routing of its own). Not with IN_REG = 1 (which registers the
//           write's enable and address; a caller that wants the data
//           registered too gives it one cycle late).  0..1.  Default 0.
//   OUT_REG 0: rd_data is the read register; 1: the read word passes a
//           second register, loaded with the read register's word when the
//           (registered, with IN_REG) read enable is 1: the output register
//           of a block RAM (ECP5 DP16KD REGMODE "OUTREG"), which takes the
//           block's clock-to-out off the path into the caller's logic.
//           2: as 1, but the output register loads when out_en is 1, not
//           with the read enable: a caller whose word moves on from the
//           read to its use at a step of its own (the block RAM's output
//           register enable, ECP5 OCEB). Not with IN_REG = 1.
//           0..2.  Default 0.
//   DIST    1: a small RAM whose read word feeds logic within the cycle:
//           distributed RAM (LUTs) where the technology has it, so the read
//           register is a flip-flop of the fabric (ECP5: 0.5 ns from clock
//           to data, not a DP16KD's 4.1 ns). Not with IN_REG or OUT_REG = 1.
//           Behaviour as DIST = 0; a read of the word written in the
//           same cycle returns the old word on every form (the distributed
//           RAM reads before the edge that writes).  0..1.  Default 0.
//   AW      address width (derived; not to be set).
//
// Latency
//   Read: 1 cycle (rd_data is mem[rd_addr] of the last cycle with rd_en = 1;
//   it holds while rd_en = 0). Write: visible to a read one cycle later. A
//   read of the word being written in the same cycle returns the old word
//   here; on a device that is not promised (ECP5 DP16KD, whose two ports
//   then collide), so no caller reads a word in the cycle it is written,
//   except with DIST = 1 (above).
//   IN_REG = 1: the same, one cycle after the inputs (one register stage).
//   WR_REG = 1: a write is visible to a read two cycles after its inputs (a
//   read in the cycle after them returns the old word).
//   OUT_REG = 1: one more: rd_data is the word of the read before the last
//   one with rd_en = 1 (both registers advance with the read enable, so a
//   caller that reads on every cycle sees a latency of 2, one that reads on
//   its pipeline's step sees the word two steps later). Total read latency
//   1 + IN_REG + (OUT_REG > 0). OUT_REG = 2: rd_data is the word the read
//   register held at the last edge with out_en = 1 (the read of the last
//   edge with rd_en before it), and holds while out_en is 0.
//
// Ports
//   rd_en, rd_addr  in   read enable, address  [AW]
//   out_en          in   the output register's load enable (OUT_REG = 2;
//                        ignored otherwise: tie it to 0)
//   rd_data         out  [DATA_W] any format
//   wr_en, wr_addr  in   write enable, address [AW] (IN_REG = 1: one cycle early)
//   wr_data         in   [DATA_W] the word, in the cycle of wr_en (IN_REG = 1:
//                        of the registered write enable)
//
// Bit growth and rounding: none. No reset: the contents are data.
// =============================================================================
module cube4_sdp_ram
`include "cube4_sdp_ram_if.vh"

    wire          re, we;               // the access's enables and addresses
    wire [AW-1:0] ra, wa;
    wire [DATA_W-1:0] wd;               // the word written
    generate
        if (IN_REG == 1) begin : g_in_reg
            reg          re_q, we_q;
            reg [AW-1:0] ra_q, wa_q;
            always @(posedge clk) begin
                re_q <= rd_en;
                we_q <= wr_en;
                ra_q <= rd_addr;
                wa_q <= wr_addr;
            end
            assign {re, we, ra, wa} = {re_q, we_q, ra_q, wa_q};
            assign wd = wr_data;
        end else if (WR_REG == 1) begin : g_wr_reg
            reg              we_q;
            reg [AW-1:0]     wa_q;
            reg [DATA_W-1:0] wd_q;
            always @(posedge clk) begin
                we_q <= wr_en;
                wa_q <= wr_addr;
                wd_q <= wr_data;
            end
            assign {re, we, ra, wa} = {rd_en, we_q, rd_addr, wa_q};
            assign wd = wd_q;
        end else begin : g_direct
            assign {re, we, ra, wa} = {rd_en, wr_en, rd_addr, wr_addr};
            assign wd = wr_data;
        end
    endgenerate

    reg [DATA_W-1:0] mem [0:DEPTH-1];    // DEPTH words (reads at DEPTH and above: none in use)
    reg [DATA_W-1:0] rd_q;
    always @(posedge clk) begin
        if (we) mem[wa] <= wd;
        if (re) rd_q <= mem[ra];
    end
    generate
        if (OUT_REG != 0) begin : g_out_reg
            wire oe = (OUT_REG == 2) ? out_en : re;
            reg [DATA_W-1:0] out_q;
            always @(posedge clk) begin
                if (oe) out_q <= rd_q;
            end
            assign rd_data = out_q;
        end else begin : g_no_out_reg
            assign rd_data = rd_q;
        end
        if (OUT_REG != 2) begin : g_no_out_en
            wire unused_out_en = out_en;   // (the output register, if any, loads with the read)
        end
    endgenerate

endmodule
`default_nettype wire

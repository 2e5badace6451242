`default_nettype none
// =============================================================================
// cube4_sdp_ram
// -----------------------------------------------------------------------------
// Purpose
//   Simple dual-port RAM: one write port, one registered read port, one clock.
//   It maps to block RAM (an ECP5 DP16KD, an FPGA's BRAM, an ASIC's SRAM
//   macro) with the read register inside the macro. Used where the caller
//   computes both addresses itself, e.g. cube4_com's base-plane buffer, whose
//   write lands several pipeline stages after the read of the same position.
//   For synthesis (`ifdef SYNTHESIS`, which Yosys defines), a RAM deeper than
//   2048 words (more than one ECP5 block RAM deep in its 2048 x 9 shape)
//   stores its word as slices of 4, 2 or 1 bits (4096, 8192, 16384+ words),
//   one memory each: each slice maps to block RAMs in their 4K x 4, 8K x 2 or
//   16K x 1 shape, so that up to 16384 words the read data needs no
//   multiplexer between the block RAMs and the next register (about as many
//   block RAMs as the 2048 x 9 shape plus a multiplexer). Simulation keeps one
//   word-wide memory: the same contents and timing, and Verilator evaluates
//   one wide array far faster than hundreds of narrow ones (256 two-bit
//   slices at MAX_DIM = 256, P = 8 halved the simulated cycles/s).
//   tb/cube4_top test_synthesis_ram_form_p1 simulates the sliced form too.
//
// Parameters
//   DATA_W  word width.                     1..4096.  Default 8.
//   DEPTH   words.                          1..2^24.  Default 16.
//   AW      address width (derived; do not set).
//
// Latency
//   Read: 1 cycle (rd_data is mem[rd_addr] of the last cycle with rd_en = 1;
//   it holds while rd_en = 0). Write: visible to a read one cycle later. A
//   read of the word being written in the same cycle returns the old word.
//
// Ports
//   rd_en, rd_addr  in   read this cycle, address  [AW]
//   rd_data         out  [DATA_W] any format
//   wr_en, wr_addr, wr_data  in   write port
//
// Bit growth and rounding: none. No reset: the contents are data.
// =============================================================================
module cube4_sdp_ram #(
    parameter integer DATA_W = 8,
    parameter integer DEPTH  = 16,
    parameter integer AW     = (DEPTH > 1) ? $clog2(DEPTH) : 1
) (
    input  wire              clk,
    input  wire              rd_en,
    input  wire [AW-1:0]     rd_addr,
    output wire [DATA_W-1:0] rd_data,
    input  wire              wr_en,
    input  wire [AW-1:0]     wr_addr,
    input  wire [DATA_W-1:0] wr_data
);
    generate
        if (DATA_W < 1 || DATA_W > 4096) begin : g_bad_data_w
            $error("cube4_sdp_ram: DATA_W = %0d is out of range 1..4096", DATA_W);
        end
        if (DEPTH < 1 || DEPTH > (1 << 24)) begin : g_bad_depth
            $error("cube4_sdp_ram: DEPTH = %0d is out of range 1..2^24", DEPTH);
        end
    endgenerate

`ifdef SYNTHESIS
    // slice width: 4, 2, 1 bits from 4096, 8192, 16384 words on; else the word
    localparam integer SL_W = (AW >= 14) ? 1 : ((AW == 13) ? 2 : ((AW == 12) ? 4 : DATA_W));
`else
    localparam integer SL_W = DATA_W;   // simulation: one word-wide memory
`endif
    localparam integer N_SL = (DATA_W + SL_W - 1) / SL_W;

    genvar sl;
    generate
        for (sl = 0; sl < N_SL; sl = sl + 1) begin : g_slice
            localparam integer LO = sl * SL_W;
            localparam integer W  = (DATA_W - LO < SL_W) ? DATA_W - LO : SL_W;
            reg [W-1:0] mem [0:(1 << AW)-1];
            reg [W-1:0] rd_q;
            always @(posedge clk) begin
                if (wr_en) mem[wr_addr] <= wr_data[LO +: W];
                if (rd_en) rd_q <= mem[rd_addr];
            end
            assign rd_data[LO +: W] = rd_q;
        end
    endgenerate

endmodule
`default_nettype wire

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
//   With ADDR_REG = 1 the RAM registers its read and write addresses itself
//   (the caller gives them one cycle early, with a load enable). For
//   synthesis every two slices get their own copies of these address
//   registers (`keep`, so that Yosys does not merge them; RAMs up to 2048
//   words deep are then sliced into 18-bit words, two 2048 x 9 block RAMs),
//   so no single flip-flop drives the address of every block RAM: a RAM
//   spread over dozens of block RAMs across the die otherwise spends most of
//   a cycle routing one address net. For the same reason the enables may
//   come as EN_COPIES identical copies (flip-flop copies made by the caller);
//   for synthesis each slice and address copy uses one of them, in
//   contiguous groups; simulation uses copy 0.
//
// Parameters
//   DATA_W  word width.                     1..4096.  Default 8.
//   DEPTH   words.                          1..2^24.  Default 16.
//   ADDR_REG  0: rd_addr / wr_addr address this cycle's access; 1: they are
//           loaded into the RAM's address registers at addr_ld, and the
//           access uses the registered addresses.  0..1.  Default 0.
//   EN_COPIES  copies of rd_en, wr_en and addr_ld (all bits equal).
//           1..64.  Default 1.
//   AW      address width (derived; do not set).
//
// Latency
//   Read: 1 cycle (rd_data is mem[rd_addr] of the last cycle with rd_en = 1;
//   it holds while rd_en = 0). Write: visible to a read one cycle later. A
//   read of the word being written in the same cycle returns the old word.
//   ADDR_REG = 1: the same, with rd_addr / wr_addr replaced by the values
//   they had at the last cycle with addr_ld = 1 (one register stage).
//
// Ports
//   rd_en, rd_addr  in   read this cycle [EN_COPIES], address  [AW]
//   rd_data         out  [DATA_W] any format
//   wr_en, wr_addr, wr_data  in   write port (wr_en [EN_COPIES])
//   addr_ld         in   [EN_COPIES] ADDR_REG = 1: load rd_addr and wr_addr
//                        (else unused)
//
// Bit growth and rounding: none. No reset: the contents are data.
// =============================================================================
module cube4_sdp_ram #(
    parameter integer DATA_W = 8,
    parameter integer DEPTH  = 16,
    parameter integer ADDR_REG = 0,
    parameter integer EN_COPIES = 1,
    parameter integer AW     = (DEPTH > 1) ? $clog2(DEPTH) : 1
) (
    input  wire                 clk,
    input  wire [EN_COPIES-1:0] addr_ld,
    input  wire [EN_COPIES-1:0] rd_en,
    input  wire [AW-1:0]        rd_addr,
    output wire [DATA_W-1:0]    rd_data,
    input  wire [EN_COPIES-1:0] wr_en,
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
        if (ADDR_REG < 0 || ADDR_REG > 1) begin : g_bad_addr_reg
            $error("cube4_sdp_ram: ADDR_REG = %0d is out of range 0..1", ADDR_REG);
        end
        if (EN_COPIES < 1 || EN_COPIES > 64) begin : g_bad_en_copies
            $error("cube4_sdp_ram: EN_COPIES = %0d is out of range 1..64", EN_COPIES);
        end
    endgenerate

`ifdef SYNTHESIS
    // slice width: 4, 2, 1 bits from 4096, 8192, 16384 words on; else the
    // word (18 bits with ADDR_REG, so that the address copies have slices)
    localparam integer SL_SHALLOW = (ADDR_REG == 1 && DATA_W > 18) ? 18 : DATA_W;
    localparam integer SL_W = (AW >= 14) ? 1 : ((AW == 13) ? 2 : ((AW == 12) ? 4 : SL_SHALLOW));
    localparam integer SPC  = 2;        // slices per address copy
`else
    localparam integer SL_W = DATA_W;   // simulation: one word-wide memory
    localparam integer SPC  = 1;
`endif
    localparam integer N_SL = (DATA_W + SL_W - 1) / SL_W;

    localparam integer N_CP = (N_SL + SPC - 1) / SPC;   // address copies (ADDR_REG = 1)

    wire [N_CP*AW-1:0] ra_cp, wa_cp;    // the registered addresses, one per copy
    // ADDR_REG = 0 has no address registers; simulation uses enable copy 0
    wire unused_en = ^{addr_ld, rd_en, wr_en};
    genvar sl, cp;
    generate
        for (cp = 0; cp < N_CP; cp = cp + 1) begin : g_acopy
            if (ADDR_REG == 1) begin : g_reg
                reg [AW-1:0] ra_q, wa_q;
                (* keep *)              // one copy per SPC slices: never merged
                always @(posedge clk) begin
                    if (addr_ld[(cp * EN_COPIES) / N_CP]) begin
                        ra_q <= rd_addr;
                        wa_q <= wr_addr;
                    end
                end
                assign ra_cp[cp*AW +: AW] = ra_q;
                assign wa_cp[cp*AW +: AW] = wa_q;
            end else begin : g_direct
                assign ra_cp[cp*AW +: AW] = rd_addr;
                assign wa_cp[cp*AW +: AW] = wr_addr;
            end
        end
        for (sl = 0; sl < N_SL; sl = sl + 1) begin : g_slice
            localparam integer LO = sl * SL_W;
            localparam integer W  = (DATA_W - LO < SL_W) ? DATA_W - LO : SL_W;
            localparam integer E  = (sl * EN_COPIES) / N_SL;   // this slice's enable copy
            wire [AW-1:0] ra = ra_cp[(sl / SPC) * AW +: AW];
            wire [AW-1:0] wa = wa_cp[(sl / SPC) * AW +: AW];
            reg [W-1:0] mem [0:(1 << AW)-1];
            reg [W-1:0] rd_q;
            always @(posedge clk) begin
                if (wr_en[E]) mem[wa] <= wr_data[LO +: W];
                if (rd_en[E]) rd_q <= mem[ra];
            end
            assign rd_data[LO +: W] = rd_q;
        end
    endgenerate

endmodule
`default_nettype wire

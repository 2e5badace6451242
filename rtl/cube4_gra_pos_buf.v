`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_gra_pos_buf
// -----------------------------------------------------------------------------
// Purpose
//   One of GRA's position buffers (cube4_gra_pos): a RAM read when a step's
//   position loads (ld: its registered read) and written when the step
//   steps (we), whose word for a read takes the writes made since the read
//   (bypass: the RAM returns the old word for a read in the cycle of the
//   write). With OUT_STAGE = 1 the word read passes one more register, the
//   RAM's output register (cube4_sdp_ram OUT_REG = 2: a block RAM's own
//   where the RAM is one, a flip-flop of the fabric for a shallow RAM),
//   loaded as the position moves on from the read to the step (mv); the
//   write at mv's own edge, if it hits the read (a second bypass), is kept in
//   a register beside it and chosen after it: a block RAM's clock-to-data
//   ends at its output register (0.7 ns on the ECP5), not in the caller's
//   arithmetic. ld, mv and we reach this buffer's words only (cube4_gra_pos
//   gives each buffer its own copies).
//
// Parameters
//   DATA_W     word bits.                              1..4096. Default 8.
//   AW         address bits (DEPTH = 2^AW words).      1..24.   Default 4.
//   OUT_STAGE  0: the word read is on rd_word from the edge after ld; 1: from
//              the edge after mv.                      0..1.    Default 0.
//
// Latency
//   OUT_STAGE = 0: the word for an address read at an edge with ld is on
//   rd_word after it (with the write of that edge, if it hits), until the
//   next ld. OUT_STAGE = 1: after the next edge with mv (with the writes of
//   the read's edge and of mv's edge), until the next mv; the caller writes
//   nothing between a read and its mv but at mv's edge (cube4_gra_pos checks
//   it in simulation). A write lands at its edge.
//
// Ports
//   ld, rd_addr [AW]             the read (a step's position loads)
//   mv                           (OUT_STAGE = 1) the word read loads
//   we, wr_addr [AW], wr_data    the write (the step steps)
//   rd_word   out [DATA_W]       the word read, with the writes since
//
// Bit growth and rounding: none (storage only). No reset: the words are data.
// =============================================================================
module cube4_gra_pos_buf #(
    parameter integer DATA_W    = 8,
    parameter integer AW        = 4,
    parameter integer OUT_STAGE = 0
) (
    input  wire              clk,
    input  wire              ld,
    input  wire [AW-1:0]     rd_addr,
    input  wire              mv,
    input  wire              we,
    input  wire [AW-1:0]     wr_addr,
    input  wire [DATA_W-1:0] wr_data,
    output wire [DATA_W-1:0] rd_word
);
    // OUT_STAGE = 1: the RAM's output register (OUT_REG = 2, loaded at mv) is the stage
    localparam integer ORG = (OUT_STAGE != 0) ? 2 : 0;
    wire [DATA_W-1:0] rd;
    cube4_sdp_ram #(.DATA_W (DATA_W), .DEPTH (1 << AW), .OUT_REG (ORG)) u_ram (
        .clk (clk), .rd_en (ld), .out_en ((OUT_STAGE != 0) && mv), .rd_addr (rd_addr), .rd_data (rd),
        .wr_en (we), .wr_addr (wr_addr), .wr_data (wr_data));
    // the write in the read's own cycle (loaded at ld only: with OUT_STAGE = 1
    // a write after the read comes at mv's edge, where the stage below takes it)
    reg              by;
    reg [DATA_W-1:0] bd;
    reg [AW-1:0]     ra1;                       // the read's address, for a write at its mv
    always @(posedge clk) begin
        if (ld) begin
            ra1 <= rd_addr;
            by  <= we && (wr_addr == rd_addr);
            bd  <= wr_data;
        end
    end
    generate
        if (OUT_STAGE == 0) begin : g_direct
            assign rd_word = by ? bd : rd;      // the word with every write since
            wire unused_mv = ^{mv, ra1};        // (read for the step itself)
        end else begin : g_stage
            // the RAM's word passes its output register at mv; the bypass's choice
            // and word (with a write at mv's own edge) beside it, the choice
            // applied after the registers
            wire             hit = we && (wr_addr == ra1);
            reg              s;
            reg [DATA_W-1:0] sd;
            always @(posedge clk) begin
                if (mv) begin
                    s  <= hit || by;
                    sd <= hit ? wr_data : bd;
                end
            end
            assign rd_word = s ? sd : rd;
        end
    endgenerate

    // ---- parameter checks (stop elaboration on illegal values) ----
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_gra_pos_buf", "DATA_W", DATA_W, 1, 4096)
        `CUBE4_RANGE(g_bad_aw, "cube4_gra_pos_buf", "AW", AW, 1, 24)
        `CUBE4_RANGE(g_bad_out_stage, "cube4_gra_pos_buf", "OUT_STAGE", OUT_STAGE, 0, 1)
    endgenerate

endmodule
`default_nettype wire

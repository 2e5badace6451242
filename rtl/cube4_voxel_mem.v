`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_voxel_mem
// -----------------------------------------------------------------------------
// Purpose
//   The Cube-4 voxel memory: P banks, one per pipeline, each DEPTH words of
//   WORD_W bits (a voxel, or a voxel and its gradient: CUBE4_WORD_LAYOUT),
//   holding the volume skewed and partitioned as golden/cube4/memory.py writes it (bank (x+y+z) mod P, address
//   floor(x/P) + ceil(nx/P) * (y + ny*z)). One read request beat carries one
//   address per bank and a read enable per bank; the response beat carries the
//   P words (0 for banks not read) and the request's tag unchanged.
//   The load port writes one word into every bank at the same address per
//   beat (a column of the packer's bank images); it is independent of the
//   read port (simple dual port RAM), and is meant for use between frames:
//   a read of a word that is loaded in the same cycle returns an undefined
//   word (the memories are marked no_rw_check for synthesis).
//
// Parameters
//   P        banks.                          1..64.     Default 8.
//   WORD_W   word width.                     1..73.     Default 8.
//   DEPTH    words per bank.                 2..2^24.   Default 65536.
//   ADDR_W   address width, >= clog2(DEPTH). 1..30.     Default 16.
//   TAG_W    request tag width.              1..4096.   Default 8.
//
// Latency
//   2 cycles from an accepted request to rsp_valid: each bank is a
//   cube4_sdp_ram with its output register (OUT_REG: on an FPGA the block
//   RAM's own, so that no block RAM's clock-to-out lies on the path into the
//   reader). The two stages stall together: while rsp_valid is high and
//   rsp_ready low, nothing moves; req_ready = !rsp_valid || rsp_ready. Full
//   rate with rsp_ready high. ld_ready is always 1 (a write per cycle).
//
// Ports
//   ld_valid/ld_ready        load handshake
//   ld_addr   in  [ADDR_W]   word address (the same in every bank)
//   ld_data   in  [P*WORD_W] bank q's word at q*WORD_W
//   req_valid/req_ready      read request handshake
//   req_addr  in  [P*ADDR_W] bank q's address at q*ADDR_W
//   req_rden  in  [P]        read bank q
//   req_tag   in  [TAG_W]    carried to rsp_tag
//   rsp_valid/rsp_ready      read response handshake
//   rsp_data  out [P*WORD_W] words read (0 where req_rden was 0)
//   rsp_tag   out [TAG_W]
//
// Bit growth and rounding: none (storage only). Addresses >= DEPTH with the
// read enable set are a host error (the packer never makes them); they read
// an undefined word (address bits above clog2(DEPTH) are ignored).
// =============================================================================
module cube4_voxel_mem #(
    parameter integer P      = 8,     parameter integer WORD_W  = 8,
    parameter integer DEPTH  = 65536, parameter integer ADDR_W  = 16,
    parameter integer TAG_W  = 8
) (
    input  wire clk, input wire rst,
    // load port, read requests, read responses
    `CUBE4_VOXEL_MEM_PORTS
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_voxel_mem", "P", P, 1, 64)
        `CUBE4_RANGE(g_bad_word_w, "cube4_voxel_mem", "WORD_W", WORD_W, 1, 73)
        if (DEPTH < 2 || DEPTH > (1 << 24) || ADDR_W < 1 || ADDR_W > 30 || DEPTH > (1 << ADDR_W)) begin : g_bad_depth
            $error("cube4_voxel_mem: DEPTH = %0d does not fit ADDR_W = %0d", DEPTH, ADDR_W);
        end
    endgenerate

    localparam integer AW = $clog2(DEPTH);     // the RAM's address bits (<= ADDR_W)

    // two stages, s1 (the RAMs' read registers) and s2 (their output
    // registers, rsp_*), advancing together while s2 is empty or read
    reg              v1_q, v2_q;
    reg [TAG_W-1:0]  tag1_q, tag2_q;
    reg [P-1:0]      rden1_q, rden2_q;
    wire             adv  = !v2_q || rsp_ready;
    wire             take = req_valid && adv;

    assign req_ready = adv;
    assign ld_ready  = 1'b1;

    always @(posedge clk) begin
        if (rst) begin
            v1_q <= 1'b0;
            v2_q <= 1'b0;
        end else if (adv) begin
            v1_q <= take;
            v2_q <= v1_q;
        end
    end
    always @(posedge clk) begin
        if (adv) begin
            tag1_q  <= req_tag;
            rden1_q <= req_rden;
            tag2_q  <= tag1_q;
            rden2_q <= rden1_q;
        end
    end

    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_bank
            // Loads and reads never meet in one cycle in use (loads come
            // between frames): a read of a word loaded at the same edge is
            // undefined. Both registers advance with adv (a read on every
            // advance; rden marks the words that count).
            wire [WORD_W-1:0] rd_word;
            cube4_sdp_ram #(.DATA_W(WORD_W), .DEPTH(DEPTH), .OUT_REG(1)) u_ram (
                .clk(clk), .rd_en(adv), .out_en(1'b0), .rd_addr(req_addr[q*ADDR_W +: AW]), .rd_data(rd_word),
                .wr_en(ld_valid), .wr_addr(ld_addr[AW-1:0]), .wr_data(ld_data[q*WORD_W +: WORD_W]));
            assign rsp_data[q*WORD_W +: WORD_W] = rden2_q[q] ? rd_word : {WORD_W{1'b0}};
            if (AW < ADDR_W) begin : g_unused_addr
                wire unused_hi = ^req_addr[q*ADDR_W + AW +: ADDR_W - AW];
            end
        end
        if (AW < ADDR_W) begin : g_unused_ld
            wire unused_ld_hi = ^ld_addr[ADDR_W-1:AW];
        end
    endgenerate

    assign rsp_valid = v2_q;
    assign rsp_tag   = tag2_q;

endmodule
`default_nettype wire

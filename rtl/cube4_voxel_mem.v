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
//   DEPTH    words per bank.                 2..2^30.   Default 65536.
//   ADDR_W   address width, >= clog2(DEPTH). 1..30.     Default 16.
//   TAG_W    request tag width.              1..4096.   Default 8.
//
// Latency
//   1 cycle from an accepted request to rsp_valid (synchronous read). The
//   response register holds while rsp_ready is low; req_ready = !rsp_valid ||
//   rsp_ready. ld_ready is always 1 (a write per cycle).
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
// an undefined word.
// =============================================================================
module cube4_voxel_mem #(
    parameter integer P      = 8,     parameter integer WORD_W  = 8,
    parameter integer DEPTH  = 65536, parameter integer ADDR_W  = 16,
    parameter integer TAG_W  = 8
) (
    input  wire clk, input wire rst,
    // load port: one word per bank at the same address
    input  wire ld_valid, output wire ld_ready,
    input  wire [ADDR_W-1:0] ld_addr, input wire [P*WORD_W-1:0] ld_data,
    // read requests: an address and a read enable per bank, a tag
    input  wire req_valid, output wire req_ready, input wire [TAG_W-1:0] req_tag,
    input  wire [P*ADDR_W-1:0] req_addr,
    input  wire [P-1:0] req_rden,
    // read responses: the words, the request's tag
    output wire rsp_valid, input wire rsp_ready, output wire [TAG_W-1:0] rsp_tag,
    output wire [P*WORD_W-1:0] rsp_data
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_voxel_mem", "P", P, 1, 64)
        `CUBE4_RANGE(g_bad_word_w, "cube4_voxel_mem", "WORD_W", WORD_W, 1, 73)
        if (DEPTH < 2 || ADDR_W < 1 || ADDR_W > 30 || DEPTH > (1 << ADDR_W)) begin : g_bad_depth
            $error("cube4_voxel_mem: DEPTH = %0d does not fit ADDR_W = %0d", DEPTH, ADDR_W);
        end
    endgenerate

    reg              v_q;
    reg [TAG_W-1:0]  tag_q;
    reg [P-1:0]      rden_q;
    wire             take = req_valid && req_ready;

    assign req_ready = !v_q || rsp_ready;
    assign ld_ready  = 1'b1;

    always @(posedge clk) begin
        if (rst) v_q <= 1'b0;
        else if (req_ready) v_q <= req_valid;
    end
    always @(posedge clk) begin
        if (take) begin
            tag_q  <= req_tag;
            rden_q <= req_rden;
        end
    end

    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_bank
            // Loads and reads never meet in one cycle in use (loads come between
            // frames), so synthesis needs no read-during-write logic: without
            // no_rw_check Yosys adds an address comparator and a bypass after
            // the block RAM (the P = 8 critical path of an FPGA build).
            (* no_rw_check *)
            reg [WORD_W-1:0] mem [0:DEPTH-1];
            reg [WORD_W-1:0] rd_q;
            always @(posedge clk) begin
                if (ld_valid) mem[ld_addr] <= ld_data[q*WORD_W +: WORD_W];
            end
            always @(posedge clk) begin
                if (take && req_rden[q]) rd_q <= mem[req_addr[q*ADDR_W +: ADDR_W]];
            end
            assign rsp_data[q*WORD_W +: WORD_W] = rden_q[q] ? rd_q : {WORD_W{1'b0}};
        end
    endgenerate

    assign rsp_valid = v_q;
    assign rsp_tag   = tag_q;

endmodule
`default_nettype wire

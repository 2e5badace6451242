`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_sync_fifo
// -----------------------------------------------------------------------------
// Purpose
//   A first-in first-out queue of DEPTH items on one clock, as a stream
//   (in: valid/ready, out: valid/ready). out_valid and the read pointer are
//   registers; out_data is the memory's asynchronous read at the read pointer
//   (distributed RAM on an FPGA), which the consumer registers.
//
// Parameters
//   DATA_W   width of an item.              1..4096.   Default 8.
//   DEPTH    entries; a power of two.       2..1024.   Default 16.
//
// Latency
//   An item written at a clock edge is on out_valid/out_data right after that
//   edge when the queue was empty. Full rate: one in and one out per cycle;
//   in_ready = count < DEPTH (a register), so a full queue takes an item in
//   the cycle after one leaves.
//
// Ports
//   clk, rst                    clock, synchronous active-high reset (empties it)
//   in_valid/in_ready/in_data   items in (any format, DATA_W bits)
//   out_valid/out_ready/out_data items out, in order
//
// Bit growth and rounding: none (storage only).
// =============================================================================
module cube4_sync_fifo #(
    parameter integer DATA_W = 8,
    parameter integer DEPTH  = 16,
    localparam integer PTR_W = (DEPTH > 1) ? $clog2(DEPTH) : 1,
    localparam integer CNT_W = PTR_W + 1
) (
    `CUBE4_STREAM_PORTS(DATA_W)
);
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_sync_fifo", "DATA_W", DATA_W, 1, 4096)
        if (DEPTH < 2 || DEPTH > 1024 || (DEPTH & (DEPTH - 1)) != 0) begin : g_bad_depth
            $error("cube4_sync_fifo: DEPTH = %0d must be a power of two in 2..1024", DEPTH);
        end
    endgenerate

    reg [DATA_W-1:0] mem [0:DEPTH-1];
    reg [PTR_W-1:0]  wr_q, rd_q;
    reg [CNT_W-1:0]  cnt_q;

    wire push = in_valid && in_ready;
    wire pop  = out_valid && out_ready;

    always @(posedge clk) begin
        if (push) mem[wr_q] <= in_data;
    end

    always @(posedge clk) begin
        if (rst) begin
            wr_q  <= {PTR_W{1'b0}};
            rd_q  <= {PTR_W{1'b0}};
            cnt_q <= {CNT_W{1'b0}};
        end else begin
            if (push) wr_q <= wr_q + 1'b1;
            if (pop)  rd_q <= rd_q + 1'b1;
            cnt_q <= cnt_q + {{PTR_W{1'b0}}, push} - {{PTR_W{1'b0}}, pop};
        end
    end

    assign in_ready  = (cnt_q != CNT_W'(DEPTH));
    assign out_valid = (cnt_q != {CNT_W{1'b0}});
    assign out_data  = mem[rd_q];

endmodule
`default_nettype wire

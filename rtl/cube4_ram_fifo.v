`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_ram_fifo
// -----------------------------------------------------------------------------
// Purpose
//   A deep first-in first-out queue in block RAM (cube4_sdp_ram), as a stream
//   (in: valid/ready, out: valid/ready), for queues too deep for distributed
//   RAM (cube4_sync_fifo): the beat schedule's lane bits, which wait about two
//   slices between the decisions and the walk (cube4_cfb_skip). The RAM's read
//   takes L = 1 + OUT_REG cycles, so items leave through a register queue of
//   L + 2 entries that the RAM keeps filled: a read is issued while the
//   register queue and the reads in flight hold fewer than L + 2 items,
//   counted before this cycle's pop, so out_ready reaches only the register
//   queue (not the RAM's read enable, its pointer or the count behind
//   in_ready); L + 2 entries keep the full rate with a read decided L cycles
//   before the pop it refills.
//
// Parameters
//   DATA_W   width of an item.              1..4096.     Default 8.
//   DEPTH    entries in the RAM; a power of two.  4..2^20.  Default 1024.
//            The queue holds DEPTH + L + 2 items (the RAM and the register queue).
//   OUT_REG  1: the RAM's word passes its output register (cube4_sdp_ram
//            OUT_REG: the block RAM's clock-to-data ends at that register, not
//            in the queue's multiplexers), L = 2; its read enable is also on
//            in the cycle after a read, which loads that register (a read
//            there of no item is not used).  0..1.  Default 0.
//
// Latency
//   An item written at an edge is read from the RAM at the next edge at the
//   earliest and is on out_valid / out_data L edges after that (L + 1 edges
//   after its write, when the queue was empty).
//   Full rate: one item in and one out per cycle. in_ready, out_valid and
//   out_data are registers (out_data a register of the register queue).
//
// Ports
//   clk, rst                     clock, synchronous active-high reset (empties it)
//   in_valid/in_ready/in_data    items in (any format, DATA_W bits)
//   out_valid/out_ready/out_data items out, in order
//
// Bit growth and rounding: none (storage only).
// =============================================================================
module cube4_ram_fifo #(
    parameter integer DATA_W = 8,
    parameter integer DEPTH  = 1024,
    parameter integer OUT_REG = 0,
    localparam integer PTR_W = (DEPTH > 1) ? $clog2(DEPTH) : 1,
    localparam integer CNT_W = PTR_W + 1
) (
    `CUBE4_STREAM_PORTS(DATA_W)
);
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_ram_fifo", "DATA_W", DATA_W, 1, 4096)
        if (DEPTH < 4 || DEPTH > (1 << 20) || (DEPTH & (DEPTH - 1)) != 0) begin : g_bad_depth
            $error("cube4_ram_fifo: DEPTH = %0d must be a power of two in 4..2^20", DEPTH);
        end
        `CUBE4_RANGE(g_bad_out_reg, "cube4_ram_fifo", "OUT_REG", OUT_REG, 0, 1)
    endgenerate
    localparam integer L  = 1 + OUT_REG;   // the RAM's read latency
    localparam integer QN = L + 2;         // register queue entries

    // ==== the RAM: items written and not yet read (count), its pointers ====
    reg  [PTR_W-1:0] wr_q, rd_q;
    reg  [CNT_W-1:0] cnt_q;                // items in the RAM, written and not read
    reg              full_q;               // cnt_q = DEPTH, counting this cycle's read
    reg              nz_q;                 // cnt_q != 0
    wire             push = in_valid && in_ready;
    assign in_ready = !full_q;
    // ==== the register queue: q[0] (the head) .. q[QN-1]; the reads in flight ====
    reg  [DATA_W-1:0] q [0:QN-1];
    reg  [2:0]        nq;                  // items in the register queue
    reg  [L-1:0]      fly;                 // fly[k]: a read was issued k + 1 edges ago
    wire              pop  = out_valid && out_ready;
    wire [2:0]        in_fly = (L == 2) ? 3'(fly[0]) + 3'(fly[L-1]) : 3'(fly[0]);
    wire              rd   = nz_q && (nq + in_fly < 3'(QN));   // before this cycle's pop
    wire [DATA_W-1:0] rd_data;
    cube4_sdp_ram #(.DATA_W(DATA_W), .DEPTH(DEPTH), .OUT_REG(OUT_REG)) u_ram (
        .clk(clk), .rd_en((OUT_REG != 0) ? (rd || fly[0]) : rd), .out_en(1'b0), .rd_addr(rd_q), .rd_data(rd_data),
        .wr_en(push), .wr_addr(wr_q), .wr_data(in_data));
    wire [CNT_W-1:0] cnt_n = cnt_q + CNT_W'(push) - CNT_W'(rd);
    // the flags of cnt_n from compares of cnt_q, the read choosing between them last (so
    // neither the adder nor a compare after it lies between rd and the flags that rd
    // reads in the next cycle): a read needs cnt_q != 0, a push !full_q
    wire nz_n   = rd ? !((cnt_q == CNT_W'(1)) && !push) : !((cnt_q == '0) && !push);
    wire full_n = !rd && (full_q || ((cnt_q == CNT_W'(DEPTH - 1)) && push));
    always @(posedge clk) begin
        if (rst) begin
            wr_q   <= '0;
            rd_q   <= '0;
            cnt_q  <= '0;
            full_q <= 1'b0;
            nz_q   <= 1'b0;
            fly    <= '0;
        end else begin
            if (push) wr_q <= wr_q + 1'b1;
            if (rd)   rd_q <= rd_q + 1'b1;
            cnt_q  <= cnt_n;
            full_q <= full_n;
            nz_q   <= nz_n;
            fly    <= (L == 2) ? L'({fly[0], rd}) : L'(rd);
        end
    end
    // the word of the read issued L edges ago joins the queue behind what stays in it
    wire [2:0] keep = nq - 3'(pop);
    integer k;
    always @(posedge clk) begin
        if (rst) begin
            nq <= '0;
        end else begin
            nq <= keep + 3'(fly[L-1]);
            if (pop) begin
                for (k = 0; k < QN - 1; k = k + 1) q[k] <= q[k+1];
            end
            if (fly[L-1]) q[keep[1:0]] <= rd_data;          // (keep < QN <= 4)
        end
    end
    assign out_valid = (nq != '0);
    assign out_data  = q[0];
`ifndef SYNTHESIS
    always @(posedge clk) begin
        if (!rst && (nz_q != (cnt_q != '0) || full_q != (cnt_q == CNT_W'(DEPTH))))
            $fatal(1, "cube4_ram_fifo: the count's flags (nz %b, full %b) disagree with the count %0d", nz_q, full_q, cnt_q);
    end
`endif
endmodule
`default_nettype wire

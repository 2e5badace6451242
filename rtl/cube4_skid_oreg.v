`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_skid_oreg
// -----------------------------------------------------------------------------
// Purpose
//   Two-entry skid buffer whose out_data is a register: the head (head_q)
//   and a spare entry behind it (spare_q). Where cube4_skid_peek reads its
//   head through a 2:1 multiplexer at a read pointer (a register whose
//   placement its own state decides), here the consumer's logic starts at
//   the head's flip-flops, which load only as it takes, so the placer puts
//   them beside it, however far the producer lies: the route from the
//   producer ends in front of a register (cube4_top: the beat's header into
//   COM, whose look-ahead compares the entering header's slot; from a skid
//   across the die into those compares was a beat build's longest path).
//   Same stream behaviour as cube4_skid: in_ready is a register (!full),
//   two items held at most, latency one edge, full rate. Occupancy follows
//   in_valid and out_ready alone, so two buffers driven alike (this and a
//   cube4_skid beside it for a wider payload) hold the same count in every
//   cycle.
//   The cost is out_ready's fan-out: it reaches the clock enable of every
//   head bit (DATA_W loads), so it suits a narrow payload beside its consumer;
//   the spare loads in_data in every cycle it is free (its enable a register).
//
// Parameters
//   DATA_W        width of the payload.  Range 1..256.  Default 8.
//
// Latency
//   1 cycle from an accepted input to out_valid. Order is kept; nothing is
//   lost or duplicated under any pattern of out_ready.
//
// Ports
//   clk, rst                     clock, synchronous active-high reset (empties it)
//   in_valid/in_ready/in_data    input stream (in_data: any format, DATA_W bits);
//                                in_ready is a register
//   out_valid/out_ready/out_data output stream (same format); out_valid and
//                                out_data are registers
//
// Bit growth and rounding: none (storage only).
// =============================================================================
module cube4_skid_oreg #(
    parameter integer DATA_W = 8
) (
    `CUBE4_STREAM_PORTS(DATA_W)
);
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_skid_oreg", "DATA_W", DATA_W, 1, 256)
    endgenerate

    reg              valid_q;        // the head holds an item
    reg              full_q;         // the spare holds one too
    reg              ready_q;        // !full_q, the register in_ready is
    reg [DATA_W-1:0] head_q, spare_q;

    wire push  = in_valid && ready_q;
    // the head loads when it is empty or taken: the spare's item if it holds one,
    // else the input's (valid only with push; a head loaded with no item is not read)
    wire h_ld  = !valid_q || out_ready;
    wire valid_d = h_ld ? (full_q || push) : 1'b1;
    wire full_d  = h_ld ? 1'b0 : (full_q || push);
    always @(posedge clk) begin
        if (rst) begin
            valid_q <= 1'b0;
            full_q  <= 1'b0;
            ready_q <= 1'b1;
        end else begin
            valid_q <= valid_d;
            full_q  <= full_d;
            ready_q <= !full_d;
        end
    end
    always @(posedge clk) begin
        if (h_ld)    head_q  <= full_q ? spare_q : in_data;
        if (!full_q) spare_q <= in_data;
    end
    assign in_ready  = ready_q;
    assign out_valid = valid_q;
    assign out_data  = head_q;
endmodule
`default_nettype wire

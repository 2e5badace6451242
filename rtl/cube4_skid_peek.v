`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_skid_peek
// -----------------------------------------------------------------------------
// Purpose
//   Two-entry skid buffer for a valid/ready stream. in_ready is a register
//   (no combinational path from out_ready to in_ready), so it ends a pipeline
//   that advances under one stall enable: the pipeline's enable is in_ready,
//   and an item already on its way when out_ready drops lands in the second
//   entry. Full throughput: one item per cycle when out_ready stays high.
//   Built as a two-entry FIFO (entries written at a write pointer, read
//   through a multiplexer at a read pointer). An entry's data registers load
//   in_data on every cycle while the entry is free, so their clock enable is
//   a register (the entry's "free" flag, one flip-flop copy per 64 data bits),
//   never logic of in_valid or out_ready: a push marks the entry used in the
//   cycle it loads the pushed item. out_ready moves only the read pointer
//   and the state bits, so a late out_ready (e.g. a downstream hazard check)
//   does not fan out to every data flip-flop's clock enable.
//   The free flags and the read pointer are register copies
//   (cube4_prim_copies), one per 64 data bits, so the multiplexer's select,
//   where a consumer's decisions start, drives 64 loads, not DATA_W.
//   The entry behind the head is visible too (nx_valid, nx_data): a consumer
//   can decide one cycle ahead what it will do with the item after the one
//   it is offered (cube4_com_ahead, COM's read-after-write rule as a
//   register, takes nx_valid: whether a beat waits behind the head; it keeps
//   its own compares of each beat, so no user reads nx_data now).
//   in_ready is kept as READY_N register copies (cube4_prim_lut_copies), all
//   equal: copy 0 is in_ready, the others go to a producer whose stall
//   enable reaches loads far apart (the front end's CFB: one per group of
//   its advance's loads), so no one register drives them all; each copy's
//   next value is a LUT of its own, shared with no other logic.
//   out_valid is kept alike as VALID_N register copies: copy 0 is out_valid
//   and drives the buffer's own state, the others go to a consumer whose
//   handshake lies far from the buffer's entries (cube4_top: the beat's bits
//   into SHA's output, beside it), so that the route to them starts at a
//   register of their own.
//   in_ready_nx is the value in_ready takes at the next edge (the copies'
//   input, combinational): a producer that joins this buffer's ready with
//   another's registers the AND of both next values in copies of its own
//   (cube4_frontend: CFB's ready), one register and no LUT between it and
//   its loads, where the AND of two copies would be a LUT between registers
//   placed beside two buffers.
//   cube4_skid is this buffer without nx_valid, nx_data and the copies.
//
// Parameters
//   DATA_W        width of the payload.  Range 1..4096.  Default 8.
//   READY_N       copies of in_ready (in_ready_cp).  Range 1..16.  Default 1.
//   VALID_N       copies of out_valid (out_valid_cp).  Range 1..16.  Default 1.
//
// Latency
//   1 cycle from an accepted input to out_valid. Order is kept; nothing is
//   lost or duplicated under any pattern of out_ready. out_data is a 2:1
//   multiplexer after the entry registers, selected by a register (a copy
//   of the read pointer per 64 bits).
//
// Ports
//   clk, rst                 clock, synchronous active-high reset (empties it)
//   in_valid/in_ready/in_data   input stream  (in_data: any format, DATA_W bits);
//                            in_ready is a register
//   in_ready_cp    out  [READY_N] copies of in_ready (copy 0 is in_ready)
//   in_ready_nx    out  in_ready after the next edge (combinational; 1 in reset)
//   out_valid/out_ready/out_data output stream (same format)
//   out_valid_cp   out  [VALID_N] copies of out_valid (copy 0 is out_valid)
//   nx_valid, nx_data  out   the buffer holds a second item, behind the head on
//                            out_data; that item (a 2:1 multiplexer after the
//                            entries, as out_data's; any value while nx_valid
//                            is 0)
//
// Bit growth and rounding: none (storage only).
// =============================================================================
module cube4_skid_peek #(
    parameter integer DATA_W  = 8,
    parameter integer READY_N = 1,
    parameter integer VALID_N = 1
) (
    `CUBE4_STREAM_PORTS(DATA_W),
    output wire nx_valid, output wire [DATA_W-1:0] nx_data,
    output wire [READY_N-1:0] in_ready_cp,
    output wire in_ready_nx,
    output wire [VALID_N-1:0] out_valid_cp
);
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_skid_peek", "DATA_W", DATA_W, 1, 4096)
        `CUBE4_RANGE(g_bad_ready_n, "cube4_skid_peek", "READY_N", READY_N, 1, 16)
        `CUBE4_RANGE(g_bad_valid_n, "cube4_skid_peek", "VALID_N", VALID_N, 1, 16)
    endgenerate

    wire             nonempty_q;     // at least one entry holds an item (copy 0 of out_valid_cp)
    reg              full_q;         // both entries hold items
    reg              wp_q;           // write pointer
    wire             rp_q;           // read pointer (copy 0 of g_grp's copies)
    // the entries: registers per group of 64 bits (g_grp)

    wire push = in_valid && !full_q;
    wire pop  = nonempty_q && out_ready;

    always @(posedge clk) begin
        if (rst) begin
            full_q     <= 1'b0;
            wp_q       <= 1'b0;
        end else begin
            if (push) wp_q <= !wp_q;
            if (push && !pop)      full_q <= nonempty_q;
            else if (pop && !push) full_q <= 1'b0;
        end
    end
    // nonempty: a register in VALID_N kept copies (cube4_prim_copies)
    wire nonempty_d = (push && !pop) ? 1'b1 : ((pop && !push) ? full_q : nonempty_q);
    cube4_prim_copies #(.N(VALID_N), .RST_VAL(64'd0)) u_valid (
        .clk(clk), .rst(rst), .d(nonempty_d), .q(out_valid_cp));
    assign nonempty_q = out_valid_cp[0];

    // Entry e is free when it holds no unread item. A push writes entry wp_q,
    // which is free (a push needs !full_q). A pop and a push never hit the
    // same entry in one cycle (that would need both entries full).
    wire free0_now, free1_now;          // the flags (copy 0)
    wire free0_d = !(push && !wp_q) && (free0_now || (pop && !rp_q));
    wire free1_d = !(push &&  wp_q) && (free1_now || (pop &&  rp_q));
    localparam integer GRP_W = 64;                           // data bits per flag copy
    localparam integer NGRP  = (DATA_W + GRP_W - 1) / GRP_W;
    wire rp_d = rp_q ^ pop;
    wire [3*NGRP-1:0] free_q;           // copy g: {rp, free1, free0}
    cube4_prim_copies #(.N(NGRP), .W(3), .RST_VAL(64'd3)) u_free (
        .clk(clk), .rst(rst), .d({rp_d, free1_d, free0_d}), .q(free_q));
    assign {rp_q, free1_now, free0_now} = free_q[2:0];
    genvar g;
    generate
        for (g = 0; g < NGRP; g = g + 1) begin : g_grp
            localparam integer LO = g * GRP_W;
            localparam integer W  = (DATA_W - LO < GRP_W) ? DATA_W - LO : GRP_W;
            reg [W-1:0] d0_q, d1_q;     // this group's bits of the two entries
            always @(posedge clk) begin
                if (free_q[3*g])     d0_q <= in_data[LO +: W];
                if (free_q[3*g + 1]) d1_q <= in_data[LO +: W];
            end
            assign out_data[LO +: W] = free_q[3*g + 2] ? d1_q : d0_q;
            assign nx_data[LO +: W]  = free_q[3*g + 2] ? d0_q : d1_q;
        end
    endgenerate

    // in_ready: a register holding !full_q, in READY_N kept copies, each
    // taking !full_d from a LUT of its own (cube4_prim_lut_copies: {D, C, B, A}
    // = {nonempty_q, full_q, out_ready, in_valid}, INIT 16'hCD0F): a copy far
    // from the buffer (beside its producer) then takes in_valid and out_ready
    // into its own LUT, not through full_q's next-value LUT beside the buffer
    wire full_d = (push && !pop) ? nonempty_q : ((pop && !push) ? 1'b0 : full_q);
    cube4_prim_lut_copies #(.COPIES(READY_N), .INIT(32'hCD0F), .RESET(1), .RST_VAL(1)) u_ready (
        .clk(clk), .rst(rst), .in({READY_N{nonempty_q, full_q, out_ready, in_valid}}), .q(in_ready_cp));
    assign in_ready    = in_ready_cp[0];
    assign in_ready_nx = rst || !full_d;
    assign out_valid = nonempty_q;
    assign nx_valid  = full_q;

endmodule
`default_nettype wire

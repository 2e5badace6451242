`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_credit_fifo
// -----------------------------------------------------------------------------
// Purpose
//   The output FIFO of a pipeline that never stalls (credit-based flow
//   control). The pipeline in front of it moves on every cycle and carries a
//   valid bit per stage; it accepts a new item only when this FIFO grants a
//   credit, so every item in flight has a FIFO entry reserved for it and
//   nothing is lost however long out_ready stays low. No clock enable of the
//   pipeline's datapath depends on out_ready: back-pressure reaches only the
//   pipeline's input (its in_ready) and this FIFO's read pointers.
//
//   Reservations: `take` reserves an entry (an item entered the pipeline),
//   `give` returns one unused (an item left the pipeline without producing
//   an output), and an entry read out of the FIFO returns its reservation. credit is 1 while fewer than DEPTH reservations
//   are held, counting this cycle's take / give / read, so `take` may be 1
//   in a cycle with credit = 1 and the FIFO never overflows.
//
//   Storage: DEPTH words with an asynchronous read (distributed / LUT RAM on
//   an FPGA): out_data is the memory's read port at the read pointer (a
//   register), out_valid a register; the consumer registers the data. The
//   words are stored as groups of 64 bits; each group has its own copy of
//   the write enable (cube4_prim_copies of push_d) and its own write and
//   read pointers, so that no single net drives every memory cell of a wide
//   word. The memory takes the place of the pipeline's last register: the
//   caller says one cycle ahead (push_d) that its last stage will hold an
//   item, and the FIFO stores that stage's results. With IN_REG = 1 those
//   results pass a register first (one cycle later into the memory): the
//   caller's last stage then ends at a flip-flop that can sit beside its
//   logic, and the route to the memory has a cycle of its own.
//
// Parameters
//   DATA_W     width of an item.                        1..8192.  Default 8.
//   DEPTH      entries; a power of two.                 4..64.    Default 16.
//              For full throughput DEPTH must be at least the number of
//              cycles from a `take` to the first cycle its item could be read
//              (the pipeline's stages + 2, + 1 with IN_REG).
//   IN_REG     1: in_data registered before the memory.  0..1.  Default 0.
//   VALID_N    copies of out_valid (out_valid_cp), each a flip-flop of its
//              own: for a consumer far from the FIFO that ANDs out_valid with
//              its ready itself (so that AND is not the FIFO's own read, one
//              gate beside the FIFO, whose output would then cross the die
//              to it).                                  1..4.     Default 1.
//
// Latency
//   An item pushed at a clock edge is on out_valid/out_data right after that
//   edge (when the FIFO was empty): the memory is the last pipeline register.
//   With IN_REG = 1 the push is one edge later (in_data's register).
//   credit and out_valid are registers; out_data comes from the memory's
//   read port, addressed by registers.
//
// Ports
//   clk, rst        clock, synchronous active-high reset (empties the FIFO and
//                   drops every reservation)
//   take            in   an item was accepted by the pipeline this cycle
//                        (allowed only when credit = 1)
//   give            in   an item left the pipeline this cycle without a push
//   credit          out  a register: a take is allowed
//   credit_d        out  the value credit takes at the next edge, for a
//                        consumer that keeps its own register copies of credit
//                        (cube4_prim_copies, reset to 1)
//   push_d          in   in_data of the next cycle is an item: it is stored
//                        then. Each push uses the reservation of its item.
//   in_data         in   [DATA_W] any format
//   out_valid/out_ready/out_data   output stream (same format)
//   out_valid_cp    out  [VALID_N] copies of out_valid (copy 0 is out_valid)
//
// Bit growth and rounding: none (storage only).
// =============================================================================
module cube4_credit_fifo #(
    parameter integer DATA_W        = 8,
    parameter integer DEPTH         = 16,
    parameter integer IN_REG        = 0,
    parameter integer VALID_N       = 1
) (
    input  wire                     clk,
    input  wire                     rst,
    input  wire                     take,
    input  wire                     give,
    output wire                     credit,
    output wire                     credit_d,
    input  wire                     push_d,
    input  wire [DATA_W-1:0]        in_data,
    output wire                     out_valid,
    input  wire                     out_ready,
    output wire [DATA_W-1:0]        out_data,
    output wire [VALID_N-1:0]       out_valid_cp
);
    localparam integer AW = (DEPTH > 1) ? $clog2(DEPTH) : 1;
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_credit_fifo", "DATA_W", DATA_W, 1, 8192)
        if (DEPTH < 4 || DEPTH > 64 || (1 << AW) != DEPTH) begin : g_bad_depth
            $error("cube4_credit_fifo: DEPTH = %0d must be a power of two in 4..64", DEPTH);
        end
        `CUBE4_RANGE(g_bad_in_reg, "cube4_credit_fifo", "IN_REG", IN_REG, 0, 1)
        `CUBE4_RANGE(g_bad_valid_n, "cube4_credit_fifo", "VALID_N", VALID_N, 1, 4)
    endgenerate

    localparam integer GW   = 64;                            // bits per group (the last may be fewer)
    localparam integer NGRP = (DATA_W + GW - 1) / GW;
    // the write enable: one flip-flop copy per group (IN_REG: after one more register)
    wire [NGRP-1:0] push;
    wire [DATA_W-1:0] wr_data;          // the word the memory stores
    generate
        if (IN_REG == 1) begin : g_in_reg
            reg push_dd;
            reg [DATA_W-1:0] in_q;
            always @(posedge clk) begin
                if (rst) push_dd <= 1'b0;
                else     push_dd <= push_d;
            end
            always @(posedge clk) in_q <= in_data;
            cube4_prim_copies #(.N(NGRP)) u_push (.clk(clk), .rst(rst), .d(push_dd), .q(push));
            assign wr_data = in_q;
        end else begin : g_in_direct
            cube4_prim_copies #(.N(NGRP)) u_push (.clk(clk), .rst(rst), .d(push_d), .q(push));
            assign wr_data = in_data;
        end
    endgenerate
    localparam [AW:0]  DEPTH_C = DEPTH[AW:0];

    // out_ready comes from the next unit, often from far away on a chip, so
    // it reaches only a few flip-flops, each through one small gate beside
    // it: the next values of nonempty and credit are chosen by a read (and
    // push, take, give) among flags computed from registers. nonempty has
    // kept copies (cube4_prim_copies): [0] out_valid and the occupancy, [1]
    // the reservations, [2 + g] group g's read pointer; each ANDs its own
    // copy with out_ready, so no one net carries "an item leaves" across
    // the FIFO; [2 + NGRP + k - 1] out_valid_cp's copy k (k >= 1).
    localparam integer NNE = NGRP + 1 + VALID_N;
    wire [NNE-1:0] ne_q;                // copies of nonempty
    // ---- occupancy of the memory: pushes - reads (push[0] is the reference copy) ----
    reg  [AW:0] cnt_q;                  // items stored in the memory
    wire        rd = ne_q[0] && out_ready;          // an item leaves
    // (rd selects between two sums of registers, after them)
    wire [AW:0] cnt_p = cnt_q + {{AW{1'b0}}, push[0]};
    wire [AW:0] cnt_d = rd ? cnt_p - 1'b1 : cnt_p;
    wire        cnt_ge2 = (cnt_q >= (AW + 1)'(2));
    always @(posedge clk) begin
        if (rst) cnt_q <= '0;
        else     cnt_q <= cnt_d;
    end
    // cnt_d != 0
    wire ne_d = push[0] || cnt_ge2 || (ne_q[0] && !rd);
    cube4_prim_copies #(.N(NNE), .RESET(1)) u_nonempty (.clk(clk), .rst(rst), .d(ne_d), .q(ne_q));

    // ---- reservations ----
    // res_d = res_q + take - give - rd: take, give and rd come late (the
    // pipeline's input handshake, the next unit's ready), so they select
    // among res_q + 1, res_q, res_q - 1 and res_q - 2, sums of the register
    // alone (the same values modulo 2^(AW+1) as the one sum)
    reg  [AW:0] res_q;                  // reservations held: 0 .. DEPTH
    wire [AW:0] res_p1 = res_q + 1'b1;
    wire [AW:0] res_m1 = res_q - 1'b1;
    wire [AW:0] res_m2 = res_q - (AW + 1)'(2);
    wire        rd_r   = ne_q[1] && out_ready;              // rd, from copy 1
    wire        dn_one = give ^ rd_r;                       // give + rd = 1
    wire        dn_two = give && rd_r;                      // give + rd = 2
    wire [AW:0] res_d  = take ? (dn_two ? res_m1 : (dn_one ? res_q : res_p1))
                              : (dn_two ? res_m2 : (dn_one ? res_m1 : res_q));
    always @(posedge clk) begin
        if (rst) res_q <= '0;
        else     res_q <= res_d;
    end
    // credit_d = (res_d < DEPTH): res_d - res_q = take - give - rd is +1, 0 or
    // negative, and res_q <= DEPTH
    wire res_lt_dm1 = (res_q < DEPTH_C - 1'b1);
    wire res_lt_d   = (res_q < DEPTH_C);
    wire up   = take && !give && !rd_r;                     // res_d = res_q + 1
    wire same = take ? (give != rd_r) : (!give && !rd_r);   // res_d = res_q
    assign credit_d = up ? res_lt_dm1 : (same ? res_lt_d : 1'b1);
    reg credit_q;
    always @(posedge clk) begin
        if (rst) credit_q <= 1'b1;
        else     credit_q <= credit_d;
    end
    assign credit = credit_q;

    // ---- the memory, per group: own pointers, own write enable ----
    wire [DATA_W-1:0] rd_data;
    genvar g;
    generate
        for (g = 0; g < NGRP; g = g + 1) begin : g_grp
            localparam integer LO = g * GW;
            localparam integer W  = (DATA_W - LO < GW) ? DATA_W - LO : GW;
            reg [AW-1:0] wp_q, rp_q;
            wire rd_g = ne_q[2 + g] && out_ready;           // rd, from copy 2 + g
            (* keep *)
            always @(posedge clk) begin
                if (rst) begin
                    wp_q <= '0;
                    rp_q <= '0;
                end else begin
                    if (push[g]) wp_q <= wp_q + 1'b1;
                    if (rd_g)    rp_q <= rp_q + 1'b1;
                end
            end
            reg [W-1:0] mem [0:DEPTH-1];
            always @(posedge clk) begin
                if (push[g]) mem[wp_q] <= wr_data[LO +: W];
            end
            assign rd_data[LO +: W] = mem[rp_q];
        end
    endgenerate
    assign out_valid = ne_q[0];
    generate
        if (VALID_N > 1) begin : g_valid_cp
            assign out_valid_cp = {ne_q[NNE-1 : NGRP+2], ne_q[0]};
        end else begin : g_valid_one
            assign out_valid_cp = ne_q[0];
        end
    endgenerate
`ifndef SYNTHESIS
    // the copies load the same value and reset alike: after a reset they agree
    reg reset_seen;
    initial reset_seen = 1'b0;
    always @(posedge clk) begin
        if (rst) reset_seen <= 1'b1;
        else if (reset_seen && out_valid_cp != {VALID_N{out_valid}})
            $fatal(1, "cube4_credit_fifo: out_valid_cp %b differs from out_valid %b", out_valid_cp, out_valid);
    end
`endif
    assign out_data  = rd_data;

endmodule
`default_nettype wire

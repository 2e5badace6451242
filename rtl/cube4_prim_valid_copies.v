`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_prim_valid_copies
// -----------------------------------------------------------------------------
// Purpose
//   The valid bit of a pipeline's output register in COPIES kept copies, each
//   with its own copy of the taker's ready, and the stage's advance per copy:
//     adv[c] = ~q[c] | ready[c]          (the register is free or taken)
//     q[c]  <= rst ? 0 : adv[c] ? d : q[c]
//   written as q[c] <= !rst & (d | (q[c] & ~ready[c])), so that each copy's
//   next value is logic of its own beside it and not the advance net: a
//   caller's advance reaches a group of loads across the die, and a copy
//   whose own enable was that net ran to the net's LUT, placed among the
//   loads, and back (0.2 + 8.2 ns on the crop beat build). Each copy is a
//   cube4_prim_lut_copies copy (its next value a LUT4 of its own on the
//   ECP5, {D, C, B, A} = {rst, ready[c], q[c], d}, INIT 16'h00AE), which
//   synthesis cannot share with adv.
//
// Parameters
//   COPIES   copies (one per group of the stage's loads).  1..64. Default 1.
//
// Latency: 1 cycle (q[c] is the value of the last clock edge).
//
// Ports
//   clk, rst   clock, synchronous active-high reset (every copy to 0)
//   d          in   [1]       the valid bit to load (the stage before's)
//   ready      in   [COPIES]  copy c's ready of the taker (equal copies)
//   q          out  [COPIES]  the valid bit, copy c
//   adv        out  [COPIES]  the stage moves, copy c: ~q[c] | ready[c]
//
// Bit growth and rounding: none.
// =============================================================================
module cube4_prim_valid_copies #(
    parameter integer COPIES = 1
) (
    input  wire              clk,
    input  wire              rst,
    input  wire              d,
    input  wire [COPIES-1:0] ready,
    output wire [COPIES-1:0] q,
    output wire [COPIES-1:0] adv
);
    generate
        `CUBE4_RANGE(g_bad_copies, "cube4_prim_valid_copies", "COPIES", COPIES, 1, 64)
    endgenerate

    genvar c;
    wire [4*COPIES-1:0] lut_in;         // copy c's {rst, ready, q, d}
    generate
        for (c = 0; c < COPIES; c = c + 1) begin : g_copy
            assign lut_in[4*c +: 4] = {rst, ready[c], q[c], d};
            assign adv[c] = !q[c] || ready[c];
        end
    endgenerate
    // !D & (A | (B & !C)): !rst & (d | (q & !ready))
    cube4_prim_lut_copies #(.COPIES(COPIES), .INIT(32'h00AE), .RESET(0)) u_copies (
        .clk(clk), .rst(1'b0), .in(lut_in), .q(q));
endmodule
`default_nettype wire

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
//   loads, and back (0.2 + 8.2 ns on the crop beat build). The ECP5 form
//   (rtl/ecp5/) makes each copy's next value a LUT4 of its own, which
//   synthesis cannot share with adv; this generic form is the simulation's.
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
module cube4_prim_valid_copies
`include "cube4_prim_valid_copies_if.vh"

    genvar c;
    generate
        for (c = 0; c < COPIES; c = c + 1) begin : g_copy
            reg q_q;
            (* keep *)                  // one copy per group of loads: never merged
            always @(posedge clk) q_q <= !rst && (d || (q_q && !ready[c]));
            assign q[c]   = q_q;
            assign adv[c] = !q_q || ready[c];
        end
    endgenerate
endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_prim_valid_copies  (ECP5 form; the generic form is
// rtl/cube4_prim_valid_copies.v)
// -----------------------------------------------------------------------------
// Purpose
//   The valid copies of rtl/cube4_prim_valid_copies.v (same ports, parameters
//   and timing), each copy's next value !rst & (d | (q & ~ready)) an
//   instantiated LUT4 whose only load is the copy's flip-flop: Yosys maps
//   inferred logic with ABC, which may build that value from the adv net
//   (d | ~adv) and so put the adv LUT, placed among the stage's loads, back
//   on the copy's own loop; a LUT4 instance is a cell ABC does not touch.
//   Simulation of this form uses the model of the primitive in
//   sim/hdl/ecp5/LUT4.v (tb/cube4_prim_valid_copies runs both forms).
//
// Parameters, latency, ports, bit growth: as rtl/cube4_prim_valid_copies.v.
// =============================================================================
module cube4_prim_valid_copies
`include "cube4_prim_valid_copies_if.vh"

    genvar c;
    generate
        for (c = 0; c < COPIES; c = c + 1) begin : g_copy
            reg  q_q;
            wire nx;
            // Z = INIT[{D, C, B, A}] = !D & (A | (B & !C)): A = d, B = q, C = ready, D = rst
            LUT4 #(.INIT(16'h00AE)) u_nx (.A(d), .B(q_q), .C(ready[c]), .D(rst), .Z(nx));
            (* keep *)                  // one copy per group of loads: never merged
            always @(posedge clk) q_q <= nx;
            assign q[c]   = q_q;
            assign adv[c] = !q_q || ready[c];
        end
    endgenerate
endmodule
`default_nettype wire

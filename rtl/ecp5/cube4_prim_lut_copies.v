`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_prim_lut_copies  (ECP5 form; the generic form is
// rtl/cube4_prim_lut_copies.v)
// -----------------------------------------------------------------------------
// Purpose
//   The copies of rtl/cube4_prim_lut_copies.v (same ports, parameters and
//   timing), each copy's next value an instantiated LUT4 whose only load is
//   the copy's flip-flop: Yosys maps inferred logic with ABC, which may share
//   one LUT between the copies and the logic of the flag's other users (a
//   skid buffer's ready copies took their next value from a LUT beside the
//   buffer's own state, across the die from the copy); a LUT4 instance is a
//   cell ABC does not touch. The reset is the flip-flop's (its LSR).
//   Simulation of this form uses the model of the primitive in
//   sim/hdl/ecp5/LUT4.v (tb/cube4_prim_lut_copies runs both forms).
//
// Parameters, latency, ports, bit growth: as rtl/cube4_prim_lut_copies.v.
// =============================================================================
module cube4_prim_lut_copies
`include "cube4_prim_lut_copies_if.vh"

    genvar k;
    generate
        for (k = 0; k < COPIES; k = k + 1) begin : g_copy
            wire nx;
            // Z = INIT[{D, C, B, A}]
            LUT4 #(.INIT(INIT[15:0])) u_nx (.A(in[4*k]), .B(in[4*k + 1]), .C(in[4*k + 2]), .D(in[4*k + 3]), .Z(nx));
            reg  q_q;
            if (RESET == 1) begin : g_rst
                (* keep *)              // one copy per group of loads: never merged
                always @(posedge clk) q_q <= rst ? RST_VAL[0] : nx;
            end else begin : g_no_rst
                (* keep *)
                always @(posedge clk) q_q <= nx;
                wire unused_rst = rst;
            end
            assign q[k] = q_q;
        end
    endgenerate
endmodule
`default_nettype wire

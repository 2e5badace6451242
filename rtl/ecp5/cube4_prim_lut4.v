`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_prim_lut4  (ECP5 form; the generic form is rtl/cube4_prim_lut4.v)
// -----------------------------------------------------------------------------
// Purpose
//   The function of rtl/cube4_prim_lut4.v as an instantiated LUT4, kept
//   (`keep`): Yosys maps inferred logic with ABC, which may share one LUT
//   between equal functions or build a function from other logic's nets; a
//   LUT4 instance is a cell ABC does not touch. Simulation of this form
//   uses the model of the primitive in sim/hdl/ecp5/LUT4.v.
//
// Parameters, latency, ports: as rtl/cube4_prim_lut4.v.
// =============================================================================
module cube4_prim_lut4
`include "cube4_prim_lut4_if.vh"
    // Z = INIT[{D, C, B, A}]
    (* keep *)
    LUT4 #(.INIT(INIT[15:0])) u_lut (.A(a), .B(b), .C(c), .D(d), .Z(z));
endmodule
`default_nettype wire

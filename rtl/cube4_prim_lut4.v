`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_prim_lut4
// -----------------------------------------------------------------------------
// Purpose
//   One four-input function, z = INIT[{d, c, b, a}] (INIT a LUT4's truth
//   table: bit k is the value at {d, c, b, a} = k), that synthesis must keep
//   as it is: the ECP5 form (rtl/ecp5/) is an instantiated LUT4 with `keep`,
//   a cell ABC neither merges with equal logic nor restructures; this
//   generic form is the simulation's and the gate count's. The one place
//   the vendor layer instantiates a LUT4 (cube4_prim_lut_copies uses it).
//
// Parameters
//   INIT   the truth table.  0..65535.  Default 0.
//
// Latency: none (combinational).
//
// Ports
//   a, b, c, d   in   the inputs (a the lowest index bit)
//   z            out  INIT[{d, c, b, a}]
//
// Bit growth and rounding: none.
// =============================================================================
module cube4_prim_lut4
`include "cube4_prim_lut4_if.vh"
    localparam [15:0] TABLE = INIT[15:0];
    assign z = TABLE[{d, c, b, a}];
endmodule
`default_nettype wire

`default_nettype none
// =============================================================================
// LUT4  (behavioural simulation model of the Lattice ECP5 primitive)
// -----------------------------------------------------------------------------
// Purpose
//   The 4-input look-up table the vendor layer (rtl/ecp5/) instantiates where
//   synthesis must not share or restructure a piece of logic:
//   Z = INIT[{D, C, B, A}]. Never read by synthesis (Yosys has its own model
//   of the primitive).
//
// Parameters
//   INIT   the table, 16 bits.
//
// Latency: none (combinational).
//
// Ports (names as the primitive's)
//   A, B, C, D   inputs (A the lowest index bit);  Z   output
// =============================================================================
/* verilator lint_off DECLFILENAME */
module LUT4 #(
    parameter [15:0] INIT = 16'h0000
) (
    input  wire A, input wire B, input wire C, input wire D,
    output wire Z
);
    assign Z = INIT[{D, C, B, A}];
endmodule
/* verilator lint_on DECLFILENAME */
`default_nettype wire

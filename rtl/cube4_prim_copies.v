`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_prim_copies
// -----------------------------------------------------------------------------
// Purpose
//   Register copies for fan-out: N flip-flop copies of one W-bit register,
//   each kept apart in synthesis (`keep`), so that a signal that drives
//   hundreds of loads (a write enable, a credit, a stream's valid bit, a RAM
//   address) is driven by one register per group of loads instead of one
//   register for all. Neither Yosys nor nextpnr replicates registers for
//   fan-out, so the copies are made here, in this one primitive; a block
//   that needs copies instantiates it inside itself and keeps a one-bit
//   interface. Simulation: every copy holds the same value. Yosys merges
//   a plain register of the same input into a kept copy (two kept copies
//   stay apart), so a value wanted near two groups of loads takes all its
//   registers from here. The copies are cube4_prim_reg_copies (the one
//   definition of a kept register copy) with one shared value, always enabled.
//
// Parameters
//   N        copies.                               1..512.  Default 1.
//   W        bits of the register.                 1..4096. Default 1.
//   RESET    1: synchronous reset to RST_VAL; 0: no reset (data registers).
//                                                  0..1.    Default 1.
//   RST_VAL  reset value of each copy (its low W bits; zero above 64).
//                                                  64 bits. Default 0.
//
// Latency: 1 cycle (q is d of the last clock edge).
//
// Ports
//   d   in   [W]     the value to register (any format)
//   q   out  [N*W]   copy c at bits [c*W +: W], all equal
//
// Bit growth and rounding: none.
// =============================================================================
module cube4_prim_copies #(
    parameter integer N       = 1,
    parameter integer W       = 1,
    parameter integer RESET   = 1,
    parameter [63:0]  RST_VAL = 64'd0
) (
    input  wire           clk,
    input  wire           rst,
    input  wire [W-1:0]   d,
    output wire [N*W-1:0] q
);
    // the kept copies: cube4_prim_reg_copies without enables, all loading d
    cube4_prim_reg_copies #(.COPIES(N), .W(W), .RESET(RESET), .RST_VAL(RST_VAL), .ENABLE(0)) u_copies (
        .clk(clk), .rst(rst), .en({N{1'b1}}), .d({N{d}}), .q(q));
endmodule
`default_nettype wire

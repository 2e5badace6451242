`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_prim_lut_copies
// -----------------------------------------------------------------------------
// Purpose
//   COPIES kept flip-flops, copy c loading a four-input function of its own
//   inputs {d, c, b, a} = in[4c +: 4]:
//     q[c] <= (RESET && rst) ? RST_VAL : INIT[{d, c, b, a}]
//   (INIT is a LUT4's truth table: bit k is the value at {d, c, b, a} = k).
//   For a flag whose copies reach loads far apart and whose next value is
//   logic of inputs that come from other places: each copy's next value is
//   logic of its own beside it, never a net synthesis shares between the
//   copies or with the flag's other users, so no route runs from a copy to
//   a LUT placed among another copy's loads and back: each copy's function
//   is a cube4_prim_lut4 (on the ECP5 an instantiated, kept LUT4, which ABC
//   neither merges nor builds from other nets). Users:
//   cube4_prim_valid_copies (a pipeline register's valid bit),
//   cube4_skid_peek (its in_ready copies).
//
// Parameters
//   COPIES   copies.                                          1..64. Default 1.
//   INIT     the function's truth table, as a LUT4's INIT.     0..65535. Default 0.
//   RESET    1: synchronous reset to RST_VAL (the flip-flop's
//            own set/reset); 0: no reset (a caller may take rst
//            as one of the four inputs).                      0..1.  Default 0.
//   RST_VAL  reset value.                                     0..1.  Default 0.
//
// Latency: 1 cycle (q[c] is the function of in[4c +: 4] at the last clock edge).
//
// Ports
//   clk, rst   clock, synchronous active-high reset (with RESET = 1)
//   in    in   [4*COPIES]  copy c's inputs {d, c, b, a} at bits [4c +: 4]
//   q     out  [COPIES]    copy c
//
// Bit growth and rounding: none.
// =============================================================================
module cube4_prim_lut_copies #(
    parameter integer COPIES  = 1,
    parameter integer INIT    = 0,
    parameter integer RESET   = 0,
    parameter integer RST_VAL = 0
) (
    input  wire                clk,
    input  wire                rst,
    input  wire [4*COPIES-1:0] in,
    output wire [COPIES-1:0]   q
);
    generate
        `CUBE4_RANGE(g_bad_copies, "cube4_prim_lut_copies", "COPIES", COPIES, 1, 64)
        `CUBE4_RANGE(g_bad_init, "cube4_prim_lut_copies", "INIT", INIT, 0, 65535)
        `CUBE4_RANGE(g_bad_reset, "cube4_prim_lut_copies", "RESET", RESET, 0, 1)
        `CUBE4_RANGE(g_bad_rst_val, "cube4_prim_lut_copies", "RST_VAL", RST_VAL, 0, 1)
    endgenerate

    // copy k: its function (cube4_prim_lut4), then its kept flip-flop (cube4_prim_reg_copies)
    wire [COPIES-1:0] nx;
    genvar k;
    generate
        for (k = 0; k < COPIES; k = k + 1) begin : g_copy
            cube4_prim_lut4 #(.INIT(INIT)) u_nx (
                .a(in[4*k]), .b(in[4*k + 1]), .c(in[4*k + 2]), .d(in[4*k + 3]), .z(nx[k]));
        end
    endgenerate
    cube4_prim_reg_copies #(.COPIES(COPIES), .W(1), .RESET(RESET), .RST_VAL(64'(RST_VAL)), .ENABLE(0)) u_q (
        .clk(clk), .rst(rst), .en({COPIES{1'b1}}), .d(nx), .q(q));
endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_prim_reg_copies
// -----------------------------------------------------------------------------
// Purpose
//   Register copies for fan-out, each with its own clock enable and its own
//   next value: COPIES flip-flop copies of one W-bit register, kept apart in
//   synthesis (`keep`), for a register whose loads are split into groups
//   that must not share one net: copy c loads d[c] when en[c]. A caller
//   feeds every copy the same value, either one net replicated
//   ({COPIES{x}}) or each copy's own next-value logic (a flag whose copies
//   each follow their own value and their own enable copy, so that no
//   shared net lies between the copies). Simulation: every copy holds the
//   same value when the caller keeps that promise. cube4_prim_copies is
//   the special case of one shared value and no enable.
//
// Parameters
//   COPIES   copies.                               1..512.  Default 1.
//   W        bits of the register.                 1..4096. Default 1.
//   RESET    1: synchronous reset to RST_VAL (before the enable);
//            0: no reset (data registers).         0..1.    Default 1.
//   RST_VAL  reset value of each copy (its low W bits; zero above 64).
//                                                  64 bits. Default 0.
//   ENABLE   1: copy c loads when en[c]; 0: every copy loads on every
//            edge and en is not read (cube4_prim_copies: no enable logic
//            even where synthesis keeps the hierarchy).  0..1. Default 1.
//
// Latency: 1 cycle (q[c] is d[c] of the last clock edge with en[c] = 1).
//
// Ports
//   en  in   [COPIES]     the clock enable of each copy
//   d   in   [COPIES*W]   copy c's next value at bits [c*W +: W] (any format)
//   q   out  [COPIES*W]   copy c at bits [c*W +: W]
//
// Bit growth and rounding: none.
// =============================================================================
module cube4_prim_reg_copies #(
    parameter integer COPIES  = 1,
    parameter integer W       = 1,
    parameter integer RESET   = 1,
    parameter [63:0]  RST_VAL = 64'd0,
    parameter integer ENABLE  = 1
) (
    input  wire                clk,
    input  wire                rst,
    input  wire [COPIES-1:0]   en,
    input  wire [COPIES*W-1:0] d,
    output wire [COPIES*W-1:0] q
);
    generate
        `CUBE4_RANGE(g_bad_copies, "cube4_prim_reg_copies", "COPIES", COPIES, 1, 512)
        `CUBE4_RANGE(g_bad_w, "cube4_prim_reg_copies", "W", W, 1, 4096)
        `CUBE4_RANGE(g_bad_enable, "cube4_prim_reg_copies", "ENABLE", ENABLE, 0, 1)
    endgenerate

    genvar c;
    generate
        for (c = 0; c < COPIES; c = c + 1) begin : g_copy
            reg [W-1:0] q_q;
            (* keep *)                  // one copy per group of loads: never merged
            always @(posedge clk) begin
                if (RESET != 0 && rst) q_q <= W'(RST_VAL);
                else if (ENABLE == 0 || en[c]) q_q <= d[c*W +: W];
            end
            assign q[c*W +: W] = q_q;
        end
        if (RESET == 0) begin : g_no_reset
            wire unused_rst = rst;
        end
        if (ENABLE == 0) begin : g_no_enable
            wire unused_en = ^en;
        end
    endgenerate
endmodule
`default_nettype wire

// cube4_prim_lut_copies_if.vh: the interface of cube4_prim_lut_copies (flip-flop copies, each
// loading a four-input function of its own inputs): its parameters, ports and parameter checks,
// included by both of its forms, rtl/cube4_prim_lut_copies.v (generic, which documents them)
// and rtl/ecp5/cube4_prim_lut_copies.v (ECP5), right after "module cube4_prim_lut_copies".
#(
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

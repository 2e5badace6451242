// cube4_prim_valid_copies_if.vh: the interface of cube4_prim_valid_copies (a pipeline register's
// valid bit in copies): its parameters, ports and parameter checks, included by both of its forms,
// rtl/cube4_prim_valid_copies.v (generic, which documents them) and
// rtl/ecp5/cube4_prim_valid_copies.v (ECP5), right after "module cube4_prim_valid_copies".
#(
    parameter integer COPIES = 1
) (
    input  wire              clk,
    input  wire              rst,
    input  wire              d,
    input  wire [COPIES-1:0] ready,
    output wire [COPIES-1:0] q,
    output wire [COPIES-1:0] adv
);
    generate
        `CUBE4_RANGE(g_bad_copies, "cube4_prim_valid_copies", "COPIES", COPIES, 1, 64)
    endgenerate

// cube4_prim_lut4_if.vh: the interface of cube4_prim_lut4 (one kept four-input function): its
// parameter, ports and parameter check, included by both of its forms, rtl/cube4_prim_lut4.v
// (generic, which documents them) and rtl/ecp5/cube4_prim_lut4.v (ECP5), right after
// "module cube4_prim_lut4".
#(
    parameter integer INIT = 0
) (
    input  wire a, input wire b, input wire c, input wire d,
    output wire z
);
    generate
        `CUBE4_RANGE(g_bad_init, "cube4_prim_lut4", "INIT", INIT, 0, 65535)
    endgenerate

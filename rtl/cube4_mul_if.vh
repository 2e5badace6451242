// cube4_mul_if.vh: the interface of cube4_mul (the registered multiplier): its parameters, ports and
// parameter checks, included by both of its forms, rtl/cube4_mul.v (generic, which documents
// them) and rtl/ecp5/cube4_mul.v (ECP5), right after "module cube4_mul".
#(
    parameter  integer A_W = 18,
    parameter  integer B_W = 18,
    localparam integer P_W = A_W + B_W
) (
    input  wire                  clk,
    input  wire                  en,
    input  wire signed [A_W-1:0] a,
    input  wire signed [B_W-1:0] b,
    output wire signed [P_W-1:0] p
);
    generate
        `CUBE4_RANGE(g_bad_a_w, "cube4_mul", "A_W", A_W, 2, 32)
        `CUBE4_RANGE(g_bad_b_w, "cube4_mul", "B_W", B_W, 2, 32)
    endgenerate

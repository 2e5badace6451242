// cube4_mul_if.vh: the interface of cube4_mul (the registered multiplier): its parameters, ports,
// parameter checks and its optional fabric output register, included by both of its forms,
// rtl/cube4_mul.v (generic, which documents them) and rtl/ecp5/cube4_mul.v (ECP5), right after
// "module cube4_mul". A form gives the product of its own output register on p_core.
#(
    parameter  integer A_W    = 18,
    parameter  integer B_W    = 18,
    parameter  integer OUT_FF = 0,
    localparam integer P_W    = A_W + B_W
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
        `CUBE4_RANGE(g_bad_out_ff, "cube4_mul", "OUT_FF", OUT_FF, 0, 1)
    endgenerate
    wire signed [P_W-1:0] p_core;       // the form's product register (2 cycles after a, b)
    generate
        if (OUT_FF != 0) begin : g_out_ff
            // a flip-flop in the fabric after the product register: the route from a
            // multiplier placed far from its consumers ends here, and the consumer's
            // logic starts here (the placer puts it anywhere on the way)
            reg signed [P_W-1:0] p_ff;
            always @(posedge clk) begin
                if (en) p_ff <= p_core;
            end
            assign p = p_ff;
        end else begin : g_out_direct
            assign p = p_core;
        end
    endgenerate

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_prim_reg_en
// -----------------------------------------------------------------------------
// Purpose
//   A W-bit data register with a load enable, the enable itself a register in
//   COPIES kept copies (cube4_prim_copies), each loading one group of
//   ceil(W / COPIES) bits: no enable net drives more than a group's
//   flip-flops (one enable for a lane's wide words drove 2 * W of them and was
//   the P = 8 build's critical net). The data bits have no reset.
//
// Parameters
//   W        data bits.                                1..4096. Default 1.
//   COPIES   enable copies (the last groups may be
//            empty when W is small: their copy stays). 1..512.  Default 4.
//   RESET    1: the enable copies reset to 0 (no load
//            in the cycle after a reset); 0: no reset.  0..1.    Default 1.
//
// Latency: the enable one cycle, the data none: q takes d at a clock edge
//   when en_d was 1 at the edge before.
//
// Ports
//   en_d   in   [1]   the enable, one cycle early
//   d      in   [W]   the word to load (any format)
//   q      out  [W]   the register
//
// Bit growth and rounding: none.
// =============================================================================
module cube4_prim_reg_en #(
    parameter integer W      = 1,
    parameter integer COPIES = 4,
    parameter integer RESET  = 1
) (
    input  wire         clk,
    input  wire         rst,
    input  wire         en_d,
    input  wire [W-1:0] d,
    output wire [W-1:0] q
);
    generate
        `CUBE4_RANGE(g_bad_w, "cube4_prim_reg_en", "W", W, 1, 4096)
    endgenerate
    localparam integer GW = (W + COPIES - 1) / COPIES;   // bits per copy

    wire [COPIES-1:0] en;
    cube4_prim_copies #(.N(COPIES), .RESET(RESET)) u_en (
        .clk(clk), .rst(rst), .d(en_d), .q(en));
    reg [W-1:0] q_q;
    assign q = q_q;
    genvar g;
    generate
        for (g = 0; g < COPIES; g = g + 1) begin : g_grp
            localparam integer GL = g * GW;
            localparam integer GN = (W - GL < GW) ? W - GL : GW;
            if (GN > 0) begin : g_bits
                always @(posedge clk) begin
                    if (en[g]) q_q[GL +: GN] <= d[GL +: GN];
                end
            end else begin : g_empty
                wire unused_en = en[g];
            end
        end
    endgenerate
endmodule
`default_nettype wire

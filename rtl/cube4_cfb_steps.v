`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_steps
// -----------------------------------------------------------------------------
// Purpose
//   The slices' accumulated steps for the beat schedule's decisions
//   (cube4_cfb_decide's st_*; BEATS = 1 of cube4_cfb): one item per sample
//   slice m = 0 .. M - 1, in order,
//     stepx(m) = floor((PH0_X + m * VIEW_X) / 2^(W + g)),  stepy alike
//   (golden/cube4/view.py Traversal.steps), kept incrementally: a phase
//   accumulator per axis adds VIEW at each item and counts its carries, as
//   cube4_cfb_tmpl does a slice at a time for the template.
//
// Parameters (CUBE4_CFB_PARAMS; ranges as cube4_cfb)
//   P, MAX_DIM, WEIGHT_W (W), MAX_SS_LOG2 (g = log2 S of the frame).
//
// Latency
//   Registers; st_valid from the start edge on (the first item is slice 0's,
//   zero), an item per cycle while st_ready. M = (NK - 1) * S + 1 items.
//
// Ports
//   clk, rst     clock, synchronous active-high reset (the item count)
//   cfg          in   [VIEW_W] view registers (NK, log2 S, VIEW_X/Y, PH0_X/Y)
//   start        in   pulse: a frame starts (cube4_cfb's go)
//   st_valid, st_ready   the items' handshake
//   st_x, st_y   out  [DIM_W] stepx(m), stepy(m)
//
// Bit growth and rounding
//   None: the phases are W + g bits and wrap by design (the carry is the
//   step); a step count is at most M - 1 < 2^DIM_W when VIEW < 1 (Q1.W).
// =============================================================================
module cube4_cfb_steps #(`CUBE4_CFB_PARAMS) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    input  wire start,
    output wire st_valid, input wire st_ready,
    output wire [DIM_W-1:0] st_x, output wire [DIM_W-1:0] st_y
);
    `CUBE4_VIEW_FIELDS(cfg);
    localparam integer PH_W = PHASE_W;
    wire [2:0]    g      = {1'b0, cfg_ss_log2};
    wire [PH_W:0] ph_one = {{PH_W{1'b0}}, 1'b1} << (WEIGHT_W[3:0] + {1'b0, g});
    // M = (NK - 1) * S + 1
    wire [M_W-1:0] nm = (M_W'(cfg_nk - 1'b1) << g) + 1'b1;

    reg [M_W-1:0]   n_q;               // items given
    reg [PH_W-1:0]  phx_q, phy_q;
    reg [DIM_W-1:0] sx_q, sy_q;
    reg             act_q;
    wire [PH_W:0] phx_sum = {1'b0, phx_q} + {{(PH_W - WEIGHT_W){1'b0}}, cfg_view_x};
    wire [PH_W:0] phy_sum = {1'b0, phy_q} + {{(PH_W - WEIGHT_W){1'b0}}, cfg_view_y};
    wire          cx = (phx_sum >= ph_one);
    wire          cy = (phy_sum >= ph_one);
    assign st_valid = act_q && (n_q < nm);
    always @(posedge clk) begin
        if (rst) begin
            act_q <= 1'b0;
        end else if (start) begin
            act_q <= 1'b1;
            n_q   <= '0;
            phx_q <= cfg_ph0_x;
            phy_q <= cfg_ph0_y;
            sx_q  <= '0;
            sy_q  <= '0;
        end else if (st_valid && st_ready) begin
            n_q   <= n_q + 1'b1;
            phx_q <= cx ? phx_sum[PH_W-1:0] - ph_one[PH_W-1:0] : phx_sum[PH_W-1:0];
            phy_q <= cy ? phy_sum[PH_W-1:0] - ph_one[PH_W-1:0] : phy_sum[PH_W-1:0];
            sx_q  <= sx_q + DIM_W'(cx);
            sy_q  <= sy_q + DIM_W'(cy);
        end
    end
    assign st_x = sx_q;
    assign st_y = sy_q;
endmodule
`default_nettype wire

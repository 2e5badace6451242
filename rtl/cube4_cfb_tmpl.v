`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_tmpl
// -----------------------------------------------------------------------------
// Purpose
//   The template unit of cube4_cfb (Teramac paper, section 5): the phases of
//   pass m, kept incrementally (docs/architecture.md "Front end"), and from
//   them the pass's resampling weights and its X/Y steps (the carry).
//   Pass 0 starts at the phase PH0 and its old step (slice -1 to 0) is
//   floor(PH0 / 2^(W+g)) - floor((PH0 - VIEW) / 2^(W+g)) = [PH0 < VIEW];
//   each next pass adds VIEW and takes the carry as its step.
//
// Parameters (CUBE4_CFB_PARAMS; ranges as cube4_cfb)
//   P, MAX_DIM, WEIGHT_W (W), MAX_SS_LOG2, ADDR_W (unused here).
//
// Latency
//   The phases are registers; wx, wy, wz and steps are combinational from
//   them and from r. They load PH0 while idle and step at next_pass.
//
// Ports
//   clk, rst     clock, synchronous active-high reset (no register is reset;
//                nothing moves while rst is high)
//   cfg          in   [VIEW_W] view registers (VIEW_X/Y Q1.W, PH0_X/Y, log2 S)
//   idle         in   the control unit is idle (load pass 0's phases)
//   next_pass    in   the control unit moves on to the next pass
//   r            in   [CFB_R_W] m mod S (cube4_cfb_trav)
//   wx, wy       out  [W] the weights of pass m (Q0.W): phase bits g .. g+W-1
//   wz           out  [W] r / S (Q0.W)
//   steps        out  [4] {old Y-step, old X-step, Y-step, X-step} of pass m
//
// Bit growth and rounding
//   The phases are W + log2 S bits (PHASE_W) and wrap by design (the carry is
//   the step); the weights drop the g guard bits below them (truncation, as
//   golden/cube4/view.py).
// =============================================================================
module cube4_cfb_tmpl #(`CUBE4_CFB_PARAMS) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    input  wire idle, input wire next_pass,
    input  wire [CFB_R_W-1:0] r,
    output wire [WEIGHT_W-1:0] wx, output wire [WEIGHT_W-1:0] wy, output wire [WEIGHT_W-1:0] wz,
    output wire [3:0] steps
);
    `CUBE4_VIEW_FIELDS(cfg);
    localparam integer PH_W = PHASE_W;

    // resampling weight = phase bits g .. g+W-1 (the g guard bits are below)
    function automatic [WEIGHT_W-1:0] phase_weight(input [PH_W-1:0] ph, input [1:0] gg);
        reg [PH_W-1:0] sh;
        begin
            sh = ph >> gg;
            phase_weight = sh[WEIGHT_W-1:0];
        end
    endfunction

    reg [PH_W-1:0] phx_q, phy_q;        // template phases of pass m
    reg            old_sx_q, old_sy_q;  // the steps of pass m - 1

    wire [2:0]      g = {1'b0, cfg_ss_log2};
    wire [PH_W:0]   phx_sum = {1'b0, phx_q} + {{(PH_W - WEIGHT_W){1'b0}}, cfg_view_x};
    wire [PH_W:0]   phy_sum = {1'b0, phy_q} + {{(PH_W - WEIGHT_W){1'b0}}, cfg_view_y};
    wire [PH_W:0]   ph_one  = {{PH_W{1'b0}}, 1'b1} << (WEIGHT_W[3:0] + {1'b0, g});
    wire            sx_step = (phx_sum >= ph_one);   // X-step of pass m
    wire            sy_step = (phy_sum >= ph_one);   // Y-step of pass m
    wire [PH_W-1:0] phx_next = sx_step ? phx_sum[PH_W-1:0] - ph_one[PH_W-1:0] : phx_sum[PH_W-1:0];
    wire [PH_W-1:0] phy_next = sy_step ? phy_sum[PH_W-1:0] - ph_one[PH_W-1:0] : phy_sum[PH_W-1:0];
    assign wx = phase_weight(phx_q, cfg_ss_log2);
    assign wy = phase_weight(phy_q, cfg_ss_log2);
    // wz = r / S in Q0.W: r < 2^g, so the shift loses nothing
    wire [WEIGHT_W-1:0] r_ext = {{(WEIGHT_W - CFB_R_W){1'b0}}, r};
    assign wz    = r_ext << (WEIGHT_W[3:0] - {1'b0, g});
    assign steps = {old_sy_q, old_sx_q, sy_step, sx_step};

    always @(posedge clk) begin
        if (!rst) begin
            if (idle) begin
                phx_q    <= cfg_ph0_x;
                phy_q    <= cfg_ph0_y;
                old_sx_q <= ({1'b0, cfg_ph0_x} < (PH_W + 1)'(cfg_view_x));
                old_sy_q <= ({1'b0, cfg_ph0_y} < (PH_W + 1)'(cfg_view_y));
            end else if (next_pass) begin
                phx_q    <= phx_next;
                phy_q    <= phy_next;
                old_sx_q <= sx_step;
                old_sy_q <= sy_step;
            end
        end
    end
endmodule
`default_nettype wire

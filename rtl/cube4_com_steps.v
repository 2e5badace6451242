`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_steps
// -----------------------------------------------------------------------------
// Purpose
//   The steps and phases of each beat's slice on the beat schedule (BEATS = 1;
//   numerics.md section 19), for COM (cube4_com_beats reads them as c_geo):
//     stepx(m) = floor((PH0_X + m * VIEW_X) / 2^(W + g)),  ph_x(m) its remainder
//   (golden/cube4/view.py Traversal.steps), y alike, kept incrementally as the
//   beats pass (q_push): a phase accumulator per axis adds VIEW each time the
//   beats' slice moves on (slices arrive in order, each with at least one beat:
//   its marker), from PH0 at a frame's first beat (SOP), as cube4_cfb_steps
//   does a slice at a time. It sits where the beats leave SHA (cube4_top, at
//   the push into the skid buffer before COM), so the beat's q_geo goes through
//   the skid buffers to COM with it and no logic of it lies on the route
//   between the two.
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2 (CUBE4_SLICE_PARAMS; ranges as cube4_com).
//
// Latency
//   q_geo is combinational from q_hdr and the accumulators; the accumulators
//   move at q_push.
//
// Ports
//   clk          clock (no reset: a frame's first beat, SOP, loads the state)
//   cfg          in   [VIEW_W] view registers (VIEW_X/Y, PH0_X/Y, log2 S)
//   q_push       in   a beat passes (in the order COM takes the beats)
//   q_hdr        in   [HDR_W] its header (slice m, SOP)
//   q_geo        out  [GEO_W] {stepx, stepy [DIM_W], ph_x, ph_y [PHASE_W]}
//                     of the beat's slice (CUBE4_BEAT_GEO)
//
// Bit growth and rounding
//   None: the phases are W + g bits and wrap by design (the carry is the step);
//   a step count is at most M - 1 < 2^DIM_W when VIEW < 1 (Q1.W).
// =============================================================================
module cube4_com_steps #(
    `CUBE4_SLICE_PARAMS,
    localparam integer GEO_W = 2 * DIM_W + 2 * PHASE_W
) (
    input  wire clk,
    input  wire [VIEW_W-1:0] cfg,
    input  wire q_push, input wire [HDR_W-1:0] q_hdr,
    output wire [GEO_W-1:0] q_geo
);
    `CUBE4_VIEW_FIELDS(cfg);
    localparam integer PH_W = PHASE_W;
    wire [M_W-1:0] q_m   = q_hdr[HDR_M +: M_W];
    wire           q_sop = q_hdr[HDR_CTRL + CTRL_SOP];
    reg  [M_W-1:0]   cur_m;
    reg  [PH_W-1:0]  phx_q, phy_q;
    reg  [DIM_W-1:0] sx_q, sy_q;
    wire [2:0]      g      = {1'b0, cfg_ss_log2};
    wire [PH_W:0]   ph_one = {{PH_W{1'b0}}, 1'b1} << (WEIGHT_W[3:0] + {1'b0, g});
    `CUBE4_PHASE_FUNCTIONS
    wire [PH_W:0]    ax = phase_advance(phx_q, cfg_view_x, ph_one), ay = phase_advance(phy_q, cfg_view_y, ph_one);
    wire             q_new = !q_sop && (q_m != cur_m);     // the next slice (m + 1: every slice has a beat)
    wire [PH_W-1:0]  q_phx = q_sop ? cfg_ph0_x : (q_new ? ax[PH_W-1:0] : phx_q);
    wire [PH_W-1:0]  q_phy = q_sop ? cfg_ph0_y : (q_new ? ay[PH_W-1:0] : phy_q);
    wire [DIM_W-1:0] q_sx = q_sop ? '0 : sx_q + DIM_W'(q_new && ax[PH_W]);
    wire [DIM_W-1:0] q_sy = q_sop ? '0 : sy_q + DIM_W'(q_new && ay[PH_W]);
    always @(posedge clk) begin
        if (q_push) begin
            // the frame's first beat (SOP) is of slice 0 (steps 0, phase PH0)
            cur_m <= q_m;
            phx_q <= q_phx;
            phy_q <= q_phy;
            sx_q  <= q_sx;
            sy_q  <= q_sy;
        end
    end
    assign q_geo = {q_sx, q_sy, q_phx, q_phy};
endmodule
`default_nettype wire

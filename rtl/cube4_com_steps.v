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
//   beats pass (q_push). Slices arrive in order, each with at least one beat
//   (its marker), so a beat's slice is the one after the previous beat's when
//   that beat was the last of its slice (EOSS), and slice 0 after a frame's
//   last beat (EOP) or a reset. Registers hold the previous beat's slice's
//   {stepx, stepy, ph_x, ph_y} (cur) and the next slice's (nxt: cur advanced
//   by VIEW, a phase accumulator per axis), so a beat's q_geo is a choice
//   among registers by registers (first_q, eoss_q): nothing of the beat that
//   passes reaches q_geo, only the state's next values. It sits at COM's
//   input (cube4_top: the state moves as COM takes a beat from the skid
//   buffer after SHA, and q_geo enters COM's own skid with the beat), so its
//   clock enable is COM's take, beside COM, not the push into that skid
//   buffer, whose ready and SHA's output FIFO lie apart.
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2 (CUBE4_SLICE_PARAMS; ranges as cube4_com).
//
// Latency
//   q_geo is combinational from registers; the state moves at q_push.
//
// Ports
//   clk, rst     clock, synchronous active-high reset (the next beat is a
//                frame's first)
//   cfg          in   [VIEW_W] view registers (VIEW_X/Y, PH0_X/Y, log2 S),
//                static while a frame's beats pass
//   q_push       in   a beat passes (in the order COM takes the beats)
//   q_hdr        in   [HDR_W] its header (EOP: the frame's last beat)
//   q_eoss       in   it is the last beat of its slice
//   q_geo        out  [GEO_W] {stepx, stepy [DIM_W], ph_x, ph_y [PHASE_W]}
//                     of the beat's slice
//
// Bit growth and rounding
//   None: the phases are W + g bits and wrap by design (the carry is the step);
//   a step count is at most M - 1 < 2^DIM_W when VIEW < 1 (Q1.W).
// =============================================================================
module cube4_com_steps #(
    `CUBE4_SLICE_PARAMS,
    localparam integer GEO_W = `CUBE4_GEO_W
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    input  wire q_push, input wire [HDR_W-1:0] q_hdr, input wire q_eoss,
    output wire [GEO_W-1:0] q_geo
);
    `CUBE4_VIEW_FIELDS(cfg);
    `CUBE4_PHASE_FUNCTIONS
    localparam integer PH_W = PHASE_W;
    wire [2:0]    g      = {1'b0, cfg_ss_log2};
    wire [PH_W:0] ph_one = phase_one(g);
    // {stepx, stepy, ph_x, ph_y} one slice on
    function automatic [GEO_W-1:0] advance(input [GEO_W-1:0] geo);
        reg [DIM_W-1:0] sx, sy;
        reg [PH_W-1:0]  px, py;
        reg [PH_W:0]    ax, ay;
        begin
            {sx, sy, px, py} = geo;
            ax = phase_advance(px, cfg_view_x, ph_one);
            ay = phase_advance(py, cfg_view_y, ph_one);
            advance = {sx + DIM_W'(ax[PH_W]), sy + DIM_W'(ay[PH_W]), ax[PH_W-1:0], ay[PH_W-1:0]};
        end
    endfunction
    wire [GEO_W-1:0] geo0 = {{(2 * DIM_W){1'b0}}, cfg_ph0_x, cfg_ph0_y};   // slice 0
    reg              first_q;           // the next beat is a frame's first
    reg              eoss_q;            // the previous beat was its slice's last
    reg  [GEO_W-1:0] cur_q, nxt_q;      // the previous beat's slice, the one after it
    assign q_geo = first_q ? geo0 : (eoss_q ? nxt_q : cur_q);
    wire [GEO_W-1:0] nxt_d = first_q ? advance(geo0) : (eoss_q ? advance(nxt_q) : nxt_q);
    always @(posedge clk) begin
        if (rst) begin
            first_q <= 1'b1;
            eoss_q  <= 1'b0;
        end else if (q_push) begin
            first_q <= q_hdr[HDR_CTRL + CTRL_EOP];
            eoss_q  <= q_eoss;
        end
    end
    always @(posedge clk) begin
        if (q_push) begin
            cur_q <= q_geo;
            nxt_q <= nxt_d;
        end
    end
    wire unused_hdr = ^{q_hdr[HDR_W-1:HDR_CTRL+CTRL_EOP+1], q_hdr[HDR_CTRL+CTRL_EOP-1:0]};
endmodule
`default_nettype wire

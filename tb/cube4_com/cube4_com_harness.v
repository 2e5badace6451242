`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_com (tb/cube4_com): a Verilog clock, the view
//   registers as individual ports packed into COM's cfg bus
//   (CUBE4_VIEW_PACK), COM's shaded input and its finished-ray output as
//   top-level ports, which the testbench drives and reads every cycle (golden
//   shaded beats in with random gaps in valid; random ready out), and a
//   cube4_stream_check on each of the two streams. With BEATS = 1 the beats'
//   steps and phases come from cube4_com_steps at COM's input, as in cube4_top.
//
// Parameters: as cube4_com (P 1..64, WEIGHT_W 4..12, ALPHA_W 8..16,
//   ACC_W 8..24, VOXEL_W 1..16, COMPOSITING, EXTREMUM 0..1, MAX_DIM 2..2048,
//   MAX_SS_LOG2 0..3).
//
// Latency: that of cube4_com (the ports connect straight to it).
//
// Ports
//   clk       out  the harness's clock (cube4_sim_clock, 10 ns)
//   rst       in   synchronous reset
//   cfg_*     in   view registers (golden/cube4/memory.py top_regs)
//   rect_*, rt_*, stop_*  in   the rectangle (RECTS = 1) and stop (ZIN = 1) tables
//   in_*      in   shaded stream (cube4_sha's format, with in_sample and in_fall)
//   out_*     out  finished rays: cube4_com's pix_* (valid, ready, mask, m,
//                  by, bx, rgba, eop)
// =============================================================================
module cube4_com_harness #(
    `CUBE4_BUILD_PARAMS,
    `CUBE4_RECT_LAYOUT,
    `CUBE4_STOP_LAYOUT,
    // port widths by name (the runner's port scan takes no parentheses)
    localparam integer BX_W    = DIM_W + 1,
    localparam integer IN_W    = P * (24 + ALPHA_W),
    localparam integer PIX_W   = P * 4 * (ACC_W + 1),
    localparam integer PWC_W   = (PLW != 0) ? 4 * ALPHA_W : 1
) (
    output wire                  clk,
    input  wire                  rst,
    `CUBE4_VIEW_PORTS
    input  wire                  lut_we,
    input  wire [VOXEL_W-1:0]    lut_addr,
    input  wire [PWC_W-1:0]      lut_data,
    input  wire                  rect_we,     // write the rt_* fields as entry rect_addr (RECTS = 1)
    input  wire [M_W-1:0]        rect_addr,
    `CUBE4_RECT_PORTS
    input  wire                  stop_we,     // the stop table (ZIN = 1): one word of all P banks
    input  wire [STOP_AW-1:0]    stop_addr,
    input  wire [P*M_W-1:0]      stop_data,
    input  wire                  in_valid,
    output wire                  in_ready,
    input  wire [HDR_W-1:0]      in_hdr,
    input  wire [IN_W-1:0]       in_rgba,
    input  wire [P*VOXEL_W-1:0]  in_sample,
    input  wire [P*FALL_W-1:0]   in_fall,
    input  wire [4*P-1:0]        in_bits,     // BEATS = 1: {soon, last, fresh, run}
    input  wire                  in_eoss,     // BEATS = 1: the last beat of its slice
    input  wire                  frame_start, // BEATS = 1: termination and the reports
    input  wire                  term_en,
    input  wire [ACC_W:0]        term_tau,
    input  wire [VOXEL_W-1:0]    term_vmin,
    input  wire [VOXEL_W-1:0]    term_vmax,
    output wire                  rep_valid,
    output wire [DIM_W-1:0]      rep_j,
    output wire [PB_W-1:0]       rep_pb,
    output wire [DIM_W-1:0]      rep_stx,
    output wire [DIM_W-1:0]      rep_sty,
    output wire [P-1:0]          rep_en,
    output wire [P*M_W-1:0]      rep_end,
    output wire [M_W-1:0]        com_m,
    output wire                  out_valid,
    input  wire                  out_ready,
    output wire [P-1:0]          out_mask,
    output wire [M_W-1:0]        out_m,
    output wire [BX_W-1:0]       out_by,
    output wire [P*BX_W-1:0]     out_bx,
    output wire [PIX_W-1:0]      out_rgba,
    output wire                  out_eop,
    output wire [P*2*(M_W+1)-1:0] out_z
);
    cube4_sim_clock u_clock (.clk (clk));

    wire [VIEW_W-1:0] cfg = `CUBE4_VIEW_PACK;
    wire [RECT_W-1:0] rect_data = `CUBE4_RECT_PACK;

    // BEATS = 1: the steps and phases of each beat's slice, decided as it enters
    // (as cube4_top does where the beats leave SHA)
    wire [`CUBE4_GEO_W-1:0] in_geo;
    cube4_com_steps #(`CUBE4_SLICE_PASS) u_steps (
        .clk (clk), .rst (rst), .cfg (cfg), .q_push (in_valid && in_ready), .q_hdr (in_hdr), .q_eoss (in_eoss),
        .q_geo (in_geo));

    cube4_com #(
        `CUBE4_BUILD_PASS
    ) u_com (
        .clk       (clk),
        .rst       (rst),
        .cfg       (cfg),
        .lut_we    (lut_we),
        .lut_addr  (lut_addr),
        .lut_data  (lut_data),
        .rect_we   (rect_we),
        .rect_addr (rect_addr),
        .rect_data (rect_data),
        .stop_we   (stop_we),
        .stop_addr (stop_addr),
        .stop_data (stop_data),
        .in_valid  (in_valid),
        .in_ready  (in_ready),
        .in_hdr    (in_hdr),
        .in_rgba   (in_rgba),
        .in_sample (in_sample),
        .in_fall   (in_fall),
        .in_bits   (in_bits),
        .in_eoss   (in_eoss),
        .in_geo    (in_geo),
        .frame_start (frame_start),
        .term_en   (term_en),
        .term_tau  (term_tau),
        .term_vmin (term_vmin),
        .term_vmax (term_vmax),
        .rep_valid (rep_valid),
        .rep_j     (rep_j),
        .rep_pb    (rep_pb),
        .rep_stx   (rep_stx),
        .rep_sty   (rep_sty),
        .rep_en    (rep_en),
        .rep_end   (rep_end),
        .com_m     (com_m),
        .pix_valid (out_valid),
        .pix_ready (out_ready),
        .pix_mask  (out_mask),
        .pix_m     (out_m),
        .pix_by    (out_by),
        .pix_bx    (out_bx),
        .pix_rgba  (out_rgba),
        .pix_eop   (out_eop),
        .pix_z     (out_z)
    );

    cube4_stream_check #(
        .NAME   ("com.in (shaded)"),
        .DATA_W (HDR_W + IN_W + P * VOXEL_W + P * FALL_W + 4 * P + 1)
    ) u_chk_in (
        .clk   (clk),
        .rst   (rst),
        .valid (in_valid),
        .ready (in_ready),
        .data  ({in_hdr, in_rgba, in_sample, in_fall, in_bits, in_eoss})
    );

    cube4_stream_check #(
        .NAME   ("com.out (pixels)"),
        .DATA_W (P + M_W + BX_W + P * BX_W + PIX_W + 1 + P * 2 * (M_W + 1))
    ) u_chk_out (
        .clk   (clk),
        .rst   (rst),
        .valid (out_valid),
        .ready (out_ready),
        .data  ({out_mask, out_m, out_by, out_bx, out_rgba, out_eop, out_z})
    );

endmodule
`default_nettype wire

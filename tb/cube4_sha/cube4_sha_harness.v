`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_sha_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_sha (tb/cube4_sha): a Verilog clock, SHA's
//   table load ports, its gradient input and shaded output as top-level ports,
//   which the testbench drives and reads every cycle (golden gradient beats
//   in with random gaps in valid; random ready out), and a cube4_stream_check
//   on each of the two streams. The view registers (cfg_*) reach SHA's slab
//   unit only (SLAB = 1).
//
// Parameters: as cube4_sha (P 1..64, VOXEL_W 1..16, ALPHA_W 8..16,
//   RMAP_BITS 2..6, SHADING 0..1, CARRY_SAMPLE 0..1, VALID_N 1..4, SLAB 0..1, MAX_DIM 2..2048,
//   MAX_SS_LOG2 0..3).
//
// Latency: that of cube4_sha (the ports connect straight to it).
//
// Ports
//   clk             out  the harness's clock (cube4_sim_clock, 10 ns)
//   rst             in   synchronous reset
//   cfg_*           in   view registers (cube4_defs.vh)
//   lut_*, rmap_*   in   table writes (cube4_sha)
//   in_*            in   gradient stream (cube4_gra's format)
//   out_*           out  shaded stream (cube4_sha's format, with out_idx and
//                        out_sample; out_valid_cp: out_valid's copies)
// =============================================================================
module cube4_sha_harness #(
    `CUBE4_BUILD_PARAMS, parameter integer CARRY_SAMPLE = 1, parameter integer VALID_N = 1,
    `CUBE4_GM_LAYOUT,
    localparam integer GRAD_W = VOXEL_W + 5,
    localparam integer SMP_W  = VOXEL_W + ((LABELS != 0) ? 4 : 0),   // a sample: {label, value}
    localparam integer RI_W   = 2 * RMAP_BITS + 3,
    localparam integer RGBA_W = P * (24 + ALPHA_W)   // out_rgba (a name, for the runner's port scan)
) (
    output wire                      clk,
    input  wire                      rst,
    `CUBE4_VIEW_PORTS
    input  wire                      lut_we,
    input  wire [SMP_W-1:0]          lut_addr,
    input  wire [24+ALPHA_W-1:0]     lut_data,
    input  wire                      rmap_we,
    input  wire [RI_W-1:0]           rmap_addr,
    input  wire [19:0]               rmap_data,
    input  wire                      gm_we,       // the modulation table (GMOD = 1): {fa, fs}
    input  wire [GMA_W-1:0]          gm_addr,
    input  wire [2*GMF_W-1:0]        gm_data,
    input  wire                      in_valid,
    output wire                      in_ready,
    `CUBE4_GRA_BEAT_PORTS(input, in)
    output wire                      out_valid,
    input  wire                      out_ready,
    output wire [HDR_W-1:0]          out_hdr,
    output wire [RGBA_W-1:0]         out_rgba,
    output wire [P*RI_W-1:0]         out_idx,
    output wire [P*VOXEL_W-1:0]      out_sample,
    output wire [P*FALL_W-1:0]       out_fall,
    output wire [VALID_N-1:0]        out_valid_cp
);
    cube4_sim_clock u_clock (.clk (clk));

    wire [VIEW_W-1:0] cfg = `CUBE4_VIEW_PACK;

    cube4_sha #(
        `CUBE4_BUILD_PASS,
        .CARRY_SAMPLE(CARRY_SAMPLE),
        .VALID_N     (VALID_N)
    ) u_sha (.*);

    cube4_stream_check #(
        .NAME   ("sha.in (gradients)"),
        .DATA_W (HDR_W + P * SMP_W + 3 * P * GRAD_W)
    ) u_chk_in (
        .clk   (clk),
        .rst   (rst),
        .valid (in_valid),
        .ready (in_ready),
        .data  ({in_hdr, in_sample, in_gi, in_gj, in_gk})
    );

    cube4_stream_check #(
        .NAME   ("sha.out (shaded)"),
        .DATA_W (HDR_W + RGBA_W + P * RI_W + P * VOXEL_W + P * FALL_W)
    ) u_chk_out (
        .clk   (clk),
        .rst   (rst),
        .valid (out_valid),
        .ready (out_ready),
        .data  ({out_hdr, out_rgba, out_idx, out_sample, out_fall})
    );

endmodule
`default_nettype wire

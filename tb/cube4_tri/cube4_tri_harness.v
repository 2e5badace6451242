`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_tri_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_tri (tb/cube4_tri). TRI's input is the memory's
//   response beats (voxels + cube4_cfb's tag); the exact source of those is
//   cube4_cfb reading cube4_voxel_mem, so the harness contains both, with a
//   seeded random stall generator (cube4_sim_stall) on the memory request and
//   one on the memory response, i.e. on TRI's input. TRI's sample output is a
//   top-level port that the testbench reads every cycle with random ready.
//   A cube4_stream_check watches TRI's input and its output stream.
//   The testbench loads the volume through the memory's load port
//   (golden/cube4/memory.py pack_volume: word a of bank q; with VGRAD = 1 the
//   words of golden/cube4/vgrad.py), sets the
//   registers and pulses start.
//
// Parameters: as cube4_tri (P 1..64, VOXEL_W 1..16, WEIGHT_W 4..12,
//   MAX_DIM 2..2048, MAX_SS_LOG2 0..3, CLIP 0..1, VGRAD 0..1, LABELS 0..1), plus DEPTH (words per bank, >= 2)
//   and ADDR_W (bank address width, 1..30) of the memory.
//
// Latency: TRI's, plus one cycle in each stall generator.
//
// Ports
//   clk                    out  the harness's clock (cube4_sim_clock, 10 ns)
//   rst                    in   synchronous reset
//   seed                   in   [32] the test's random seed (COCOTB_RANDOM_SEED)
//   stall_req, stall_in    in   [8] stall probability /256 of the memory request
//                               and of TRI's input (the memory response)
//   ld_valid/addr/data     in   memory load port (cube4_voxel_mem)
//   start                  in   pulse: cube4_cfb starts a frame
//   cfg_*                  in   view and address registers (memory.py top_regs)
//   out_*                  out  TRI's sample stream (cube4_defs.vh)
// =============================================================================
module cube4_tri_harness #(
    parameter integer P           = 8,
    parameter integer VOXEL_W     = 8,
    parameter integer WEIGHT_W    = 8,
    parameter integer MAX_DIM     = 32,
    parameter integer MAX_SS_LOG2 = 0,
    parameter integer DEPTH       = 4096,
    parameter integer ADDR_W      = 12,
    parameter integer CLIP        = 1,
    parameter integer VGRAD       = 0,
    parameter integer LABELS      = 0,
    `CUBE4_GEOMETRY,
    `CUBE4_VIEW_LAYOUT,
    `CUBE4_ADDR_LAYOUT,
    `CUBE4_TAG_LAYOUT,
    `CUBE4_RECT_LAYOUT,
    `CUBE4_WORD_LAYOUT
) (
    output wire                  clk,
    input  wire                  rst,
    input  wire [31:0]           seed,
    input  wire [7:0]            stall_req,
    input  wire [7:0]            stall_in,
    input  wire                  ld_valid,
    output wire                  ld_ready,
    input  wire [ADDR_W-1:0]     ld_addr,
    input  wire [P*WORD_W-1:0]   ld_data,
    input  wire                  start,
    `CUBE4_VIEW_PORTS
    `CUBE4_ADDR_PORTS
    output wire                  out_valid,
    input  wire                  out_ready,
    output wire [HDR_W-1:0]      out_hdr,
    output wire [P*WORD_W-1:0]   out_sample
);
    localparam integer PV    = P * WORD_W;
    localparam integer REQ_W = P * ADDR_W + P + TAG_W;

    cube4_sim_clock u_clock (.clk (clk));

    wire [VIEW_W-1:0]    cfg      = `CUBE4_VIEW_PACK;
    wire [ADR_W_ALL-1:0] cfg_addr = `CUBE4_ADDR_PACK;

    // ------------------------------------------------------------ CFB -> memory
    wire               unused_cfb_busy;
    wire               c_req_valid, c_req_ready, req_valid, req_ready;
    wire [REQ_W-1:0]   c_req, req;
    wire [4*P-1:0] unused_bits;   // the beat schedule's (not this build's)
    wire           unused_eos, unused_eoss;
    cube4_cfb #(
        .P           (P),
        .MAX_DIM     (MAX_DIM),
        .ADDR_W      (ADDR_W),
        .WEIGHT_W    (WEIGHT_W),
        .MAX_SS_LOG2 (MAX_SS_LOG2)
    ) u_cfb (
        .clk       (clk),
        .rst       (rst),
        .start     (start),
        .busy      (unused_cfb_busy),
        .cfg       (cfg),
        .cfg_addr  (cfg_addr),
        .rect_we   (1'b0),               // the fixed schedule (RECTS = 0)
        .rect_addr ({M_W{1'b0}}),
        .rect_data ({RECT_W{1'b0}}),
        `CUBE4_BEATS_IN_NONE,
        .req_bits  (unused_bits),
        .req_eos   (unused_eos),
        .req_eoss  (unused_eoss),
        .req_valid (c_req_valid),
        .req_ready ({`CUBE4_CFB_ADV_N{c_req_ready}}),   // its copies, one per advance
        .req_addr  (c_req[TAG_W + P +: P * ADDR_W]),
        .req_rden  (c_req[TAG_W +: P]),
        .req_tag   (c_req[0 +: TAG_W])
    );

    cube4_sim_stall #(
        .DATA_W (REQ_W),
        .STREAM (0)
    ) u_stall_req (
        .clk       (clk),
        .rst       (rst),
        .seed      (seed),
        .stall     (stall_req),
        .in_valid  (c_req_valid),
        .in_ready  (c_req_ready),
        .in_data   (c_req),
        .out_valid (req_valid),
        .out_ready (req_ready),
        .out_data  (req)
    );

    wire              rsp_valid, rsp_ready, in_valid, in_ready;
    wire [PV-1:0]     rsp_data, in_data;
    wire [TAG_W-1:0]  rsp_tag, in_tag;
    cube4_voxel_mem #(
        .P       (P),
        .WORD_W  (WORD_W),
        .DEPTH   (DEPTH),
        .ADDR_W  (ADDR_W),
        .TAG_W   (TAG_W)
    ) u_mem (
        .clk       (clk),
        .rst       (rst),
        .ld_valid  (ld_valid),
        .ld_ready  (ld_ready),
        .ld_addr   (ld_addr),
        .ld_data   (ld_data),
        .req_valid (req_valid),
        .req_ready (req_ready),
        .req_addr  (req[TAG_W + P +: P * ADDR_W]),
        .req_rden  (req[TAG_W +: P]),
        .req_tag   (req[0 +: TAG_W]),
        .rsp_valid (rsp_valid),
        .rsp_ready (rsp_ready),
        .rsp_data  (rsp_data),
        .rsp_tag   (rsp_tag)
    );

    // ------------------------------------------------------------ memory -> stall -> TRI
    cube4_sim_stall #(
        .DATA_W (PV + TAG_W),
        .STREAM (1)
    ) u_stall_in (
        .clk       (clk),
        .rst       (rst),
        .seed      (seed),
        .stall     (stall_in),
        .in_valid  (rsp_valid),
        .in_ready  (rsp_ready),
        .in_data   ({rsp_data, rsp_tag}),
        .out_valid (in_valid),
        .out_ready (in_ready),
        .out_data  ({in_data, in_tag})
    );

    cube4_tri #(
        .P           (P),
        .VOXEL_W     (VOXEL_W),
        .WEIGHT_W    (WEIGHT_W),
        .MAX_DIM     (MAX_DIM),
        .MAX_SS_LOG2 (MAX_SS_LOG2),
        .CLIP        (CLIP),
        .VGRAD       (VGRAD),
        .LABELS      (LABELS)
    ) u_tri (
        .clk        (clk),
        .rst        (rst),
        .cfg        (cfg),
        .in_valid   (in_valid),
        .in_ready   (in_ready),
        .in_tag     (in_tag),
        .in_data    (in_data),
        .out_valid  (out_valid),
        .out_ready  (out_ready),
        .out_hdr    (out_hdr),
        .out_sample (out_sample)
    );

    cube4_stream_check #(
        .NAME   ("tri.in (memory response)"),
        .DATA_W (PV + TAG_W)
    ) u_chk_in (
        .clk   (clk),
        .rst   (rst),
        .valid (in_valid),
        .ready (in_ready),
        .data  ({in_data, in_tag})
    );

    cube4_stream_check #(
        .NAME   ("tri.out (samples)"),
        .DATA_W (HDR_W + PV)
    ) u_chk_out (
        .clk   (clk),
        .rst   (rst),
        .valid (out_valid),
        .ready (out_ready),
        .data  ({out_hdr, out_sample})
    );

endmodule
`default_nettype wire

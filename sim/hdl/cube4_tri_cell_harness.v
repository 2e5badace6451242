`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_tri_cell_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of TRI's cell path (tb/cube4_tri_src, tb/cube4_tri_beam):
//   cube4_tri_src and cube4_tri_beam behind their one exact source of beats,
//   cube4_cfb reading cube4_voxel_mem, with a seeded random stall generator
//   (cube4_sim_stall) on the memory request and one on the memory response,
//   which is the units' input. The units have no output stream (they move on
//   every cycle, TRI's FIFO credit gates their input): here every response
//   beat is taken when offered, and the testbench reads s1's and s4's beats
//   every cycle. A cube4_stream_check watches the units' input stream.
//
// Parameters: as cube4_tri_src (P 1..64, VOXEL_W 1..16, WEIGHT_W 4..12,
//   MAX_DIM 2..2048, MAX_SS_LOG2 0..3, VGRAD 0..1), plus DEPTH (words per
//   bank, >= 2) and ADDR_W (bank address width, 1..30) of the memory.
//
// Latency: the units', plus one cycle in each stall generator.
//
// Ports
//   clk                    out  the harness's clock (cube4_sim_clock, 10 ns)
//   rst, seed, stall_req, stall_in, ld_*, start, cfg_*   in   as cube4_tri_harness
//   s1_*, s3_wx, give, s4_*  out  cube4_tri_src's and cube4_tri_beam's outputs
// =============================================================================
module cube4_tri_cell_harness #(
    // (the build parameters by name, not CUBE4_TRI_PARAMS: the testbench reads them)
    parameter integer P = 8, parameter integer MAX_DIM = 32, parameter integer VOXEL_W = 8,
    parameter integer MAX_SS_LOG2 = 0, parameter integer WEIGHT_W = 8, parameter integer VGRAD = 0,
    parameter integer LABELS = 0,   // (the cell tests run without labels; CUBE4_WORD_LAYOUT reads it)
    parameter integer DEPTH = 4096, parameter integer ADDR_W = 12,
    `CUBE4_GEOMETRY, `CUBE4_TAG_LAYOUT, `CUBE4_WORD_LAYOUT, `CUBE4_TRI_LAYOUT,
    `CUBE4_VIEW_LAYOUT, `CUBE4_ADDR_LAYOUT, `CUBE4_RECT_LAYOUT
) (
    output wire clk, input wire rst, input wire [31:0] seed,
    input  wire [7:0] stall_req, input wire [7:0] stall_in,
    input  wire ld_valid, output wire ld_ready, input wire [ADDR_W-1:0] ld_addr,
    input  wire [P*WORD_W-1:0] ld_data,
    input  wire start,
    `CUBE4_VIEW_PORTS
    `CUBE4_ADDR_PORTS
    output wire s1_v, output wire [2*P*WORD_W-1:0] s1_pair, output wire [TRI_C_W-1:0] s1_ctl,
    output wire [WEIGHT_W-1:0] s3_wx, output wire give,
    output wire s4_v, output wire [4*P*WORD_W-1:0] s4_vals, output wire [4*P*WORD_W-1:0] s4_nvals,
    output wire [4*P*WORD_W-1:0] s3_cell, output wire [4*P*WORD_W-1:0] s3_ncell,
    output wire [WEIGHT_W-1:0] s4_wx, output wire [WEIGHT_W-1:0] s4_wy, output wire [WEIGHT_W-1:0] s4_wz,
    output wire [HDR_W-1:0] s4_meta
);
    localparam integer PV    = P * WORD_W;
    localparam integer REQ_W = P * ADDR_W + P + TAG_W;

    cube4_sim_clock u_clock (.clk(clk));
    wire [VIEW_W-1:0] cfg = `CUBE4_VIEW_PACK;

    // CFB -> stall -> memory -> stall -> the units (taken when offered)
    wire             unused_busy, c_valid, c_ready, r_valid, r_ready, m_valid, m_ready, in_valid;
    wire [REQ_W-1:0] c_req, r_req;
    wire [PV-1:0]    m_data, in_data;
    wire [TAG_W-1:0] m_tag, in_tag;
    wire [4*P-1:0] unused_bits;   // the beat schedule's (not this build's)
    wire           unused_eos, unused_eoss;
    cube4_cfb #(.P(P), .MAX_DIM(MAX_DIM), .ADDR_W(ADDR_W), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2)) u_cfb (
        .clk(clk), .rst(rst), .start(start), .busy(unused_busy), .cfg(cfg), .cfg_addr(`CUBE4_ADDR_PACK),
        .rect_we(1'b0), .rect_addr({M_W{1'b0}}), .rect_data({RECT_W{1'b0}}),   // the fixed schedule
        `CUBE4_BEATS_IN_NONE, .req_bits(unused_bits), .req_eos(unused_eos), .req_eoss(unused_eoss),
        .req_valid(c_valid), .req_ready({`CUBE4_CFB_ADV_N{c_ready}}), .req_addr(c_req[TAG_W + P +: P * ADDR_W]),
        .req_rden(c_req[TAG_W +: P]), .req_tag(c_req[0 +: TAG_W]));
    cube4_sim_stall #(.DATA_W(REQ_W), .STREAM(0)) u_stall_req (
        .clk(clk), .rst(rst), .seed(seed), .stall(stall_req), .in_valid(c_valid), .in_ready(c_ready),
        .in_data(c_req), .out_valid(r_valid), .out_ready(r_ready), .out_data(r_req));
    cube4_voxel_mem #(.P(P), .WORD_W(WORD_W), .DEPTH(DEPTH), .ADDR_W(ADDR_W), .TAG_W(TAG_W)) u_mem (
        .clk(clk), .rst(rst), .ld_valid(ld_valid), .ld_ready(ld_ready), .ld_addr(ld_addr), .ld_data(ld_data),
        .req_valid(r_valid), .req_ready(r_ready), .req_addr(r_req[TAG_W + P +: P * ADDR_W]),
        .req_rden(r_req[TAG_W +: P]), .req_tag(r_req[0 +: TAG_W]),
        .rsp_valid(m_valid), .rsp_ready(m_ready), .rsp_data(m_data), .rsp_tag(m_tag));
    cube4_sim_stall #(.DATA_W(PV + TAG_W), .STREAM(1)) u_stall_in (
        .clk(clk), .rst(rst), .seed(seed), .stall(stall_in), .in_valid(m_valid), .in_ready(m_ready),
        .in_data({m_data, m_tag}), .out_valid(in_valid), .out_ready(1'b1), .out_data({in_data, in_tag}));
    cube4_stream_check #(.NAME("tri cells.in (memory response)"), .DATA_W(PV + TAG_W)) u_chk_in (
        .clk(clk), .rst(rst), .valid(in_valid), .ready(1'b1), .data({in_data, in_tag}));

    wire s1_ywrap, s1_bbwe;
    wire [PB_W-1:0] s1_pb;
    cube4_tri_src #(
        .P(P), .MAX_DIM(MAX_DIM), .VOXEL_W(VOXEL_W), .MAX_SS_LOG2(MAX_SS_LOG2), .WEIGHT_W(WEIGHT_W), .VGRAD(VGRAD)
    ) u_src (
        .clk(clk), .rst(rst), .take(in_valid), .in_tag(in_tag), .in_data(in_data), .flip_k(cfg_flip_k),
        .s1_v(s1_v), .s1_pair(s1_pair), .s1_ywrap(s1_ywrap), .s1_bbwe(s1_bbwe), .s1_pb(s1_pb), .s1_ctl(s1_ctl));
    cube4_tri_beam #(
        .P(P), .MAX_DIM(MAX_DIM), .VOXEL_W(VOXEL_W), .MAX_SS_LOG2(MAX_SS_LOG2), .WEIGHT_W(WEIGHT_W), .VGRAD(VGRAD)
    ) u_beam (
        .clk(clk), .rst(rst), .flip_j(cfg_flip_j), .flip_i(cfg_flip_i),
        .s1_v(s1_v), .s1_pair(s1_pair), .s1_ywrap(s1_ywrap), .s1_bbwe(s1_bbwe), .s1_pb(s1_pb), .s1_ctl(s1_ctl),
        .s3_wx(s3_wx), .give(give), .s4_v(s4_v), .s4_vals(s4_vals), .s4_nvals(s4_nvals),
        .s3_cell(s3_cell), .s3_ncell(s3_ncell),
        .s4_wx(s4_wx), .s4_wy(s4_wy), .s4_wz(s4_wz), .s4_meta(s4_meta));
endmodule
`default_nettype wire

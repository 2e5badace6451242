`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_seq_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_com_seq (tb/cube4_com_seq): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus
//   (CUBE4_VIEW_PACK), every other port of the unit as a top-level port, and
//   a cube4_stream_check on the input stream.
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W as cube4_com_seq; the slot
//   width as cube4_com derives it without rectangles.
//
// Latency: that of cube4_com_seq (the ports connect straight to it).
//
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports.
// =============================================================================
module cube4_com_seq_harness #(
    parameter integer P           = 5,
    parameter integer MAX_DIM     = 32,
    parameter integer MAX_SS_LOG2 = 0,
    parameter integer WEIGHT_W    = 8,
    `CUBE4_GEOMETRY,
    `CUBE4_VIEW_LAYOUT,
    localparam integer SP_W  = (MAX_DIM * NBMAX > 1) ? $clog2(MAX_DIM * NBMAX) : 1,
    localparam integer SPF_W = 9 * SP_W,
    localparam integer PI_W  = P * IW,
    localparam integer BX_W  = DIM_W + 1,
    localparam integer PBX_W = P * BX_W
) (
    output wire              clk,
    input  wire              rst,
    `CUBE4_VIEW_PORTS
    input  wire              in_valid,
    output wire              in_ready,
    input  wire [HDR_W-1:0]  in_hdr,
    output wire              take,
    input  wire              credit,
    input  wire              hazard,
    output wire              step,
    output wire [1:0]        step_c,
    output wire [M_W-1:0]    r0_m,
    output wire [DIM_W-1:0]  r0_j,
    output wire [PB_W-1:0]   r0_pb,
    output wire              sop,
    output wire              first,
    output wire              dxb,
    output wire              dyb,
    output wire [PI_W-1:0]   ipos,
    output wire [PI_W-1:0]   f1_ipos,
    output wire [IW-1:0]     f1_j,
    output wire              f1_dxf,
    output wire              f1_dyf,
    input  wire [SP_W-1:0]   pos_sp,
    input  wire [PB_W-1:0]   pos_pb,
    input  wire [P-1:0]      fresh,
    input  wire [DIM_W-1:0]  stx,
    input  wire [DIM_W-1:0]  sty,
    input  wire [P-1:0]      nx_in,
    output wire [10:1]       v_s,
    output wire [SPF_W-1:0]  sp_fly,
    output wire [SP_W-1:0]   sp_wr,
    output wire [PB_W-1:0]   pb_rd,
    output wire [PB_W-1:0]   pb_wr,
    output wire              dxb4,
    output wire              dyb4,
    output wire              dkb4,
    output wire [P-1:0]      t0_4,
    output wire [P-1:0]      fresh_4,
    output wire [P-1:0]      cnt_6,
    output wire [P-1:0]      cnt_7,
    output wire              mode_xray,
    output wire              mode_ext,
    output wire              mode_min,
    output wire              push_d,
    output wire              give,
    output wire [P-1:0]      fin_o,
    output wire [M_W-1:0]    m_o,
    output wire [BX_W-1:0]   by_o,
    output wire [PBX_W-1:0]  bx_o,
    output wire              eop_o
);
    cube4_sim_clock u_clock (.clk (clk));
    wire [VIEW_W-1:0] cfg = `CUBE4_VIEW_PACK;
    cube4_com_seq #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .SP_W(SP_W)
    ) u_seq (
        .clk(clk), .rst(rst), .cfg(cfg),
        .in_valid(in_valid), .in_ready(in_ready), .in_hdr(in_hdr),
        .take(take), .credit(credit), .hazard(hazard), .step(step), .step_c(step_c),
        .r0_m(r0_m), .r0_j(r0_j), .r0_pb(r0_pb), .sop(sop), .first(first), .dxb(dxb), .dyb(dyb),
        .ipos(ipos), .f1_ipos(f1_ipos), .f1_j(f1_j), .f1_dxf(f1_dxf), .f1_dyf(f1_dyf),
        .pos_sp(pos_sp), .pos_pb(pos_pb), .fresh(fresh), .stx(stx), .sty(sty), .nx_in(nx_in),
        .v_s(v_s), .sp_fly(sp_fly), .sp_wr(sp_wr), .pb_rd(pb_rd), .pb_wr(pb_wr),
        .dxb4(dxb4), .dyb4(dyb4), .dkb4(dkb4), .t0_4(t0_4), .fresh_4(fresh_4),
        .cnt_6(cnt_6), .cnt_7(cnt_7),
        .mode_xray(mode_xray), .mode_ext(mode_ext), .mode_min(mode_min),
        .push_d(push_d), .give(give),
        .fin_o(fin_o), .m_o(m_o), .by_o(by_o), .bx_o(bx_o), .eop_o(eop_o));
    cube4_stream_check #(.NAME("com_seq.in (shaded headers)"), .DATA_W(HDR_W)) u_chk_in (
        .clk(clk), .rst(rst), .valid(in_valid), .ready(in_ready), .data(in_hdr));
endmodule
`default_nettype wire

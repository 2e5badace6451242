`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_com_seq_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_com_seq (tb/cube4_com_seq): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus
//   (CUBE4_VIEW_PACK), every other port of the unit as a top-level port, and
//   a cube4_stream_check on the input stream.
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W as cube4_com_seq
//   (CUBE4_UNIT_PARAMS); T_R0 as cube4_com_seq (0..1, default 0; 1: the lanes'
//   positions registered at R0, as BEATS builds it); the slot width as
//   cube4_com derives it without rectangles.
//
// Latency: that of cube4_com_seq (the ports connect straight to it).
//
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports
//   (the groups shared with cube4_com_walk and _rect: cube4_unit_ports.vh).
// =============================================================================
module cube4_com_seq_harness #(
    `CUBE4_UNIT_PARAMS
    parameter  integer T_R0  = 0,
    localparam integer SP_W  = (MAX_DIM * NBMAX > 1) ? $clog2(MAX_DIM * NBMAX) : 1,
    localparam integer BX_W  = DIM_W + 1
) (
    `CUBE4_HARNESS_PORTS
    `CUBE4_COM_STEP_PORTS(output)
    `CUBE4_COM_SLOT_PORTS(input)
    input  wire               in_valid,
    output wire               in_ready,
    input  wire [HDR_W-1:0]   in_hdr,
    output wire               take,
    input  wire               credit,
    output wire               step,
    output wire [1:0]         step_c,
    output wire [PB_W-1:0]    r0_pb,
    output wire               sop,
    output wire               first,
    output wire [10:1]        v_s,
    output wire [9*SP_W-1:0]  sp_fly,
    output wire [SP_W-1:0]    sp_wr,
    output wire [PB_W-1:0]    pb_rd,
    output wire [PB_W-1:0]    pb_wr,
    output wire               dxb4,
    output wire               dyb4,
    output wire               dkb4,
    output wire [P-1:0]       t0_4,
    output wire [P-1:0]       fresh_4,
    output wire [P*LANE_W-1:0] tpos,      // S0: the lanes' positions t
    input  wire [P-1:0]       keep_5,     // S5: depth in's ok (ANDed into S6's counts)
    output wire [P-1:0]       cnt_6,
    output wire [P-1:0]       cnt_7,
    output wire               mode_xray,
    output wire               mode_ext,
    output wire               mode_min,
    output wire               push_d,
    output wire               give,
    output wire [P-1:0]       fin_o,
    output wire [M_W-1:0]     m_o,
    output wire [BX_W-1:0]    by_o,
    output wire [P*BX_W-1:0]  bx_o,
    output wire               eop_o
);
    `CUBE4_HARNESS_VIEW
    wire [P-1:0] fin_5 = '0;     // (the beat schedule's countdown: cube4_com's)
    wire [P-1:0] run0  = '1;     // (the beat schedule's run bits: cube4_com's)
    cube4_com_seq #(`CUBE4_SLICE_PASS, .SP_W(SP_W), .T_R0(T_R0)) u_seq (.*);
    cube4_stream_check #(.NAME("com_seq.in (shaded headers)"), .DATA_W(HDR_W)) u_chk_in (
        .clk(clk), .rst(rst), .valid(in_valid), .ready(in_ready), .data(in_hdr));
endmodule
`default_nettype wire

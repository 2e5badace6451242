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
//   (cube4_unit_params.vh); the slot width as cube4_com derives it without
//   rectangles.
//
// Latency: that of cube4_com_seq (the ports connect straight to it).
//
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports
//   (the groups shared with cube4_com_walk and _rect: cube4_unit_ports.vh).
// =============================================================================
module cube4_com_seq_harness #(
    `include "cube4_unit_params.vh"
    localparam integer SP_W  = (MAX_DIM * NBMAX > 1) ? $clog2(MAX_DIM * NBMAX) : 1,
    localparam integer BX_W  = DIM_W + 1
) (
    output wire               clk,
    input  wire               rst,
    `CUBE4_VIEW_PORTS
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
    cube4_sim_clock u_clock (.clk (clk));
    wire [VIEW_W-1:0] cfg = `CUBE4_VIEW_PACK;
    cube4_com_seq #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .SP_W(SP_W)
    ) u_seq (.*);
    cube4_stream_check #(.NAME("com_seq.in (shaded headers)"), .DATA_W(HDR_W)) u_chk_in (
        .clk(clk), .rst(rst), .valid(in_valid), .ready(in_ready), .data(in_hdr));
endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_com_rect_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_com_rect (tb/cube4_com_rect): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus
//   (CUBE4_VIEW_PACK), every other port of the unit as a top-level port (the
//   table entry rect_data as one word, CUBE4_RECT_LAYOUT).
//
// Parameters: P, MAX_DIM, ADDR_W as cube4_com_rect (MAX_SS_LOG2 = 0;
//   CUBE4_UNIT_PARAMS); the slot width as cube4_com derives it.
//
// Latency: that of cube4_com_rect (the ports connect straight to it).
//
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports
//   (the groups shared with cube4_com_seq: cube4_unit_ports.vh).
// =============================================================================
module cube4_com_rect_harness #(
    `CUBE4_UNIT_PARAMS
    parameter integer ADDR_W = 16,
    `CUBE4_RECT_LAYOUT,
    localparam integer SP_W  = ((MAX_DIM > 1) ? $clog2(MAX_DIM) : 1) + PB_W
) (
    `CUBE4_HARNESS_PORTS
    `CUBE4_COM_STEP_PORTS(input)
    `CUBE4_COM_SLOT_PORTS(output)
    input  wire              rect_we,
    input  wire [M_W-1:0]    rect_addr,
    input  wire [RECT_W-1:0] rect_data,
    input  wire              take,
    input  wire [HDR_W-1:0]  in_hdr,
    input  wire              step,
    input  wire [9:1]        v_fly,
    input  wire [9*SP_W-1:0] sp_fly,
    input  wire [PB_W-1:0]   r0_pb,
    output wire              col1_4
);
    `CUBE4_HARNESS_VIEW
    cube4_com_rect #(`CUBE4_SLICE_PASS, .ADDR_W(ADDR_W), .SP_W(SP_W)) u_rect (.*);
endmodule
`default_nettype wire

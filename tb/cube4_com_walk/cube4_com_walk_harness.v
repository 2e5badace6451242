`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_com_walk_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_com_walk (tb/cube4_com_walk): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus
//   (CUBE4_VIEW_PACK), every other port of the unit as a top-level port.
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W as cube4_com_walk
//   (CUBE4_UNIT_PARAMS); the slot width as cube4_com derives it.
//
// Latency: that of cube4_com_walk (the ports connect straight to it).
//
// Ports: clk out (cube4_sim_clock, 10 ns); rst, cfg_* and the unit's ports
//   (the groups shared with cube4_com_seq and _plw: cube4_unit_ports.vh).
// =============================================================================
module cube4_com_walk_harness #(
    `CUBE4_UNIT_PARAMS
    localparam integer SP_W = (MAX_DIM * NBMAX > 1) ? $clog2(MAX_DIM * NBMAX) : 1
) (
    `CUBE4_HARNESS_PORTS
    `CUBE4_COM_STEP_PORTS(input)
    `CUBE4_COM_SLOT_PORTS(output)
    `CUBE4_COM_PHASE_PORTS(output)
    input  wire [1:0] step_c,
    input  wire       take,
    input  wire       step,
    input  wire [8:1] v_fly,
    input  wire       sop,
    input  wire       first
);
    `CUBE4_HARNESS_VIEW
    cube4_com_walk #(`CUBE4_SLICE_PASS, .SP_W(SP_W)) u_walk (.*);
endmodule
`default_nettype wire

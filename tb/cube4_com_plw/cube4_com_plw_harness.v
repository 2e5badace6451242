`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_com_plw_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_com_plw (tb/cube4_com_plw): a Verilog clock,
//   the view registers as ports packed into the unit's cfg bus
//   (CUBE4_VIEW_PACK), every other port of the unit as a top-level port.
//
// Parameters: P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W (CUBE4_UNIT_PARAMS), VOXEL_W,
//   ALPHA_W as cube4_com_plw.
//
// Latency: that of cube4_com_plw (the ports connect straight to it).
//
// Ports: clk out (cube4_sim_clock, 10 ns); rst (unused by the unit), cfg_*
//   and the unit's ports (the groups from cube4_com_seq and _walk:
//   cube4_unit_ports.vh).
// =============================================================================
module cube4_com_plw_harness #(
    `CUBE4_UNIT_PARAMS
    parameter integer VOXEL_W = 8,
    parameter integer ALPHA_W = 12
) (
    `CUBE4_HARNESS_PORTS
    `CUBE4_COM_STEP_PORTS(input)
    `CUBE4_COM_PHASE_PORTS(input)
    input  wire                   step,
    input  wire                   first,
    input  wire                   lut_we,
    input  wire [VOXEL_W-1:0]     lut_addr,
    input  wire [4*ALPHA_W-1:0]   lut_data,
    input  wire [P*VOXEL_W-1:0]   smp,
    input  wire                   mode_ext,
    input  wire [P*ALPHA_W-1:0]   a3,
    output wire [P*ALPHA_W-1:0]   a_w
);
    `CUBE4_HARNESS_VIEW
    wire unused_rst = rst;
    cube4_com_plw #(`CUBE4_SLICE_PASS, .VOXEL_W(VOXEL_W), .ALPHA_W(ALPHA_W)) u_plw (.*);
endmodule
`default_nettype wire

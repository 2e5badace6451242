`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_gra_window_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_gra_window (tb/cube4_gra_window): a Verilog
//   clock, the view registers as individual ports packed into the cfg bus
//   (CUBE4_VIEW_PACK), and the window's source side (step and the
//   neighbourhood) and operand side as top-level ports, which the testbench
//   drives and reads every cycle.
//
// Parameters: as cube4_gra_window (P 1..64, VOXEL_W 1..16, WEIGHT_W 4..12,
//   MAX_DIM 2..2048, MAX_SS_LOG2 0..3, RECTS 0..1; CUBE4_UNIT_PARAMS).
//
// Latency: that of cube4_gra_window (the ports connect straight to it).
//
// Ports
//   clk      out  the harness's clock (cube4_sim_clock, 10 ns)
//   rst      in   synchronous reset
//   cfg_*    in   view registers (golden/cube4/memory.py top_regs)
//   step .. c_edge   in   as cube4_gra_window (the source's interface,
//                         CUBE4_GRA_STEP_PORTS of cube4_unit_ports.vh)
//   take .. gj       out  as cube4_gra_window (s .. gj: CUBE4_GRA_OPERAND_PORTS)
// =============================================================================
module cube4_gra_window_harness #(
    `CUBE4_UNIT_PARAMS
    parameter integer VOXEL_W = 8,
    parameter integer RECTS   = 0,
    `CUBE4_GRA_LAYOUT
) (
    `CUBE4_HARNESS_PORTS
    `CUBE4_GRA_STEP_PORTS(input)
    `CUBE4_GRA_OPERAND_PORTS(output, )
    output wire                     take,
    output wire [HDR_W-1:0]         c_hdr
);
    `CUBE4_HARNESS_VIEW

    cube4_gra_window #(`CUBE4_GRA_PASS, .RECTS (RECTS)) u_window (.*);

endmodule
`default_nettype wire

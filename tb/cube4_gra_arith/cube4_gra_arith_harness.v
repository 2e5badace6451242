`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// =============================================================================
// cube4_gra_arith_harness  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Unit test harness of cube4_gra_arith (tb/cube4_gra_arith): a Verilog
//   clock, the view registers as individual ports packed into the cfg bus
//   (CUBE4_VIEW_PACK), and the unit's operand input and gradient output as
//   top-level ports, which the testbench drives and reads every cycle.
//
// Parameters: as cube4_gra_arith (P 1..64, VOXEL_W 1..16, WEIGHT_W 4..12,
//   MAX_DIM 2..2048, MAX_SS_LOG2 0..3; CUBE4_UNIT_PARAMS).
//
// Latency: that of cube4_gra_arith (the ports connect straight to it).
//
// Ports
//   clk     out  the harness's clock (cube4_sim_clock, 10 ns)
//   rst     in   synchronous reset
//   cfg_*   in   view registers (golden/cube4/memory.py top_regs)
//   in_*, out_*  as cube4_gra_arith (in_s .. in_gj: CUBE4_GRA_OPERAND_PORTS,
//                out_*: CUBE4_GRA_BEAT_PORTS)
// =============================================================================
module cube4_gra_arith_harness #(
    `CUBE4_UNIT_PARAMS
    parameter integer VOXEL_W = 8,
    localparam integer SMP_W  = VOXEL_W     // (the arithmetic's samples carry no label)
) (
    `CUBE4_HARNESS_PORTS
    `CUBE4_GRA_BEAT_PORTS(output, out)
    `CUBE4_GRA_OPERAND_PORTS(input, in_)
    input  wire                     in_v,
    input  wire [HDR_W-1:0]         in_hdr,
    output wire                     out_v_d
);
    `CUBE4_HARNESS_VIEW

    cube4_gra_arith #(`CUBE4_GRA_PASS) u_arith (.*);

endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// cube4_cfb_steps_harness (simulation only): cube4_cfb_steps with the host's
// view registers one port each (CUBE4_HARNESS_PORTS, as the other CFB units).
module cube4_cfb_steps_harness #(
    `CUBE4_CFB_UNIT_PARAMS(0)
) (
    `CUBE4_HARNESS_PORTS
    input  wire start,
    output wire st_valid, input wire st_ready,
    output wire [DIM_W-1:0] st_x, output wire [DIM_W-1:0] st_y
);
    `CUBE4_HARNESS_VIEW
    cube4_cfb_steps #(`CUBE4_CFB_PASS) u_steps (.*);
endmodule
`default_nettype wire

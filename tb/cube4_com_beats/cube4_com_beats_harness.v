`default_nettype none
`include "cube4_defs.vh"
`include "cube4_unit_ports.vh"
// cube4_com_beats_harness (simulation only): cube4_com_beats (and, at the input
// queue's push, cube4_com_steps, which gives the beats' q_geo) with the host's view
// registers one port each (CUBE4_HARNESS_PORTS) and the sequencer's fields as ports
// (the groups shared with cube4_com_rect: cube4_unit_ports.vh).
module cube4_com_beats_harness #(
    `CUBE4_UNIT_PARAMS
    localparam integer SP_W  = ((MAX_DIM > 1) ? $clog2(MAX_DIM) : 1) + PB_W
) (
    `CUBE4_HARNESS_PORTS
    `CUBE4_COM_SLOT_PORTS(output)
    input  wire [4*P-1:0]      in_bits,
    input  wire [P*LANE_W-1:0] tpos,
    input  wire                q_push,
    input  wire [HDR_W-1:0]    q_hdr,
    input  wire                q_eoss,
    output wire [`CUBE4_GEO_W-1:0] q_geo,
    input  wire [`CUBE4_GEO_W-1:0] c_geo,
    input  wire                in_valid,
    input  wire [HDR_W-1:0]    in_hdr,
    input  wire                nx_valid,
    input  wire [HDR_W-1:0]    sk_hdr,
    input  wire                take,
    input  wire                step,
    input  wire [9:1]          v_fly,
    input  wire [9*SP_W-1:0]   sp_fly,
    input  wire [M_W-1:0]      r0_m,
    input  wire [DIM_W-1:0]    r0_j,
    input  wire [PB_W-1:0]     r0_pb,
    input  wire [P*IW-1:0]     f1_ipos,
    input  wire [IW-1:0]       f1_j,
    input  wire                f1_dxf,
    input  wire                f1_dyf,
    output wire                col1_4,
    output wire [P-1:0]        soon_0,
    output wire [PHASE_W-1:0]  ph_x,
    output wire [PHASE_W-1:0]  ph_y,
    output wire [PHASE_W-1:0]  phn_x,
    output wire [PHASE_W-1:0]  phn_y,
    output wire                f1_klast,
    output wire                f1_wxn,
    output wire                f1_wyn
);
    `CUBE4_HARNESS_VIEW
    cube4_com_steps #(`CUBE4_SLICE_PASS) u_steps (.clk(clk), .rst(rst), .cfg(cfg), .q_push(q_push), .q_hdr(q_hdr),
                                                  .q_eoss(q_eoss), .q_geo(q_geo));
    cube4_com_beats #(`CUBE4_SLICE_PASS, .SP_W(SP_W)) u_beats (.*);
endmodule
`default_nettype wire

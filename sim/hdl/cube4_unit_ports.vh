// cube4_unit_ports.vh: what the unit harnesses (tb/cube4_gra_*, tb/cube4_com_*,
// tb/cube4_cfb_*, sim/hdl/cube4_gra_source_harness.v) share, declared once: their
// parameters, their first ports and body, and the groups of ports that one unit of GRA or COM
// drives and another reads. The argument of a port group is the direction: the harness of
// the unit that drives a group declares it output, the harness of a unit that reads it input
// (a stream's beat also takes the prefix of its port names). Widths come from CUBE4_GEOMETRY
// and CUBE4_GRA_LAYOUT (cube4_defs.vh); SP_W, the slot width, from the harness. Each
// declaration ends with a comma: a macro stands on its own line before further ports.
`ifndef CUBE4_UNIT_PORTS_VH
`define CUBE4_UNIT_PORTS_VH

// The parameters every unit harness starts its parameter list with: the build parameters
// of the unit (ranges as in its header; the testbenches' defaults) and the geometry and
// view layout derived from them (cube4_defs.vh). The harness's own parameters follow.
`define CUBE4_UNIT_PARAMS \
    parameter integer P           = 5, \
    parameter integer MAX_DIM     = 32, \
    parameter integer MAX_SS_LOG2 = 0, \
    parameter integer WEIGHT_W    = 8, \
    `CUBE4_GEOMETRY, \
    `CUBE4_VIEW_LAYOUT,

// The whole parameter list of a CFB unit's harness (CUBE4_CFB_PARAMS with the
// testbenches' defaults; RECTS_DEFAULT: RECTS's), passed on with CUBE4_CFB_PASS.
`define CUBE4_CFB_UNIT_PARAMS(RECTS_DEFAULT) \
    `CUBE4_UNIT_PARAMS \
    parameter integer ADDR_W = 16, \
    parameter integer RECTS  = RECTS_DEFAULT, \
    `CUBE4_CFB_LAYOUT

// A harness's first ports: the Verilog clock (an output, cube4_sim_clock, 10 ns), the
// reset and the view registers, one port per field (CUBE4_VIEW_PORTS).
`define CUBE4_HARNESS_PORTS \
    output wire clk, \
    input  wire rst, \
    `CUBE4_VIEW_PORTS

// A harness's clock and the view registers packed into the unit's cfg bus; with
// CUBE4_HARNESS_ADDR also the address registers into its cfg_addr bus (CUBE4_ADDR_PORTS).
`define CUBE4_HARNESS_VIEW \
    cube4_sim_clock u_clock (.clk (clk)); \
    wire [VIEW_W-1:0] cfg = `CUBE4_VIEW_PACK;
`define CUBE4_HARNESS_ADDR \
    wire [ADR_W_ALL-1:0] cfg_addr = `CUBE4_ADDR_PACK;

// R0's step fields of cube4_com_seq, read by cube4_com_walk, _rect and _plw: slice m and
// row j, the back steps dxb, dyb, i of each lane (ipos, pb * P + lane position), and the S1
// registers: ipos, j and the next sample's steps dxf, dyf.
`define CUBE4_COM_STEP_PORTS(DIR) \
    DIR wire [M_W-1:0]   r0_m, \
    DIR wire [DIM_W-1:0] r0_j, \
    DIR wire             dxb, \
    DIR wire             dyb, \
    DIR wire [P*IW-1:0]  ipos, \
    DIR wire [P*IW-1:0]  f1_ipos, \
    DIR wire [IW-1:0]    f1_j, \
    DIR wire             f1_dxf, \
    DIR wire             f1_dyf,

// The slice geometry of cube4_com_walk (or _rect), read by cube4_com_seq: R0's slot and
// partial beam, the read-after-write hold, the lanes whose ray starts, whether each lane's
// next sample is inside (S1), stepx(m) and stepy(m).
`define CUBE4_COM_SLOT_PORTS(DIR) \
    DIR wire [SP_W-1:0]  pos_sp, \
    DIR wire [PB_W-1:0]  pos_pb, \
    DIR wire             hazard, \
    DIR wire [P-1:0]     fresh, \
    DIR wire [P-1:0]     nx_in, \
    DIR wire [DIM_W-1:0] stx, \
    DIR wire [DIM_W-1:0] sty,

// The phases of cube4_com_walk, read by cube4_com_plw: slice m's and slice m+1's phase
// (x, y), and S1's m = M - 1, wx(m+1) > 0, wy(m+1) > 0.
`define CUBE4_COM_PHASE_PORTS(DIR) \
    DIR wire [PHASE_W-1:0] ph_x, \
    DIR wire [PHASE_W-1:0] ph_y, \
    DIR wire [PHASE_W-1:0] phn_x, \
    DIR wire [PHASE_W-1:0] phn_y, \
    DIR wire               f1_last, \
    DIR wire               f1_wxn, \
    DIR wire               f1_wyn,

// The neighbourhood that GRA's source (cube4_gra_lines or cube4_gra_walk) gives
// cube4_gra_window at each step: X and its six neighbour beats (samples Q0.VOXEL_W, P lanes
// at [q*VOXEL_W +: VOXEL_W]), C's {real, header}, its select flags and edge count.
`define CUBE4_GRA_STEP_PORTS(DIR) \
    DIR wire                  step, \
    DIR wire                  sop, \
    DIR wire [P*VOXEL_W-1:0]  x, \
    DIR wire [P*VOXEL_W-1:0]  b1, \
    DIR wire [P*VOXEL_W-1:0]  p1, \
    DIR wire [P*VOXEL_W-1:0]  c, \
    DIR wire [P*VOXEL_W-1:0]  p1b2, \
    DIR wire [P*VOXEL_W-1:0]  p2b1, \
    DIR wire [P*VOXEL_W-1:0]  p2b2, \
    DIR wire [GRA_META_W-1:0] c_meta, \
    DIR wire [P*GRA_NSEL-1:0] c_sel, \
    DIR wire [1:0]            c_edge,

// The operands cube4_gra_window gives cube4_gra_arith for a centre: its samples s, the
// neighbours hi, lo (i +/- 1), fwd, back (along the ray; Q0.VOXEL_W, P lanes) and gj
// (VOXEL_W + 1 bits signed a lane), the port names prefixed by PFX (empty, in_).
`define CUBE4_GRA_OPERAND_PORTS(DIR, PFX) \
    DIR wire [P*VOXEL_W-1:0]     PFX``s, \
    DIR wire [P*VOXEL_W-1:0]     PFX``hi, \
    DIR wire [P*VOXEL_W-1:0]     PFX``lo, \
    DIR wire [P*VOXEL_W-1:0]     PFX``fwd, \
    DIR wire [P*VOXEL_W-1:0]     PFX``back, \
    DIR wire [P*(VOXEL_W+1)-1:0] PFX``gj,

// A beat of GRA's gradient stream (cube4_gra's output, cube4_gra_arith's, cube4_sha's
// input): the header, the samples (SMP_W bits a lane, which the harness defines: Q0.VOXEL_W,
// with labels the label above it) and the gradient components gi, gj, gk (VOXEL_W + 5
// bits signed each, P lanes), the port names prefixed by PFX (in, out).
`define CUBE4_GRA_BEAT_PORTS(DIR, PFX) \
    DIR wire [HDR_W-1:0]           PFX``_hdr, \
    DIR wire [P*SMP_W-1:0]         PFX``_sample, \
    DIR wire [P*(VOXEL_W+5)-1:0]   PFX``_gi, \
    DIR wire [P*(VOXEL_W+5)-1:0]   PFX``_gj, \
    DIR wire [P*(VOXEL_W+5)-1:0]   PFX``_gk,

`endif

// cube4_gra_source_if.vh: the interface of GRA's neighbourhood source (its parameters, ports and
// parameter checks), included right after "module cube4_gra_lines" (delay lines, RECTS = 0, which
// documents the ports), "module cube4_gra_walk" (position walk, RECTS = 1) and "module
// cube4_gra_beats" (the beat schedule, BEATS = 1; in_eoss, the input beat is the last of its
// slice, is its only user): cube4_gra instantiates one of them, by the same ports.
#(
    `CUBE4_GRA_PARAMS
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    input  wire in_valid,  output wire in_ready,  input  wire [HDR_W-1:0] in_hdr,
    input  wire [P*VOXEL_W-1:0] in_sample,
    input  wire in_eoss,
    input  wire [GRA_STEPS-1:0] credit,
    output wire step, output wire sop, output wire fend,
    output wire [P*VOXEL_W-1:0] x, output wire [P*VOXEL_W-1:0] b1, output wire [P*VOXEL_W-1:0] p1,
    output wire [P*VOXEL_W-1:0] c, output wire [P*VOXEL_W-1:0] p1b2,
    output wire [P*VOXEL_W-1:0] p2b1, output wire [P*VOXEL_W-1:0] p2b2,
    output wire [GRA_META_W-1:0] c_meta,
    output wire [P*GRA_NSEL-1:0] c_sel,
    output wire [1:0] c_edge
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_gra source", "P", P, 1, 64)
        `CUBE4_RANGE(g_bad_voxel_w, "cube4_gra source", "VOXEL_W", VOXEL_W, 1, 16)
    endgenerate

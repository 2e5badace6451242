// cube4_prim_ebr_if.vh: the interface of cube4_prim_ebr (the block-RAM primitive): its parameters, ports and
// parameter checks, included by both of its forms, rtl/cube4_prim_ebr.v (generic, which documents
// them) and rtl/ecp5/cube4_prim_ebr.v (ECP5), right after "module cube4_prim_ebr".
#(
    parameter integer SHAPE_W = 18,
    parameter integer W       = 18,
    parameter integer AW      = 10,
    parameter integer READ_A  = 0
) (
    input  wire          clk,
    input  wire          a_en,
    input  wire          a_we,
    input  wire [AW-1:0] a_addr,
    input  wire [W-1:0]  a_wd,
    output wire [W-1:0]  a_rd,
    input  wire          b_en,
    input  wire          b_oe,
    input  wire [AW-1:0] b_addr,
    output wire [W-1:0]  b_rd
);
    // a port of SHAPE_W bits addresses AD13..AD(LOW)
    localparam integer LOW = (SHAPE_W == 18) ? 4 : ((SHAPE_W == 9) ? 3 : ((SHAPE_W == 4) ? 2 : ((SHAPE_W == 2) ? 1 : 0)));
    generate
        if (!(SHAPE_W == 1 || SHAPE_W == 2 || SHAPE_W == 4 || SHAPE_W == 9 || SHAPE_W == 18)) begin : g_bad_shape
            $error("cube4_prim_ebr: SHAPE_W = %0d is not one of 1, 2, 4, 9, 18", SHAPE_W);
        end
        `CUBE4_RANGE(g_bad_w, "cube4_prim_ebr", "W", W, 1, SHAPE_W)
        `CUBE4_RANGE(g_bad_aw, "cube4_prim_ebr", "AW", AW, 1, 14 - LOW)
        `CUBE4_RANGE(g_bad_read_a, "cube4_prim_ebr", "READ_A", READ_A, 0, 1)
    endgenerate

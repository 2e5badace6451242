// cube4_dual_read_ram_if.vh: the interface of cube4_dual_read_ram (the RAM with two read ports): its parameters, ports and
// parameter checks, included by both of its forms, rtl/cube4_dual_read_ram.v (generic, which documents
// them) and rtl/ecp5/cube4_dual_read_ram.v (ECP5), right after "module cube4_dual_read_ram".
#(
    parameter  integer DATA_W  = 8,
    parameter  integer DEPTH   = 16,
    parameter  integer OUT_REG = 1,
    localparam integer AW      = (DEPTH > 1) ? $clog2(DEPTH) : 1
) (
    input  wire              clk,
    input  wire              rd_en,
    input  wire [AW-1:0]     rd0_addr,
    output wire [DATA_W-1:0] rd0_data,
    input  wire [AW-1:0]     rd1_addr,
    output wire [DATA_W-1:0] rd1_data,
    input  wire              wr_en,
    input  wire [AW-1:0]     wr_addr,
    input  wire [DATA_W-1:0] wr_data
);
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_dual_read_ram", "DATA_W", DATA_W, 1, 4096)
        if (DEPTH < 1 || DEPTH > (1 << 24)) begin : g_bad_depth
            $error("cube4_dual_read_ram: DEPTH = %0d is out of range 1..2^24", DEPTH);
        end
        `CUBE4_RANGE(g_bad_out_reg, "cube4_dual_read_ram", "OUT_REG", OUT_REG, 0, 1)
    endgenerate

// cube4_sdp_ram_if.vh: the interface of cube4_sdp_ram (the simple dual-port RAM): its parameters, ports and
// parameter checks, included by both of its forms, rtl/cube4_sdp_ram.v (generic, which documents
// them) and rtl/ecp5/cube4_sdp_ram.v (ECP5), right after "module cube4_sdp_ram".
#(
    parameter  integer DATA_W = 8,
    parameter  integer DEPTH  = 16,
    parameter  integer IN_REG = 0,
    parameter  integer WR_REG = 0,
    parameter  integer OUT_REG = 0,
    parameter  integer DIST   = 0,
    localparam integer AW     = (DEPTH > 1) ? $clog2(DEPTH) : 1
) (
    input  wire              clk,
    input  wire              rd_en,
    input  wire              out_en,
    input  wire [AW-1:0]     rd_addr,
    output wire [DATA_W-1:0] rd_data,
    input  wire              wr_en,
    input  wire [AW-1:0]     wr_addr,
    input  wire [DATA_W-1:0] wr_data
);
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_sdp_ram", "DATA_W", DATA_W, 1, 4096)
        if (DEPTH < 1 || DEPTH > (1 << 24)) begin : g_bad_depth
            $error("cube4_sdp_ram: DEPTH = %0d is out of range 1..2^24", DEPTH);
        end
        `CUBE4_RANGE(g_bad_in_reg, "cube4_sdp_ram", "IN_REG", IN_REG, 0, 1)
        `CUBE4_RANGE(g_bad_wr_reg, "cube4_sdp_ram", "WR_REG", WR_REG, 0, 1)
        `CUBE4_RANGE(g_bad_out_reg, "cube4_sdp_ram", "OUT_REG", OUT_REG, 0, 2)
        `CUBE4_RANGE(g_bad_dist, "cube4_sdp_ram", "DIST", DIST, 0, 1)
        if (DIST == 1 && (IN_REG == 1 || OUT_REG != 0)) begin : g_bad_dist_regs
            $error("cube4_sdp_ram: DIST = 1 with IN_REG = 1 or OUT_REG > 0 (a distributed RAM's read register is already in the fabric)");
        end
        if (OUT_REG == 2 && IN_REG == 1) begin : g_bad_out_en
            $error("cube4_sdp_ram: OUT_REG = 2 with IN_REG = 1 (out_en acts in its own cycle, the read a cycle after its inputs)");
        end
        if (IN_REG == 1 && WR_REG == 1) begin : g_bad_regs
            $error("cube4_sdp_ram: IN_REG = 1 with WR_REG = 1 (IN_REG registers the write's enable and address already)");
        end
    endgenerate

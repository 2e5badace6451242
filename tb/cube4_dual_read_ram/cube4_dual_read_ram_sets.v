`default_nettype none
// =============================================================================
// cube4_dual_read_ram_sets (testbench harness, not synthesised)
// -----------------------------------------------------------------------------
// Purpose
//   N instances of cube4_dual_read_ram, each at its own parameter set, in one
//   simulation build: the testbench (test_cube4_dual_read_ram.py) drives and
//   checks every instance on every edge, each against its own model (as
//   tb/cube4_sdp_ram/cube4_sdp_ram_sets.v).
//
// Parameters
//   N          instances, 1..64
//   DATA_WS, DEPTHS, OUT_REGS
//              instance k's parameter at bits [32 k +: 32] (cube4_dual_read_ram's
//              ranges; the testbench builds them from its PARAM_SETS)
//   DW_MAX     the ports' word stride, >= every DATA_W
//   AW_MAX     the ports' address stride, >= every instance's address width
//
// Ports (instance k's at [k], [k*AW_MAX +: AW], [k*DW_MAX +: DATA_W])
//   rd_en, rd0_addr, rd0_data, rd1_addr, rd1_data, wr_en, wr_addr, wr_data as
//   cube4_dual_read_ram; the read data's bits above an instance's DATA_W are 0
// =============================================================================
module cube4_dual_read_ram_sets #(
    parameter integer N = 1,
    parameter [N*32-1:0] DATA_WS  = {N{32'd8}},
    parameter [N*32-1:0] DEPTHS   = {N{32'd16}},
    parameter [N*32-1:0] OUT_REGS = {N{32'd1}},
    parameter integer DW_MAX = 8,
    parameter integer AW_MAX = 4
) (
    input  wire                clk,
    input  wire [N-1:0]        rd_en,
    input  wire [N*AW_MAX-1:0] rd0_addr,
    output wire [N*DW_MAX-1:0] rd0_data,
    input  wire [N*AW_MAX-1:0] rd1_addr,
    output wire [N*DW_MAX-1:0] rd1_data,
    input  wire [N-1:0]        wr_en,
    input  wire [N*AW_MAX-1:0] wr_addr,
    input  wire [N*DW_MAX-1:0] wr_data
);
    genvar k;
    generate
        if (N < 1 || N > 64) begin : g_bad_n
            $error("cube4_dual_read_ram_sets: N = %0d is out of range 1..64", N);
        end
        for (k = 0; k < N; k = k + 1) begin : g_set
            localparam integer DW    = DATA_WS[k*32 +: 32];
            localparam integer DEPTH = DEPTHS[k*32 +: 32];
            localparam integer AW    = (DEPTH > 1) ? $clog2(DEPTH) : 1;
            if (DW > DW_MAX || AW > AW_MAX) begin : g_bad_stride
                $error("cube4_dual_read_ram_sets: set %0d (DATA_W %0d, %0d address bits) exceeds DW_MAX %0d or AW_MAX %0d",
                       k, DW, AW, DW_MAX, AW_MAX);
            end
            wire [DW-1:0] rd0, rd1;
            cube4_dual_read_ram #(
                .DATA_W(DW), .DEPTH(DEPTH), .OUT_REG(OUT_REGS[k*32 +: 32])
            ) u_ram (
                .clk(clk), .rd_en(rd_en[k]),
                .rd0_addr(rd0_addr[k*AW_MAX +: AW]), .rd0_data(rd0),
                .rd1_addr(rd1_addr[k*AW_MAX +: AW]), .rd1_data(rd1),
                .wr_en(wr_en[k]), .wr_addr(wr_addr[k*AW_MAX +: AW]), .wr_data(wr_data[k*DW_MAX +: DW]));
            assign rd0_data[k*DW_MAX +: DW_MAX] = DW_MAX'(rd0);
            assign rd1_data[k*DW_MAX +: DW_MAX] = DW_MAX'(rd1);
            if (AW < AW_MAX) begin : g_unused_addr
                wire unused = ^{rd0_addr[k*AW_MAX + AW +: AW_MAX - AW], rd1_addr[k*AW_MAX + AW +: AW_MAX - AW],
                                wr_addr[k*AW_MAX + AW +: AW_MAX - AW]};
            end
            if (DW < DW_MAX) begin : g_unused_data
                wire unused = ^wr_data[k*DW_MAX + DW +: DW_MAX - DW];
            end
        end
    endgenerate

endmodule
`default_nettype wire

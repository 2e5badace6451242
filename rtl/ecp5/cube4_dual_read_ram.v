`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_dual_read_ram  (ECP5 form; the generic form is rtl/cube4_dual_read_ram.v)
// -----------------------------------------------------------------------------
// Purpose
//   The two-lane table of rtl/cube4_dual_read_ram.v (same ports, parameters
//   and timing) on the ECP5's DP16KD block RAMs. With OUT_REG = 1 and an
//   address of 7 to 14 bits (DEPTH 65 .. 16384), the word is sliced as rtl/ecp5/cube4_sdp_ram.v slices it
//   (rtl/ecp5/cube4_ebr_plan.vh: the block's shape for the depth, or deeper
//   shapes stacked up to 4 deep where they take fewer blocks), each slice a
//   column of blocks (cube4_prim_ebr_column) in true dual-port use:
//   port A writes, or reads for port 0 (its address is the write's in a
//   write cycle, port 0's otherwise), port B reads for port 1, both through
//   the block's output register. Other sizes (or OUT_REG = 0) are one
//   cube4_sdp_ram per read port, both written: a copy per lane, as if the
//   table were not shared (SHA's map at RMAP_BITS = 6, its LUT at VOXEL_W
//   above 14).
//
// Parameters, latency, ports: as rtl/cube4_dual_read_ram.v.
// =============================================================================
module cube4_dual_read_ram
`include "cube4_dual_read_ram_if.vh"

    localparam integer USE_EBR = (OUT_REG == 1 && AW >= 7 && AW <= 14) ? 1 : 0;
    // the blocks' shapes (as rtl/ecp5/cube4_sdp_ram.v with OUT_REG = 1)
    `include "ecp5/cube4_ebr_plan.vh"
    localparam integer PLAN = ebr_plan(DATA_W, DEPTH);
    localparam integer N_SL = ebr_n_main(DATA_W, PLAN / 8, PLAN % 8) + ebr_n_rest(DATA_W, PLAN / 8, PLAN % 8);

    generate
        if (USE_EBR == 1) begin : g_ebr
            wire [AW-1:0] a_addr = wr_en ? wr_addr : rd0_addr;
            genvar sl;
            for (sl = 0; sl < N_SL; sl = sl + 1) begin : g_slice
                localparam integer LO = ebr_sl_lo(DATA_W, PLAN, sl);
                localparam integer W  = ebr_sl_w(DATA_W, PLAN, sl);
                localparam integer SH = ebr_sl_shape(DATA_W, PLAN, sl);
                cube4_prim_ebr_column #(.SHAPE_W(ebr_w(SH)), .W(W), .AW(AW), .BLK_AW(10 + SH),
                                        .BANKS(ebr_banks(SH, DEPTH)), .READ_A(1)) u_ebr (
                    .clk(clk), .a_en(rd_en), .a_we(wr_en), .a_addr(a_addr), .a_wd(wr_data[LO +: W]),
                    .a_rd(rd0_data[LO +: W]),
                    .b_en(rd_en), .b_oe(rd_en), .b_addr(rd1_addr), .b_rd(rd1_data[LO +: W]));
            end
        end else begin : g_two
            // one RAM per read port, both written (Yosys infers each)
            cube4_sdp_ram #(.DATA_W(DATA_W), .DEPTH(DEPTH), .OUT_REG(OUT_REG)) u_rd0 (
                .clk(clk), .rd_en(rd_en && !wr_en), .out_en(1'b0), .rd_addr(rd0_addr), .rd_data(rd0_data),
                .wr_en(wr_en), .wr_addr(wr_addr), .wr_data(wr_data));
            cube4_sdp_ram #(.DATA_W(DATA_W), .DEPTH(DEPTH), .OUT_REG(OUT_REG)) u_rd1 (
                .clk(clk), .rd_en(rd_en), .out_en(1'b0), .rd_addr(rd1_addr), .rd_data(rd1_data),
                .wr_en(wr_en), .wr_addr(wr_addr), .wr_data(wr_data));
        end
    endgenerate

endmodule
`default_nettype wire

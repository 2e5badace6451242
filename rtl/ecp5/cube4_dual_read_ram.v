`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_dual_read_ram  (ECP5 form; the generic form is rtl/cube4_dual_read_ram.v)
// -----------------------------------------------------------------------------
// Purpose
//   The two-lane table of rtl/cube4_dual_read_ram.v (same ports, parameters
//   and timing) on the ECP5's DP16KD block RAMs. With OUT_REG = 1 and an
//   address of 7 to 14 bits (DEPTH 65 .. 16384), the word is sliced as rtl/ecp5/cube4_sdp_ram.v slices it
//   (1024 x 18 up to 1024 words, 2048 x 9, 4096 x 4, 8192 x 2, 16384 x 1),
//   each slice one block (rtl/ecp5/cube4_prim_ebr.v) in true dual-port use:
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
    // the block's shape for the depth (as rtl/ecp5/cube4_sdp_ram.v with OUT_REG = 1)
    localparam integer SL_W = (AW >= 14) ? 1 : ((AW == 13) ? 2 : ((AW == 12) ? 4 : ((AW == 11) ? 9 : 18)));
    localparam integer N_SL = (DATA_W + SL_W - 1) / SL_W;

    generate
        if (USE_EBR == 1) begin : g_ebr
            wire [AW-1:0] a_addr = wr_en ? wr_addr : rd0_addr;
            genvar sl;
            for (sl = 0; sl < N_SL; sl = sl + 1) begin : g_slice
                localparam integer LO = sl * SL_W;
                localparam integer W  = (DATA_W - LO < SL_W) ? DATA_W - LO : SL_W;
                cube4_prim_ebr #(.SHAPE_W(SL_W), .W(W), .AW(AW), .READ_A(1)) u_ebr (
                    .clk(clk), .a_en(rd_en), .a_we(wr_en), .a_addr(a_addr), .a_wd(wr_data[LO +: W]),
                    .a_rd(rd0_data[LO +: W]),
                    .b_en(rd_en), .b_addr(rd1_addr), .b_rd(rd1_data[LO +: W]));
            end
        end else begin : g_two
            // one RAM per read port, both written (Yosys infers each)
            cube4_sdp_ram #(.DATA_W(DATA_W), .DEPTH(DEPTH), .OUT_REG(OUT_REG)) u_rd0 (
                .clk(clk), .rd_en(rd_en && !wr_en), .rd_addr(rd0_addr), .rd_data(rd0_data),
                .wr_en(wr_en), .wr_addr(wr_addr), .wr_data(wr_data));
            cube4_sdp_ram #(.DATA_W(DATA_W), .DEPTH(DEPTH), .OUT_REG(OUT_REG)) u_rd1 (
                .clk(clk), .rd_en(rd_en), .rd_addr(rd1_addr), .rd_data(rd1_data),
                .wr_en(wr_en), .wr_addr(wr_addr), .wr_data(wr_data));
        end
    endgenerate

endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_sdp_ram  (ECP5 form; the generic form is rtl/cube4_sdp_ram.v)
// -----------------------------------------------------------------------------
// Purpose
//   The simple dual-port RAM of rtl/cube4_sdp_ram.v (same ports, parameters
//   and timing), shaped for the ECP5's DP16KD block RAMs. rtl/sources.f
//   names the generic form; synthesis for the ECP5 takes this one instead
//   (a file of the same name in rtl/ecp5/ replaces the generic one).
//   * A RAM deeper than 2048 words (more than one block RAM deep in its
//     2048 x 9 shape) stores its word as slices of 4, 2 or 1 bits (4096,
//     8192, 16384+ words), one memory each: each slice maps to block RAMs in
//     their 4K x 4, 8K x 2 or 16K x 1 shape, so that up to 16384 words the
//     read data needs no multiplexer between the block RAMs and the next
//     register (about as many block RAMs as the 2048 x 9 shape plus a
//     multiplexer).
//   * With IN_REG = 1 every two slices get their own copies of the address
//     and enable registers (cube4_prim_copies; RAMs up to 2048 words deep are
//     then sliced into 18-bit words, two 2048 x 9 block RAMs), so no single
//     flip-flop drives the address of every block RAM: a RAM spread over
//     dozens of block RAMs across the die otherwise spends most of a cycle
//     routing one address net.
//   tb/cube4_top test_synthesis_ram_form_p1 simulates this form.
//
// Parameters, latency, ports, bit growth: as rtl/cube4_sdp_ram.v.
// =============================================================================
module cube4_sdp_ram #(
    parameter  integer DATA_W = 8,
    parameter  integer DEPTH  = 16,
    parameter  integer IN_REG = 0,
    localparam integer AW     = (DEPTH > 1) ? $clog2(DEPTH) : 1
) (
    input  wire              clk,
    input  wire              rd_en,
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
    endgenerate

    // slice width: 4, 2, 1 bits from 4096, 8192, 16384 words on; else the
    // word (18 bits with IN_REG, so that the register copies have slices)
    localparam integer SL_SHALLOW = (IN_REG == 1 && DATA_W > 18) ? 18 : DATA_W;
    localparam integer SL_W = (AW >= 14) ? 1 : ((AW == 13) ? 2 : ((AW == 12) ? 4 : SL_SHALLOW));
    localparam integer SPC  = 2;                        // slices per register copy
    localparam integer N_SL = (DATA_W + SL_W - 1) / SL_W;
    localparam integer N_CP = (N_SL + SPC - 1) / SPC;   // register copies (IN_REG = 1)
    localparam integer CW   = 2 * AW + 2;               // a copy: {re, we, ra, wa}

    wire [N_CP*CW-1:0] in_cp;           // the access's inputs, one set per copy
    generate
        if (IN_REG == 1) begin : g_in_reg
            cube4_prim_copies #(.N(N_CP), .W(CW), .RESET(0)) u_in (
                .clk(clk), .rst(1'b0), .d({rd_en, wr_en, rd_addr, wr_addr}), .q(in_cp));
        end else begin : g_direct
            assign in_cp = {N_CP{rd_en, wr_en, rd_addr, wr_addr}};
        end
    endgenerate

    genvar sl;
    generate
        for (sl = 0; sl < N_SL; sl = sl + 1) begin : g_slice
            localparam integer LO = sl * SL_W;
            localparam integer W  = (DATA_W - LO < SL_W) ? DATA_W - LO : SL_W;
            wire [CW-1:0] cp = in_cp[(sl / SPC) * CW +: CW];
            wire          re = cp[CW-1];
            wire          we = cp[CW-2];
            wire [AW-1:0] ra = cp[AW +: AW];
            wire [AW-1:0] wa = cp[0 +: AW];
            reg [W-1:0] mem [0:(1 << AW)-1];
            reg [W-1:0] rd_q;
            always @(posedge clk) begin
                if (we) mem[wa] <= wr_data[LO +: W];
                if (re) rd_q <= mem[ra];
            end
            assign rd_data[LO +: W] = rd_q;
        end
    endgenerate

endmodule
`default_nettype wire

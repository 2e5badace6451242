`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_tri_meta
// -----------------------------------------------------------------------------
// Purpose
//   What travels beside TRI's lerps (cube4_tri, after s4): the beat's valid
//   bit and header, and the y and z weights until their lerps start. The
//   header's KEEP (LVALID until here) becomes LVALID & keep, cube4_clip's
//   result (all ones without CLIP), TRI_CLIP_LAT cycles after s4.
//
// Parameters
//   P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W as cube4_tri (the header's widths).
//   Lerp latency TRI_LERP_LAT, NL = 3 * TRI_LERP_LAT stages (x, y, z lerps).
//
// Latency
//   Stage n after s4 (n = 1 .. NL) holds the beat's header; the valid bit is
//   carried to stage NL - 1 (push_d: the z-lerp's result is an item at the
//   next cycle). wy / wz leave TRI_LERP_LAT - 1 / 2 * TRI_LERP_LAT - 1 cycles
//   after s4, one cycle before the y / z lerps load the lanes' copies.
//   The valid bits are reset; nothing else.
//
// Ports
//   s4_v, s4_meta, s4_wy, s4_wz  in   cube4_tri_beam's s4 (header CUBE4_GEOMETRY,
//                                     weights unsigned Q0.WEIGHT_W)
//   keep     in   cube4_clip's KEEP, TRI_CLIP_LAT cycles after s4's fields
//   wy, wz   out  the weights for the lanes' copies (as s4_wy, s4_wz)
//   push_d   out  stage NL - 1 holds a beat
//   hdr      out  stage NL's header, KEEP replaced
//
// Bit growth and rounding: none (registers and one AND).
// =============================================================================
module cube4_tri_meta #(
    parameter integer P = 8, parameter integer MAX_DIM = 256, parameter integer MAX_SS_LOG2 = 0,
    parameter integer WEIGHT_W = 8,
    `CUBE4_GEOMETRY, `CUBE4_TRI_LAYOUT
) (
    input  wire clk, input wire rst,
    input  wire s4_v, input wire [HDR_W-1:0] s4_meta,
    input  wire [WEIGHT_W-1:0] s4_wy, input wire [WEIGHT_W-1:0] s4_wz,
    input  wire [P-1:0] keep,
    output wire [WEIGHT_W-1:0] wy, output wire [WEIGHT_W-1:0] wz,
    output wire push_d, output wire [HDR_W-1:0] hdr
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_tri_meta", "P", P, 1, 64)
    endgenerate

    localparam integer LERP_LAT = TRI_LERP_LAT;
    localparam integer NL       = 3 * LERP_LAT;
    reg [NL-1:1]                     lv_q;     // (stage NL: the FIFO's push copies)
    reg [HDR_W-1:0]    lmeta_q [1:NL];
    reg [WEIGHT_W-1:0] lwy_q [1:LERP_LAT-1];     // (the last stage: each lane's wy_l)
    reg [WEIGHT_W-1:0] lwz_q [1:2*LERP_LAT-1];   // (the last stage: each lane's wz_l)

    always @(posedge clk) begin
        if (rst) lv_q <= '0;
        else     lv_q <= {lv_q[NL-2:1], s4_v};
    end
    integer kl;
    always @(posedge clk) begin
        lmeta_q[1] <= s4_meta;
        for (kl = 2; kl <= NL; kl = kl + 1) lmeta_q[kl] <= lmeta_q[kl - 1];
        // cube4_clip's KEEP (TRI_CLIP_LAT cycles after s4) replaces the placeholder
        lmeta_q[TRI_CLIP_LAT + 1][HDR_KEEP +: P] <= lmeta_q[TRI_CLIP_LAT][HDR_LVALID +: P] & keep;
        lwy_q[1] <= s4_wy;
        for (kl = 2; kl <= LERP_LAT - 1; kl = kl + 1) lwy_q[kl] <= lwy_q[kl - 1];
        lwz_q[1] <= s4_wz;
        for (kl = 2; kl <= 2 * LERP_LAT - 1; kl = kl + 1) lwz_q[kl] <= lwz_q[kl - 1];
    end
    assign wy     = lwy_q[LERP_LAT - 1];
    assign wz     = lwz_q[2 * LERP_LAT - 1];
    assign push_d = lv_q[NL - 1];
    assign hdr    = lmeta_q[NL];
endmodule
`default_nettype wire

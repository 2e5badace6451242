`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_ext
// -----------------------------------------------------------------------------
// Purpose
//   One lane of COM's extremum datapath (EXTREMUM = 1; numerics.md section
//   13): the ray keeps {v, R, G, B, A} of the sample with the largest (MIP)
//   or smallest (MinIP) v among those that count:
//     MIP    take the sample if it counts and v >= the kept v
//     MinIP  take the sample if it counts and v <= the kept v
//   (a fresh ray's v is 0, MinIP 2^VOXEL_W - 1, with RGBA 0). The finished
//   ray's pixel: colour << (ACC_W - 8); A << (ACC_W - ALPHA_W), or
//   round_shift(A, ALPHA_W - ACC_W) when ALPHA_W > ACC_W.
//
// Parameters
//   ALPHA_W  opacity width.                 8..16.  Default 12.
//   ACC_W    the pixel's fraction bits.     8..24.  Default 16.
//   VOXEL_W  the sample v's width.          1..16.  Default 8.
//
// Latency
//   R0's sample v0 is carried S1 .. S6; acc5 (S5) is registered at the edge
//   into S6 (a kept register of its own, cube4_prim_copies: the blending
//   lane's shares its low bits). S6 compares, S7 registers the choice beside
//   both candidates (the sample's {R, G, B, A} in cube4_com_lane's S7
//   register, rgba7, shared with the blending lane), S8 selects, S9, S10
//   carry; acc_q is the S11 register (loads on every cycle), pix is formed
//   from it. cnt6 is S6's.
//
// Ports
//   v0        in   R0: the sample v, unsigned VOXEL_W
//   acc5      in   S5: the kept {v, R, G, B, A} (VOXEL_W, 8, 8, 8, ALPHA_W bits)
//   rgba7     in   S7: the sample's {R, G, B (Q0.8), A (Q0.ALPHA_W)}
//   cnt6      in   S6: the sample counts
//   mode_min  in   MinIP (else MIP); static within a frame
//   acc_q     out  S11: the new {v, R, G, B, A}, as acc5
//   pix       out  S11: {R, G, B, A}, ACC_W + 1 bits each, Q0.ACC_W
//   take_q    out  S11: the sample was taken (depth out)
//   vmin, vmax in  termination's values (static)
//   done_q    out  S11: acc_q's v is vmin (MinIP) or vmax (MIP)
//
// Bit growth and rounding: no arithmetic but the comparison; the pixel's
//   shifts lose nothing, A's round_shift rounds half up and stays <= 2^ACC_W.
// =============================================================================
module cube4_com_ext #(
    parameter integer ALPHA_W = 12, parameter integer ACC_W = 16, parameter integer VOXEL_W = 8,
    localparam integer CW    = ACC_W + 1,
    localparam integer LUT_W = 24 + ALPHA_W,
    localparam integer EXT_W = VOXEL_W + LUT_W
) (
    input  wire clk,
    input  wire [VOXEL_W-1:0] v0, input wire [EXT_W-1:0] acc5, input wire [LUT_W-1:0] rgba7,
    input  wire cnt6, input wire mode_min,
    input  wire [VOXEL_W-1:0] vmin, input wire [VOXEL_W-1:0] vmax,
    output reg  [EXT_W-1:0] acc_q, output wire [4*CW-1:0] pix,
    output reg  take_q, output reg done_q
);
    generate
        `CUBE4_RANGE(g_bad_alpha_w, "cube4_com_ext", "ALPHA_W", ALPHA_W, 8, 16)
        `CUBE4_RANGE(g_bad_acc_w, "cube4_com_ext", "ACC_W", ACC_W, 8, 24)
        `CUBE4_RANGE(g_bad_voxel_w, "cube4_com_ext", "VOXEL_W", VOXEL_W, 1, 16)
    endgenerate

    // the sample v, R0's word carried along S1 .. S6
    reg [6*VOXEL_W-1:0] v_l;
    always @(posedge clk) begin
        v_l <= {v_l[5*VOXEL_W-1:0], v0};
    end
    wire [VOXEL_W-1:0] v6 = v_l[5*VOXEL_W +: VOXEL_W];
    // S6: the kept word in a register of its own (kept apart from the
    // blending lane's, which shares its low bits: both are cube4_prim_copies,
    // which synthesis never merges), then take the sample if it counts and is
    // at least (MinIP: at most) the kept v
    wire [EXT_W-1:0] s6_e;
    cube4_prim_copies #(.N(1), .W(EXT_W), .RESET(0)) u_s6_e (
        .clk(clk), .rst(1'b0), .d(acc5), .q(s6_e));
    wire [VOXEL_W-1:0] kept = s6_e[LUT_W +: VOXEL_W];
    // (the choice is registered as a flag beside both candidates and made at
    // S7 -> S8: the compare's result reaches one flip-flop, not the select of
    // every bit of the word)
    wire take_s = cnt6 && (mode_min ? (v6 <= kept) : (v6 >= kept));
    reg               s7_take;
    reg [VOXEL_W-1:0] s7_v;             // the new candidate: {s7_v, rgba7}
    reg [EXT_W-1:0]   s7_old, s8_e, s9_e, s10_e;
    wire [EXT_W-1:0]  s7_new = {s7_v, rgba7};
    always @(posedge clk) begin
        s7_take <= take_s;
        s7_v    <= v6;
        s7_old  <= s6_e;
        s8_e    <= s7_take ? s7_new : s7_old;
        s9_e    <= s8_e;
        s10_e   <= s9_e;
        acc_q   <= s10_e;               // S11
        // termination's rule on the S11 word, registered with it: its v is the
        // volume's largest (MIP) or smallest (MinIP) value
        done_q  <= s10_e[LUT_W +: VOXEL_W] == (mode_min ? vmin : vmax);
    end
    // depth out: the sample was taken, carried S7 -> S11 beside the word
    reg s8_take, s9_take, s10_take;
    always @(posedge clk) {take_q, s10_take, s9_take, s8_take} <= {s10_take, s9_take, s8_take, s7_take};
    // S11: the pixel from the register: colour << (F - 8), A to F bits
    wire [CW-1:0] a_px;
    generate
        if (ACC_W >= ALPHA_W) begin : g_a_up
            assign a_px = CW'(acc_q[0 +: ALPHA_W]) << (ACC_W - ALPHA_W);
        end else begin : g_a_down
            wire signed [ACC_W+1:0] a_rs;
            cube4_round_shift #(.IN_W(ALPHA_W + 1), .SHIFT(ALPHA_W - ACC_W)) u_a (
                .x($signed({1'b0, acc_q[0 +: ALPHA_W]})), .y(a_rs));
            assign a_px = a_rs[CW-1:0];
        end
    endgenerate
    wire [CW-1:0] r_px = CW'(acc_q[ALPHA_W + 16 +: 8]) << (ACC_W - 8);
    wire [CW-1:0] g_px = CW'(acc_q[ALPHA_W + 8 +: 8]) << (ACC_W - 8);
    wire [CW-1:0] b_px = CW'(acc_q[ALPHA_W +: 8]) << (ACC_W - 8);
    wire unused_v = ^acc_q[EXT_W-1:LUT_W];   // v: kept for the next sample only
    assign pix = {r_px, g_px, b_px, a_px};
endmodule
`default_nettype wire

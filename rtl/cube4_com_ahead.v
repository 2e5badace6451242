`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_ahead
// -----------------------------------------------------------------------------
// Purpose
//   COM's read-after-write rule by position (cube4_com_slot's hazard) as a
//   register, for an input that passes a skid buffer (cube4_com on the beat
//   schedule): the hazard of the beat the skid will offer at the next edge,
//   decided at this one, so that no slot compare lies between the skid's
//   head and COM's in_ready (and the skid's pointers behind it). A beat's
//   slot is {j, pb} from its header; the hazard of a beat with slot x is
//     step && pos_sp == x  ||  v_fly[k] && sp_fly[k] == x  (k = 1 .. 9)
//   over R0 .. S9, which move on every cycle (R0 loads the beat taken, S1
//   R0, S k S k-1).
//   A beat is compared with the stages once, as it enters the skid: its
//   compares become a vector at[0 .. 9] (at[k]: stage k, R0 .. S9, holds a
//   beat of its slot at the next edge; at[0] = take && the head's slot is
//   x, at[1] = step && pos_sp == x, at[k+1] = v_fly[k] && sp_fly[k] == x).
//   While the beat waits the vector moves with the stages (at[k] <=
//   at[k-1]; at[0] <= take && the head's slot is x, which for the second
//   item is a register, eq_q, set as it enters behind the head), so its
//   hazard is the OR of its vector. The register at the output holds the
//   OR of the vector of the beat offered at the next edge: the head's (not
//   taken), the second item's (taken, two held) or the entering header's
//   (taken with one held, or none held). Only the entering header's
//   compares (against R0 .. S8 and the head) lie before a register; a held
//   beat's rule is an OR of registers, and take only chooses at the end.
//   Exact: the register equals cube4_com_slot's hazard of the head in every
//   cycle the skid offers one (cube4_com_beats checks that in simulation).
//
// Parameters: as cube4_com_slot (the geometry; SP_W the slot's width).
//
// Latency
//   hazard: a register, the rule for the beat offered in its cycle.
//
// Ports
//   hd_valid, hd_hdr   in   the skid offers a beat; its header (out_valid, out_data)
//   nx_valid           in   the skid holds a second beat
//   in_hdr             in   the header at the skid's input (it enters at this
//                           edge if offered and taken; it counts only then)
//   take               in   the head enters R0 at this edge
//   step, pos_sp       in   R0 holds a beat; its slot
//   v_fly, sp_fly      in   S1 .. S8 hold a beat; their slots (S k at [(k-1)*SP_W])
//   hazard             out  the offered beat's slot is the slot of a beat in
//                           R0 .. S9 (registered)
//
// Bit growth and rounding: none (compares).
// =============================================================================
module cube4_com_ahead #(
    `CUBE4_SLICE_PARAMS,
    parameter integer SP_W = 13
) (
    input  wire clk, input wire rst,
    input  wire hd_valid, input wire [HDR_W-1:0] hd_hdr,
    input  wire nx_valid,
    input  wire [HDR_W-1:0] in_hdr,
    input  wire take,
    input  wire step, input wire [SP_W-1:0] pos_sp,
    input  wire [8:1] v_fly, input wire [8*SP_W-1:0] sp_fly,
    output wire hazard
);
    generate
        `CUBE4_RANGE(g_bad_sp_w, "cube4_com_ahead", "SP_W", SP_W, 2, 22)
    endgenerate
    localparam integer RW = (MAX_DIM > 1) ? $clog2(MAX_DIM) : 1;

    // the slots {j, pb} of the head and of the header entering the skid
    wire [SP_W-1:0] s_hd = SP_W'({hd_hdr[HDR_J +: RW], hd_hdr[HDR_PB +: PB_W]});
    wire [SP_W-1:0] s_in = SP_W'({in_hdr[HDR_J +: RW], in_hdr[HDR_PB +: PB_W]});
    // the entering header against R0 .. S8 (S1 .. S9 at the next edge), one bit a stage
    wire [9:1] in_at;
    assign in_at[1] = step && (pos_sp == s_in);
    genvar k;
    generate
        for (k = 1; k <= 8; k = k + 1) begin : g_in_at
            assign in_at[k+1] = v_fly[k] && (sp_fly[(k-1)*SP_W +: SP_W] == s_in);
        end
    endgenerate
    wire eq_in = (s_hd == s_in);          // the entering header against the head
    // Each held beat keeps its compares as a vector (at[0] R0 .. at[9] S9: the beat in
    // that stage has its slot), which moves with the stages: at[k] <= at[k-1], and
    // at[0] <= take && the head (which enters R0) has its slot. A beat is compared
    // with the stages once, as it enters; after that the rule of a held beat is an
    // OR of its vector's registers. hd_at is the head's vector, nx_at the second
    // item's, eq_q "the second item's slot is the head's".
    // (at[9] is kept in no register: a stage later the beat in S9 has left, and
    // the output register ORs the whole vector as it forms)
    reg  [8:0] hd_at, nx_at;
    reg        eq_q;
    wire [9:0] in_tk = {in_at, take && eq_in};      // the entering one's, with the head taken
    wire [8:0] in_st = {in_at[8:1], 1'b0};          // the entering one's, the head staying (kept part)
    always @(posedge clk) begin
        hd_at <= take ? (nx_valid ? {nx_at[7:0], eq_q} : in_tk[8:0])
                      : (hd_valid ? {hd_at[7:0], 1'b0} : in_st);
        nx_at <= (nx_valid && !take) ? {nx_at[7:0], 1'b0} : in_tk[8:0];
        eq_q  <= nx_valid ? eq_q : eq_in;
    end
    // the register: the rule of the beat offered at the next edge, as its vector there
    // (the vectors' ORs are of registers; only the entering header's compares remain)
    reg  hz_q;
    always @(posedge clk) begin
        if (rst) hz_q <= 1'b0;
        else     hz_q <= take ? (nx_valid ? ((nx_at != '0) || eq_q) : (in_tk != '0))
                              : (hd_valid ? (hd_at != '0) : (in_at != '0));
    end
    assign hazard = hz_q;
    wire unused_hdr = ^{hd_hdr, in_hdr};   // (the fields besides J and PB)
endmodule
`default_nettype wire

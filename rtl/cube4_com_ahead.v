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
//   R0, S k S k-1). At the next edge R0 holds the head if it is taken now,
//   and S1 .. S9 hold R0 .. S8 of now, so the hazard there of a beat x is
//     base(x) || take && slot(head) == x,
//     base(x) = step && pos_sp == x  ||  v_fly[k] && sp_fly[k] == x (k = 1 .. 8)
//   and the beat offered then is: the head (not taken), the skid's second
//   item (taken, two held), or the item entering the skid now (taken with
//   one held, or none held). The three compares run from registers (the
//   skid's entries, the header entering it, R0 .. S8), and take only
//   chooses among them at the register's input.
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
//   nx_valid, nx_hdr   in   the skid holds a second beat; its header
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
    input  wire nx_valid, input wire [HDR_W-1:0] nx_hdr,
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

    // base(x): x against R0 .. S8 (which are S1 .. S9 at the next edge)
    function automatic base(input [SP_W-1:0] x, input st, input [SP_W-1:0] r0,
                            input [8:1] v, input [8*SP_W-1:0] sp);
        integer k;
        begin
            base = st && (r0 == x);
            for (k = 1; k <= 8; k = k + 1) base = base || (v[k] && (sp[(k-1)*SP_W +: SP_W] == x));
        end
    endfunction

    // the slots {j, pb} of the head, the second item and the entering one
    wire [SP_W-1:0] s_hd = SP_W'({hd_hdr[HDR_J +: RW], hd_hdr[HDR_PB +: PB_W]});
    wire [SP_W-1:0] s_nx = SP_W'({nx_hdr[HDR_J +: RW], nx_hdr[HDR_PB +: PB_W]});
    wire [SP_W-1:0] s_in = SP_W'({in_hdr[HDR_J +: RW], in_hdr[HDR_PB +: PB_W]});
    wire hz_hd = base(s_hd, step, pos_sp, v_fly, sp_fly);                         // the head stays
    wire hz_nx = base(s_nx, step, pos_sp, v_fly, sp_fly) || (s_hd == s_nx);      // taken: the second
    wire hz_in = base(s_in, step, pos_sp, v_fly, sp_fly) || (take && s_hd == s_in);  // the entering one
    reg  hz_q;
    always @(posedge clk) begin
        if (rst) hz_q <= 1'b0;
        else     hz_q <= take ? (nx_valid ? hz_nx : hz_in) : (hd_valid ? hz_hd : hz_in);
    end
    assign hazard = hz_q;
    wire unused_hdr = ^{hd_hdr, nx_hdr, in_hdr};   // (the fields besides J and PB)
endmodule
`default_nettype wire

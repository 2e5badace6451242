`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_gra_beats_in
// -----------------------------------------------------------------------------
// Purpose
//   The input of GRA's beat source (cube4_gra_beats), in two parts that
//   leave separately. The beats' control (their keys, places and bits) is
//   a two-slot skid whose head the source's choice pops (out_valid,
//   out_ready): each beat comes with its place against the row the source
//   steps, decided a cycle ahead, so that the choice starts at flip-flops,
//   not at a compare of the head's slice and row with the source's. The
//   beats' data (in_data: samples and header) wait in a three-entry queue
//   of their own, which the source pops (d_pop) one stage later, as the step
//   that took the beat moves on (at most one beat is popped from the slots
//   and not yet from the queue), so the choice drives no data register's
//   enable or multiplexer select.
//   A beat's key is {m, j} (its slice and row), the
//   row's {w, r}; keys compare in order of slice, then row:
//     eq0  key == {w, r}        gt0  key >  {w, r}
//     eq1  key == {w, r + 1}    gt1  key >  {w, r + 1}
//   (r + 1 in DIM_W bits, as the source computes it, which gives it: r1 and
//   nx_r1 come from its registers, so no adder lies before the compares;
//   likewise w - 1 and nx_w - 1, wm1 and nx_wm1, for m_eq1).
//   Each of the two
//   slots keeps its key and its flags; the flags follow the row: when it
//   moves on (mv: to {nx_w, nx_r}, the source's next row) or a frame starts
//   (home: to {0, 0}) they are compared again against the new row, and a
//   beat that enters takes its flags against the row of the next cycle.
//   The flags are kept in two slots of registers, not in
//   entries behind a multiplexer: the head slot (h_*) holds the head
//   beat's, the back slot (b_*) the beat behind it. A pop moves the back
//   slot's beat (or, where none waits, the entering one) into the head slot,
//   so the head's flags are flip-flops that feed the choice directly, with
//   no read pointer between them and the choice that pops them. The back
//   slot loads the entering beat whenever it holds none (its enable a
//   register), as the skid's entries do.
//   Each slot also keeps its beat's partial beam, binary and as bit words
//   decoded as it enters (oh: bit pb; below: bits 0 .. pb - 1), its slice,
//   and CW control bits of the beat (in_ctl: the source's end of slice and
//   of frame, SY, OSY), so that the source's choice and what it loads take
//   them from flip-flops, not from a multiplexer and a compare with every
//   bit position.
//   Its slice m against the row's slice w follows the row alike (the source's
//   w_in and w_last, which load from w or w + 1 against m + 1, take these
//   flags instead of an adder and a compare behind the skid's multiplexer):
//     m_ge  m >= w       m_gt  m > w
//     m_eq  m == w       m_eq1 m + 1 == w  (M_W bits, as the source's w + 1)
//
// Parameters
//   DATA_W   the payload (any format).                1..4096.
//   M_W      bits of a slice.                         1..16.
//   DIM_W    bits of a row.                           1..16.
//   PB_W     bits of a partial beam.                  1..8.
//   NBX      bits of a row word (partial beams 0 .. NBX - 1).  1..256.
//   CW       control bits kept with the flags (in_ctl). 1..8.
//
// Latency: one cycle from an accepted input to out_valid; in_ready is a
//   register (the back slot is free). The head's flags, bit words, slice,
//   partial beam and control bits are registers (the head slot). d_data is
//   the queue's oldest entry not yet popped by d_pop, a 3:1 multiplexer
//   after the entries, selected by a register (the queue's read pointer).
//   The caller pops the queue only for a beat it took from the slots
//   (simulation checks: never an empty queue, never more than one beat taken
//   and not popped); then the queue never overflows (two slots and one beat).
//
// Ports
//   in_valid, in_ready, in_data   the input stream (in_data: any format)
//   in_m, in_j    the key of in_data
//   out_valid, out_ready   the head slot's beat; a transfer takes it
//   d_pop         the queue's oldest beat leaves (the caller took it)
//   d_data        out  the queue's oldest beat's in_data
//   w, r, r1, wm1 the row being stepped, r + 1 and w - 1 (M_W bits; the
//                 source's registers)
//   mv, nx_w, nx_r, nx_r1, nx_wm1  it moves on to {nx_w, nx_r} this cycle
//                 (nx_r1 = nx_r + 1, nx_wm1 = nx_w - 1)
//   home          it is set to {0, 0} this cycle (a frame's start)
//   in_pb         the partial beam of in_data (below NBX)
//   in_ctl        [CW] control bits of in_data (any meaning; ctl shows the head's)
//   eq0, gt0, eq1, gt1   out  the head's place (valid with out_valid)
//   m_ge, m_gt, m_eq, m_eq1  out  the head's slice against w (valid with
//                 out_valid)
//   oh, below     out  the head's partial beam pb as bit words [NBX]: bit pb;
//                 bits 0 .. pb - 1 (valid with out_valid)
//   ctl           out  [CW] the head's in_ctl (valid with out_valid)
//   m, pb         out  the head's slice (in_m) and partial beam (in_pb)
//
// Bit growth and rounding: none (compares only).
// =============================================================================
module cube4_gra_beats_in #(
    parameter integer DATA_W = 8,
    parameter integer M_W    = 8,
    parameter integer DIM_W  = 8,
    parameter integer PB_W   = 4,
    parameter integer NBX    = 16,
    parameter integer CW     = 1
) (
    input  wire clk, input wire rst,
    input  wire in_valid, output wire in_ready, input wire [DATA_W-1:0] in_data,   // the beats
    output wire out_valid, input wire out_ready,                                 // the head slot
    input  wire d_pop, output wire [DATA_W-1:0] d_data,                          // the data queue
    input  wire [M_W-1:0]   in_m,
    input  wire [DIM_W-1:0] in_j,
    input  wire [M_W-1:0]   w,
    input  wire [DIM_W-1:0] r,
    input  wire [DIM_W-1:0] r1,
    input  wire [M_W-1:0]   wm1,
    input  wire             mv,
    input  wire [M_W-1:0]   nx_w,
    input  wire [DIM_W-1:0] nx_r,
    input  wire [DIM_W-1:0] nx_r1,
    input  wire [M_W-1:0]   nx_wm1,
    input  wire             home,
    input  wire [PB_W-1:0]  in_pb,
    input  wire [CW-1:0]    in_ctl,
    output wire             eq0, output wire gt0, output wire eq1, output wire gt1,
    output wire             m_ge, output wire m_gt, output wire m_eq, output wire m_eq1,
    output wire [NBX-1:0]   oh, output wire [NBX-1:0] below,
    output wire [CW-1:0]    ctl,
    output wire [M_W-1:0]   m,
    output wire [PB_W-1:0]  pb
);
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_gra_beats_in", "DATA_W", DATA_W, 1, 4096)
        `CUBE4_RANGE(g_bad_m_w, "cube4_gra_beats_in", "M_W", M_W, 1, 16)
        `CUBE4_RANGE(g_bad_dim_w, "cube4_gra_beats_in", "DIM_W", DIM_W, 1, 16)
        `CUBE4_RANGE(g_bad_pb_w, "cube4_gra_beats_in", "PB_W", PB_W, 1, 8)
        `CUBE4_RANGE(g_bad_nbx, "cube4_gra_beats_in", "NBX", NBX, 1, 256)
        `CUBE4_RANGE(g_bad_cw, "cube4_gra_beats_in", "CW", CW, 1, 8)
    endgenerate
    localparam integer KW = M_W + DIM_W;

    wire push = in_valid && in_ready;
    wire pop  = out_valid && out_ready;      // (out_valid: the head slot's h_v)

    // {eq0, gt0, eq1, gt1, m_ge, m_gt, m_eq, m_eq1} of a key {m, j} against the
    // row {rw, rr} (rr1 = rr + 1, rwm1 = rw - 1)
    localparam integer PLW = 8;
    // Each compare is a pair of carry chains, a <= b and a >= b (a < b + 1/2 and
    // b < a + 1/2: a bit below the LSB tells them apart from each other and from
    // a plain compare, so synthesis keeps them as two chains), and equality is
    // their AND: one LUT after the chains, not a tree of LUTs over the bits
    // before the choices the flags go through (m + 1 == w is m == w - 1, whose
    // w - 1 comes from registers: the caller's wm1, nx_wm1).
    function automatic [1:0] le_ge_k(input [KW-1:0] a, input [KW-1:0] b);     // {a <= b, a >= b}
        le_ge_k = {{a, 1'b0} < {b, 1'b1}, {b, 1'b0} < {a, 1'b1}};
    endfunction
    function automatic [1:0] le_ge_m(input [M_W-1:0] a, input [M_W-1:0] b);
        le_ge_m = {{a, 1'b0} < {b, 1'b1}, {b, 1'b0} < {a, 1'b1}};
    endfunction
    function automatic [PLW-1:0] place(input [KW-1:0] key, input [M_W-1:0] rw, input [DIM_W-1:0] rr,
                                       input [DIM_W-1:0] rr1, input [M_W-1:0] rwm1);
        reg [1:0] c0, c1, cm, cm1;       // {<=, >=} against {rw, rr}, {rw, rr1}, rw, rw - 1
        begin
            c0  = le_ge_k(key, {rw, rr});
            c1  = le_ge_k(key, {rw, rr1});
            cm  = le_ge_m(key[KW-1 -: M_W], rw);
            cm1 = le_ge_m(key[KW-1 -: M_W], rwm1);
            place = {&c0, !c0[1], &c1, !c1[1], cm[0], !cm[1], &cm, &cm1};
        end
    endfunction
    // a key's place in the next cycle, from its place now (kept while the row stays)
    function automatic [PLW-1:0] next_place(input [KW-1:0] key, input [PLW-1:0] now, input h, input mvd,
                                            input [M_W-1:0] mw, input [DIM_W-1:0] mr, input [DIM_W-1:0] mr1,
                                            input [M_W-1:0] mwm1);
        next_place = h ? place(key, '0, '0, DIM_W'(1), {M_W{1'b1}})
                       : (mvd ? place(key, mw, mr, mr1, mwm1) : now);
    endfunction

    // a partial beam's bit words
    function automatic [NBX-1:0] bit_of(input [PB_W-1:0] b_pb);    // bit b_pb
        integer b;
        for (b = 0; b < NBX; b = b + 1) bit_of[b] = (PB_W'(b) == b_pb);
    endfunction
    function automatic [NBX-1:0] below_of(input [PB_W-1:0] b_pb);  // bits 0 .. b_pb - 1
        integer b;
        for (b = 0; b < NBX; b = b + 1) below_of[b] = (PB_W'(b) < b_pb);
    endfunction

    // a slot: {key, flags, bit words, partial beam, control bits}; the flags move with the row
    localparam integer LOW = 2 * NBX + PB_W + CW;         // the bits below the flags
    localparam integer SLW = KW + PLW + LOW;
    function automatic [SLW-1:0] moved(input [SLW-1:0] sl, input h, input mvd, input [M_W-1:0] mw,
                                       input [DIM_W-1:0] mr, input [DIM_W-1:0] mr1, input [M_W-1:0] mwm1);
        moved = {sl[SLW-1 -: KW], next_place(sl[SLW-1 -: KW], sl[SLW-KW-1 -: PLW], h, mvd, mw, mr, mr1, mwm1),
                 sl[LOW-1:0]};
    endfunction
    wire [KW-1:0]  in_key = {in_m, in_j};
    wire [SLW-1:0] in_sl  = {in_key, next_place(in_key, place(in_key, w, r, r1, wm1), home, mv, nx_w, nx_r, nx_r1,
                                                nx_wm1),
                             bit_of(in_pb), below_of(in_pb), in_pb, in_ctl};
    reg            h_v, b_v;                // the head slot holds the head beat, the back slot the one behind
    reg  [SLW-1:0] h_sl, b_sl;
    wire [SLW-1:0] h_mv = moved(h_sl, home, mv, nx_w, nx_r, nx_r1, nx_wm1);
    wire [SLW-1:0] b_mv = moved(b_sl, home, mv, nx_w, nx_r, nx_r1, nx_wm1);
    always @(posedge clk) begin
        if (rst) begin
            h_v <= 1'b0;
            b_v <= 1'b0;
        end else begin
            h_v <= pop ? (b_v || push) : (h_v || push);
            b_v <= !pop && (b_v || (push && h_v));
        end
        // the head slot: the back slot's beat or the entering one when the head
        // leaves or none is there, its own moved on otherwise
        h_sl <= (pop && b_v) ? b_mv : ((pop || !h_v) ? in_sl : h_mv);
        // the back slot: the entering beat whenever it holds none that stays
        b_sl <= (b_v && !pop) ? b_mv : in_sl;
    end
    assign out_valid = h_v;
    assign in_ready  = !b_v;
    assign {eq0, gt0, eq1, gt1, m_ge, m_gt, m_eq, m_eq1} = h_sl[SLW-KW-1 -: PLW];
    assign oh    = h_sl[LOW-1 -: NBX];
    assign below = h_sl[LOW-NBX-1 -: NBX];
    assign pb    = h_sl[PB_W+CW-1 -: PB_W];
    assign ctl   = h_sl[CW-1:0];
    assign m     = h_sl[SLW-1 -: M_W];

    // the data queue: entry dw loads in_data while in_ready (it is free then: the
    // slots hold at most one beat and one more is taken and not popped), so its
    // enable is registers; d_pop moves the read pointer alone
    reg [1:0]        dw, dr;                  // write and read pointers, 0 .. 2
    reg [DATA_W-1:0] dq [0:2];
    function automatic [1:0] inc3(input [1:0] ptr);
        inc3 = (ptr == 2'd2) ? 2'd0 : ptr + 2'd1;
    endfunction
    always @(posedge clk) begin
        if (rst) begin
            dw <= 2'd0;
            dr <= 2'd0;
        end else begin
            if (push)  dw <= inc3(dw);
            if (d_pop) dr <= inc3(dr);
        end
    end
    genvar e;
    generate
        for (e = 0; e < 3; e = e + 1) begin : g_dq
            always @(posedge clk) begin
                if (in_ready && dw == 2'(e)) dq[e] <= in_data;
            end
        end
    endgenerate
    assign d_data = dq[dr];
`ifndef SYNTHESIS
    // the caller's promise: the queue holds the slots' beats and at most one more
    reg       reset_seen;
    integer   taken;                         // beats taken from the slots and not popped from the queue
    initial reset_seen = 1'b0;
    always @(posedge clk) begin
        if (rst) begin
            reset_seen <= 1'b1;
            taken      <= 0;
        end else if (reset_seen) begin
            if (d_pop && taken == 0 && !pop)
                $fatal(1, "cube4_gra_beats_in: d_pop with no beat taken from the slots");
            if (taken + (pop ? 1 : 0) - (d_pop ? 1 : 0) > 1)
                $fatal(1, "cube4_gra_beats_in: two beats taken from the slots and not popped from the queue");
            taken <= taken + (pop ? 1 : 0) - (d_pop ? 1 : 0);
        end
    end
`endif
endmodule
`default_nettype wire

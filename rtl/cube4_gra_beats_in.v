`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_gra_beats_in
// -----------------------------------------------------------------------------
// Purpose
//   The input of GRA's beat source (cube4_gra_beats): a skid buffer
//   (cube4_skid) whose head beat comes with its place against the row the
//   source steps, decided a cycle ahead, so that the source's choice of the
//   next step starts at flip-flops, not at a compare of the head's slice and
//   row with the source's. A beat's key is {m, j} (its slice and row), the
//   row's {w, r}; keys compare in order of slice, then row:
//     eq0  key == {w, r}        gt0  key >  {w, r}
//     eq1  key == {w, r + 1}    gt1  key >  {w, r + 1}
//   (r + 1 in DIM_W bits, as the source computes it, which gives it: r1 and
//   nx_r1 come from its registers, so no adder lies before the compares).
//   Each of the two
//   entries keeps its key and its flags; the flags follow the row: when it
//   moves on (mv: to {nx_w, nx_r}, the source's next row) or a frame starts
//   (home: to {0, 0}) they are compared again against the new row, and a
//   beat that enters takes its flags against the row of the next cycle.
//   The flags are kept in two slots of registers of their own, not in the
//   skid's entries behind a multiplexer: the head slot (h_*) holds the head
//   beat's, the back slot (b_*) the beat behind it. A pop moves the back
//   slot's beat (or, where none waits, the entering one) into the head slot,
//   so the head's flags are flip-flops that feed the choice directly, with
//   no read pointer between them and the choice that pops them. The back
//   slot loads the entering beat whenever it holds none (its enable a
//   register), as the skid's entries do.
//   Each slot also keeps its beat's partial beam as bit words, decoded as it
//   enters (oh: bit pb; below: bits 0 .. pb - 1), and CW control bits of
//   the beat (in_ctl: the source's end of slice and end of frame), so that
//   the source's choice takes them from flip-flops, not through the skid's
//   multiplexer and a compare with every bit position.
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
// Latency: as cube4_skid (one cycle; in_ready is a register). The head's
//   flags, bit words and control bits are registers (the head slot);
//   out_valid is the head slot's valid register, and out_data the skid's
//   entry at its read pointer (a simulation check holds the skid's valid
//   and ready to the slots').
//
// Ports
//   in_*, out_*   the stream (cube4_skid); in_m, in_j the key of in_data
//   w, r, r1      the row being stepped and r + 1 (the source's registers)
//   mv, nx_w, nx_r, nx_r1  it moves on to {nx_w, nx_r} this cycle (nx_r1 =
//                 nx_r + 1)
//   home          it is set to {0, 0} this cycle (a frame's start)
//   in_pb         the partial beam of in_data (below NBX)
//   in_ctl        [CW] control bits of in_data (any meaning; ctl shows the head's)
//   eq0, gt0, eq1, gt1   out  the head's place (valid with out_valid)
//   m_ge, m_gt, m_eq, m_eq1  out  the head's slice against w (valid with
//                 out_valid)
//   oh, below     out  the head's partial beam pb as bit words [NBX]: bit pb;
//                 bits 0 .. pb - 1 (valid with out_valid)
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
    `CUBE4_STREAM_PORTS(DATA_W),
    input  wire [M_W-1:0]   in_m,
    input  wire [DIM_W-1:0] in_j,
    input  wire [M_W-1:0]   w,
    input  wire [DIM_W-1:0] r,
    input  wire [DIM_W-1:0] r1,
    input  wire             mv,
    input  wire [M_W-1:0]   nx_w,
    input  wire [DIM_W-1:0] nx_r,
    input  wire [DIM_W-1:0] nx_r1,
    input  wire             home,
    input  wire [PB_W-1:0]  in_pb,
    input  wire [CW-1:0]    in_ctl,
    output wire             eq0, output wire gt0, output wire eq1, output wire gt1,
    output wire             m_ge, output wire m_gt, output wire m_eq, output wire m_eq1,
    output wire [NBX-1:0]   oh, output wire [NBX-1:0] below,
    output wire [CW-1:0]    ctl
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

    wire skid_valid;
    cube4_skid #(.DATA_W(DATA_W)) u_skid (
        .clk(clk), .rst(rst),
        .in_valid(in_valid), .in_ready(in_ready), .in_data(in_data),
        .out_valid(skid_valid), .out_ready(out_ready), .out_data(out_data));
    wire push = in_valid && in_ready;
    wire pop  = out_valid && out_ready;      // (out_valid: the head slot's h_v)

    // {eq0, gt0, eq1, gt1, m_ge, m_gt, m_eq, m_eq1} of a key {m, j} against the
    // row {rw, rr} (rr1 = rr + 1)
    localparam integer PLW = 8;
    // Each compare is a pair of carry chains, a <= b and a >= b (a < b + 1/2 and
    // b < a + 1/2: a bit below the LSB tells them apart from each other and from
    // a plain compare, so synthesis keeps them as two chains), and equality is
    // their AND: one LUT after the chains, not a tree of LUTs over the bits
    // before the choices the flags go through (m + 1 == w is m == w - 1, whose
    // w - 1 comes from registers).
    function automatic [1:0] le_ge_k(input [KW-1:0] a, input [KW-1:0] b);     // {a <= b, a >= b}
        le_ge_k = {{a, 1'b0} < {b, 1'b1}, {b, 1'b0} < {a, 1'b1}};
    endfunction
    function automatic [1:0] le_ge_m(input [M_W-1:0] a, input [M_W-1:0] b);
        le_ge_m = {{a, 1'b0} < {b, 1'b1}, {b, 1'b0} < {a, 1'b1}};
    endfunction
    function automatic [PLW-1:0] place(input [KW-1:0] key, input [M_W-1:0] rw, input [DIM_W-1:0] rr,
                                       input [DIM_W-1:0] rr1);
        reg [1:0] c0, c1, cm, cm1;       // {<=, >=} against {rw, rr}, {rw, rr1}, rw, rw - 1
        begin
            c0  = le_ge_k(key, {rw, rr});
            c1  = le_ge_k(key, {rw, rr1});
            cm  = le_ge_m(key[KW-1 -: M_W], rw);
            cm1 = le_ge_m(key[KW-1 -: M_W], M_W'(rw - 1'b1));
            place = {&c0, !c0[1], &c1, !c1[1], cm[0], !cm[1], &cm, &cm1};
        end
    endfunction
    // a key's place in the next cycle, from its place now (kept while the row stays)
    function automatic [PLW-1:0] next_place(input [KW-1:0] key, input [PLW-1:0] now, input h, input m,
                                            input [M_W-1:0] mw, input [DIM_W-1:0] mr, input [DIM_W-1:0] mr1);
        next_place = h ? place(key, '0, '0, DIM_W'(1)) : (m ? place(key, mw, mr, mr1) : now);
    endfunction

    // a partial beam's bit words
    function automatic [NBX-1:0] bit_of(input [PB_W-1:0] pb);      // bit pb
        integer b;
        for (b = 0; b < NBX; b = b + 1) bit_of[b] = (PB_W'(b) == pb);
    endfunction
    function automatic [NBX-1:0] below_of(input [PB_W-1:0] pb);    // bits 0 .. pb - 1
        integer b;
        for (b = 0; b < NBX; b = b + 1) below_of[b] = (PB_W'(b) < pb);
    endfunction

    // a slot: {key, flags, bit words, control bits}; the flags move with the row
    localparam integer SLW = KW + PLW + 2 * NBX + CW;
    function automatic [SLW-1:0] moved(input [SLW-1:0] sl, input h, input m, input [M_W-1:0] mw,
                                       input [DIM_W-1:0] mr, input [DIM_W-1:0] mr1);
        moved = {sl[SLW-1 -: KW], next_place(sl[SLW-1 -: KW], sl[SLW-KW-1 -: PLW], h, m, mw, mr, mr1),
                 sl[2*NBX+CW-1:0]};
    endfunction
    wire [KW-1:0]  in_key = {in_m, in_j};
    wire [SLW-1:0] in_sl  = {in_key, next_place(in_key, place(in_key, w, r, r1), home, mv, nx_w, nx_r, nx_r1),
                             bit_of(in_pb), below_of(in_pb), in_ctl};
    reg            h_v, b_v;                // the head slot holds the head beat, the back slot the one behind
    reg  [SLW-1:0] h_sl, b_sl;
    wire [SLW-1:0] h_mv = moved(h_sl, home, mv, nx_w, nx_r, nx_r1);
    wire [SLW-1:0] b_mv = moved(b_sl, home, mv, nx_w, nx_r, nx_r1);
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
    assign {eq0, gt0, eq1, gt1, m_ge, m_gt, m_eq, m_eq1} = h_sl[SLW-KW-1 -: PLW];
    assign oh    = h_sl[2*NBX+CW-1 -: NBX];
    assign below = h_sl[NBX+CW-1 -: NBX];
    assign ctl   = h_sl[CW-1:0];
`ifndef SYNTHESIS
    // the slots follow the skid's own state (from the first reset on)
    reg reset_seen;
    initial reset_seen = 1'b0;
    always @(posedge clk) begin
        if (rst) reset_seen <= 1'b1;
        if (!rst && reset_seen && (skid_valid != h_v || in_ready == b_v))
            $fatal(1, "cube4_gra_beats_in: the slots' valid (%b, %b) are not the skid's (out_valid %b, in_ready %b)",
                   h_v, b_v, skid_valid, in_ready);
    end
`endif
endmodule
`default_nettype wire

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
//   The entries' pointers shadow the skid's (both move on its push and pop).
//   Each entry also keeps its beat's partial beam as bit words, decoded as it
//   enters (oh: bit pb; below: bits 0 .. pb - 1), so that the source's choice
//   takes them from flip-flops through one multiplexer, not through the
//   skid's multiplexer and a compare with every bit position.
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
//
// Latency: as cube4_skid (one cycle; in_ready is a register). The flags of
//   the head are registers selected by a register (the read pointer).
//
// Ports
//   in_*, out_*   the stream (cube4_skid); in_m, in_j the key of in_data
//   w, r, r1      the row being stepped and r + 1 (the source's registers)
//   mv, nx_w, nx_r, nx_r1  it moves on to {nx_w, nx_r} this cycle (nx_r1 =
//                 nx_r + 1)
//   home          it is set to {0, 0} this cycle (a frame's start)
//   in_pb         the partial beam of in_data (below NBX)
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
    parameter integer NBX    = 16
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
    output wire             eq0, output wire gt0, output wire eq1, output wire gt1,
    output wire             m_ge, output wire m_gt, output wire m_eq, output wire m_eq1,
    output wire [NBX-1:0]   oh, output wire [NBX-1:0] below
);
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_gra_beats_in", "DATA_W", DATA_W, 1, 4096)
        `CUBE4_RANGE(g_bad_m_w, "cube4_gra_beats_in", "M_W", M_W, 1, 16)
        `CUBE4_RANGE(g_bad_dim_w, "cube4_gra_beats_in", "DIM_W", DIM_W, 1, 16)
        `CUBE4_RANGE(g_bad_pb_w, "cube4_gra_beats_in", "PB_W", PB_W, 1, 8)
        `CUBE4_RANGE(g_bad_nbx, "cube4_gra_beats_in", "NBX", NBX, 1, 256)
    endgenerate
    localparam integer KW = M_W + DIM_W;

    cube4_skid #(.DATA_W(DATA_W)) u_skid (
        .clk(clk), .rst(rst),
        .in_valid(in_valid), .in_ready(in_ready), .in_data(in_data),
        .out_valid(out_valid), .out_ready(out_ready), .out_data(out_data));
    wire push = in_valid && in_ready;
    wire pop  = out_valid && out_ready;

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

    reg            wp, rp;                 // the skid's pointers, shadowed
    reg  [KW-1:0]  key [0:1];
    reg  [PLW-1:0] pl  [0:1];
    reg  [NBX-1:0] e_oh [0:1], e_below [0:1];
    wire [KW-1:0]  in_key = {in_m, in_j};
    wire [PLW-1:0] in_pl  = next_place(in_key, place(in_key, w, r, r1), home, mv, nx_w, nx_r, nx_r1);
    always @(posedge clk) begin
        if (rst) begin
            wp <= 1'b0;
            rp <= 1'b0;
        end else begin
            if (push) wp <= !wp;
            if (pop)  rp <= !rp;
        end
    end
    genvar e;
    generate
        for (e = 0; e < 2; e = e + 1) begin : g_entry
            always @(posedge clk) begin
                if (push && wp == (e == 1)) begin
                    key[e]     <= in_key;
                    pl[e]      <= in_pl;
                    e_oh[e]    <= bit_of(in_pb);
                    e_below[e] <= below_of(in_pb);
                end else begin
                    pl[e]  <= next_place(key[e], pl[e], home, mv, nx_w, nx_r, nx_r1);
                end
            end
        end
    endgenerate
    assign {eq0, gt0, eq1, gt1, m_ge, m_gt, m_eq, m_eq1} = pl[rp];
    assign oh    = e_oh[rp];
    assign below = e_below[rp];
endmodule
`default_nettype wire

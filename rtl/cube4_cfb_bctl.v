`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_bctl
// -----------------------------------------------------------------------------
// Purpose
//   The control and traversal of cube4_cfb on the beat schedule (BEATS = 1;
//   docs/numerics.md section 19, docs/architecture.md "The front end's
//   plan"): in place of cube4_cfb_ctl and cube4_cfb_trav, it turns the
//   walk's beats (cube4_cfb_skip: voxel beat (m, j, pb) of sample slice m,
//   rows and slices in order, partial beams rising within a row, every row
//   ending with a beat that carries EOR) into the fields of the request beat
//   (CUBE4_TAG_LAYOUT, as cube4_cfb_ctl describes them) and the address terms
//   of cube4_cfb_addr. The same three stages follow (cube4_cfb_mask,
//   cube4_cfb_addr), with the box as the pass's rectangle (cube4_cfb_box).
//     the row     j and its terms c_j mod P, A_j and j * NB step at each
//                 row's last beat (EOR); the walk's tokens (rows that read
//                 nothing) only step them and issue nothing
//     the slice   m, r = m mod S, the template (next_pass) step at each
//                 slice's last beat (EOS); then row 0 again. As the fixed
//                 schedule's traversal (cube4_cfb_trav): a pass reads the
//                 memory where it reads a voxel slice (pass 0 its lower
//                 slice, LMEM; with S > 1 each pass k0 S + 1 its upper slice
//                 k0 + 1, UMEM), the others replay the slices from TRI's
//                 slice buffers (K0ODD their parity); c_k mod P and A_k of
//                 the next slice to read step after a pass that read, the
//                 lower slice's residue (the pass's skew) when r wraps
//     the beat    pb from the walk; pb * I_PB from cube4_mul (two stages
//                 before the state, so the product meets its beat)
//   The emitted row (as cube4_cfb_ctl): the row below, j - 1, or at row 0
//   the previous slice's last row NJ - 1 (use_prev: its weights, steps and
//   the skew of its virtual row NJ are kept at its slice's last beat; the
//   read row is then zero for it, YWRAP). Every beat but a token emits the
//   sample beat of its row below, its lanes below NI valid where that beat
//   runs (LEAVE), none elsewhere: COM's buffers move the partial results
//   through the beats of the cover and of the row above, and every slice
//   reaches the units behind (its marker). A beat of row 0 of slice 0,
//   which would emit slice -1, emits nothing. The last beat carries EOP.
//   The last beat of row 0 of a slice m > 0 (the walk makes it a marker
//   when it walks nothing) and of the flush row emits the last beat of
//   sample slice m - 1: it carries EOSS (x_eoss), and a push beat follows
//   it, so that GRA and COM see each sample slice end without waiting for
//   the next beat (numerics.md section 19, lag).
//   A beat needs its voxel beat (BBWE; from the memory in a pass that reads
//   one, else from the slice buffers) when the walk says it reads, except in
//   the flush row (m = M), which reads nothing. Tokens issue nothing; after LAST one drain beat
//   pushes TRI's beam-extension delay empty, as the fixed schedule's, and
//   after each slice's last beat (EOS) one such beat pushes it too: TRI
//   gives a sample beat when the next beat comes, and the next may wait for
//   the decisions, which wait for COM's reports of the slices before (the
//   loop the push beat opens; numerics.md section 19, lag).
//
// Parameters (CUBE4_CFB_PARAMS; ranges as cube4_cfb)
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2, ADDR_W. (With MAX_SS_LOG2 = 0 the
//   view's log2 S is taken as 0.)
//
// Latency
//   Two register stages in front of the state: a (the walk's beat, the
//   multiplier's operand registers) and b (the state, the product). Both
//   move under mv = the state is empty or taken (advance, cube4_cfb_mask's
//   stall enable); in_ready = mv. The state's outputs are combinational
//   from registers, and the three stages of cube4_cfb_mask follow. The
//   slice and row counters and the template's step (next_pass) take the
//   beat by advance_step, an equal copy of advance (CFB_ADV_STEP), so that
//   neither net reaches all of the unit's registers.
//
// Ports
//   clk, rst     clock, synchronous active-high reset (the state and the
//                stages' valid bits)
//   cfg, cfg_addr  in  view and address registers (NJ, NK, NB, NI, log2 S,
//                the flips, residues and address terms)
//   start, busy  in   start a frame (taken while not busy); cube4_cfb's busy
//   go           out  start && !busy (the walk starts with it)
//   in_valid/in_ready   the walk's beats: in_pb [PB_W], in_read, in_leave,
//                in_tok, in_eor, in_eos, in_last, in_bits [4P] ({soon, last,
//                fresh, run} of the leaving beat, cube4_cfb_skip)
//   advance      in   the stages move (cube4_cfb_mask)
//   advance_step in   an equal copy of advance for the counters (above)
//   wx, wy, wz [W] (Q0.W), steps [4]  in  the template's (cube4_cfb_tmpl)
//   idle, next_pass, r [CFB_R_W]  out  the template's controls (r = m mod S:
//                its wz; idle also cube4_cfb_mask's)
//   issue, fields [CFB_F1_W], use_prev, skew_out, p_ilo, p_iin, p_ihi,
//   rowv, rowin, rd   out  the state's beat (CUBE4_CFB_MASK_PORTS)
//   pbp [IW]     out  pb * P;  skew_rd [LANE_W], aj, ak, pbx [ADDR_W]  out
//                the read's address terms (cube4_cfb_addr)
//   x_bits [4P], x_eos, x_eoss  out  the state's beat's position bits, EOS
//                and EOSS (it emits its sample slice's last beat)
//
// Bit growth and rounding
//   None: counters and modular address arithmetic in ADDR_W bits; the
//   product pb * I_PB is exact in PB_W + ADDR_W + 2 bits and taken mod
//   2^ADDR_W, as the fixed schedule's sum of I_PB steps.
// =============================================================================
module cube4_cfb_bctl #(`CUBE4_CFB_PARAMS) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg, input wire [ADR_W_ALL-1:0] cfg_addr,
    input  wire start, input wire busy, output wire go,
    input  wire in_valid, output wire in_ready, input wire [PB_W-1:0] in_pb,
    input  wire in_read, input wire in_leave, input wire in_tok, input wire in_eor, input wire in_eos,
    input  wire in_last,
    input  wire [4*P-1:0] in_bits,
    input  wire advance, input wire advance_step,
    input  wire [WEIGHT_W-1:0] wx, input wire [WEIGHT_W-1:0] wy, input wire [WEIGHT_W-1:0] wz,
    input  wire [3:0] steps,
    output wire idle, output wire next_pass, output wire [CFB_R_W-1:0] r,
    output wire issue, output wire [CFB_F1_W-1:0] fields,
    output wire use_prev, output wire [LANE_W-1:0] skew_out,
    output wire [DIM_W-1:0] p_ilo, output wire [DIM_W-1:0] p_iin, output wire [DIM_W-1:0] p_ihi,
    output wire rowv, output wire rowin, output wire rd,
    output wire [IW-1:0] pbp, output wire [LANE_W-1:0] skew_rd,
    output wire [ADDR_W-1:0] aj, output wire [ADDR_W-1:0] ak, output wire [ADDR_W-1:0] pbx,
    output wire [4*P-1:0] x_bits, output wire x_eos, output wire x_eoss
);
    `CUBE4_VIEW_FIELDS(cfg);
    `CUBE4_ADDR_FIELDS(cfg_addr);
    `CUBE4_LANE_FUNCTIONS
    localparam integer MA_W = PB_W + 1, MB_W = ADDR_W + 1;   // unsigned operands, a zero bit on top

    `CUBE4_STEP_FUNCTIONS

    // ==== the state: idle, the walk's beats, the drain beat ====
    localparam [1:0] ST_IDLE = 2'd0, ST_RUN = 2'd1, ST_DRAIN = 2'd2, ST_PUSH = 2'd3;
    reg [1:0] state_q;
    assign idle = (state_q == ST_IDLE);
    assign go   = start && !busy;
    wire in_run   = (state_q == ST_RUN);
    wire in_drain = (state_q == ST_DRAIN) || (state_q == ST_PUSH);

    // ==== two stages in front of the state ====
    localparam integer B_W = 4 * P + 6;    // {bits, read, leave, eor, eos, last, token}
    reg              a_v, b_v;
    reg [PB_W-1:0]   a_pb, b_pb;
    reg [B_W-1:0]    a_f, b_f;
    wire             take = b_v && advance && in_run; // the state's beat moves on (not in a push)
    wire             mv   = !b_v || take;
    assign in_ready = mv;
    always @(posedge clk) begin
        if (rst) begin
            a_v <= 1'b0;
            b_v <= 1'b0;
        end else if (mv) begin
            a_v <= in_valid;
            b_v <= a_v;
        end
        if (mv) begin
            a_pb <= in_pb;
            a_f  <= {in_bits, in_read, in_leave, in_eor, in_eos, in_last, in_tok};
            b_pb <= a_pb;
            b_f  <= a_f;
        end
    end
    wire [4*P-1:0] b_bits;
    wire           b_read, b_leave, b_eor, b_eos, b_last, b_token;
    assign {b_bits, b_read, b_leave, b_eor, b_eos, b_last, b_token} = b_f;

    // pb * I_PB, two stages from in_pb: it meets its beat in the state
    wire signed [MA_W+MB_W-1:0] prod;
    cube4_mul #(.A_W(MA_W), .B_W(MB_W)) u_pbx (
        .clk (clk),
        .en  (mv),
        .a   ($signed({1'b0, in_pb})),
        .b   ($signed({1'b0, cfg_i_pb})),
        .p   (prod)
    );
    wire [ADDR_W-1:0] pb_term = prod[ADDR_W-1:0];
    wire unused_prod = ^prod[MA_W+MB_W-1:ADDR_W];

    // ==== the counters: slice, row and their terms ====
    reg [M_W-1:0]    m_q;
    reg [DIM_W-1:0]  j_q;
    reg              j0_q;         // j_q = 0: the emitted row is the previous slice's last
    reg              lsl_q;        // m_q = M - 1
    reg              fl_q;         // m_q = M: the flush row
    reg [LANE_W-1:0] rj_q, rk_q;  // rk_q, ak_q: the next voxel slice to read
    reg [ADDR_W-1:0] aj_q, ak_q;
    reg [LANE_W-1:0] rk0_q;        // c_k mod P of the pass's lower voxel slice k0
    reg              k0o_q;        // k0 mod 2 (the slice buffers' parity)
    reg [CFB_R_W-1:0] r_q;         // m mod S
    reg [SB_W-1:0]   sbrow_q;      // j * NB
    reg              sopp_q;       // no sample beat emitted yet
    // the previous slice, for the row emitted in row 0 and the flush row
    reg [WEIGHT_W-1:0] pwx_q, pwy_q, pwz_q;
    reg [3:0]          psteps_q;
    reg [LANE_W-1:0]   pskew_q;

    wire run_take   = b_v && advance_step && in_run;   // take, from the counters' copy
`ifndef SYNTHESIS
    always @(posedge clk) begin
        if (!rst && advance != advance_step)
            $fatal(1, "cube4_cfb_bctl: advance and its copy advance_step differ");
    end
`endif
    wire emit       = in_run && !(j0_q && m_q == '0);   // (tokens do not issue; no slice -1)
    wire reads      = in_run && b_read && !fl_q;        // the beat's voxel beat is needed
    // the pass (as cube4_cfb_trav): log2 S, which slice it reads from the memory
    `CUBE4_VIEW_SLICES;
    wire [1:0] ssl       = view_ssl;
    wire [CFB_R_W-1:0] ss_m1 = CFB_R_W'((1 << ssl) - 1);
    wire       last_r    = (r_q == ss_m1);
    wire       lower_mem = (ssl == 2'd0) || (m_q == '0);
    wire       upper_mem = (ssl != 2'd0) && (r_q == CFB_R_W'(1));
    wire       any_read  = lower_mem || upper_mem;
    wire slice_step = run_take && b_eos;
    wire b_eoss     = b_eor && ((j0_q && m_q != '0) || fl_q);   // the row emits its sample slice's last beat
    wire row_step   = run_take && b_eor && !b_eos;
    assign next_pass = slice_step;
    wire [LANE_W-1:0] skew_pas = add_p(rj_q, rk0_q);  // the pass's lower slice

    always @(posedge clk) begin
        if (rst) begin
            state_q <= ST_IDLE;
        end else begin
            case (state_q)
                ST_IDLE:  if (go) state_q <= ST_RUN;
                ST_RUN:   if (take && b_last) state_q <= ST_DRAIN;
                          else if (take && (b_eos || b_eoss)) state_q <= ST_PUSH;
                ST_DRAIN: if (advance) state_q <= ST_IDLE;    // one beat
                ST_PUSH:  if (advance) state_q <= ST_RUN;     // one beat
                default:  state_q <= ST_IDLE;
            endcase
        end
    end
    always @(posedge clk) begin
        if (idle) begin
            m_q     <= '0;
            j_q     <= '0;
            j0_q    <= 1'b1;
            lsl_q   <= (cfg_nk == DIM_W'(1));           // M = 1
            fl_q    <= 1'b0;
            rj_q    <= cfg_j_r0;
            aj_q    <= cfg_j_a0;
            rk_q    <= cfg_k_r0;
            ak_q    <= cfg_k_a0;
            rk0_q   <= cfg_k_r0;
            k0o_q   <= 1'b0;
            r_q     <= '0;
            sbrow_q <= '0;
            sopp_q  <= 1'b1;
        end else begin
            if (run_take && issue && emit) sopp_q <= 1'b0;
            if (row_step) begin
                j_q     <= j_q + 1'b1;
                j0_q    <= 1'b0;
                rj_q    <= r_step(rj_q, cfg_flip_j);
                aj_q    <= a_step(aj_q, rj_q, cfg_flip_j, cfg_j_lin, cfg_j_blk);
                sbrow_q <= sbrow_q + SB_W'(cfg_nb);
            end
            if (slice_step) begin
                // slice m's last beat: keep its last row's fields, go to row 0 of m + 1
                pwx_q    <= wx;
                pwy_q    <= wy;
                pwz_q    <= wz;
                psteps_q <= steps;
                pskew_q  <= r_step(skew_pas, cfg_flip_j);   // the virtual row NJ
                m_q      <= m_q + 1'b1;
                lsl_q    <= (m_q + 1'b1 == view_m_last);
                fl_q     <= lsl_q;
                j_q      <= '0;
                j0_q     <= 1'b1;
                rj_q     <= cfg_j_r0;
                aj_q     <= cfg_j_a0;
                sbrow_q  <= '0;
                `CUBE4_PASS_NEXT
                if (last_r) k0o_q <= !k0o_q;
            end
        end
    end

    // ==== the state's beat ====
    assign issue    = (in_run && b_v && !b_token) || in_drain;
    assign use_prev = j0_q;
    assign r        = r_q;                             // the template's wz = r / S
    assign skew_out = j0_q ? pskew_q : skew_pas;
    wire [M_W-1:0]      mout   = j0_q ? m_q - 1'b1 : m_q;
    wire [DIM_W-1:0]    jout   = j0_q ? cfg_nj - 1'b1 : j_q - 1'b1;
    wire [WEIGHT_W-1:0] wy_out = j0_q ? pwy_q : wy;
    assign rowv  = emit && b_leave;
    assign rowin = !(j0_q && (wy_out != '0));      // the box's high-face rule on row NJ - 1
    assign rd    = reads && any_read;
    assign {p_ilo, p_iin, p_ihi} = {{DIM_W{1'b0}}, {DIM_W{1'b0}}, cfg_ni};
    assign fields = {emit, emit && sopp_q, in_run && b_last, j0_q,
                     reads, reads && lower_mem, reads && upper_mem,   // BBWE, LMEM, UMEM
                     in_run && (r_q != '0),                    // UUSE
                     k0o_q, sbrow_q + SB_W'(b_pb), b_pb,
                     j0_q ? pwx_q : wx, wy_out, j0_q ? pwz_q : wz,
                     mout, jout, skew_out, j0_q,               // YLAST: the emitted row is NJ - 1
                     j0_q ? psteps_q : steps};
    assign pbp     = IW'(b_pb) * IW'(P);
    assign skew_rd = add_p(rj_q, rk_q);               // the slice read
    assign aj      = aj_q;
    assign ak      = ak_q;
    assign pbx     = cfg_flip_i ? cfg_i_a0 - pb_term : pb_term;
    assign x_bits  = in_run ? b_bits : '0;
    assign x_eos   = in_run && b_eos;
    assign x_eoss  = in_run && b_eoss;
endmodule
`default_nettype wire

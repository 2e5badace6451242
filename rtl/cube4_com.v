`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com
// -----------------------------------------------------------------------------
// Purpose
//   The COM units of all P pipelines (Teramac paper, section 5, Fig. 13, 14):
//   the ray's accumulation over the samples that count (header INSIDE and
//   KEEP), in the mode of the MODE register (docs/numerics.md sections 7, 13):
//     0 composite  w = round_shift(T * A', ALPHA_W);  C += round_shift(w * C', 8);  T -= w
//     1 X-ray      w = round_shift(2^ACC_W * A', ALPHA_W);
//                  C = min(2^ACC_W, C + round_shift(w * C', 8));  T = max(0, T - w)
//     2 MIP        keep (v, R, G, B, A) of a sample with v >= the kept v
//     3 MinIP      likewise with v <= the kept v (v starts at 2^VOXEL_W - 1)
//   with C, T in Q0.ACC_W (T starts at 2^ACC_W), and the finished-ray stream
//   (numerics.md section 8). A build has the compositing datapath (modes 0, 1:
//   the T * A and w * C' multipliers), the extremum datapath (modes 2, 3: one
//   comparator per lane, no multiplier), or both (COMPOSITING, EXTREMUM).
//
//   Base-plane buffers: the partial result of every ray lives in the lane and
//   slot of its latest sample. A one-slice buffer (NJ*NB beats per lane,
//   the paper's "base-plane buffer for one slice of intermediate compositing
//   results") and a one-beam buffer return, for sample (m, j, i), the
//   ray's partial result at its previous sample (m-1, j - dyb, i - dxb): one
//   ring hop for the k step of the skew, one for the j step, and one for the
//   X-step, which for the lane at t = 0 comes from the previous beat (Fig. 13:
//   results forwarded across partial beams and beams). A ray starts fresh
//   (C = 0, T = 1) when its previous sample is outside the slice (m = 0,
//   j - dyb < 0, i - dxb < 0). The compositing arithmetic is pipelined
//   (S6..S10); the recurrence closes through the buffer one slice later, and a
//   beat waits while the beat it depends on is still in flight.
//
//   Path-length weights (PLW = 1, numerics.md section 17): the first sample of
//   a ray that enters through a face in FACES, and the last of one that leaves
//   through one, take a weight w in quarters (1/2 .. 3/2) from the template's
//   phase and the same causes as a fresh or a finished ray, split by face; a
//   sample with w != 1 composites the LUT's path-weight column for w (a table of
//   2^VOXEL_W x 4 opacities per lane, read with the sample) instead of its A.
//
//   Finished rays: a sample that is inside and whose next sample along the ray
//   (m+1, j+dyf, i+dxf) is not (or m = M-1) finishes its ray; the ray leaves as
//   (R, G, B, A = 2^ACC_W - T) with its base-plane address
//   (bx, by) = (i - stepx(m) + SX, j - stepy(m) + SY). Output beats carry up to
//   P finished rays (lane mask) and the frame's last beat (eop) always leaves.
//
// Parameters
//   P, WEIGHT_W, MAX_DIM, MAX_SS_LOG2 and
//   the derived widths as cube4_gra.
//   VOXEL_W     sample width (the extremum's v).   1..16.  Default 8.
//   ALPHA_W     opacity width AW.                  8..16.  Default 12.
//   ACC_W       accumulator fraction bits F.       8..24.  Default 16.
//   COMPOSITING 1: modes 0, 1 (multipliers).       0..1.   Default 1.
//   EXTREMUM    1: modes 2, 3 (comparators).       0..1.   Default 1.
//               At least one of the two (elaboration stops otherwise).
//   PLW         1: path-length weights (needs COMPOSITING). 0..1. Default 1.
//   RECTS       1: slice rectangles (docs/architecture.md "COM"): the slot
//               {j, pb} from the header, fresh and finished rays against the
//               neighbouring slices' inside rectangles from the host's table
//               (rect_*, cube4_cfb's layout), the read-after-write rule by
//               position. Needs PLW = 0.              0..1.   Default 0.
//   ADDR_W      the table layout's address width (cube4_cfb's).  Default 16.
//
// Latency
//   12 register stages (R0, S1 .. S11, below) that move on every cycle (no
//   stall enable); R0 .. S10 carry a valid bit each, S11 (acc_q) is written
//   under S10's (the slice buffer's write enable and the FIFO's push, both
//   given one stage early). S11's results are written into the output FIFO (cube4_credit_fifo, 16 entries), whose memory stands in
//   for a last register: a finished-ray beat is on pix_* 12 cycles after it
//   entered R0 when the FIFO was empty.
//   Back-pressure is credit-based: a beat enters R0 only when the FIFO has an
//   entry reserved for it, so pix_ready reaches only in_ready and the FIFO's
//   pointers, never a datapath register. in_ready depends on registers only
//   (the FIFO's credit and the valid bits of R0 .. S9). The partial results
//   take exactly one slice (NJ*NB steps) round the base-plane buffer.
//   Throughput is one beat per cycle when a slice has NJ*NB >= 11 beats; a
//   smaller slice runs at NJ*NB beats per 11 cycles (the read-after-write
//   hazard on the base-plane buffer, see "pipeline" below). RECTS = 1: a beat
//   waits while the beat that wrote its slot is in R0 .. S9; in_ready then
//   also depends on in_hdr (the slot compare).
//
// Ports
//   in_*      the shaded stream of cube4_sha: in_rgba lane q = {R, G, B (Q0.8),
//             A (Q0.ALPHA_W)}; in_sample lane q = the sample v (unsigned
//             VOXEL_W; read by the extremum datapath and the path weights only)
//   lut_*     the LUT's path-weight columns (PLW = 1): lut_data = {A at w = 3/2,
//             5/4, 3/4, 1/2}, Q0.ALPHA_W each, written at lut_addr when lut_we
//             (between frames); PLW = 0: one unused bit
//   pix_*     finished rays: pix_mask (lane holds a finished ray), pix_m, pix_by,
//             pix_bx lane q, pix_rgba lane q = {R, G, B, A} each ACC_W + 1 bits
//             (Q0.ACC_W, 0 .. 2^ACC_W), pix_eop (last beat of the frame).
//             MIP / MinIP: colour << (ACC_W - 8); A << (ACC_W - ALPHA_W), or
//             round_shift(A, ALPHA_W - ACC_W) when ALPHA_W > ACC_W
//   cfg       view registers (cube4_defs.vh); SX, SY = stepx(M-1), stepy(M-1)
//
// Bit growth and rounding
//   T * A: (F+1) x AW bits; round_shift by AW (half up) gives w <= T (F+1 bits).
//   w * C': (F+1) x 8 bits; round_shift by 8 gives at most w; C + that <= 2^F - T.
//   Composite: nothing wraps and nothing saturates (numerics.md section 7).
//   X-ray: C + round_shift(w * C', 8) is formed in F+2 bits and saturates at
//   2^F; T - w saturates at 0 (section 13). MIP / MinIP: no arithmetic but
//   the comparison; path weights: comparisons only (a column's opacity is the
//   host's 1 - (1 - A)^w in Q0.ALPHA_W); the pixel's shifts lose nothing, A's round_shift rounds
//   half up and stays <= 2^F.
// =============================================================================
module cube4_com #(
    parameter integer P        = 8, parameter integer MAX_DIM     = 256,
    parameter integer WEIGHT_W = 8, parameter integer MAX_SS_LOG2 = 0,
    parameter integer ALPHA_W  = 12, parameter integer ACC_W      = 16,
    parameter integer VOXEL_W  = 8,
    parameter integer COMPOSITING = 1, parameter integer EXTREMUM = 1,
    parameter integer PLW = 1,
    parameter integer RECTS = 0, parameter integer ADDR_W = 16,
    `CUBE4_GEOMETRY, `CUBE4_VIEW_LAYOUT, `CUBE4_RECT_LAYOUT,
    localparam integer BX_W = DIM_W + 1,
    localparam integer PWC_W = (PLW != 0) ? 4 * ALPHA_W : 1   // the path-weight columns
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    // the LUT's path-weight columns (PLW = 1)
    input  wire lut_we, input wire [VOXEL_W-1:0] lut_addr, input wire [PWC_W-1:0] lut_data,
    // the rectangle table (RECTS = 1; cube4_cfb's, written alike; COM reads INS, J_IN,
    // J_HI, I_IN, I_HIN, STX, STY)
    input  wire rect_we, input wire [M_W-1:0] rect_addr, input wire [RECT_W-1:0] rect_data,
    // shaded stream in
    input  wire in_valid, output wire in_ready, input wire [HDR_W-1:0] in_hdr,
    input  wire [P*(24+ALPHA_W)-1:0] in_rgba,
    input  wire [P*VOXEL_W-1:0] in_sample,
    // finished rays out: lane mask, slice, base-plane row and columns, RGBA, last beat
    output wire pix_valid, input wire pix_ready,
    output wire [P-1:0] pix_mask, output wire [M_W-1:0] pix_m, output wire pix_eop,
    output wire [BX_W-1:0] pix_by, output wire [P*BX_W-1:0] pix_bx,
    output wire [P*4*(ACC_W+1)-1:0] pix_rgba
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_com", "P", P, 1, 64)
        `CUBE4_RANGE(g_bad_alpha_w, "cube4_com", "ALPHA_W", ALPHA_W, 8, 16)
        `CUBE4_RANGE(g_bad_acc_w, "cube4_com", "ACC_W", ACC_W, 8, 24)
        `CUBE4_RANGE(g_bad_voxel_w, "cube4_com", "VOXEL_W", VOXEL_W, 1, 16)
        `CUBE4_RANGE(g_bad_compositing, "cube4_com", "COMPOSITING", COMPOSITING, 0, 1)
        `CUBE4_RANGE(g_bad_extremum, "cube4_com", "EXTREMUM", EXTREMUM, 0, 1)
        `CUBE4_RANGE(g_bad_plw, "cube4_com", "PLW", PLW, 0, 1)
        `CUBE4_RANGE(g_bad_rects, "cube4_com", "RECTS", RECTS, 0, 1)
        if (PLW != 0 && RECTS != 0) begin : g_plw_rects
            $error("cube4_com: PLW = 1 with RECTS = 1 is not built (the path weights follow every slice's template)");
        end
        if (PLW != 0 && COMPOSITING == 0) begin : g_plw_alone
            $error("cube4_com: PLW = 1 needs COMPOSITING = 1 (only the blending modes are weighted)");
        end
        if (COMPOSITING == 0 && EXTREMUM == 0) begin : g_no_mode
            $error("cube4_com: COMPOSITING = 0 and EXTREMUM = 0 leave no rendering mode");
        end
    endgenerate

    localparam integer CW     = ACC_W + 1;          // one accumulator channel
    localparam integer CMP_W  = 4 * CW;             // compositing word {R, G, B, T}; a pixel {R, G, B, A}
    localparam integer LUT_W  = 24 + ALPHA_W;
    localparam integer EXT_W  = VOXEL_W + LUT_W;    // extremum word {v, R, G, B, A}
    // a ray's partial result in the buffers: wide enough for the build's modes
    localparam integer AC_W   = (COMPOSITING != 0 && (EXTREMUM == 0 || CMP_W >= EXT_W)) ? CMP_W : EXT_W;
    localparam integer PA     = P * AC_W;
    localparam integer PX_W   = P * CMP_W;          // the pixels of a beat
    localparam integer PH_W   = PHASE_W;
    localparam [CW-1:0]   ONE = {1'b1, {ACC_W{1'b0}}};  // T = 1.0

    `CUBE4_VIEW_FIELDS(cfg);
    `CUBE4_LANE_FUNCTIONS

    // ---- pipeline (docs/architecture.md, "COM") ----
    //   R0  input register
    //   S0  (R0's beat) counters, template, lane positions, fresh; parts of finished
    //   S1  ... finished rays and bx computed from S1's registered parts
    //   S1  read the base-plane (slice) buffer at the beat's slice position
    //   S2  slice buffer output; read the beam buffer at the beat's beam position
    //   S3  register the slice word; beam buffer output; write it to the beam buffer
    //   S4  select (m-1, j-dyb, i): beam or slice word, j and k ring hops
    //   S5  the X-step hop; the previous partial result, or a fresh ray
    //   S6  T * A (multiplier)
    //   S7  w = round_shift(T * A, AW)
    //   S8  w in a fabric register (between the two multipliers), T - w
    //   S9  w * C' (multipliers)
    //   S10 C += round_shift(w * C', 8)
    //   S11 the new partial results (per lane, one register per mode): the
    //       slice buffer's write word acc_q (the mode's select on the route
    //       to its block RAMs, which are spread over the die) and the source
    //       of the pixels pushed into the FIFO (one edge later in it)
    // Every stage moves on every cycle and carries a valid bit; the datapath
    // registers have no clock enable. The registers that must hold across
    // bubbles load under a valid bit: the position counters under step (R0's
    // valid bit), the last beat's words for the X-step and NB = 1 under each
    // lane's own copies of v_s[4] (u_v3, u_v4).
    // A beat's slice position is read two edges after its acceptance into
    // R0 (S1 -> S2) and written at the edge where it leaves S11. The ray's
    // previous partial result was written by the beat L = NJ*NB steps earlier
    // at the same position, so a beat is accepted only if that beat is not in
    // R0..S9 (one in S10 is written at the edge after acceptance, before the
    // read).
    // Slices of L >= 11 beats never wait; smaller ones (volumes of fewer than 11
    // beats per slice) run at L beats per 11 cycles.
    // slice-buffer slot: j * NB + pb counted; with rectangles {j, pb} from the header
    localparam integer RW    = (MAX_DIM > 1) ? $clog2(MAX_DIM) : 1;
    localparam integer SP_W  = (RECTS != 0) ? RW + PB_W : ((MAX_DIM * NBMAX > 1) ? $clog2(MAX_DIM * NBMAX) : 1);
    localparam integer SB_DEPTH = (RECTS != 0) ? (1 << SP_W) : MAX_DIM * NBMAX;
    localparam integer TA_W  = CW + ALPHA_W;    // T * A
    localparam integer WC_W  = CW + 8;          // w * C'

    localparam integer NS      = 10;            // stages S1 .. S10
    localparam integer FIFO_DEPTH = 16;         // >= 14 cycles from acceptance to the FIFO's read
    reg  [NS:1] v_s;                    // stage valid bits
    wire        hazard;                 // the beat L back is in R0..S9 (see above)
    wire        credit;                 // the output FIFO has an entry for one more beat
    assign in_ready = credit && !hazard;
    wire take = in_valid && in_ready;   // a beat enters R0

    // ==== R0: input register (loads on every cycle; r0_v marks a beat) ====
    wire                r0_v;           // u_step's first copy (below)
    wire [P*LUT_W-1:0]  r0_rgba;        // per lane registers (g_r0)
    wire [P*VOXEL_W-1:0] r0_smp;        // per lane registers (g_r0; extremum builds)
    reg [HDR_W-1:0]     r0_hdr;
    wire [P-1:0]        r0_lane_valid  = r0_hdr[HDR_LVALID +: P];
    wire [P-1:0]        r0_lane_inside = r0_hdr[HDR_INSIDE +: P];
    wire [M_W-1:0]      r0_m           = r0_hdr[HDR_M +: M_W];
    wire [DIM_W-1:0]    r0_j           = r0_hdr[HDR_J +: DIM_W];
    wire [PB_W-1:0]     r0_pb          = r0_hdr[HDR_PB +: PB_W];
    wire [LANE_W-1:0]   r0_skew        = r0_hdr[HDR_SKEW +: LANE_W];
    wire [6:0]          r0_ctrl        = r0_hdr[HDR_CTRL +: 7];
    reg                 r0_first;       // j = 0 and pb = 0: the first beat of a slice
    always @(posedge clk) begin
        r0_first <= (in_hdr[HDR_J +: DIM_W] == '0) && (in_hdr[HDR_PB +: PB_W] == '0);
        r0_hdr   <= in_hdr;
    end
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_r0
            reg [LUT_W-1:0] r0_rgba_q;
            assign r0_rgba[q*LUT_W +: LUT_W] = r0_rgba_q;
            always @(posedge clk) begin
                r0_rgba_q <= in_rgba[q*LUT_W +: LUT_W];
            end
            if (EXTREMUM != 0 || PLW != 0) begin : g_smp
                reg [VOXEL_W-1:0] r0_smp_q;
                always @(posedge clk) r0_smp_q <= in_sample[q*VOXEL_W +: VOXEL_W];
                assign r0_smp[q*VOXEL_W +: VOXEL_W] = r0_smp_q;
            end else begin : g_no_smp
                wire unused_in_smp = ^in_sample[q*VOXEL_W +: VOXEL_W];
                assign r0_smp[q*VOXEL_W +: VOXEL_W] = '0;
            end
        end
    endgenerate
    wire step = r0_v;                   // the R0 beat enters S1
    // R0's valid in three kept copies: r0_v (the stage valid bits and the
    // lanes' loads), and one each for S0's position counters and slice
    // template (a plain r0_v register would be merged into one of them)
    wire [1:0] step_c;
    cube4_prim_copies #(.N(3), .RESET(1)) u_step (
        .clk(clk), .rst(rst), .d(take), .q({step_c, r0_v}));

    wire sop   = r0_ctrl[CTRL_SOP];
    wire eop   = r0_ctrl[CTRL_EOP];
    wire dxf   = r0_ctrl[CTRL_SX];
    wire dyf   = r0_ctrl[CTRL_SY];
    wire dxb   = r0_ctrl[CTRL_OSX];
    wire dyb   = r0_ctrl[CTRL_OSY];
    wire first_of_slice = r0_first;
    wire unused_y_last = r0_ctrl[CTRL_YLAST];   // rows are checked against cfg_nj directly
    // ==== slice rectangles (RECTS = 1) ====
    // The inside rectangles of slices m - 1 (a ray is fresh where its previous
    // sample is not inside it) and m + 1 (a ray finishes where its next sample
    // is not inside it) and the steps of m, from the host's table (three copies,
    // read as a slice's first beat enters R0, so that R0's beat has them); a beat
    // waits while the beat of the same slot is in R0 .. S9 (the read-after-write
    // rule by position); and whether the previous beat is the row above at the
    // same partial beam.
    wire             rx_prev_v, rx_next_v;
    wire [DIM_W-1:0] rx_p_j0, rx_p_j1, rx_p_i0, rx_p_i1, rx_n_j0, rx_n_j1, rx_n_i0, rx_n_i1;
    wire [DIM_W-1:0] rx_stx, rx_sty;
    wire             rx_hazard, rx_col1;
    generate
        if (RECTS != 0) begin : g_rx
            localparam integer TAW = (MAX_DIM > 1) ? $clog2(MAX_DIM) : 1;
            wire [M_W-1:0] in_m  = in_hdr[HDR_M +: M_W];
            reg            cur_v;
            reg [M_W-1:0]  cur_m;
            wire           rd = take && (!cur_v || (in_m != cur_m) || in_hdr[HDR_CTRL + CTRL_SOP]);
            always @(posedge clk) begin
                if (rst)       cur_v <= 1'b0;
                else if (take) cur_v <= 1'b1;
                if (take) cur_m <= in_m;
            end
            wire [M_W-1:0]    m_pv = in_m - 1'b1;
            wire [M_W-1:0]    m_nx = in_m + 1'b1;
            wire [RECT_W-1:0] e_p, e_c, e_n;
            cube4_sdp_ram #(.DATA_W(RECT_W), .DEPTH(MAX_DIM)) u_tab_p (
                .clk(clk), .rd_en(rd), .rd_addr(TAW'(m_pv)), .rd_data(e_p),
                .wr_en(rect_we), .wr_addr(TAW'(rect_addr)), .wr_data(rect_data));
            cube4_sdp_ram #(.DATA_W(RECT_W), .DEPTH(MAX_DIM)) u_tab_c (
                .clk(clk), .rd_en(rd), .rd_addr(TAW'(in_m)), .rd_data(e_c),
                .wr_en(rect_we), .wr_addr(TAW'(rect_addr)), .wr_data(rect_data));
            cube4_sdp_ram #(.DATA_W(RECT_W), .DEPTH(MAX_DIM)) u_tab_n (
                .clk(clk), .rd_en(rd), .rd_addr(TAW'(m_nx)), .rd_data(e_n),
                .wr_en(rect_we), .wr_addr(TAW'(rect_addr)), .wr_data(rect_data));
            reg p_ok, n_ok;                  // slices m - 1 >= 0, m + 1 < M (= NK: S = 1)
            always @(posedge clk) begin
                if (rd) begin
                    p_ok <= (in_m != '0);
                    n_ok <= (m_nx < M_W'(cfg_nk));
                end
            end
            assign rx_prev_v = p_ok && e_p[RT_INS];
            assign rx_next_v = n_ok && e_n[RT_INS];
            assign rx_p_j0 = e_p[RT_JIN +: DIM_W];
            assign rx_p_j1 = e_p[RT_JHI +: DIM_W];
            assign rx_p_i0 = e_p[RT_IIN +: DIM_W];
            assign rx_p_i1 = e_p[RT_IHIN +: DIM_W];
            assign rx_n_j0 = e_n[RT_JIN +: DIM_W];
            assign rx_n_j1 = e_n[RT_JHI +: DIM_W];
            assign rx_n_i0 = e_n[RT_IIN +: DIM_W];
            assign rx_n_i1 = e_n[RT_IHIN +: DIM_W];
            assign rx_stx  = e_c[RT_STX +: DIM_W];
            assign rx_sty  = e_c[RT_STY +: DIM_W];
            // read after write by position: the incoming slot against R0 .. S9
            wire [SP_W-1:0] in_sp = SP_W'({in_hdr[HDR_J +: RW], in_hdr[HDR_PB +: PB_W]});
            reg hz;
            integer kz;
            always @* begin
                hz = r0_v && (pos_sp == in_sp);
                for (kz = 1; kz <= NS - 1; kz = kz + 1) hz = hz || (v_s[kz] && (sp_s[kz] == in_sp));
            end
            assign rx_hazard = hz;
            // the last beat that left R0
            reg             lb_v;
            reg [M_W-1:0]   lb_m;
            reg [DIM_W-1:0] lb_j;
            reg [PB_W-1:0]  lb_pb;
            always @(posedge clk) begin
                if (rst) lb_v <= 1'b0;
                else if (step) lb_v <= 1'b1;
                if (step) begin
                    lb_m  <= r0_m;
                    lb_j  <= r0_j;
                    lb_pb <= r0_pb;
                end
            end
            assign rx_col1 = lb_v && (lb_m == r0_m) && (lb_pb == r0_pb) && (lb_j + 1'b1 == r0_j);
            wire unused_rx = ^{e_p, e_c, e_n, hazard_q, nb1_l, f1_last, f1_wxn, f1_wyn, rect_addr, m_pv};
        end else begin : g_no_rx
            assign {rx_prev_v, rx_next_v, rx_hazard, rx_col1} = 4'b0000;
            assign {rx_p_j0, rx_p_j1, rx_p_i0, rx_p_i1, rx_n_j0, rx_n_j1, rx_n_i0, rx_n_i1} = '0;
            assign {rx_stx, rx_sty} = '0;
            wire unused_rx = ^{rect_we, rect_addr, rect_data};
        end
    endgenerate

    // ==== S0 ====
    // ---- positions: partial beam, row and slice position (as cube4_gra) ----
    reg  [PB_W-1:0]  pb_q;
    reg  [DIM_W-1:0] row_q;
    reg  [SP_W-1:0]  sp_q;
    // with rectangles the position comes with the beat (its slot {j, pb}).
    // Without, sop (a register) only selects between results computed from
    // registers: lb_q / ls_q say pb_q / row_q are at the last beam / the last
    // slot of a slice (kept with the counters, as in cube4_gra), the increments
    // run on pb_q, row_q, sp_q, and the compares on registered view constants.
    wire [PB_W-1:0]  pos_pb  = (RECTS != 0) ? r0_pb : (sop ? {PB_W{1'b0}} : pb_q);
    wire [DIM_W-1:0] pos_row = sop ? {DIM_W{1'b0}} : row_q;
    wire [SP_W-1:0]  pos_sp  = (RECTS != 0) ? SP_W'({r0_j[RW-1:0], r0_pb}) : (sop ? {SP_W{1'b0}} : sp_q);
    reg              lb_q, ls_q;                 // pb_q = NB - 1; and row_q = NJ - 1
    reg              nb1_q, nb2_q, nj1_q, nj2_q; // NB = 1, NB = 2, NJ = 1, NJ = 2
    reg  [NB_W-1:0]  nbm1_q, nbm2_q;             // NB - 1, NB - 2
    reg  [DIM_W-1:0] njm1_q, njm2_q;             // NJ - 1, NJ - 2
    always @(posedge clk) begin
        nb1_q  <= (cfg_nb == NB_W'(1));
        nb2_q  <= (cfg_nb == NB_W'(2));
        nj1_q  <= (cfg_nj == DIM_W'(1));
        nj2_q  <= (cfg_nj == DIM_W'(2));
        nbm1_q <= cfg_nb - NB_W'(1);
        nbm2_q <= cfg_nb - NB_W'(2);
        njm1_q <= cfg_nj - DIM_W'(1);
        njm2_q <= cfg_nj - DIM_W'(2);
    end
    wire last_beam  = (RECTS != 0) ? (NB_W'(r0_pb) == nbm1_q) : (sop ? nb1_q : lb_q);
    wire last_slice = (RECTS != 0) ? (last_beam && (pos_row == njm1_q)) : (sop ? (nb1_q && nj1_q) : ls_q);
    // pos_pb + 1 == NB - 1, pos_row == NJ - 1, pos_row + 1 == NJ - 1 (used where NB > 1 / NJ > 1)
    wire pb_e2  = sop ? nb2_q : (NB_W'(pb_q) == nbm2_q);
    wire row_e1 = sop ? nj1_q : (row_q == njm1_q);
    wire row_e2 = sop ? nj2_q : (row_q == njm2_q);
    wire [PB_W-1:0]  pb_inc  = sop ? PB_W'(1) : pb_q + 1'b1;
    wire [DIM_W-1:0] row_inc = sop ? DIM_W'(1) : row_q + 1'b1;
    wire [SP_W-1:0]  sp_inc  = (RECTS != 0) ? pos_sp + 1'b1 : (sop ? SP_W'(1) : sp_q + 1'b1);
    wire lb_n = last_beam ? nb1_q : pb_e2;
    wire ls_n = lb_n && (!last_beam ? row_e1 : (last_slice ? nj1_q : row_e2));

    // ---- template of slice m+1 (for "next sample inside") and steps of slice m ----
    reg  [PH_W-1:0]  phx_q, phy_q;      // phase of slice m + 1
    reg  [DIM_W-1:0] stx_q, sty_q;      // stepx(m), stepy(m)
    wire [PH_W:0]    ph_one  = {{PH_W{1'b0}}, 1'b1} << (WEIGHT_W[3:0] + {2'b00, cfg_ss_log2});
    wire [PH_W:0]    phx_sum = {1'b0, sop ? cfg_ph0_x : phx_q} + (PH_W + 1)'(cfg_view_x);
    wire [PH_W:0]    phy_sum = {1'b0, sop ? cfg_ph0_y : phy_q} + (PH_W + 1)'(cfg_view_y);
    wire [PH_W-1:0]  phx_add = (phx_sum >= ph_one) ? PH_W'(phx_sum - ph_one) : phx_sum[PH_W-1:0];
    wire [PH_W-1:0]  phy_add = (phy_sum >= ph_one) ? PH_W'(phy_sum - ph_one) : phy_sum[PH_W-1:0];
    wire [PH_W-1:0]  phx_n   = first_of_slice ? phx_add : phx_q;
    wire [PH_W-1:0]  phy_n   = first_of_slice ? phy_add : phy_q;
    // wx(m+1) = phase >> g, and phase < 2^(W+g): every bit above g is a weight bit
    wire             wxn_nz  = ((phx_n >> cfg_ss_log2) != '0);   // wx(m+1) > 0
    wire             wyn_nz  = ((phy_n >> cfg_ss_log2) != '0);
    wire [DIM_W-1:0] stx_n   = !first_of_slice ? stx_q : (sop ? {DIM_W{1'b0}} : stx_q + DIM_W'(dxb));
    wire [DIM_W-1:0] sty_n   = !first_of_slice ? sty_q : (sop ? {DIM_W{1'b0}} : sty_q + DIM_W'(dyb));
    wire [M_W-1:0]   m_last  = M_W'(cfg_nk - 1'b1) << cfg_ss_log2;
    wire             in_last_slice = (r0_m == m_last);
    wire [M_W-1:0]   ss_mask = M_W'((1 << cfg_ss_log2) - 1);
    wire             dk_b    = (r0_m & ss_mask) == '0;   // voxel slice changed from m-1

    always @(posedge clk) begin
        if (rst) begin
            pb_q  <= {PB_W{1'b0}};
            row_q <= {DIM_W{1'b0}};
            sp_q  <= {SP_W{1'b0}};
            lb_q  <= 1'b0;
            ls_q  <= 1'b0;
        end else if (step_c[0]) begin
            pb_q  <= last_beam ? {PB_W{1'b0}} : pb_inc;
            row_q <= !last_beam ? pos_row : (last_slice ? {DIM_W{1'b0}} : row_inc);
            sp_q  <= last_slice ? {SP_W{1'b0}} : sp_inc;
            lb_q  <= lb_n;
            ls_q  <= ls_n;
        end
    end
    always @(posedge clk) begin
        if (step_c[1]) begin
            phx_q <= phx_n;
            phy_q <= phy_n;
            stx_q <= stx_n;
            sty_q <= sty_n;
        end
    end

    // ---- per lane: position in the beam, fresh ray, finished ray ----
    wire [P-1:0]      fresh_d, t0_d, ins_d, cnt_d;
    wire [P-1:0]      r0_lane_keep = r0_hdr[HDR_KEEP +: P];
    wire [P*IW-1:0]   ipos_d;            // i of each lane
    wire [IW-1:0]     pbp    = IW'(r0_pb) * IW'(P);
    wire [IW-1:0]     ni_ext = IW'(cfg_ni);
    wire [IW-1:0]     nj_ext = IW'(cfg_nj);
    wire [IW-1:0]     j_ext  = IW'(r0_j);
    generate
        for (q = 0; q < P; q = q + 1) begin : g_pos
            wire [LANE_W-1:0] t = lane_pos(q, r0_skew, cfg_flip_i, cfg_i_r1);
            wire [IW-1:0] i_pos = pbp + IW'(t);
            assign t0_d[q]    = (t == '0);
            // the ray starts here: its previous sample is outside the slice
            // (rectangles: where it is not inside slice m - 1's inside rectangle)
            wire [IW-1:0] i_pv = i_pos - IW'(dxb);
            wire [IW-1:0] j_pv = j_ext - IW'(dyb);
            wire pv_in = rx_prev_v && (j_pv >= IW'(rx_p_j0)) && (j_pv <= IW'(rx_p_j1))
                                   && (i_pv >= IW'(rx_p_i0)) && (i_pv <= IW'(rx_p_i1));
            assign fresh_d[q] = (RECTS != 0) ? !pv_in
                                             : ((r0_m == '0) || (dyb && r0_j == '0) || (dxb && i_pos == '0));
            assign ins_d[q]   = r0_lane_valid[q] && r0_lane_inside[q];
            assign cnt_d[q]   = ins_d[q] && r0_lane_keep[q];   // the sample counts
            assign ipos_d[q*IW +: IW] = i_pos;
        end
    endgenerate

    // ---- S1 -> S2: finished rays and base-plane x, y, from registered parts ----
    // fin: the next sample along the ray (m+1, j+dyf, i+dxf) is not inside
    // (numerics.md section 8); bx = i - stepx(m) + SX, by = j - stepy(m) + SY.
    reg [P*IW-1:0]   f1_ipos;
    reg [IW-1:0]     f1_j;
    reg              f1_dxf, f1_dyf, f1_last, f1_wxn, f1_wyn;
    reg [DIM_W-1:0]  f1_stx, f1_sty;
    reg              f1_nv;              // (rectangles) slice m + 1's inside rectangle
    reg [DIM_W-1:0]  f1_nj0, f1_nj1, f1_ni0, f1_ni1;
    always @(posedge clk) begin
        f1_ipos <= ipos_d;
        f1_j    <= j_ext;
        f1_dxf  <= dxf;
        f1_dyf  <= dyf;
        f1_last <= in_last_slice;
        f1_wxn  <= wxn_nz;
        f1_wyn  <= wyn_nz;
        f1_stx  <= (RECTS != 0) ? rx_stx : stx_n;
        f1_sty  <= (RECTS != 0) ? rx_sty : sty_n;
        f1_nv   <= rx_next_v;
        f1_nj0  <= rx_n_j0;
        f1_nj1  <= rx_n_j1;
        f1_ni0  <= rx_n_i0;
        f1_ni1  <= rx_n_i1;
    end
    wire [P-1:0]      fin_1;
    wire [P*BX_W-1:0] bx_1;
    wire [BX_W-1:0]   by_1 = BX_W'(f1_j) - BX_W'(f1_sty) + BX_W'(cfg_sy);   // by = j - stepy(m) + SY
    generate
        for (q = 0; q < P; q = q + 1) begin : g_fin
            wire [IW-1:0] i_pos = f1_ipos[q*IW +: IW];
            wire [IW-1:0] i_nx  = i_pos + IW'(f1_dxf);
            wire [IW-1:0] j_nx  = f1_j + IW'(f1_dyf);
            wire nx_box = !f1_last && (i_nx < ni_ext) && (j_nx < nj_ext)
                        && !(i_nx + 1'b1 == ni_ext && f1_wxn) && !(j_nx + 1'b1 == nj_ext && f1_wyn);
            wire nx_rect = f1_nv && (j_nx >= IW'(f1_nj0)) && (j_nx <= IW'(f1_nj1))
                                 && (i_nx >= IW'(f1_ni0)) && (i_nx <= IW'(f1_ni1));
            wire nx_in = (RECTS != 0) ? nx_rect : nx_box;
            assign fin_1[q] = ins_s1[q] && !nx_in;
            assign bx_1[q*BX_W +: BX_W] = BX_W'(i_pos) - BX_W'(f1_stx) + BX_W'(cfg_sx);
        end
    endgenerate

    // ---- path weights (PLW): per slice, the quarter bins of the entry and exit
    // fractions; per lane, the causes split by face (numerics.md section 17) ----
    // rq(num, VIEW) = #{k in 1, 3, 5, 7 : 8 num >= k VIEW}: e = num / VIEW rounded
    // half up to quarters. Entry: num = ph(m) (an old step has just wrapped it
    // below VIEW); exit: num = VIEW - ph(m+1) (a step has just wrapped ph(m+1)).
    // Three register stages, each with little logic: S0 -> S1 the phases of
    // slices m and m+1 and the entry causes; S1 -> S2 the bins and the exit
    // causes; S2 -> S3 the lane's weight (a register per lane); S3 -> S4 its
    // column's opacity (below, g_pwt).
    wire [P-1:0] pw_use_3;               // S3: the lane's weight is not 1
    wire [2*P-1:0] pw_col_3;             // S3: its column (w = 1/2, 3/4, 5/4, 3/2)
    generate
        if (PLW != 0) begin : g_pw
            localparam integer NW = PH_W + 4;
            reg  [PH_W-1:0] phx_m_q, phy_m_q;       // phase of slice m
            wire [PH_W-1:0] phx_m = first_of_slice ? (sop ? cfg_ph0_x : phx_q) : phx_m_q;
            wire [PH_W-1:0] phy_m = first_of_slice ? (sop ? cfg_ph0_y : phy_q) : phy_m_q;
            always @(posedge clk) begin
                if (step) begin
                    phx_m_q <= phx_m;
                    phy_m_q <= phy_m;
                end
            end
            function automatic [2:0] qbins(input [NW-1:0] num, input [NW-1:0] view);
                reg [NW-1:0] n8;
                begin
                    n8   = num << 3;
                    qbins = 3'(n8 >= view) + 3'(n8 >= 3 * view) + 3'(n8 >= 5 * view) + 3'(n8 >= 7 * view);
                end
            endfunction
            wire [NW-1:0] vx = NW'(cfg_view_x);
            wire [NW-1:0] vy = NW'(cfg_view_y);
            wire [5:0]    fc = cfg_faces;
            // S0 -> S1: the phases of slices m and m+1, the entry causes
            reg  [PH_W-1:0] f1_phxm, f1_phym, f1_phxn, f1_phyn;
            reg             f1_kin, f1_yin;
            reg  [P-1:0]    f1_xin;
            integer         l;
            always @(posedge clk) begin
                f1_phxm <= phx_m;
                f1_phym <= phy_m;
                f1_phxn <= phx_n;
                f1_phyn <= phy_n;
                f1_kin  <= fc[4] && (r0_m == '0);
                f1_yin  <= fc[2] && dyb && (r0_j == '0);
                for (l = 0; l < P; l = l + 1)
                    f1_xin[l] <= fc[0] && dxb && (ipos_d[l*IW +: IW] == '0);
            end
            // S1 -> S2: the bins (entry: num = ph(m), an old step has just wrapped it
            // below VIEW; exit: num = VIEW - ph(m+1), a step has just wrapped ph(m+1))
            // and the exit causes
            reg  [2:0]   s2_rxi, s2_rxo, s2_ryi, s2_ryo;
            reg          s2_kin, s2_yin, s2_kout, s2_yout0, s2_yout1;
            reg  [P-1:0] s2_xin, s2_xout0, s2_xout1;
            always @(posedge clk) begin
                s2_rxi   <= qbins(NW'(f1_phxm), vx);
                s2_ryi   <= qbins(NW'(f1_phym), vy);
                s2_rxo   <= qbins(vx - NW'(f1_phxn), vx);
                s2_ryo   <= qbins(vy - NW'(f1_phyn), vy);
                s2_kin   <= f1_kin;
                s2_yin   <= f1_yin;
                s2_xin   <= f1_xin;
                s2_kout  <= fc[5] && f1_last;
                s2_yout0 <= fc[3] && (f1_j + IW'(1) == nj_ext) && (f1_dyf || f1_wyn);
                s2_yout1 <= fc[3] && (f1_j + IW'(2) == nj_ext) && f1_dyf && f1_wyn;
                for (l = 0; l < P; l = l + 1) begin
                    s2_xout0[l] <= fc[1] && (f1_ipos[l*IW +: IW] + IW'(1) == ni_ext) && (f1_dxf || f1_wxn);
                    s2_xout1[l] <= fc[1] && (f1_ipos[l*IW +: IW] + IW'(2) == ni_ext) && f1_dxf && f1_wxn;
                end
            end
            // S2 -> S3: the weight wq = (entry ? rq_in : 2) + (exit ? rq_out : 2),
            // clamped to 2..6 quarters, rq of an end the minimum over its active
            // causes; 4 keeps the LUT's A. The lane's own registers: the causes
            // shared by the lanes fan out to P of them, not to P * ALPHA_W
            // selects of the opacity
            for (q = 0; q < P; q = q + 1) begin : g_pw_lane
                wire [3:0] in_x  = s2_xin[q] ? {1'b0, s2_rxi} : 4'd9;   // 9: no cause
                wire [3:0] in_y  = s2_yin ? {1'b0, s2_ryi} : 4'd9;
                wire [3:0] in_xy = (in_x < in_y) ? in_x : in_y;
                wire [3:0] rq_in = s2_kin ? 4'd0 : in_xy;
                wire [3:0] o_x   = s2_xout0[q] ? 4'd0 : (s2_xout1[q] ? {1'b0, s2_rxo} : 4'd9);
                wire [3:0] o_y   = s2_yout0 ? 4'd0 : (s2_yout1 ? {1'b0, s2_ryo} : 4'd9);
                wire [3:0] o_xy  = (o_x < o_y) ? o_x : o_y;
                wire [3:0] rq_out = s2_kout ? 4'd0 : o_xy;
                wire [3:0] wsum = ((rq_in == 4'd9) ? 4'd2 : rq_in) + ((rq_out == 4'd9) ? 4'd2 : rq_out);
                wire [2:0] wq   = (wsum < 4'd2) ? 3'd2 : (wsum > 4'd6) ? 3'd6 : wsum[2:0];
                reg       use_q;
                reg [1:0] col_q;
                always @(posedge clk) begin
                    use_q <= (wq != 3'd4);
                    col_q <= (wq == 3'd2) ? 2'd0 : (wq == 3'd3) ? 2'd1 : (wq == 3'd5) ? 2'd2 : 2'd3;
                end
                assign pw_use_3[q] = use_q;
                assign pw_col_3[2*q +: 2] = col_q;
            end
        end else begin : g_no_pw
            wire unused_pw = ^{cfg_faces, lut_we, lut_addr, lut_data};
            assign pw_use_3 = '0;
            assign pw_col_3 = '0;
        end
    endgenerate

    // ---- the beat's fields, carried along the pipeline (index = stage) ----
    // (unpacked arrays: a packed [stage][field] array of fields that are not word
    // aligned made Verilator's model about 20% slower at P = 8)
    reg [SP_W-1:0]    sp_s    [1:NS];    // slice position: read at S1, written at the end of S11
    reg [PB_W-1:0]    pb_s    [1:2];     // beam position: read at S2, written at the end of S3 (RAM's registers)
    reg [P-1:0]       ins_s1;            // inside (finished rays, S1)
    reg [P-1:0]       cnt_s   [1:7];     // the sample counts (S6, S7)
    reg [P-1:0]       fin_s   [2:NS];    // from S2 on (computed from S1's parts)
    reg [M_W-1:0]     m_s     [1:NS];
    reg [BX_W-1:0]    by_s    [2:NS];    // from S2 on (computed from S1's parts)
    reg [P*BX_W-1:0]  bx_s    [2:NS];
    reg [NS:1]        eop_s;
    reg [4:1]         dxb_s;             // S5's copies: g_lane's sel5
    reg [4:1]         col1_s;            // (rectangles) the previous beat is the row above, same pb
    reg [4:1]         dyb_s, dkb_s;
    reg [P-1:0]       fresh_s [1:4];     // S5's copies: g_lane's sel5
    reg [P-1:0]       t0_s    [1:4];
    integer k;
    always @(posedge clk) begin
        if (rst) v_s <= '0;
        else     v_s <= {v_s[NS-1:1], step};
    end
    always @(posedge clk) begin
        sp_s[1] <= pos_sp;   pb_s[1] <= pos_pb;  ins_s1 <= ins_d;  cnt_s[1] <= cnt_d;
        fin_s[2] <= fin_1;
        m_s[1]  <= r0_m;     by_s[2] <= by_1;    bx_s[2]  <= bx_1;   fresh_s[1] <= fresh_d;
        t0_s[1] <= t0_d;
        eop_s <= {eop_s[NS-1:1], eop};
        dxb_s <= {dxb_s[3:1], dxb};
        col1_s <= {col1_s[3:1], rx_col1};
        dyb_s <= {dyb_s[3:1], dyb};
        dkb_s <= {dkb_s[3:1], dk_b};
        for (k = 2; k <= NS; k = k + 1) begin
            sp_s[k] <= sp_s[k-1];  m_s[k] <= m_s[k-1];
        end
        for (k = 3; k <= NS; k = k + 1) begin
            fin_s[k] <= fin_s[k-1];  bx_s[k] <= bx_s[k-1];  by_s[k] <= by_s[k-1];
        end
        pb_s[2] <= pb_s[1];
        for (k = 2; k <= 7; k = k + 1) cnt_s[k] <= cnt_s[k-1];
        for (k = 2; k <= 4; k = k + 1) begin
            fresh_s[k] <= fresh_s[k-1];  t0_s[k] <= t0_s[k-1];
        end
    end
    // Read-after-write rule: a beat's position repeats every L = NJ*NB beats,
    // so the beat it depends on is the L-th most recent one, and that one is
    // in R0..S9 exactly when R0..S9 hold L or more valid beats. Counting them
    // needs no field of the incoming beat. The count is made for the next
    // cycle (R0..S9 after this edge hold take, r0_v, v_s[1..8]) and the
    // comparison registered, so hazard, like in_ready, is a register.
    reg  [3:0] lim_q;                   // min(NJ*NB, 11): 11 never stalls
    always @(posedge clk) begin
        lim_q <= (32'(cfg_nj) * 32'(cfg_nb) >= 32'd11) ? 4'd11 : 4'(32'(cfg_nj) * 32'(cfg_nb));
    end
    reg [3:0] n_fly_d;                  // valid beats in R0..S9 in the next cycle (at most 10)
    integer kh;
    always @* begin
        n_fly_d = {3'b000, take} + {3'b000, r0_v};
        for (kh = 1; kh < NS - 1; kh = kh + 1) n_fly_d = n_fly_d + {3'b000, v_s[kh]};
    end
    reg hazard_q;
    always @(posedge clk) begin
        if (rst) hazard_q <= 1'b0;
        else     hazard_q <= (n_fly_d >= lim_q);
    end
    assign hazard = (RECTS != 0) ? rx_hazard : hazard_q;

    // ==== S1 .. S4: base-plane buffers: partial results of slice m-1 ====
    // Both RAMs end in their output register (cube4_sdp_ram OUT_REG: the
    // block RAM's own on an FPGA, whose clock-to-out is most of a cycle
    // without it): s3_a1 and s4_a2 are those registers.
    wire [PA-1:0] acc_q;                // S11 (g_lane's registers): results after slice m
    wire [PA-1:0] a1_ram, a2_ram;       // S3, S4: the RAMs' output registers
    // Both buffers register their addresses and write enables themselves (with
    // copies for their block RAMs, cube4_sdp_ram IN_REG): they get them one
    // stage early. The slice buffer is read at S1 (sp_s[1]) and written at the
    // end of S11 (from acc_q, at the address and enable of the beat that left
    // S10: sp_s[NS], v_s[NS], given one stage early).
    cube4_sdp_ram #(.DATA_W(PA), .DEPTH(SB_DEPTH), .IN_REG(1), .OUT_REG(1)) u_bp_slice (
        .clk(clk), .rd_en(1'b1), .rd_addr(pos_sp), .rd_data(a1_ram),
        .wr_en(v_s[NS]), .wr_addr(sp_s[NS]), .wr_data(acc_q));
    wire [PA-1:0] s4_a1, prev_a1_q;     // per lane registers (g_buf)
    wire [PA-1:0] s3_a1 = a1_ram;       // the slice buffer's output register
    wire [PA-1:0] s4_a2 = a2_ram;       // the beam buffer's output register
    // One beam of the slice buffer's words (a2 of a beat = a1 of the beat NB
    // steps earlier, at the same beam position): read at the end of S2, written
    // at the end of S3. For NB >= 2 the write comes first; for NB = 1 a2 is the
    // previous beat's a1 (prev_a1_q).
    // (read at S2: address pb_s[1] given one stage early; written at the end of
    // S3: address pb_s[2] and enable v_s[2], one stage early)
    cube4_sdp_ram #(.DATA_W(PA), .DEPTH(NBMAX), .IN_REG(1), .OUT_REG(1)) u_bp_beam (
        .clk(clk), .rd_en(1'b1), .rd_addr(pb_s[1]), .rd_data(a2_ram),
        .wr_en(v_s[2]), .wr_addr(pb_s[2]), .wr_data(s3_a1));
    // the wide buffer words, per lane (registers of the lane's own, so that a
    // simulator writes each in place). Their enable is v_s[4], as a tree of
    // copies: v3[q] (a copy of v_s[3] per lane) and, per lane, one copy of
    // v_s[4] per quarter of each of its two registers (v4_l), so that no net
    // drives more than a quarter word's flip-flops (one copy per lane drove
    // 2 * AC_W of them and was the P = 8 build's critical net: 15 ns of routing).
    localparam integer NQ = 4;                      // enable copies per register
    localparam integer QW = (AC_W + NQ - 1) / NQ;   // bits per copy (the last may be fewer)
    // NB = 1, one copy per quarter of each lane's word (each selects a quarter
    // of a lane's AC_W-bit word at S4, whose result the ring shifts carry to
    // the neighbouring lanes; one flip-flop for every lane was shared with
    // GRA's and placed far from both, one per lane still drove AC_W selects
    // spread over three lanes: 9 ns of routing at P = 8)
    wire [P*NQ-1:0] nb1_l;
    cube4_prim_copies #(.N(P * NQ), .RESET(0)) u_nb1 (
        .clk(clk), .rst(1'b0), .d(cfg_nb == NB_W'(1)), .q(nb1_l));
    wire [PA-1:0] s5_back, s5_prevb;   // this beat's and the previous beat's "back" (g_buf)
    wire [PA-1:0] back;
    wire [P-1:0]  v3;
    cube4_prim_copies #(.N(P)) u_v3 (.clk(clk), .rst(rst), .d(v_s[2]), .q(v3));
    generate
        for (q = 0; q < P; q = q + 1) begin : g_buf
            localparam integer LO = q * AC_W;
            reg [AC_W-1:0] s4_a1_q, prev_a1_q_l;
            reg [AC_W-1:0] s5_back_q, s5_prevb_q, lastb_q;
            wire [2*NQ-1:0] v4_l;           // copies of v_s[4]: [NQ-1:0] prev_a1, [2*NQ-1:NQ] lastb
            cube4_prim_copies #(.N(2 * NQ)) u_v4 (.clk(clk), .rst(rst), .d(v3[q]), .q(v4_l));
            always @(posedge clk) begin
                s4_a1_q    <= a1_ram[LO +: AC_W];
                s5_back_q  <= back[LO +: AC_W];
                s5_prevb_q <= lastb_q;      // the "back" of the last beat before this one
            end
            genvar qq;
            for (qq = 0; qq < NQ; qq = qq + 1) begin : g_q
                localparam integer QL = qq * QW;
                localparam integer QN = (AC_W - QL < QW) ? AC_W - QL : QW;
                if (QN > 0) begin : g_bits
                    always @(posedge clk) begin
                        if (v4_l[qq])      prev_a1_q_l[QL +: QN] <= s4_a1_q[QL +: QN];
                        if (v4_l[NQ + qq]) lastb_q[QL +: QN]     <= back[LO + QL +: QN];
                    end
                end
            end
            assign s4_a1[LO +: AC_W]     = s4_a1_q;
            assign prev_a1_q[LO +: AC_W] = prev_a1_q_l;
            assign s5_back[LO +: AC_W]   = s5_back_q;
            assign s5_prevb[LO +: AC_W]  = s5_prevb_q;
        end
    endgenerate

    // ==== S4: (m-1, j-dyb, i) in this beat's skew ====
    wire [PA-1:0] a1 = s4_a1;
    // the row above at the same partial beam is the previous beat (NB = 1, or a
    // rectangle one partial beam wide): its beam-buffer write comes too late
    wire [PA-1:0] a2;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_a2
            genvar qa;
            for (qa = 0; qa < NQ; qa = qa + 1) begin : g_q
                localparam integer QL = q * AC_W + qa * QW;
                localparam integer QN = (AC_W - qa * QW < QW) ? AC_W - qa * QW : QW;
                if (QN > 0) begin : g_bits
                    wire from_prev = (RECTS != 0) ? col1_s[4] : nb1_l[q*NQ + qa];
                    assign a2[QL +: QN] = from_prev ? prev_a1_q[QL +: QN] : s4_a2[QL +: QN];
                end
            end
        end
    endgenerate
    wire [PA-1:0] a1_k, a2_j, a2_jk;
    cube4_ring_shift #(.P(P), .DATA_W(AC_W)) u_a1k  (.down(cfg_flip_k), .x(a1),   .y(a1_k));
    cube4_ring_shift #(.P(P), .DATA_W(AC_W)) u_a2j  (.down(cfg_flip_j), .x(a2),   .y(a2_j));
    cube4_ring_shift #(.P(P), .DATA_W(AC_W)) u_a2jk (.down(cfg_flip_k), .x(a2_j), .y(a2_jk));
    assign back = dyb_s[4] ? (dkb_s[4] ? a2_jk : a2_j) : (dkb_s[4] ? a1_k : a1);

    // ==== S5: the X-step hop (the lane at t = 0 takes the previous beat) ====
    wire [PA-1:0] back_sh, prevb_sh;
    cube4_ring_shift #(.P(P), .DATA_W(AC_W)) u_bsh (.down(cfg_flip_i), .x(s5_back),  .y(back_sh));
    cube4_ring_shift #(.P(P), .DATA_W(AC_W)) u_psh (.down(cfg_flip_i), .x(s5_prevb), .y(prevb_sh));

    // ==== S6 .. S10: the ray's step, per lane ====
    // the mode (cfg is stable during a frame), registered once
    reg mode_xray_q, mode_ext_q, mode_min_q;
    always @(posedge clk) begin
        mode_xray_q <= (COMPOSITING != 0) && (cfg_mode == 2'd1);
        mode_ext_q  <= (EXTREMUM != 0) && ((COMPOSITING == 0) || cfg_mode[1]);
        mode_min_q  <= (cfg_mode == 2'd3);
    end
    // a fresh ray: C = 0, T = 1 (compositing); v = 0 or 2^VOXEL_W - 1, RGBA = 0 (extremum)
    // (the words; each lane's quarters choose with their own mode copies, g_sel)
    localparam [AC_W-1:0] FRESH_CMP = AC_W'({{(3*CW){1'b0}}, ONE});
    localparam [AC_W-1:0] FRESH_MIN = AC_W'({{VOXEL_W{1'b1}}, {LUT_W{1'b0}}});   // MinIP; MIP: 0
    wire [PX_W-1:0] pix_d;              // S11: the lanes' {R, G, B, A}, from acc_q
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            // S11: the lane's new partial result (below), one register per mode
            // (acc_c_l compositing, acc_e_l the extremum), each beside its own
            // sums; the slice buffer's write word is chosen from them on the
            // route to its block RAM, the pixel for the FIFO is formed from them
            reg [AC_W-1:0] acc_c_l, acc_e_l;
            // S5: previous partial result, or a fresh ray. The selects are
            // S5's {dxb, t0, fresh} of this lane and the (static) mode bits,
            // as NQ register copies (sel5), one per quarter of the word: one
            // flip-flop for all lanes, or one per lane, drove 2 * AC_W
            // multiplexers spread over the lane and was the P = 8 build's
            // critical net (10.8 ns of routing).
            wire [5*NQ-1:0] sel5;           // copy c: {dxb, t0, fresh, ext, min} at [5*c +: 5]
            cube4_prim_copies #(.N(NQ), .W(5), .RESET(0)) u_sel5 (
                .clk(clk), .rst(1'b0),
                .d({dxb_s[4], t0_s[4][q], fresh_s[4][q], mode_ext_q, mode_min_q}), .q(sel5));
            wire [AC_W-1:0] acc_in;
            genvar qs;
            for (qs = 0; qs < NQ; qs = qs + 1) begin : g_sel
                localparam integer QL = qs * QW;
                localparam integer QN = (AC_W - QL < QW) ? AC_W - QL : QW;
                if (QN > 0) begin : g_bits
                    wire dxb5 = sel5[5*qs + 4], t05 = sel5[5*qs + 3], fresh5 = sel5[5*qs + 2];
                    wire ext5 = sel5[5*qs + 1], min5 = sel5[5*qs];
                    wire [QN-1:0] prev = dxb5
                        ? (t05 ? prevb_sh[q*AC_W + QL +: QN] : back_sh[q*AC_W + QL +: QN])
                        : s5_back[q*AC_W + QL +: QN];
                    wire [QN-1:0] fresh_q = ext5 ? (min5 ? FRESH_MIN[QL +: QN] : {QN{1'b0}})
                                                 : FRESH_CMP[QL +: QN];
                    assign acc_in[QL +: QN] = fresh5 ? fresh_q : prev;
                end
            end
            // the sample's {R', G', B', A}, R0's word carried along S1 .. S5
            // (stage k in bits [(k-1)*LUT_W +: LUT_W], a packed shift register)
            // PLW: at S3 -> S4 the A of a weighted sample becomes its column's
            reg  [5*LUT_W-1:0] rgba_l;
            wire [ALPHA_W-1:0] a_s3;
            always @(posedge clk) begin
                rgba_l <= {rgba_l[4*LUT_W-1:3*LUT_W], rgba_l[2*LUT_W+ALPHA_W +: 24], a_s3,
                           rgba_l[0 +: 2*LUT_W], r0_rgba[q*LUT_W +: LUT_W]};
            end
            if (PLW != 0) begin : g_pwt
                // the lane's copy of the path-weight columns, read with R0's sample
                // (S1: the RAM's read register), its word registered once more
                // (S2: the RAM's output register, a block RAM's own, so no logic
                // and no clock-to-out of the block after it), then carried to S3
                wire [PWC_W-1:0] w2_cols;
                reg  [PWC_W-1:0] w3_cols;
                cube4_sdp_ram #(.DATA_W(PWC_W), .DEPTH(1 << VOXEL_W), .OUT_REG(1)) u_wtab (
                    .clk(clk), .rd_en(1'b1), .rd_addr(r0_smp[q*VOXEL_W +: VOXEL_W]), .rd_data(w2_cols),
                    .wr_en(lut_we), .wr_addr(lut_addr), .wr_data(lut_data));
                always @(posedge clk) w3_cols <= w2_cols;
                wire [ALPHA_W-1:0] a_col = w3_cols[pw_col_3[2*q +: 2] * ALPHA_W +: ALPHA_W];
                assign a_s3 = (pw_use_3[q] && !mode_ext_q) ? a_col : rgba_l[2*LUT_W +: ALPHA_W];
            end else begin : g_no_pwt
                wire unused_pw_lane = ^{pw_use_3[q], pw_col_3[2*q +: 2]};
                assign a_s3 = rgba_l[2*LUT_W +: ALPHA_W];
            end
            wire [LUT_W-1:0] rgba5 = rgba_l[4*LUT_W +: LUT_W];
            reg  [LUT_W-1:0] s6_rgba;
            always @(posedge clk) begin
                s6_rgba <= rgba5;
            end
            wire [AC_W-1:0]  word_cmp, word_ext;    // S10: the new partial result
            wire [CMP_W-1:0] pix_cmp, pix_ext;      // S11: {R, G, B, A} of a finished ray

            if (COMPOSITING != 0) begin : g_cmp
                // S6: compositing's register of the partial result, kept
                // apart from the extremum's (g_ext's s6_e, which shares its
                // low bits): each is placed by its own logic
                wire [CMP_W-1:0] s6_acc;
                cube4_prim_copies #(.N(1), .W(CMP_W), .RESET(0)) u_s6_acc (
                    .clk(clk), .rst(1'b0), .d(acc_in[CMP_W-1:0]), .q(s6_acc));
                reg  [CMP_W-1:0] s7_acc, s8_acc;    // {C_R, C_G, C_B, T}
                reg  [3*CW-1:0]  s9_cc;             // {C_R, C_G, C_B} (T: s9_t)
                reg  [23:0]      s7_c, s8_c;        // the sample's {R', G', B'}
                always @(posedge clk) begin
                    {s7_acc, s8_acc, s9_cc}  <= {s6_acc, s7_acc, s8_acc[CW +: 3*CW]};
                    {s7_c, s8_c}             <= {s6_rgba[ALPHA_W +: 24], s7_c};
                end
                // S6: T * A (X-ray: 2^F * A); cube4_mul's operand registers
                // take S5's values as s6_acc and s6_rgba do, its product
                // register is S7's
                wire [CW-1:0] t_mul_d = mode_xray_q ? ONE : acc_in[0 +: CW];
                wire signed [TA_W+1:0] ta_p;
                cube4_mul #(.A_W(CW + 1), .B_W(ALPHA_W + 1)) u_ta (
                    .clk (clk), .en (1'b1), .a ($signed({1'b0, t_mul_d})),
                    .b ($signed({1'b0, rgba5[0 +: ALPHA_W]})), .p (ta_p));
                wire [TA_W-1:0] s7_ta = ta_p[TA_W-1:0];   // 0 <= T * A < 2^TA_W
                wire unused_ta = ^{ta_p[TA_W +: 2], s6_rgba[0 +: ALPHA_W]};   // (A's copy at S6: the extremum's)
                // S7: w = round_shift(T * A, AW), 0 <= w <= T (X-ray: <= 2^F);
                // 0 for a sample that does not count
                wire signed [CW+1:0] w_rs;
                cube4_round_shift #(.IN_W(TA_W + 1), .SHIFT(ALPHA_W)) u_w (
                    .x($signed({1'b0, s7_ta})), .y(w_rs));
                wire [CW-1:0] w_d = cnt_s[7][q] ? w_rs[CW-1:0] : {CW{1'b0}};
                // S8: w in fabric registers between the two multipliers (the T * A
                // product register through the rounding straight into the w * C'
                // multipliers' operand registers was a DSP -> fabric -> DSP path
                // of 7 ns of routing): one copy per w * C' multiplier and one for
                // T - w, each placed by its own loads
                wire [4*CW-1:0] s8_w;       // copy ch: channel ch's multiplier; copy 3: T - w
                cube4_prim_copies #(.N(4), .W(CW), .RESET(0)) u_w8 (
                    .clk(clk), .rst(1'b0), .d(w_d), .q(s8_w));
                // S8: T - w (X-ray: at least 0)
                wire [CW-1:0] w8_t = s8_w[3*CW +: CW];
                wire [CW-1:0] t8   = s8_acc[0 +: CW];
                reg  [CW-1:0] s9_t, s10_t;
                always @(posedge clk) begin
                    s9_t  <= (mode_xray_q && w8_t > t8) ? {CW{1'b0}} : t8 - w8_t;
                    s10_t <= s9_t;
                end
                // S9: w * C' per channel (cube4_mul: its operand registers take
                // S8's w and C', its product register is S10's)
                wire [3*WC_W-1:0] s10_wc;
                reg  [3*WC_W-1:0] s10_cin;   // {C, 2^7} per channel: C * 2^8 + the rounding half
                reg  [3*(WC_W+1)-1:0] s10_dsat;  // C * 2^8 + 2^7 - (ONE + 1) * 2^8, signed
                genvar ch;
                for (ch = 0; ch < 3; ch = ch + 1) begin : g_mul   // channel ch = B, G, R for 0, 1, 2
                    wire signed [WC_W+1:0] wc_p;
                    cube4_mul #(.A_W(CW + 1), .B_W(9)) u_wc (
                        .clk (clk), .en (1'b1), .a ($signed({1'b0, s8_w[ch*CW +: CW]})),
                        .b ($signed({1'b0, s8_c[8 * ch +: 8]})), .p (wc_p));
                    assign s10_wc[ch*WC_W +: WC_W] = wc_p[WC_W-1:0];   // 0 <= w * C' < 2^WC_W
                    wire unused_wc = ^wc_p[WC_W +: 2];
                    always @(posedge clk) begin
                        s10_cin[ch*WC_W +: WC_W] <= {s9_cc[ch*CW +: CW], 8'h80};
                        s10_dsat[ch*(WC_W+1) +: WC_W+1] <= (WC_W+1)'({1'b0, s9_cc[ch*CW +: CW], 8'h80})
                                                         - (WC_W+1)'({1'b0, ONE} + 1'b1) * (WC_W+1)'(256);
                    end
                end
                // S10: C += round_shift(w * C', 8) (X-ray: at most 2^F), in one
                // add: C + floor((wc + 2^7) / 2^8) = floor((C * 2^8 + 2^7 + wc) / 2^8)
                // (w * C' / 2^8 < 2^CW, so the sum needs CW + 1 bits, as before).
                // The X-ray's sum > ONE, i.e. C * 2^8 + 2^7 + wc >= (ONE + 1) * 2^8,
                // is the sign of a second add beside the first, s10_dsat + wc, with
                // s10_dsat in [-2^WC_W, 0) and wc in [0, 2^WC_W): it fits WC_W + 2
                // signed bits and nothing wraps (no compare after the add)
                wire [3*CW-1:0] c_out;
                for (ch = 0; ch < 3; ch = ch + 1) begin : g_ch
                    wire [WC_W:0] sum_x = {1'b0, s10_cin[ch*WC_W +: WC_W]} + {1'b0, s10_wc[ch*WC_W +: WC_W]};
                    wire [CW:0]   sum   = sum_x[WC_W:8];
                    wire unused_frac = ^sum_x[7:0];
                    wire signed [WC_W+1:0] sat_x = $signed({s10_dsat[ch*(WC_W+1) + WC_W], s10_dsat[ch*(WC_W+1) +: WC_W+1]})
                                                 + $signed({2'b00, s10_wc[ch*WC_W +: WC_W]});
                    wire over = !sat_x[WC_W+1];    // sum > ONE
                    wire unused_sat = ^{sat_x[WC_W:0], sum[CW]};
                    assign c_out[ch*CW +: CW] = (mode_xray_q && over) ? ONE : sum[CW-1:0];
                end
                assign word_cmp = AC_W'({c_out, s10_t});
                // S11: the pixel {R, G, B, A = 1 - T} from the register
                assign pix_cmp  = {acc_c_l[CW +: 3*CW], ONE - acc_c_l[0 +: CW]};
            end else begin : g_no_cmp
                wire unused_xray = mode_xray_q;
                assign word_cmp = '0;
                assign pix_cmp  = '0;
            end

            if (EXTREMUM != 0) begin : g_ext
                // the sample v, R0's word carried along S1 .. S6
                reg [6*VOXEL_W-1:0] v_l;
                always @(posedge clk) begin
                    v_l <= {v_l[5*VOXEL_W-1:0], r0_smp[q*VOXEL_W +: VOXEL_W]};
                end
                wire [VOXEL_W-1:0] v6 = v_l[5*VOXEL_W +: VOXEL_W];
                // S6: the extremum's register of the partial result (kept
                // apart from g_cmp's s6_acc, which shares its low bits: both
                // are cube4_prim_copies, which synthesis never merges; a plain
                // register would be merged into the kept one), then take
                // the sample if it counts and is at least (MinIP: at most) the kept v
                wire [EXT_W-1:0] s6_e;
                cube4_prim_copies #(.N(1), .W(EXT_W), .RESET(0)) u_s6_e (
                    .clk(clk), .rst(1'b0), .d(acc_in[EXT_W-1:0]), .q(s6_e));
                wire [VOXEL_W-1:0] kept = s6_e[LUT_W +: VOXEL_W];
                // (the choice is registered as a flag beside both candidates and
                // made at S7 -> S8: the compare's result reaches one flip-flop,
                // not the select of every bit of the word)
                wire take_s = cnt_s[6][q] && (mode_min_q ? (v6 <= kept) : (v6 >= kept));
                reg              s7_take;
                reg [EXT_W-1:0]  s7_new, s7_old, s8_e, s9_e, s10_e;
                always @(posedge clk) begin
                    s7_take <= take_s;
                    s7_new  <= {v6, s6_rgba};
                    s7_old  <= s6_e;
                    s8_e    <= s7_take ? s7_new : s7_old;
                    s9_e  <= s8_e;
                    s10_e <= s9_e;
                end
                // S11: the pixel from the register: colour << (F - 8), A to F bits
                wire [EXT_W-1:0] e11 = acc_e_l[EXT_W-1:0];
                wire [CW-1:0] a_px;
                if (ACC_W >= ALPHA_W) begin : g_a_up
                    assign a_px = CW'(e11[0 +: ALPHA_W]) << (ACC_W - ALPHA_W);
                end else begin : g_a_down
                    wire signed [ACC_W+1:0] a_rs;
                    cube4_round_shift #(.IN_W(ALPHA_W + 1), .SHIFT(ALPHA_W - ACC_W)) u_a (
                        .x($signed({1'b0, e11[0 +: ALPHA_W]})), .y(a_rs));
                    assign a_px = a_rs[CW-1:0];
                end
                wire [CW-1:0] r_px = CW'(e11[ALPHA_W + 16 +: 8]) << (ACC_W - 8);
                wire [CW-1:0] g_px = CW'(e11[ALPHA_W + 8 +: 8]) << (ACC_W - 8);
                wire [CW-1:0] b_px = CW'(e11[ALPHA_W +: 8]) << (ACC_W - 8);
                wire unused_e11 = ^e11[EXT_W-1:LUT_W];   // v: kept for the next sample only
                assign word_ext = AC_W'(s10_e);
                assign pix_ext  = {r_px, g_px, b_px, a_px};
            end else begin : g_no_ext
                wire unused_smp = ^r0_smp[q*VOXEL_W +: VOXEL_W];
                assign word_ext = '0;
                assign pix_ext  = '0;
            end

            // S11: the mode's registers (load on every cycle; the slice buffer's
            // write enable is the beat's valid bit). One register for both
            // modes sat between the two modes' logic, the slice buffer and
            // the FIFO, and S10's compositing sums reached it over 4.9 ns of
            // routing (P = 8). The write word's select per quarter uses that
            // quarter's mode copy (sel5: static within a frame).
            always @(posedge clk) begin
                acc_c_l <= word_cmp;
                acc_e_l <= word_ext;
            end
            for (qs = 0; qs < NQ; qs = qs + 1) begin : g_wr
                localparam integer QL = qs * QW;
                localparam integer QN = (AC_W - QL < QW) ? AC_W - QL : QW;
                if (QN > 0) begin : g_bits
                    assign acc_q[q*AC_W + QL +: QN] = sel5[5*qs + 1] ? acc_e_l[QL +: QN] : acc_c_l[QL +: QN];
                end
            end
            assign pix_d[q*CMP_W +: CMP_W] = mode_ext_q ? pix_ext : pix_cmp;
        end
    endgenerate

    // ---- output FIFO: an S11 beat with a finished ray, or the frame's last beat ----
    // give: an S10 beat that leaves nothing returns its FIFO entry.
    wire out_d = v_s[NS-1] && ((fin_s[NS-1] != '0) || eop_s[NS-1]);   // S9: will push
    reg  give_q, push_q;                // S10: returns its entry; will push at S11
    always @(posedge clk) begin
        if (rst) begin
            give_q <= 1'b0;
            push_q <= 1'b0;
        end else begin
            give_q <= v_s[NS-1] && !out_d;
            push_q <= out_d;
        end
    end
    // the beat's fields at S11, beside its pixels
    reg [P-1:0]      fin_11;
    reg [M_W-1:0]    m_11;
    reg [BX_W-1:0]   by_11;
    reg [P*BX_W-1:0] bx_11;
    reg              eop_11;
    always @(posedge clk) begin
        fin_11 <= fin_s[NS];  m_11 <= m_s[NS];  by_11 <= by_s[NS];  bx_11 <= bx_s[NS];  eop_11 <= eop_s[NS];
    end

    // the word: P lane groups of AC_W bits (pixels), then the shared fields
    localparam integer SH_W  = P + M_W + BX_W + P * BX_W + 1;
    localparam integer OUT_W = PX_W + SH_W;
    wire [OUT_W-1:0] fifo_out;
    wire unused_credit_d;
    // The FIFO stores S11's word: S10's sums end at acc_q alone (the slice
    // buffer's write register), and the pixels are formed from it on the
    // route to the FIFO's distributed RAM (one cycle more through COM than
    // a FIFO written at S10)
    cube4_credit_fifo #(.DATA_W(OUT_W), .DEPTH(FIFO_DEPTH)) u_fifo (
        .clk(clk), .rst(rst), .take(take), .give(give_q),
        .credit(credit), .credit_d(unused_credit_d),
        .push_d(push_q), .in_data({fin_11, m_11, by_11, bx_11, eop_11, pix_d}),
        .out_valid(pix_valid), .out_ready(pix_ready), .out_data(fifo_out));
    assign {pix_mask, pix_m, pix_by, pix_bx, pix_eop, pix_rgba} = fifo_out;

endmodule
`default_nettype wire

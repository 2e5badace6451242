`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com
// -----------------------------------------------------------------------------
// Purpose
//   The COM units of all P pipelines (Teramac paper, section 5, Fig. 13, 14):
//   the ray's accumulation over the samples that count (header INSIDE and
//   KEEP), in the mode of the MODE register (docs/numerics.md sections 7, 13):
//     0 composite, 1 X-ray   cube4_com_blend (COMPOSITING = 1)
//     2 MIP, 3 MinIP         cube4_com_ext   (EXTREMUM = 1)
//   and the finished-ray stream (numerics.md section 8). A thin top of units
//   (docs/architecture.md "COM"):
//     u_seq      cube4_com_seq: takes a beat, R0's header, lane positions, the
//                beat's fields along S1 .. S11, finished rays, bx / by, mode
//     u_walk     cube4_com_walk (RECTS = 0): slot counters, the template,
//                fresh / next-inside rays, the read-after-write count
//     u_rect     cube4_com_rect (RECTS = 1): the same from the rectangle table
//     u_plw      cube4_com_plw (PLW = 1): path-length weights (section 17)
//     u_bpb      cube4_com_bpb: base-plane buffers and their ring hops
//     g_lane     cube4_com_lane per lane: the sample's word, previous result or
//                fresh ray, cube4_com_blend and / or cube4_com_ext
//     u_fifo     cube4_credit_fifo: the finished-ray beats
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
//   SLAB        1 (with COMPOSITING): each lane multiplies the blending A by
//               the sample's falloff weight (in_fall; cube4_com_lane).  0..1.  Default 0.
//   ZOUT        1: depth out: the buffer word grows by 2 (M_W + 1) bits, the
//               ray's {passed, first} slice numbers, given on pix_z.  0..1.  Default 0.
//   ZIN         1: depth in: cube4_com_stop reads each lane's stop slice from
//               the host's table (stop_*) and the sample counts only when
//               m < stop (S5 -> S6).  0..1.  Default 0.
//   BEATS       1: the beat schedule (numerics.md section 19; cube4_com_beats):
//               the slot {j, pb} from the header, the rays' intervals from the
//               front end's position bits (in_bits), a pixel only for a ray
//               that holds something, ray termination (term_*), its state
//               in the buffer word (CUBE4_TERM_CNT_W bits: live, a countdown,
//               done) and the reports (rep_*, com_m).
//               Needs RECTS, ZIN = 0.                  0..1. Default 0.
//   LAG         (after the build's list) BEATS: slices between a report and
//               the decisions' use of it (cube4_cfb_decide's LAG).  2..7.
//               Default CUBE4_BEAT_LAG (4).
//   The defaults are cube4_top's.
//
// Latency
//   12 register stages (R0, S1 .. S11) that move on every cycle (no stall
//   enable); R0 .. S10 carry a valid bit each, S11 (the lanes' acc_q) is
//   written under S10's (the slice buffer's write enable and the FIFO's push,
//   both given one stage early). S11's results are written into the output
//   FIFO (cube4_credit_fifo, 16 entries), whose memory stands in for a last
//   register: a finished-ray beat is on pix_* 12 cycles after it entered R0
//   when the FIFO was empty.
//   Back-pressure is credit-based: a beat enters R0 only when the FIFO has an
//   entry reserved for it, so pix_ready reaches only in_ready and the FIFO's
//   pointers, never a datapath register. in_ready depends on registers only
//   (the FIFO's credit and the valid bits of R0 .. S9). The partial results
//   take exactly one slice (NJ*NB steps) round the base-plane buffer.
//   Throughput is one beat per cycle when a slice has NJ*NB >= 11 beats; a
//   smaller slice runs at NJ*NB beats per 11 cycles (the read-after-write
//   hazard on the slice buffer: a beat's slot is read at S1 and written at
//   the end of S11, so a beat waits while the beat L = NJ*NB steps earlier
//   is in R0 .. S9). RECTS = 1 or BEATS = 1 (slots by position): a beat
//   waits while the beat that wrote its slot is in R0 .. S9. With RECTS,
//   in_ready then also depends on in_hdr (the slot compare); with BEATS the
//   input passes a skid buffer first (cube4_skid_peek, one cycle): in_ready
//   is its register, and the slot compare is a register decided a cycle
//   ahead from its entries (cube4_com_ahead).
//
// Ports
//   in_*      the shaded stream of cube4_sha: in_rgba lane q = {R, G, B (Q0.8),
//             A (Q0.ALPHA_W)}; in_sample lane q = the sample v (unsigned
//             VOXEL_W; read by the extremum datapath and the path weights only);
//             in_fall lane q = the slab's falloff weight f, 0 .. 256 (SLAB = 1
//             with COMPOSITING: the blending modes' A becomes round_shift(A f, 8)
//             at S5, cube4_com_lane; otherwise unused)
//   lut_*     the LUT's path-weight columns (PLW = 1): lut_data = {A at w = 3/2,
//             5/4, 3/4, 1/2}, Q0.ALPHA_W each, written at lut_addr when lut_we
//             (between frames); PLW = 0: one unused bit
//   rect_*    the rectangle table (RECTS = 1; cube4_cfb's, written alike)
//   stop_*    the stop table (ZIN = 1; cube4_com_stop, CUBE4_STOP_LAYOUT),
//             written between frames
//   in_bits   BEATS: each beat's {soon, last, fresh, run}, P bits each by
//             position t in the partial beam (cube4_cfb_skip)
//   in_eoss   BEATS: the beat is the last of its slice (cube4_frontend's
//             smp_eoss): com_m counts the slice once the beat has passed
//   in_geo    BEATS: {stepx, stepy [DIM_W], ph_x, ph_y [PHASE_W]} of the beat's
//             slice (cube4_com_steps, where the beats leave SHA); else unused
//   frame_start, term_en, term_tau [ACC_W+1] (Q0.ACC_W), term_vmin, term_vmax
//             [VOXEL_W]   BEATS: the frame's start; termination's rule (static)
//   rep_valid, rep_j, rep_pb, rep_stx, rep_sty, rep_en [P] (by position),
//   rep_end [P*M_W], com_m [M_W]   BEATS: the reports into the ray table and
//             the slices whose beats have all passed (cube4_cfb_decide's rep_*)
//   pix_*     finished rays: pix_mask (lane holds a finished ray), pix_m, pix_by,
//             pix_bx lane q, pix_rgba lane q = {R, G, B, A} each ACC_W + 1 bits
//             (Q0.ACC_W, 0 .. 2^ACC_W), pix_eop (last beat of the frame), pix_z
//             lane q = {passed, first}, each {valid, m} (ZOUT = 1, depth out,
//             numerics.md section 21; else 0)
//   cfg       view registers (cube4_defs.vh); SX, SY = stepx(M-1), stepy(M-1)
//
// Bit growth and rounding: in the units (cube4_com_blend: T * A, w * C';
//   cube4_com_ext: the pixel's A; cube4_com_plw: comparisons only). Composite:
//   nothing wraps and nothing saturates (numerics.md section 7); X-ray
//   saturates C at 2^F and T at 0 (section 13).
// =============================================================================
module cube4_com #(
    `CUBE4_BUILD_PARAMS,
    parameter integer LAG   = `CUBE4_BEAT_LAG,
    `CUBE4_RECT_LAYOUT, `CUBE4_STOP_LAYOUT,
    localparam integer BX_W = DIM_W + 1,
    localparam integer PWC_W = (PLW != 0) ? 4 * ALPHA_W : 1,  // the path-weight columns
    localparam integer GEO_W = `CUBE4_GEO_W         // cube4_com_steps' q_geo
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    // the LUT's path-weight columns (PLW = 1)
    input  wire lut_we, input wire [VOXEL_W-1:0] lut_addr, input wire [PWC_W-1:0] lut_data,
    // the rectangle table (RECTS = 1; cube4_cfb's, written alike; COM reads INS, J_IN,
    // J_HI, I_IN, I_HIN, STX, STY)
    input  wire rect_we, input wire [M_W-1:0] rect_addr, input wire [RECT_W-1:0] rect_data,
    // the stop table (ZIN = 1; cube4_com_stop: one word of all P banks per address)
    input  wire stop_we, input wire [STOP_AW-1:0] stop_addr, input wire [P*M_W-1:0] stop_data,
    // shaded stream in
    input  wire in_valid, output wire in_ready, input wire [HDR_W-1:0] in_hdr,
    input  wire [P*(24+ALPHA_W)-1:0] in_rgba,
    input  wire [P*VOXEL_W-1:0] in_sample,
    input  wire [P*FALL_W-1:0] in_fall,
    input  wire [4*P-1:0] in_bits,      // BEATS = 1: the beat's {soon, last, fresh, run}
    input  wire           in_eoss,      // BEATS = 1: the beat is the last of its slice
    input  wire [GEO_W-1:0] in_geo,     // BEATS = 1: the steps and phases of its slice
    // BEATS = 1: ray termination's rule (static in a frame), the frame's start, and
    // the reports into the front end's ray table (cube4_cfb_decide's rep_*, com_m)
    input  wire frame_start,
    input  wire term_en, input wire [ACC_W:0] term_tau,
    input  wire [VOXEL_W-1:0] term_vmin, input wire [VOXEL_W-1:0] term_vmax,
    output wire rep_valid, output wire [DIM_W-1:0] rep_j, output wire [PB_W-1:0] rep_pb,
    output wire [DIM_W-1:0] rep_stx, output wire [DIM_W-1:0] rep_sty,
    output wire [P-1:0] rep_en, output wire [P*M_W-1:0] rep_end, output wire [M_W-1:0] com_m,
    // finished rays out: lane mask, slice, base-plane row and columns, RGBA, last beat
    output wire pix_valid, input wire pix_ready,
    output wire [P-1:0] pix_mask, output wire [M_W-1:0] pix_m, output wire pix_eop,
    output wire [BX_W-1:0] pix_by, output wire [P*BX_W-1:0] pix_bx,
    output wire [P*4*(ACC_W+1)-1:0] pix_rgba,
    output wire [P*2*(M_W+1)-1:0] pix_z
);
    generate
        `CUBE4_BUILD_CHECKS("cube4_com")
        if (PLW != 0 && RECTS != 0) begin : g_plw_rects
            $error("cube4_com: PLW = 1 with RECTS = 1 is not built (the path weights follow every slice's template)");
        end
        if (PLW != 0 && COMPOSITING == 0) begin : g_plw_alone
            $error("cube4_com: PLW = 1 needs COMPOSITING = 1 (only the blending modes are weighted)");
        end
        `CUBE4_RANGE(g_bad_lag, "cube4_com", "LAG", LAG, 2, 7)
        if (BEATS != 0 && (RECTS != 0 || ZIN != 0)) begin : g_beats_alone
            $error("cube4_com: BEATS = 1 needs RECTS = 0 and ZIN = 0 (not built; depth in: the ray table's stops)");
        end
        if (COMPOSITING == 0 && EXTREMUM == 0) begin : g_no_mode
            $error("cube4_com: COMPOSITING = 0 and EXTREMUM = 0 leave no rendering mode");
        end
    endgenerate

    `CUBE4_VIEW_FIELDS(cfg);
    `CUBE4_LANE_FUNCTIONS
    localparam integer CW     = ACC_W + 1;          // one accumulator channel
    generate
        if (CW < 25) begin : g_depth_t_top
            wire unused_depth_t = ^cfg_depth_t[24:CW];   // DEPTH_T holds T of the widest ACC_W
        end
    endgenerate
    localparam integer CMP_W  = 4 * CW;             // blending word {R, G, B, T}; a pixel {R, G, B, A}
    localparam integer LUT_W  = 24 + ALPHA_W;       // a sample's {R', G', B', A}
    localparam integer EXT_W  = VOXEL_W + LUT_W;    // extremum word {v, R, G, B, A}
    // a ray's partial result in the buffers: wide enough for the build's modes
    localparam integer AM_W   = (COMPOSITING != 0 && (EXTREMUM == 0 || CMP_W >= EXT_W)) ? CMP_W : EXT_W;
    // depth out (ZOUT = 1): the ray's two slice numbers {valid, m} above the mode's word
    localparam integer ZW     = 2 * (M_W + 1);
    localparam integer AC_W   = AM_W + ((ZOUT != 0) ? ZW : 0) + ((BEATS != 0) ? `CUBE4_TERM_CNT_W(LAG) : 0);   // (BEATS: the termination state)
    localparam integer PA     = P * AC_W;
    // slice-buffer slot: j * NB + pb counted; with rectangles {j, pb} from the header
    localparam integer RW     = (MAX_DIM > 1) ? $clog2(MAX_DIM) : 1;
    localparam integer BYPOS  = (RECTS != 0 || BEATS != 0) ? 1 : 0;   // slots by position {j, pb}
    localparam integer SP_W   = (BYPOS != 0) ? RW + PB_W : ((MAX_DIM * NBMAX > 1) ? $clog2(MAX_DIM * NBMAX) : 1);
    localparam integer SB_DEPTH = (BYPOS != 0) ? (1 << SP_W) : MAX_DIM * NBMAX;
    localparam integer NS     = 10;                 // stages S1 .. S10 (cube4_com_seq)
    localparam integer NQ     = 4;                  // control copies per lane word
    localparam integer FIFO_DEPTH = 16;             // >= 14 cycles from acceptance to the FIFO's read
    localparam integer PH_W   = PHASE_W;

    // ==== the input: on the beat schedule through a skid buffer (cube4_skid_peek),
    // so R0 starts at its registers, in_ready is a register, and the slot compare
    // (hazard) is a register decided a cycle ahead from compares each beat keeps while it waits (cube4_com_ahead); otherwise straight in (the fixed, box and rectangle schedules,
    // whose cycles the golden model predicts) ====
    localparam integer IN_W = HDR_W + P * (24 + ALPHA_W) + P * VOXEL_W + P * FALL_W + 4 * P + 1;
    wire                      c_valid, c_ready, c_eoss;
    wire [HDR_W-1:0]          c_hdr;
    wire [P*(24+ALPHA_W)-1:0] c_rgba;
    wire [P*VOXEL_W-1:0]      c_sample;
    wire [P*FALL_W-1:0]       c_fall;
    wire [4*P-1:0]            c_bits;
    wire [GEO_W-1:0]          c_geo;          // BEATS: the beat's steps and phases, with it
    wire                      c_nx_valid;     // BEATS: the skid holds a second beat
    generate
        if (BEATS != 0) begin : g_in_skid
            wire [IN_W+GEO_W-1:0] c_nx;
            wire unused_ready_cp, unused_ready_nx, unused_valid_cp;   // (in_ready, c_valid are their copies)
            cube4_skid_peek #(.DATA_W(IN_W + GEO_W)) u_in (
                .clk(clk), .rst(rst),
                .in_valid(in_valid), .in_ready(in_ready),
                .in_data({in_geo, in_hdr, in_rgba, in_sample, in_fall, in_bits, in_eoss}),
                .out_valid(c_valid), .out_ready(c_ready),
                .out_data({c_geo, c_hdr, c_rgba, c_sample, c_fall, c_bits, c_eoss}),
                .nx_valid(c_nx_valid), .nx_data(c_nx), .in_ready_cp(unused_ready_cp),
                .in_ready_nx(unused_ready_nx), .out_valid_cp(unused_valid_cp));
            wire unused_nx = ^{c_nx, unused_ready_cp, unused_ready_nx, unused_valid_cp};   // (the look-ahead keeps its own compares)
        end else begin : g_in_direct
            assign {c_valid, c_hdr, c_rgba, c_sample, c_fall, c_bits, c_eoss}
                 = {in_valid, in_hdr, in_rgba, in_sample, in_fall, in_bits, in_eoss};
            assign in_ready = c_ready;
            assign c_geo = '0;
            assign c_nx_valid = 1'b0;
            wire unused_geo = ^{in_geo, c_geo, c_nx_valid};
        end
    endgenerate

    // ==== the sequencer (BEATS = 1: a lane is inside only where its ray runs) ====
    wire [P-1:0]     run0;                // S0: the lanes whose rays run (BEATS; all otherwise)
    wire [P*LANE_W-1:0] tpos;
    generate
        if (BEATS != 0) begin : g_run
            // the bits come by position t in the partial beam; lane q holds t = tpos[q]
            // (S0, a register of its own, cube4_com_seq T_R0): R0 registers the bits as
            // they come, S0 takes each lane's, so neither the skew's lane positions nor
            // the bits' multiplexer lies between COM's input skid and R0, and only the
            // multiplexer lies between R0 and S1
            reg [P-1:0] r0_runp;
            always @(posedge clk) r0_runp <= c_bits[0 +: P];
            genvar qr;
            for (qr = 0; qr < P; qr = qr + 1) begin : g_lane_run
                assign run0[qr] = r0_runp[tpos[qr*LANE_W +: LANE_W]];
            end
        end else begin : g_no_run
            assign run0 = '1;
            wire unused_bits = ^{c_bits, c_eoss, frame_start, term_en, term_tau, term_vmin, term_vmax};
        end
    endgenerate
    wire              take, credit, hazard, step, sop, first, dxb, dyb;
    wire [1:0]        step_c;
    wire [M_W-1:0]    r0_m;
    wire [DIM_W-1:0]  r0_j;
    wire [PB_W-1:0]   r0_pb;
    wire [P*IW-1:0]   ipos, f1_ipos;
    wire [P-1:0]      keep_5;
    wire [IW-1:0]     f1_j;
    wire              f1_dxf, f1_dyf;
    wire [SP_W-1:0]   pos_sp, sp_wr;
    wire [PB_W-1:0]   pos_pb, pb_rd, pb_wr;
    wire [P-1:0]      fresh, nx_in;
    wire [DIM_W-1:0]  stx, sty;
    wire [NS:1]       v_s;
    wire [(NS-1)*SP_W-1:0] sp_fly;
    wire              dxb4, dyb4, dkb4, col1_4;
    wire [P-1:0]      t0_4, fresh_4, cnt_6, cnt_7;
    wire              mode_xray, mode_ext, mode_min;
    wire              push_d, give;
    wire [P-1:0]      fin_o;
    wire [M_W-1:0]    m_o;
    wire [BX_W-1:0]   by_o;
    wire [P*BX_W-1:0] bx_o;
    wire              eop_o;
    cube4_com_seq #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .SP_W(SP_W),
        .COMPOSITING(COMPOSITING), .EXTREMUM(EXTREMUM), .T_R0(BEATS != 0 ? 1 : 0)
    ) u_seq (
        .clk(clk), .rst(rst), .cfg(cfg),
        .in_valid(c_valid), .in_ready(c_ready), .in_hdr(c_hdr),
        .take(take), .credit(credit), .hazard(hazard), .step(step), .step_c(step_c),
        .r0_m(r0_m), .r0_j(r0_j), .r0_pb(r0_pb), .sop(sop), .first(first), .dxb(dxb), .dyb(dyb),
        .ipos(ipos), .tpos(tpos), .f1_ipos(f1_ipos), .f1_j(f1_j), .f1_dxf(f1_dxf), .f1_dyf(f1_dyf),
        .pos_sp(pos_sp), .pos_pb(pos_pb), .fresh(fresh), .run0(run0), .stx(stx), .sty(sty), .nx_in(nx_in),
        .v_s(v_s), .sp_fly(sp_fly), .sp_wr(sp_wr), .pb_rd(pb_rd), .pb_wr(pb_wr),
        .dxb4(dxb4), .dyb4(dyb4), .dkb4(dkb4), .t0_4(t0_4), .fresh_4(fresh_4),
        .keep_5(keep_5), .fin_5(fin_t5), .cnt_6(cnt_6), .cnt_7(cnt_7),
        .mode_xray(mode_xray), .mode_ext(mode_ext), .mode_min(mode_min),
        .push_d(push_d), .give(give),
        .fin_o(fin_o), .m_o(m_o), .by_o(by_o), .bx_o(bx_o), .eop_o(eop_o));

    // ==== the slice geometry: the template (counted slots) or the rectangles ====
    wire [PH_W-1:0] ph_x, ph_y, phn_x, phn_y;
    wire            f1_last, f1_wxn, f1_wyn;
    generate
        if (BEATS != 0) begin : g_beats
            wire [P-1:0] soon_0;
            cube4_com_beats #(
                .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .SP_W(SP_W)
            ) u_beats (
                .clk(clk), .rst(rst), .cfg(cfg), .in_bits(c_bits), .tpos(tpos),
                .c_geo(c_geo),
                .in_valid(c_valid), .in_hdr(c_hdr), .nx_valid(c_nx_valid),
                .sk_hdr(in_hdr), .take(take), .step(step), .v_fly(v_s[9:1]), .sp_fly(sp_fly),
                .r0_m(r0_m), .r0_j(r0_j), .r0_pb(r0_pb),
                .f1_ipos(f1_ipos), .f1_j(f1_j), .f1_dxf(f1_dxf), .f1_dyf(f1_dyf),
                .pos_sp(pos_sp), .pos_pb(pos_pb), .hazard(hazard), .fresh(fresh), .nx_in(nx_in),
                .stx(stx), .sty(sty), .col1_4(col1_4), .soon_0(soon_0),
                .ph_x(ph_x), .ph_y(ph_y), .phn_x(phn_x), .phn_y(phn_y),
                .f1_klast(f1_last), .f1_wxn(f1_wxn), .f1_wyn(f1_wyn));
            // ---- the reports (S11 -> S12 -> registers): a lane whose ray COM found done
            // writes m + LAG + 1 at its position of the ray table; com_m counts
            // the slices whose beats have all passed: a beat of a later slice,
            // or the slice's last beat (EOSS, with R0 .. S11 beside it), has ----
            reg          r0_eoss, eoss11;
            reg [NS:1]   eoss_s;
            always @(posedge clk) begin
                r0_eoss <= c_eoss;                  // (R0 loads on every cycle)
                eoss_s  <= {eoss_s[NS-1:1], r0_eoss};
                eoss11  <= eoss_s[NS];
            end
            localparam integer RX_W = P + P * LANE_W + 2 * DIM_W;   // {rok, tpos, stx, sty} S1 .. S11
            reg  [RX_W-1:0] rx_s [1:11];
            reg  [SP_W-1:0] sp11;
            reg             v11;
            integer kx;
            always @(posedge clk) begin
                rx_s[1] <= {run0 & ~soon_0, tpos, stx, sty};
                for (kx = 2; kx <= 11; kx = kx + 1) rx_s[kx] <= rx_s[kx-1];
                sp11 <= sp_wr;
                v11  <= rst ? 1'b0 : v_s[NS];
            end
            wire [P*LANE_W-1:0] t11;
            wire [DIM_W-1:0]    stx11, sty11;
            assign {rok11, t11, stx11, sty11} = rx_s[11];
            // S12: the lanes' reports and the beat's fields registered, so the lanes'
            // "done" tests end at flip-flops; the reports and com_m leave a cycle
            // later together (their order, which the decisions rely on, is kept)
            reg  [P-1:0]        rep12;
            reg  [P*LANE_W-1:0] t12;
            reg  [SP_W-1:0]     sp12;
            reg  [DIM_W-1:0]    stx12, sty12;
            reg  [M_W-1:0]      m12;
            reg                 v12, c12, end12;   // c12: v11 outside a frame's start (com_m's)
            always @(posedge clk) begin
                rep12 <= rep;
                t12   <= t11;
                sp12  <= sp11;
                stx12 <= stx11;
                sty12 <= sty11;
                m12   <= m_o;
                end12 <= eop_o || eoss11;
                v12   <= !rst && v11;
                c12   <= !rst && !frame_start && v11;
            end
            reg  [P-1:0] at_pos;
            integer qt, tt;
            always @* begin
                at_pos = '0;
                for (tt = 0; tt < P; tt = tt + 1)
                    for (qt = 0; qt < P; qt = qt + 1)
                        if (rep12[qt] && (32'(t12[qt*LANE_W +: LANE_W]) == tt)) at_pos[tt] = 1'b1;
            end
            reg              rv_q;
            reg [P-1:0]      ren_q;
            reg [DIM_W-1:0]  rj_q, rsx_q, rsy_q;
            reg [PB_W-1:0]   rpb_q;
            reg [M_W-1:0]    rend_q, com_q;
            always @(posedge clk) begin
                rv_q   <= !rst && v12 && (rep12 != '0);
                ren_q  <= at_pos;
                rj_q   <= DIM_W'(sp12[PB_W +: RW]);
                rpb_q  <= sp12[0 +: PB_W];
                rsx_q  <= stx12;
                rsy_q  <= sty12;
                rend_q <= m12 + M_W'(LAG + 1);
                if (rst || frame_start) com_q <= '0;
                else if (c12)           com_q <= end12 ? m12 + 1'b1 : m12;
            end
            assign {rep_valid, rep_en, rep_j, rep_pb, rep_stx, rep_sty} = {rv_q, ren_q, rj_q, rpb_q, rsx_q, rsy_q};
            assign rep_end = {P{rend_q}};
            assign com_m = com_q;
            wire unused_beats = ^{rect_we, rect_addr, rect_data, step_c, sop, first, v_s[NS], dxb, dyb, ipos};
        end else if (RECTS == 0) begin : g_walk
            cube4_com_walk #(
                .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .SP_W(SP_W)
            ) u_walk (
                .clk(clk), .rst(rst), .cfg(cfg),
                .step_c(step_c), .take(take), .step(step), .v_fly(v_s[8:1]),
                .sop(sop), .first(first), .r0_m(r0_m), .r0_j(r0_j), .dxb(dxb), .dyb(dyb), .ipos(ipos),
                .f1_ipos(f1_ipos), .f1_j(f1_j), .f1_dxf(f1_dxf), .f1_dyf(f1_dyf),
                .pos_sp(pos_sp), .pos_pb(pos_pb), .hazard(hazard), .fresh(fresh), .nx_in(nx_in),
                .stx(stx), .sty(sty), .ph_x(ph_x), .ph_y(ph_y), .phn_x(phn_x), .phn_y(phn_y),
                .f1_last(f1_last), .f1_wxn(f1_wxn), .f1_wyn(f1_wyn));
            assign col1_4 = 1'b0;
            wire unused_walk = ^{rect_we, rect_addr, rect_data, r0_pb, v_s[NS:9], sp_fly};
        end else begin : g_rect
            cube4_com_rect #(
                .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2),
                .ADDR_W(ADDR_W), .SP_W(SP_W)
            ) u_rect (
                .clk(clk), .rst(rst), .cfg(cfg),
                .rect_we(rect_we), .rect_addr(rect_addr), .rect_data(rect_data),
                .take(take), .in_hdr(c_hdr), .step(step), .v_fly(v_s[9:1]), .sp_fly(sp_fly),
                .r0_m(r0_m), .r0_j(r0_j), .r0_pb(r0_pb), .dxb(dxb), .dyb(dyb), .ipos(ipos),
                .f1_ipos(f1_ipos), .f1_j(f1_j), .f1_dxf(f1_dxf), .f1_dyf(f1_dyf),
                .pos_sp(pos_sp), .pos_pb(pos_pb), .hazard(hazard), .fresh(fresh), .nx_in(nx_in),
                .stx(stx), .sty(sty), .col1_4(col1_4));
            assign {ph_x, ph_y, phn_x, phn_y} = '0;
            assign {f1_last, f1_wxn, f1_wyn} = 3'b000;
            wire unused_rect = ^{step_c, sop, first, v_s[NS]};
        end
    endgenerate

    generate
        if (BEATS == 0) begin : g_no_rep
            assign {rep_valid, rep_en, rep_j, rep_pb, rep_stx, rep_sty} = '0;
            assign rep_end = '0;
            assign com_m   = '0;
            assign rok11   = '0;
            wire unused_rep = ^{fin_t5, rep, run0};
        end
    endgenerate

    // ==== depth in: the lanes' samples in front of the geometry (S5) ====
    generate
        if (ZIN != 0) begin : g_stop
            cube4_com_stop #(
                .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2)
            ) u_stop (
                .clk(clk), .cfg(cfg),
                .stop_we(stop_we), .stop_addr(stop_addr), .stop_data(stop_data),
                .r0_m(r0_m), .r0_j(r0_j), .r0_pb(r0_pb), .tpos(tpos), .stx(stx), .sty(sty),
                .ok(keep_5));
        end else begin : g_no_stop
            assign keep_5 = '1;
            wire unused_stop = ^{stop_we, stop_addr, stop_data, tpos};
        end
    endgenerate

    // ==== the lanes, with the path weights between S3 and S4 ====
    wire [P*VOXEL_W-1:0] smp0;
    wire [P*ALPHA_W-1:0] a3, a3_w;
    wire [PA-1:0]        s5_back, back_sh, prevb_sh, acc_q;
    wire [P*CMP_W-1:0]   pix_d;
    wire [P*ZW-1:0]      pix_zd;
    wire [P-1:0]         live;           // S11: the ray holds more than the fresh word (BEATS)
    wire [P-1:0]         fin_t5, rep;    // S5: a ray ends by its countdown; S11: reports done (BEATS)
    wire [P-1:0]         rok11;          // S11: the lane's ray runs and its stop is not soon
    generate
        if (PLW != 0) begin : g_plw
            cube4_com_plw #(
                .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2),
                .VOXEL_W(VOXEL_W), .ALPHA_W(ALPHA_W)
            ) u_plw (
                .clk(clk), .cfg(cfg), .step(step), .first(first || BEATS != 0),   // (BEATS: ph_x, ph_y R0's own)
                .ph_x(ph_x), .ph_y(ph_y), .phn_x(phn_x), .phn_y(phn_y),
                .r0_m(r0_m), .r0_j(r0_j), .dxb(dxb), .dyb(dyb), .ipos(ipos),
                .f1_ipos(f1_ipos), .f1_j(f1_j), .f1_dxf(f1_dxf), .f1_dyf(f1_dyf),
                .f1_last(f1_last), .f1_wxn(f1_wxn), .f1_wyn(f1_wyn),
                .lut_we(lut_we), .lut_addr(lut_addr), .lut_data(lut_data),
                .smp(smp0), .mode_ext(mode_ext), .a3(a3), .a_w(a3_w));
        end else begin : g_no_plw
            assign a3_w = a3;
            wire unused_plw = ^{lut_we, lut_addr, lut_data, ph_x, ph_y, phn_x, phn_y,
                                f1_last, f1_wxn, f1_wyn, smp0};
        end
    endgenerate

    cube4_com_bpb #(
        .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2), .AC_W(AC_W),
        .SP_W(SP_W), .SB_DEPTH(SB_DEPTH), .RECTS(BYPOS), .COPIES(NQ)
    ) u_bpb (
        .clk(clk), .rst(rst), .cfg(cfg),
        .rd_sp(pos_sp), .pb_rd(pb_rd), .pb_wr(pb_wr), .v2(v_s[2]), .wr_en(v_s[NS]), .wr_sp(sp_wr),
        .acc_q(acc_q), .dyb4(dyb4), .dkb4(dkb4), .col1_4(col1_4),
        .s5_back(s5_back), .back_sh(back_sh), .prevb_sh(prevb_sh));

    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            cube4_com_lane #(
                .ALPHA_W(ALPHA_W), .ACC_W(ACC_W), .VOXEL_W(VOXEL_W),
                .COMPOSITING(COMPOSITING), .EXTREMUM(EXTREMUM), .AC_W(AC_W),
                .SAMPLE((EXTREMUM != 0 || PLW != 0) ? 1 : 0), .COPIES(NQ),
                .FALL((SLAB != 0 && COMPOSITING != 0) ? 1 : 0), .ZOUT(ZOUT), .ZM_W(M_W), .LIVE(BEATS),
                .TERM(BEATS), .LAG(LAG)
            ) u_lane (
                .clk(clk),
                .in_rgba(c_rgba[q*LUT_W +: LUT_W]), .in_sample(c_sample[q*VOXEL_W +: VOXEL_W]),
                .in_fall(c_fall[q*FALL_W +: FALL_W]),
                .smp0(smp0[q*VOXEL_W +: VOXEL_W]),
                .a3(a3[q*ALPHA_W +: ALPHA_W]), .a3_w(a3_w[q*ALPHA_W +: ALPHA_W]),
                .back5(s5_back[q*AC_W +: AC_W]), .back_sh(back_sh[q*AC_W +: AC_W]),
                .prevb_sh(prevb_sh[q*AC_W +: AC_W]),
                .dxb4(dxb4), .t0_4(t0_4[q]), .fresh_4(fresh_4[q]),
                .mode_xray(mode_xray), .mode_ext(mode_ext), .mode_min(mode_min),
                .cnt_6(cnt_6[q]), .cnt_7(cnt_7[q]),
                .depth_t(cfg_depth_t[CW-1:0]), .m11(m_o),
                .acc_q(acc_q[q*AC_W +: AC_W]), .pix(pix_d[q*CMP_W +: CMP_W]), .pix_z(pix_zd[q*ZW +: ZW]),
                .live(live[q]),
                .term_en(term_en), .term_tau(term_tau), .term_vmin(term_vmin), .term_vmax(term_vmax),
                .rok11(rok11[q]), .fin_t5(fin_t5[q]), .rep(rep[q]));
        end
    endgenerate

    // ==== the output FIFO: the S11 beat's fields beside its pixels ====
    localparam integer OUT_W = P * CMP_W + P + M_W + BX_W + P * BX_W + 1;
    localparam integer OZ_W  = (ZOUT != 0) ? P * ZW : 0;   // depth out beside the pixels
    // BEATS = 1: a finished ray leaves a pixel only when it holds something (a ray
    // that ran through samples that added nothing leaves the base plane's zero)
    wire [P-1:0] fin_q = (BEATS != 0) ? (fin_o & live) : fin_o;
    wire [OUT_W+OZ_W-1:0] fifo_out;
    wire unused_credit_d, unused_valid_cp;
    generate
        if (ZOUT != 0) begin : g_fifo_z
            cube4_credit_fifo #(.DATA_W(OUT_W + OZ_W), .DEPTH(FIFO_DEPTH)) u_fifo (
                .clk(clk), .rst(rst), .take(take), .give(give),
                .credit(credit), .credit_d(unused_credit_d),
                .push_d(push_d), .in_data({pix_zd, fin_q, m_o, by_o, bx_o, eop_o, pix_d}),
                .out_valid(pix_valid), .out_ready(pix_ready), .out_data(fifo_out),
                .out_valid_cp(unused_valid_cp));
            assign {pix_z, pix_mask, pix_m, pix_by, pix_bx, pix_eop, pix_rgba} = fifo_out;
        end else begin : g_fifo
            cube4_credit_fifo #(.DATA_W(OUT_W), .DEPTH(FIFO_DEPTH)) u_fifo (
                .clk(clk), .rst(rst), .take(take), .give(give),
                .credit(credit), .credit_d(unused_credit_d),
                .push_d(push_d), .in_data({fin_q, m_o, by_o, bx_o, eop_o, pix_d}),
                .out_valid(pix_valid), .out_ready(pix_ready), .out_data(fifo_out),
                .out_valid_cp(unused_valid_cp));
            assign {pix_mask, pix_m, pix_by, pix_bx, pix_eop, pix_rgba} = fifo_out;
            assign pix_z = '0;
            wire unused_zd = ^pix_zd;
        end
    endgenerate
endmodule
`default_nettype wire

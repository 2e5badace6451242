`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_seq
// -----------------------------------------------------------------------------
// Purpose
//   COM's sequencer (docs/architecture.md "COM"): takes a shaded beat when the
//   output FIFO has an entry for it (credit) and the read-after-write rule
//   allows (hazard, from cube4_com_walk or cube4_com_rect), registers its
//   header (R0), gives each lane its position along i, and carries the
//   beat's fields with a valid bit through S1 .. S10 to the FIFO's write at
//   S11 (the beat's finished-ray mask, slice, base-plane row and columns,
//   eop). The slice geometry (slot, fresh rays, whether the next sample is
//   inside, the steps) comes from cube4_com_walk (the template) or
//   cube4_com_rect (the rectangle table); from them, per lane:
//     finished = inside(m, j, i) && !inside(m+1, j+dyf, i+dxf)   (numerics.md 8)
//     bx = i - stepx(m) + SX,   by = j - stepy(m) + SY
//   It also registers the frame's mode (cfg is stable during a frame).
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2: as cube4_com (1..64, 2..2048, 4..12, 0..3).
//   SP_W    the slice-buffer slot's width (cube4_com).   1..22.  Default 13.
//   COMPOSITING, EXTREMUM: as cube4_com (the mode registers).  0..1.
//   T_R0    where the lanes' positions t are formed.  0..1.  Default 0.
//           0: at S0, from R0's skew (the input comes straight from SHA);
//           1: at R0, from in_hdr's skew, one register per lane (BEATS: the
//           input is a skid buffer's registers, and the lanes' run, fresh,
//           last and soon bits are picked by t at S0, so t must come from a
//           register beside them, not through lane_pos from R0's one skew).
//
// Latency
//   Stages R0, S1 .. S10 move on every cycle, each with a valid bit (v_s[k]:
//   S k); a beat entering R0 at an edge (take) is in S k k edges later; the
//   FIFO's fields (*_o) are S11 registers, push_d and give are S10's (the
//   push at S11, the entry returned at S10). in_ready = credit && !hazard.
//   R0's valid bit is in three kept copies (step, step_c): a plain register
//   would be merged into a copy that the counters or the template load under.
//
// Ports
//   in_valid, in_ready, in_hdr   the shaded stream's handshake and header
//   take      out  a beat enters R0 (cube4_com_rect's table read, the FIFO)
//   credit    in   the FIFO has an entry for one more beat
//   hazard    in   the read-after-write rule holds the next beat
//   step, step_c   R0 holds a beat (three copies)
//   r0_*, sop, first, dxb, dyb   R0's fields: slice m [M_W], row j [DIM_W],
//             partial beam pb [PB_W]; first: j = 0 and pb = 0
//   ipos      S0: i of each lane [IW] (pb * P + lane position)
//   tpos      S0: each lane's position t [LANE_W] (lane_pos)
//   f1_*      S1 registers: ipos, j [IW], the next sample's steps dxf, dyf
//   pos_sp, pos_pb   in   R0's slot and partial beam (walk / rect)
//   fresh     in   S0: the lane's ray starts (its previous sample is outside)
//   run0      in   S0: the lane's ray runs (the beat schedule's run bit at the
//             lane's position, ANDed with inside; all ones otherwise)
//   stx, sty  in   S0: stepx(m), stepy(m) [DIM_W]
//   nx_in     in   S1: the lane's next sample is inside
//   v_s       out  the valid bits of S1 .. S10
//   sp_fly    out  S1 .. S9's slots (S k at [(k-1)*SP_W +: SP_W])
//   sp_wr, pb_rd, pb_wr   S10's slot, S1's and S2's partial beam
//   dxb4, dyb4, dkb4, t0_4, fresh_4   S4's back steps (x, y, voxel slice
//             changed), lane at t = 0 and fresh ray per lane
//   keep_5    in   S5: the lane's sample may count (depth in, cube4_com_stop;
//             all ones without), ANDed into S6's counts
//   fin_5     in   S5: the lane's ray ends here (the beat schedule's countdown
//             after COM reported it done; zero otherwise), ANDed with inside
//   cnt_6, cnt_7   S6, S7: the lane's sample counts (inside, KEEP, keep_5)
//   mode_xray, mode_ext, mode_min   the mode, registered
//   push_d, give   S10: pushes at S11; returns its FIFO entry
//   fin_o, m_o, by_o, bx_o, eop_o   S11: finished-ray mask, slice, by, bx
//             per lane [DIM_W + 1], the frame's last beat
//
// Bit growth and rounding: positions in IW bits, bx and by in DIM_W + 1 bits
//   (0 .. SX + NI, no wrap: numerics.md 8); no rounding.
// =============================================================================
module cube4_com_seq #(
    `CUBE4_SLICE_PARAMS,
    parameter integer SP_W     = 13,
    parameter integer COMPOSITING = 1, parameter integer EXTREMUM = 1,
    parameter integer T_R0     = 0,
    localparam integer BX_W = DIM_W + 1,
    localparam integer NS   = 10                 // stages S1 .. S10
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    input  wire in_valid, output wire in_ready, input wire [HDR_W-1:0] in_hdr,
    output wire take, input wire credit, input wire hazard,
    output wire step, output wire [1:0] step_c,
    output wire [M_W-1:0] r0_m, output wire [DIM_W-1:0] r0_j, output wire [PB_W-1:0] r0_pb,
    output wire sop, output wire first, output wire dxb, output wire dyb,
    output wire [P*IW-1:0] ipos, output wire [P*LANE_W-1:0] tpos,
    output reg  [P*IW-1:0] f1_ipos, output reg [IW-1:0] f1_j, output reg f1_dxf, output reg f1_dyf,
    input  wire [SP_W-1:0] pos_sp, input wire [PB_W-1:0] pos_pb, input wire [P-1:0] fresh,
    input  wire [P-1:0] run0,
    input  wire [DIM_W-1:0] stx, input wire [DIM_W-1:0] sty, input wire [P-1:0] nx_in,
    output reg  [NS:1] v_s,
    output wire [(NS-1)*SP_W-1:0] sp_fly, output wire [SP_W-1:0] sp_wr,
    output wire [PB_W-1:0] pb_rd, output wire [PB_W-1:0] pb_wr,
    output wire dxb4, output wire dyb4, output wire dkb4, output wire [P-1:0] t0_4, output wire [P-1:0] fresh_4,
    input  wire [P-1:0] keep_5, input wire [P-1:0] fin_5,
    output wire [P-1:0] cnt_6, output wire [P-1:0] cnt_7,
    output reg  mode_xray, output reg mode_ext, output reg mode_min,
    output reg  push_d, output reg give,
    output reg  [P-1:0] fin_o, output reg [M_W-1:0] m_o, output reg [BX_W-1:0] by_o,
    output reg  [P*BX_W-1:0] bx_o, output reg eop_o
);
    `CUBE4_VIEW_FIELDS(cfg);
    `CUBE4_LANE_FUNCTIONS

    // ==== R0: the header (loads on every cycle; step marks a beat) ====
    assign in_ready = credit && !hazard;
    assign take     = in_valid && in_ready;
    reg [HDR_W-1:0] r0_hdr;
    reg             r0_first;            // j = 0 and pb = 0: the first beat of a slice
    always @(posedge clk) begin
        r0_first <= (in_hdr[HDR_J +: DIM_W] == '0) && (in_hdr[HDR_PB +: PB_W] == '0);
        r0_hdr   <= in_hdr;
    end
    cube4_prim_copies #(.N(3), .RESET(1)) u_step (
        .clk(clk), .rst(rst), .d(take), .q({step_c, step}));
    wire [P-1:0]      r0_lane_valid  = r0_hdr[HDR_LVALID +: P];
    wire [P-1:0]      r0_lane_inside = r0_hdr[HDR_INSIDE +: P];
    wire [P-1:0]      r0_lane_keep   = r0_hdr[HDR_KEEP +: P];
    wire [LANE_W-1:0] r0_skew        = r0_hdr[HDR_SKEW +: LANE_W];
    wire [6:0]        r0_ctrl        = r0_hdr[HDR_CTRL +: 7];
    assign r0_m  = r0_hdr[HDR_M +: M_W];
    assign r0_j  = r0_hdr[HDR_J +: DIM_W];
    assign r0_pb = r0_hdr[HDR_PB +: PB_W];
    assign sop   = r0_ctrl[CTRL_SOP];
    assign first = r0_first;
    assign dxb   = r0_ctrl[CTRL_OSX];
    assign dyb   = r0_ctrl[CTRL_OSY];
    wire eop = r0_ctrl[CTRL_EOP];
    wire dxf = r0_ctrl[CTRL_SX];
    wire dyf = r0_ctrl[CTRL_SY];
    wire unused_y_last = r0_ctrl[CTRL_YLAST];   // rows are checked against cfg_nj directly
    wire [M_W-1:0] ss_mask = M_W'((1 << cfg_ss_log2) - 1);
    wire           dk_b    = (r0_m & ss_mask) == '0;   // voxel slice changed from m-1

    // ==== S0, per lane: i, at t = 0, inside, counts ====
    wire [P-1:0]  t0_d, ins_d, cnt_d;
    wire [IW-1:0] pbp   = IW'(r0_pb) * IW'(P);
    wire [IW-1:0] j_ext = IW'(r0_j);
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_pos
            wire [LANE_W-1:0] t;
            if (T_R0 != 0) begin : g_t_r0
                reg [LANE_W-1:0] r0_t;       // R0: lane_pos of the header it registers
                always @(posedge clk) r0_t <= lane_pos(q, in_hdr[HDR_SKEW +: LANE_W], cfg_flip_i, cfg_i_r1);
                assign t = r0_t;
`ifndef SYNTHESIS
                always @(posedge clk) begin
                    if (!rst && step && (r0_t != lane_pos(q, r0_skew, cfg_flip_i, cfg_i_r1)))
                        $fatal(1, "cube4_com_seq: lane %0d's registered position differs from R0's skew", q);
                end
`endif
            end else begin : g_t_s0
                assign t = lane_pos(q, r0_skew, cfg_flip_i, cfg_i_r1);
            end
            assign t0_d[q]  = (t == '0);
            assign ins_d[q] = r0_lane_valid[q] && r0_lane_inside[q] && run0[q];
            assign cnt_d[q] = ins_d[q] && r0_lane_keep[q];   // the sample counts
            assign ipos[q*IW +: IW] = pbp + IW'(t);
            assign tpos[q*LANE_W +: LANE_W] = t;
        end
    endgenerate

    // ==== S1 -> S2: finished rays and base-plane x, y, from S1's registers ====
    reg [DIM_W-1:0] f1_stx, f1_sty;
    always @(posedge clk) begin
        f1_ipos <= ipos;
        f1_j    <= j_ext;
        f1_dxf  <= dxf;
        f1_dyf  <= dyf;
        f1_stx  <= stx;
        f1_sty  <= sty;
    end
    reg  [P-1:0]      ins_s1;            // inside (S1)
    reg  [P-1:0]      ins_s2, ins_s3, ins_s4, ins_s5;   // ... carried to S5 (fin_5)
    wire [P-1:0]      fin_1 = ins_s1 & ~nx_in;
    wire [P*BX_W-1:0] bx_1;
    wire [BX_W-1:0]   by_1 = BX_W'(f1_j) - BX_W'(f1_sty) + BX_W'(cfg_sy);   // by = j - stepy(m) + SY
    generate
        for (q = 0; q < P; q = q + 1) begin : g_bx
            assign bx_1[q*BX_W +: BX_W] = BX_W'(f1_ipos[q*IW +: IW]) - BX_W'(f1_stx) + BX_W'(cfg_sx);
        end
    endgenerate

    // ==== the beat's fields, carried along the pipeline (index = stage) ====
    // (unpacked arrays: a packed [stage][field] array of fields that are not word
    // aligned made Verilator's model about 20% slower at P = 8)
    reg [SP_W-1:0]    sp_s    [1:NS];    // slice slot: read at S1, written at the end of S11
    reg [PB_W-1:0]    pb_s    [1:2];     // partial beam: the beam buffer's read (S2), write (S3)
    reg [P-1:0]       cnt_s   [1:7];     // the sample counts (S6, S7)
    reg [P-1:0]       fin_s   [2:NS];    // from S2 on (computed from S1's registers)
    reg [M_W-1:0]     m_s     [1:NS];
    reg [BX_W-1:0]    by_s    [2:NS];
    reg [P*BX_W-1:0]  bx_s    [2:NS];
    reg [NS:1]        eop_s;
    reg [4:1]         dxb_s, dyb_s, dkb_s;
    reg [P-1:0]       fresh_s [1:4];
    reg [P-1:0]       t0_s    [1:4];
    integer k;
    always @(posedge clk) begin
        if (rst) v_s <= '0;
        else     v_s <= {v_s[NS-1:1], step};
    end
    always @(posedge clk) begin
        sp_s[1] <= pos_sp;   pb_s[1] <= pos_pb;  ins_s1 <= ins_d;  cnt_s[1] <= cnt_d;
        fin_s[2] <= fin_1;
        m_s[1]  <= r0_m;     by_s[2] <= by_1;    bx_s[2]  <= bx_1;   fresh_s[1] <= fresh;
        t0_s[1] <= t0_d;
        eop_s <= {eop_s[NS-1:1], eop};
        dxb_s <= {dxb_s[3:1], dxb};
        dyb_s <= {dyb_s[3:1], dyb};
        dkb_s <= {dkb_s[3:1], dk_b};
        for (k = 2; k <= NS; k = k + 1) begin
            sp_s[k] <= sp_s[k-1];  m_s[k] <= m_s[k-1];
        end
        for (k = 3; k <= NS; k = k + 1) begin
            fin_s[k] <= fin_s[k-1];  bx_s[k] <= bx_s[k-1];  by_s[k] <= by_s[k-1];
        end
        {ins_s5, ins_s4, ins_s3, ins_s2} <= {ins_s4, ins_s3, ins_s2, ins_s1};
        fin_s[6] <= fin_s[5] | (fin_5 & ins_s5);   // a ray that ends by its countdown (BEATS)
        pb_s[2] <= pb_s[1];
        for (k = 2; k <= 7; k = k + 1) cnt_s[k] <= cnt_s[k-1];
        cnt_s[6] <= cnt_s[5] & keep_5;       // depth in: in front of the geometry (all ones without)
        for (k = 2; k <= 4; k = k + 1) begin
            fresh_s[k] <= fresh_s[k-1];  t0_s[k] <= t0_s[k-1];
        end
    end
    generate
        for (q = 1; q < NS; q = q + 1) begin : g_fly
            assign sp_fly[(q-1)*SP_W +: SP_W] = sp_s[q];
        end
    endgenerate
    assign sp_wr   = sp_s[NS];
    assign pb_rd   = pb_s[1];
    assign pb_wr   = pb_s[2];
    assign dxb4    = dxb_s[4];
    assign dyb4    = dyb_s[4];
    assign dkb4    = dkb_s[4];
    assign t0_4    = t0_s[4];
    assign fresh_4 = fresh_s[4];
    assign cnt_6   = cnt_s[6];
    assign cnt_7   = cnt_s[7];

    // ==== the mode (cfg is stable during a frame), registered once ====
    always @(posedge clk) begin
        mode_xray <= (COMPOSITING != 0) && (cfg_mode == 2'd1);
        mode_ext  <= (EXTREMUM != 0) && ((COMPOSITING == 0) || cfg_mode[1]);
        mode_min  <= (cfg_mode == 2'd3);
    end

    // ==== the output FIFO's control: an S11 beat with a finished ray, or the
    // frame's last beat; an S10 beat that leaves nothing returns its entry ====
    wire out_d = v_s[NS-1] && ((fin_s[NS-1] != '0) || eop_s[NS-1]);   // S9: will push
    always @(posedge clk) begin
        if (rst) begin
            give   <= 1'b0;
            push_d <= 1'b0;
        end else begin
            give   <= v_s[NS-1] && !out_d;
            push_d <= out_d;
        end
    end
    always @(posedge clk) begin
        fin_o <= fin_s[NS];  m_o <= m_s[NS];  by_o <= by_s[NS];  bx_o <= bx_s[NS];  eop_o <= eop_s[NS];
    end
endmodule
`default_nettype wire

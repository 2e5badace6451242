`default_nettype none
// =============================================================================
// cube4_frontend
// -----------------------------------------------------------------------------
// Purpose
//   The Cube-4 front end: cube4_cfb (traversal, template, address, control)
//   issuing memory read beats, and cube4_tri turning the returned voxels into
//   tri-linear samples. The voxel memory sits outside (cube4_voxel_mem or any
//   memory with the same valid/ready request/response ports and a tag that is
//   returned unchanged, in order).
//
// Parameters
//   P            pipelines = memory banks.          1..64.   Default 8.
//   VOXEL_W      voxel width (Q0.VOXEL_W).           1..16.   Default 8.
//   WEIGHT_W     weight width W (Q0.W).              4..12.   Default 8.
//   MAX_DIM      largest volume dimension.           2..2048. Default 256.
//   ADDR_W       memory address width.               1..30.   Default 16.
//   MAX_SS_LOG2  log2 of the largest supersampling.  0..3.    Default 0.
//   TAG_W        width of mem_req_tag (derived; read it, do not set it).
//
// Latency
//   A frame: (M * NJ + 1) * NB + 1 request beats (M = (NK-1) * S + 1 passes,
//   NB = ceil(NI / P)), i.e. NI*NJ*NK/P cycles plus padding of the last
//   partial beam, one flush beam and the pipeline fill (22 cycles), when no
//   port stalls. done pulses the cycle the last sample beat is accepted;
//   cycles counts the clock cycles from start to that beat inclusive.
//
// Ports
//   start / busy / done / cycles   frame control (cycles: 32-bit count)
//   cfg_*                          view registers, see cube4_cfb
//   mem_req_* / mem_rsp_*          memory read port (see cube4_voxel_mem)
//   smp_*                          sample stream, see cube4_tri out_*
//
// Bit growth and rounding: see cube4_tri (one rounding per lerp).
// =============================================================================
module cube4_frontend #(
    parameter integer P           = 8,
    parameter integer VOXEL_W     = 8,
    parameter integer WEIGHT_W    = 8,
    parameter integer MAX_DIM     = 256,
    parameter integer ADDR_W      = 16,
    parameter integer MAX_SS_LOG2 = 0,
    parameter integer DIM_W  = $clog2(MAX_DIM + 1),
    parameter integer NB_W   = $clog2((MAX_DIM + P - 1) / P + 1),
    parameter integer PB_W   = ((MAX_DIM + P - 1) / P > 1) ? $clog2((MAX_DIM + P - 1) / P) : 1,
    parameter integer LANE_W = (P > 1) ? $clog2(P) : 1,
    parameter integer M_W    = $clog2((MAX_DIM - 1) * (1 << MAX_SS_LOG2) + 2),
    parameter integer SB_W   = $clog2(MAX_DIM * ((MAX_DIM + P - 1) / P)),
    parameter integer TAG_W  = 10 + SB_W + PB_W + 3 * WEIGHT_W + M_W + DIM_W + LANE_W + 5 + 3 * P
) (
    input  wire                  clk,
    input  wire                  rst,
    input  wire                  start,
    output wire                  busy,
    output wire                  done,
    output wire [31:0]           cycles,
    input  wire [DIM_W-1:0]      cfg_ni,
    input  wire [DIM_W-1:0]      cfg_nj,
    input  wire [DIM_W-1:0]      cfg_nk,
    input  wire [NB_W-1:0]       cfg_nb,
    input  wire                  cfg_flip_i,
    input  wire                  cfg_flip_j,
    input  wire                  cfg_flip_k,
    input  wire [1:0]            cfg_ss_log2,
    input  wire [WEIGHT_W:0]     cfg_view_x,
    input  wire [WEIGHT_W:0]     cfg_view_y,
    input  wire [LANE_W-1:0]     cfg_j_r0,
    input  wire [LANE_W-1:0]     cfg_k_r0,
    input  wire [LANE_W-1:0]     cfg_i_r1,
    input  wire [LANE_W-1:0]     cfg_i_rt,
    input  wire [ADDR_W-1:0]     cfg_j_a0,
    input  wire [ADDR_W-1:0]     cfg_j_lin,
    input  wire [ADDR_W-1:0]     cfg_j_blk,
    input  wire [ADDR_W-1:0]     cfg_k_a0,
    input  wire [ADDR_W-1:0]     cfg_k_lin,
    input  wire [ADDR_W-1:0]     cfg_k_blk,
    input  wire [ADDR_W-1:0]     cfg_i_a0,
    input  wire [ADDR_W-1:0]     cfg_i_pb,
    input  wire [ADDR_W-1:0]     cfg_i_lin,
    // memory read port
    output wire                  mem_req_valid,
    input  wire                  mem_req_ready,
    output wire [P*ADDR_W-1:0]   mem_req_addr,
    output wire [P-1:0]          mem_req_rden,
    output wire [TAG_W-1:0]      mem_req_tag,
    input  wire                  mem_rsp_valid,
    output wire                  mem_rsp_ready,
    input  wire [P*VOXEL_W-1:0]  mem_rsp_data,
    input  wire [TAG_W-1:0]      mem_rsp_tag,
    // sample stream
    output wire                  smp_valid,
    input  wire                  smp_ready,
    output wire [P*VOXEL_W-1:0]  smp_sample,
    output wire [P-1:0]          smp_lane_valid,
    output wire [P-1:0]          smp_lane_inside,
    output wire [M_W-1:0]        smp_m,
    output wire [DIM_W-1:0]      smp_j,
    output wire [PB_W-1:0]       smp_pb,
    output wire [LANE_W-1:0]     smp_skew,
    output wire [6:0]            smp_ctrl
);
    // ---- CFB ----
    wire                unused_cfb_busy;   // the frame ends at the last sample, not the last request
    wire                t_emit, t_sop, t_eop, t_drain, t_ywrap, t_bbwe, t_lmem, t_umem, t_uuse, t_k0odd;
    wire [SB_W-1:0]     t_sb;
    wire [PB_W-1:0]     t_pb;
    wire [WEIGHT_W-1:0] t_wx, t_wy, t_wz;
    wire [M_W-1:0]      t_m;
    wire [DIM_W-1:0]    t_j;
    wire [LANE_W-1:0]   t_skew;
    wire                t_ylast;
    wire [3:0]          t_steps;
    wire [P-1:0]        t_lval, t_lnbr, t_lwrap;

    wire                c_req_valid, c_req_ready;   // CFB's request, into u_req_skid
    wire [P*ADDR_W-1:0] c_req_addr;
    wire [P-1:0]        c_req_rden;
    cube4_cfb #(
        .P           (P),
        .MAX_DIM     (MAX_DIM),
        .ADDR_W      (ADDR_W),
        .WEIGHT_W    (WEIGHT_W),
        .MAX_SS_LOG2 (MAX_SS_LOG2)
    ) u_cfb (
        .clk            (clk),
        .rst            (rst),
        .start          (start && !busy),
        .busy           (unused_cfb_busy),
        .cfg_ni         (cfg_ni),
        .cfg_nj         (cfg_nj),
        .cfg_nk         (cfg_nk),
        .cfg_nb         (cfg_nb),
        .cfg_flip_i     (cfg_flip_i),
        .cfg_flip_j     (cfg_flip_j),
        .cfg_flip_k     (cfg_flip_k),
        .cfg_ss_log2    (cfg_ss_log2),
        .cfg_view_x     (cfg_view_x),
        .cfg_view_y     (cfg_view_y),
        .cfg_j_r0       (cfg_j_r0),
        .cfg_k_r0       (cfg_k_r0),
        .cfg_i_r1       (cfg_i_r1),
        .cfg_i_rt       (cfg_i_rt),
        .cfg_j_a0       (cfg_j_a0),
        .cfg_j_lin      (cfg_j_lin),
        .cfg_j_blk      (cfg_j_blk),
        .cfg_k_a0       (cfg_k_a0),
        .cfg_k_lin      (cfg_k_lin),
        .cfg_k_blk      (cfg_k_blk),
        .cfg_i_a0       (cfg_i_a0),
        .cfg_i_pb       (cfg_i_pb),
        .cfg_i_lin      (cfg_i_lin),
        .req_valid      (c_req_valid),
        .req_ready      (c_req_ready),
        .req_addr       (c_req_addr),
        .req_rden       (c_req_rden),
        .tag_emit       (t_emit),
        .tag_sop        (t_sop),
        .tag_eop        (t_eop),
        .tag_drain      (t_drain),
        .tag_ywrap      (t_ywrap),
        .tag_bb_we      (t_bbwe),
        .tag_lower_mem  (t_lmem),
        .tag_upper_mem  (t_umem),
        .tag_upper_use  (t_uuse),
        .tag_k0_odd     (t_k0odd),
        .tag_sb_addr    (t_sb),
        .tag_pb         (t_pb),
        .tag_wx         (t_wx),
        .tag_wy         (t_wy),
        .tag_wz         (t_wz),
        .tag_m          (t_m),
        .tag_j          (t_j),
        .tag_skew       (t_skew),
        .tag_y_last     (t_ylast),
        .tag_steps      (t_steps),
        .tag_lane_valid (t_lval),
        .tag_lane_nbr   (t_lnbr),
        .tag_lane_wrap  (t_lwrap)
    );

    // CFB's requests pass a skid buffer: CFB advances on the skid's registered
    // ready, so the memory's ready (and what feeds it) never reaches CFB's
    // traversal counters in the same cycle. One cycle of latency.
    wire [TAG_W-1:0] c_req_tag = {t_emit, t_sop, t_eop, t_drain, t_ywrap, t_bbwe, t_lmem, t_umem, t_uuse,
                                  t_k0odd, t_sb, t_pb, t_wx, t_wy, t_wz, t_m, t_j, t_skew, t_ylast,
                                  t_steps, t_lval, t_lnbr, t_lwrap};
    cube4_skid #(
        .DATA_W (P * ADDR_W + P + TAG_W)
    ) u_req_skid (
        .clk       (clk),
        .rst       (rst),
        .in_valid  (c_req_valid),
        .in_ready  (c_req_ready),
        .in_data   ({c_req_addr, c_req_rden, c_req_tag}),
        .out_valid (mem_req_valid),
        .out_ready (mem_req_ready),
        .out_data  ({mem_req_addr, mem_req_rden, mem_req_tag})
    );

    // ---- TRI ----
    wire                r_emit, r_sop, r_eop, r_drain, r_ywrap, r_bbwe, r_lmem, r_umem, r_uuse, r_k0odd;
    wire [SB_W-1:0]     r_sb;
    wire [PB_W-1:0]     r_pb;
    wire [WEIGHT_W-1:0] r_wx, r_wy, r_wz;
    wire [M_W-1:0]      r_m;
    wire [DIM_W-1:0]    r_j;
    wire [LANE_W-1:0]   r_skew;
    wire                r_ylast;
    wire [3:0]          r_steps;
    wire [P-1:0]        r_lval, r_lnbr, r_lwrap;

    assign {r_emit, r_sop, r_eop, r_drain, r_ywrap, r_bbwe, r_lmem, r_umem, r_uuse,
            r_k0odd, r_sb, r_pb, r_wx, r_wy, r_wz, r_m, r_j, r_skew, r_ylast,
            r_steps, r_lval, r_lnbr, r_lwrap} = mem_rsp_tag;
    // drain beats need no flag in TRI: they carry emit = 0 and only push the
    // beam-extension stage
    wire unused_drain = r_drain;

    cube4_tri #(
        .P           (P),
        .VOXEL_W     (VOXEL_W),
        .WEIGHT_W    (WEIGHT_W),
        .MAX_DIM     (MAX_DIM),
        .MAX_SS_LOG2 (MAX_SS_LOG2)
    ) u_tri (
        .clk             (clk),
        .rst             (rst),
        .cfg_flip_j      (cfg_flip_j),
        .cfg_flip_k      (cfg_flip_k),
        .cfg_flip_i      (cfg_flip_i),
        .in_valid        (mem_rsp_valid),
        .in_ready        (mem_rsp_ready),
        .in_data         (mem_rsp_data),
        .in_t_emit       (r_emit),
        .in_t_sop        (r_sop),
        .in_t_eop        (r_eop),
        .in_t_ywrap      (r_ywrap),
        .in_t_bb_we      (r_bbwe),
        .in_t_lower_mem  (r_lmem),
        .in_t_upper_mem  (r_umem),
        .in_t_upper_use  (r_uuse),
        .in_t_k0_odd     (r_k0odd),
        .in_t_sb_addr    (r_sb),
        .in_t_pb         (r_pb),
        .in_t_wx         (r_wx),
        .in_t_wy         (r_wy),
        .in_t_wz         (r_wz),
        .in_t_m          (r_m),
        .in_t_j          (r_j),
        .in_t_skew       (r_skew),
        .in_t_y_last     (r_ylast),
        .in_t_steps      (r_steps),
        .in_t_lane_valid (r_lval),
        .in_t_lane_nbr   (r_lnbr),
        .in_t_lane_wrap  (r_lwrap),
        .out_valid       (smp_valid),
        .out_ready       (smp_ready),
        .out_sample      (smp_sample),
        .out_lane_valid  (smp_lane_valid),
        .out_lane_inside (smp_lane_inside),
        .out_m           (smp_m),
        .out_j           (smp_j),
        .out_pb          (smp_pb),
        .out_skew        (smp_skew),
        .out_ctrl        (smp_ctrl)
    );

    // ---- frame control: busy from start until the last sample beat ----
    reg        busy_q;
    reg [31:0] cycles_q;
    wire       last_beat = smp_valid && smp_ready && smp_ctrl[5];   // eop
    always @(posedge clk) begin
        if (rst) begin
            busy_q   <= 1'b0;
            cycles_q <= 32'd0;
        end else if (!busy_q) begin
            if (start) begin
                busy_q   <= 1'b1;
                cycles_q <= 32'd1;
            end
        end else begin
            cycles_q <= cycles_q + 32'd1;
            if (last_beat) busy_q <= 1'b0;
        end
    end
    // busy also covers the cycle of start, before busy_q rises
    assign busy   = busy_q;
    assign done   = busy_q && last_beat;
    assign cycles = cycles_q;

endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_top_harness  (simulation only)
// -----------------------------------------------------------------------------
// Purpose
//   Drives cube4_top for tests and for `cube4 render --engine rtl`: a Verilog
//   clock; loaders that read $readmemh images (volume: line a*P + q = bank q,
//   word a; LUT: one {R,G,B,A} word per line; reflectance map: one {D,P} word
//   per line) and stream them through the top's load ports; random holds on
//   every internal stream (dbg_hold) and random ready on the pixel port, from
//   LFSRs seeded at reset from the `seed` port (the test's COCOTB_RANDOM_SEED);
//   and a binary dump of every pixel beat (cube4_sim.dump reads it).
//   Python only sets registers and pulses load_* / start.
//
//   Pixel dump: records of REC_WORDS 32-bit little-endian words ($fwrite "%u"):
//     word 0              header {8'hC4, kind, frame}: kind 1 = frame start,
//                         2 = pixel beat, 3 = the frame's last beat (eop);
//                         frame = number of start records before this frame's
//                         own, mod 2^16 (not reset)
//     word 1, 2           m, by
//     words 3 ..          mask, MASK_WORDS words (lane q: bit q % 32 of word q / 32)
//     next P words        bx of lane q
//     next 4P words       R, G, B, A of lane q at 4q .. 4q + 3
//     next 2P words       depth out of lane q at 2q, 2q + 1: passed, first,
//                         each m + 1 when valid, 0 when not (0 without ZOUT)
//   A start record is zero after its header. The file is flushed after each
//   last beat and after any beat outside a frame, so stray beats are seen.
//
//   The stop table (ZIN = 1; golden/cube4/memory.py stop_table: one word of
//   all P banks per line) is loaded with the tables, one line a clock; with
//   BEATS = 1 the same file holds the ray table's stops, and the block table
//   (sim/cube4_sim/beat_frames.py block_words: one word per line, address
//   {kb, jb}) comes from CUBE4_BLKFILE alike.
//
//   DRAM = 1: the voxel memory is the generated DRAM core (cube4_litedram, from
//   cube4_sim.dram_core: LiteDRAM's controller and memory model) behind the
//   top's cube4_dram_fetch, on its own clock (DRAM_HALF_PS); the pipelines' clock
//   is CLK_HALF_PS. The DRAM's resets are a power-on reset only (rst, which tests
//   raise in mid-frame, never resets it). The loader waits for ld_ready.
//   dram_reads / dram_writes count the bursts, dram_stat_* the controller's
//   commands (activate, precharge, refresh, read, write), all since power-on.
//
//   Plusargs: +CUBE4_MEMFILE= +CUBE4_LUTFILE= +CUBE4_RMAPFILE= +CUBE4_RECTFILE=
//   +CUBE4_STOPFILE= +CUBE4_GMFILE= +CUBE4_DUMP=
//
// Parameters: as cube4_top; CLK_HALF_PS, DRAM_HALF_PS the two clocks' half
// periods in picoseconds.
// =============================================================================
module cube4_top_harness #(
    parameter integer P           = 8,
    parameter integer VOXEL_W     = 8,
    parameter integer WEIGHT_W    = 8,
    parameter integer ALPHA_W     = 12,
    parameter integer ACC_W       = 16,
    parameter integer RMAP_BITS   = 5,
    parameter integer MAX_DIM     = 64,
    parameter integer MAX_SS_LOG2 = 0,
    parameter integer DEPTH       = 4096,
    parameter integer ADDR_W      = 12,
    parameter integer SHADING     = 1,
    parameter integer COMPOSITING = 1,
    parameter integer EXTREMUM    = 1,
    parameter integer CLIP        = 1,
    parameter integer VGRAD       = 0,
    parameter integer PLW         = 1,
    parameter integer RECTS       = 0,    // 1: slice rectangles (the table from CUBE4_RECTFILE)
    parameter integer SLAB        = 0,    // 1: the cut slab (CUT_T, FALL_*)
    parameter integer ZOUT        = 0,    // 1: depth out (DEPTH_T, pix_z)
    parameter integer ZIN         = 0,    // 1: depth in (the stop table from CUBE4_STOPFILE)
    parameter integer GMOD        = 0,    // 1: gradient-magnitude modulation (its table from CUBE4_GMFILE)
    parameter integer LABELS      = 0,    // 1: label volumes (labelled words; a LUT block per label)
    parameter integer BEATS       = 0,    // 1: the beat schedule (the block table from CUBE4_BLKFILE, the stops from CUBE4_STOPFILE)
    parameter integer DRAM        = 0,    // 1: the voxel memory in the generated DRAM (cube4_litedram)
    parameter integer DRAM_AW     = 21,   // its port's address width
    parameter integer CLK_HALF_PS = 5000, // the pipelines' clock: half period in ps (default 100 MHz)
    parameter integer DRAM_HALF_PS = 6667, // the DRAM controller's clock (75 MHz: the ECP5 PHY's 1:2)
    `CUBE4_GEOMETRY,
    `CUBE4_VIEW_LAYOUT,
    `CUBE4_WORD_LAYOUT,
    `CUBE4_RECT_LAYOUT,
    `CUBE4_STOP_LAYOUT,
    `CUBE4_GM_LAYOUT,
    localparam integer BLOCK_LOG2 = 2,
    `CUBE4_BLOCK_LAYOUT,
    localparam integer RI_W = 2 * RMAP_BITS + 3
) (
    `CUBE4_VIEW_PORTS
    `CUBE4_ADDR_PORTS
    output wire                  clk,
    input  wire                  rst,
    input  wire                  load_mem,     // pulse: stream the volume image in
    input  wire                  load_tables,  // pulse: stream LUT and reflectance map in
    input  wire [31:0]           load_words,   // volume words per bank
    output wire                  load_done,    // level: the last load finished
    input  wire [31:0]           seed,         // the stall patterns' seed, taken at reset
    input  wire [7:0]            stall,        // hold probability /256, every internal stream
    input  wire [7:0]            stall_out,    // pixel-port not-ready probability /256
    input  wire                  dump_en,
    input  wire                  start,
    output wire                  busy,
    output wire                  done,
    output wire [31:0]           cycles,
    output wire [31:0]           beats_run,    // BEATS = 1: the frame's running sample beats into COM
    output wire [31:0]           dram_reads,   // bursts read from the DRAM since power-on (DRAM = 1)
    output wire [31:0]           dram_writes,  // bursts written
    // the commands the DRAM controller sent (cube4_sim.dram_core STAT_NAMES), since power-on
    output wire [31:0]           dram_stat_act,
    output wire [31:0]           dram_stat_pre,
    output wire [31:0]           dram_stat_ref,
    output wire [31:0]           dram_stat_rd,
    output wire [31:0]           dram_stat_wr
);
    cube4_sim_clock #(.HALF_PS(CLK_HALF_PS)) u_clock (.clk(clk));

    // ------------------------------------------------------------ input registers
    // Every input Python drives is registered once here, so that no logic of the
    // design depends combinationally on a top-level input. Verilator evaluates
    // input-dependent logic on every eval() (twice per clock with the Verilog
    // clock); registered, the datapath is evaluated once per clock. Python sees a
    // one-cycle delay on every input, which it never depends on.
    reg                  rst_q, load_mem_q, load_tables_q, dump_en_q, start_q;
    reg [31:0]           load_words_q;
    reg [7:0]            stall_q, stall_out_q;
    reg [31:0]           seed_q;
    reg [DIM_W-1:0]      cfg_ni_q, cfg_nj_q, cfg_nk_q, cfg_sx_q, cfg_sy_q;
    reg [NB_W-1:0]       cfg_nb_q;
    reg                  cfg_flip_i_q, cfg_flip_j_q, cfg_flip_k_q;
    reg [1:0]            cfg_ss_log2_q;
    reg [WEIGHT_W:0]     cfg_view_x_q, cfg_view_y_q;
    reg [LANE_W-1:0]     cfg_j_r0_q, cfg_k_r0_q, cfg_i_r1_q, cfg_i_rt_q;
    reg [ADDR_W-1:0]     cfg_j_a0_q, cfg_j_lin_q, cfg_j_blk_q, cfg_k_a0_q, cfg_k_lin_q, cfg_k_blk_q;
    reg [ADDR_W-1:0]     cfg_i_a0_q, cfg_i_pb_q, cfg_i_lin_q;
    reg [1:0]            cfg_mode_q;
    reg [PHASE_W-1:0]    cfg_ph0_x_q, cfg_ph0_y_q;
    reg [DIM_W-1:0]      cfg_win_i0_q, cfg_win_i1_q, cfg_win_j0_q, cfg_win_j1_q;
    reg [M_W-1:0]        cfg_win_m0_q, cfg_win_m1_q;
    reg [DIM_W-1:0]      cfg_cr_i0_q, cfg_cr_i1_q, cfg_cr_j0_q, cfg_cr_j1_q;
    reg [M_W-1:0]        cfg_cr_m0_q, cfg_cr_m1_q;
    reg [26:0]           cfg_cr_hide_q;
    reg [CUT_W-1:0]      cfg_cut_a_q, cfg_cut_b_q, cfg_cut_c_q;
    reg [CUT_E_W-1:0]    cfg_cut_d_q;
    reg [CUT_E_W-1:0]    cfg_cut_t_q;
    reg [5:0]            cfg_fall_sh_q;
    reg                  cfg_fall_on_q;
    reg [24:0]           cfg_depth_t_q;
    reg [5:0]            cfg_faces_q;
    reg [DIM_W-1:0]      cfg_bb_i_q, cfg_bb_j_q, cfg_bb_k_q;
    reg                  cfg_nbr_q, cfg_term_q;
    reg [24:0]           cfg_tau_q;
    reg [15:0]           cfg_vmin_q, cfg_vmax_q;
    always @(posedge clk) begin
        rst_q         <= rst;
        load_mem_q    <= load_mem;
        load_tables_q <= load_tables;
        load_words_q  <= load_words;
        dump_en_q     <= dump_en;
        start_q       <= start;
        seed_q        <= seed;
        stall_q       <= stall;
        stall_out_q   <= stall_out;
        cfg_ni_q      <= cfg_ni;
        cfg_nj_q      <= cfg_nj;
        cfg_nk_q      <= cfg_nk;
        cfg_nb_q      <= cfg_nb;
        cfg_flip_i_q  <= cfg_flip_i;
        cfg_flip_j_q  <= cfg_flip_j;
        cfg_flip_k_q  <= cfg_flip_k;
        cfg_ss_log2_q <= cfg_ss_log2;
        cfg_view_x_q  <= cfg_view_x;
        cfg_view_y_q  <= cfg_view_y;
        cfg_j_r0_q    <= cfg_j_r0;
        cfg_k_r0_q    <= cfg_k_r0;
        cfg_i_r1_q    <= cfg_i_r1;
        cfg_i_rt_q    <= cfg_i_rt;
        cfg_j_a0_q    <= cfg_j_a0;
        cfg_j_lin_q   <= cfg_j_lin;
        cfg_j_blk_q   <= cfg_j_blk;
        cfg_k_a0_q    <= cfg_k_a0;
        cfg_k_lin_q   <= cfg_k_lin;
        cfg_k_blk_q   <= cfg_k_blk;
        cfg_i_a0_q    <= cfg_i_a0;
        cfg_i_pb_q    <= cfg_i_pb;
        cfg_i_lin_q   <= cfg_i_lin;
        cfg_sx_q      <= cfg_sx;
        cfg_sy_q      <= cfg_sy;
        cfg_mode_q      <= cfg_mode;
        cfg_ph0_x_q     <= cfg_ph0_x;
        cfg_ph0_y_q     <= cfg_ph0_y;
        cfg_win_i0_q    <= cfg_win_i0;
        cfg_win_i1_q    <= cfg_win_i1;
        cfg_win_j0_q    <= cfg_win_j0;
        cfg_win_j1_q    <= cfg_win_j1;
        cfg_win_m0_q    <= cfg_win_m0;
        cfg_win_m1_q    <= cfg_win_m1;
        cfg_cr_i0_q     <= cfg_cr_i0;
        cfg_cr_i1_q     <= cfg_cr_i1;
        cfg_cr_j0_q     <= cfg_cr_j0;
        cfg_cr_j1_q     <= cfg_cr_j1;
        cfg_cr_m0_q     <= cfg_cr_m0;
        cfg_cr_m1_q     <= cfg_cr_m1;
        cfg_cr_hide_q   <= cfg_cr_hide;
        cfg_cut_a_q     <= cfg_cut_a;
        cfg_cut_b_q     <= cfg_cut_b;
        cfg_cut_c_q     <= cfg_cut_c;
        cfg_cut_d_q     <= cfg_cut_d;
        cfg_cut_t_q     <= cfg_cut_t;
        cfg_fall_sh_q   <= cfg_fall_sh;
        cfg_fall_on_q   <= cfg_fall_on;
        cfg_depth_t_q   <= cfg_depth_t;
        cfg_faces_q     <= cfg_faces;
        cfg_bb_i_q      <= cfg_bb_i;
        cfg_bb_j_q      <= cfg_bb_j;
        cfg_bb_k_q      <= cfg_bb_k;
        cfg_nbr_q       <= cfg_nbr;
        cfg_term_q      <= cfg_term;
        cfg_tau_q       <= cfg_tau;
        cfg_vmin_q      <= cfg_vmin;
        cfg_vmax_q      <= cfg_vmax;
    end

    localparam integer PW     = P * WORD_W;
    localparam integer LUT_W  = 24 + ALPHA_W + PLW * 4 * ALPHA_W;   // with the path-weight columns
    localparam integer RMAP_N = 6 * (1 << (2 * RMAP_BITS)) + 1;
    localparam integer BX_W   = DIM_W + 1;

    // ------------------------------------------------------------ loaders
    reg [WORD_W-1:0]  img  [0:P*DEPTH-1];
    localparam integer LUT_N = 1 << SMP_W;  // 2^VOXEL_W entries, a block per label with LABELS
    reg [LUT_W-1:0]   luti [0:LUT_N-1];
    reg [19:0]        rmi  [0:RMAP_N-1];
    reg [RECT_W-1:0]  rti  [0:MAX_DIM-1];   // the rectangle table (RECTS = 1)
    localparam integer STOP_IW = (ZIN != 0 || BEATS != 0) ? STOP_AW : 1;
    localparam integer BK_N    = (BEATS != 0) ? (1 << (2 * BK_W)) : 2;
    reg [NBK-1:0]     bki  [0:BK_N-1];      // the block table (BEATS = 1)
    localparam integer STOP_N  = 1 << STOP_IW;
    reg [P*M_W-1:0]   sti  [0:STOP_N-1];    // the stop table (ZIN = 1; the ray table's stops with BEATS)
    reg [2*GMF_W-1:0] gmi  [0:GM_N-1];      // the modulation table (GMOD = 1)
    string memfile, lutfile, rmapfile, rectfile, stopfile, gmfile, blkfile, dumpfile;
    integer dump_fd, b;
    initial begin
        if (!$value$plusargs("CUBE4_MEMFILE=%s", memfile))   memfile  = "cube4_mem.hex";
        if (!$value$plusargs("CUBE4_LUTFILE=%s", lutfile))   lutfile  = "cube4_lut.hex";
        if (!$value$plusargs("CUBE4_RMAPFILE=%s", rmapfile)) rmapfile = "cube4_rmap.hex";
        if (!$value$plusargs("CUBE4_RECTFILE=%s", rectfile)) rectfile = "cube4_rects.hex";
        if (!$value$plusargs("CUBE4_STOPFILE=%s", stopfile)) stopfile = "cube4_stop.hex";
        if (!$value$plusargs("CUBE4_GMFILE=%s", gmfile))     gmfile   = "cube4_gm.hex";
        if (!$value$plusargs("CUBE4_BLKFILE=%s", blkfile))   blkfile  = "cube4_blk.hex";
        if (!$value$plusargs("CUBE4_DUMP=%s", dumpfile))     dumpfile = "cube4_pixels.bin";
        dump_fd = $fopen(dumpfile, "wb");
    end

    reg        mem_busy_q, tab_busy_q, done_q;
    reg [31:0] la_q;
    reg [PW-1:0] ld_data;
    always @(posedge clk) begin
        if (rst_q) begin
            mem_busy_q <= 1'b0;
            tab_busy_q <= 1'b0;
            done_q     <= 1'b0;
        end else if (load_mem_q && !mem_busy_q && !tab_busy_q) begin
            $readmemh(memfile, img);
            mem_busy_q <= 1'b1;
            done_q     <= 1'b0;
            la_q       <= 32'd0;
        end else if (load_tables_q && !mem_busy_q && !tab_busy_q) begin
            $readmemh(lutfile, luti);
            $readmemh(rmapfile, rmi);
            if (RECTS != 0) $readmemh(rectfile, rti);
            if (ZIN != 0 || BEATS != 0) $readmemh(stopfile, sti);
            if (BEATS != 0) $readmemh(blkfile, bki);
            if (GMOD != 0) $readmemh(gmfile, gmi);
            tab_busy_q <= 1'b1;
            done_q     <= 1'b0;
            la_q       <= 32'd0;
        end else if (mem_busy_q) begin
            if (!ld_ready) begin
                // the DRAM's load port takes a column when it can
            end else if (la_q + 32'd1 >= load_words_q) begin
                mem_busy_q <= 1'b0;
                done_q     <= 1'b1;
            end
            if (ld_ready) la_q <= la_q + 32'd1;
        end else if (tab_busy_q) begin
            if (la_q + 32'd1 >= RMAP_N && la_q + 32'd1 >= LUT_N
                && (RECTS == 0 || la_q + 32'd1 >= MAX_DIM) && ((ZIN == 0 && BEATS == 0) || la_q + 32'd1 >= STOP_N) && (GMOD == 0 || la_q + 32'd1 >= GM_N)
                && (BEATS == 0 || la_q + 32'd1 >= BK_N)) begin
                tab_busy_q <= 1'b0;
                done_q     <= 1'b1;
            end
            la_q <= la_q + 32'd1;
        end
    end
    always @(*) begin
        for (b = 0; b < P; b = b + 1) ld_data[b*WORD_W +: WORD_W] = img[la_q * P + b];
    end
    assign load_done = done_q;
    wire lut_we  = tab_busy_q && (la_q < LUT_N);
    wire rmap_we = tab_busy_q && (la_q < RMAP_N);
    wire rect_we = (RECTS != 0) && tab_busy_q && (la_q < MAX_DIM);
    wire stop_we = (ZIN != 0 || BEATS != 0) && tab_busy_q && (la_q < STOP_N);
    wire blk_we  = (BEATS != 0) && tab_busy_q && (la_q < BK_N);
    wire gm_we   = (GMOD != 0) && tab_busy_q && (la_q < GM_N);   // STOP_N: 2 without ZIN (unused)

    // ------------------------------------------------------------ random holds
    // LFSR s starts from the seed and its index (never from zero)
    function automatic [15:0] lfsr_init(input [31:0] sd, input integer idx);
        reg [15:0] x;
        begin
            x = sd[15:0] ^ sd[31:16] ^ 16'hACE1 ^ (16'h9E37 * 16'(idx + 1));
            lfsr_init = (x == 16'd0) ? 16'hACE1 : x;
        end
    endfunction
    reg [15:0] lfsr_q [0:5];
    integer    s;
    always @(posedge clk) begin
        for (s = 0; s < 6; s = s + 1) begin
            if (rst_q) lfsr_q[s] <= lfsr_init(seed_q, s);
            else     lfsr_q[s] <= {lfsr_q[s][14:0], lfsr_q[s][15] ^ lfsr_q[s][13] ^ lfsr_q[s][12] ^ lfsr_q[s][10]};
        end
    end
    wire [4:0] hold;
    genvar h;
    generate
        for (h = 0; h < 5; h = h + 1) begin : g_hold
            assign hold[h] = (lfsr_q[h][7:0] < stall_q);
        end
    endgenerate
    wire pix_ready = (lfsr_q[5][7:0] >= stall_out_q);

    // ------------------------------------------------------------ DRAM
    // DRAM = 1: the voxel memory is the generated LiteDRAM controller and memory
    // model (cube4_sim.dram_core) on its own clock. Its resets (and the fetch
    // unit's dram_rst) are a power-on reset only: rst, which tests raise in
    // mid-frame, resets the pipelines, never the DRAM.
    wire                 dram_cmd_valid, dram_cmd_we, dram_wdata_valid, dram_rdata_ready;
    wire                 dram_cmd_ready, dram_wdata_ready, dram_rdata_valid;
    wire [DRAM_AW-1:0]   dram_cmd_addr;
    wire [127:0]         dram_wdata_data, dram_rdata_data;
    wire [15:0]          dram_wdata_we;
    // the port's side leaves reset after the controller's (16 of its cycles against 64
    // of the pipelines' clock, at most twice as fast): nothing enters the port's clock
    // crossing while the controller's side of it is still in reset
    reg  [3:0]           por_sys_q;
    reg  [5:0]           por_user_q;
    wire                 dram_por_sys  = (por_sys_q != 4'hF);
    wire                 dram_por_user = (por_user_q != 6'h3F);
    reg  [31:0]          dram_rd_q, dram_wr_q;
    initial begin
        por_sys_q  = 4'd0;
        por_user_q = 6'd0;
        dram_rd_q  = 32'd0;
        dram_wr_q  = 32'd0;
    end
    generate
        if (DRAM != 0) begin : g_dram
            wire sys_clk;
            cube4_sim_clock #(.HALF_PS(DRAM_HALF_PS)) u_sys_clock (.clk(sys_clk));
            always @(posedge sys_clk) if (dram_por_sys) por_sys_q <= por_sys_q + 4'd1;
            cube4_litedram u_dram (
                .sys_clk          (sys_clk),
                .sys_rst          (dram_por_sys),
                .user_clk         (clk),
                .user_rst         (dram_por_user),
                .user_cmd_valid   (dram_cmd_valid),
                .user_cmd_ready   (dram_cmd_ready),
                .user_cmd_we      (dram_cmd_we),
                .user_cmd_addr    (dram_cmd_addr),
                .user_wdata_valid (dram_wdata_valid),
                .user_wdata_ready (dram_wdata_ready),
                .user_wdata_we    (dram_wdata_we),
                .user_wdata_data  (dram_wdata_data),
                .user_rdata_valid (dram_rdata_valid),
                .user_rdata_ready (dram_rdata_ready),
                .user_rdata_data  (dram_rdata_data),
                .stat_act         (dram_stat_act),
                .stat_pre         (dram_stat_pre),
                .stat_ref         (dram_stat_ref),
                .stat_rd          (dram_stat_rd),
                .stat_wr          (dram_stat_wr)
            );
        end else begin : g_no_dram
            wire unused_dram = &{1'b0, dram_por_sys, dram_cmd_addr, dram_wdata_valid, dram_wdata_data,
                                 dram_wdata_we, dram_rdata_ready};
            assign dram_stat_act = 32'd0;
            assign dram_stat_pre = 32'd0;
            assign dram_stat_ref = 32'd0;
            assign dram_stat_rd  = 32'd0;
            assign dram_stat_wr  = 32'd0;
            assign dram_cmd_ready   = 1'b0;
            assign dram_wdata_ready = 1'b0;
            assign dram_rdata_valid = 1'b0;
            assign dram_rdata_data  = 128'd0;
        end
    endgenerate
    always @(posedge clk) begin
        if (dram_por_user) por_user_q <= por_user_q + 6'd1;
        if (dram_cmd_valid && dram_cmd_ready && !dram_cmd_we) dram_rd_q <= dram_rd_q + 32'd1;
        if (dram_cmd_valid && dram_cmd_ready && dram_cmd_we)  dram_wr_q <= dram_wr_q + 32'd1;
    end
    assign dram_reads  = dram_rd_q;
    assign dram_writes = dram_wr_q;

    // ------------------------------------------------------------ DUT
    wire                      ld_ready;
    wire                      pix_valid, pix_eop;
    wire [P-1:0]              pix_mask;
    wire [M_W-1:0]            pix_m;
    wire [BX_W-1:0]           pix_by;
    wire [P*BX_W-1:0]         pix_bx;
    wire [P*4*(ACC_W+1)-1:0]  pix_rgba;
    wire [P*2*(M_W+1)-1:0]    pix_z;

    cube4_top #(
        .P           (P),
        .VOXEL_W     (VOXEL_W),
        .WEIGHT_W    (WEIGHT_W),
        .ALPHA_W     (ALPHA_W),
        .ACC_W       (ACC_W),
        .RMAP_BITS   (RMAP_BITS),
        .MAX_DIM     (MAX_DIM),
        .MAX_SS_LOG2 (MAX_SS_LOG2),
        .DEPTH       (DEPTH),
        .ADDR_W      (ADDR_W),
        .SHADING     (SHADING),
        .COMPOSITING (COMPOSITING),
        .EXTREMUM    (EXTREMUM),
        .CLIP        (CLIP),
        .VGRAD       (VGRAD),
        .PLW         (PLW),
        .RECTS       (RECTS),
        .SLAB        (SLAB),
        .ZOUT        (ZOUT),
        .ZIN         (ZIN),
        .GMOD        (GMOD),
        .LABELS      (LABELS),
        .BEATS       (BEATS),
        .DRAM        (DRAM),
        .DRAM_AW     (DRAM_AW)
    ) u_top (
        .clk         (clk),
        .rst         (rst_q),
        .ld_valid    (mem_busy_q),
        .ld_ready    (ld_ready),
        .ld_addr     (la_q[ADDR_W-1:0]),
        .ld_data     (ld_data),
        .dram_rst         (dram_por_user),
        `CUBE4_DRAM_CONNECT,
        .lut_we      (lut_we),
        .lut_addr    (la_q[SMP_W-1:0]),
        .lut_data    (luti[la_q[SMP_W-1:0]]),
        .rmap_we     (rmap_we),
        .rmap_addr   (la_q[RI_W-1:0]),
        .rmap_data   (rmi[la_q[RI_W-1:0]]),
        .rect_we     (rect_we),
        .rect_addr   (M_W'(la_q)),
        .rect_data   (rti[la_q[$clog2(MAX_DIM)-1:0]]),
        .gm_we       (gm_we),
        .gm_addr     (la_q[GMA_W-1:0]),
        .gm_data     (gmi[la_q[GMA_W-1:0]]),
        .blk_we      (blk_we),
        .blk_addr    (la_q[2*BK_W-1:0]),
        .blk_data    (bki[la_q[$clog2(BK_N)-1:0]]),
        .stop_we     (stop_we),
        .stop_addr   (la_q[STOP_AW-1:0]),
        .stop_data   (sti[la_q[STOP_IW-1:0]]),
        .cfg_ni      (cfg_ni_q),
        .cfg_nj      (cfg_nj_q),
        .cfg_nk      (cfg_nk_q),
        .cfg_nb      (cfg_nb_q),
        .cfg_flip_i  (cfg_flip_i_q),
        .cfg_flip_j  (cfg_flip_j_q),
        .cfg_flip_k  (cfg_flip_k_q),
        .cfg_ss_log2 (cfg_ss_log2_q),
        .cfg_view_x  (cfg_view_x_q),
        .cfg_view_y  (cfg_view_y_q),
        .cfg_j_r0    (cfg_j_r0_q),
        .cfg_k_r0    (cfg_k_r0_q),
        .cfg_i_r1    (cfg_i_r1_q),
        .cfg_i_rt    (cfg_i_rt_q),
        .cfg_j_a0    (cfg_j_a0_q),
        .cfg_j_lin   (cfg_j_lin_q),
        .cfg_j_blk   (cfg_j_blk_q),
        .cfg_k_a0    (cfg_k_a0_q),
        .cfg_k_lin   (cfg_k_lin_q),
        .cfg_k_blk   (cfg_k_blk_q),
        .cfg_i_a0    (cfg_i_a0_q),
        .cfg_i_pb    (cfg_i_pb_q),
        .cfg_i_lin   (cfg_i_lin_q),
        .cfg_sx      (cfg_sx_q),
        .cfg_sy      (cfg_sy_q),
        .cfg_mode     (cfg_mode_q),
        .cfg_ph0_x    (cfg_ph0_x_q),
        .cfg_ph0_y    (cfg_ph0_y_q),
        .cfg_win_i0   (cfg_win_i0_q),
        .cfg_win_i1   (cfg_win_i1_q),
        .cfg_win_j0   (cfg_win_j0_q),
        .cfg_win_j1   (cfg_win_j1_q),
        .cfg_win_m0   (cfg_win_m0_q),
        .cfg_win_m1   (cfg_win_m1_q),
        .cfg_cr_i0    (cfg_cr_i0_q),
        .cfg_cr_i1    (cfg_cr_i1_q),
        .cfg_cr_j0    (cfg_cr_j0_q),
        .cfg_cr_j1    (cfg_cr_j1_q),
        .cfg_cr_m0    (cfg_cr_m0_q),
        .cfg_cr_m1    (cfg_cr_m1_q),
        .cfg_cr_hide  (cfg_cr_hide_q),
        .cfg_cut_a    (cfg_cut_a_q),
        .cfg_cut_b    (cfg_cut_b_q),
        .cfg_cut_c    (cfg_cut_c_q),
        .cfg_cut_d    (cfg_cut_d_q),
        .cfg_cut_t    (cfg_cut_t_q),
        .cfg_fall_sh  (cfg_fall_sh_q),
        .cfg_fall_on  (cfg_fall_on_q),
        .cfg_depth_t  (cfg_depth_t_q),
        .cfg_faces    (cfg_faces_q),
        .cfg_bb_i     (cfg_bb_i_q),
        .cfg_bb_j     (cfg_bb_j_q),
        .cfg_bb_k     (cfg_bb_k_q),
        .cfg_nbr      (cfg_nbr_q),
        .cfg_term     (cfg_term_q),
        .cfg_tau      (cfg_tau_q),
        .cfg_vmin     (cfg_vmin_q),
        .cfg_vmax     (cfg_vmax_q),
        .start       (start_q),
        .busy        (busy),
        .done        (done),
        .cycles      (cycles),
        .beats_run   (beats_run),
        .pix_valid   (pix_valid),
        .pix_ready   (pix_ready),
        .pix_mask    (pix_mask),
        .pix_m       (pix_m),
        .pix_by      (pix_by),
        .pix_bx      (pix_bx),
        .pix_rgba    (pix_rgba),
        .pix_eop     (pix_eop),
        .pix_z       (pix_z),
        .dbg_hold    (hold)
    );

    // ------------------------------------------------------------ pixel dump
    localparam integer CW         = ACC_W + 1;
    localparam integer MASK_WORDS = (P + 31) / 32;
    localparam integer BX_WORD0   = 3 + MASK_WORDS;
    localparam integer RGBA_WORD0 = BX_WORD0 + P;
    localparam integer Z_WORD0    = RGBA_WORD0 + 4 * P;
    localparam integer REC_WORDS  = Z_WORD0 + 2 * P;
    localparam integer ZF_W       = M_W + 1;
    localparam [7:0]   REC_MAGIC  = 8'hC4;
    localparam [7:0]   REC_START  = 8'd1;
    localparam [7:0]   REC_BEAT   = 8'd2;
    localparam [7:0]   REC_LAST   = 8'd3;

    reg [15:0]             frame_q;     // start records written so far
    reg [32*REC_WORDS-1:0] start_rec, beat_rec;
    integer                l, c;
    initial frame_q = 16'd0;
    always @(*) begin
        start_rec       = {(32*REC_WORDS){1'b0}};
        start_rec[31:0] = {REC_MAGIC, REC_START, frame_q};
        beat_rec        = {(32*REC_WORDS){1'b0}};
        beat_rec[31:0]  = {REC_MAGIC, pix_eop ? REC_LAST : REC_BEAT, frame_q - 16'd1};
        beat_rec[32 +: M_W]  = pix_m;
        beat_rec[64 +: BX_W] = pix_by;
        beat_rec[96 +: P]    = pix_mask;
        for (l = 0; l < P; l = l + 1) begin
            beat_rec[32 * (BX_WORD0 + l) +: BX_W] = pix_bx[l * BX_W +: BX_W];
            for (c = 0; c < 4; c = c + 1)   // pix_rgba lane l: {R, G, B, A}, R on top
                beat_rec[32 * (RGBA_WORD0 + 4 * l + c) +: CW] = pix_rgba[(4 * l + 3 - c) * CW +: CW];
            for (c = 0; c < 2; c = c + 1)   // pix_z lane l: {passed, first}, {valid, m} each
                beat_rec[32 * (Z_WORD0 + 2 * l + c) +: ZF_W] =
                    pix_z[(2 * l + 1 - c) * ZF_W + M_W] ? ZF_W'(pix_z[(2 * l + 1 - c) * ZF_W +: M_W]) + 1'b1 : '0;
        end
    end

    always @(posedge clk) begin
        if (!rst_q) begin
            if (start_q && !busy) begin
                $fwrite(dump_fd, "%u", start_rec);
                frame_q <= frame_q + 16'd1;
            end
            if (pix_valid && pix_ready) begin
                if (dump_en_q) $fwrite(dump_fd, "%u", beat_rec);
                if (pix_eop || !busy) $fflush(dump_fd);
            end
        end
    end

endmodule
`default_nettype wire

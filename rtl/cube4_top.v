`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_top
// -----------------------------------------------------------------------------
// Purpose
//   The whole Cube-4: P pipelines, each with its voxel memory bank, CFB, TRI,
//   GRA, SHA and COM (docs/architecture.md). A build leaves out what its
//   scenes do not need (SHADING, COMPOSITING, EXTREMUM, CLIP, PLW below). The host loads the volume once
//   (load port; golden/cube4/memory.py packs it), writes the classification
//   LUT and the reflectance map (load ports, any time between frames), sets
//   the view registers (frontend_regs + SX, SY) and pulses start; the frame's
//   finished rays leave on the pixel stream, and done pulses with the last
//   beat. Frames may follow each other with other views and tables, without
//   a reset; a reset in mid-frame leaves the design ready for a clean frame.
//
// Parameters
//   P            pipelines = memory banks.              1..64.    Default 8.
//   VOXEL_W      voxel width.                           1..16.    Default 8.
//   WEIGHT_W     resampling weight width W.             4..12.    Default 8.
//   ALPHA_W      LUT opacity width.                     8..16.    Default 12.
//   ACC_W        compositing accumulator fraction bits. 8..24.    Default 16.
//   RMAP_BITS    reflectance-map resolution log2 R.     2..6.     Default 5.
//   MAX_DIM      largest volume dimension.              2..2048.  Default 256.
//   MAX_SS_LOG2  log2 of the largest supersampling.     0..3.     Default 0.
//   DEPTH        voxel words per bank.                  2..2^30.  Default 65536.
//   ADDR_W       bank address width.                    1..30.    Default 16.
//   DRAM         0: the voxel memory on chip (cube4_voxel_mem, DEPTH words
//                per bank); 1: in a DRAM behind the dram_* port
//                (cube4_dram_fetch; DEPTH unused).       0..1.     Default 0.
//   DRAM_AW      the DRAM port's address width (128-bit words). 1..32. Default 21.
//   SHADING      1: GRA, the reflectance map and the shading multipliers;
//                0: none of them (classification only).  0..1.   Default 1.
//   COMPOSITING  1: COM's compositing datapath (composite, X-ray). 0..1. Default 1.
//   EXTREMUM     1: COM's comparators (MIP, MinIP).       0..1.     Default 1.
//   CLIP         1: the window and the cut plane (cube4_clip). 0..1. Default 1.
//   VGRAD        1: the gradient comes from the voxel memory (each word
//                holds a voxel and its gradient, golden/cube4/vgrad.py) and
//                TRI interpolates it: no GRA (numerics.md section 5b);
//                0: the paper's GRA on the sample stream.  0..1. Default 0.
//   PLW          1: path-length weights: the LUT carries four more opacity
//                columns (lut_data's top 4*ALPHA_W bits) that COM reads for a
//                ray's first and last samples (numerics.md section 17; FACES
//                = 0 turns them off for a frame); 0: none.  0..1. Default 1.
//   Illegal (elaboration stops): COMPOSITING = EXTREMUM = 0; SHADING = 1 with
//   COMPOSITING = 0 (only compositing is shaded); VGRAD = 1 with SHADING = 0;
//   PLW = 1 with COMPOSITING = 0 (only the blending modes are weighted);
//   RECTS = 1 with PLW = 1 or MAX_SS_LOG2 > 0; SLAB = 1 with CLIP = 0;
//   ZIN = 1 with RECTS = 1; GMOD = 1 with SHADING = 0 or RECTS = 1;
//   LABELS = 1 with VGRAD, PLW or RECTS = 1; BEATS = 1 with RECTS or
//   ZIN = 1.
//   RECTS        1: slice rectangles (numerics.md section 18): CFB walks each
//                slice's entry of the table (rect_*), GRA and COM follow the
//                rectangles; every frame needs its table (the whole box for the
//                fixed schedule).                       0..1. Default 0.
//   SLAB         1: the cut slab (numerics.md section 12): its far face in
//                cube4_clip (CUT_T), and with COMPOSITING its falloff weights
//                (cube4_sha_slab, FALL_*) by which COM multiplies the blending
//                modes' opacity.                        0..1. Default 0.
//   ZOUT         1: depth out (numerics.md section 21): COM keeps two slice
//                numbers per ray in its buffer word and gives them beside each
//                finished ray (pix_z; DEPTH_T).          0..1. Default 0.
//   GMOD         1: gradient-magnitude modulation (numerics.md section 23):
//                cube4_sha_gm's factors of |g|^2 from the host's table (gm_*)
//                modulate A, D and P in SHA (two more SHA stages). 0..1. Default 0.
//   ZIN          1: depth in (numerics.md section 22): COM reads each lane's
//                stop slice from the host's table (stop_*, cube4_com_stop)
//                and counts only the samples in front of it; every frame
//                needs its table (all 2^M_W - 1: no geometry). 0..1. Default 0.
//   BEATS        1: beat skipping and ray termination (numerics.md section 19):
//                CFB decides every beat from the block table (blk_*) and the
//                ray table (the stops, written through stop_*) and walks the
//                voxel beats the running ones read (GRA: cube4_gra_beats);
//                the front end's sample beats pass a skid buffer (one cycle);
//                COM takes each beat's position bits (a FIFO beside GRA and
//                SHA, between two skid buffers: in block RAM, a slice and two
//                rows of beats deep, with shading; the beat waits at SHA's
//                output for its bits) and each beat's slice steps
//                (cube4_com_steps at COM's input, moved as COM takes the beat
//                from the skid buffer after SHA), ends the rays and reports
//                the done ones back (view registers BB_*, NBR, TERM, TAU,
//                VMIN, VMAX). Every frame needs both tables.   0..1. Default 0.
//   LABELS       1: label volumes (numerics.md section 24): each memory word
//                holds the voxel's label (LABEL_W = 4 bits) above it, TRI
//                picks the nearest corner's, GRA carries it with the sample,
//                and SHA's LUT has a block of 2^VOXEL_W entries per label
//                (lut_addr = {label, value}).            0..1. Default 0.
//
// Latency
//   A frame: (M*NJ + 1)*NB + 1 memory beats (cube4_cfb), then GRA finishes the
//   last slice (NJ*NB + NB + 2 steps; not in a build without GRA: SHADING = 0
//   or VGRAD = 1), plus a
//   fixed pipeline fill per build (golden/cube4/cycles.py; tb/cube4_top
//   checks it at P = 1, 4, 5, 8 and for every build).
//   cycles counts the clock cycles from start to the last pixel beat;
//   beats_run (BEATS = 1; 0 otherwise) the frame's sample beats that ran, a
//   lane valid, into COM (numerics.md section 19, run_beats). With
//   DRAM = 1 the memory stalls the front end as it must: a frame takes at least
//   those cycles (cube4_sim.engine dram_stats, reports/dram.md).
//
// Ports
//   ld_*           voxel load port (cube4_voxel_mem; WORD_W-bit words)
//   dram_*         a DRAM controller's native port and its reset (DRAM = 1):
//                  LiteDRAM's, as cube4_dram_fetch describes
//   lut_*, rmap_*  table load ports: lut_data = {the path-weight columns (PLW = 1:
//                  A at w = 3/2, 5/4, 3/4, 1/2 from the top, Q0.ALPHA_W each; cube4_com),
//                  R, G, B (Q0.8), A (Q0.ALPHA_W) (cube4_sha)}
//   rect_*, stop_*, gm_*, blk_*   the slice-rectangle (RECTS), stop-slice (ZIN,
//                  and the ray table's stops with BEATS), modulation (GMOD)
//                  and block (BEATS) tables, written between frames (layouts
//                  at the ports below)
//   cfg_*          view registers, stable from start to done
//   start, busy, done, cycles   frame control
//   pix_*          finished rays (cube4_com)
//   dbg_hold       [5] verification only, tie to 0: hold the internal streams
//                  {memory request, memory response, samples, gradients, shaded}
//   Every internal stream and the pixel stream are checked in simulation by
//   cube4_stream_check (valid held and data stable while stalled, no unknown
//   bits on a valid beat); synthesis sees empty modules.
//
// Bit growth and rounding: see the units; every format is in docs/numerics.md.
// =============================================================================
module cube4_top #(
    `CUBE4_BUILD_PARAMS, parameter integer DEPTH = 65536,
    parameter integer DRAM = 0, parameter integer DRAM_AW = 21,
    `CUBE4_ADDR_LAYOUT, `CUBE4_TAG_LAYOUT,
    `CUBE4_WORD_LAYOUT, `CUBE4_RECT_LAYOUT, `CUBE4_STOP_LAYOUT, `CUBE4_GM_LAYOUT,
    localparam integer BLOCK_LOG2 = 2, `CUBE4_BLOCK_LAYOUT,
    localparam integer BX_W = DIM_W + 1,
    localparam integer RI_W = 2 * RMAP_BITS + 3,
    localparam integer LUT_W = 24 + ALPHA_W + PLW * 4 * ALPHA_W,  // a LUT entry (lut_data)
    localparam integer LUT_AW = SMP_W                               // a LUT address: {label, value}
) (
    input  wire                      clk,
    input  wire                      rst,
    // voxel memory load port
    input  wire                      ld_valid,
    output wire                      ld_ready,
    input  wire [ADDR_W-1:0]         ld_addr,
    input  wire [P*WORD_W-1:0]       ld_data,
    // the DRAM controller's native port (DRAM = 1; unused otherwise):
    // 128-bit words, one burst each, and the port's reset (cube4_dram_fetch)
    input  wire                      dram_rst,
    `CUBE4_DRAM_PORTS,
    // table load ports
    input  wire                      lut_we,
    input  wire [LUT_AW-1:0]         lut_addr,
    input  wire [LUT_W-1:0]          lut_data,
    input  wire                      rmap_we,
    input  wire [RI_W-1:0]           rmap_addr,
    input  wire [19:0]               rmap_data,
    // gradient-magnitude modulation's table (GMOD = 1; unused otherwise): entry
    // gm_addr = {fa, fs}, GMF_W bits each (golden/cube4/gmod.py gm_table)
    input  wire                      gm_we,
    input  wire [GMA_W-1:0]          gm_addr,
    input  wire [2*GMF_W-1:0]        gm_data,
    // the slice-rectangle table (RECTS = 1; unused otherwise): entry rect_addr =
    // sample slice, layout CUBE4_RECT_LAYOUT (golden/cube4/memory.py rect_table)
    input  wire                      rect_we,
    input  wire [M_W-1:0]            rect_addr,
    input  wire [RECT_W-1:0]         rect_data,
    // the stop table (ZIN = 1; unused otherwise): address {by, bx div P}, bank b
    // of the word at [b*M_W] (golden/cube4/memory.py stop_table, CUBE4_STOP_LAYOUT)
    // the block table (BEATS = 1; unused otherwise): word {kb, jb} = the bits of the
    // blocks along the frame's i axis (sim/cube4_sim/beat_frames.py block_words,
    // CUBE4_BLOCK_LAYOUT); with BEATS the stop_* port writes the ray table's stops
    input  wire                      blk_we,
    input  wire [2*BK_W-1:0]         blk_addr,
    input  wire [NBK-1:0]            blk_data,
    input  wire                      stop_we,
    input  wire [STOP_AW-1:0]        stop_addr,
    input  wire [P*M_W-1:0]          stop_data,
    // view registers
    `CUBE4_VIEW_PORTS
    `CUBE4_ADDR_PORTS
    // frame control
    input  wire                      start,
    output wire                      busy,
    output wire                      done,
    output wire [31:0]               cycles,
    output wire [31:0]               beats_run,
    // finished rays
    output wire                      pix_valid,
    input  wire                      pix_ready,
    output wire [P-1:0]              pix_mask,
    output wire [M_W-1:0]            pix_m,
    output wire [BX_W-1:0]           pix_by,
    output wire [P*BX_W-1:0]         pix_bx,
    output wire [P*4*(ACC_W+1)-1:0]  pix_rgba,
    output wire                      pix_eop,
    output wire [P*2*(M_W+1)-1:0]    pix_z,       // depth out (ZOUT = 1): lane q {passed, first}, {valid, m} each
    // verification hook
    input  wire [4:0]                dbg_hold
);
    localparam integer PV     = P * VOXEL_W;
    localparam integer PW     = P * WORD_W;    // a beat of memory words (= P * SMP_W without VGRAD)
    localparam integer GRAD_W = VOXEL_W + 5;
    generate
        `CUBE4_BUILD_CHECKS("cube4_top")
        if (PLW != 0 && COMPOSITING == 0) begin : g_plw_alone
            $error("cube4_top: PLW = 1 needs COMPOSITING = 1 (only the blending modes are path-weighted)");
        end
        if (VGRAD != 0 && SHADING == 0) begin : g_vgrad_alone
            $error("cube4_top: VGRAD = 1 needs SHADING = 1 (voxel gradients only feed shading)");
        end
        if (COMPOSITING == 0 && EXTREMUM == 0) begin : g_no_mode
            $error("cube4_top: COMPOSITING = 0 and EXTREMUM = 0 leave no rendering mode");
        end
        if (RECTS != 0 && (PLW != 0 || MAX_SS_LOG2 != 0)) begin : g_rects_plw
            $error("cube4_top: RECTS = 1 needs PLW = 0 and MAX_SS_LOG2 = 0 (rectangles run with S = 1, unweighted)");
        end
        if (SLAB != 0 && CLIP == 0) begin : g_slab_clip
            $error("cube4_top: SLAB = 1 needs CLIP = 1 (the slab is the cut plane's)");
        end
        if (GMOD != 0 && (SHADING == 0 || RECTS != 0)) begin : g_gmod_shading
            $error("cube4_top: GMOD = 1 needs SHADING = 1 and RECTS = 0 (the gradient comes with shading; not with rectangles)");
        end
        if (LABELS != 0 && (VGRAD != 0 || PLW != 0 || RECTS != 0)) begin : g_labels_alone
            $error("cube4_top: LABELS = 1 needs VGRAD = 0 and PLW = 0 and RECTS = 0 (labels run without voxel gradients, path weights and rectangles)");
        end
        if (BEATS != 0 && (RECTS != 0 || ZIN != 0)) begin : g_beats_alone
            $error("cube4_top: BEATS = 1 needs RECTS = 0 and ZIN = 0 (the beat schedule runs without rectangles, and depth in through the ray table's stops)");
        end
        if (ZIN != 0 && RECTS != 0) begin : g_zin_rects
            $error("cube4_top: ZIN = 1 needs RECTS = 0 (depth in runs on the fixed and box schedules)");
        end
        `CUBE4_RANGE(g_bad_dram, "cube4_top", "DRAM", DRAM, 0, 1)
        if (SHADING != 0 && COMPOSITING == 0) begin : g_shading_alone
            $error("cube4_top: SHADING = 1 needs COMPOSITING = 1 (MIP, MinIP and X-ray are not shaded)");
        end
    endgenerate
    wire [VIEW_W-1:0]    cfg      = `CUBE4_VIEW_PACK;
    wire [ADR_W_ALL-1:0] cfg_addr = `CUBE4_ADDR_PACK;
    wire                 busy_q;   // a frame runs: start accepted, last pixel beat not yet out

    // ---------------------------------------------------------------- front end + memory
    wire                 fe_req_valid, fe_req_ready, mem_req_valid, mem_req_ready;
    wire [P*ADDR_W-1:0]  req_addr;
    wire [P-1:0]         req_rden;
    wire [TAG_W-1:0]     req_tag;
    wire                 mem_rsp_valid, mem_rsp_ready, fe_rsp_valid, fe_rsp_ready;
    wire [PW-1:0]        rsp_data;
    wire [TAG_W-1:0]     rsp_tag;
    wire                 smp_valid, smp_ready, gra_in_valid, gra_in_ready;
    wire [HDR_W-1:0]     smp_hdr;
    wire [PW-1:0]        smp_sample;
    wire                 unused_fe_busy, unused_fe_done;
    wire [31:0]          unused_fe_cycles;

    // the beat schedule (BEATS = 1): the position bits of each sample beat wait for it
    // at COM's input, COM's reports go back to the front end
    wire [4*P-1:0]   smp_bits, fe_smp_bits;
    wire             smp_eos, smp_eoss, fe_smp_eos, fe_smp_eoss, fe_smp_valid, fe_smp_ready;
    wire [HDR_W-1:0] fe_smp_hdr;
    wire [PW-1:0]    fe_smp_sample;
    wire             com_rep_valid;
    wire [DIM_W-1:0] com_rep_j, com_rep_stx, com_rep_sty;
    wire [PB_W-1:0]  com_rep_pb;
    wire [P-1:0]     com_rep_en;
    wire [P*M_W-1:0] com_rep_end;
    wire [M_W-1:0]   com_m;
    cube4_frontend #(
        `CUBE4_BUILD_PASS
    ) u_frontend (
        .clk           (clk),
        .rst           (rst),
        .start         (start && !busy_q),
        .busy          (unused_fe_busy),
        .done          (unused_fe_done),
        .cycles        (unused_fe_cycles),
        .cfg           (cfg),
        .cfg_addr      (cfg_addr),
        .rect_we       (rect_we),
        .rect_addr     (rect_addr),
        .rect_data     (rect_data),
        .blk_base      ({cfg_bb_k, cfg_bb_j, cfg_bb_i}),
        .nbr_en        (cfg_nbr),
        .blk_we        (blk_we),
        .blk_addr      (blk_addr),
        .blk_data      (blk_data),
        .tab_we        (stop_we && BEATS != 0),
        .tab_addr      (stop_addr),
        .tab_data      (stop_data),
        `CUBE4_REPORT_CONN,
        .com_m         (cfg_term ? com_m : {M_W{1'b1}}),   // no termination: no wait
        .smp_bits      (fe_smp_bits),
        .smp_eos       (fe_smp_eos),
        .smp_eoss      (fe_smp_eoss),
        .mem_req_valid (fe_req_valid),
        .mem_req_ready (fe_req_ready),
        .mem_req_addr  (req_addr),
        .mem_req_rden  (req_rden),
        .mem_req_tag   (req_tag),
        .mem_rsp_valid (fe_rsp_valid),
        .mem_rsp_ready (fe_rsp_ready),
        .mem_rsp_data  (rsp_data),
        .mem_rsp_tag   (rsp_tag),
        .smp_valid     (fe_smp_valid),
        .smp_ready     (fe_smp_ready),
        .smp_hdr       (fe_smp_hdr),
        .smp_sample    (fe_smp_sample)
    );

    cube4_stream_hold u_hold_req (
        .hold (dbg_hold[4]), .in_valid (fe_req_valid), .in_ready (fe_req_ready),
        .out_valid (mem_req_valid), .out_ready (mem_req_ready));

    generate
        if (DRAM != 0) begin : g_dram
            cube4_dram_fetch #(
                .P       (P),
                .MAX_DIM (MAX_DIM),
                .WORD_W  (WORD_W),
                .ADDR_W  (ADDR_W),
                .TAG_W   (TAG_W),
                .DRAM_AW (DRAM_AW)
            ) u_mem (
                .clk              (clk),
                .rst              (rst),
                .dram_rst         (dram_rst),
                `CUBE4_VOXEL_MEM_CONNECT,
                `CUBE4_DRAM_CONNECT
            );
        end else begin : g_bram
            cube4_voxel_mem #(
                .P       (P),
                .WORD_W  (WORD_W),
                .DEPTH   (DEPTH),
                .ADDR_W  (ADDR_W),
                .TAG_W   (TAG_W)
            ) u_mem (
                .clk       (clk),
                .rst       (rst),
                `CUBE4_VOXEL_MEM_CONNECT
            );
            assign dram_cmd_valid   = 1'b0;
            assign dram_cmd_we      = 1'b0;
            assign dram_cmd_addr    = {DRAM_AW{1'b0}};
            assign dram_wdata_valid = 1'b0;
            assign dram_wdata_data  = 128'd0;
            assign dram_wdata_we    = 16'd0;
            assign dram_rdata_ready = 1'b1;
            wire unused_dram = &{1'b0, dram_rst, dram_cmd_ready, dram_wdata_ready, dram_rdata_valid, dram_rdata_data};
        end
    endgenerate

    cube4_stream_hold u_hold_rsp (
        .hold (dbg_hold[3]), .in_valid (mem_rsp_valid), .in_ready (mem_rsp_ready),
        .out_valid (fe_rsp_valid), .out_ready (fe_rsp_ready));

    // BEATS = 1: each sample beat's bits into a FIFO as it leaves the front end
    // (it waits for room), out as the beat enters COM (GRA and SHA keep the order
    // and count; the beat waits at SHA's output until its bits are there). GRA
    // holds a slice and two rows of beats (cube4_gra_beats: a centre leaves at
    // its X-step), so with GRA (shading, not VGRAD) the FIFO is
    // (MAX_DIM + 2) * NBMAX beats and 128 for the pipelines, rounded up to a
    // power of two; never full while a beat waits in GRA for the next ones;
    // otherwise 64. The bits wait packed (3P bits a beat,
    // CUBE4_RAY_BITS_FUNCTIONS).
    `CUBE4_RAY_BITS_FUNCTIONS
    localparam integer BITS_DEPTH = (SHADING != 0 && VGRAD == 0) ? (1 << $clog2((MAX_DIM + 2) * NBMAX + 128)) : 64;
    wire [4*P-1:0] com_bits;
    wire           com_eoss;       // the beat is the last of its sample slice
    wire           com_in_take;
    wire           sha_take;       // SHA's beat leaves (its bits leave their FIFO with it)
    wire           com_bits_valid; // the bits of SHA's beat are at their FIFO's output
    generate
        if (BEATS != 0) begin : g_bits
            // the front end's sample beats pass a skid buffer: its ready (TRI's FIFO
            // and the front end's bits FIFO pop on it) is a register, not the AND of
            // GRA's ready and the bits FIFO's room across the die (cycles are measured
            // on this schedule: the cycle it adds changes no prediction)
            // (its valid in two copies: copy 0 drives the skid's own state and the
            // bits FIFO's push beside it, copy 1 GRA's take; with one register the
            // AND of it and GRA's ready was one LUT beside GRA that both GRA's
            // enables and the skid's pointers took, across the die: a crop beat
            // build's longest path on one placement)
            wire s_valid, s_ready;
            wire [1:0] s_valid_cp;
            wire s_nx_valid, s_ready_cp, s_ready_nx;
            wire [HDR_W+PW+4*P+1:0] s_nx_data;
            cube4_skid_peek #(.DATA_W (HDR_W + PW + 4 * P + 2), .VALID_N (2)) u_smp_skid (
                .clk (clk), .rst (rst),
                .in_valid (fe_smp_valid), .in_ready (fe_smp_ready),
                .in_data ({fe_smp_hdr, fe_smp_sample, fe_smp_bits, fe_smp_eos, fe_smp_eoss}),
                .out_valid (s_valid), .out_ready (s_ready),
                .out_data ({smp_hdr, smp_sample, smp_bits, smp_eos, smp_eoss}),
                .nx_valid (s_nx_valid), .nx_data (s_nx_data), .in_ready_cp (s_ready_cp),
                .in_ready_nx (s_ready_nx), .out_valid_cp (s_valid_cp));
            wire unused_smp_skid = ^{s_nx_valid, s_nx_data, s_ready_cp, s_ready_nx, s_valid_cp[0]};
            wire k_ready, b_valid;
            wire [1:0] k_ready_cp;   // copies of k_ready (u_bits)
            wire [3*P-1:0] com_packed;
            assign com_bits     = ray_bits_unpack(com_packed);
            // the beat forks to GRA and, its bits, to the FIFO's skid beside it, and
            // they leave through its skid beside SHA's output, which the beat's
            // departure (sha_take) pops: the FIFO's ready and GRA's, registers at
            // either end of the die, each reach only the logic beside them
            // (cube4_skid_fifo; block RAM behind GRA, distributed RAM otherwise)
            assign smp_valid    = s_valid_cp[1] && k_ready;
            assign s_ready      = smp_ready && k_ready_cp[1];
            // (the RAM's word through its output register, OUT_REG: at 64 words,
            // without GRA, the vendor layer makes it distributed RAM read into
            // flip-flops, whose asynchronous read with the route to the back skid
            // was the unshaded beat build's longest path)
            // (its valid in two copies: copy 1, com_bits_valid, reaches SHA's output
            // and COM's skid alone, not the back skid's own state, so that it lies
            // beside them: from the back skid's register into SHA's output FIFO
            // across the die was the unshaded beat build's longest path)
            wire [1:0] b_valid_cp;
            wire       k_ready_nx;   // (k_ready_cp are its registers)
            // (its ready in two copies: copy 0, k_ready, gates the beat to GRA;
            // copy 1 pops the sample skid and lies beside it: copy 0 across the
            // die into that skid's pointers was the default beat build's longest
            // path on one placement)
            cube4_skid_fifo #(.DATA_W (3 * P + 1), .DEPTH (BITS_DEPTH), .RAM (1), .OUT_REG (1),
                              .READY_N (2), .VALID_N (2)) u_bits (
                .clk (clk), .rst (rst),
                .in_valid (s_valid && smp_ready), .in_ready (k_ready),
                .in_data ({smp_eoss, ray_bits_pack(smp_bits)}),
                .out_valid (b_valid), .out_ready (sha_take), .out_data ({com_eoss, com_packed}),
                .in_ready_cp (k_ready_cp), .in_ready_nx (k_ready_nx), .out_valid_cp (b_valid_cp));
            wire unused_bits = ^{smp_eos, k_ready_cp[0], k_ready_nx, b_valid, b_valid_cp[0]};
            assign com_bits_valid = b_valid_cp[1];
        end else begin : g_no_bits
            assign smp_valid    = fe_smp_valid;
            assign fe_smp_ready = smp_ready;
            assign {smp_hdr, smp_sample, smp_bits, smp_eos, smp_eoss} =
                   {fe_smp_hdr, fe_smp_sample, fe_smp_bits, fe_smp_eos, fe_smp_eoss};
            assign com_bits     = '0;
            assign com_eoss     = 1'b0;
            assign com_bits_valid = 1'b1;
            wire unused_bits = ^{smp_bits, smp_eos, smp_eoss, com_in_take, sha_take, blk_we, blk_addr, blk_data, com_m,
                                 com_rep_valid, com_rep_j, com_rep_pb, com_rep_stx, com_rep_sty,
                                 com_rep_en, com_rep_end};
        end
    endgenerate

    cube4_stream_hold u_hold_smp (
        .hold (dbg_hold[2]), .in_valid (smp_valid), .in_ready (smp_ready),
        .out_valid (gra_in_valid), .out_ready (gra_in_ready));

    // ---------------------------------------------------------------- GRA
    // (a build without shading has none: SHA takes the sample stream; with
    // VGRAD, TRI's interpolated voxel gradients take GRA's place)
    wire                 gra_valid, gra_ready, sha_in_valid, sha_in_ready;
    wire [HDR_W-1:0]     gra_hdr;
    wire [P*SMP_W-1:0]   gra_sample;      // {label, value} per lane (the label with LABELS)
    wire [P*GRAD_W-1:0]  gra_gi, gra_gj, gra_gk;

    generate
        if (VGRAD != 0) begin : g_vgrad
            // each lane's word: the sample, then g_x, g_y, g_z (signed VG_W bits,
            // sign-extended to GRAD_W; |g| <= 4 (2^VOXEL_W - 1) < 2^(GRAD_W-1))
            genvar q;
            for (q = 0; q < P; q = q + 1) begin : g_lane
                wire [WORD_W-1:0] w = smp_sample[q*WORD_W +: WORD_W];
                assign gra_sample[q*VOXEL_W +: VOXEL_W] = w[0 +: VOXEL_W];
                assign gra_gi[q*GRAD_W +: GRAD_W] = GRAD_W'($signed(w[VOXEL_W +: VG_W]));
                assign gra_gj[q*GRAD_W +: GRAD_W] = GRAD_W'($signed(w[VOXEL_W + VG_W +: VG_W]));
                assign gra_gk[q*GRAD_W +: GRAD_W] = GRAD_W'($signed(w[VOXEL_W + 2*VG_W +: VG_W]));
            end
            assign gra_valid    = gra_in_valid;
            assign gra_in_ready = gra_ready;
            assign gra_hdr      = smp_hdr;
        end else if (SHADING != 0) begin : g_gra
            cube4_gra #(
                .P           (P),
                .VOXEL_W     (VOXEL_W),
                .WEIGHT_W    (WEIGHT_W),
                .MAX_DIM     (MAX_DIM),
                .MAX_SS_LOG2 (MAX_SS_LOG2),
                .RECTS       (RECTS),
                .BEATS       (BEATS),
                .LABELS      (LABELS)
            ) u_gra (
                .clk        (clk),
                .rst        (rst),
                .cfg        (cfg),
                .in_valid   (gra_in_valid),
                .in_ready   (gra_in_ready),
                .in_hdr     (smp_hdr),
                .in_sample  (smp_sample),
                .in_eoss    (smp_eoss),
                .out_valid  (gra_valid),
                .out_ready  (gra_ready),
                .out_hdr    (gra_hdr),
                .out_sample (gra_sample),
                .out_gi     (gra_gi),
                .out_gj     (gra_gj),
                .out_gk     (gra_gk)
            );
        end else begin : g_no_gra
            assign gra_valid    = gra_in_valid;
            assign gra_in_ready = gra_ready;
            assign gra_hdr      = smp_hdr;
            assign gra_sample   = smp_sample;
            assign gra_gi       = '0;
            assign gra_gj       = '0;
            assign gra_gk       = '0;
        end
    endgenerate

    cube4_stream_hold u_hold_gra (
        .hold (dbg_hold[1]), .in_valid (gra_valid), .in_ready (gra_ready),
        .out_valid (sha_in_valid), .out_ready (sha_in_ready));

    // ---------------------------------------------------------------- SHA
    wire                       sha_valid, sha_ready, com_in_valid, com_in_ready;
    wire                       com_skid_valid;  // the skid before COM: its own valid (copy 0; COM's in_valid is copy 1)
    wire [HDR_W-1:0]           sha_hdr;
    wire [P*(24+ALPHA_W)-1:0]  sha_rgba;
    wire [P*RI_W-1:0]          unused_sha_idx;
    wire [PV-1:0]              sha_sample;
    wire [P*FALL_W-1:0]        sha_fall;

    // SHA's output valid in two copies with beats: copy 1 pops the bits' FIFO
    // (sha_take, below), so that AND is not SHA's FIFO's own read: as one
    // gate beside SHA it sent COM's ready across the die to SHA and back to
    // the bits' FIFO beside COM in one cycle, on one placement the default
    // beat build's longest path
    localparam integer SHA_VN = (BEATS != 0) ? 2 : 1;
    wire [SHA_VN-1:0]          sha_valid_cp;
    cube4_sha #(
        `CUBE4_BUILD_PASS,
        .CARRY_SAMPLE((EXTREMUM != 0 || PLW != 0) ? 1 : 0),
        .VALID_N     (SHA_VN)
    ) u_sha (
        .clk       (clk),
        .rst       (rst),
        .cfg       (cfg),
        .lut_we    (lut_we),
        .lut_addr  (lut_addr),
        .lut_data  (lut_data[0 +: 24 + ALPHA_W]),   // (SHA: the label's block)
        .rmap_we   (rmap_we),
        .rmap_addr (rmap_addr),
        .rmap_data (rmap_data),
        .gm_we     (gm_we),
        .gm_addr   (gm_addr),
        .gm_data   (gm_data),
        .in_valid  (sha_in_valid),
        .in_ready  (sha_in_ready),
        .in_hdr    (gra_hdr),
        .in_sample (gra_sample),
        .in_gi     (gra_gi),
        .in_gj     (gra_gj),
        .in_gk     (gra_gk),
        .out_valid (sha_valid),
        .out_ready (sha_ready),
        .out_hdr   (sha_hdr),
        .out_rgba  (sha_rgba),
        .out_idx   (unused_sha_idx),
        .out_sample(sha_sample),
        .out_fall  (sha_fall),
        .out_valid_cp (sha_valid_cp)
    );

    wire x_valid, x_ready;          // SHA's stream after the debug hold
    cube4_stream_hold u_hold_sha (
        .hold (dbg_hold[0]), .in_valid (sha_valid), .in_ready (sha_ready),
        .out_valid (x_valid), .out_ready (x_ready));
    wire xb_valid, unused_xb_ready;  // SHA's valid copy SHA_VN - 1 after the same hold
    cube4_stream_hold u_hold_sha_b (
        .hold (dbg_hold[0]), .in_valid (sha_valid_cp[SHA_VN-1]), .in_ready (unused_xb_ready),
        .out_valid (xb_valid), .out_ready (x_ready));
    assign sha_take = xb_valid && x_ready;

    // SHA's beat (BEATS = 1: and its bits) pass a skid buffer into COM (which
    // takes them through its own: two register stages on the route across the
    // die; COM's input ready, its output FIFO's credit and its walk's hazard,
    // reaches SHA's output FIFO from the skid's register, not across the die in
    // one cycle: one cycle more a frame, in golden/cube4/cycles.py's fill).
    // BEATS = 1: the steps and phases of the beat's slice (cube4_com_steps) are
    // decided as COM takes the beat from the skid (its state moves at COM's
    // take, its registers beside COM's input, q_geo a choice among them); at
    // the push into the skid, where SHA's output FIFO and the skid's ready meet
    // across the die, their clock enable was a slab beat build's longest path
    localparam integer GEO_W = `CUBE4_GEO_W;     // cube4_com_steps' q_geo
    localparam integer XC_W = P * (24 + ALPHA_W) + PV + P * FALL_W + 4 * P + 1;
    wire [HDR_W-1:0]          c_hdr;
    wire [P*(24+ALPHA_W)-1:0] c_rgba;
    wire [PV-1:0]             c_sample;
    wire [P*FALL_W-1:0]       c_fall;
    wire [4*P-1:0]            c_bits;
    wire                      c_eoss;
    wire [GEO_W-1:0]          c_geo;
    generate
        if (BEATS != 0) begin : g_com_skid
            cube4_com_steps #(`CUBE4_SLICE_PASS) u_steps (
                .clk (clk), .rst (rst), .cfg (cfg),
                .q_push (com_in_take), .q_hdr (c_hdr), .q_eoss (c_eoss), .q_geo (c_geo));
            // the beat leaves SHA with its bits: a join of the two streams (a beat
            // that left SHA without GRA (unshaded, VGRAD) can be ahead of its
            // bits, which pass three registers and the FIFO's RAM read)
            wire xk_ready;
            assign x_ready = xk_ready && com_bits_valid;
            // (its valid in two copies: copy 0 drives the skid's own state, copy 1 is
            // COM's in_valid and its take, com_in_take, beside COM: with one register
            // the AND of it and COM's ready was one LUT beside COM that both COM's
            // enables and the skid's pointers took, across the die: the crop beat
            // build's longest path on one placement)
            wire [1:0] xk_valid_cp;
            wire xk_nx_valid, xk_ready_cp, xk_ready_nx;
            wire [XC_W-1:0] xk_nx_data;
            cube4_skid_peek #(.DATA_W (XC_W), .VALID_N (2)) u_com_skid (
                .clk (clk), .rst (rst),
                .in_valid (x_valid && com_bits_valid), .in_ready (xk_ready),
                .in_data ({sha_rgba, sha_sample, sha_fall, com_bits, com_eoss}),
                .out_valid (com_skid_valid), .out_ready (com_in_ready),
                .out_data ({c_rgba, c_sample, c_fall, c_bits, c_eoss}),
                .nx_valid (xk_nx_valid), .nx_data (xk_nx_data), .in_ready_cp (xk_ready_cp),
                .in_ready_nx (xk_ready_nx), .out_valid_cp (xk_valid_cp));
            assign com_in_valid = xk_valid_cp[1];
            wire unused_com_skid = ^{xk_nx_valid, xk_nx_data, xk_ready_cp, xk_ready_nx, xk_valid_cp[0]};
            // the header passes a skid of its own with the same valid and ready (so the
            // same count in every cycle), whose head is a register (cube4_skid_oreg): COM
            // compares the entering header's slot with its stages into a register
            // (cube4_com_ahead), and the head's flip-flops, which load as COM takes, lie
            // beside COM; the wide skid's entries lie toward SHA (from them, or from a
            // skid's read pointer, across the die into those compares was a beat
            // build's longest path)
            wire hk_ready, hk_valid;
            cube4_skid_oreg #(.DATA_W (HDR_W)) u_com_hdr_skid (
                .clk (clk), .rst (rst),
                .in_valid (x_valid && com_bits_valid), .in_ready (hk_ready),
                .in_data (sha_hdr),
                .out_valid (hk_valid), .out_ready (com_in_ready),
                .out_data (c_hdr));
`ifndef SYNTHESIS
            always @(posedge clk) begin
                if (!rst && {hk_ready, hk_valid} != {xk_ready, com_skid_valid})
                    $fatal(1, "cube4_top: the COM header skid's ready/valid %b differ from the COM skid's %b",
                           {hk_ready, hk_valid}, {xk_ready, com_skid_valid});
                if (!rst && com_in_valid != com_skid_valid)
                    $fatal(1, "cube4_top: the COM skid's valid copies differ (%b, %b)",
                           com_skid_valid, com_in_valid);
            end
`endif
            wire unused_hk = ^{hk_ready, hk_valid, com_skid_valid};     // (xk_ready and com_in_valid)
        end else begin : g_com_fixed
            localparam integer XF_W = HDR_W + P * (24 + ALPHA_W) + PV + P * FALL_W;
            // (its valid in two copies, as with beats: copy 1 is COM's)
            wire [1:0] xf_valid_cp;
            wire xf_nx_valid, xf_ready_cp, xf_ready_nx;
            wire [XF_W-1:0] xf_nx_data;
            cube4_skid_peek #(.DATA_W (XF_W), .VALID_N (2)) u_com_skid (
                .clk (clk), .rst (rst),
                .in_valid (x_valid), .in_ready (x_ready),
                .in_data ({sha_hdr, sha_rgba, sha_sample, sha_fall}),
                .out_valid (com_skid_valid), .out_ready (com_in_ready),
                .out_data ({c_hdr, c_rgba, c_sample, c_fall}),
                .nx_valid (xf_nx_valid), .nx_data (xf_nx_data), .in_ready_cp (xf_ready_cp),
                .in_ready_nx (xf_ready_nx), .out_valid_cp (xf_valid_cp));
            assign com_in_valid = xf_valid_cp[1];
            wire unused_com_skid = ^{xf_nx_valid, xf_nx_data, xf_ready_cp, xf_ready_nx, xf_valid_cp[0],
                                     com_skid_valid};
            assign {c_bits, c_eoss} = {com_bits, com_eoss};     // (constants: no beats)
            wire unused_bits_valid = com_bits_valid;
            assign c_geo = '0;
        end
    endgenerate

    // ---------------------------------------------------------------- COM
    assign com_in_take = com_in_valid && com_in_ready;
    cube4_com #(
        `CUBE4_BUILD_PASS
    ) u_com (
        .clk       (clk),
        .rst       (rst),
        .cfg       (cfg),
        .lut_we    (lut_we),
        .lut_addr  (lut_addr[VOXEL_W-1:0]),          // (PLW: no labels)
        .lut_data  (lut_data[LUT_W-1 -: PLW * 4 * ALPHA_W + (1 - PLW)]),
        .rect_we   (rect_we),
        .rect_addr (rect_addr),
        .rect_data (rect_data),
        .stop_we   (stop_we),
        .stop_addr (stop_addr),
        .stop_data (stop_data),
        .in_valid  (com_in_valid),
        .in_ready  (com_in_ready),
        .in_hdr    (c_hdr),
        .in_rgba   (c_rgba),
        .in_sample (c_sample),
        .in_fall   (c_fall),
        .in_bits   (c_bits),
        .in_eoss   (c_eoss),
        .in_geo    (c_geo),
        .frame_start (start && !busy_q),
        .term_en   (cfg_term),
        .term_tau  (cfg_tau[ACC_W:0]),
        .term_vmin (cfg_vmin[VOXEL_W-1:0]),
        .term_vmax (cfg_vmax[VOXEL_W-1:0]),
        `CUBE4_REPORT_CONN,
        .com_m     (com_m),
        .pix_valid (pix_valid),
        .pix_ready (pix_ready),
        .pix_mask  (pix_mask),
        .pix_m     (pix_m),
        .pix_by    (pix_by),
        .pix_bx    (pix_bx),
        .pix_rgba  (pix_rgba),
        .pix_eop   (pix_eop),
        .pix_z     (pix_z)
    );

    // ---------------------------------------------------------------- stream checks
    // Every internal stream's rules (cube4_stream_check; simulation only, empty
    // under SYNTHESIS), on the producer's side, before the verification holds.
    cube4_stream_check #(.NAME ("top.mem_req"), .DATA_W (P * ADDR_W + P + TAG_W)) u_chk_req (
        .clk (clk), .rst (rst), .valid (fe_req_valid), .ready (fe_req_ready),
        .data ({req_addr, req_rden, req_tag}));
    cube4_stream_check #(.NAME ("top.mem_rsp"), .DATA_W (PW + TAG_W)) u_chk_rsp (
        .clk (clk), .rst (rst), .valid (mem_rsp_valid), .ready (mem_rsp_ready),
        .data ({rsp_data, rsp_tag}));
    cube4_stream_check #(.NAME ("top.samples"), .DATA_W (HDR_W + PW)) u_chk_smp (
        .clk (clk), .rst (rst), .valid (smp_valid), .ready (smp_ready),
        .data ({smp_hdr, smp_sample}));
    generate
        if (SHADING != 0 && VGRAD == 0) begin : g_chk_gra   // (otherwise: the held sample stream)
            cube4_stream_check #(.NAME ("top.gradients"), .DATA_W (HDR_W + P * SMP_W + 3 * P * GRAD_W)) u_chk_gra (
                .clk (clk), .rst (rst), .valid (gra_valid), .ready (gra_ready),
                .data ({gra_hdr, gra_sample, gra_gi, gra_gj, gra_gk}));
        end
    endgenerate
    cube4_stream_check #(.NAME ("top.shaded"), .DATA_W (HDR_W + P * (24 + ALPHA_W) + PV + P * FALL_W)) u_chk_sha (
        .clk (clk), .rst (rst), .valid (sha_valid), .ready (sha_ready),
        .data ({sha_hdr, sha_rgba, sha_sample, sha_fall}));
    cube4_stream_check #(
        .NAME ("top.pixels"), .DATA_W (P + M_W + BX_W + P * BX_W + P * 4 * (ACC_W + 1) + 1 + P * 2 * (M_W + 1))
    ) u_chk_pix (
        .clk (clk), .rst (rst), .valid (pix_valid), .ready (pix_ready),
        .data ({pix_mask, pix_m, pix_by, pix_bx, pix_rgba, pix_eop, pix_z}));

    // ---------------------------------------------------------------- frame control
    cube4_frame_ctl u_frame (
        .clk       (clk),
        .rst       (rst),
        .start     (start),
        .last_beat (pix_valid && pix_ready && pix_eop),
        .busy      (busy_q),
        .done      (done),
        .cycles    (cycles)
    );
    assign busy = busy_q;

    // BEATS = 1: the frame's running sample beats (a lane valid) into COM
    generate
        if (BEATS != 0) begin : g_beats_run
            reg [31:0] run_q;
            always @(posedge clk) begin
                if (rst || (start && !busy_q)) run_q <= 32'd0;
                else if (com_in_take && (c_hdr[HDR_LVALID +: P] != '0)) run_q <= run_q + 32'd1;
            end
            assign beats_run = run_q;
        end else begin : g_no_beats_run
            assign beats_run = 32'd0;
        end
    endgenerate

endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
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
//   CLIP         1: TRI's cube4_clip (window, cut plane). 0..1. Default 1.
//   SLAB         1: cube4_clip's slab far face too (needs CLIP). 0..1. Default 0.
//   VGRAD        1: memory words carry voxel gradients, which TRI
//                interpolates (CUBE4_WORD_LAYOUT).   0..1.    Default 0.
//   RECTS        1: slice rectangles (cube4_cfb).      0..1.    Default 0.
//   BEATS        1: the beat schedule (cube4_cfb).     0..1.    Default 0.
//   (after the build's list)
//   BITS_DEPTH   BEATS = 1: emitted beats in flight between the CFB and
//                TRI's output (a power of two, the RAM of their bits' FIFO,
//                whose register queue and two skid buffers hold 8 more;
//                every request, one that emits no beat too, waits beyond it).
//                                                      4..1024. Default 64.
//   Derived widths and the layouts of cfg, cfg_addr, the memory tag and the
//   sample header: cube4_defs.vh.
//
// Latency
//   A frame: (M * NJ + 1) * NB + 1 request beats (M = (NK-1) * S + 1 passes,
//   NB = ceil(NI / P)), i.e. NI*NJ*NK/P cycles plus padding of the last
//   partial beam, one flush beam and the pipeline fill (26 cycles in
//   tb/cube4_frontend, whose harness adds a cycle on the request and on the
//   response path), when no port stalls. With slice rectangles (RECTS = 1):
//   SliceRects.beats request beats plus one cycle per empty slice before the
//   last that is not empty, and the same fill. done pulses the cycle the last
//   sample beat is accepted; cycles counts the clock cycles from start to that
//   beat inclusive.
//
// Ports
//   start / busy / done / cycles   frame control (cycles: 32-bit count)
//   cfg, cfg_addr                  view and address registers, see cube4_cfb
//   rect_*                         the rectangle table (RECTS = 1), see cube4_cfb
//   blk_*, tab_*, rep_*, com_m, blk_base, nbr_en   the beat schedule's tables,
//                                  COM's reports, the axes (BEATS = 1; cube4_cfb)
//   smp_bits [4P], smp_eos, smp_eoss  BEATS = 1: with each sample beat, its
//                                  position bits {soon, last, fresh, run}, its
//                                  EOS and EOSS (the last beat of its slice)
//   mem_req_* / mem_rsp_*          memory read port (see cube4_voxel_mem);
//                                  the tag is CUBE4_TAG_LAYOUT, a word WORD_W bits
//   smp_*                          sample stream, see cube4_tri out_*
//
// Bit growth and rounding: see cube4_tri (one rounding per lerp).
// =============================================================================
module cube4_frontend #(
    `CUBE4_BUILD_PARAMS,
    parameter integer BITS_DEPTH = 64,
    `CUBE4_ADDR_LAYOUT, `CUBE4_TAG_LAYOUT,
    `CUBE4_WORD_LAYOUT, `CUBE4_RECT_LAYOUT,
    localparam integer BLOCK_LOG2 = 2,
    `CUBE4_STOP_LAYOUT, `CUBE4_BLOCK_LAYOUT
) (
    input  wire clk, input wire rst,
    input  wire start, output wire busy, output wire done, output wire [31:0] cycles,
    input  wire [VIEW_W-1:0]    cfg,
    input  wire [ADR_W_ALL-1:0] cfg_addr,
    input  wire rect_we, input wire [M_W-1:0] rect_addr, input wire [RECT_W-1:0] rect_data,
    `CUBE4_BEATS_IN_PORTS,
    // memory read port: request, response
    output wire mem_req_valid, input wire mem_req_ready, output wire [TAG_W-1:0] mem_req_tag,
    output wire [P*ADDR_W-1:0] mem_req_addr,
    output wire [P-1:0] mem_req_rden,
    input  wire mem_rsp_valid, output wire mem_rsp_ready, input wire [TAG_W-1:0] mem_rsp_tag,
    input  wire [P*WORD_W-1:0]  mem_rsp_data,
    // sample stream
    output wire smp_valid, input wire smp_ready, output wire [HDR_W-1:0] smp_hdr,
    output wire [P*WORD_W-1:0]  smp_sample,
    output wire [4*P-1:0] smp_bits, output wire smp_eos, output wire smp_eoss   // BEATS = 1: with each sample beat
);
    // ---- CFB ----
    wire                unused_cfb_busy;   // the frame ends at the last sample, not the last request
    // CFB's request, into u_req_skid; its ready as CFB_ADV_N equal copies, one
    // per group of CFB's stall enable's loads (cube4_cfb_mask), each a
    // register of its own (u_cfb_ready, below)
    localparam integer ADV_N = `CUBE4_CFB_ADV_N;
    wire                c_req_valid;
    wire [ADV_N-1:0]    c_req_ready;
    wire [P*ADDR_W-1:0] c_req_addr;
    wire [P-1:0]        c_req_rden;
    wire [TAG_W-1:0]    c_req_tag;
    wire [4*P-1:0]      c_req_bits;
    wire                c_req_eos, c_req_eoss;
    cube4_cfb #(
        .P           (P),
        .MAX_DIM     (MAX_DIM),
        .ADDR_W      (ADDR_W),
        .WEIGHT_W    (WEIGHT_W),
        .MAX_SS_LOG2 (MAX_SS_LOG2),
        .RECTS       (RECTS),
        .BEATS       (BEATS)
    ) u_cfb (
        .clk       (clk),
        .rst       (rst),
        .start     (start && !busy),
        .busy      (unused_cfb_busy),
        .cfg       (cfg),
        .cfg_addr  (cfg_addr),
        .rect_we   (rect_we),
        .rect_addr (rect_addr),
        .rect_data (rect_data),
        `CUBE4_BEATS_IN_PASS,
        .req_bits  (c_req_bits),
        .req_eos   (c_req_eos),
        .req_eoss  (c_req_eoss),
        .req_valid (c_req_valid),
        .req_ready (c_req_ready),
        .req_addr  (c_req_addr),
        .req_rden  (c_req_rden),
        .req_tag   (c_req_tag)
    );

    // CFB's requests pass a skid buffer: CFB advances on the skid's registered
    // ready, so the memory's ready (and what feeds it) never reaches CFB's
    // traversal counters in the same cycle. One cycle of latency. CFB's ready
    // is a register of its own in ADV_N copies (u_cfb_ready): the skid's
    // next ready (in_ready_nx), with BEATS = 1 ANDed with the bits FIFO's.
    wire             s_req_valid, s_req_ready, s_ready_nx;
    wire             unused_req_ready_cp;   // (s_req_ready is its copy)
    wire             unused_req_nx_valid;
    wire [P*ADDR_W+P+TAG_W-1:0] unused_req_nx_data;
    wire             unused_req_valid_cp;   // (mem_req_valid is its copy)
    cube4_skid_peek #(
        .DATA_W  (P * ADDR_W + P + TAG_W)
    ) u_req_skid (
        .clk         (clk),
        .rst         (rst),
        .in_valid    (s_req_valid),
        .in_ready    (s_req_ready),
        .in_data     ({c_req_addr, c_req_rden, c_req_tag}),
        .out_valid   (mem_req_valid),
        .out_ready   (mem_req_ready),
        .out_data    ({mem_req_addr, mem_req_rden, mem_req_tag}),
        .nx_valid    (unused_req_nx_valid),
        .nx_data     (unused_req_nx_data),
        .in_ready_cp (unused_req_ready_cp),
        .in_ready_nx (s_ready_nx),
        .out_valid_cp (unused_req_valid_cp)
    );
    wire unused_req_nx = ^{unused_req_nx_valid, unused_req_nx_data, unused_req_ready_cp, unused_req_valid_cp};

    // CFB's ready: every request waits for room in the request skid and (BEATS
    // = 1) the bits FIFO, so CFB's ready is the AND of both buffers' in_ready,
    // registered here as the AND of their next values, ADV_N copies: each
    // copy one flip-flop beside its group of CFB's loads, no logic between
    // (the AND of two copies, one beside each buffer, was a LUT routed across
    // the die into CFB's beat stages on the crop beat build)
    wire k_ready, k_ready_nx;           // the bits FIFO's ready and its next value (1 without BEATS)
    cube4_prim_copies #(.N (ADV_N), .RST_VAL (64'd1)) u_cfb_ready (
        .clk (clk), .rst (rst), .d (s_ready_nx && k_ready_nx), .q (c_req_ready));
`ifndef SYNTHESIS
    always @(posedge clk) begin
        if (!rst && c_req_ready != {ADV_N{s_req_ready && k_ready}})
            $fatal(1, "cube4_frontend: CFB's ready %b is not the buffers' (%b, %b)",
                   c_req_ready, s_req_ready, k_ready);
    end
`endif

    // ---- TRI ----
    cube4_tri #(
        .P           (P),
        .VOXEL_W     (VOXEL_W),
        .WEIGHT_W    (WEIGHT_W),
        .MAX_DIM     (MAX_DIM),
        .MAX_SS_LOG2 (MAX_SS_LOG2),
        .CLIP        (CLIP),
        .SLAB        (SLAB),
        .VGRAD       (VGRAD),
        .LABELS      (LABELS)
    ) u_tri (
        .clk        (clk),
        .rst        (rst),
        .cfg        (cfg),
        .in_valid   (mem_rsp_valid),
        .in_ready   (mem_rsp_ready),
        .in_tag     (mem_rsp_tag),
        .in_data    (mem_rsp_data),
        .out_valid  (smp_valid),
        .out_ready  (smp_ready),
        .out_hdr    (smp_hdr),
        .out_sample (smp_sample)
    );

    // ---- BEATS = 1: each emitted beat's position bits and EOS wait beside the
    // memory and TRI in a FIFO (every request waits for room in it), and
    // leave with its sample beat. The FIFO is cube4_ram_fifo (OUT_REG): the
    // sample stream's ready, a register at the far end of the die (cube4_top's
    // skid buffer), reaches only its register queue, not the RAM's read
    // address (the memory's and TRI's latency hide its three cycles) ----
    generate
        if (BEATS != 0) begin : g_bits
            wire emits = c_req_tag[TAG_EMIT];
            wire b_valid;
            wire unused_k_ready_cp;     // (k_ready is its copy)
            // the request forks to the memory's skid buffer and, its bits, to the
            // FIFO's skid beside it (CFB advances on registers beside it), and they
            // leave through its skid beside TRI's output, which the sample beat's
            // departure pops (cube4_skid_fifo: its block RAM lies elsewhere). Every
            // request waits for room in the FIFO, one that emits no sample beat
            // too: CFB's ready is then a register (u_cfb_ready), not a function
            // of the request's tag
            assign s_req_valid = c_req_valid && k_ready;
            wire b_valid_cp;            // (b_valid is its copy)
            cube4_skid_fifo #(.DATA_W (4 * P + 2), .DEPTH (BITS_DEPTH), .RAM (1), .OUT_REG (1)) u_bits (
                .clk (clk), .rst (rst),
                .in_valid (c_req_valid && s_req_ready && emits), .in_ready (k_ready),
                .in_data ({c_req_eoss, c_req_eos, c_req_bits}),
                .out_valid (b_valid), .out_ready (smp_valid && smp_ready),
                .out_data ({smp_eoss, smp_eos, smp_bits}), .in_ready_cp (unused_k_ready_cp),
                .in_ready_nx (k_ready_nx), .out_valid_cp (b_valid_cp));
            wire unused_bits = ^{b_valid, unused_k_ready_cp, b_valid_cp};
`ifndef SYNTHESIS
            // a sample beat always finds its bits: they wait beside the memory and TRI
            always @(posedge clk) begin
                if (!rst && smp_valid && smp_ready && !b_valid) begin
                    $error("cube4_frontend: a sample beat left before its position bits reached their FIFO");
                    $fatal(1, "cube4_frontend: beat bits out of step");
                end
            end
`endif
        end else begin : g_no_bits
            assign s_req_valid = c_req_valid;
            assign k_ready     = 1'b1;
            assign k_ready_nx  = 1'b1;
            assign {smp_eoss, smp_eos, smp_bits} = '0;
            wire unused_s_ready = s_req_ready;   // (the bits FIFO's fork only)
            wire unused_bits = ^{c_req_bits, c_req_eos, c_req_eoss};
        end
    endgenerate

    // ---- frame control: busy from start until the last sample beat ----
    cube4_frame_ctl u_frame (
        .clk       (clk),
        .rst       (rst),
        .start     (start),
        .last_beat (smp_valid && smp_ready && smp_hdr[HDR_CTRL + CTRL_EOP]),
        .busy      (busy),
        .done      (done),
        .cycles    (cycles)
    );

endmodule
`default_nettype wire

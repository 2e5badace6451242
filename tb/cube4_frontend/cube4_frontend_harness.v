`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_frontend_harness  (simulation only)
// -----------------------------------------------------------------------------
// Purpose
//   Test harness around cube4_frontend: a Verilog clock, cube4_voxel_mem, a
//   loader that streams a $readmemh image through the memory's load port,
//   random stall injection (cube4_sim_stall) on the memory request, the memory
//   response and the sample output, and a dump of every sample beat to a text
//   file. Python sets registers, pulses load / start and waits for load_done /
//   done; it never touches individual clocks, so a 128^3 frame simulates at the
//   speed of the compiled model.
//
//   Plusargs: +CUBE4_MEMFILE=<path>  image, one hex word per line, line
//             a*P + q = bank q, word a (golden/cube4/memory.py);
//             +CUBE4_DUMP=<path>     sample dump, one line per beat:
//             "m j pb skew ctrl lane_valid lane_inside samples {gi,gj,gk}" (all but
//             the first four in hex; gradients zero unless OPT_GRA),
//             after a line "start" at every frame start (flushed at done).
//             Input dump_en = 0 leaves the sample lines out (speed measurements).
//
// Parameters: as cube4_frontend, plus DEPTH (words per bank).
// =============================================================================
module cube4_frontend_harness #(
    `CUBE4_BUILD_PARAMS,
    parameter integer DEPTH       = 4096,
    parameter integer OPT_GRA     = 0,    // 1: cube4_gra after the front end, gradients dumped too
    `CUBE4_ADDR_LAYOUT,
    `CUBE4_TAG_LAYOUT,
    `CUBE4_RECT_LAYOUT,
    localparam integer GRAD_W = VOXEL_W + 5,
    localparam integer BLOCK_LOG2 = 2,
    `CUBE4_STOP_LAYOUT,
    `CUBE4_BLOCK_LAYOUT
) (
    `CUBE4_VIEW_PORTS
    `CUBE4_ADDR_PORTS
    `CUBE4_RECT_PORTS
    input  wire                  rect_we,     // write the rt_* fields as entry rect_addr
    input  wire [M_W-1:0]        rect_addr,
    `CUBE4_BEATS_IN_PORTS,                    // BEATS = 1: the decisions' tables, COM's reports
    output wire [31:0]           eos_count,   // BEATS = 1: sample beats with EOS taken this frame
    output wire                  clk,
    input  wire                  rst,
    // loader
    input  wire                  load,        // pulse: read the image file, stream it in
    input  wire [31:0]           load_words,  // words per bank to load
    output wire                  load_done,   // level: the last load finished
    // stall injection, probability /256 per port and cycle; seed: the test's
    // random seed (COCOTB_RANDOM_SEED), taken at reset
    input  wire [31:0]           seed,
    input  wire [7:0]            stall_req,
    input  wire [7:0]            stall_rsp,
    input  wire [7:0]            stall_out,
    input  wire                  dump_en,     // write sample beats to the dump file
    // frame
    input  wire                  start,
    output wire                  busy,
    output wire                  done,
    output wire [31:0]           cycles,
    output wire [31:0]           beats  // sample beats of the last frame
);
    cube4_sim_clock u_clock (.clk(clk));

    // ------------------------------------------------------------ input registers
    // Every input Python drives is registered once, so no logic of the design
    // depends combinationally on a top-level input: Verilator evaluates such logic
    // on every eval() (twice per clock with the Verilog clock). Python sees a
    // one-cycle delay on every input, which it never depends on.
    reg              rst_q;
    reg              load_q;
    reg [31:0]       load_words_q;
    reg [7:0]        stall_req_q;
    reg [7:0]        stall_rsp_q;
    reg [7:0]        stall_out_q;
    reg              dump_en_q;
    reg              start_q;
    reg [31:0]       seed_q;
    // the register ports as the design's buses (cube4_defs.vh); the front end
    // has no use for SX and SY
    reg [VIEW_W-1:0]     cfg_q;
    reg [ADR_W_ALL-1:0]  cfg_addr_q;
    reg                  rect_we_q;
    reg [M_W-1:0]        rect_addr_q;
    reg [RECT_W-1:0]     rect_data_q;
    localparam integer BT_W = 3 * DIM_W + 4 + 2 * BK_W + NBK + STOP_AW + 2 * P * M_W + 3 * DIM_W + PB_W + P + M_W;
    reg [BT_W-1:0]       bt_q;
    always @(posedge clk) begin
        rst_q         <= rst;
        load_q        <= load;
        load_words_q  <= load_words;
        seed_q        <= seed;
        stall_req_q   <= stall_req;
        stall_rsp_q   <= stall_rsp;
        stall_out_q   <= stall_out;
        dump_en_q     <= dump_en;
        start_q       <= start;
        cfg_q         <= `CUBE4_VIEW_PACK;
        cfg_addr_q    <= `CUBE4_ADDR_PACK;
        rect_we_q     <= rect_we;
        rect_addr_q   <= rect_addr;
        rect_data_q   <= `CUBE4_RECT_PACK;
        bt_q          <= {blk_base, nbr_en, blk_we, blk_addr, blk_data, tab_we, tab_addr, tab_data,
                          rep_valid, rep_j, rep_pb, rep_stx, rep_sty, rep_en, rep_end, com_m};
    end
    wire [3*DIM_W-1:0] blk_base_q;
    wire               nbr_en_q, blk_we_q, tab_we_q, rep_valid_q;
    wire [2*BK_W-1:0]  blk_addr_q;
    wire [NBK-1:0]     blk_data_q;
    wire [STOP_AW-1:0] tab_addr_q;
    wire [P*M_W-1:0]   tab_data_q, rep_end_q;
    wire [DIM_W-1:0]   rep_j_q, rep_stx_q, rep_sty_q;
    wire [PB_W-1:0]    rep_pb_q;
    wire [P-1:0]       rep_en_q;
    wire [M_W-1:0]     com_m_q;
    assign {blk_base_q, nbr_en_q, blk_we_q, blk_addr_q, blk_data_q, tab_we_q, tab_addr_q, tab_data_q,
            rep_valid_q, rep_j_q, rep_pb_q, rep_stx_q, rep_sty_q, rep_en_q, rep_end_q, com_m_q} = bt_q;

    localparam integer PV = P * VOXEL_W;

    // ------------------------------------------------------------ loader
    reg [VOXEL_W-1:0] img [0:P*DEPTH-1];
    string            memfile;
    integer           dump_fd;
    reg               load_busy_q, load_done_q;
    reg [31:0]        load_addr_q;
    reg [PV-1:0]      ld_data;
    integer           b;

    initial begin
        if (!$value$plusargs("CUBE4_MEMFILE=%s", memfile)) memfile = "cube4_mem.hex";
        begin : open_dump
            string dumpfile;
            if (!$value$plusargs("CUBE4_DUMP=%s", dumpfile)) dumpfile = "cube4_samples.txt";
            dump_fd = $fopen(dumpfile, "w");
        end
    end

    always @(posedge clk) begin
        if (rst_q) begin
            load_busy_q <= 1'b0;
            load_done_q <= 1'b0;
        end else if (load_q && !load_busy_q) begin
            $readmemh(memfile, img);
            load_busy_q <= 1'b1;
            load_done_q <= 1'b0;
            load_addr_q <= 32'd0;
        end else if (load_busy_q) begin
            if (load_addr_q + 32'd1 >= load_words_q) begin
                load_busy_q <= 1'b0;
                load_done_q <= 1'b1;
            end
            load_addr_q <= load_addr_q + 32'd1;
        end
    end
    always @(*) begin
        for (b = 0; b < P; b = b + 1) begin
            ld_data[b*VOXEL_W +: VOXEL_W] = img[load_addr_q * P + b];
        end
    end
    assign load_done = load_done_q;

    // ------------------------------------------------------------ front end
    wire              req_valid, req_ready, req_valid_m, req_ready_m;
    wire [P*ADDR_W-1:0] req_addr, req_addr_m;
    wire [P-1:0]      req_rden, req_rden_m;
    wire [TAG_W-1:0]  req_tag, req_tag_m;
    wire              rsp_valid_m, rsp_ready_m, rsp_valid, rsp_ready;
    wire [PV-1:0]     rsp_data_m, rsp_data;
    wire [TAG_W-1:0]  rsp_tag_m, rsp_tag;
    wire              smp_valid_f, smp_ready_f;
    wire              unused_fe_busy, unused_fe_done;
    wire [31:0]       unused_fe_cycles;
    wire [HDR_W-1:0]  smp_hdr;
    wire [PV-1:0]     smp_sample;

    wire [4*P-1:0]    smp_bits;
    wire              smp_eos, smp_eoss;
    cube4_frontend #(
        `CUBE4_BUILD_PASS
    ) u_fe (
        .clk             (clk),
        .rst             (rst_q),
        .start           (start_q),
        .busy            (unused_fe_busy),
        .done            (unused_fe_done),
        .cycles          (unused_fe_cycles),
        .cfg             (cfg_q),
        .cfg_addr        (cfg_addr_q),
        .rect_we         (rect_we_q),
        .rect_addr       (rect_addr_q),
        .rect_data       (rect_data_q),
        .blk_base        (blk_base_q),
        .nbr_en          (nbr_en_q),
        .blk_we          (blk_we_q),
        .blk_addr        (blk_addr_q),
        .blk_data        (blk_data_q),
        .tab_we          (tab_we_q),
        .tab_addr        (tab_addr_q),
        .tab_data        (tab_data_q),
        .rep_valid       (rep_valid_q),
        .rep_j           (rep_j_q),
        .rep_pb          (rep_pb_q),
        .rep_stx         (rep_stx_q),
        .rep_sty         (rep_sty_q),
        .rep_en          (rep_en_q),
        .rep_end         (rep_end_q),
        .com_m           (com_m_q),
        .smp_bits        (smp_bits),
        .smp_eos         (smp_eos),
        .smp_eoss        (smp_eoss),
        .mem_req_valid   (req_valid),
        .mem_req_ready   (req_ready),
        .mem_req_addr    (req_addr),
        .mem_req_rden    (req_rden),
        .mem_req_tag     (req_tag),
        .mem_rsp_valid   (rsp_valid),
        .mem_rsp_ready   (rsp_ready),
        .mem_rsp_data    (rsp_data),
        .mem_rsp_tag     (rsp_tag),
        .smp_valid       (smp_valid_f),
        .smp_ready       (smp_ready_f),
        .smp_hdr         (smp_hdr),
        .smp_sample      (smp_sample)
    );

    // request: front end -> stall -> memory
    cube4_sim_stall #(
        .DATA_W (P * ADDR_W + P + TAG_W),
        .STREAM (0)
    ) u_stall_req (
        .clk       (clk),
        .rst       (rst_q),
        .seed      (seed_q),
        .stall     (stall_req_q),
        .in_valid  (req_valid),
        .in_ready  (req_ready),
        .in_data   ({req_addr, req_rden, req_tag}),
        .out_valid (req_valid_m),
        .out_ready (req_ready_m),
        .out_data  ({req_addr_m, req_rden_m, req_tag_m})
    );

    wire unused_ld_ready;   // always 1: the loader writes one word per bank per cycle
    cube4_voxel_mem #(
        .P       (P),
        .WORD_W  (VOXEL_W),
        .DEPTH   (DEPTH),
        .ADDR_W  (ADDR_W),
        .TAG_W   (TAG_W)
    ) u_mem (
        .clk       (clk),
        .rst       (rst_q),
        .ld_valid  (load_busy_q),
        .ld_ready  (unused_ld_ready),
        .ld_addr   (load_addr_q[ADDR_W-1:0]),
        .ld_data   (ld_data),
        .req_valid (req_valid_m),
        .req_ready (req_ready_m),
        .req_addr  (req_addr_m),
        .req_rden  (req_rden_m),
        .req_tag   (req_tag_m),
        .rsp_valid (rsp_valid_m),
        .rsp_ready (rsp_ready_m),
        .rsp_data  (rsp_data_m),
        .rsp_tag   (rsp_tag_m)
    );

    // response: memory -> stall -> front end
    cube4_sim_stall #(
        .DATA_W (PV + TAG_W),
        .STREAM (1)
    ) u_stall_rsp (
        .clk       (clk),
        .rst       (rst_q),
        .seed      (seed_q),
        .stall     (stall_rsp_q),
        .in_valid  (rsp_valid_m),
        .in_ready  (rsp_ready_m),
        .in_data   ({rsp_data_m, rsp_tag_m}),
        .out_valid (rsp_valid),
        .out_ready (rsp_ready),
        .out_data  ({rsp_data, rsp_tag})
    );

    // ------------------------------------------------------------ optional GRA
    wire              snk_valid, snk_ready;
    wire [HDR_W-1:0]  snk_hdr;
    wire [PV-1:0]     snk_sample;
    wire [3*P*GRAD_W-1:0] snk_grad;   // {gi, gj, gk}, zero without GRA

    generate
        if (OPT_GRA != 0) begin : g_gra
            cube4_gra #(
                .P           (P),
                .VOXEL_W     (VOXEL_W),
                .WEIGHT_W    (WEIGHT_W),
                .MAX_DIM     (MAX_DIM),
                .MAX_SS_LOG2 (MAX_SS_LOG2),
                .RECTS       (RECTS)
            ) u_gra (
                .clk        (clk),
                .rst        (rst_q),
                .cfg        (cfg_q),
                .in_valid   (smp_valid_f),
                .in_ready   (smp_ready_f),
                .in_hdr     (smp_hdr),
                .in_sample  (smp_sample),
                .in_eoss    (1'b0),                // (GRA's beat build runs in cube4_top)
                .out_valid  (snk_valid),
                .out_ready  (snk_ready),
                .out_hdr    (snk_hdr),
                .out_sample (snk_sample),
                .out_gi     (snk_grad[2*P*GRAD_W +: P*GRAD_W]),
                .out_gj     (snk_grad[P*GRAD_W +: P*GRAD_W]),
                .out_gk     (snk_grad[0 +: P*GRAD_W])
            );
        end else begin : g_no_gra
            assign snk_valid   = smp_valid_f;
            assign smp_ready_f = snk_ready;
            assign snk_hdr     = smp_hdr;
            assign snk_sample  = smp_sample;
            assign snk_grad    = {(3*P*GRAD_W){1'b0}};
        end
    endgenerate
    // the beat build's bits, EOS and EOSS go straight to the sink (not with GRA behind it)
    wire [4*P+1:0]    snk_bits = (OPT_GRA != 0) ? '0 : {smp_eoss, smp_eos, smp_bits};
    wire [P-1:0]      snk_lins = snk_hdr[HDR_INSIDE +: P];
    wire [P-1:0]      snk_lval = snk_hdr[HDR_LVALID +: P];
    wire [6:0]        snk_ctrl = snk_hdr[HDR_CTRL +: 7];
    wire [LANE_W-1:0] snk_skew = snk_hdr[HDR_SKEW +: LANE_W];
    wire [PB_W-1:0]   snk_pb   = snk_hdr[HDR_PB +: PB_W];
    wire [DIM_W-1:0]  snk_j    = snk_hdr[HDR_J +: DIM_W];
    wire [M_W-1:0]    snk_m    = snk_hdr[HDR_M +: M_W];

    // ------------------------------------------------------------ stream checks
    // (cube4_stream_check) on the front end's request, on its response input and
    // on the stream the sink takes (samples, or GRA's gradients)
    cube4_stream_check #(.NAME ("frontend.mem_req"), .DATA_W (P * ADDR_W + P + TAG_W)) u_chk_req (
        .clk (clk), .rst (rst_q), .valid (req_valid), .ready (req_ready),
        .data ({req_addr, req_rden, req_tag}));
    cube4_stream_check #(.NAME ("frontend.mem_rsp"), .DATA_W (PV + TAG_W)) u_chk_rsp (
        .clk (clk), .rst (rst_q), .valid (rsp_valid), .ready (rsp_ready),
        .data ({rsp_data, rsp_tag}));
    cube4_stream_check #(.NAME ("frontend.out"), .DATA_W (HDR_W + PV + 3 * P * GRAD_W)) u_chk_out (
        .clk (clk), .rst (rst_q), .valid (snk_valid), .ready (snk_ready),
        .data ({snk_hdr, snk_sample, snk_grad}));

    // ------------------------------------------------------------ sink
    // random ready, dump every accepted beat; the frame ends with the eop beat
    reg  [15:0] lfsr_q;
    wire [15:0] snk_mix = seed_q[15:0] ^ seed_q[31:16] ^ 16'h5A5A;   // the sink's stall pattern
    reg  [31:0] beats_q, cycles_q, eos_q;
    reg        busy_q;
    always @(posedge clk) begin
        if (rst_q) lfsr_q <= (snk_mix == 16'h0) ? 16'h5A5A : snk_mix;
        else     lfsr_q <= {lfsr_q[14:0], lfsr_q[15] ^ lfsr_q[13] ^ lfsr_q[12] ^ lfsr_q[10]};
    end
    assign snk_ready = (lfsr_q[7:0] >= stall_out_q);
    wire last_beat = snk_valid && snk_ready && snk_ctrl[CTRL_EOP];

    always @(posedge clk) begin
        if (rst_q) begin
            beats_q  <= 32'd0;
            cycles_q <= 32'd0;
            eos_q    <= 32'd0;
            busy_q   <= 1'b0;
        end else begin
            if (start_q && !busy_q) begin
                beats_q  <= 32'd0;
                eos_q    <= 32'd0;
                cycles_q <= 32'd1;
                busy_q   <= 1'b1;
                $fwrite(dump_fd, "start\n");   // frame marker: the reader takes what follows the last one
            end else if (busy_q) begin
                cycles_q <= cycles_q + 32'd1;
                if (last_beat) busy_q <= 1'b0;
            end
            if (snk_valid && snk_ready) begin
                beats_q <= beats_q + 32'd1;
                if (snk_bits[4*P]) eos_q <= eos_q + 32'd1;
                if (dump_en_q) $fwrite(dump_fd, "%0d %0d %0d %0d %h %h %h %h %h %h\n", snk_m, snk_j, snk_pb, snk_skew,
                        snk_ctrl, snk_lval, snk_lins, snk_sample, snk_grad, snk_bits);
                if (last_beat) $fflush(dump_fd);
            end
        end
    end
    assign beats  = beats_q;
    assign eos_count = eos_q;
    assign busy   = busy_q;
    assign done   = busy_q && last_beat;
    assign cycles = cycles_q;

endmodule
`default_nettype wire

`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_dram_fetch
// -----------------------------------------------------------------------------
// Purpose
//   The voxel memory of a DRAM build: the ports of cube4_voxel_mem (a load
//   port, and read requests of one address per bank) in front of a DRAM
//   controller's native port (LiteDRAM's: 128-bit words, one BL8 burst of a x16
//   DDR3 chip; commands, write data and read data as streams; read data in
//   command order, never held back).
//
//   Layout. The memory image is golden/cube4/memory.py's, unchanged: column a
//   is word a of every bank (P words, COL_W = P * WORD_W bits). A DRAM word
//   (a burst) holds L = 2^floor(log2(128 / COL_W)) consecutive columns:
//   column a lies in burst a >> LOG_L at bits (a mod L) * COL_W, bank q's
//   word at q * WORD_W within the column (the rest of a burst is unused when
//   COL_W * L < 128). Where the beam axis i is the memory's x (every view
//   whose major axis is y or z), a beat reads one column, or two consecutive
//   ones when the partial beam starts inside a block of P, and consecutive
//   beats read consecutive columns: a burst serves L beats.
//
//   Reads. Each request resolves its banks' columns against NS slots, the
//   bursts read most recently: NS = max(P, ROW_BURSTS + 1), ROW_BURSTS =
//   ceil((ceil(MAX_DIM / P) + 1) / L) + 1 the most bursts a row of beats
//   touches. A beat's banks need at most P bursts; a row whose neighbour row
//   starts in the burst where it ends (rows contiguous in memory, traversed
//   backwards) finds that burst still in a slot. A burst in no slot is read from the DRAM into a slot (one read
//   command per cycle), the victim being the first slot from a rotating
//   pointer that no bank of the request uses; a request whose banks miss
//   one burst or none takes one cycle. The request's descriptor (for each
//   bank: its slot and column; the slots filled, in order) goes through a
//   queue to the response side, which takes the read data in the same order
//   into the same slots and assembles the response: bank q's word from its
//   slot (or from the read data arriving in that cycle), 0 where not read.
//   Both sides run the same rule on the same requests, so the response side
//   needs no addresses. Reads in flight plus read data waiting are at most
//   RD_DEPTH (the read data queue's size): the controller's read data is
//   always accepted. Loading any column invalidates every slot.
//
//   Resets. rst (the pipelines' reset, at any time, in mid-frame too) drops
//   every request and descriptor; reads already issued still return, so the
//   count of reads owed and the read data queue belong to the DRAM port and
//   are reset by dram_rst (the port's reset, with the controller's), and rst
//   only starts a drain of the words owed then. The load state machine (a
//   command, then its data) is the port's protocol: dram_rst resets it too.
//
//   Load. Columns come in address order; a burst is written (a command, then
//   its data, all bytes enabled) when its last column (a mod L = L - 1)
//   arrives, so the host loads whole bursts (pads the image to a multiple of
//   L columns). Loads are meant for use between frames (as cube4_voxel_mem's).
//
// Parameters
//   P          banks.                             1..16, P * WORD_W <= 128.  Default 8.
//   MAX_DIM    the longest row of beats, in voxels. 2..2048.  Default 256.
//   WORD_W     word width.                        1..128.    Default 8.
//   ADDR_W     column address width.              1..30.     Default 16.
//   TAG_W      request tag width.                 1..4096.   Default 8.
//   DRAM_AW    the native port's address width    1..32.     Default 21.
//              (128-bit words); ADDR_W - LOG_L <= DRAM_AW.
//   RD_DEPTH   reads in flight and waiting; power of two >= P. 2..1024. Default 32.
//   DESC_DEPTH descriptors queued; power of two.            2..1024. Default 128.
//              Requests in flight: enough for the DRAM's latency (about 50
//              pipeline cycles) when a burst serves L = 16 requests (P = 1).
//
// Latency
//   From an accepted request to rsp_valid: 4 cycles when its bursts are in
//   the slots (input skid, compare stage, resolve stage, response register); a
//   read's DRAM latency more when not. The compare stage registers each bank's
//   burst against every slot (P * NS compares) and against every other bank's;
//   the resolve stage keeps those bits up to date as its own misses fill slots,
//   and a request entering the compare stage sees the slot filled in that cycle. Full rate while each request misses at most one burst, the
//   DRAM keeps up and rsp_ready is high. req_ready is a register (cube4_skid).
//
// Ports
//   clk, rst, dram_rst   clock; synchronous active-high resets (above)
//   ld_valid/ld_ready, ld_addr [ADDR_W], ld_data [P*WORD_W]   load (as cube4_voxel_mem)
//   req_valid/req_ready, req_addr [P*ADDR_W], req_rden [P], req_tag [TAG_W]
//   rsp_valid/rsp_ready, rsp_data [P*WORD_W] (0 where not read), rsp_tag
//   dram_cmd_valid/ready, dram_cmd_we, dram_cmd_addr [DRAM_AW]   native port commands
//   dram_wdata_valid/ready, dram_wdata_data [128], dram_wdata_we [16]  write data
//   dram_rdata_valid/ready, dram_rdata_data [128]                read data (ready is 1)
//
// Bit growth and rounding: none (storage only).
// =============================================================================
module cube4_dram_fetch #(
    parameter integer P          = 8,
    parameter integer MAX_DIM    = 256,
    parameter integer WORD_W     = 8,
    parameter integer ADDR_W     = 16,
    parameter integer TAG_W      = 8,
    parameter integer DRAM_AW    = 21,
    parameter integer RD_DEPTH   = 32,
    parameter integer DESC_DEPTH = 128,
    localparam integer DATA_W = 128,                 // the native port's word: one BL8 burst of x16
    localparam integer COL_W  = P * WORD_W,
    localparam integer LOG_L  = $clog2(DATA_W / COL_W + 1) - 1,   // floor(log2(128 / COL_W))
    localparam integer L      = 1 << LOG_L,
    localparam integer OFF_W  = (LOG_L > 0) ? LOG_L : 1,
    localparam integer BA_W   = (ADDR_W > LOG_L) ? ADDR_W - LOG_L : 1,
    localparam integer ROW_BURSTS = ((MAX_DIM + P - 1) / P + 1 + L - 1) / L + 1,
    localparam integer NS     = (P > ROW_BURSTS + 1) ? P : ROW_BURSTS + 1,
    localparam integer SL_W   = $clog2(NS),
    localparam integer NF_W   = $clog2(P + 1),
    localparam integer FI_W   = (P > 1) ? $clog2(P) : 1,
    localparam integer DESC_W = TAG_W + P + P * SL_W + P * OFF_W + NF_W + P * SL_W
) (
    input  wire                  clk,
    input  wire                  rst,
    input  wire                  dram_rst,
    // load port (a column: a word per bank), read requests and responses (cube4_voxel_mem's)
    `CUBE4_VOXEL_MEM_PORTS,
    // the DRAM controller's native port (DATA_W = 128 bits a word)
    `CUBE4_DRAM_PORTS
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_dram_fetch", "P", P, 1, 16)
        `CUBE4_RANGE(g_bad_word_w, "cube4_dram_fetch", "WORD_W", WORD_W, 1, 128)
        `CUBE4_RANGE(g_bad_max_dim, "cube4_dram_fetch", "MAX_DIM", MAX_DIM, 2, 2048)
        `CUBE4_RANGE(g_bad_addr_w, "cube4_dram_fetch", "ADDR_W", ADDR_W, 1, 30)
        `CUBE4_RANGE(g_bad_dram_aw, "cube4_dram_fetch", "DRAM_AW", DRAM_AW, 1, 32)
        if (COL_W > DATA_W) begin : g_bad_col
            $error("cube4_dram_fetch: a column of P * WORD_W = %0d bits does not fit a 128-bit burst", COL_W);
        end
        if (BA_W > DRAM_AW) begin : g_bad_space
            $error("cube4_dram_fetch: %0d-bit burst addresses do not fit DRAM_AW = %0d", BA_W, DRAM_AW);
        end
        if (RD_DEPTH < 2 || RD_DEPTH > 1024 || (RD_DEPTH & (RD_DEPTH - 1)) != 0 || RD_DEPTH < P) begin : g_bad_rd_depth
            $error("cube4_dram_fetch: RD_DEPTH = %0d must be a power of two in 2..1024, at least P", RD_DEPTH);
        end
    endgenerate

    localparam integer RC_W = $clog2(RD_DEPTH) + 1;
    integer q, s, k;

    // ---------------------------------------------------------------- load
    localparam [1:0] LD_IDLE = 2'd0, LD_CMD = 2'd1, LD_DATA = 2'd2;
    reg [1:0]        ld_st_q;
    reg [DATA_W-1:0] asm_q;
    reg [BA_W-1:0]   ld_ba_q;
    wire [OFF_W-1:0] ld_off = (LOG_L > 0) ? OFF_W'(ld_addr) : {OFF_W{1'b0}};
    wire             ld_fire = ld_valid && ld_ready;
    assign ld_ready = (ld_st_q == LD_IDLE) && !dram_rst;
    always @(posedge clk) begin
        if (ld_fire) begin
            asm_q[ld_off * COL_W +: COL_W] <= ld_data;
            ld_ba_q <= BA_W'(ld_addr >> LOG_L);
        end
    end
    wire ld_cmd_valid = (ld_st_q == LD_CMD);
    always @(posedge clk) begin
        if (dram_rst) begin
            ld_st_q  <= LD_IDLE;
        end else begin
            case (ld_st_q)
                LD_IDLE: if (ld_fire && ld_off == OFF_W'(L - 1)) ld_st_q <= LD_CMD;
                LD_CMD:  if (dram_cmd_ready) ld_st_q <= LD_DATA;
                LD_DATA: if (dram_wdata_ready) ld_st_q <= LD_IDLE;
                default: ld_st_q <= LD_IDLE;
            endcase
        end
    end
    assign dram_wdata_valid = (ld_st_q == LD_DATA);
    assign dram_wdata_data  = asm_q;
    assign dram_wdata_we    = {(DATA_W/8){1'b1}};

    // ---------------------------------------------------------------- issue side
    wire                r_valid;
    reg                 r_ready;
    wire [TAG_W-1:0]    r_tag;
    wire [P-1:0]        r_rden;
    wire [P*ADDR_W-1:0] r_addr;
    cube4_skid #(.DATA_W(TAG_W + P + P * ADDR_W)) u_req (
        .clk       (clk),
        .rst       (rst),
        .in_valid  (req_valid),
        .in_ready  (req_ready),
        .in_data   ({req_tag, req_rden, req_addr}),
        .out_valid (r_valid),
        .out_ready (r_ready),
        .out_data  ({r_tag, r_rden, r_addr})
    );

    reg [BA_W-1:0]   slot_ba_q [0:NS-1];
    reg [NS-1:0]     slot_vld_q;
    reg [NS-1:0]     rr_mask_q;       // the rotating pointer as a mask: slots at or above it
    reg [NF_W-1:0]   nfill_q;
    reg [SL_W-1:0]   fill_q [0:P-1];
    reg [RC_W-1:0]   owed_q;          // reads issued whose data the response side has not taken

    // Compare stage: each bank's burst against every slot and against every other bank's,
    // registered with the request (s_*). A slot written in that cycle (a miss of the
    // request in the resolve stage) is compared by the burst written.
    reg [BA_W-1:0]   c_ba [0:P-1];
    reg [P*NS-1:0]   c_hitv;          // bank q holds its burst in slot s: bit q*NS + s
    reg [P*P-1:0]    c_eq;            // banks q and r read the same burst: bit q*P + r
    reg              s_valid_q;
    reg [TAG_W-1:0]  s_tag_q;
    reg [P-1:0]      s_rden_q;
    reg [P*ADDR_W-1:0] s_addr_q;
    reg [P*NS-1:0]   s_hitv_q;
    reg [P*P-1:0]    s_eq_q;
    wire             c_take;
    wire             rd_fire;
    wire             inval = ld_cmd_valid && dram_cmd_ready;   // a load invalidates every slot
    reg [BA_W-1:0]   want;
    reg [SL_W-1:0]   victim;
    always @(*) begin
        for (q = 0; q < P; q = q + 1)
            c_ba[q] = BA_W'(r_addr[q*ADDR_W +: ADDR_W] >> LOG_L);
        for (q = 0; q < P; q = q + 1) begin
            for (s = 0; s < NS; s = s + 1)
                c_hitv[q*NS + s] = !inval && ((rd_fire && SL_W'(s) == victim) ? (c_ba[q] == want)
                                                                              : (slot_vld_q[s] && slot_ba_q[s] == c_ba[q]));
            for (k = 0; k < P; k = k + 1)
                c_eq[q*P + k] = (c_ba[q] == c_ba[k]);
        end
    end

    // Resolve stage: the request in s_*, its hit vectors kept up to date as its misses fill slots
    reg [OFF_W-1:0]  off  [0:P-1];
    reg [P-1:0]      hit;
    reg [SL_W-1:0]   hit_slot [0:P-1];
    reg [NS-1:0]     used;
    reg [P-1:0]      pend, first, same;
    reg              any_pend, found, single;
    always @(*) begin
        used = {NS{1'b0}};
        for (q = 0; q < P; q = q + 1) begin
            off[q] = (LOG_L > 0) ? OFF_W'(s_addr_q[q*ADDR_W +: ADDR_W]) : {OFF_W{1'b0}};
            hit[q] = |s_hitv_q[q*NS +: NS];
            hit_slot[q] = {SL_W{1'b0}};
            for (s = 0; s < NS; s = s + 1)
                if (s_hitv_q[q*NS + s]) hit_slot[q] = SL_W'(s);
            if (s_rden_q[q]) used = used | s_hitv_q[q*NS +: NS];
        end
        pend = s_rden_q & ~hit;
        any_pend = |pend;
        // the first bank that misses names the burst to read
        first = {P{1'b0}};
        found = 1'b0;
        want = {BA_W{1'b0}};
        for (q = 0; q < P; q = q + 1) begin
            if (pend[q] && !found) begin
                first[q] = 1'b1;
                want = BA_W'(s_addr_q[q*ADDR_W +: ADDR_W] >> LOG_L);
                found = 1'b1;
            end
        end
        // the banks that read the first missing bank's burst
        for (q = 0; q < P; q = q + 1)
            same[q] = |(s_eq_q[q*P +: P] & first);
        single = ((pend & ~same) == {P{1'b0}});
        // the first slot at or above the pointer that no bank of this request uses, else the
        // first one below it (two priority encoders, no arithmetic on the pointer)
        victim = {SL_W{1'b0}};
        for (k = NS - 1; k >= 0; k = k - 1) begin
            if (!used[k]) victim = SL_W'(k);
        end
        for (k = NS - 1; k >= 0; k = k - 1) begin
            if (!used[k] && rr_mask_q[k]) victim = SL_W'(k);
        end
    end

    wire desc_in_ready;
    wire rd_cmd_valid = !rst && !dram_rst && s_valid_q && any_pend && (ld_st_q == LD_IDLE) && (owed_q < RC_W'(RD_DEPTH));
    assign rd_fire    = rd_cmd_valid && dram_cmd_ready;
    wire resolve      = s_valid_q && desc_in_ready && (!any_pend || (rd_fire && single));
    assign c_take     = r_valid && (!s_valid_q || resolve);
    always @(*) r_ready = c_take;

    always @(posedge clk) begin
        if (rst) s_valid_q <= 1'b0;
        else if (c_take) s_valid_q <= 1'b1;
        else if (resolve) s_valid_q <= 1'b0;
    end
    always @(posedge clk) begin
        if (c_take) begin
            s_tag_q  <= r_tag;
            s_rden_q <= r_rden;
            s_addr_q <= r_addr;
            s_hitv_q <= c_hitv;
            s_eq_q   <= c_eq;
        end else if (inval) begin
            s_hitv_q <= {(P*NS){1'b0}};
        end else if (rd_fire) begin
            // the slot just filled holds the burst of the banks that read the first miss's
            for (q = 0; q < P; q = q + 1)
                s_hitv_q[q*NS + int'(victim)] <= same[q];
        end
    end

    // the descriptor: tag, read enables, each bank's slot and column, the fills in order
    reg [P*SL_W-1:0]  d_lane_slot, d_fill;
    reg [P*OFF_W-1:0] d_lane_off;
    reg [NF_W-1:0]    d_nfill;
    always @(*) begin
        for (q = 0; q < P; q = q + 1) begin
            d_lane_slot[q*SL_W +: SL_W] = hit[q] ? hit_slot[q] : victim;
            d_lane_off[q*OFF_W +: OFF_W] = off[q];
            d_fill[q*SL_W +: SL_W] = (rd_fire && NF_W'(q) == nfill_q) ? victim : fill_q[q];
        end
        d_nfill = nfill_q + NF_W'(rd_fire);
    end

    always @(posedge clk) begin
        if (rst) begin
            slot_vld_q <= {NS{1'b0}};
            rr_mask_q  <= {NS{1'b1}};
            nfill_q    <= {NF_W{1'b0}};
        end else begin
            if (ld_cmd_valid && dram_cmd_ready) slot_vld_q <= {NS{1'b0}};
            else if (rd_fire) slot_vld_q[victim] <= 1'b1;
            if (rd_fire) begin
                for (k = 0; k < NS; k = k + 1)      // the slots after the victim (all: it was the last)
                    rr_mask_q[k] <= (k > int'(victim)) || (int'(victim) == NS - 1);
            end
            if (resolve) nfill_q <= {NF_W{1'b0}};
            else if (rd_fire) nfill_q <= nfill_q + 1'b1;
        end
    end
    always @(posedge clk) begin
        if (rd_fire) begin
            slot_ba_q[victim] <= want;
            if (int'(nfill_q) < P) fill_q[FI_W'(nfill_q)] <= victim;
        end
    end

    assign dram_cmd_valid = ld_cmd_valid || rd_cmd_valid;
    assign dram_cmd_we    = ld_cmd_valid;
    assign dram_cmd_addr  = ld_cmd_valid ? DRAM_AW'(ld_ba_q) : DRAM_AW'(want);

    wire              d_valid;
    reg               d_ready;
    wire [DESC_W-1:0] d_word;
    cube4_sync_fifo #(.DATA_W(DESC_W), .DEPTH(DESC_DEPTH)) u_desc (
        .clk       (clk),
        .rst       (rst),
        .in_valid  (resolve),
        .in_ready  (desc_in_ready),
        .in_data   ({s_tag_q, s_rden_q, d_lane_slot, d_lane_off, d_nfill, d_fill}),
        .out_valid (d_valid),
        .out_ready (d_ready),
        .out_data  (d_word)
    );

    // ---------------------------------------------------------------- read data
    wire              rq_valid;
    reg               rq_pop;
    wire [DATA_W-1:0] rq_data;
    wire              unused_rq_in_ready;
    reg               rq_take;             // a word leaves the queue: taken or drained
    reg [RC_W-1:0]    drain_q;             // words owed when rst came, to drop
    cube4_sync_fifo #(.DATA_W(DATA_W), .DEPTH(RD_DEPTH)) u_rdata (
        .clk       (clk),
        .rst       (dram_rst),
        .in_valid  (dram_rdata_valid),
        .in_ready  (unused_rq_in_ready),   // never low: owed_q reserves the room
        .in_data   (dram_rdata_data),
        .out_valid (rq_valid),
        .out_ready (rq_take),
        .out_data  (rq_data)
    );
    assign dram_rdata_ready = 1'b1;
    always @(posedge clk) begin
        if (dram_rst) begin
            owed_q  <= {RC_W{1'b0}};
            drain_q <= {RC_W{1'b0}};
        end else begin
            owed_q <= owed_q + RC_W'(rd_fire) - RC_W'(rq_take);
            if (rst) drain_q <= owed_q;
            else if (rq_take && drain_q != {RC_W{1'b0}}) drain_q <= drain_q - 1'b1;
        end
    end

    // ---------------------------------------------------------------- response side
    wire [TAG_W-1:0]   e_tag;
    wire [P-1:0]       e_rden;
    wire [P*SL_W-1:0]  e_lane_slot, e_fill;
    wire [P*OFF_W-1:0] e_lane_off;
    wire [NF_W-1:0]    e_nfill;
    assign {e_tag, e_rden, e_lane_slot, e_lane_off, e_nfill, e_fill} = d_word;

    reg [DATA_W-1:0]  slot_q [0:NS-1];
    reg [NF_W-1:0]    k_q;                 // fills of the head descriptor taken
    reg               o_valid_q;
    reg [TAG_W-1:0]   o_tag_q;
    reg [P*WORD_W-1:0] o_data_q;

    wire [SL_W-1:0] cur_fill = e_fill[(k_q >= NF_W'(P) ? 0 : int'(k_q))*SL_W +: SL_W];
    wire            more     = (k_q + 1'b1 < e_nfill);         // fills before the last
    wire            last     = (k_q < e_nfill);                 // the last fill is now
    wire            o_free   = !o_valid_q || rsp_ready;
    wire            draining = (drain_q != {RC_W{1'b0}});
    wire            emit     = !rst && !draining && d_valid && !more && o_free && (!last || rq_valid);
    always @(*) begin
        rq_pop  = !rst && !draining && d_valid && rq_valid && (more || emit && last);
        rq_take = rq_pop || (!rst && draining && rq_valid);
        d_ready = emit;
    end

    reg [DATA_W-1:0]   src;
    reg [P*WORD_W-1:0] asm_rsp;
    always @(*) begin
        for (q = 0; q < P; q = q + 1) begin
            src = (last && e_lane_slot[q*SL_W +: SL_W] == cur_fill) ? rq_data : slot_q[e_lane_slot[q*SL_W +: SL_W]];
            asm_rsp[q*WORD_W +: WORD_W] = e_rden[q]
                ? src[int'(e_lane_off[q*OFF_W +: OFF_W]) * COL_W + q * WORD_W +: WORD_W] : {WORD_W{1'b0}};
        end
    end

    always @(posedge clk) begin
        if (rq_pop) slot_q[cur_fill] <= rq_data;
        if (emit) begin
            o_tag_q  <= e_tag;
            o_data_q <= asm_rsp;
        end
    end
    always @(posedge clk) begin
        if (rst) begin
            k_q       <= {NF_W{1'b0}};
            o_valid_q <= 1'b0;
        end else begin
            if (emit) k_q <= {NF_W{1'b0}};
            else if (rq_pop) k_q <= k_q + 1'b1;
            if (emit) o_valid_q <= 1'b1;
            else if (rsp_ready) o_valid_q <= 1'b0;
        end
    end
    assign rsp_valid = o_valid_q;
    assign rsp_tag   = o_tag_q;
    assign rsp_data  = o_data_q;

endmodule
`default_nettype wire

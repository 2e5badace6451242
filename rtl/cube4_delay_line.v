`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_delay_line
// -----------------------------------------------------------------------------
// Purpose
//   A run-time length delay line in a RAM, counted in steps (accepted beats),
//   not clocks: dout during step b is din of step b - L, where L = len is the
//   period of the caller's position counter (last = 1 on the step at position
//   L-1). Cube-4 uses it for beam delays (L = NB partial beams) and plane
//   delays (L = NJ * NB beats, one slice): the plane buffers of the paper's
//   Fig. 3. The RAM is read RA steps ahead at a registered address, and its
//   word passes plain registers before dout's register with the bypass
//   multiplexer, so neither the RAM's address nor its output has logic in
//   series (a block RAM's clock-to-out is most of a cycle on an FPGA). The
//   write passes the RAM's write register (cube4_sdp_ram WR_REG: the write
//   lands one cycle after its step, so a plane line's enable, address and
//   data, spread over dozens of block RAMs, get a cycle of routing of their
//   own):
//     up to 2048 words: one bank, a cube4_sdp_ram with its output register
//       (OUT_REG: the block RAM's own on an FPGA), then dout; RA = 3;
//     more: banks of 2048 words (one block RAM deep each, 2048 x 9 on ECP5),
//       each a cube4_sdp_ram with its output register; the bank multiplexer,
//       selected by a register, loads rd3_q; then dout; RA = 4.
//   L = 1 .. RA + 1 are bypassed (din and its last RA values): the RAM is
//   read for the step RA ahead and a word lands one cycle after its step, so
//   its word must have been written at least two steps before. Between steps
//   everything holds.
//
// Parameters
//   DATA_W  word width.                  1..4096.
//   DEPTH   largest L (words stored).    1..2^24.
//   AW      address width (derived; not to be set).
//
// Latency
//   Exactly L steps (step b sees din(b - L)); 0 clock cycles of extra delay.
//   The first L steps after clear see stale words (for L > RA the RA outputs
//   after the clear are zero words), which the caller ignores.
//
// Ports
//   clear  in   this step is position 0 (frame start)
//   step   in   a beat is accepted this cycle (din valid, dout consumed)
//   last   in   this step's position is L - 1 (the caller's counter)
//   len    in   [AW+1]  L, 1..DEPTH, constant from a clear to the next
//   din    in   [DATA_W]  any format
//   dout   out  [DATA_W]  din delayed by L steps
//
// Bit growth and rounding: none.
// =============================================================================
module cube4_delay_line #(
    parameter integer DATA_W = 8,
    parameter integer DEPTH  = 16,
    localparam integer AW    = (DEPTH > 1) ? $clog2(DEPTH) : 1
) (
    input  wire              clk,
    input  wire              rst,
    input  wire              clear,
    input  wire              step,
    input  wire              last,
    input  wire [AW:0]       len,
    input  wire [DATA_W-1:0] din,
    output wire [DATA_W-1:0] dout
);
    generate
        `CUBE4_RANGE(g_bad_data_w, "cube4_delay_line", "DATA_W", DATA_W, 1, 4096)
        if (DEPTH < 1 || DEPTH > (1 << 24)) begin : g_bad_depth
            $error("cube4_delay_line: DEPTH = %0d is out of range 1..2^24", DEPTH);
        end
    endgenerate

    localparam integer BW    = (AW > 11) ? 11 : AW;      // bank address bits
    localparam integer SW    = (AW > BW) ? AW - BW : 1;  // bank select bits
    localparam integer NBANK = 1 << (AW - BW);
    localparam integer RA    = (NBANK > 1) ? 4 : 3;      // steps read ahead
    localparam integer RB    = RA + 1;                   // L = 1 .. RB are bypassed

    reg [DATA_W-1:0] out_q;             // dout
    reg [DATA_W-1:0] dh_q [1:RB-1];     // din of 1 .. RB-1 steps back (bypass)
    reg [AW-1:0]     ptr_q;             // position of the next step (without a clear)
    reg [AW-1:0]     ra_q;              // position RA steps after the next one: the read address
    // dout's multiplexers in groups of G_W bits (a block RAM's width): each
    // group has its own copies of the length flags and of the zero-word flag,
    // so that a wide line (a plane line spans dozens of block RAMs) needs no
    // select routed across the chip
    localparam integer G_W = 18;
    localparam integer NG  = (DATA_W + G_W - 1) / G_W;
    wire [NG*RB-1:0] l_c;               // group g's l_q: bit g*RB + k-1 is L = k
    wire [NG-1:0]    z_c;               // group g: one of the last RA - 1 steps was a clear
    wire [DATA_W-1:0] rd_word;          // the RAM word for this step's dout

    wire [AW-1:0] pos = clear ? {AW{1'b0}} : ptr_q;     // position of this step
    // position of the next step: the increment of the register, the clear and
    // last selected after it (pos feeds the RAM's write-address copies across
    // the block RAMs; an increment of pos would wait for that net)
    wire [AW-1:0] inc = ptr_q + 1'b1;
    wire [AW-1:0] nxt = last ? {AW{1'b0}} : (clear ? AW'(1) : inc);
    // (x + 1) mod L, and (RA + 1) mod L (the read address after a clear, L > RA).
    // ra_end_q says ra_q = L - 1 (kept with ra_q, a step ahead: ra_q + 1 = L - 1
    // against a register of L - 2), so the address's next value is its
    // increment and a multiplexer, no compare in series: the compare after the
    // increment, back into ra_q, limited a full build at P = 1 on one placement
    reg           ra_end_q;
    reg  [AW:0]   lenm2_q;              // L - 2 (len is constant from a clear)
    always @(posedge clk) lenm2_q <= len - (AW + 1)'(2);
    wire [AW-1:0] ra_inc = ra_end_q ? {AW{1'b0}} : ra_q + 1'b1;
    wire [AW-1:0] ra_clr = (len == (AW + 1)'(RA + 1)) ? {AW{1'b0}} : AW'(RA + 1);
    wire          ra_end_n = clear ? ({1'b0, ra_clr} + 1'b1 == len)
                                   : (ra_end_q ? (len == (AW + 1)'(1)) : ({1'b0, ra_q} == lenm2_q));

    genvar k;
    wire [RB-1:0] l_d;
    generate
        for (k = 1; k <= RB; k = k + 1) begin : g_len
            assign l_d[k - 1] = (len == (AW + 1)'(k));
        end
    endgenerate
    // (copies: this line's own, lines with the same len share none)
    cube4_prim_copies #(.N(NG), .W(RB), .RESET(0)) u_len (
        .clk(clk), .rst(rst), .d(l_d), .q(l_c));
    always @(posedge clk) begin
        if (rst) begin
            ptr_q    <= {AW{1'b0}};
            ra_q     <= {AW{1'b0}};
            ra_end_q <= 1'b0;
        end else if (step) begin
            ptr_q    <= nxt;
            ra_q     <= clear ? ra_clr : ra_inc;
            ra_end_q <= ra_end_n;
        end
    end
`ifndef SYNTHESIS
    // ra_end_q against the compare it stands for, from the first clear on,
    // where the RAM is read (L > RB; below, ra_q wanders unused, and wraps
    // at 2^AW where the compare would not)
    reg cleared_q;
    always @(posedge clk) begin
        if (rst) cleared_q <= 1'b0;
        else if (step && clear) cleared_q <= 1'b1;
        if (!rst && cleared_q && step && !clear && 32'(len) > RB
            && ra_end_q != ({1'b0, ra_q} + 1'b1 == len))
            $fatal(1, "cube4_delay_line: ra_end_q %0d, but ra_q %0d and L %0d", ra_end_q, ra_q, len);
    end
`endif
    // Step b writes position pos(b) (the word lands one cycle later) and reads
    // position pos(b + RA) (= ra_q; a word written at step b + RA - L <= b - 2
    // when L > RB, so it has landed before the read); dout for step
    // b + 1 is the word read at step b + 1 - RA. Right after a clear ra_q is
    // off for RA steps, so the RA outputs after a clear are zero words instead
    // (they fall in the first L steps, which the caller ignores; a zero word
    // carries no stale frame-start flag): clr_g[k], the step k back was a
    // clear, in a copy per group of dout's bits (step on its clock enable, as
    // on the data registers: no logic between the step and the copies).
    // "keep": each delay line has its own copies, not one set shared by every
    // line of the caller.
    genvar g;
    generate
        for (g = 0; g < NG; g = g + 1) begin : g_clr
            reg [RA-1:1] clr_g;
            (* keep *)
            always @(posedge clk) begin
                if (rst) clr_g <= '0;
                else if (step) clr_g <= (RA - 1)'({clr_g, clear});
            end
            assign z_c[g] = |clr_g;
        end
    endgenerate

    generate
        if (NBANK == 1) begin : g_one_bank
            // the RAM's read register, then its output register (rd2_q):
            // no logic after the RAM
            cube4_sdp_ram #(.DATA_W(DATA_W), .DEPTH(1 << AW), .WR_REG(1), .OUT_REG(1)) u_ram (
                .clk(clk), .rd_en(step), .out_en(1'b0), .rd_addr(ra_q), .rd_data(rd_word),
                .wr_en(step), .wr_addr(pos), .wr_data(din));
        end else begin : g_banks
            wire [DATA_W-1:0] rd2_w [0:NBANK-1];
            reg  [SW-1:0]     sel1_q, sel2_q;   // bank of the word in rd_q / rd2_q
            reg  [DATA_W-1:0] rd3_q;            // the selected bank's word
            genvar b;
            for (b = 0; b < NBANK; b = b + 1) begin : g_bank
                cube4_sdp_ram #(.DATA_W(DATA_W), .DEPTH(1 << BW), .WR_REG(1), .OUT_REG(1)) u_ram (
                    .clk(clk), .rd_en(step), .out_en(1'b0), .rd_addr(ra_q[BW-1:0]), .rd_data(rd2_w[b]),
                    .wr_en(step && pos[AW-1:BW] == SW'(b)), .wr_addr(pos[BW-1:0]), .wr_data(din));
            end
            always @(posedge clk) begin
                if (step) begin
                    sel1_q <= ra_q[AW-1:BW];
                    sel2_q <= sel1_q;
                    rd3_q  <= rd2_w[sel2_q];
                end
            end
            assign rd_word = rd3_q;
        end
    endgenerate

    // dout: the bypass for L <= RA, the zero words after a clear, else the
    // RAM, or for L = RB its bypass word (din of RB - 1 steps back); group g
    // selects with its own copies
    integer kd;
    always @(posedge clk) begin
        if (step) begin
            dh_q[1] <= din;
            for (kd = 2; kd < RB; kd = kd + 1) dh_q[kd] <= dh_q[kd - 1];
        end
    end
    generate
        for (g = 0; g < NG; g = g + 1) begin : g_out
            localparam integer LO = g * G_W;
            localparam integer GW = (DATA_W - LO < G_W) ? DATA_W - LO : G_W;
            wire [RB:1] lg = l_c[g*RB +: RB];
            reg  [GW-1:0] byp;
            integer kb;
            always @(*) begin
                byp = din[LO +: GW];
                for (kb = RA; kb >= 2; kb = kb - 1) begin
                    if (lg[kb]) byp = dh_q[kb - 1][LO +: GW];
                end
            end
            wire [GW-1:0] far = lg[RB] ? dh_q[RB - 1][LO +: GW] : rd_word[LO +: GW];   // L > RA
            always @(posedge clk) begin
                if (step) out_q[LO +: GW] <= (|lg[RA:1]) ? byp : ((clear || z_c[g]) ? {GW{1'b0}} : far);
            end
        end
    endgenerate

    assign dout = out_q;

endmodule
`default_nettype wire

`default_nettype none
// =============================================================================
// cube4_delay_line
// -----------------------------------------------------------------------------
// Purpose
//   A run-time length delay line in a RAM, counted in steps (accepted beats),
//   not clocks: dout during step b is din of step b - L, where L = len is the
//   period of the caller's position counter (last = 1 on the step at position
//   L-1). Cube-4 uses it for beam delays (L = NB partial beams) and plane
//   delays (L = NJ * NB beats, one slice): the plane buffers of the paper's
//   Fig. 3. The RAM is read three steps ahead at a registered address, and
//   its word passes two registers (rd_q, a plain copy rd2_q that can sit
//   beside the block RAM, then dout's register with the bypass multiplexer),
//   so neither the RAM's address nor its output has logic in series (a block
//   RAM's clock-to-out is most of a cycle on an FPGA). L = 1, 2 and 3 are
//   bypassed. Between steps everything holds.
//
// Parameters
//   DATA_W  word width.                  1..4096.
//   DEPTH   largest L (words stored).    1..2^24.
//
// Latency
//   Exactly L steps (step b sees din(b - L)); 0 clock cycles of extra delay.
//   The first L steps after clear see stale words (for L >= 4 the second,
//   third and fourth are zero words), which the caller ignores.
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
    parameter integer AW     = (DEPTH > 1) ? $clog2(DEPTH) : 1
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
        if (DATA_W < 1 || DATA_W > 4096) begin : g_bad_data_w
            $error("cube4_delay_line: DATA_W = %0d is out of range 1..4096", DATA_W);
        end
        if (DEPTH < 1 || DEPTH > (1 << 24)) begin : g_bad_depth
            $error("cube4_delay_line: DEPTH = %0d is out of range 1..2^24", DEPTH);
        end
    endgenerate

    reg [DATA_W-1:0] mem [0:(1 << AW)-1];
    reg [DATA_W-1:0] rd_q;    // RAM read register: the word for three steps on
    reg [DATA_W-1:0] rd2_q;   // rd_q one step later: no logic after the RAM
    reg [DATA_W-1:0] out_q;   // dout
    reg [DATA_W-1:0] din_q;   // din of the previous step (L = 2)
    reg [DATA_W-1:0] din2_q;  // din of two steps back (L = 3)
    reg [AW-1:0]     ptr_q;   // position of the next step (without a clear)
    reg [AW-1:0]     ra_q;    // position three steps after the next one: the read address
    reg              l1_q, l2_q, l3_q;
    reg              clr1_q, clr2_q;  // the last / the second-last step was a clear

    wire [AW-1:0] pos = clear ? {AW{1'b0}} : ptr_q;     // position of this step
    wire [AW-1:0] nxt = last ? {AW{1'b0}} : pos + 1'b1; // position of the next step
    // (x + 1) mod L, and 4 mod L (the read address after a clear, L >= 4)
    wire [AW-1:0] ra_inc = ({1'b0, ra_q} + 1'b1 == len) ? {AW{1'b0}} : ra_q + 1'b1;
    wire [AW-1:0] four   = (len == (AW + 1)'(4)) ? {AW{1'b0}} : AW'(32'd4);   // (AW <= 2: L <= 4)

    always @(posedge clk) begin
        l1_q <= (len == (AW + 1)'(1));
        l2_q <= (len == (AW + 1)'(2));
        l3_q <= (len == (AW + 1)'(3));
    end
    always @(posedge clk) begin
        if (rst) begin
            ptr_q <= {AW{1'b0}};
            ra_q  <= {AW{1'b0}};
        end else if (step) begin
            ptr_q <= nxt;
            ra_q  <= clear ? four : ra_inc;
        end
    end
    // Step b writes position pos(b) and reads position pos(b + 3) (= ra_q; a
    // word written at step b + 3 - L <= b - 1 when L >= 4); dout for step b + 1
    // is the word read at step b - 2. Right after a clear ra_q is off for three
    // steps, so the three outputs after a clear are zero words instead (they
    // fall in the first L steps, which the caller ignores; a zero word carries
    // no stale frame-start flag).
    always @(posedge clk) begin
        if (rst) begin
            clr1_q <= 1'b0;
            clr2_q <= 1'b0;
        end else if (step) begin
            clr1_q <= clear;
            clr2_q <= clr1_q;
        end
    end
    always @(posedge clk) begin
        if (step) begin
            mem[pos] <= din;
            rd_q     <= mem[ra_q];
            rd2_q    <= rd_q;
            din_q    <= din;
            din2_q   <= din_q;
            out_q    <= l1_q ? din : (l2_q ? din_q : (l3_q ? din2_q
                        : ((clear || clr1_q || clr2_q) ? {DATA_W{1'b0}} : rd2_q)));
        end
    end

    assign dout = out_q;

endmodule
`default_nettype wire

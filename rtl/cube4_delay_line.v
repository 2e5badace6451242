`default_nettype none
// =============================================================================
// cube4_delay_line
// -----------------------------------------------------------------------------
// Purpose
//   A run-time length delay line in a RAM, counted in steps (accepted beats),
//   not clocks: dout during step b is din of step b - L, where L is the period
//   of the caller's position counter (last = 1 on the step at position L-1).
//   Cube-4 uses it for beam delays (L = NB partial beams) and plane delays
//   (L = NJ * NB beats, one slice): the plane buffers of the paper's Fig. 3.
//   dout is a register, read one step ahead (read address = next position);
//   L = 1 is bypassed. Between steps everything holds.
//
// Parameters
//   DATA_W  word width.                  1..4096.
//   DEPTH   largest L (words stored).    1..2^24.
//
// Latency
//   Exactly L steps (step b sees din(b - L)); 0 clock cycles of extra delay.
//   The first L steps after clear see stale words, which the caller ignores.
//
// Ports
//   clear  in   this step is position 0 (frame start)
//   step   in   a beat is accepted this cycle (din valid, dout consumed)
//   last   in   this step's position is L - 1 (the caller's counter)
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
    reg [DATA_W-1:0] rd_q;
    reg [AW-1:0]     ptr_q;

    wire [AW-1:0] pos = clear ? {AW{1'b0}} : ptr_q;     // position of this step
    wire [AW-1:0] nxt = last ? {AW{1'b0}} : pos + 1'b1; // position of the next step

    always @(posedge clk) begin
        if (rst) ptr_q <= {AW{1'b0}};
        else if (step) ptr_q <= nxt;
    end
    always @(posedge clk) begin
        if (step) begin
            mem[pos] <= din;
            rd_q     <= (nxt == pos) ? din : mem[nxt];   // L = 1: the word just written
        end
    end

    assign dout = rd_q;

endmodule
`default_nettype wire

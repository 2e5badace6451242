`default_nettype none
// =============================================================================
// cube4_stream_check  (verification only: empty under SYNTHESIS)
// -----------------------------------------------------------------------------
// Purpose
//   Checks the rules of one valid/ready stream on every clock edge, in every
//   simulation that instantiates it (cube4_top on each internal stream, the
//   unit harnesses on each unit's input and output), the way ibex and
//   common_cells assert their interfaces:
//     * valid is never unknown (X/Z) out of reset;
//     * a valid beat carries no unknown (X/Z) data bit;
//     * a beat offered and not taken (valid && !ready at an edge) is offered
//       again, unchanged, at the next edge: valid stays 1 and data keeps its
//       value (a reset in between releases the beat).
//   A transfer is valid && ready at a rising edge of clk. The check reads the
//   producer's side of the stream (before any verification hold such as
//   cube4_stream_hold, which drops valid on purpose).
//   On a violation it prints an error naming the stream (NAME) and the rule,
//   then stops the simulation with $fatal, so the running test fails.
//
//   Unknown bits: Verilator is a two-state simulator, so there the X/Z checks
//   never fire (every bit is 0 or 1); they are written with $isunknown so that
//   a four-state simulator (Icarus, Questa, Xcelium) checks them for real.
//   The hold rule works in both.
//   Synthesis (SYNTHESIS defined, as Yosys does) sees an empty module.
//
// Parameters
//   NAME    the stream's name in messages (a string).
//   DATA_W  width of the payload checked for stability.  1..65536.  Default 1.
//
// Latency
//   None: a violation is reported at the clock edge where it is seen.
//
// Ports (all inputs)
//   clk, rst  the stream's clock and synchronous reset (active high)
//   valid     the producer's valid
//   ready     the consumer's ready
//   data      [DATA_W] every payload bit of the beat (header, data, tags)
// =============================================================================
module cube4_stream_check #(
    parameter        NAME   = "stream",
    parameter integer DATA_W = 1
) (
    input  wire              clk,
    input  wire              rst,
    input  wire              valid,
    input  wire              ready,
    input  wire [DATA_W-1:0] data
);
`ifndef SYNTHESIS
    reg              pending_q;   // the last edge saw valid && !ready out of reset
    reg [DATA_W-1:0] data_q;      // the payload of that beat

    always @(posedge clk) begin
        if (rst) begin
            pending_q <= 1'b0;
        end else begin
            if ($isunknown(valid)) begin
                $error("stream %s: valid is unknown (X/Z)", NAME);
                $fatal(1, "stream %s: protocol violation", NAME);
            end
            if (valid && $isunknown(data)) begin
                $error("stream %s: valid beat with unknown (X/Z) data bits: %h", NAME, data);
                $fatal(1, "stream %s: protocol violation", NAME);
            end
            if (pending_q && !valid) begin
                $error("stream %s: valid dropped while the beat was stalled (valid && !ready)", NAME);
                $fatal(1, "stream %s: protocol violation", NAME);
            end
            if (pending_q && valid && data !== data_q) begin
                $error("stream %s: data changed while stalled: %h, was %h", NAME, data, data_q);
                $fatal(1, "stream %s: protocol violation", NAME);
            end
            pending_q <= valid && !ready;
            data_q    <= data;
        end
    end
`endif
endmodule
`default_nettype wire

`default_nettype none
// =============================================================================
// cube4_stream_check_demo  (simulation only: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Harness of tb/cube4_stream_check: one cube4_stream_check (NAME
//   "demo.beats") on a stream whose valid, ready and data the testbench drives
//   directly, so that it can break the stream rules on purpose (drop valid or
//   change data while stalled) and see the checker stop the simulation
//   naming the stream, and drive legal traffic that must pass.
//
// Parameters
//   DATA_W  payload width.  1..64.  Default 8.
//
// Latency: none (the checker reports at the edge where it sees a violation).
//
// Ports
//   clk     out  the harness's clock (cube4_sim_clock, 10 ns)
//   rst     in   synchronous reset
//   valid, ready, data [DATA_W]   in   the stream under check
// =============================================================================
module cube4_stream_check_demo #(
    parameter integer DATA_W = 8
) (
    output wire              clk,
    input  wire              rst,
    input  wire              valid,
    input  wire              ready,
    input  wire [DATA_W-1:0] data
);
    cube4_sim_clock u_clock (.clk (clk));

    cube4_stream_check #(
        .NAME   ("demo.beats"),
        .DATA_W (DATA_W)
    ) u_chk (
        .clk   (clk),
        .rst   (rst),
        .valid (valid),
        .ready (ready),
        .data  (data)
    );

endmodule
`default_nettype wire

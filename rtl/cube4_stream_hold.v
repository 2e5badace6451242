`default_nettype none
// =============================================================================
// cube4_stream_hold
// -----------------------------------------------------------------------------
// Purpose
//   Verification hook on an internal valid/ready stream of cube4_top: while
//   hold = 1 no transfer happens (the consumer sees valid = 0, the producer
//   sees ready = 0, so it keeps its item). With hold tied to 0 it is two wires
//   and synthesis removes it. Testbenches drive hold at random to stall every
//   internal port.
//
// Parameters: none.  Latency: 0 cycles.
//
// Ports
//   hold                     in   block transfers this cycle
//   in_valid / in_ready      producer side
//   out_valid / out_ready    consumer side (data passes outside this module)
// =============================================================================
module cube4_stream_hold (
    input  wire hold,
    input  wire in_valid,
    output wire in_ready,
    output wire out_valid,
    input  wire out_ready
);
    assign out_valid = in_valid && !hold;
    assign in_ready  = out_ready && !hold;
endmodule
`default_nettype wire

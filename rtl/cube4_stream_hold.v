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
// Parameters
//   READY_N   copies of ready passed through (a consumer's register copies,
//             cube4_skid_peek's in_ready_cp), each held alike.  1 or more.
//             Default 1.
// Latency: 0 cycles.
//
// Ports
//   hold                     in   block transfers this cycle
//   in_valid / in_ready      producer side (in_ready [READY_N])
//   out_valid / out_ready    consumer side (out_ready [READY_N]; data passes
//                            outside this module)
// =============================================================================
module cube4_stream_hold #(
    parameter integer READY_N = 1
) (
    input  wire               hold,
    input  wire               in_valid,
    output wire [READY_N-1:0] in_ready,
    output wire               out_valid,
    input  wire [READY_N-1:0] out_ready
);
    assign out_valid = in_valid && !hold;
    assign in_ready  = out_ready & {READY_N{!hold}};
endmodule
`default_nettype wire

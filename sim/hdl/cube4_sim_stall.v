`default_nettype none
// =============================================================================
// cube4_sim_stall  (simulation only)
// -----------------------------------------------------------------------------
// Purpose
//   Random stall injection on a valid/ready stream, driven from Verilog (an
//   LFSR), so that long tests stall every port without Python touching every
//   clock. The input side's ready is dropped at random (probability
//   STALL/256 per cycle, set at run time); the items then pass a cube4_skid,
//   so the output side keeps valid and data stable until accepted, as the
//   stream rules require. With stall = 0 it only adds one cycle of latency.
//
// Parameters
//   DATA_W  payload width.   1..4096.
//   STREAM  which stream of the testbench (0..255): streams with the same
//           seed get different stall patterns.
//
// Ports
//   seed   in  [32]  the test's random seed (COCOTB_RANDOM_SEED), taken at reset
//   stall  in  [8]   stall probability, /256 (0: never, 255: almost always)
//   in_*, out_*      the stream (any format)
// =============================================================================
module cube4_sim_stall #(
    parameter integer DATA_W = 8,
    parameter integer STREAM = 0
) (
    input  wire              clk,
    input  wire              rst,
    input  wire [31:0]       seed,
    input  wire [7:0]        stall,
    input  wire              in_valid,
    output wire              in_ready,
    input  wire [DATA_W-1:0] in_data,
    output wire              out_valid,
    input  wire              out_ready,
    output wire [DATA_W-1:0] out_data
);
    // the LFSR's start state from the seed and the stream (never zero)
    wire [15:0] mix  = seed[15:0] ^ seed[31:16] ^ (16'h9E37 * 16'(STREAM + 1));
    wire [15:0] init = (mix == 16'd0) ? 16'hACE1 : mix;
    reg  [15:0] lfsr_q;
    always @(posedge clk) begin
        if (rst) lfsr_q <= init;
        else     lfsr_q <= {lfsr_q[14:0], lfsr_q[15] ^ lfsr_q[13] ^ lfsr_q[12] ^ lfsr_q[10]};
    end
    wire go = (lfsr_q[7:0] >= stall);

    wire skid_ready;
    cube4_skid #(
        .DATA_W (DATA_W)
    ) u_skid (
        .clk       (clk),
        .rst       (rst),
        .in_valid  (in_valid && go),
        .in_ready  (skid_ready),
        .in_data   (in_data),
        .out_valid (out_valid),
        .out_ready (out_ready),
        .out_data  (out_data)
    );
    assign in_ready = skid_ready && go;

endmodule
`default_nettype wire

`default_nettype none
// =============================================================================
// cube4_lerp_vclk  (SIMULATION ONLY: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   cube4_lerp with its clock generated in Verilog by cube4_sim_clock: the
//   pattern for testbenches whose clock should not be driven from Python.
//   Same parameters and ports as cube4_lerp, except clk, which is an output
//   here: the clock is generated inside, and cocotb waits on its edges.
//
// Parameters
//   DATA_W, WEIGHT_W, LATENCY  passed to cube4_lerp (same ranges).
//   HALF_PERIOD                passed to cube4_sim_clock (ns).
//
// Latency, ports and fixed-point formats: as cube4_lerp.
// =============================================================================
module cube4_lerp_vclk #(
    parameter integer DATA_W      = 8,
    parameter integer WEIGHT_W    = 8,
    parameter integer LATENCY     = 0,
    parameter integer HALF_PERIOD = 5
) (
    output wire                clk,    // generated here; Python waits on its edges
    input  wire                en,
    input  wire [DATA_W-1:0]   a,
    input  wire [DATA_W-1:0]   b,
    input  wire [WEIGHT_W-1:0] w,
    output wire [DATA_W-1:0]   y,
    output wire [DATA_W-1:0]   y_next
);

    cube4_sim_clock #(
        .HALF_PERIOD (HALF_PERIOD)
    ) u_clock (
        .clk (clk)
    );

    cube4_lerp #(
        .DATA_W   (DATA_W),
        .WEIGHT_W (WEIGHT_W),
        .LATENCY  (LATENCY)
    ) u_lerp (
        .clk (clk),
        .en  (en),
        .a   (a),
        .b   (b),
        .d   ({(DATA_W + 1){1'b0}}),   // (DIFF_IN = 0: b - a formed inside)
        .w   (w),
        .y   (y),
        .y_next (y_next)
    );

endmodule
`default_nettype wire

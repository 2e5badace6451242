`default_nettype none
// =============================================================================
// cube4_sim_clock  (SIMULATION ONLY: needs Verilator --timing)
// -----------------------------------------------------------------------------
// Purpose
//   Free-running clock generated in Verilog, for long tests: the simulator
//   toggles it by itself instead of cocotb scheduling every edge through VPI.
//   Instantiate it in a small sim-only wrapper around the DUT (see
//   cube4_lerp_vclk.v) and build with run_test(..., timing=True). The cocotb
//   test must then NOT start a cocotb Clock on the same signal.
//
// Parameters
//   HALF_PERIOD  half clock period in time units of the runner's timescale
//                (1 ns). Range >= 1. Default 5 (10 ns period).
//   HALF_PS      half period in picoseconds (the runner's precision); when
//                not 0 it replaces HALF_PERIOD. Range >= 0. Default 0.
//
// Latency
//   n/a. clk starts at 0 and rises first at t = HALF_PERIOD.
//
// Ports
//   clk  out  1 bit  the clock
// =============================================================================
module cube4_sim_clock #(
    parameter integer HALF_PERIOD = 5,
    parameter integer HALF_PS     = 0
) (
    output wire clk
);

    generate
        if (HALF_PERIOD < 1 || HALF_PS < 0) begin : g_bad_half_period
            $error("cube4_sim_clock: HALF_PERIOD = %0d must be >= 1", HALF_PERIOD);
        end
    endgenerate

    reg clk_q;

    initial begin
        clk_q = 1'b0;
    end

    always begin
        if (HALF_PS > 0) #(HALF_PS * 1.0e-3) clk_q = ~clk_q;
        else #(HALF_PERIOD) clk_q = ~clk_q;
    end

    assign clk = clk_q;

endmodule
`default_nettype wire

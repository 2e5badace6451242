`default_nettype none
// =============================================================================
// cube4_frame_ctl
// -----------------------------------------------------------------------------
// Purpose
//   Frame control of cube4_top and cube4_frontend: busy from an accepted start
//   until the frame's last beat leaves, done with that beat, and the frame's
//   cycle count. start is ignored while busy.
//
// Parameters: none.
//
// Latency
//   busy rises the cycle after start; done is combinational from last_beat
//   (the cycle the last beat is accepted); cycles counts the clock cycles
//   from start to that beat inclusive (1 in the first cycle after start) and
//   holds its value until the next start.
//
// Ports
//   start      in   pulse: start a frame
//   last_beat  in   the frame's last beat is accepted this cycle
//   busy       out  a frame runs
//   done       out  pulse with the last beat
//   cycles     out  [32] cycle count (wraps after 2^32 - 1 cycles)
//
// Bit growth and rounding: none (a 32-bit counter).
// =============================================================================
module cube4_frame_ctl (
    input  wire        clk,
    input  wire        rst,
    input  wire        start,
    input  wire        last_beat,
    output wire        busy,
    output wire        done,
    output wire [31:0] cycles
);
    reg        busy_q;
    reg [31:0] cycles_q;
    always @(posedge clk) begin
        if (rst) begin
            busy_q   <= 1'b0;
            cycles_q <= 32'd0;
        end else if (!busy_q) begin
            if (start) begin
                busy_q   <= 1'b1;
                cycles_q <= 32'd1;
            end
        end else begin
            cycles_q <= cycles_q + 32'd1;
            if (last_beat) busy_q <= 1'b0;
        end
    end
    assign busy   = busy_q;
    assign done   = busy_q && last_beat;
    assign cycles = cycles_q;
endmodule
`default_nettype wire

`default_nettype none
// =============================================================================
// cube4_skid
// -----------------------------------------------------------------------------
// Purpose
//   Two-entry skid buffer for a valid/ready stream. in_ready is a register
//   (no combinational path from out_ready to in_ready), so it ends a pipeline
//   that advances under one stall enable: the pipeline's enable is in_ready,
//   and an item already on its way when out_ready drops lands in the second
//   entry. Full throughput: one item per cycle when out_ready stays high.
//
// Parameters
//   DATA_W  width of the payload.  Range 1..4096.  Default 8.
//
// Latency
//   1 cycle from an accepted input to out_valid. Order is kept; nothing is
//   lost or duplicated under any pattern of out_ready.
//
// Ports
//   clk, rst                 clock, synchronous active-high reset (empties it)
//   in_valid/in_ready/in_data   input stream  (in_data: any format, DATA_W bits)
//   out_valid/out_ready/out_data output stream (same format)
//
// Bit growth and rounding: none (storage only).
// =============================================================================
module cube4_skid #(
    parameter integer DATA_W = 8
) (
    input  wire              clk,
    input  wire              rst,
    input  wire              in_valid,
    output wire              in_ready,
    input  wire [DATA_W-1:0] in_data,
    output wire              out_valid,
    input  wire              out_ready,
    output wire [DATA_W-1:0] out_data
);
    generate
        if (DATA_W < 1 || DATA_W > 4096) begin : g_bad_data_w
            $error("cube4_skid: DATA_W = %0d is out of range 1..4096", DATA_W);
        end
    endgenerate

    reg              a_v_q, b_v_q;   // a: head (output), b: the skid entry
    reg [DATA_W-1:0] a_q, b_q;

    wire pop  = a_v_q && out_ready;
    wire push = in_valid && !b_v_q;

    always @(posedge clk) begin
        if (rst) begin
            a_v_q <= 1'b0;
            b_v_q <= 1'b0;
        end else if (b_v_q) begin
            if (pop) begin
                b_v_q <= 1'b0;   // b moves to a (data below)
            end
        end else if (push) begin
            if (a_v_q && !pop) begin
                b_v_q <= 1'b1;
            end else begin
                a_v_q <= 1'b1;
            end
        end else if (pop) begin
            a_v_q <= 1'b0;
        end
    end

    always @(posedge clk) begin
        if (b_v_q) begin
            if (pop) a_q <= b_q;
        end else if (push) begin
            if (a_v_q && !pop) b_q <= in_data;
            else               a_q <= in_data;
        end
    end

    assign in_ready  = !b_v_q;
    assign out_valid = a_v_q;
    assign out_data  = a_q;

endmodule
`default_nettype wire

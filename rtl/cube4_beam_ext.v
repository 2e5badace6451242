`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_beam_ext
// -----------------------------------------------------------------------------
// Purpose
//   Beam extension (Teramac paper, Fig. 6): gives every lane the value of the
//   next position along the beam, i + 1, which its ring neighbour holds (lane
//   q + 1, or q - 1 when the i axis is traversed backwards). For the lane that
//   holds the last position of a partial beam (wrap = 1) the neighbour's value
//   belongs to the NEXT partial beam, which arrives one beat later: the caller
//   delays its own beat by one (prev) and this module takes that lane's
//   neighbour from the newer beat (cur). Lanes whose i + 1 lies outside the
//   volume (nbr_ok = 0) get zero, the padding of docs/numerics.md section 4.
//
// Parameters
//   P       lanes (pipelines).     Range 1..64.    Default 8.
//   DATA_W  bits per lane.         Range 1..512.   Default 8.
//
// Latency
//   0 cycles (combinational; the one-beat delay register is the caller's).
//
// Ports
//   down    in   1 bit        0: neighbour is lane q + 1; 1: lane q - 1
//   prev    in   [P*DATA_W]   beat b (the beat being completed), lane-major
//   cur     in   [P*DATA_W]   beat b + 1 (the next partial beam)
//   wrap    in   [P]          lane holds the last position of beat b's partial beam
//   nbr_ok  in   [P]          position i + 1 of lane q in beat b is inside (< NI)
//   nbr     out  [P*DATA_W]   value at position i + 1 for each lane of beat b
//
// Bit growth and rounding: none.
// =============================================================================
module cube4_beam_ext #(
    parameter integer P      = 8,
    parameter integer DATA_W = 8
) (
    input  wire                down,
    input  wire [P*DATA_W-1:0] prev,
    input  wire [P*DATA_W-1:0] cur,
    input  wire [P-1:0]        wrap,
    input  wire [P-1:0]        nbr_ok,
    output wire [P*DATA_W-1:0] nbr
);
    generate
        `CUBE4_RANGE(g_bad_p, "cube4_beam_ext", "P", P, 1, 64)
        `CUBE4_RANGE(g_bad_data_w, "cube4_beam_ext", "DATA_W", DATA_W, 1, 512)
    endgenerate

    // lane q's neighbour value in beat b and in beat b + 1
    wire [P*DATA_W-1:0] prev_n, cur_n;

    cube4_ring_shift #(
        .P      (P),
        .DATA_W (DATA_W)
    ) u_shift_prev (
        .down (!down),
        .x    (prev),
        .y    (prev_n)
    );

    cube4_ring_shift #(
        .P      (P),
        .DATA_W (DATA_W)
    ) u_shift_cur (
        .down (!down),
        .x    (cur),
        .y    (cur_n)
    );

    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            assign nbr[q*DATA_W +: DATA_W] = !nbr_ok[q] ? {DATA_W{1'b0}}
                                           : wrap[q]    ? cur_n[q*DATA_W +: DATA_W]
                                                        : prev_n[q*DATA_W +: DATA_W];
        end
    endgenerate

endmodule
`default_nettype wire

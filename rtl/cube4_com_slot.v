`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_slot
// -----------------------------------------------------------------------------
// Purpose
//   COM's slot by position, for the schedules whose slices are not the whole
//   box (slice rectangles, cube4_com_rect; the beat schedule, cube4_com_beats):
//   the slice-buffer slot of R0's beat is {j, pb} from its header, and
//     hazard  the offered beat's slot is the slot of a beat in R0 .. S9 (the
//             read-after-write rule by position: that beat's write of the
//             slot comes after the offered beat's read would)
//     col1_4  the beat before R0's, in the order they left R0, is the row
//             above at the same partial beam (its beam-buffer write comes too
//             late: cube4_com_bpb takes its slice word instead), at S4
//   Its parents' testbenches check it (tb/cube4_com_rect, tb/cube4_com_beats).
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2: the geometry (cube4_defs.vh).
//   SP_W   the slot's width, clog2(MAX_DIM) + PB_W (cube4_com).  2..22.
//
// Latency
//   hazard: combinational from in_hdr and the slots of R0 .. S9 (in_ready
//   then depends on in_hdr); pos_sp, pos_pb: from R0's fields; col1_4: S4.
//
// Ports
//   in_hdr    in   the offered beat's header (J, PB)
//   step, v_fly, sp_fly   in   R0, S1 .. S9 hold a beat; S1 .. S9's slots
//   r0_m, r0_j, r0_pb     in   R0's fields (cube4_com_seq)
//   pos_sp, pos_pb, hazard, col1_4   out  as above
//
// Bit growth and rounding: none (compares).
// =============================================================================
module cube4_com_slot #(
    `CUBE4_SLICE_PARAMS,
    parameter integer SP_W = 13
) (
    input  wire clk, input wire rst,
    input  wire [HDR_W-1:0] in_hdr,
    input  wire step, input wire [9:1] v_fly, input wire [9*SP_W-1:0] sp_fly,
    input  wire [M_W-1:0] r0_m, input wire [DIM_W-1:0] r0_j, input wire [PB_W-1:0] r0_pb,
    output wire [SP_W-1:0] pos_sp, output wire [PB_W-1:0] pos_pb, output wire hazard,
    output wire col1_4
);
    localparam integer RW = (MAX_DIM > 1) ? $clog2(MAX_DIM) : 1;

    // ---- the slot {j, pb}; read after write by position: the offered
    // beat's slot against R0 .. S9 ----
    assign pos_pb = r0_pb;
    assign pos_sp = SP_W'({r0_j[RW-1:0], r0_pb});
    wire [SP_W-1:0] in_sp = SP_W'({in_hdr[HDR_J +: RW], in_hdr[HDR_PB +: PB_W]});
    reg hz;
    integer kz;
    always @* begin
        hz = step && (pos_sp == in_sp);
        for (kz = 1; kz <= 9; kz = kz + 1) hz = hz || (v_fly[kz] && (sp_fly[(kz-1)*SP_W +: SP_W] == in_sp));
    end
    assign hazard = hz;
    wire unused_hdr = ^in_hdr;   // (the fields besides J and PB)

    // ---- the last beat that left R0: is R0's the row below it, same pb? ----
    reg             lb_v;
    reg [M_W-1:0]   lb_m;
    reg [DIM_W-1:0] lb_j;
    reg [PB_W-1:0]  lb_pb;
    always @(posedge clk) begin
        if (rst) lb_v <= 1'b0;
        else if (step) lb_v <= 1'b1;
        if (step) begin
            lb_m  <= r0_m;
            lb_j  <= r0_j;
            lb_pb <= r0_pb;
        end
    end
    reg [4:1] col1_s;
    always @(posedge clk) begin
        col1_s <= {col1_s[3:1], lb_v && (lb_m == r0_m) && (lb_pb == r0_pb) && (lb_j + 1'b1 == r0_j)};
    end
    assign col1_4 = col1_s[4];
endmodule
`default_nettype wire

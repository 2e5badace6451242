`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_com_rect
// -----------------------------------------------------------------------------
// Purpose
//   COM's slice geometry with slice rectangles (RECTS = 1; docs/architecture.md
//   "COM", numerics.md section 18): the beats of a slice are those of its
//   traversed rectangle, so the beat's slot is {j, pb} from its header; the
//   host's rectangle table (cube4_cfb's layout, written alike; three copies,
//   read as a slice's first beat enters R0) gives the inside rectangles of
//   slices m - 1 and m + 1 and the steps of slice m. Per lane:
//     fresh   the previous sample (m-1, j-dyb, i-dxb) is not in slice m-1's
//             inside rectangle (or m = 0)
//     nx_in   the next sample (m+1, j+dyf, i+dxf) is in slice m+1's (m+1 < M)
//   The read-after-write rule by position (cube4_com_slot): a beat waits while
//   the beat of the same slot is in R0 .. S9. col1_4: the previous beat is the row above at
//   the same partial beam (its beam-buffer write comes too late).
//
// Parameters
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2 (0 here: rectangles run with S = 1),
//   ADDR_W: as cube4_com (the table layout).
//   SP_W   the slot's width, clog2(MAX_DIM) + PB_W (cube4_com).  2..22.  Default 13.
//
// Latency
//   The table: read at the edge a slice's first beat enters R0 (take), its
//   entries are R0's. fresh, pos_*, stx, sty: combinational from R0 (S0).
//   nx_in: from S1 registers. hazard: combinational from in_hdr and the
//   slots of R0 .. S9 (in_ready then depends on in_hdr). col1_4: S4.
//
// Ports
//   rect_we, rect_addr, rect_data   the table's write port (CUBE4_RECT_LAYOUT;
//             reads INS, J_IN, J_HI, I_IN, I_HIN, STX, STY)
//   take, in_hdr   a beat enters R0; the offered beat's header
//   step, v_fly, sp_fly   R0, S1 .. S9 hold a beat; S1 .. S9's slots
//   r0_m, r0_j, r0_pb, dxb, dyb, ipos   R0's fields (cube4_com_seq)
//   f1_ipos, f1_j, f1_dxf, f1_dyf       S1's (cube4_com_seq)
//   pos_sp, pos_pb, hazard, fresh, nx_in, stx, sty: as cube4_com_walk
//   col1_4    out  S4: the previous beat is the row above, same pb
//
// Bit growth and rounding: comparisons of positions in IW bits only.
// =============================================================================
module cube4_com_rect #(
    `CUBE4_SLICE_PARAMS,
    parameter integer ADDR_W   = 16, parameter integer SP_W       = 13,
    `CUBE4_RECT_LAYOUT
) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg,
    input  wire rect_we, input wire [M_W-1:0] rect_addr, input wire [RECT_W-1:0] rect_data,
    input  wire take, input wire [HDR_W-1:0] in_hdr,
    input  wire step, input wire [9:1] v_fly, input wire [9*SP_W-1:0] sp_fly,
    input  wire [M_W-1:0] r0_m, input wire [DIM_W-1:0] r0_j, input wire [PB_W-1:0] r0_pb,
    input  wire dxb, input wire dyb, input wire [P*IW-1:0] ipos,
    input  wire [P*IW-1:0] f1_ipos, input wire [IW-1:0] f1_j, input wire f1_dxf, input wire f1_dyf,
    output wire [SP_W-1:0] pos_sp, output wire [PB_W-1:0] pos_pb, output wire hazard,
    output wire [P-1:0] fresh, output wire [P-1:0] nx_in,
    output wire [DIM_W-1:0] stx, output wire [DIM_W-1:0] sty,
    output wire col1_4
);
    `CUBE4_VIEW_FIELDS(cfg);
    localparam integer RW = (MAX_DIM > 1) ? $clog2(MAX_DIM) : 1;

    // ---- the table: entries m - 1, m, m + 1 of the offered beat's slice ----
    wire [M_W-1:0] in_m = in_hdr[HDR_M +: M_W];
    reg            cur_v;
    reg [M_W-1:0]  cur_m;
    wire           rd = take && (!cur_v || (in_m != cur_m) || in_hdr[HDR_CTRL + CTRL_SOP]);
    always @(posedge clk) begin
        if (rst)       cur_v <= 1'b0;
        else if (take) cur_v <= 1'b1;
        if (take) cur_m <= in_m;
    end
    wire [M_W-1:0]    m_pv = in_m - 1'b1;
    wire [M_W-1:0]    m_nx = in_m + 1'b1;
    wire [RECT_W-1:0] e_p, e_c, e_n;
    cube4_sdp_ram #(.DATA_W(RECT_W), .DEPTH(MAX_DIM)) u_tab_p (
        .clk(clk), .rd_en(rd), .out_en(1'b0), .rd_addr(RW'(m_pv)), .rd_data(e_p),
        .wr_en(rect_we), .wr_addr(RW'(rect_addr)), .wr_data(rect_data));
    cube4_sdp_ram #(.DATA_W(RECT_W), .DEPTH(MAX_DIM)) u_tab_c (
        .clk(clk), .rd_en(rd), .out_en(1'b0), .rd_addr(RW'(in_m)), .rd_data(e_c),
        .wr_en(rect_we), .wr_addr(RW'(rect_addr)), .wr_data(rect_data));
    cube4_sdp_ram #(.DATA_W(RECT_W), .DEPTH(MAX_DIM)) u_tab_n (
        .clk(clk), .rd_en(rd), .out_en(1'b0), .rd_addr(RW'(m_nx)), .rd_data(e_n),
        .wr_en(rect_we), .wr_addr(RW'(rect_addr)), .wr_data(rect_data));
    reg p_ok, n_ok;                  // slices m - 1 >= 0, m + 1 < M (= NK: S = 1)
    always @(posedge clk) begin
        if (rd) begin
            p_ok <= (in_m != '0);
            n_ok <= (m_nx < M_W'(cfg_nk));
        end
    end
    wire             prev_v = p_ok && e_p[RT_INS];
    wire             next_v = n_ok && e_n[RT_INS];
    wire [DIM_W-1:0] p_j0 = e_p[RT_JIN +: DIM_W], p_j1 = e_p[RT_JHI +: DIM_W];
    wire [DIM_W-1:0] p_i0 = e_p[RT_IIN +: DIM_W], p_i1 = e_p[RT_IHIN +: DIM_W];
    assign stx = e_c[RT_STX +: DIM_W];
    assign sty = e_c[RT_STY +: DIM_W];
    wire unused_tab = ^{e_p, e_c, e_n, rect_addr, m_pv};

    // ---- the slot {j, pb}, the read-after-write rule by position, "the row above" ----
    cube4_com_slot #(`CUBE4_SLICE_PASS, .SP_W(SP_W)) u_slot (
        .clk(clk), .rst(rst), .in_hdr(in_hdr), .step(step), .v_fly(v_fly), .sp_fly(sp_fly),
        .r0_m(r0_m), .r0_j(r0_j), .r0_pb(r0_pb),
        .pos_sp(pos_sp), .pos_pb(pos_pb), .hazard(hazard), .col1_4(col1_4));

    // ---- per lane: fresh ray (S0) and next sample inside (S1) ----
    reg             f1_nv;              // slice m + 1's inside rectangle (S1)
    reg [DIM_W-1:0] f1_nj0, f1_nj1, f1_ni0, f1_ni1;
    always @(posedge clk) begin
        f1_nv  <= next_v;
        f1_nj0 <= e_n[RT_JIN +: DIM_W];
        f1_nj1 <= e_n[RT_JHI +: DIM_W];
        f1_ni0 <= e_n[RT_IIN +: DIM_W];
        f1_ni1 <= e_n[RT_IHIN +: DIM_W];
    end
    wire [IW-1:0] j_ext = IW'(r0_j);
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            wire [IW-1:0] i_pv = ipos[q*IW +: IW] - IW'(dxb);
            wire [IW-1:0] j_pv = j_ext - IW'(dyb);
            assign fresh[q] = !(prev_v && (j_pv >= IW'(p_j0)) && (j_pv <= IW'(p_j1))
                                       && (i_pv >= IW'(p_i0)) && (i_pv <= IW'(p_i1)));
            wire [IW-1:0] i_nx = f1_ipos[q*IW +: IW] + IW'(f1_dxf);
            wire [IW-1:0] j_nx = f1_j + IW'(f1_dyf);
            assign nx_in[q] = f1_nv && (j_nx >= IW'(f1_nj0)) && (j_nx <= IW'(f1_nj1))
                                    && (i_nx >= IW'(f1_ni0)) && (i_nx <= IW'(f1_ni1));
        end
    endgenerate
endmodule
`default_nettype wire

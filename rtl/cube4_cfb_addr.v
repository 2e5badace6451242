`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_addr
// -----------------------------------------------------------------------------
// Purpose
//   The address unit of cube4_cfb: one word address per bank for the partial
//   beam being read. Lane q reads bank q and holds the position t of the
//   partial beam with (c_i + c_j + c_k) mod P = q (eq. 1, CUBE4_LANE_FUNCTIONS):
//     t = (q - skew) mod P              (i not flipped)
//     t = (I_R1 + skew - q) mod P       (i flipped), skew = (c_j + c_k) mod P
//   and reads  A_j + A_k + pbx +/- (t*I_LIN + [t > I_RT])  (golden/cube4/memory.py;
//   pbx: the partial-beam term with its sign and I_A0, cube4_cfb_trav).
//
// Parameters (CUBE4_CFB_PARAMS; ranges as cube4_cfb)
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2, ADDR_W.
//
// Latency
//   Three register stages under advance, as the beat's fields (cube4_cfb_mask):
//   s1 registers each lane's t and A_j + A_k; s2 adds pbx (the base address);
//   the output register adds the lane's +/-(t*I_LIN + [t > I_RT]) from a
//   table of P entries (recomputed every cycle from I_LIN and I_RT, which are
//   stable during a frame).
//
// Ports
//   clk          clock (no reset: data registers only)
//   cfg, cfg_addr  in  view and address registers (I flip, I_R1, I_RT, I_LIN)
//   advance      in   the stages move (cube4_cfb_mask)
//   skew_rd      in   [LANE_W] the read row's skew;  aj, ak, pbx  in  [ADDR_W]
//                     the address terms of the beat (cube4_cfb_trav)
//   t1           out  [P*LANE_W] s1: lane q's position t (at q*LANE_W)
//   addr         out  [P*ADDR_W] the output register: lane q's word address
//
// Bit growth and rounding
//   None: modular address arithmetic in ADDR_W bits (exact for every lane
//   that reads; the others may wrap and are never read).
// =============================================================================
module cube4_cfb_addr #(`CUBE4_CFB_PARAMS) (
    input  wire clk,
    input  wire [VIEW_W-1:0] cfg, input wire [ADR_W_ALL-1:0] cfg_addr,
    input  wire advance,
    input  wire [LANE_W-1:0] skew_rd,
    input  wire [ADDR_W-1:0] aj, input wire [ADDR_W-1:0] ak, input wire [ADDR_W-1:0] pbx,
    output wire [P*LANE_W-1:0] t1,
    output wire [P*ADDR_W-1:0] addr
);
    `CUBE4_VIEW_FIELDS(cfg);
    `CUBE4_LANE_FUNCTIONS
    `CUBE4_ADDR_FIELDS(cfg_addr);

    // t*I_LIN + [t > I_RT] for t = 0 .. P-1, by shifts and adds of the constant t
    function automatic [ADDR_W-1:0] lin_of(input integer t);
        integer b;
        begin
            lin_of = {{(ADDR_W - 1){1'b0}}, (LANE_W'(t) > cfg_i_rt)};
            for (b = 0; b < LANE_W; b = b + 1) begin
                if (((t >> b) & 1) == 1) lin_of = lin_of + (cfg_i_lin << b);
            end
        end
    endfunction
    // a packed vector (entry t at t*ADDR_W): a table of registers, not a RAM
    reg [P*ADDR_W-1:0] lin_tab_q;
    wire [P*LANE_W-1:0] t_d;
    genvar q;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lane
            always @(posedge clk) lin_tab_q[q*ADDR_W +: ADDR_W] <= lin_of(q);
            assign t_d[q*LANE_W +: LANE_W] = lane_pos(q, skew_rd, cfg_flip_i, cfg_i_r1);
        end
    endgenerate

    reg [P*LANE_W-1:0] t1_q, t2_q;        // lane positions t of the read
    reg [ADDR_W-1:0]   ajk1_q;            // A_j + A_k
    reg [ADDR_W-1:0]   pbx1_q;
    reg [ADDR_W-1:0]   base2_q;           // A_j + A_k + pbx
    reg                flip1_q, flip2_q;
    reg [P*ADDR_W-1:0] addr_q;
    // each lane's table entry at its t (cube4_mux: no index arithmetic in front of it)
    wire [P*ADDR_W-1:0] lin2;
    generate
        for (q = 0; q < P; q = q + 1) begin : g_lin
            cube4_mux #(.N(P), .W(ADDR_W)) u_lin (
                .words(lin_tab_q), .sel(t2_q[q*LANE_W +: LANE_W]), .word(lin2[q*ADDR_W +: ADDR_W]));
        end
    endgenerate
    integer ql;
    always @(posedge clk) begin
        if (advance) begin
            // s1
            t1_q    <= t_d;
            ajk1_q  <= aj + ak;
            pbx1_q  <= pbx;
            flip1_q <= cfg_flip_i;
            // s2
            t2_q    <= t1_q;
            base2_q <= ajk1_q + pbx1_q;
            flip2_q <= flip1_q;
            // output register
            for (ql = 0; ql < P; ql = ql + 1) begin
                addr_q[ql*ADDR_W +: ADDR_W] <= flip2_q ? base2_q - lin2[ql*ADDR_W +: ADDR_W]
                                                      : base2_q + lin2[ql*ADDR_W +: ADDR_W];
            end
        end
    end
    assign t1   = t1_q;
    assign addr = addr_q;
endmodule
`default_nettype wire

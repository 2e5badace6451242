`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_trav
// -----------------------------------------------------------------------------
// Purpose
//   The traversal unit of cube4_cfb: the counters of the schedule
//   (docs/architecture.md "Front end") and the per-axis address terms kept
//   with them (golden/cube4/memory.py):
//     pass    m, k0 (lower voxel slice), r = m mod S; c_k mod P and A_k of the
//             next voxel slice to read, c_k mod P of the pass's lower slice
//     row     j, pb, the slot j * NB + pb, pb * P, the partial-beam address
//             term (I_A0 folded in), c_j mod P and A_j
//   A pass starts with the row counters at its rectangle's first row and
//   partial beam (rt_nxt: while idle pass 0's, at next_pass the next pass's);
//   each beat steps them; a row's last partial beam goes back to the first.
//   The skews (c_j + c_k) mod P of the read row, of the pass's row, and of
//   the virtual row JL + 1 (the pass's last emitted row) follow.
//
// Parameters (CUBE4_CFB_PARAMS; ranges as cube4_cfb)
//   P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2, ADDR_W.
//
// Latency
//   Registers; every output is a register or combinational from them and cfg.
//   The pass counters load while idle (not in reset) and step at next_pass
//   (advance and pass_next); the row counters load while idle and at
//   next_pass, and step with a beat (advance, not idle). Their next value is
//   chosen by idle and pass_next alone, and advance is only their enable: it
//   comes from the request stream's ready, a long way from here, so it
//   passes one gate to the registers' enables, none of their next-value logic
//   (a placed SLAB build's path, the skid's ready through four gates of it).
//   last_pass is a register kept with the pass counters (set from the counters'
//   next values), so that the box's FLUSH and LAST, and with them pass_done
//   and next_pass, start at a flop rather than behind k0's compare.
//
// Ports (past clk, rst and the register buses: CUBE4_CFB_TRAV_PORTS)
//   clk, rst     clock, synchronous active-high reset (no register is reset;
//                the pass counters hold while rst is high)
//   cfg, cfg_addr  in  view and address registers (cube4_defs.vh)
//   rt_cur, rt_nxt in  [RECT_W] pass m's entry, the next pass's (CUBE4_RECT_LAYOUT)
//   idle         in   the control unit is idle
//   advance      in   the state's beat leaves (cube4_cfb_mask; a beat when not idle)
//   pass_next    in   that beat ends the pass and a next pass follows (next_pass
//                = advance and pass_next: cube4_cfb_ctl)
//   row          in   the beat ends a row that is not the pass's last
//   flush_row    in   the beat ends the pass and a flush beam follows (slots)
//   m [M_W], k0_odd, r [CFB_R_W], j [DIM_W], pb [PB_W], sb [SB_W]   out  counters
//   pbp [IW]     out  pb * P;  pbx, aj, ak [ADDR_W]  out  address terms
//   last_pb, last_j  out  pb and j are the pass's last (PBL, JL)
//   last_pass    out  k0 = NK - 1 and r = 0 (the box's last pass)
//   lower_mem, upper_mem  out  the pass reads its lower / upper voxel slice
//   skew_rd, skew_pas, skew_vrt  out  [LANE_W] the skews above
//
// Bit growth and rounding
//   None: counters and modular address arithmetic in ADDR_W bits.
// =============================================================================
module cube4_cfb_trav #(`CUBE4_CFB_PARAMS) (
    input  wire clk, input wire rst,
    input  wire [VIEW_W-1:0] cfg, input wire [ADR_W_ALL-1:0] cfg_addr,
    `CUBE4_CFB_TRAV_PORTS
);
    // the entries (the box's constant fields as constants: CUBE4_CFB_ENTRY)
    wire [RECT_W-1:0] cur = `CUBE4_CFB_ENTRY(rt_cur);
    wire [RECT_W-1:0] nxt = `CUBE4_CFB_ENTRY(rt_nxt);
    `CUBE4_VIEW_FIELDS(cfg);
    `CUBE4_LANE_FUNCTIONS
    `CUBE4_ADDR_FIELDS(cfg_addr);
    wire unused_trav = ^{cur, nxt};   // the fields read elsewhere

    `CUBE4_STEP_FUNCTIONS

    reg [M_W-1:0]      m_q;        // pass (sample slice)
    reg [DIM_W-1:0]    k0_q;       // lower voxel slice of the pass
    reg [CFB_R_W-1:0]      r_q;        // m mod S
    reg [DIM_W-1:0]    j_q;        // beam
    reg [PB_W-1:0]     pb_q;       // partial beam
    reg                lpb_q;      // pb_q is the last partial beam (PBL)
    reg                lj_q;       // j_q is the last beam (JL)
    reg [SB_W-1:0]     sb_q;       // j * NB + pb
    reg [IW-1:0]       pbp_q;      // pb * P
    reg [ADDR_W-1:0]   pbx_q;      // I_A0 - pb * I_PB (i flipped), pb * I_PB (not)
    reg [LANE_W-1:0]   rj_q;       // c_j mod P
    reg [ADDR_W-1:0]   aj_q;       // A_j(c_j)
    reg [LANE_W-1:0]   rk_q;       // c_k mod P of the next slice to read
    reg [ADDR_W-1:0]   ak_q;       // A_k(c_k) of the next slice to read
    reg [LANE_W-1:0]   rk0_q;      // c_k mod P of the pass's lower slice
    reg                lp_q;       // k0_q = NK - 1 and r_q = 0 (last_pass)

    wire [2:0]     g      = {1'b0, cfg_ss_log2};
    wire [CFB_R_W-1:0] ss_m1  = CFB_R_W'((1 << g) - 1);
    wire           last_r = (r_q == ss_m1);
    wire           any_read = lower_mem || upper_mem;
    wire [DIM_W-1:0] k0_inc = k0_q + 1'b1;
    assign last_pass = lp_q;
    assign lower_mem = (g == 3'd0) || (m_q == '0);
    assign upper_mem = (g != 3'd0) && (r_q == CFB_R_W'(1));
    assign skew_rd   = add_p(rj_q, rk_q);
    assign skew_pas  = add_p(rj_q, rk0_q);
    assign skew_vrt  = r_step(skew_pas, cfg_flip_j);   // virtual row JL + 1

    // ---- the pass ----
    always @(posedge clk) begin
        if (!rst) begin
            if (idle) begin
                m_q   <= '0;
                k0_q  <= '0;
                r_q   <= '0;
                rk_q  <= cfg_k_r0;
                ak_q  <= cfg_k_a0;
                rk0_q <= cfg_k_r0;
                lp_q  <= (cfg_nk == DIM_W'(1));   // k0 = 0 = NK - 1, r = 0
            end else if (advance && pass_next) begin
                m_q <= m_q + 1'b1;
                `CUBE4_PASS_NEXT
                if (last_r) begin
                    k0_q <= k0_inc;
                    lp_q <= (k0_inc == cfg_nk - 1'b1);
                end else begin
                    lp_q <= 1'b0;                        // r_q + 1 <= S - 1 is not 0
                end
            end
        end
    end

    // ---- the row and partial beam, slot, address terms ----
    wire [DIM_W-1:0] e_jl  = cur[RT_JL +: DIM_W];
    wire [PB_W-1:0]  e_pb0 = cur[RT_PB0 +: PB_W];
    wire [PB_W-1:0]  e_pbl = cur[RT_PBL +: PB_W];
    wire [DIM_W-1:0] n_j0  = nxt[RT_J0 +: DIM_W];
    wire [PB_W-1:0]  n_pb0 = nxt[RT_PB0 +: PB_W];
    wire row_en = idle || advance;      // the enable (a beat, or idle)
    wire row_ld = idle || pass_next;    // the next value: the next pass's first, or a step
    always @(posedge clk) begin
        if (row_en) begin
            if (row_ld) begin
                j_q   <= n_j0;
                lj_q  <= (n_j0 == nxt[RT_JL +: DIM_W]);
                pb_q  <= n_pb0;
                lpb_q <= (n_pb0 == nxt[RT_PBL +: PB_W]);
                sb_q  <= nxt[RT_SB0 +: SB_W];
                pbp_q <= nxt[RT_PBP0 +: IW];
                pbx_q <= nxt[RT_PBX0 +: ADDR_W];
                rj_q  <= nxt[RT_RJ0 +: LANE_W];
                aj_q  <= nxt[RT_AJ0 +: ADDR_W];
            end else begin
                if (!lpb_q) begin
                    pb_q  <= pb_q + 1'b1;
                    lpb_q <= (pb_q + 1'b1 == e_pbl);
                    pbp_q <= pbp_q + IW'(P);
                    pbx_q <= cfg_flip_i ? pbx_q - cfg_i_pb : pbx_q + cfg_i_pb;
                    sb_q  <= sb_q + 1'b1;
                end else begin
                    pb_q  <= e_pb0;
                    lpb_q <= (e_pb0 == e_pbl);
                    pbp_q <= cur[RT_PBP0 +: IW];
                    pbx_q <= cur[RT_PBX0 +: ADDR_W];
                end
                if (row) begin
                    j_q  <= j_q + 1'b1;
                    lj_q <= (j_q + 1'b1 == e_jl);
                    sb_q <= sb_q + cur[RT_SBROW +: SB_W];
                    rj_q <= r_step(rj_q, cfg_flip_j);
                    aj_q <= a_step(aj_q, rj_q, cfg_flip_j, cfg_j_lin, cfg_j_blk);
                end
                if (flush_row) sb_q <= cur[RT_SB0 +: SB_W];   // the flush beam's slots
            end
        end
    end

    assign {m, k0_odd, r, j, pb, sb, pbp, pbx, aj, ak} =
           {m_q, k0_q[0], r_q, j_q, pb_q, sb_q, pbp_q, pbx_q, aj_q, ak_q};
    assign {last_pb, last_j} = {lpb_q, lj_q};
endmodule
`default_nettype wire

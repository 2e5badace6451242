// cube4_ebr_plan.vh: how the ECP5 vendor layer lays a RAM of DATA_W-bit words, DEPTH deep, over
// DP16KD block RAMs; included inside rtl/ecp5/cube4_sdp_ram.v and rtl/ecp5/cube4_dual_read_ram.v
// after their parameters (one definition of the plan for both).
//
// The block's shapes s = 0 .. 4: 1024 x 18, 2048 x 9, 4096 x 4, 8192 x 2, 16384 x 1 (width
// ebr_w(s), 2^(10 + s) words). The word is cut into column slices; every slice is a column of
// ebr_banks(s, DEPTH) blocks of one shape, stacked in depth (word a in block a >> (10 + s)).
// The plan is the shape of the depth (ebr_natural: one block deep, so no multiplexer between the
// blocks' output registers and the caller) unless a plan of the form "n slices of shape sm, the
// bits left in slices of shape sr", at most EBR_MAX_BANKS blocks deep, takes fewer blocks; then
// the cheapest such plan (the fewest blocks; among equals the shallowest). Examples: 4096 x 9
// takes two 2048 x 9 blocks instead of three 4096 x 4; 6145 x 20 takes 2 columns of four
// 2048 x 9 and one 8192 x 2, 9 blocks instead of ten 8192 x 2.
//   ebr_plan(DATA_W, DEPTH) = {sm, sr} as sm * 8 + sr; slices: ebr_n_main full slices of sm,
//   then ebr_n_rest slices of sr (the last one narrower where the bits run out).
localparam integer EBR_MAX_BANKS = 4;          // a 4:1 multiplexer at most behind the blocks
function automatic integer ebr_w(input integer s);
    ebr_w = (s == 0) ? 18 : ((s == 1) ? 9 : ((s == 2) ? 4 : ((s == 3) ? 2 : 1)));
endfunction
function automatic integer ebr_banks(input integer s, input integer depth);
    ebr_banks = (depth + (1 << (10 + s)) - 1) >> (10 + s);
endfunction
function automatic integer ebr_natural(input integer depth);
    integer s;
    begin
        ebr_natural = 4;
        for (s = 3; s >= 0; s = s - 1)
            if (depth <= (1 << (10 + s))) ebr_natural = s;
    end
endfunction
function automatic integer ebr_n_main(input integer w, input integer sm, input integer sr);
    ebr_n_main = (sm == sr) ? (w + ebr_w(sm) - 1) / ebr_w(sm) : w / ebr_w(sm);
endfunction
function automatic integer ebr_n_rest(input integer w, input integer sm, input integer sr);
    integer r;
    begin
        r = w - ebr_n_main(w, sm, sr) * ebr_w(sm);
        ebr_n_rest = (sm == sr || r <= 0) ? 0 : (r + ebr_w(sr) - 1) / ebr_w(sr);
    end
endfunction
function automatic integer ebr_cost(input integer w, input integer depth, input integer sm, input integer sr);
    ebr_cost = ebr_n_main(w, sm, sr) * ebr_banks(sm, depth) + ebr_n_rest(w, sm, sr) * ebr_banks(sr, depth);
endfunction
function automatic integer ebr_deep(input integer w, input integer depth, input integer sm, input integer sr);
    ebr_deep = (ebr_n_rest(w, sm, sr) > 0 && ebr_banks(sr, depth) > ebr_banks(sm, depth))
             ? ebr_banks(sr, depth) : ebr_banks(sm, depth);
endfunction
function automatic integer ebr_plan(input integer w, input integer depth);
    integer sm, sr, best, cost, deep;
    begin
        best = ebr_natural(depth) * 9;
        for (sm = 0; sm < 5; sm = sm + 1)
            for (sr = 0; sr < 5; sr = sr + 1) begin
                cost = ebr_cost(w, depth, sm, sr);
                deep = ebr_deep(w, depth, sm, sr);
                if (deep <= EBR_MAX_BANKS
                    && (cost < ebr_cost(w, depth, best / 8, best % 8)
                        || (cost == ebr_cost(w, depth, best / 8, best % 8)
                            && deep < ebr_deep(w, depth, best / 8, best % 8))))
                    best = sm * 8 + sr;
            end
        ebr_plan = best;
    end
endfunction
// slice sl of the plan {sm, sr}: its shape, its lowest bit, its width
function automatic integer ebr_sl_shape(input integer w, input integer plan, input integer sl);
    ebr_sl_shape = (sl < ebr_n_main(w, plan / 8, plan % 8)) ? plan / 8 : plan % 8;
endfunction
function automatic integer ebr_sl_lo(input integer w, input integer plan, input integer sl);
    integer nm;
    begin
        nm = ebr_n_main(w, plan / 8, plan % 8);
        ebr_sl_lo = (sl < nm) ? sl * ebr_w(plan / 8) : nm * ebr_w(plan / 8) + (sl - nm) * ebr_w(plan % 8);
    end
endfunction
function automatic integer ebr_sl_w(input integer w, input integer plan, input integer sl);
    integer room;
    begin
        room = w - ebr_sl_lo(w, plan, sl);
        ebr_sl_w = (room < ebr_w(ebr_sl_shape(w, plan, sl))) ? room : ebr_w(ebr_sl_shape(w, plan, sl));
    end
endfunction

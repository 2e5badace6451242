"""Unit testbench of rtl/cube4_cfb_ctl.v: the CFB's control unit.

The states of golden frames (``cube4_sim.cfb_walk``: the walks of random ``cube4.slices``
rectangles and of the whole box, S = 1 and S = 2) are played as the other units give
them: the traversal unit's counters and skews (``read_terms``), the template of the pass
(``template``), the pass's and the next pass's table entries (``cube4.memory.rect_table``);
the unit advances under a seeded random advance (stalls). On every cycle its outputs must
be the state's:

* the moves: row, flush_row, pass_done and next_pass at the state's end, pass_next
  (the end without advance);
* the beat: issue (not an empty pass), the read-side tag fields (in_run, reads, slot, pb,
  k0 odd), the read flag; sop on the frame's first emitted row, eop on the last flush beat;
* the emitted row (``SliceRects.emitted``' order): emit, its pass, row, skew, Y-last flag,
  its pass's weights and steps, whether it is a row of a pass before (use_prev), its pass's
  positions I_LO, I_IN, I_HI, and whether it holds samples / is inside (rowv, rowin).

After the drain beat the unit is idle.
"""

from __future__ import annotations

import cocotb
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

import cube4.slices as slices
from cube4.memory import rect_table
from cube4.view import make_traversal
from cube4_sim.cfb_walk import cfb_walk, read_terms, tag_offsets, template
from cube4_sim.rect_port import rect_layout, rect_word
from cube4_sim.unit_bench import UnitBench, param_id, run_unit
from cube4_sim.sweeps import sweep

VIEWS = [((0.3, -0.45, 1.0), (13, 9, 6)), ((-0.6, 0.25, -1.0), (11, 10, 5)), ((1.0, -0.4, 0.7), (9, 12, 6))]


def field(word: int, off: dict, name: str, width: int) -> int:
    return (word >> off[name]) & ((1 << width) - 1)


def unit_inputs(trav, p: int, aw: int, st, walk) -> dict[str, int]:
    """The traversal unit's and the template's outputs in state st."""
    s = trav.supersample
    k0, r = divmod(st.m, s)
    wx, wy, wz, steps = template(trav, st.m)
    return {"m": st.m, "j": st.j, "pb": st.pb, "sb": st.sb, "k0_odd": k0 & 1, "r": r,
            "last_pb": int(st.pb == walk[3]), "last_j": int(st.j == walk[1] - 1),
            "lower_mem": int(s == 1 or st.m == 0), "upper_mem": int(s > 1 and r == 1),
            "skew_pas": read_terms(trav, p, k0, st.j, st.pb, aw)["skew"],
            "skew_vrt": read_terms(trav, p, k0, st.j + 1, st.pb, aw)["skew"],
            "wx": wx, "wy": wy, "wz": wz, "steps": steps}


def want_fields(trav, p: int, aw: int, st, inp: dict, table, first_emit: bool, last_pb: bool) -> dict:
    """The tag fields the state's beat must carry (those that matter for it)."""
    run = st.kind == "run"
    want = {"EMIT": int(st.emit is not None), "SOP": int(first_emit), "EOP": int(st.kind == "flush" and st.last
                                                                                   and last_pb),
            "BBWE": int(run), "LMEM": int(run and inp["lower_mem"]), "UMEM": int(run and inp["upper_mem"]),
            "UUSE": int(run and inp["r"] != 0), "K0ODD": inp["k0_odd"], "SB": st.sb, "PB": st.pb}
    if st.emit is not None:
        me, je = st.emit
        wx, wy, wz, steps = template(trav, me)
        want.update(YWRAP=int(me != st.m or st.kind == "flush"), M=me, J=je, WX=wx, WY=wy, WZ=wz, STEPS=steps,
                    SKEW=read_terms(trav, p, me // trav.supersample, je + 1, 0, aw)["skew"],
                    YLAST=int(je == trav.nj - 1))
    return want


async def play(dut, bench, trav, p: int, aw: int, table: list[dict], rects, off: dict, widths: dict,
               stall: float) -> int:
    layout = rect_layout(p, int(dut.MAX_DIM.value), aw)
    entry = lambda m: rect_word(table[m], layout) if m < len(table) else 0  # noqa: E731
    states = cfb_walk(trav, p, rects)
    nb = -(-trav.ni // p)
    await FallingEdge(dut.clk)
    dut.rt_cur.value = dut.rt_nxt.value = entry(0)
    dut.busy.value, dut.start.value = 0, 1
    await ReadOnly()
    assert int(dut.idle.value) and int(dut.go.value), "not idle, or start not taken"
    await FallingEdge(dut.clk)
    dut.start.value, dut.busy.value = 0, 1
    k, first_emit = 0, True
    while k < len(states):
        st = states[k]
        walk = (0, trav.nj, 0, nb - 1) if rects is None else (rects.walk(st.m, p) or (0, 0, 0, 0))
        inp = unit_inputs(trav, p, aw, st, walk)
        for name, val in inp.items():
            getattr(dut, name).value = val
        dut.rt_cur.value, dut.rt_nxt.value = entry(st.m), entry(st.m + 1)
        adv = int(bench.rng.random() >= stall)
        dut.advance.value = adv
        await ReadOnly()
        moves = {n: int(getattr(dut, n).value) for n in ("pass_next", "row", "flush_row", "pass_done", "next_pass", "issue")}
        want = {"pass_next": int(st.pass_done and not st.last), "row": int(st.row), "flush_row": int(st.kind == "run" and st.pass_end),
                "pass_done": adv & st.pass_done, "next_pass": adv & st.pass_done & (not st.last),
                "issue": int(st.kind != "empty")}
        if st.kind in ("empty", "drain"):
            del want["row"], want["flush_row"]          # the counters hold no walk there
        bad = {n: (moves[n], want[n]) for n in want if moves[n] != want[n]}
        assert not bad, f"{st} moves (RTL, golden): {bad}"
        if st.kind in ("run", "flush"):
            fw = int(dut.fields.value)
            wf = want_fields(trav, p, aw, st, inp, table, first_emit and st.emit is not None, st.pb == walk[3])
            bad = {n: (field(fw, off, n, widths[n]), v) for n, v in wf.items() if field(fw, off, n, widths[n]) != v}
            assert not bad, f"{st} tag fields (RTL, golden): {bad}"
            assert int(dut.rd.value) == int(st.read is not None), f"{st}: rd {int(dut.rd.value)}"
            if st.emit is not None:
                me, je = st.emit
                pe = table[me]
                rowv = int(pe["tj0"] <= je <= pe["tjl"])
                rowin = int(je >= pe["j_in"] and not (je == pe["tjl"] and int(trav.weights(me)[1]) > 0))
                got = (int(dut.rowv.value), int(dut.rowin.value))
                assert got == (rowv, rowin), f"{st}: emitted row (rowv, rowin) {got}, golden {(rowv, rowin)}"
                if wf["YWRAP"]:
                    got = tuple(int(getattr(dut, n).value) for n in ("p_ilo", "p_iin", "p_ihi"))
                    assert got == (pe["i_lo"], pe["i_in"], pe["i_hi"]), f"{st}: the emitted row's positions {got}"
        await FallingEdge(dut.clk)
        if adv:
            first_emit = first_emit and st.emit is None
            k += 1
    dut.advance.value = 1
    await ReadOnly()
    assert int(dut.idle.value), "not idle after the drain beat"
    await FallingEdge(dut.clk)
    dut.busy.value = 0
    return len(states)


@cocotb.test()
async def test_ctl(dut):
    p, md, aw, w = (int(getattr(dut, n).value) for n in ("P", "MAX_DIM", "ADDR_W", "WEIGHT_W"))
    ss_max = 1 << int(dut.MAX_SS_LOG2.value)
    off = tag_offsets(p, md, int(dut.MAX_SS_LOG2.value), w)
    names = list(off)
    widths = {n: off[names[i + 1]] - off[n] for i, n in enumerate(names[:-3])}
    bench = UnitBench(dut)
    await bench.reset({"start": 0, "busy": 0, "advance": 0})
    total = 0
    for n, (direction, dims) in enumerate(VIEWS):
        stall = (0.0, 0.3, 0.6)[n % 3]
        one = make_traversal(dims, direction, w, 1)
        for ss in sorted({1, ss_max}):
            trav = make_traversal(dims, direction, w, ss)
            box = rect_table(one, slices.whole_box_rects(one), p, aw)[0]
            M = trav.num_sample_slices
            table = [{**box, "flush": int(m == M - 1), "last": int(m == M - 1)} for m in range(M)]
            bench.set_view(trav, p)
            total += await play(dut, bench, trav, p, aw, table, None, off, widths, stall)
        for density in (0.05, 0.3) if int(dut.RECTS.value) else ():
            need = bench.rng.random((one.num_sample_slices, one.nj, one.ni)) < density
            rects = slices.rects_from_needed(need, one)
            if rects.last() >= 0:
                bench.set_view(one, p)
                total += await play(dut, bench, one, p, aw, rect_table(one, rects, p, aw), rects, off, widths, stall)
    dut._log.info("%d states: moves, tag fields and emitted rows as the golden walk", total)


BUILDS = [{"P": 1, "RECTS": 0}, {"P": 5, "RECTS": 1}]   # RECTS = 0: whole-box frames only


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_cfb_ctl(params):
    run_unit(__file__, {"MAX_DIM": 32, "ADDR_W": 16, "WEIGHT_W": 8, "MAX_SS_LOG2": 1, **params})

"""Unit testbench of rtl/cube4_cfb_trav.v: the CFB's traversal counters and address terms.

The states of golden frames (``cube4_sim.cfb_walk``: the passes, rows and partial beams of
``cube4.slices`` walks, flush beams, empty passes, the drain beat) are played into the
unit's strobes (advance, row, flush_row, pass_next) with seeded random stalls between them,
the pass's rectangle-table entries (``cube4.memory.rect_table``) on rt_cur / rt_nxt as the
table reader gives them. Before each advance the unit's outputs must be those of the state:

* m, j, pb, the slot, pb * P, last_pb, last_j, lower_mem / upper_mem;
* on a read beat: A_j, A_k, the partial-beam term and the read row's skew as
  ``cube4.memory`` keeps them (``read_terms``), and the address each bank forms from them
  equal to ``cube4.memory.address_of`` of the voxel it holds (``read_addresses``);
* on a run beat: the skews of the pass's row and of the row above (for the emitted row);
* during a stall nothing moves; after the frame the unit is back at pass 0's first beat.

Views: flipped axes, each major axis, S = 2 (MAX_SS_LOG2 = 1) without rectangles, and
frames of random slice rectangles (S = 1).
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

import cube4.slices as slices
from cube4.memory import frontend_regs
from cube4.view import make_traversal
from cube4_sim.cfb_walk import cfb_walk, read_addresses, read_terms
from cube4_sim.rect_port import rect_words
from cube4_sim.unit_bench import UnitBench, param_id, run_unit
from cube4_sim.sweeps import sweep

VIEWS = [((0.3, -0.45, 1.0), (13, 9, 6)), ((-0.6, 0.25, -1.0), (11, 10, 5)), ((1.0, 0.4, -0.7), (9, 12, 8)),
         ((0.5, -1.0, 0.5), (10, 7, 11))]
OUTS = ("m", "j", "pb", "sb", "pbp", "last_pb", "last_j", "lower_mem", "upper_mem")


def lane_addresses(regs: dict, terms: dict, p: int, aw: int) -> list[int]:
    """The address each bank forms from the unit's terms (cube4_cfb_addr's sum)."""
    out = []
    for q in range(p):
        t = ((regs["I_R1"] + terms["skew"] - q) if regs["FLIP_I"] else (q - terms["skew"])) % p
        lin = t * regs["I_LIN"] + int(t > regs["I_RT"])
        base = terms["aj"] + terms["ak"] + terms["pbx"]
        out.append((base - lin if regs["FLIP_I"] else base + lin) % (1 << aw))
    return out


def expected(trav, p: int, aw: int, st, rects) -> dict:
    s = trav.supersample
    walk = (0, trav.nj, 0, -(-trav.ni // p) - 1) if rects is None else rects.walk(st.m, p)
    return {"m": st.m, "j": st.j, "pb": st.pb, "sb": st.sb, "pbp": st.pb * p,
            "last_pb": int(st.pb == walk[3]), "last_j": int(st.j == walk[1] - 1),
            "lower_mem": int(s == 1 or st.m == 0), "upper_mem": int(s > 1 and st.m % s == 1)}


def check_state(dut, trav, p: int, aw: int, st, rects, regs: dict) -> None:
    got = {n: int(getattr(dut, n).value) for n in OUTS}
    want = expected(trav, p, aw, st, rects)
    bad = {n: (got[n], want[n]) for n in want if got[n] != want[n]}
    assert not bad, f"{st} (RTL, golden): {bad}"
    k0 = st.m // trav.supersample
    pas = read_terms(trav, p, k0, st.j, st.pb, aw)["skew"]
    vrt = read_terms(trav, p, k0, st.j + 1, st.pb, aw)["skew"]
    got_sk = (int(dut.skew_pas.value), int(dut.skew_vrt.value))
    assert got_sk == (pas, vrt), f"{st}: skews of the pass's row / the row above {got_sk}, golden {(pas, vrt)}"
    if st.read is None:
        return
    terms = read_terms(trav, p, st.read, st.j, st.pb, aw)
    got_t = {"aj": int(dut.aj.value), "ak": int(dut.ak.value), "pbx": int(dut.pbx.value),
             "skew": int(dut.skew_rd.value)}
    assert got_t == terms, f"{st}: read terms {got_t}, golden {terms}"
    want_a = read_addresses(trav, p, st.read, st.j, st.pb)
    have_a = lane_addresses(regs, got_t, p, aw)
    bad_q = [q for q in range(p) if want_a[q] is not None and want_a[q] != have_a[q]]
    assert not bad_q, f"{st} bank {bad_q[0]}: address {have_a[bad_q[0]]}, memory.py {want_a[bad_q[0]]}"


async def play(dut, bench, trav, p: int, aw: int, words: list[int], rects, gap: float) -> int:
    """One frame; words[m]: pass m's table entry."""
    regs = frontend_regs(trav, p)
    states = cfb_walk(trav, p, rects)
    entry = lambda m: words[m] if m < len(words) else 0  # noqa: E731
    dut.idle.value = 1
    dut.rt_cur.value = dut.rt_nxt.value = entry(0)
    await bench.cycles(2)
    for st in states:
        await FallingEdge(dut.clk)
        dut.idle.value = 0
        dut.rt_cur.value, dut.rt_nxt.value = entry(st.m), entry(st.m + 1)
        dut.advance.value = 0
        # pass_next is the state's own (it does not wait for advance): a stall must hold
        # the counters even where it is set
        dut.pass_next.value = int(st.pass_done and not st.last)
        while bench.rng.random() < gap:          # a stall: nothing moves
            await ReadOnly()
            held = {n: int(getattr(dut, n).value) for n in OUTS}
            await FallingEdge(dut.clk)
            now = {n: int(getattr(dut, n).value) for n in OUTS}
            assert now == held, f"{st}: moved during a stall: {held} -> {now}"
        await ReadOnly()
        if st.kind in ("run", "flush"):
            check_state(dut, trav, p, aw, st, rects, regs)
        else:
            assert int(dut.m.value) == st.m, f"{st}: m {int(dut.m.value)}"
        await FallingEdge(dut.clk)
        dut.advance.value = 1
        dut.row.value = int(st.row)
        dut.flush_row.value = int(st.kind == "run" and st.pass_end)
    await FallingEdge(dut.clk)
    dut.advance.value = dut.pass_next.value = dut.row.value = dut.flush_row.value = 0
    dut.idle.value = 1
    dut.rt_cur.value = dut.rt_nxt.value = entry(0)
    await bench.cycles(2)
    await ReadOnly()
    # Pass 0's table entry: its first row and partial beam (0, 0 for the box, and for an
    # empty pass 0 of slice rectangles, whose entry's fields are zero; its first run state
    # is then in a later pass).
    walk0 = (0, trav.nj, 0, 0) if rects is None else (rects.walk(0, p) or (0, 0, 0, 0))
    got = (int(dut.m.value), int(dut.j.value), int(dut.pb.value))
    assert got == (0, walk0[0], walk0[2]), f"after the frame: (m, j, pb) = {got}, pass 0's entry starts at {walk0}"
    await FallingEdge(dut.clk)
    return len(states)


@cocotb.test()
async def test_trav(dut):
    p, md, aw, w = (int(getattr(dut, n).value) for n in ("P", "MAX_DIM", "ADDR_W", "WEIGHT_W"))
    ss_max = 1 << int(dut.MAX_SS_LOG2.value)
    bench = UnitBench(dut)
    await bench.reset({"idle": 1, "advance": 0, "pass_next": 0, "row": 0, "flush_row": 0})
    total = 0
    for n, (direction, dims) in enumerate(VIEWS):
        gap = (0.0, 0.3, 0.6)[n % 3]
        for ss in sorted({1, ss_max}):
            trav = make_traversal(dims, direction, w, ss)
            one = make_traversal(dims, direction, w, 1)     # the box's entry does not depend on S
            box = rect_words(one, slices.whole_box_rects(one), p, md, aw)[0]
            bench.set_view(trav, p)
            total += await play(dut, bench, trav, p, aw, [box] * trav.num_sample_slices, None, gap)
        trav = make_traversal(dims, direction, w, 1)
        for density in (0.05, 0.3) if int(dut.RECTS.value) else ():
            need = bench.rng.random((trav.num_sample_slices, trav.nj, trav.ni)) < density
            rects = slices.rects_from_needed(need, trav)
            if rects.beats(p) == 0:
                continue
            bench.set_view(trav, p)
            total += await play(dut, bench, trav, p, aw, rect_words(trav, rects, p, md, aw), rects, gap)
        dut._log.info("view %s dims %s gap %.1f: counters, slots, address terms and skews right", direction, dims, gap)
    dut._log.info("%d states checked", total)


BUILDS = [{"P": 1, "RECTS": 0}, {"P": 5, "RECTS": 1}]   # RECTS = 0: whole-box frames only


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_cfb_trav(params):
    run_unit(__file__, {"MAX_DIM": 32, "ADDR_W": 16, "MAX_SS_LOG2": 1, "WEIGHT_W": 8, **params})

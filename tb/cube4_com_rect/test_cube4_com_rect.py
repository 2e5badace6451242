"""Unit testbench of rtl/cube4_com_rect.v: COM's slice geometry with slice rectangles.

For golden views and random rectangles (``cube4.slices.rects_from_needed``; sparse sets
give slices of one or two beats), the table (``cube4_sim.rect_port.rect_words``) is
written through the rect_* port and the beats of the traversed rectangles
(``cube4_sim.beats.BeatSchedule``) are offered with seeded random gaps, taken only when
the golden read-after-write rule allows (no beat of the same slot {j, pb} in R0 .. S9),
and played through R0 and S1 as cube4_com_seq gives them. Checked against the golden
model on every beat:

* offered: hazard = a beat of the offered beat's slot is in R0 .. S9;
* R0: the slot {j, pb}, pb; stepx(m), stepy(m) (``Traversal.steps``); per lane "fresh":
  the ray's previous sample (m-1, j-dyb, i-dxb) is not in slice m-1's
  ``SliceRects.inside``;
* S1: per lane "next inside": (m+1, j+dyf, i+dxf) is in slice m+1's ``SliceRects.inside``;
* S4: col1 = the beat before it is the row above at the same partial beam.

Every beat offered must be taken and checked (the count is compared).

The test can fail (tried with a deliberately corrupted expectation, not kept).
"""

from __future__ import annotations


import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

import cube4.slices as slices
from cube4.view import make_traversal
from cube4_sim.beats import BeatSchedule, Geometry, clog2, mask_bits, pack_lanes, unpack_lanes
from cube4_sim.rect_port import rect_words
from cube4_sim.unit_bench import UnitBench, param_id, run_unit
from cube4_sim.sweeps import sweep


VIEWS = [(0.3, -0.45, 1.0), (-0.6, 0.25, -1.0), (1.0, 0.4, -0.7), (0.5, 1.0, 0.5), (-0.2, -1.0, -0.9),
         (1.0, 1.0, 1.0), (0.0, 0.0, -1.0)]


def lookup(mask: np.ndarray, j, i) -> np.ndarray:
    """mask[j, i] where (j, i) lies in the slice, else False."""
    nj, ni = mask.shape
    ok = (j >= 0) & (j < nj) & (i >= 0) & (i < ni)
    out = np.zeros(np.shape(i), dtype=bool)
    out[ok] = mask[np.broadcast_to(j, np.shape(i))[ok], np.asarray(i)[ok]]
    return out


async def play(dut, bench, trav, rects, p: int, geo: Geometry, iw: int, gap: float) -> int:
    M = trav.num_sample_slices
    sched = BeatSchedule(trav, p, np.ones((M, trav.nj, trav.ni), dtype=bool), rects=rects)
    hdrs = sched.headers(geo)
    n, m, j, pb, pos = len(sched), sched.m, sched.j, sched.pb, sched.pos
    sx, sy = trav.steps(m)
    sxb, syb = trav.steps(m - 1)
    sxf, syf = trav.steps(m + 1)
    dxb, dyb, dxf, dyf = sx - sxb, sy - syb, sxf - sx, syf - sy
    ins = {k: rects.inside(k) for k in range(-1, M + 1)}
    fresh = np.stack([~lookup(ins[m[b] - 1], j[b] - dyb[b], pos[b] - dxb[b]) if m[b] > 0
                      else np.ones(p, dtype=bool) for b in range(n)])
    nx_in = np.stack([lookup(ins[m[b] + 1], j[b] + dyf[b], pos[b] + dxf[b]) if m[b] + 1 < M
                      else np.zeros(p, dtype=bool) for b in range(n)])
    slot = (j << geo.pb_w) | pb
    col1 = np.zeros(n, dtype=bool)
    col1[1:] = (m[1:] == m[:-1]) & (pb[1:] == pb[:-1]) & (j[1:] == j[:-1] + 1)
    sp_w = clog2(int(dut.MAX_DIM.value)) + geo.pb_w
    r0, k, c, offering = {}, 0, 0, False
    checked = 0
    while k < n or any(t >= c - 5 for t in r0):
        await FallingEdge(dut.clk)
        b0, b1, b4 = r0.get(c), r0.get(c - 1), r0.get(c - 4)
        fly = [r0.get(c - s) for s in range(1, 10)]
        dut.step.value = int(b0 is not None)
        dut.v_fly.value = mask_bits([b is not None for b in fly])
        dut.sp_fly.value = sum(int(slot[b]) << (s * sp_w) for s, b in enumerate(fly) if b is not None)
        if b0 is not None:
            dut.r0_m.value, dut.r0_j.value, dut.r0_pb.value = int(m[b0]), int(j[b0]), int(pb[b0])
            dut.dxb.value, dut.dyb.value = int(dxb[b0]), int(dyb[b0])
            dut.ipos.value = pack_lanes(pos[b0], iw)
        if b1 is not None:
            dut.f1_ipos.value = pack_lanes(pos[b1], iw)
            dut.f1_j.value = int(j[b1])
            dut.f1_dxf.value, dut.f1_dyf.value = int(dxf[b1]), int(dyf[b1])
        if not offering and k < n and bench.rng.random() >= gap:
            offering = True
        hz = offering and any(b is not None and slot[b] == slot[k] for b in [b0] + fly)
        take = offering and not hz
        dut.in_hdr.value = hdrs[k] if offering else int(bench.rng.integers(0, 1 << geo.hdr_w))
        dut.take.value = int(take)
        await ReadOnly()
        if offering:
            assert int(dut.hazard.value) == int(hz), (f"{sched.describe(k)} offered: hazard {int(dut.hazard.value)}, "
                                                      f"golden {int(hz)}")
        if b0 is not None:
            got = (int(dut.pos_sp.value), int(dut.pos_pb.value), int(dut.stx.value), int(dut.sty.value))
            want = (int(slot[b0]), int(pb[b0]), int(sx[b0]), int(sy[b0]))
            assert got == want, f"{sched.describe(b0)} R0 (slot, pb, stx, sty): RTL {got}, golden {want}"
            fr = unpack_lanes(int(dut.fresh.value), p, 1).astype(bool)
            bad = np.flatnonzero(sched.lval[b0] & (fr != fresh[b0]))
            assert bad.size == 0, f"{sched.describe(b0, bad[0])}: fresh {fr[bad[0]]}, golden {fresh[b0][bad[0]]}"
            checked += 1
        if b1 is not None:
            nx = unpack_lanes(int(dut.nx_in.value), p, 1).astype(bool)
            bad = np.flatnonzero(sched.lval[b1] & (nx != nx_in[b1]))
            assert bad.size == 0, f"{sched.describe(b1, bad[0])}: next inside {nx[bad[0]]}, golden {nx_in[b1][bad[0]]}"
        if b4 is not None:
            assert int(dut.col1_4.value) == col1[b4], f"{sched.describe(b4)}: col1 {int(dut.col1_4.value)}"
        if take:
            r0[c + 1] = k
            k, offering = k + 1, False
        c += 1
    await FallingEdge(dut.clk)
    dut.take.value = 0
    assert checked == n, f"{checked} of {n} beats checked"
    return n


@cocotb.test()
async def test_rects(dut):
    p, max_dim, addr_w = int(dut.P.value), int(dut.MAX_DIM.value), int(dut.ADDR_W.value)
    geo = Geometry(p, max_dim, 0)
    iw = clog2(max_dim + 2 * p + 1)   # cube4_defs.vh IW
    bench = UnitBench(dut)
    await bench.reset({"take": 0, "step": 0, "v_fly": 0, "rect_we": 0})
    dims = (max(11, 2 * p + 3), max(9, p + 4), max(8, p + 2))
    frames = 0
    for n, direction in enumerate(VIEWS * 2):
        trav = make_traversal(dims, direction, int(dut.WEIGHT_W.value), 1, phase=(n * 37 % 256, n * 91 % 256))
        density = (0.002, 0.01, 0.05, 0.3)[n % 4]
        need = bench.rng.random((trav.num_sample_slices, trav.nj, trav.ni)) < density
        rects = slices.rects_from_needed(need, trav)
        if rects.last() < 0:
            continue
        await FallingEdge(dut.clk)
        for a, word in enumerate(rect_words(trav, rects, p, max_dim, addr_w)):
            dut.rect_we.value, dut.rect_addr.value, dut.rect_data.value = 1, a, word
            await FallingEdge(dut.clk)
        dut.rect_we.value = 0
        bench.set_view(trav, p)
        await bench.cycles(2)
        gap = (0.0, 0.3, 0.6, 0.1)[n % 4]
        beats = await play(dut, bench, trav, rects, p, geo, iw, gap)
        frames += 1
        dut._log.info("view %s rectangles %.0f%% gap %.1f: %d beats right", direction, 100 * rects.fraction(), gap, beats)
    assert frames >= 8, f"only {frames} frames had a rectangle"


BUILDS = [{"P": 1}, {"P": 5}]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_com_rect(params):
    run_unit(__file__, {"MAX_DIM": 32, **params})

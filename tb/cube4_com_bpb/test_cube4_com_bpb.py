"""Unit testbench of rtl/cube4_com_bpb.v: the base-plane buffers return each ray's previous
partial result.

The beats of golden views (``cube4.view.make_traversal``, ``cube4_sim.beats.BeatSchedule``:
slice, row, partial beam, skew and lane positions, the back steps dxb, dyb) are played
through the stages the unit sees, as cube4_com_seq gives them (slot at S0, partial beam at
S1 and S2, the back steps at S4, the write at S10 / S11), with seeded random bubbles (no
beat in a stage; the unit's fields then random) but never a beat before the one L = NJ*NB
beats back has left S9 (cube4_com's read-after-write rule). The word each beat writes in
lane q is a tag of its sample (m, j, i). At S5, lane q's previous word, chosen as
cube4_com_lane chooses it (dxb ? (t0 ? prevb_sh : back_sh) : s5_back), must be the tag of
the ray's previous sample (m-1, j-dyb, i-dxb) (numerics.md section 8) in every lane that
holds a position and whose ray is not fresh (m = 0, dyb and j = 0, dxb and i = 0). Views:
flipped axes, x-, y- and z-major, S = 2 where the build allows (the k hop only when the
voxel slice changes), and a view one partial beam wide (NB = 1: the row above is the
previous beat). RECTS = 1 takes the slot {j, pb} and "the previous beat is the row above"
(col1) from the test, as cube4_com_rect gives them. Every beat's S5 is checked (the count
of checked beats must be the number played).

The test can fail (tried with a deliberately corrupted expectation, not kept).
"""

from __future__ import annotations


import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge

from cube4_sim.beats import BeatSchedule, Geometry, pack_lanes, unpack_lanes
from cube4_sim.unit_bench import UnitBench, param_id, run_unit
from cube4_sim.sweeps import sweep
from cube4.view import make_traversal


VIEWS = [(0.3, -0.45, 1.0), (-0.6, 0.25, -1.0), (1.0, 0.4, -0.7), (0.5, 1.0, 0.5), (-0.2, -1.0, -0.9)]
RAW = 11   # a beat enters at least 11 cycles after the beat of its slot L beats back


def tag(m, j, i, nj: int, span: int):
    return 1 + (m * nj + j) * span + i


def issue_times(n: int, lim: int, gap: float, rng) -> list[int]:
    """The cycle each beat enters S0: random bubbles, and the read-after-write rule."""
    times, t = [], 0
    for k in range(n):
        t += 1 + int(rng.geometric(1 - gap) - 1 if gap > 0 else 0)
        if k >= lim:
            t = max(t, times[k - lim] + RAW)
        times.append(t)
    return times


async def play(dut, bench, trav, p: int, geo: Geometry, ac_w: int, rects: bool, gap: float) -> int:
    """Play one view's beats; returns the number of beats checked."""
    inside = np.ones((trav.num_sample_slices, trav.nj, trav.ni), dtype=bool)
    sched = BeatSchedule(trav, p, inside)
    nb, nj, ni, n = sched.nb, trav.nj, trav.ni, len(sched)
    span = ni + p
    ctrl = sched.ctrl
    dxb = (ctrl >> 2) & 1
    dyb = (ctrl >> 3) & 1
    dkb = (sched.m % trav.supersample) == 0
    slot = (sched.j << geo.pb_w | sched.pb) if rects else sched.j * nb + sched.pb
    col1 = np.zeros(n, dtype=bool)
    col1[1:] = (sched.m[1:] == sched.m[:-1]) & (sched.pb[1:] == sched.pb[:-1]) & (sched.j[1:] == sched.j[:-1] + 1)
    tags = tag(sched.m[:, None], sched.j[:, None], sched.pos, nj, span)
    times = issue_times(n, nj * nb, gap, bench.rng)
    at = {t: k for k, t in enumerate(times)}
    mask = (1 << ac_w) - 1
    rnd = lambda bits: int(bench.rng.integers(0, 1 << min(bits, 62)))  # noqa: E731
    checked = 0
    for c in range(times[-1] + 13):
        await FallingEdge(dut.clk)
        s = {d: at.get(c - d) for d in (0, 1, 2, 4, 5, 10, 11)}
        dut.rd_sp.value = int(slot[s[0]]) if s[0] is not None else rnd(geo.pb_w)
        dut.pb_rd.value = int(sched.pb[s[1]]) if s[1] is not None else rnd(geo.pb_w)
        dut.v2.value = int(s[2] is not None)
        dut.pb_wr.value = int(sched.pb[s[2]]) if s[2] is not None else rnd(geo.pb_w)
        k = s[4]
        dut.dyb4.value = int(dyb[k]) if k is not None else rnd(1)
        dut.dkb4.value = int(dkb[k]) if k is not None else rnd(1)
        dut.col1_4.value = int(col1[k]) if k is not None else rnd(1)
        dut.wr_en.value = int(s[10] is not None)
        dut.wr_sp.value = int(slot[s[10]]) if s[10] is not None else rnd(geo.pb_w)
        dut.acc_q.value = (pack_lanes(tags[s[11]] & mask, ac_w) if s[11] is not None
                           else pack_lanes(bench.rng.integers(0, 1 << 30, size=p), ac_w))
        k = s[5]
        if k is None:
            continue
        back, bsh, psh = (unpack_lanes(int(getattr(dut, x).value), p, ac_w) for x in ("s5_back", "back_sh", "prevb_sh"))
        m, j, pos = sched.m[k], sched.j[k], sched.pos[k]
        t0 = pos - sched.pb[k] * p == 0
        got = np.where(dxb[k], np.where(t0, psh, bsh), back)
        fresh = (m == 0) | (dyb[k] & (j == 0)) | (dxb[k] & (pos == 0))
        want = tag(m - 1, j - dyb[k], pos - dxb[k], nj, span) & mask
        bad = np.flatnonzero(sched.lval[k] & ~fresh & (got != want))
        assert bad.size == 0, (f"{sched.describe(k, bad[0])}: previous word {got[bad[0]]:#x}, expected the tag "
                               f"{want[bad[0]]:#x} of (m-1, j-{dyb[k]}, i-{dxb[k]})")
        checked += 1
    assert checked == n, f"{checked} of {n} beats checked"
    return n


@cocotb.test()
async def test_previous_words(dut):
    p, ac_w = int(dut.P.value), int(dut.AC_W.value)
    rects = int(dut.RECTS.value) != 0
    ss_max = 1 << int(dut.MAX_SS_LOG2.value)
    geo = Geometry(p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
    bench = UnitBench(dut)
    await bench.reset({"v2": 0, "wr_en": 0})
    dims = (max(11, 2 * p + 3), max(9, p + 4), max(8, p + 2))
    views = [(v, dims) for v in VIEWS] + [((0.1, 0.2, 1.0), (min(p, 4), 6, 5))]   # the last: NB = 1
    total = 0
    for n, (direction, d) in enumerate(views):
        ss = ss_max if n % 2 else 1
        trav = make_traversal(d, direction, 8, ss, phase=(n * 37 % 256, n * 91 % 256))
        bench.set_view(trav, p)
        await bench.cycles(2)
        gap = (0.0, 0.3, 0.6)[n % 3]
        total += await play(dut, bench, trav, p, geo, ac_w, rects, gap)
        dut._log.info("view %s dims %s S=%d gap %.1f: previous words right", direction, d, ss, gap)
    dut._log.info("%d beats checked", total)


BUILDS = [{"P": 1, "AC_W": 36, "MAX_SS_LOG2": 1}, {"P": 5, "AC_W": 44}, {"P": 3, "AC_W": 40, "RECTS": 1}]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(0, 1), ids=param_id))
def test_cube4_com_bpb(params):
    run_unit(__file__, {"MAX_DIM": 32, **params})

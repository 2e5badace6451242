"""Unit testbench of rtl/cube4_com_walk.v: COM's slice geometry without rectangles.

The beats of golden views (``cube4.view.make_traversal``, ``cube4_sim.beats.BeatSchedule``)
are offered with seeded random gaps and taken only when the unit's hazard is low (as
cube4_com_seq takes them), then played through R0 and S1 as cube4_com_seq gives them
(R0: sop, first, m, j, the back steps, each lane's i; S1: i, j and the next steps).
Checked against the golden traversal on every beat:

* R0: the slot j * NB + pb and pb; stepx(m), stepy(m) (``Traversal.steps``); the phase
  of slice m + 1 and, at a slice's first beat, of slice m ((PH0 + m VIEW) mod 2^(W+g));
  per lane "fresh": the ray's previous sample (m-1, j-dyb, i-dxb) is outside the slice;
* S1: m = M - 1; wx(m+1) > 0, wy(m+1) > 0 (``Traversal.weights``); per lane "next inside":
  the next sample (m+1, j+dyf, i+dxf) lies in slice m+1's ``cube4.model.inside_mask``;
* every cycle: hazard = R0 .. S9 hold at least min(NJ*NB, 11) beats (cube4_com's
  read-after-write rule), and then no beat was taken.

Views: flipped axes, x-, y- and z-major, S = 2 (MAX_SS_LOG2 = 1 builds) and small
slices (NJ*NB < 11: the hazard holds beats). One simulation per build, no reset between
views; every beat offered must be taken (the count is checked).

The test can fail (tried with a deliberately corrupted expectation, not kept).
"""

from __future__ import annotations


import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

from cube4.model import inside_mask
from cube4.view import make_traversal
from cube4_sim.beats import BeatSchedule, clog2, mask_bits, pack_lanes, unpack_lanes
from cube4_sim.unit_bench import UnitBench, param_id, run_unit
from cube4_sim.sweeps import sweep


VIEWS = [((0.3, -0.45, 1.0), (13, 9, 8)), ((-0.6, 0.25, -1.0), (11, 10, 9)), ((1.0, 0.4, -0.7), (9, 12, 8)),
         ((0.5, 1.0, 0.5), (10, 9, 11)), ((-0.2, -1.0, -0.9), (8, 11, 10)), ((0.7, 0.3, 1.0), (3, 2, 6))]


def expected(trav, sched: BeatSchedule) -> dict:
    """Per beat: the golden R0 and S1 values."""
    M, nj, ni = trav.num_sample_slices, trav.nj, trav.ni
    m, j, pos = sched.m, sched.j, sched.pos
    sx, sy = trav.steps(m)
    sxb, syb = trav.steps(m - 1)
    sxf, syf = trav.steps(m + 1)
    dxb, dyb = sx - sxb, sy - syb
    one = 1 << trav.phase_bits
    ph = lambda ph0, view, k: (ph0 + k * view) % one  # noqa: E731
    fresh = (m[:, None] == 0) | (j[:, None] - dyb[:, None] < 0) | (pos - dxb[:, None] < 0)
    nx_in = np.zeros_like(pos, dtype=bool)
    wxn = np.zeros(len(m), dtype=bool)
    wyn = np.zeros(len(m), dtype=bool)
    for n in range(len(m)):
        wx, wy, _ = (int(w) for w in trav.weights(int(m[n]) + 1))
        wxn[n], wyn[n] = wx > 0, wy > 0
        if m[n] + 1 < M and j[n] + (syf[n] - sy[n]) < nj:
            ins = inside_mask(trav, int(m[n]) + 1)
            i_nx = pos[n] + (sxf[n] - sx[n])
            ok = i_nx < ni
            nx_in[n, ok] = ins[j[n] + syf[n] - sy[n], i_nx[ok]]
    return {"slot": j * sched.nb + sched.pb, "stx": sx, "sty": sy, "dxb": dxb, "dyb": dyb,
            "dxf": sxf - sx, "dyf": syf - sy, "fresh": fresh, "nx_in": nx_in, "last": m == M - 1,
            "wxn": wxn, "wyn": wyn, "phm_x": ph(trav.phase_x, trav.view_x, m), "phm_y": ph(trav.phase_y, trav.view_y, m),
            "phn_x": ph(trav.phase_x, trav.view_x, m + 1), "phn_y": ph(trav.phase_y, trav.view_y, m + 1)}


async def play(dut, bench, trav, p: int, iw: int, gap: float) -> int:
    inside = np.ones((trav.num_sample_slices, trav.nj, trav.ni), dtype=bool)
    sched = BeatSchedule(trav, p, inside)
    exp = expected(trav, sched)
    n, lim = len(sched), min(trav.nj * sched.nb, 11)
    r0 = {}                              # cycle -> beat in R0
    k, c, offering = 0, 0, False
    while k < n or any(t >= c - 10 for t in r0):
        await FallingEdge(dut.clk)
        # hazard (a register): R0 .. S9 hold lim beats or more; a beat is taken only without it
        held = sum(r0.get(c - s) is not None for s in range(0, 10))
        hz = int(dut.hazard.value)
        assert hz == int(held >= lim), f"cycle {c}: hazard {hz} with {held} beats in R0 .. S9 (limit {lim})"
        if not offering and k < n and bench.rng.random() >= gap:
            offering = True
        take = offering and not hz
        dut.take.value = int(take)
        # the stage inputs of this cycle (registers of cube4_com_seq)
        b0, b1 = r0.get(c), r0.get(c - 1)
        dut.step.value = int(b0 is not None)
        dut.step_c.value = 3 if b0 is not None else 0
        dut.v_fly.value = mask_bits([r0.get(c - s) is not None for s in range(1, 9)])
        if b0 is not None:
            dut.sop.value = int(b0 == 0)
            dut.first.value = int(sched.j[b0] == 0 and sched.pb[b0] == 0)
            dut.r0_m.value, dut.r0_j.value = int(sched.m[b0]), int(sched.j[b0])
            dut.dxb.value, dut.dyb.value = int(exp["dxb"][b0]), int(exp["dyb"][b0])
            dut.ipos.value = pack_lanes(sched.pos[b0], iw)
        if b1 is not None:
            dut.f1_ipos.value = pack_lanes(sched.pos[b1], iw)
            dut.f1_j.value = int(sched.j[b1])
            dut.f1_dxf.value, dut.f1_dyf.value = int(exp["dxf"][b1]), int(exp["dyf"][b1])
        if take:
            r0[c + 1] = k
            k, offering = k + 1, False
        await ReadOnly()
        if b0 is not None:
            e = {x: exp[x][b0] for x in ("slot", "stx", "sty", "phn_x", "phn_y")}
            got = {"slot": int(dut.pos_sp.value), "stx": int(dut.stx.value), "sty": int(dut.sty.value),
                   "phn_x": int(dut.phn_x.value), "phn_y": int(dut.phn_y.value)}
            if sched.j[b0] == 0 and sched.pb[b0] == 0:
                e.update(phm_x=exp["phm_x"][b0], phm_y=exp["phm_y"][b0])
                got.update(phm_x=int(dut.ph_x.value), phm_y=int(dut.ph_y.value))
            bad = {x: (got[x], int(e[x])) for x in e if got[x] != e[x]}
            assert not bad, f"{sched.describe(b0)} R0 (RTL, golden): {bad}"
            assert int(dut.pos_pb.value) == sched.pb[b0], f"{sched.describe(b0)}: pos_pb {int(dut.pos_pb.value)}"
            fr = unpack_lanes(int(dut.fresh.value), p, 1).astype(bool)
            bad = np.flatnonzero(sched.lval[b0] & (fr != exp["fresh"][b0]))
            assert bad.size == 0, f"{sched.describe(b0, bad[0])}: fresh {fr[bad[0]]}, golden {exp['fresh'][b0][bad[0]]}"
        if b1 is not None:
            got = (int(dut.f1_last.value), int(dut.f1_wxn.value), int(dut.f1_wyn.value))
            want = (int(exp["last"][b1]), int(exp["wxn"][b1]), int(exp["wyn"][b1]))
            assert got == want, f"{sched.describe(b1)} S1 (last, wxn, wyn): RTL {got}, golden {want}"
            nx = unpack_lanes(int(dut.nx_in.value), p, 1).astype(bool)
            bad = np.flatnonzero(sched.lval[b1] & (nx != exp["nx_in"][b1]))
            assert bad.size == 0, (f"{sched.describe(b1, bad[0])}: next inside {nx[bad[0]]}, "
                                   f"golden {exp['nx_in'][b1][bad[0]]}")
        c += 1
    await FallingEdge(dut.clk)
    dut.take.value = 0
    assert k == n and len(r0) == n, f"{len(r0)} of {n} beats taken"
    return n


@cocotb.test()
async def test_walk(dut):
    p = int(dut.P.value)
    ss_max = 1 << int(dut.MAX_SS_LOG2.value)
    iw = clog2(int(dut.MAX_DIM.value) + 2 * p + 1)   # cube4_defs.vh IW
    bench = UnitBench(dut)
    await bench.reset({"take": 0, "step": 0, "step_c": 0, "v_fly": 0})
    total = 0
    for n, (direction, dims) in enumerate(VIEWS):
        ss = ss_max if n % 2 else 1
        trav = make_traversal(dims, direction, int(dut.WEIGHT_W.value), ss, phase=((n * 37) % 256 * ss, (n * 91) % 256))
        bench.set_view(trav, p)
        await bench.cycles(2)
        gap = (0.0, 0.3, 0.6)[n % 3]
        total += await play(dut, bench, trav, p, iw, gap)
        dut._log.info("view %s dims %s S=%d gap %.1f: slots, steps, phases, fresh, next inside, hazard right",
                      direction, dims, ss, gap)
    dut._log.info("%d beats checked", total)


BUILDS = [{"P": 1, "MAX_SS_LOG2": 1}, {"P": 5}]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_com_walk(params):
    run_unit(__file__, {"MAX_DIM": 32, **params})

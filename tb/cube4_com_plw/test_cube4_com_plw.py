"""Unit testbench of rtl/cube4_com_plw.v: COM's path-length weights, bit for bit.

Random path-weight columns are written through the lut_* port before every view
(random, not 1 - (1 - A)^w, so a wrong column shows); the beats of golden views
(``cube4_sim.beats.BeatSchedule``) are played through R0, S1 and S3 as cube4_com_seq,
cube4_com_walk and cube4_com_lane give them (R0: m, j, the back steps, each lane's i, the
phases of slices m and m + 1, the lanes' samples; S1: i, j, the next steps, m = M - 1,
wx(m+1) > 0, wy(m+1) > 0; S3: each lane's A), with seeded random bubbles. At S3 every
lane's A must be the golden ``cube4.pathlen.weighted_alpha`` of its sample with the
weight ``cube4.pathlen.weight_quarters(trav, m, faces)`` (the LUT's A where wq = 4), for
FACES = all six faces or a random subset; in the MIP / MinIP views (mode_ext) the A
passes unchanged. Views: flipped axes, x-, y- and z-major, S = 2 (MAX_SS_LOG2 = 1
builds). Every beat is checked (the count is compared).

The test can fail (tried with a deliberately corrupted expectation, not kept).
"""

from __future__ import annotations

from dataclasses import replace

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

from cube4.pathlen import ALL_FACES, weight_quarters, weighted_alpha
from cube4.view import make_traversal
from cube4_sim.beats import BeatSchedule, clog2, pack_lanes, unpack_lanes
from cube4_sim.unit_bench import UnitBench, param_id, run_unit
from cube4_sim.sweeps import sweep


VIEWS = [((0.3, -0.45, 1.0), (13, 9, 8)), ((-0.6, 0.25, -1.0), (11, 10, 9)), ((1.0, 0.4, -0.7), (9, 12, 8)),
         ((0.5, 1.0, 0.5), (10, 9, 11)), ((-0.2, -1.0, -0.9), (8, 11, 10))]


async def write_columns(bench, dut, cols: np.ndarray, aw: int) -> None:
    await FallingEdge(dut.clk)
    for a in range(cols.shape[0]):
        dut.lut_we.value = 1
        dut.lut_addr.value = a
        dut.lut_data.value = sum(int(cols[a, c]) << (c * aw) for c in range(4))
        await FallingEdge(dut.clk)
    dut.lut_we.value = 0


async def play(dut, bench, trav, p: int, iw: int, vw: int, aw: int, cols, ext: bool, gap: float) -> int:
    M, nj, ni = trav.num_sample_slices, trav.nj, trav.ni
    sched = BeatSchedule(trav, p, np.ones((M, nj, ni), dtype=bool))
    n, rng = len(sched), bench.rng
    m, j, pos = sched.m, sched.j, sched.pos
    sx, sy = trav.steps(m)
    sxb, syb = trav.steps(m - 1)
    sxf, syf = trav.steps(m + 1)
    one = 1 << trav.phase_bits
    phase = lambda ph0, view, k: int((ph0 + k * view) % one)  # noqa: E731
    wxn = [int(trav.weights(int(k) + 1)[0]) > 0 for k in m]
    wyn = [int(trav.weights(int(k) + 1)[1]) > 0 for k in m]
    smp = rng.integers(0, 1 << vw, size=(n, p))
    a3 = rng.integers(0, 1 << aw, size=(n, p))
    wq = {}
    want = np.empty((n, p), dtype=np.int64)
    for b in range(n):
        if m[b] not in wq:
            wq[m[b]] = weight_quarters(trav, int(m[b]), trav.faces)
        w = wq[m[b]][j[b], np.minimum(pos[b], ni - 1)]
        want[b] = a3[b] if ext else weighted_alpha(a3[b], smp[b], cols, w)
    r0, c, t = {}, 0, 0
    for b in range(n):                  # the cycle each beat is in R0: random bubbles
        t += 1 + (int(rng.geometric(1 - gap)) - 1 if gap > 0 else 0)
        r0[t] = b
    checked = 0
    for c in range(t + 5):
        await FallingEdge(dut.clk)
        b0, b1, b3 = r0.get(c), r0.get(c - 1), r0.get(c - 3)
        dut.step.value = int(b0 is not None)
        if b0 is not None:
            first = j[b0] == 0 and sched.pb[b0] == 0
            dut.first.value = int(first)
            # ph_x: the phase of slice m at a slice's first beat, else m + 1's (cube4_com_walk)
            dut.ph_x.value = phase(trav.phase_x, trav.view_x, m[b0] + (0 if first else 1))
            dut.ph_y.value = phase(trav.phase_y, trav.view_y, m[b0] + (0 if first else 1))
            dut.phn_x.value = phase(trav.phase_x, trav.view_x, m[b0] + 1)
            dut.phn_y.value = phase(trav.phase_y, trav.view_y, m[b0] + 1)
            dut.r0_m.value, dut.r0_j.value = int(m[b0]), int(j[b0])
            dut.dxb.value, dut.dyb.value = int(sx[b0] - sxb[b0]), int(sy[b0] - syb[b0])
            dut.ipos.value = pack_lanes(pos[b0], iw)
            dut.smp.value = pack_lanes(smp[b0], vw)
        else:
            dut.first.value = int(rng.integers(0, 2))
            dut.smp.value = pack_lanes(rng.integers(0, 1 << vw, size=p), vw)
        if b1 is not None:
            dut.f1_ipos.value = pack_lanes(pos[b1], iw)
            dut.f1_j.value = int(j[b1])
            dut.f1_dxf.value, dut.f1_dyf.value = int(sxf[b1] - sx[b1]), int(syf[b1] - sy[b1])
            dut.f1_last.value = int(m[b1] == M - 1)
            dut.f1_wxn.value, dut.f1_wyn.value = int(wxn[b1]), int(wyn[b1])
        if b3 is not None:
            dut.a3.value = pack_lanes(a3[b3], aw)
        await ReadOnly()
        if b3 is not None:
            got = unpack_lanes(int(dut.a_w.value), p, aw)
            bad = np.flatnonzero(sched.lval[b3] & (got != want[b3]))
            assert bad.size == 0, (f"{sched.describe(b3, bad[0])}: A {got[bad[0]]}, golden {want[b3][bad[0]]} "
                                   f"(sample {smp[b3][bad[0]]}, LUT A {a3[b3][bad[0]]})")
            checked += 1
    await FallingEdge(dut.clk)
    assert checked == n, f"{checked} of {n} beats checked"
    return n


@cocotb.test()
async def test_weights(dut):
    p, vw, aw = (int(getattr(dut, x).value) for x in ("P", "VOXEL_W", "ALPHA_W"))
    ss_max = 1 << int(dut.MAX_SS_LOG2.value)
    iw = clog2(int(dut.MAX_DIM.value) + 2 * p + 1)   # cube4_defs.vh IW
    bench = UnitBench(dut)
    await bench.reset({"step": 0, "lut_we": 0, "mode_ext": 0})
    total = 0
    for n, (direction, dims) in enumerate(VIEWS):
        ss = ss_max if n % 2 else 1
        trav = make_traversal(dims, direction, int(dut.WEIGHT_W.value), ss,
                              phase=((n * 37) % 256 * ss + n, (n * 91) % 256 * ss))
        faces = ALL_FACES if n % 2 == 0 else int(bench.rng.integers(1, ALL_FACES))
        trav = replace(trav, faces=faces)
        ext = n == 3
        cols = bench.rng.integers(0, 1 << aw, size=(1 << vw, 4), dtype=np.int64)
        await write_columns(bench, dut, cols, aw)
        bench.set_view(trav, p, mode="mip" if ext else "composite", path_weights=True)
        dut.mode_ext.value = int(ext)
        await bench.cycles(2)
        gap = (0.0, 0.3, 0.6)[n % 3]
        total += await play(dut, bench, trav, p, iw, vw, aw, cols, ext, gap)
        dut._log.info("view %s dims %s S=%d faces %06b %s gap %.1f: weighted A bit-exact",
                      direction, dims, ss, faces, "mip" if ext else "composite", gap)
    dut._log.info("%d beats checked", total)


BUILDS = [{"P": 1, "MAX_SS_LOG2": 1}, {"P": 5}]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_com_plw(params):
    run_unit(__file__, {"MAX_DIM": 32, **params})

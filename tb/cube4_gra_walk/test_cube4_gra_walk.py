"""Unit testbench of rtl/cube4_gra_walk.v: GRA's position buffers, step by step.

The DUT is ``cube4_gra_walk_harness.v``: cube4_gra_walk with its view registers as
ports, a Verilog clock, the output FIFO's credit as one port and a cube4_stream_check on
the input. The input is a slice-rectangle frame as the front end walks it
(``cube4.slices.SliceRects.walk`` of random rectangles, ``gra=True``): the golden
samples of the zero-filled traversed slices (``cube4.model.rect_slice``) in the beats'
lanes, no lane valid outside the traversed rectangles; offered with random gaps in
valid, with random credit (seeded from COCOTB_RANDOM_SEED). In every cycle with
step = 1 the bench records the interface and checks it, in order, against
``cube4_sim.gra_beats.walk_steps`` (the position buffers' rule: P1, P2b1 from the step
a slice earlier where the previous walk covered the position, B1, C, P1b2, P2b2 from
the row before after the walk's first row, else zero; then the source's own walk over
the last walk's rows and one more, and three empty steps, the last with fend): the
seven beats, C's {real, header}, its select flags and edge bits, fend and sop = 0;
exactly that many steps per frame, and none in the 30 cycles after it with the credit
high (nothing extra).

Frames: five views at three rectangle densities, back to back in one simulation, at
P = 1 and P = 5.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

import cube4.slices as slices
from cube4.memory import lane_positions
from cube4.model import padded_traversal, rect_slice
from cube4.view import make_traversal
from cube4_sim import run_test
from cube4_sim.beats import (CTRL_EOP, CTRL_OSX, CTRL_OSY, CTRL_SOP, CTRL_SX, CTRL_SY, CTRL_YLAST, Geometry,
                             mask_bits, pack_lanes)
from cube4_sim.gra_beats import NEIGHBOURS, walk_steps
from cube4_sim.unit_bench import UnitBench, harness_sources

HERE = Path(__file__).resolve().parent
SOURCES = harness_sources(HERE / "cube4_gra_walk_harness.v")

VIEWS = [(0.3, -0.45, 1.0), (-0.6, 0.25, -1.0), (1.0, 0.4, -0.7), (1.0, 1.0, 1.0), (-1.0, 1.0, 0.0)]
RECORD = NEIGHBOURS + ("c_meta", "c_sel", "c_edge", "fend", "sop")


def walk_beats(vol, rects, trav, p: int, geo: Geometry, vw: int) -> list[dict]:
    """The frame's input beats in walk order: header, packed samples, and the fields
    ``walk_steps`` reads (m, j, pb, real: a lane valid, sy and osy)."""
    M, nj, ni, nk = trav.num_sample_slices, trav.nj, trav.ni, trav.nk
    fi, fj, fk = (bool(trav.flip[a]) for a in (trav.axis_i, trav.axis_j, trav.major))
    src = padded_traversal(vol, trav)
    samples = np.zeros((M, nj, ni), dtype=np.int64)
    for m in range(M):
        if not rects.empty(m):
            samples[m] = rect_slice(src, trav, m, rects.traversed(m), trav.weight_bits)
    order = []
    for m in range(rects.last() + 1):
        w = rects.walk(m, p)
        if w is not None:
            order += [(m, j, pb) for j in range(w[0], w[1]) for pb in range(w[2], w[3] + 1)]
    beats = []
    for n, (m, j, pb) in enumerate(order):
        cj = nj - 1 - (j + 1) if fj else j + 1
        ck = nk - 1 - m if fk else m
        skew = (cj + ck + sum(int(o) for o in trav.origin)) % p
        pos = lane_positions(skew, pb, p, ni, fi)
        tj0, tj1, i0, i1 = rects.traversed(m)
        valid = (pos >= i0) & (pos < i1) & (tj0 <= j < tj1)
        smp = np.where(valid, samples[m, min(j, nj - 1), np.minimum(pos, ni - 1)], 0)
        (sx, sy), (sx1, sy1), (sxb, syb) = (trav.steps(k) for k in (m, m + 1, m - 1))
        ysf, ysb = int(sy1 - sy), int(sy - syb)
        ctrl = ((int(sx1 - sx) << CTRL_SX) | (ysf << CTRL_SY) | (int(sx - sxb) << CTRL_OSX) | (ysb << CTRL_OSY)
                | (int(n == 0) << CTRL_SOP) | (int(n == len(order) - 1) << CTRL_EOP) | (int(j == nj - 1) << CTRL_YLAST))
        hdr = geo.pack_header({"inside": mask_bits(valid), "lval": mask_bits(valid), "keep": mask_bits(valid),
                               "ctrl": ctrl, "skew": skew, "pb": pb, "j": j, "m": m})
        beats.append({"m": m, "j": j, "pb": pb, "hdr": hdr, "x": pack_lanes(smp, vw), "real": bool(valid.any()),
                      "sy": ysf, "osy": ysb})
    return beats


async def run_frame(bench, inputs, n_steps: int, gap: float, stall: float, tail: int = 30) -> list[dict]:
    """As tb/cube4_gra_lines: random gaps and credit, every step's interface recorded,
    then ``tail`` cycles with the credit high and no input."""
    d = bench.dut
    got, k, offering, quiet, cycle = [], 0, False, 0, 0
    while quiet < tail:
        await FallingEdge(d.clk)
        if not offering and k < len(inputs) and bench.rng.random() >= gap:
            for name, val in inputs[k].items():
                bench.sig(name).value = val
            offering = True
        d.in_valid.value = int(offering)
        done = len(got) >= n_steps and k == len(inputs)
        d.credit.value = 1 if done else int(bench.rng.random() >= stall)
        await ReadOnly()
        if offering and int(d.in_ready.value):
            offering, k = False, k + 1
        if int(d.step.value):
            got.append({n: int(bench.sig(n).value) for n in RECORD})
        quiet += int(done)
        cycle += 1
        assert cycle < 200000, f"{len(got)} of {n_steps} steps and {k} of {len(inputs)} beats after {cycle} cycles"
    await FallingEdge(d.clk)
    d.in_valid.value = 0
    d.credit.value = 0
    assert len(got) == n_steps, f"{len(got)} steps, expected {n_steps}: {len(got) - n_steps} extra"
    return got


def check_steps(got, want, p: int, hdr_w: int, log) -> None:
    """Every defined field of every step as expected (None: not defined, not checked)."""
    bad = 0
    for n, (g, w) in enumerate(zip(got, want)):
        errs = [(k, g[k], w[k]) for k in NEIGHBOURS + ("c_meta", "c_edge", "fend", "sop")
                if w[k] is not None and g[k] != w[k]]
        if w["c_real"] is not None and (g["c_meta"] >> hdr_w) != w["c_real"]:
            errs.append(("C's real bit", g["c_meta"] >> hdr_w, w["c_real"]))
        sel_mask = sum(w["c_sel_mask"] << (7 * q) for q in range(p))
        exp_sel = sum(w["c_sel"] << (7 * q) for q in range(p))
        if (g["c_sel"] ^ exp_sel) & sel_mask:
            errs.append(("c_sel", g["c_sel"], exp_sel))
        for name, have, exp in errs:
            bad += 1
            if bad <= 8:
                log.error("step %d (centre m, j, pb = %s): %s RTL %#x, expected %#x", n, w["centre"], name, have, exp)
    assert bad == 0, f"{bad} interface fields differ from the expected steps"


@cocotb.test()
async def test_walk_steps(dut):
    """Walk frames in, the position buffers' neighbourhoods at every step, with stalls."""
    p, vw, w = int(dut.P.value), int(dut.VOXEL_W.value), int(dut.WEIGHT_W.value)
    geo = Geometry(p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
    bench = UnitBench(dut)
    await bench.reset({"in_valid": 0, "credit": 0})
    dims = (max(7, 2 * p + 1), 6, 5)
    vol = bench.rng.integers(0, 1 << vw, size=dims[::-1], dtype=np.int64)
    frames = 0
    for n, direction in enumerate(VIEWS):
        trav = make_traversal(dims, direction, w, 1)
        density = (0.01, 0.04, 0.15)[n % 3]
        need = bench.rng.random((trav.num_sample_slices, trav.nj, trav.ni)) < density
        rects = dataclasses.replace(slices.rects_from_needed(need, trav), gra=True)
        if rects.last() < 0:
            continue
        beats = walk_beats(vol, rects, trav, p, geo, vw)
        want = walk_steps(beats, trav.nj, p, geo.hdr_w, trav.supersample)
        assert len(want) == len(beats) + rects.gra_steps(p), "walk_steps disagrees with SliceRects.gra_steps"
        inputs = [{"in_hdr": b["hdr"], "in_sample": b["x"]} for b in beats]
        bench.set_view(trav, p)
        await bench.cycles(2)
        gap, stall = (0.0, 0.0) if n % 2 == 0 else (0.3, 0.4)
        got = await run_frame(bench, inputs, len(want), gap, stall)
        check_steps(got, want, p, geo.hdr_w, bench.log)
        frames += 1
        bench.log.info("view %s: %d walk beats, %d steps as expected", direction, len(beats), len(got))
    assert frames >= 3, f"only {frames} frames had a rectangle"


BUILDS = [(1, 8), (5, 8)]   # (P, VOXEL_W)


@pytest.mark.parametrize("build", BUILDS, ids=[f"p{b[0]}_v{b[1]}" for b in BUILDS])
def test_cube4_gra_walk(build):
    p, vw = build
    run_test(top="cube4_gra_walk_harness", sources=SOURCES,
             params={"P": p, "VOXEL_W": vw, "MAX_DIM": 16},
             test_module=__file__, testcase="test_walk_steps", timing=True)

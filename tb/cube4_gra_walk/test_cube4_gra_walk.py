"""Unit testbench of rtl/cube4_gra_walk.v: GRA's position buffers, step by step.

The DUT is ``sim/hdl/cube4_gra_source_harness.v`` with WALK = 1: cube4_gra_walk with its
view registers as ports, a Verilog clock, the output FIFO's credit as one port and a
cube4_stream_check on the input. The input is a slice-rectangle frame as the front end walks it
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

import cocotb
import numpy as np
import pytest

import cube4.slices as slices
from cube4.model import padded_traversal, rect_slice
from cube4.view import make_traversal
from cube4_sim.beats import Geometry, mask_bits, pack_lanes
from cube4_sim.gra_beats import NEIGHBOURS, walk_beats, walk_steps
from cube4_sim.unit_bench import SourceBench, param_id, run_unit
from cube4_sim.sweeps import sweep

VIEWS = [(0.3, -0.45, 1.0), (-0.6, 0.25, -1.0), (1.0, 0.4, -0.7), (1.0, 1.0, 1.0), (-1.0, 1.0, 0.0)]
RECORD = NEIGHBOURS + ("c_meta", "c_sel", "c_edge", "fend", "sop")


def frame_beats(vol, rects, trav, p: int, geo: Geometry, vw: int) -> list[dict]:
    """The frame's input beats in walk order: header, packed samples, and the fields
    ``walk_steps`` reads (m, j, pb, real: a lane valid, sy and osy)."""
    M, nj, ni = trav.num_sample_slices, trav.nj, trav.ni
    src = padded_traversal(vol, trav)
    samples = np.zeros((M, nj, ni), dtype=np.int64)
    for m in range(M):
        if not rects.empty(m):
            samples[m] = rect_slice(src, trav, m, rects.traversed(m), trav.weight_bits)
    beats = []
    for b in walk_beats(rects, trav, p):
        smp = np.where(b.valid, samples[b.m, min(b.j, nj - 1), np.minimum(b.pos, ni - 1)], 0)
        lanes = mask_bits(b.valid)
        hdr = geo.pack_header({"inside": lanes, "lval": lanes, "keep": lanes, "ctrl": b.ctrl, "skew": b.skew,
                               "pb": b.pb, "j": b.j, "m": b.m})
        beats.append({"m": b.m, "j": b.j, "pb": b.pb, "hdr": hdr, "x": pack_lanes(smp, vw),
                      "real": bool(b.valid.any()), "sy": b.sy, "osy": b.osy})
    return beats


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
    bench = SourceBench(dut)
    p, vw, w, geo, dims, vol = bench.p, bench.vw, bench.w, bench.geo, bench.dims, bench.vol
    await bench.reset({"in_valid": 0, "credit": 0})
    frames = 0
    for n, direction in enumerate(VIEWS):
        trav = make_traversal(dims, direction, w, 1)
        density = (0.01, 0.04, 0.15)[n % 3]
        need = bench.rng.random((trav.num_sample_slices, trav.nj, trav.ni)) < density
        rects = dataclasses.replace(slices.rects_from_needed(need, trav), gra=True)
        if rects.last() < 0:
            continue
        beats = frame_beats(vol, rects, trav, p, geo, vw)
        want = walk_steps(beats, trav.nj, p, geo.hdr_w, trav.supersample)
        assert len(want) == len(beats) + rects.gra_steps(p), "walk_steps disagrees with SliceRects.gra_steps"
        inputs = [{"in_hdr": b["hdr"], "in_sample": b["x"]} for b in beats]
        bench.set_view(trav, p)
        await bench.cycles(2)
        gap, stall = (0.0, 0.0) if n % 2 == 0 else (0.3, 0.4)
        got = await bench.run_steps(inputs, len(want), RECORD, gap, stall)
        check_steps(got, want, p, geo.hdr_w, bench.log)
        frames += 1
        bench.log.info("view %s: %d walk beats, %d steps as expected", direction, len(beats), len(got))
    assert frames >= 3, f"only {frames} frames had a rectangle"


BUILDS = [{"P": 1, "VOXEL_W": 8}, {"P": 5, "VOXEL_W": 8}]


@pytest.mark.parametrize("build", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_gra_walk(build):
    run_unit(__file__, {**build, "MAX_DIM": 16, "WALK": 1}, "test_walk_steps", harness="cube4_gra_source_harness")

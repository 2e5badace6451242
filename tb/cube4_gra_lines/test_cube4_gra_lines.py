"""Unit testbench of rtl/cube4_gra_lines.v: GRA's delay lines, step by step.

The DUT is ``cube4_gra_lines_harness.v``: cube4_gra_lines with its view registers as
ports, a Verilog clock, the output FIFO's credit as one port and a cube4_stream_check on
the input. The input is the golden sample stream (``cube4.model.sample_stream``) in the
hardware's beat order (``cube4_sim.beats.BeatSchedule``), offered with random gaps in
valid; the credit is random (seeded from COCOTB_RANDOM_SEED), which stalls the steps.
In every cycle with step = 1 the bench records the interface and checks it, in order,
against ``cube4_sim.gra_beats.lines_steps``: X and its six neighbour beats (the golden
samples of the beats n - NB, n - NJ*NB, ... in their own lanes, zero in the flush; a
word from before the frame is stale and not checked), C's {real, header} and select
flags, and sop; exactly
M*NJ*NB + NJ*NB + NB + 2 steps per frame, and none in the 30 cycles after a frame with
the credit high (nothing extra). fend and c_edge stay 0.

Views: three directions (flipped axes among them), back to back in one simulation, at
P = 1 and P = 5; the P = 5 build runs them supersampled (S = 2).
"""

from __future__ import annotations

from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

from cube4.model import sample_stream
from cube4.view import make_traversal
from cube4_sim import run_test
from cube4_sim.beats import BeatSchedule, Geometry, pack_lanes
from cube4_sim.gra_beats import NEIGHBOURS, lines_steps
from cube4_sim.unit_bench import UnitBench, harness_sources

HERE = Path(__file__).resolve().parent
SOURCES = harness_sources(HERE / "cube4_gra_lines_harness.v")

# (direction, input gap probability, credit stall probability)
VIEWS = [((0.3, -0.45, 1.0), 0.0, 0.0), ((-0.6, 0.25, -1.0), 0.3, 0.4), ((1.0, 0.4, -0.7), 0.5, 0.2)]
RECORD = NEIGHBOURS + ("c_meta", "c_sel", "sop", "fend", "c_edge")


async def run_frame(bench, inputs, n_steps: int, gap: float, stall: float, tail: int = 30) -> list[dict]:
    """Offer ``inputs`` with random gaps and random credit; record every step's interface
    until ``n_steps`` steps happened and every input was taken, then ``tail`` cycles with
    the credit high and no input (a step there is an extra one)."""
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


def check_steps(got, want, sched, hdr_w: int, log) -> None:
    """Every defined field of every step as expected (None: a stale word, not checked)."""
    bad = 0

    def error(n, w, msg, *args):
        nonlocal bad
        bad += 1
        if bad <= 8:
            where = f"step {n} (centre {sched.describe(w['centre']) if w['centre'] >= 0 else 'none'})"
            log.error("%s: " + msg, where, *args)

    for n, (g, w) in enumerate(zip(got, want)):
        for name in NEIGHBOURS + ("c_meta", "c_sel", "sop"):
            if w[name] is not None and g[name] != w[name]:
                error(n, w, "%s RTL %#x, expected %#x", name, g[name], w[name])
        if w["c_real"] is not None and (g["c_meta"] >> hdr_w) != w["c_real"]:
            error(n, w, "C's real bit RTL %d, expected %d", g["c_meta"] >> hdr_w, w["c_real"])
        if g["fend"] or g["c_edge"]:
            error(n, w, "fend %d, c_edge %d (the lines have neither)", g["fend"], g["c_edge"])
    assert bad == 0, f"{bad} interface fields differ from the expected steps"


@cocotb.test()
async def test_lines_steps(dut):
    """Golden sample beats in, the expected neighbourhood at every step, with stalls."""
    p, vw, w = int(dut.P.value), int(dut.VOXEL_W.value), int(dut.WEIGHT_W.value)
    geo = Geometry(p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
    bench = UnitBench(dut)
    await bench.reset({"in_valid": 0, "credit": 0})
    dims = (max(7, 2 * p + 1), 6, 5)
    vol = bench.rng.integers(0, 1 << vw, size=dims[::-1], dtype=np.int64)
    for direction, gap, stall in VIEWS:
        trav = make_traversal(dims, direction, w, 1 << geo.max_ss_log2)
        samples, inside = sample_stream(vol, trav)
        sched = BeatSchedule(trav, p, inside)
        hdrs = sched.headers(geo)
        smp = sched.lanes(samples)
        inputs = [{"in_hdr": hdrs[n], "in_sample": pack_lanes(smp[n], vw)} for n in range(len(sched))]
        want = lines_steps(sched, samples, geo, vw)
        bench.set_view(trav, p)
        await bench.cycles(2)
        got = await run_frame(bench, inputs, len(want), gap, stall)
        check_steps(got, want, sched, geo.hdr_w, bench.log)
        bench.log.info("view %s S=%d: %d beats, %d steps as expected", direction, trav.supersample, len(sched),
                       len(got))


BUILDS = [(1, 8, 0), (5, 8, 1)]   # (P, VOXEL_W, MAX_SS_LOG2)


@pytest.mark.parametrize("build", BUILDS, ids=[f"p{b[0]}_v{b[1]}_ss{b[2]}" for b in BUILDS])
def test_cube4_gra_lines(build):
    p, vw, ss = build
    run_test(top="cube4_gra_lines_harness", sources=SOURCES,
             params={"P": p, "VOXEL_W": vw, "MAX_DIM": 16, "MAX_SS_LOG2": ss},
             test_module=__file__, testcase="test_lines_steps", timing=True)

"""Unit testbench of rtl/cube4_gra_lines.v: GRA's delay lines, step by step.

The DUT is ``sim/hdl/cube4_gra_source_harness.v`` with WALK = 0: cube4_gra_lines with its
view registers as ports, a Verilog clock, the output FIFO's credit as one port and a
cube4_stream_check on the input. The input is the golden sample stream (``cube4.model.sample_stream``) in the
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

import cocotb
import pytest

from cube4.model import sample_stream
from cube4.view import make_traversal
from cube4_sim.beats import BeatSchedule, pack_lanes
from cube4_sim.gra_beats import NEIGHBOURS, lines_steps
from cube4_sim.unit_bench import SourceBench, param_id, run_unit
from cube4_sim.sweeps import sweep

# (direction, input gap probability, credit stall probability)
VIEWS = [((0.3, -0.45, 1.0), 0.0, 0.0), ((-0.6, 0.25, -1.0), 0.3, 0.4), ((1.0, 0.4, -0.7), 0.5, 0.2)]
RECORD = NEIGHBOURS + ("c_meta", "c_sel", "sop", "fend", "c_edge")


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
    bench = SourceBench(dut)
    p, vw, w, geo, dims, vol = bench.p, bench.vw, bench.w, bench.geo, bench.dims, bench.vol
    await bench.reset({"in_valid": 0, "credit": 0})
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
        got = await bench.run_steps(inputs, len(want), RECORD, gap, stall)
        check_steps(got, want, sched, geo.hdr_w, bench.log)
        bench.log.info("view %s S=%d: %d beats, %d steps as expected", direction, trav.supersample, len(sched),
                       len(got))


BUILDS = [{"P": 1, "VOXEL_W": 8, "MAX_SS_LOG2": 0}, {"P": 5, "VOXEL_W": 8, "MAX_SS_LOG2": 1}]


@pytest.mark.parametrize("build", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_gra_lines(build):
    run_unit(__file__, {**build, "MAX_DIM": 16, "WALK": 0}, "test_lines_steps", harness="cube4_gra_source_harness")

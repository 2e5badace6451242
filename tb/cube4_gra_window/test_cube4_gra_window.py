"""Unit testbench of rtl/cube4_gra_window.v: GRA's window, operand by operand.

The DUT is ``cube4_gra_window_harness.v``: cube4_gra_window (RECTS = 0) with its view
registers as ports and a Verilog clock. Its source side is driven with the steps of the
fixed schedule (``cube4_sim.gra_beats.lines_steps``: X and its six neighbour beats from
the golden sample stream, C's header and select flags; random words where the lines
hold stale ones, and a flush or stale centre's header without its real bit), one step
per cycle with random stalls (step = 0, random data in between;
seeded from COCOTB_RANDOM_SEED). In every cycle with take = 1 the bench records the
operands and checks them, in order, against the golden ``cube4.model.
gradient_operand_stream`` in the beats' lanes: the centre's header and sample, hi =
s[m, j, i+1], lo = s[m, j, i-1], gj = up - dn, fwd and back along the ray, in every lane
that holds a position; exactly one take per sample beat, and none in ten more steps of
zero beats after a frame (nothing extra).

Views: three directions (flipped axes among them), back to back in one simulation, at
P = 1 and P = 5; the P = 5 build runs them supersampled (S = 2). The walk's edge beams
(RECTS = 1) are checked with cube4_gra_walk in tb/cube4_gra.
"""

from __future__ import annotations


import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

from cube4.model import gradient_operand_stream, sample_stream
from cube4.view import make_traversal
from cube4_sim.beats import BeatSchedule, Geometry, unpack_lanes
from cube4_sim.gra_beats import NEIGHBOURS, lines_steps
from cube4_sim.unit_bench import UnitBench, check_lanes, param_id, run_unit
from cube4_sim.sweeps import sweep


VIEWS = [((0.3, -0.45, 1.0), 0.0), ((-0.6, 0.25, -1.0), 0.4), ((1.0, 0.4, -0.7), 0.6)]   # (direction, stall)
INPUTS = NEIGHBOURS + ("c_meta", "c_sel", "sop")
OUTPUTS = ("c_hdr", "s", "hi", "lo", "fwd", "back", "gj")


async def run_steps(bench, steps, hdr_w: int, stall: float, tail: int = 10) -> list[dict]:
    """Give every step (random stalls, random data while stalled), then ``tail`` steps of
    zero beats; return the operands of every cycle with take = 1."""
    d = bench.dut
    got, k, extra = [], 0, 0
    while extra < tail:
        await FallingEdge(d.clk)
        go = k >= len(steps) or bench.rng.random() >= stall
        for name in INPUTS:
            junk = int(bench.rng.integers(0, 1 << min(len(bench.sig(name)), 62)))
            if k >= len(steps):
                val = 0
            elif not go or steps[k][name] is None:   # between steps, or a stale word
                val = junk
            else:
                val = steps[k][name]
            if name == "c_meta" and go and k < len(steps) and steps[k]["c_real"] != 1:
                val &= (1 << hdr_w) - 1                # a flush or stale centre is not real
            bench.sig(name).value = val
        d.step.value = int(go)
        await ReadOnly()
        if int(d.take.value):
            got.append({n: int(bench.sig(n).value) for n in OUTPUTS})
        if go:
            if k < len(steps):
                k += 1
            else:
                extra += 1
    await FallingEdge(d.clk)
    d.step.value = 0
    return got


@cocotb.test()
async def test_window_operands(dut):
    """The fixed schedule's neighbourhoods in, the golden operands out, with stalls."""
    p, vw, w = int(dut.P.value), int(dut.VOXEL_W.value), int(dut.WEIGHT_W.value)
    geo = Geometry(p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
    bench = UnitBench(dut)
    await bench.reset({"step": 0})
    dims = (max(7, 2 * p + 1), 6, 5)
    vol = bench.rng.integers(0, 1 << vw, size=dims[::-1], dtype=np.int64)
    for direction, stall in VIEWS:
        trav = make_traversal(dims, direction, w, 1 << geo.max_ss_log2)
        samples, inside = sample_stream(vol, trav)
        sched = BeatSchedule(trav, p, inside)
        hdrs = sched.headers(geo)
        ops = sched.lanes(gradient_operand_stream(samples, trav))   # (beats, 6, P)
        want = {"s": sched.lanes(samples), "hi": ops[:, 0], "lo": ops[:, 1], "gj": ops[:, 2] - ops[:, 3],
                "fwd": ops[:, 4], "back": ops[:, 5]}
        bench.set_view(trav, p)
        await bench.cycles(2)
        got = await run_steps(bench, lines_steps(sched, samples, geo, vw), geo.hdr_w, stall)
        assert len(got) == len(sched), f"{len(got)} takes, expected {len(sched)} (one per sample beat)"
        bad = [n for n, g in enumerate(got) if g["c_hdr"] != hdrs[n]]
        assert not bad, f"{len(bad)} centre headers differ, first at {sched.describe(bad[0])}"
        for name, ref in want.items():
            width, signed = (vw + 1, True) if name == "gj" else (vw, False)
            rtl = np.stack([unpack_lanes(g[name], p, width, signed=signed) for g in got])
            check_lanes(rtl, ref, sched.lval, sched, bench.log, name)
        bench.log.info("view %s S=%d stall %.1f: %d centres, operands bit-exact", direction, trav.supersample,
                       stall, len(got))


BUILDS = [{"P": 1, "VOXEL_W": 8, "MAX_SS_LOG2": 0}, {"P": 5, "VOXEL_W": 8, "MAX_SS_LOG2": 1}]


@pytest.mark.parametrize("build", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_gra_window(build):
    run_unit(__file__, {**build, "MAX_DIM": 16}, "test_window_operands")

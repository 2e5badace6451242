"""Unit testbench of rtl/cube4_gra.v: the gradient stream, bit for bit.

The DUT is ``cube4_gra_harness.v``: cube4_gra with its view registers as
ports, a Verilog clock and a cube4_stream_check on the input and the output
stream. The input is the golden sample stream (``cube4.model.sample_stream``)
turned into beats in the hardware's order (``cube4_sim.beats.BeatSchedule``: m,
j, pb; lane q holds i = pb * P + lane_pos(q, skew); header with m, j, pb, skew,
control bits, lane valid and lane inside), offered with random gaps in valid;
the output is taken with random ready (``cube4_sim.unit_bench``, seeded from
COCOTB_RANDOM_SEED). Checked per output beat, in order:

* the header equals the input beat's header (GRA passes it through), field by field;
* the sample and gi, gj, gk of every lane that holds a position equal the golden
  ``gradient_stream`` at (m, j, i);
* exactly M * NJ * NB beats come out: none missing, none extra in the 300
  cycles after the last one (GRA's flush steps must not emit).

Views: z-major with j flipped, z-major with i and k flipped, x-major with k
flipped (at least two with a flipped axis), each with other stalls, in one
simulation per build (views follow each other without a reset), at P = 1, P = 5
and P = 8; the P = 8 build (MAX_SS_LOG2 = 1) runs the views supersampled (S = 2).

The test can fail (tried with deliberately corrupted expectations, not kept):
with the golden gk of lane 0 of beat 40 raised by one, P = 1 fails with
"gk beat 40 (m=0, j=3, pb=7, lane 0: i=7): RTL 89, golden 90" and "1 gk lanes
differ from the golden model"; expecting one beat fewer fails with "N output
beats, expected N-1: 1 extra beat(s) within 300 cycles of the last one".
"""

from __future__ import annotations

from pathlib import Path

import cocotb
import numpy as np
import pytest

from cube4.model import gradient_stream, sample_stream
from cube4.view import make_traversal
from cube4_sim import run_test
from cube4_sim.beats import BeatSchedule, Geometry, pack_lanes, unpack_lanes
from cube4_sim.unit_bench import UnitBench, check_headers, check_lanes, harness_sources

HERE = Path(__file__).resolve().parent   # the harness sits beside this file

SOURCES = harness_sources(HERE / "cube4_gra_harness.v")

# (direction, input gap probability, output stall probability)
VIEWS = [((0.3, -0.45, 1.0), 0.0, 0.0), ((-0.6, 0.25, -1.0), 0.3, 0.4), ((1.0, 0.4, -0.7), 0.6, 0.2)]
OUTPUTS = ["out_hdr", "out_sample", "out_gi", "out_gj", "out_gk"]


def volume_dims(p: int) -> tuple[int, int, int]:
    """Small and non-cubic, with several partial beams along every axis."""
    return (max(11, 2 * p + 3), max(9, p + 4), max(8, p + 2))


@cocotb.test()
async def test_gradient_stream(dut):
    """Golden sample beats in, gradient beats out, bit for bit, with stalls."""
    p, vw, w = int(dut.P.value), int(dut.VOXEL_W.value), int(dut.WEIGHT_W.value)
    geo = Geometry(p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
    gw = vw + 5
    bench = UnitBench(dut)
    await bench.reset({"in_valid": 0, "out_ready": 0})
    dims = volume_dims(p)
    vol = bench.rng.integers(0, 1 << vw, size=dims[::-1], dtype=np.int64)
    ss = 1 << geo.max_ss_log2
    for direction, gap, stall in VIEWS:
        trav = make_traversal(dims, direction, w, ss)
        samples, inside = sample_stream(vol, trav)
        sched = BeatSchedule(trav, p, inside)
        hdrs = sched.headers(geo)
        smp = sched.lanes(samples)
        grads = sched.lanes(gradient_stream(samples, trav))  # (beats, 3, P)
        inputs = [{"in_hdr": hdrs[n], "in_sample": pack_lanes(smp[n], vw)} for n in range(len(sched))]
        bench.set_view(trav, p)
        await bench.cycles(2)
        got = await bench.run_stream(inputs, len(sched), OUTPUTS, gap, stall)
        check_headers([b["out_hdr"] for b in got], hdrs, geo, sched, bench.log, "gradient stream")
        check_lanes(np.stack([unpack_lanes(b["out_sample"], p, vw) for b in got]), smp, sched.lval, sched,
                    bench.log, "sample")
        for c, name in enumerate(("gi", "gj", "gk")):
            rtl = np.stack([unpack_lanes(b["out_" + name], p, gw, signed=True) for b in got])
            check_lanes(rtl, grads[:, c, :], sched.lval, sched, bench.log, name)
        bench.log.info("dims %s view %s S=%d gap %.1f stall %.1f: %d gradient beats bit-exact",
                       dims, direction, ss, gap, stall, len(got))


BUILDS = [(1, 8, 0), (5, 8, 0), (8, 12, 1)]   # (P, VOXEL_W, MAX_SS_LOG2)


@pytest.mark.parametrize("build", BUILDS, ids=[f"p{b[0]}_v{b[1]}_ss{b[2]}" for b in BUILDS])
def test_cube4_gra(build):
    p, vw, ss = build
    run_test(top="cube4_gra_harness", sources=SOURCES,
             params={"P": p, "VOXEL_W": vw, "MAX_DIM": 32, "MAX_SS_LOG2": ss},
             test_module=__file__, testcase="test_gradient_stream", timing=True)

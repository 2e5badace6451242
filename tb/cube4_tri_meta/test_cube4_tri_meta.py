"""Unit testbench of rtl/cube4_tri_meta.v: what travels beside TRI's lerps, bit for bit.

The beats are a golden sample stream's (``cube4_sim.beats.BeatSchedule`` of a random
volume's ``cube4.model.sample_stream``, with a ``random_clip`` window and cut plane):
each enters at s4 (s4_v, with seeded random gaps; random header and weights in the gaps)
with the header's KEEP = LVALID, as cube4_tri_beam gives it, and the beat's wy, wz
(``Traversal.weights``). TRI_CLIP_LAT cycles later the keep input is the golden KEEP of
the beat's lanes, with random bits in the lanes that hold no position (the unit must AND
them with LVALID). Checked:

* every header announced by push_d, read one cycle later, equals the golden one
  (``BeatSchedule.headers``: KEEP = LVALID and kept), in order;
* wy and wz leave TRI_LERP_LAT - 1 and 2 * TRI_LERP_LAT - 1 cycles after s4, every cycle;
* exactly as many beats come out as went in, none in the 30 cycles after the last.

Views: two directions (one with a window and a cut plane, one without clipping, S = 2 when
the build has MAX_SS_LOG2 > 0), in one simulation per build.

The test can fail (tried with a deliberately corrupted expectation, not kept): with lane
0's golden KEEP of beat 7 flipped, P = 5 fails with "meta beat 7 (m=0, j=2, pb=1): header
fields (RTL, golden) {'keep': (0, 1)}".
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

from cube4.model import sample_stream
from cube4.view import make_traversal
from cube4_sim.beats import BeatSchedule, Geometry
from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import check_headers, param_id, random_clip, run_rtl, start_clock

LAT, CLIP_LAT = 4, 5       # TRI_LERP_LAT, TRI_CLIP_LAT (rtl/cube4_defs.vh)
NL = 3 * LAT
TAIL = 30
# (direction, window / cut plane, gap probability)
VIEWS = [((-0.6, 0.25, -1.0), "window+cut", 0.4), ((1.0, 0.4, -0.7), None, 0.0)]


def view_beats(rng, p: int, w: int, ss: int, direction, clip_kind):
    """The golden beats of one view of a random volume: schedule, headers, weights (beats, 2)."""
    dims = (max(9, 2 * p + 3), 7, 6)
    vol = rng.integers(0, 256, size=dims[::-1], dtype=np.int64)
    trav = make_traversal(dims, direction, w, ss)
    _, inside = sample_stream(vol, trav)
    clip = random_clip(trav, clip_kind, rng)
    keep = None if clip is None else np.stack([clip.keep(trav, m) for m in range(trav.num_sample_slices)])
    sched = BeatSchedule(trav, p, inside, keep)
    wx, wy, wz = trav.weights(sched.m)
    return sched, np.stack([wy, wz], axis=1)


def rand_bits(rng, n: int) -> int:
    """A random n-bit integer."""
    return int.from_bytes(rng.bytes((n + 7) // 8), "little") & ((1 << n) - 1)


@cocotb.test()
async def test_meta(dut):
    p, w = int(dut.P.value), int(dut.WEIGHT_W.value)
    geo = Geometry(p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    start_clock(dut)
    dut.rst.value, dut.s4_v.value = 1, 0
    for _ in range(3):
        await FallingEdge(dut.clk)
    dut.rst.value = 0
    for direction, clip_kind, gap in VIEWS:
        sched, wts = view_beats(rng, p, w, 2 if geo.max_ss_log2 else 1, direction, clip_kind)
        want = sched.headers(geo)
        n = len(want)
        # the cycle of each beat at s4: gaps with probability ``gap``
        at = np.cumsum(rng.geometric(1.0 - gap, size=n)) - 1
        cycles = int(at[-1]) + NL + TAIL
        slot = np.full(cycles, -1)
        slot[at] = np.arange(n)
        hdr_in = [0] * cycles
        w_in = rng.integers(0, 1 << w, size=(cycles, 2))
        for t in range(cycles):
            b = slot[t]
            if b >= 0:
                f = geo.unpack_header(want[b])
                hdr_in[t] = geo.pack_header({**f, "keep": f["lval"]})
                w_in[t] = wts[b]
            else:
                hdr_in[t] = rand_bits(rng, geo.hdr_w)
        got, push = [], 0
        for t in range(cycles):
            await FallingEdge(dut.clk)
            b = slot[t]
            dut.s4_v.value = int(b >= 0)
            dut.s4_meta.value = hdr_in[t]
            dut.s4_wy.value, dut.s4_wz.value = int(w_in[t, 0]), int(w_in[t, 1])
            kb = slot[t - CLIP_LAT] if t >= CLIP_LAT else -1
            noise = rand_bits(rng, p)
            if kb >= 0:
                f = geo.unpack_header(want[kb])
                dut.keep.value = f["keep"] | (noise & ~f["lval"] & ((1 << p) - 1))
            else:
                dut.keep.value = noise
            await ReadOnly()
            if push:
                got.append(int(dut.hdr.value))
            push = int(dut.push_d.value)
            if t >= 2 * LAT - 1:
                assert int(dut.wy.value) == w_in[t - (LAT - 1), 0], f"cycle {t}: wy"
                assert int(dut.wz.value) == w_in[t - (2 * LAT - 1), 1], f"cycle {t}: wz"
        assert len(got) == n, f"{len(got)} headers out, expected {n}: {len(got) - n} extra within {TAIL} cycles"
        check_headers(got, want, geo, sched, dut._log, "meta")
        dut._log.info("view %s clip %s gaps %.1f: %d headers bit-exact", direction, clip_kind, gap, n)


BUILDS = [dict(P=1, MAX_DIM=32, MAX_SS_LOG2=0, WEIGHT_W=8), dict(P=5, MAX_DIM=32, MAX_SS_LOG2=1, WEIGHT_W=8),
          dict(P=16, MAX_DIM=64, MAX_SS_LOG2=2, WEIGHT_W=12)]


@pytest.mark.parametrize("build", sweep(BUILDS, quick=(0, 1), ids=param_id))
def test_cube4_tri_meta(build):
    run_rtl(__file__, build)

"""Testbench for rtl/cube4_cfb_skip.v: the beat schedule's front end without its reads.

cube4_cfb_decide, cube4_ram_fifo and cube4_cfb_beats together, on the golden frames of
``cube4_sim.beat_frames`` (two nearly opaque slabs, sparse volumes in every mode at S = 1,
and in a build with MAX_SS_LOG2 = 2 three more at S = 2 and 4):
the bench plays the host (block table, ray table, the frame's axes, each slice's steps)
and COM (the reports of slice d once the walk has given slice d's last beat, EOS, a
random delay later, ``com_m`` counting them), and takes the walk with random ready. Expected, beat for
beat: the walk of ``beats.walk_rows`` (slice, row, partial beam, read, leave, token, EOR, EOS, LAST) and,
on every beat whose leaving sample beat holds a running ray, that beat's position bits
{soon, last, fresh, run} as the golden schedule has them (soon up to the ray's done slice),
zero on the others; nothing after LAST. The units' own testbenches cover each alone; here
the decisions run ahead of the walk through the bitmaps' four slots and the bits' queue,
and no frame may stall for good. Seeded from COCOTB_RANDOM_SEED; P = 8 deciding two beats a
cycle (RATE = 2, MAX_SS_LOG2 = 2) in make test; P = 1, 4, 8 at RATE 1 and P = 1, 5 (MAX_DIM
64) at RATE 2 in make regress.
"""

from __future__ import annotations

import json
import os

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge

from cube4_sim.beat_frames import HostCom, expected_front, slab_frame, sparse_frame, view_frame
from cube4_sim.beats import Geometry
from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import param_id, run_rtl, start_clock, top_params

from cube4.beats import LAG  # noqa: E402  (the DUT's default, CUBE4_BEAT_LAG)
TAIL = 40
SLAB_VIEWS = [(0.2, -0.1, 1.0), (1.0, 1.0, 1.0)]


class TB:
    def __init__(self, dut) -> None:
        self.dut = dut
        self.log = dut._log
        self.p, self.max_dim, self.ss = top_params(dut, "P", "MAX_DIM", "MAX_SS_LOG2")
        self.geo = Geometry(self.p, self.max_dim, self.ss)
        self.rng = np.random.default_rng(cocotb.RANDOM_SEED)
        start_clock(dut)

    async def reset(self) -> None:
        d = self.dut
        for name in ("start", "ss_log2", "st_valid", "blk_we", "tab_we", "rep_valid", "rep_en", "com_m",
                     "out_ready", "out_ready_q"):
            getattr(d, name).value = 0
        d.rst.value = 1
        for _ in range(3):
            await RisingEdge(d.clk)
        await FallingEdge(d.clk)
        d.rst.value = 0

    async def frame(self, bf, stall: float, delay: int) -> tuple[list[tuple], int]:
        """Run one frame: its beats, and the cycles from start to the LAST beat's transfer."""
        d = self.dut
        host = HostCom(d, bf, self.p, self.max_dim, self.geo.m_w, LAG, self.rng, delay)
        await host.load()
        d.ss_log2.value = bf.trav.supersample.bit_length() - 1
        d.start.value = 1
        await FallingEdge(d.clk)
        d.start.value = 0
        got, walked, cycle, after, last_cycle = [], 0, 0, None, 0
        while after is None or after < TAIL:
            host.drive(cycle, walked)           # the steps; COM's reports behind the walk's slice ends
            ready = after is not None or self.rng.random() >= stall
            d.out_ready.value = int(ready)
            d.out_ready_q.value = int(ready)    # (a register copy of out_ready in cube4_cfb)
            await ReadOnly()
            host.taken()
            if ready and int(d.out_valid.value):
                beat = (int(d.out_m.value), int(d.out_j.value), int(d.out_pb.value), int(d.out_read.value),
                        int(d.out_leave.value), int(d.out_tok.value), int(d.out_eor.value), int(d.out_eos.value),
                        int(d.out_last.value), int(d.out_bits.value))
                got.append(beat)
                if beat[7]:
                    walked = beat[0] + 1        # slices the walk has finished
                if beat[8]:
                    after = 0
                    last_cycle = cycle + 1
            await RisingEdge(d.clk)
            await FallingEdge(d.clk)
            cycle += 1
            if after is not None:
                after += 1
            assert cycle < 300000, f"the frame stalled ({len(got)} beats out)"
        assert not int(d.busy.value), "busy after the frame's last beat"
        return got, last_cycle


def compare(got: list, want: list) -> None:
    for n, (g, w) in enumerate(zip(got, want)):
        assert g[:9] == w[:9], f"beat {n}: RTL (m, j, pb, read, leave, tok, eor, eos, last) = {g[:9]}, golden {w[:9]}"
        assert g[9] & w[10] == w[9] & w[10], f"beat {n} {w[:3]}: RTL bits {g[9]:#x}, golden {w[9]:#x} (mask {w[10]:#x})"
    assert len(got) == len(want), f"{len(got)} beats out, golden {len(want)}"


@cocotb.test()
async def test_front_end(dut):
    tb = TB(dut)
    await tb.reset()
    seeds = [s for s in range(200) if s % 3 == 0][:6]
    cases = [("slab", v, 1) for v in SLAB_VIEWS] + [("sparse", s, 1) for s in seeds]
    if tb.ss >= 2:
        cases += [("sparse", s, ss) for s, ss in ((1, 2), (4, 4), (13, 4))]
    nbmax = -(-tb.max_dim // tb.p)
    for n, (kind, arg, ss) in enumerate(cases):
        bf = (slab_frame(tb.p, arg) if kind == "slab"
              else sparse_frame(arg, tb.p, opaque=n % 2 == 0, terminate=n % 3 != 2, supersample=ss))
        s = bf.sched
        if s.NJ > tb.max_dim or s.NB > nbmax:
            continue
        stall, slices = ((0.0, 0.0), (0.1, 1.0), (0.4, 0.3), (0.2, 0.05))[n % 4]
        got, _ = await tb.frame(bf, stall, int(slices * s.NJ * s.NB))
        compare(got, expected_front(bf, tb.p, LAG))
        tb.log.info("%s %s S=%d: %d slices of %dx%d beats, %d rays reported done, stall %.1f: %d walk beats "
                    "bit-exact", kind, arg, ss, s.M, s.NJ, s.NB, int((s.done < s.M).sum()), stall, len(got))


MEASURE = os.environ.get("CUBE4_SKIP_MEASURE")


@cocotb.test(skip=MEASURE is None)
async def test_measure(dut):
    """make skipping's measurement (CUBE4_SKIP_MEASURE: JSON {volume, scene, out}): a
    built-in scene's own view through the front end's units, without stalls, COM's
    reports right after each slice's EOS; beat for beat against the golden schedule, and
    its cycles from start to LAST written to ``out``."""
    spec = json.loads(MEASURE)
    tb = TB(dut)
    await tb.reset()
    bf = view_frame(spec["volume"], spec["scene"], tb.p)
    got, cycles = await tb.frame(bf, 0.0, 0)
    compare(got, expected_front(bf, tb.p, LAG))
    with open(spec["out"], "w") as f:
        json.dump({"cycles": cycles, "walk_beats": sum(1 for b in got if not b[5])}, f)   # no tokens


BUILDS = [dict(P=4, MAX_DIM=32, RATE=1), dict(P=8, MAX_DIM=32, RATE=2, MAX_SS_LOG2=2), dict(P=1, MAX_DIM=32, RATE=1),
          dict(P=5, MAX_DIM=64, RATE=2), dict(P=1, MAX_DIM=32, RATE=2), dict(P=8, MAX_DIM=32, RATE=1)]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1,), ids=param_id))
def test_cube4_cfb_skip(params):
    run_rtl(__file__, params)

"""Testbench for rtl/cube4_cfb_decide.v: the beat schedule's decisions, position for position.

Each frame is a golden one (``cube4_sim.beat_frames``): two of a nearly opaque slab in
front of a dense block (rays end in the slab) and sparse volumes at S = 1 in every mode,
opaque in every other frame, termination off in every third; in a build with MAX_SS_LOG2
= 2 three more at S = 2 and 4 (a sample slice's blocks are those of voxel slice
floor(m / S): with m's own, tried, P = 4 fails with "ln beat 2 (m=10, j=0, pb=2): RTL run
0xc, golden 0x3" in the first frame at S = 2). The bench plays the host and
COM around the unit:

* the host writes the block table for the view (the volume's block bits with the frame's
  k, j, i axes as word, row and bit: ``blk_*``), the ray table with every ray's stop
  (``cube4.memory.stop_table`` layout, ``tab_*``) and the frame's axes, SX, SY;
* each slice's steps go in through ``st_*``;
* COM: the rays the golden frame reported done after slice d whose stop lies beyond
  d + LAG + 1 (not "soon") get end = d + LAG + 1 through ``rep_*``, one write per beat of
  slice d holding such rays, at a random time after the unit has decided slice d, and
  ``com_m`` counts the slices whose reports are written (delays up to five slices); the
  unit must wait for them, and decides the same whenever they arrive within that bound.

Expected, for every beat in order that holds a running ray: the bits per position of
``run`` (the golden ``BeatSchedule.running``), ``fresh`` (run and the ray's first slice
that may count is this one), ``last`` (run and m + 1 reaches the ray's stop) and ``soon``
(run and m + LAG + 1 reaches it: checked up to the ray's done slice, after which COM does
not read it and it depends on when the report came); and for every row its words of A
(``active_beats``) and OCC (the beats that may count). Both streams are taken with
random ready, and nothing more comes out (40 cycles after the last).

Without the started bits (tried, not kept: run = occ and m < end), P = 4 fails with "ln
beat 872 (m=15, j=14, pb=0): RTL run 0x3, golden 0x1"; without the wait for COM's reports
(com_m), with "ln beat 746 (m=8, j=5, pb=1): RTL run 0xf, golden 0x1" in the second slab
frame, whose reports come up to five slices late (both at RATE = 2; "ln beat" counts the
beats that hold a running ray). Seeded from COCOTB_RANDOM_SEED;
P = 4 deciding two beats a cycle (RATE = 2, MAX_SS_LOG2 = 2) in make test; P = 1, 4, 8 at
RATE 1 and P = 1, 5 (MAX_DIM 64) at RATE 2 in make regress.
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge

from cube4_sim.beat_frames import HostCom, expected_decisions, slab_frame, sparse_frame
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
        self.p, self.max_dim, self.ss, self.rate = top_params(dut, "P", "MAX_DIM", "MAX_SS_LOG2", "RATE")
        self.geo = Geometry(self.p, self.max_dim, self.ss)
        self.rng = np.random.default_rng(cocotb.RANDOM_SEED)
        start_clock(dut)

    def idle(self) -> None:
        for name in ("start", "ss_log2", "st_valid", "blk_we", "tab_we", "rep_valid", "rep_en", "com_m",
                     "bm_ready", "ln_ready"):
            getattr(self.dut, name).value = 0

    async def reset(self) -> None:
        self.idle()
        self.dut.rst.value = 1
        for _ in range(3):
            await RisingEdge(self.dut.clk)
        await FallingEdge(self.dut.clk)
        self.dut.rst.value = 0

    async def frame(self, bf, stall: float, delay: int) -> tuple[list, list]:
        d, s = self.dut, bf.sched
        host = HostCom(d, bf, self.p, self.max_dim, self.geo.m_w, LAG, self.rng, delay)
        await host.load()
        d.ss_log2.value = bf.trav.supersample.bit_length() - 1
        d.start.value = 1
        await FallingEdge(d.clk)
        d.start.value = 0
        lane, rows = [], []
        decided = 0                             # slices decided whole (their rows out)
        cycle, idle_after = 0, 0
        while idle_after < TAIL:
            host.drive(cycle, decided)          # the steps; COM's reports once a slice is decided
            ln_ready = self.rng.random() >= stall
            bm_ready = self.rng.random() >= stall
            d.ln_ready.value, d.bm_ready.value = int(ln_ready), int(bm_ready)
            await ReadOnly()
            host.taken()
            out = False
            if ln_ready and int(d.ln_valid.value):
                v = int(d.ln_bits.value)
                mask, ln = (1 << self.p) - 1, 4 * self.p + 1
                for r in range(self.rate):          # a group of RATE beats; those with a = 1
                    w = v >> (r * ln)
                    if (w >> (4 * self.p)) & 1:
                        lane.append(tuple((w >> (c * self.p)) & mask for c in range(4)))
                out = True
            if bm_ready and int(d.bm_valid.value):
                v = int(d.bm_a.value), int(d.bm_occ.value)
                rows.append(v)
                out = True
            decided = len(rows) // s.NJ             # slices decided whole
            await RisingEdge(d.clk)
            await FallingEdge(d.clk)
            cycle += 1
            done = len(rows) >= s.M * s.NJ and not int(d.busy.value)
            idle_after = idle_after + 1 if (done and not out) else 0
            assert cycle < 200000, "the frame did not end"
        return lane, rows


def compare(lane, rows, bf, p) -> None:
    want_lane, want_rows = expected_decisions(bf, p, LAG)
    for n, (g, w) in enumerate(zip(lane, want_lane)):
        m, j, pb = w[:3]
        care = (-1, -1, -1, w[7])
        for name, gv, wv, c in zip(("run", "fresh", "last", "soon"), g, w[3:7], care):
            assert gv & c == wv & c, f"ln beat {n} (m={m}, j={j}, pb={pb}): RTL {name} {gv:#x}, golden {wv:#x}"
    assert len(lane) == len(want_lane), f"{len(lane)} beats out, golden {len(want_lane)}"
    for n, (g, w) in enumerate(zip(rows, want_rows)):
        assert g == w, f"row {n} (m={n // bf.sched.NJ}, j={n % bf.sched.NJ}): RTL (A, OCC) {g}, golden {w}"
    assert len(rows) == len(want_rows), f"{len(rows)} rows out, golden {len(want_rows)}"


@cocotb.test()
async def test_decisions(dut):
    """Golden frames' tables in, COM's reports at random times, every decision checked."""
    tb = TB(dut)
    await tb.reset()
    seeds = [s for s in range(200) if s % 3 == 0][:7]
    cases = [("slab", v, 1) for v in SLAB_VIEWS] + [("sparse", s, 1) for s in seeds]
    if tb.ss >= 2:      # S = 2 and 4: a sample slice's blocks are its voxel slice's
        cases += [("sparse", s, ss) for s, ss in ((1, 2), (4, 4), (13, 4))]
    nbmax = -(-tb.max_dim // tb.p)
    for n, (kind, arg, ss) in enumerate(cases):
        bf = (slab_frame(tb.p, arg) if kind == "slab"
              else sparse_frame(arg, tb.p, opaque=n % 2 == 0, terminate=n % 3 != 2, supersample=ss))
        s = bf.sched
        if s.NJ > tb.max_dim or s.NB > nbmax:
            continue
        # report delays in slices of beats: up to five slices makes the unit wait for them
        stall, slices = ((0.0, 0.0), (0.1, 5.0), (0.3, 0.5), (0.5, 0.05))[n % 4]
        delay = int(slices * s.NJ * s.NB)
        lane, rows = await tb.frame(bf, stall, delay)
        compare(lane, rows, bf, tb.p)
        ended = int((s.done < s.M).sum())
        tb.log.info("%s %s S=%d: %d slices of %dx%d beats, %d rays reported done, stall %.1f, report delay <= %d: "
                    "%d beats and %d rows bit-exact", kind, arg, ss, s.M, s.NJ, s.NB, ended, stall, delay, len(lane),
                    len(rows))


BUILDS = [dict(P=4, MAX_DIM=32, RATE=2, MAX_SS_LOG2=2), dict(P=1, MAX_DIM=32, RATE=1), dict(P=8, MAX_DIM=32, RATE=1),
          dict(P=5, MAX_DIM=64, RATE=2), dict(P=4, MAX_DIM=32, RATE=1), dict(P=1, MAX_DIM=32, RATE=2)]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(0,), ids=param_id))
def test_cube4_cfb_decide(params):
    run_rtl(__file__, params)

"""Testbench for rtl/cube4_cfb_beats.v: the walk of the beat schedule, beat for beat.

Each frame is a golden one: ``render_frame(..., beats=..., done=...)``, first two of a
nearly opaque slab in front of a dense block (tests/test_beats.py ``opaque_slab``: shaded,
rays end in the slab, and hundreds of beats run only as GRA's neighbours of running ones),
then sparse volumes (``cube4_testutil.sparse_case``: a faint background, one dense blob,
every mode, S = 1, seven views, cut planes), with the LUT made nearly opaque in every
other frame so that COM's reports end rays, and with termination off in every third; in a
build with MAX_SS_LOG2 = 2, four more at S = 2 and 4, whose passes 0 and k0·S + 1 read all
their rows (``BeatSchedule.reads_slice``; without that rule, tried, P = 1 fails with
"beat 0: RTL (m, j, pb, read, leave, in_a, tok, eor, eos, last) = (0, 0, 0, 0, 0, 0, 1, 1,
0, 0), golden (0, 0, 0, 1, 0, 0, 0, 0, 0, 0)" in the first frame at S = 2). The
bench writes each slice's bitmaps (``BeatSchedule.active_beats``: A; the beats that may
count: OCC) through bm_*, rows in order with random gaps, and takes the walk with random
ready. Expected (``cube4_sim.beat_frames.expected_walk``): the golden front end's rows
(``beats.walk_rows``), each set bit of a row's reads and cover one beat in order of
partial beam, with its read bit and the bits of the running beats that leave with it (E,
and A: the beats with a running ray); a row that walks nothing, one beat that reads
nothing (on a slice's last row and the flush row a marker: every slice leaves a beat; on
the others a token for the address unit's row counter); EOR on each row's last beat, EOS
on each slice's, LAST on the frame's, and
nothing after it (the bench keeps ready high for 40 more cycles).

Cycles: every frame without gaps or stalls with NJ > 1 takes exactly NJ·min(2, M) + 7 +
walker_cycles edges from start to its last beat's transfer: the rows of two slices written
(an edge a row) before the first fetch, an edge to fetch, six to the emitter (two of them
the slots' read and output registers), then one cycle per beat and one per row that reads
nothing (``beats.walker_cycles``). (A row's bitmaps land in their slot an edge after the
take; with NJ = 1 the walk waits for a slice to land, not only to be taken, and the count
is not checked.)

The neighbour term matters: with it dropped from E (tried, not kept), P = 4 fails with
"beat 636: RTL (m, j, pb, read, leave, last) = (7, 1, 1, 1, 0, 0), golden (7, 1, 1, 1, 1,
0)" (before the A bit joined the beat) in the first slab frame (P = 1 at beat 2541 alike). Seeded from COCOTB_RANDOM_SEED;
P = 1 (MAX_SS_LOG2 = 2) in make test, 4 (MAX_SS_LOG2 = 2), 8 and 5 (MAX_DIM 64) in make regress.
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge

import cube4.beats as beats
from cube4_sim.beat_frames import bits_of, expected_walk, slab_frame, sparse_frame
from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import param_id, run_rtl, start_clock, top_params

FRAMES = 9
TAIL = 40
SLAB_VIEWS = [(0.2, -0.1, 1.0), (1.0, 1.0, 1.0)]


def thin_frame(p: int):
    """A shaded frame (the neighbour term: slice m + 1's bitmaps count in slice m's walk)
    of one row a slice (NJ = 1: a volume one voxel high seen along z), whose walk would
    read slice m + 1's only row in the edge its bitmaps land, were it not to wait."""
    from cube4.config import Cube4Config
    from cube4.view import make_traversal
    from cube4_sim.beat_frames import _run
    cfg = Cube4Config(pipelines=p)
    rng = np.random.default_rng(5)
    nx = 3 * p + 4
    vol = rng.integers(0, 40, size=(12, 1, nx))
    for k in range(12):                   # a band that shifts along x slice by slice
        vol[k, :, (k * p // 3) % nx: (k * p // 3) % nx + p] = 200
    lut = np.zeros((256, 4), dtype=np.int64)
    lut[100:, :3] = 255
    lut[100:, 3] = 600
    rmap = rng.integers(0, 1024, size=(cfg.rmap_entries, 2))
    trav = make_traversal((nx, 1, 12), (0.0, 0.0, 1.0), cfg.weight_bits, 1)
    return _run(vol, trav, cfg, lut, rmap, "composite", True, None, True)


class TB:
    def __init__(self, dut) -> None:
        self.dut = dut
        self.log = dut._log
        self.p, self.max_dim, self.ss = top_params(dut, "P", "MAX_DIM", "MAX_SS_LOG2")
        self.rng = np.random.default_rng(cocotb.RANDOM_SEED)
        start_clock(dut)

    async def reset(self) -> None:
        d = self.dut
        for name in ("start", "nj", "nb", "nm", "ss_log2", "nbr_en", "bm_valid", "bm_a", "bm_occ", "out_ready"):
            getattr(d, name).value = 0
        d.rst.value = 1
        for _ in range(3):
            await RisingEdge(d.clk)
        await FallingEdge(d.clk)
        d.rst.value = 0

    async def frame(self, sched, gap: float, stall: float) -> tuple[list, int]:
        """Run one frame: the beats out and the edges from start to the last beat."""
        d = self.dut
        rows = [(bits_of(a), bits_of(o)) for m in range(sched.M)
                for a, o in zip(sched.active_beats(m), sched._beats_of(sched.sample_occ(m)))]
        d.nj.value, d.nb.value, d.nm.value = sched.NJ, sched.NB, sched.M
        d.ss_log2.value = sched.trav.supersample.bit_length() - 1
        d.nbr_en.value = int(sched.neighbours)
        await FallingEdge(d.clk)
        d.start.value = 1
        await FallingEdge(d.clk)          # the start edge has passed
        d.start.value = 0
        got, n, edges, last_edge, after_last = [], 0, 0, None, 0
        while after_last < TAIL:
            offer = n < len(rows) and self.rng.random() >= gap
            d.bm_valid.value = int(offer)
            if offer:
                d.bm_a.value, d.bm_occ.value = rows[n]
            ready = last_edge is not None or self.rng.random() >= stall
            d.out_ready.value = int(ready)
            await ReadOnly()
            if offer and int(d.bm_ready.value):
                n += 1
            if ready and int(d.out_valid.value):
                got.append((int(d.out_m.value), int(d.out_j.value), int(d.out_pb.value), int(d.out_read.value),
                            int(d.out_leave.value), int(d.out_in_a.value), int(d.out_tok.value),
                            int(d.out_eor.value), int(d.out_eos.value), int(d.out_last.value)))
                if got[-1][9] and last_edge is None:
                    last_edge = edges + 1
            await RisingEdge(d.clk)
            edges += 1
            if last_edge is not None:
                after_last += 1
            await FallingEdge(d.clk)
        assert not int(d.busy.value), "busy after the frame's last beat"
        return got, (last_edge or 0)


def compare(got: list, want: list, log) -> None:
    for n, (g, w) in enumerate(zip(got, want)):
        assert g == w, f"beat {n}: RTL (m, j, pb, read, leave, in_a, tok, eor, eos, last) = {g}, golden {w}"
    assert len(got) == len(want), f"{len(got)} beats out, golden {len(want)}"


@cocotb.test()
async def test_walk(dut):
    """Golden frames' bitmaps in, the walk out beat for beat, with gaps and stalls; one
    frame without either, cycle for cycle."""
    tb = TB(dut)
    await tb.reset()
    seeds = [s for s in range(200) if s % 3 == 0][:FRAMES]
    cases = [("slab", d, 1) for d in SLAB_VIEWS] + [("sparse", s, 1) for s in seeds] + [("thin", 0, 1)]
    if tb.ss >= 2:      # S = 2 and 4: the passes that read a voxel slice walk all their rows
        cases += [("sparse", s, (2, 4)[n % 2]) for n, s in enumerate((1, 4, 8, 13))]
    read_rows = 0
    for n, (kind, seed, ss) in enumerate(cases):
        sched = (slab_frame(tb.p, seed) if kind == "slab" else thin_frame(tb.p) if kind == "thin"
                 else sparse_frame(seed, tb.p, opaque=n % 2 == 0, terminate=n % 3 != 2, supersample=ss)).sched
        read_rows += sum(sched.NJ for m in range(sched.M) if sched.reads_slice(m))
        if sched.NJ > tb.max_dim or sched.NB > -(-tb.max_dim // tb.p):
            continue
        gap, stall = ((0.0, 0.0), (0.3, 0.4), (0.6, 0.2), (0.0, 0.0), (0.1, 0.7))[n % 5]
        if kind == "thin":
            gap, stall = 0.0, 0.0           # the walk as close behind the bitmaps as it gets
        got, cycles = await tb.frame(sched, gap, stall)
        want = expected_walk(sched)
        compare(got, want, tb.log)
        if gap == 0 and stall == 0 and sched.NJ > 1:
            walker = int(beats.walker_cycles(sched).sum())
            formula = sched.NJ * min(2, sched.M) + 7 + walker
            assert cycles == formula, f"{cycles} edges, formula {formula} (walker {walker})"
        st = beats.schedule_stats(sched)
        near = sum(int((sched.run_beats(m) & ~sched.active_beats(m)).sum()) for m in range(sched.M))
        tb.log.info("%s %s S=%d: %d slices of %dx%d beats, %d run (%d as GRA's neighbours), %d walked (%d beats "
                    "out, %d edges) bit-exact", kind, seed, ss, sched.M, sched.NJ, sched.NB, st.run_beats, near,
                    st.walk_beats, len(got), cycles)
    assert read_rows > 0 or tb.ss < 2, "no pass read a voxel slice whole: S > 1 was not tested"


BUILDS = [dict(P=4, MAX_DIM=32, MAX_SS_LOG2=2), dict(P=1, MAX_DIM=32, MAX_SS_LOG2=2), dict(P=8, MAX_DIM=32),
          dict(P=5, MAX_DIM=64)]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1,), ids=param_id))
def test_cube4_cfb_beats(params):
    run_rtl(__file__, params)

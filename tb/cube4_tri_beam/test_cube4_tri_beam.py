"""Unit testbench of rtl/cube4_tri_beam.v: TRI's s2 .. s4, the 2 x 2 x 2 cells, bit for bit.

The unit's input is cube4_tri_src's s1; the DUT is the shared harness
sim/hdl/cube4_tri_cell_harness.v (``cube4_sim.tri_cells``): cube4_cfb reading
cube4_voxel_mem with seeded Verilog stalls on the memory request and response, then
cube4_tri_src (tb/cube4_tri_src checks its s1 beats), then this unit. Checked for every
s4 beat, in order, against the golden beats (``cube4_sim.beats.BeatSchedule``):

* the header (KEEP = LVALID) and the weights s4_wx, s4_wy, s4_wz;
* s4_vals: each lane's four words {prev upper, prev lower, cur upper, cur lower} = rows j
  and j + 1 of voxel slices k0 + 1 and k0 at position i (beam buffers: row j was written
  by the previous beam's beat one lane over; a Y-wrap beat's row j + 1 is zero), and
  s4_nvals the same at i + 1 (beam extension: from the neighbour lane or the next beat),
  against the traversal-frame volume zero-padded at the high end of each axis, in every
  lane that holds a position and every word its sample reads (weight > 0);
* s3_cell, s3_ncell (what the lanes form their x-lerps' differences from) in every
  cycle equal to s4_vals, s4_nvals in the next;
* exactly as many s4 beats as the view has, none in the 60 cycles after the last, and
  every other s3 beat gives its FIFO entry back: s4 beats + gives = s1 beats - 1 (the
  frame's last beat, the drain beat, stays held in s3).

Views: four directions, three of them supersampled (S = 2^MAX_SS_LOG2), with other
stalls, in one simulation per build; with VGRAD = 1 the words of ``cube4.vgrad``.

The test can fail (tried with a deliberately broken RTL, not kept): without the Y-wrap's
zero, P = 1 fails with "76 s4_vals cur lower lanes differ from the golden model, first at
beat 187 (m=1, j=8, pb=0, lane 0: i=0)".
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

from cube4_sim.tri_cells import CELL_BUILDS, VIEWS, CellBench, run_cells
from cube4_sim.unit_bench import check_headers, check_lanes

SIGNALS = ["s4_meta", "s4_wx", "s4_wy", "s4_wz", "s4_vals", "s4_nvals"]
# the four words of a lane, LSB first: (row offset dj, slice offset dk)
WORDS = [(1, 0, "cur lower"), (1, 1, "cur upper"), (0, 0, "prev lower"), (0, 1, "prev upper")]


async def watch_pre(dut, seen: list[int]) -> None:
    """s3_cell, s3_ncell are s4_vals, s4_nvals one cycle early, every cycle."""
    pre = None
    while True:
        await FallingEdge(dut.clk)
        await ReadOnly()
        now = (int(dut.s4_vals.value), int(dut.s4_nvals.value))
        if pre is not None:
            assert now == pre, f"cycle {seen[0]}: s4_vals / s4_nvals are not the last cycle's s3_cell / s3_ncell"
        pre = (int(dut.s3_cell.value), int(dut.s3_ncell.value))
        seen[0] += 1


@cocotb.test()
async def test_cells(dut):
    bench = CellBench(dut)
    await bench.start()
    seen = [0]
    watch = cocotb.start_soon(watch_pre(dut, seen))
    geo = bench.geo
    held = 0
    for direction, supersampled, stall_req, stall_in, phase in VIEWS:
        cv = bench.view(direction, supersampled, phase)
        got, counts = await bench.run_view(cv, stall_req, stall_in, "s4_v", SIGNALS)
        check_headers([b["s4_meta"] for b in got], cv.sched.headers(geo), geo, cv.sched, bench.log, "s4")
        wts = np.array([[b["s4_wx"], b["s4_wy"], b["s4_wz"]] for b in got])
        bad = np.argwhere(wts != np.stack([cv.wx, cv.wy, cv.wz], axis=1))
        assert bad.size == 0, f"s4 weights (wx, wy, wz) differ from the golden ones, first at {cv.sched.describe(bad[0][0])}"
        for name, di in (("s4_vals", 0), ("s4_nvals", 1)):
            words = [b[name] for b in got]
            for slot, (dj, dk, what) in enumerate(WORDS):
                check_lanes(bench.lanes(words, slot, 4), cv.voxels(dk, dj, di), cv.needed(dk, dj, di),
                            cv.sched, bench.log, f"{name} {what}")
        # the previous frame's drain beat leaves s3 (a give) with this frame's first beat
        assert counts["s4"] + counts["give"] == counts["s1"] - 1 + held, f"beats in and out: {counts}"
        held = 1
        assert not watch.done() or watch.exception() is None, "the s3_cell watch stopped"
        bench.log.info("view %s S=%d stalls req %d in %d: %d cells bit-exact (%s)", direction,
                       cv.trav.supersample, stall_req, stall_in, len(got), counts)


@pytest.mark.parametrize("build", CELL_BUILDS)
def test_cube4_tri_beam(build):
    run_cells(__file__, build)

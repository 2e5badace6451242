"""Unit testbench of rtl/cube4_tri_src.v: TRI's s0 and s1, bit for bit.

The unit's input is the memory's response beats (voxels + cube4_cfb's tag); their one
exact source is cube4_cfb reading cube4_voxel_mem, so the DUT is the shared harness
sim/hdl/cube4_tri_cell_harness.v (``cube4_sim.tri_cells``) with seeded Verilog stalls on
the memory request and on the memory response, the unit's input. Checked for every s1
beat the tag emits (TRI_C_EMIT of s1_ctl), in order, against the golden beats
(``cube4_sim.beats.BeatSchedule``; lane q holds i = pos[q]):

* the header that s1_ctl carries (KEEP = LVALID; INSIDE from ``cube4.model.inside_mask``);
* the weights wx, wy, wz (``Traversal.weights``);
* s1_pair: the lower slice's word (voxel slice k0 = m // S, row j + 1, the row the beat
  reads) in every lane that holds a position, and the upper slice's (k0 + 1) where
  wz > 0, from memory or, supersampled, from the slice buffers; rows j + 1 < NJ;
* exactly as many emitted beats as the view has, none in the 60 cycles after the last.

Views: four directions, three of them supersampled (S = 2^MAX_SS_LOG2), with other
stalls, in one simulation per build; with VGRAD = 1 the words of ``cube4.vgrad``.

The test can fail (tried with a deliberately broken RTL, not kept): with the upper slice
always read from slice buffer 1 (not by parity), P = 5 (S = 4: later passes read the upper
slice from its buffer) fails with "624 s1 upper word lanes differ from the golden model,
first at beat 162 (m=6, j=0, pb=0, lane 0: i=4)"; S = 2 alone does not reach that path.
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest

from cube4_sim.tri_cells import CELL_BUILDS, VIEWS, CellBench, run_cells
from cube4_sim.unit_bench import check_headers, check_lanes


@cocotb.test()
async def test_s1_stream(dut):
    bench = CellBench(dut)
    await bench.start()
    geo, p, w = bench.geo, bench.p, bench.w
    for direction, supersampled, stall_req, stall_in, phase in VIEWS:
        cv = bench.view(direction, supersampled, phase)
        got, counts = await bench.run_view(cv, stall_req, stall_in, "s1_v", ["s1_ctl", "s1_pair"])
        ctl = [b["s1_ctl"] for b in got]
        hdr_mask = (1 << geo.hdr_w) - 1
        check_headers([c & hdr_mask for c in ctl], cv.sched.headers(geo), geo, cv.sched, bench.log, "s1")
        wts = np.array([[(c >> (geo.hdr_w + 2 * p + k * w)) & ((1 << w) - 1) for k in (2, 1, 0)] for c in ctl])
        bad = np.argwhere(wts != np.stack([cv.wx, cv.wy, cv.wz], axis=1))
        assert bad.size == 0, f"s1 weights (wx, wy, wz) differ from the golden ones, first at {cv.sched.describe(bad[0][0])}"
        pairs = [b["s1_pair"] for b in got]
        row = (cv.sched.j + 1 < cv.trav.nj)[:, None]
        for slot, dk, what in ((0, 0, "s1 lower word"), (1, 1, "s1 upper word")):
            check_lanes(bench.lanes(pairs, slot, 2), cv.voxels(dk, 1, 0), cv.needed(dk, 0, 0) & row,
                        cv.sched, bench.log, what)
        bench.log.info("view %s S=%d stalls req %d in %d: %d emitted s1 beats bit-exact (%s)", direction,
                       cv.trav.supersample, stall_req, stall_in, len(got), counts)


@pytest.mark.parametrize("build", CELL_BUILDS)
def test_cube4_tri_src(build):
    run_cells(__file__, build)

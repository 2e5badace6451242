"""Unit testbench of rtl/cube4_cfb_steps.v: the slices' accumulated steps of the beat schedule.

For golden views (``cube4.view.make_traversal``: S = 1 and the build's largest S, random
starting phases, slopes up to 45°) the unit is started and its items taken with seeded
random ready: item m must be ``Traversal.steps(m)``, for m = 0 .. M - 1 in order, an item
must hold while not taken, and after the M-th nothing more is offered (the bench keeps ready
high for 20 cycles). A second start in mid-frame begins again at slice 0.
"""

from __future__ import annotations

import cocotb
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

from cube4.view import make_traversal
from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import UnitBench, param_id, run_unit

VIEWS = [((0.3, -0.45, 1.0), (9, 7, 6)), ((-0.6, 0.25, -1.0), (8, 10, 5)), ((1.0, 1.0, -1.0), (9, 6, 8)),
         ((0.5, -1.0, 0.05), (10, 7, 9))]


async def take(dut, bench, trav, stall: float, stop_after: int | None = None) -> int:
    """Start a frame and take its items; ``stop_after``: leave after that many (mid-frame)."""
    await FallingEdge(dut.clk)
    dut.start.value = 1
    await FallingEdge(dut.clk)
    dut.start.value = 0
    M = trav.num_sample_slices
    n, held, idle = 0, None, 0
    while idle < 20:
        ready = int(bench.rng.random() >= stall) if n < M else 1
        dut.st_ready.value = ready
        await ReadOnly()
        valid = int(dut.st_valid.value)
        got = (int(dut.st_x.value), int(dut.st_y.value))
        if valid:
            assert n < M, f"an item after the frame's {M}"
            if held is not None:
                assert got == held, f"item {n} changed while not taken"
            want = tuple(int(v) for v in trav.steps(n))
            assert got == want, f"item {n}: RTL {got}, golden {want}"
            held = None if ready else got
            if ready:
                n += 1
        if n >= M:
            idle += 1
        await FallingEdge(dut.clk)
        if stop_after is not None and n >= stop_after:
            return n
    assert n == M, f"{n} items, golden {M}"
    return n


@cocotb.test()
async def test_steps(dut):
    w, ss_max = int(dut.WEIGHT_W.value), 1 << int(dut.MAX_SS_LOG2.value)
    bench = UnitBench(dut)
    await bench.reset({"start": 0, "st_ready": 0})
    items = 0
    for n, (direction, dims) in enumerate(VIEWS):
        for ss in sorted({1, ss_max}):
            one = 1 << (w + ss.bit_length() - 1)
            phase = tuple(int(v) for v in bench.rng.integers(0, one, 2))
            trav = make_traversal(dims, direction, w, ss, phase=phase)
            bench.set_view(trav, int(dut.P.value))
            if n == 1:
                await take(dut, bench, trav, 0.3, stop_after=3)    # a new start in mid-frame
            items += await take(dut, bench, trav, (0.0, 0.4, 0.8)[n % 3])
    dut._log.info("%d items: the accumulated steps of every slice, in order", items)


BUILDS = [{"P": 8, "MAX_SS_LOG2": 0}, {"P": 5, "MAX_SS_LOG2": 2, "WEIGHT_W": 12}]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(0,), ids=param_id))
def test_cube4_cfb_steps(params):
    run_unit(__file__, {"MAX_DIM": 32, "ADDR_W": 16, "WEIGHT_W": 8, **params})

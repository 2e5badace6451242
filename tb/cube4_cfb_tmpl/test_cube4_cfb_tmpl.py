"""Unit testbench of rtl/cube4_cfb_tmpl.v: the CFB's template unit.

For golden views (``cube4.view.make_traversal``: S = 1 and S = 2, random starting phases)
the unit is loaded while idle and stepped pass by pass (next_pass, with seeded random
stalls between passes; r = m mod S as the traversal unit gives it). In every pass m its
weights must be ``Traversal.weights(m)`` and its steps {old Y, old X, Y, X} the golden
``Traversal.steps`` differences (m-1 -> m, m -> m+1; ``cube4_sim.cfb_walk.template``);
during a stall nothing moves, and back in idle the unit holds pass 0's values again.
"""

from __future__ import annotations

import cocotb
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

from cube4.view import make_traversal
from cube4_sim.cfb_walk import template
from cube4_sim.unit_bench import UnitBench, param_id, run_unit
from cube4_sim.sweeps import sweep

VIEWS = [((0.3, -0.45, 1.0), (9, 7, 6)), ((-0.6, 0.25, -1.0), (8, 10, 5)), ((1.0, 0.9, -0.7), (9, 6, 8)),
         ((0.5, -1.0, 0.05), (10, 7, 9))]


def outputs(dut) -> tuple[int, int, int, int]:
    return int(dut.wx.value), int(dut.wy.value), int(dut.wz.value), int(dut.steps.value)


async def play(dut, bench, trav, gap: float) -> int:
    dut.idle.value, dut.next_pass.value, dut.r.value = 1, 0, 0
    await bench.cycles(2)
    await FallingEdge(dut.clk)
    dut.idle.value = 0
    M, s = trav.num_sample_slices, trav.supersample
    for m in range(M):
        dut.r.value = m % s
        while bench.rng.random() < gap:
            await ReadOnly()
            held = outputs(dut)
            await FallingEdge(dut.clk)
            assert outputs(dut) == held, f"pass {m}: moved during a stall"
        await ReadOnly()
        got, want = outputs(dut), template(trav, m)
        assert got == want, f"pass {m} (wx, wy, wz, steps): RTL {got}, golden {want}"
        await FallingEdge(dut.clk)
        dut.next_pass.value = int(m < M - 1)
        await FallingEdge(dut.clk)
        dut.next_pass.value = 0
    dut.idle.value, dut.r.value = 1, 0
    await bench.cycles(2)
    await ReadOnly()
    assert outputs(dut) == template(trav, 0), "idle again: not back at pass 0"
    await FallingEdge(dut.clk)
    return M


@cocotb.test()
async def test_tmpl(dut):
    w, ss_max = int(dut.WEIGHT_W.value), 1 << int(dut.MAX_SS_LOG2.value)
    bench = UnitBench(dut)
    await bench.reset({"idle": 1, "next_pass": 0, "r": 0})
    passes = 0
    for n, (direction, dims) in enumerate(VIEWS):
        for ss in sorted({1, ss_max}):
            one = 1 << (w + ss.bit_length() - 1)
            phase = tuple(int(v) for v in bench.rng.integers(0, one, 2))
            trav = make_traversal(dims, direction, w, ss, phase=phase)
            bench.set_view(trav, int(dut.P.value))
            passes += await play(dut, bench, trav, (0.0, 0.4)[n % 2])
    dut._log.info("%d passes: weights and steps as the golden template", passes)


BUILDS = [{"P": 1, "MAX_SS_LOG2": 1}, {"P": 5, "MAX_SS_LOG2": 2, "WEIGHT_W": 12}]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_cfb_tmpl(params):
    run_unit(__file__, {"MAX_DIM": 32, "ADDR_W": 16, "WEIGHT_W": 8, **params})

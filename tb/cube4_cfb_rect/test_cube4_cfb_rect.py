"""Unit testbench of rtl/cube4_cfb_rect.v: the CFB's rectangle-table reader (RECTS = 1).

Golden tables (``cube4.memory.rect_table`` of random ``cube4.slices`` rectangles and of the
whole box) are written through the write port; then frames are played as the control and
traversal units move: idle, start (go), pass_done at the end of every pass with seeded
random stalls between. While idle both outputs must be entry 0; in pass m rt_cur must be
entry m and rt_nxt entry m + 1 (the table read one pass ahead), unchanged during stalls;
after the frame the unit is back at entry 0.
"""

from __future__ import annotations

import cocotb
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

import cube4.slices as slices
from cube4.view import make_traversal
from cube4_sim.rect_port import rect_words, write_rect_table
from cube4_sim.unit_bench import UnitBench, param_id, run_unit
from cube4_sim.sweeps import sweep

VIEWS = [((0.3, -0.45, 1.0), (13, 9, 8)), ((-0.6, 0.25, -1.0), (11, 10, 9)), ((1.0, -1.0, 0.0), (9, 12, 8))]


async def check(dut, words: list[int], m: int, idle: bool) -> None:
    await ReadOnly()
    want = (words[0], words[0]) if idle else (words[m], words[m + 1])
    got = (int(dut.rt_cur.value), int(dut.rt_nxt.value))
    assert got == want, f"{'idle' if idle else f'pass {m}'}: (rt_cur, rt_nxt) = {got}, table {want}"


async def play(dut, bench, words: list[int], passes: int, gap: float) -> None:
    await FallingEdge(dut.clk)
    dut.idle.value, dut.go.value, dut.pass_done.value, dut.m.value = 1, 0, 0, 0
    await bench.cycles(2)
    await check(dut, words, 0, True)
    await FallingEdge(dut.clk)
    dut.go.value = 1
    await FallingEdge(dut.clk)
    dut.go.value = dut.idle.value = 0
    for m in range(passes):
        dut.m.value = m
        while bench.rng.random() < gap:
            await check(dut, words, m, False)
            await FallingEdge(dut.clk)
        await check(dut, words, m, False)
        await FallingEdge(dut.clk)
        dut.pass_done.value = 1
        await FallingEdge(dut.clk)
        dut.pass_done.value = 0
    await FallingEdge(dut.clk)       # the drain beat
    await FallingEdge(dut.clk)
    dut.idle.value = 1
    await bench.cycles(2)
    await check(dut, words, 0, True)
    await FallingEdge(dut.clk)


@cocotb.test()
async def test_rect(dut):
    p, md, aw, w = (int(getattr(dut, n).value) for n in ("P", "MAX_DIM", "ADDR_W", "WEIGHT_W"))
    bench = UnitBench(dut)
    dut.rect_we.value, dut.idle.value, dut.go.value, dut.pass_done.value, dut.m.value = 0, 1, 0, 0, 0
    await bench.cycles(2)
    frames = 0
    for n, (direction, dims) in enumerate(VIEWS):
        trav = make_traversal(dims, direction, w, 1)
        for density in (0.05, 0.3, 1.0):
            need = bench.rng.random((trav.num_sample_slices, trav.nj, trav.ni)) < density
            rects = slices.rects_from_needed(need, trav)
            if rects.last() < 0:
                continue
            await FallingEdge(dut.clk)
            await write_rect_table(dut, trav, rects, p, aw)
            words = rect_words(trav, rects, p, md, aw)
            await play(dut, bench, words, rects.last() + 1, (0.0, 0.3, 0.6)[n % 3])
            frames += 1
    dut._log.info("%d frames: every pass saw its entry and the next", frames)


BUILDS = [{"P": 1}, {"P": 5}]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_cfb_rect(params):
    run_unit(__file__, {"MAX_DIM": 32, "ADDR_W": 16, "WEIGHT_W": 8, **params})

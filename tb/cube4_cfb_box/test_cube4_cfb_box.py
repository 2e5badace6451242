"""Unit testbench of rtl/cube4_cfb_box.v: the pass's rectangle without slice rectangles.

For golden views (``cube4.view.make_traversal``, every major axis, flipped axes, S = 1
and S = 2) the entry the unit builds from the view and address registers must be the
golden rectangle table's entry of the whole box (``cube4.memory.rect_table`` of
``cube4.slices.whole_box_rects``, at S = 1: the entry does not depend on S) in every field
the CFB reads; FLUSH and LAST follow last_pass, EMPTY and COM's fields are zero, and the
next pass's entry is the same. The unit is combinational: no stream, no stalls.
"""

from __future__ import annotations

import cocotb
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

import cube4.slices as slices
from cube4.memory import rect_table
from cube4.view import make_traversal
from cube4_sim.rect_port import rect_layout
from cube4_sim.unit_bench import UnitBench, param_id, run_unit
from cube4_sim.sweeps import sweep

VIEWS = [(0.3, -0.45, 1.0), (-0.6, 0.25, -1.0), (1.0, 0.4, -0.7), (-0.5, -1.0, 0.5), (0.0, 0.0, 1.0)]
COM_FIELDS = ("j_hi", "i_hin", "stx", "sty", "ins")


def unpack(word: int, layout) -> dict[str, int]:
    out, pos = {}, 0
    for name, w in layout:
        out[name] = (word >> pos) & ((1 << w) - 1)
        pos += w
    return out


@cocotb.test()
async def test_box(dut):
    p, md, aw, w = (int(getattr(dut, n).value) for n in ("P", "MAX_DIM", "ADDR_W", "WEIGHT_W"))
    layout = rect_layout(p, md, aw)
    bench = UnitBench(dut)
    checked = 0
    for direction in VIEWS:
        for dims in [(2 * p + 3, p + 4, 5), (p + 1, 3, 7)]:
            one = make_traversal(dims, direction, w, 1)
            want = rect_table(one, slices.whole_box_rects(one), p, aw)[0]
            for ss in (1, 2):
                await FallingEdge(dut.clk)
                bench.set_view(make_traversal(dims, direction, w, ss), p)
                for last in (0, 1):
                    await FallingEdge(dut.clk)
                    dut.last_pass.value = last
                    await ReadOnly()
                    cur, nxt = int(dut.rt_cur.value), int(dut.rt_nxt.value)
                    got = unpack(cur, layout)
                    exp = {**{k: v for k, v in want.items() if k not in COM_FIELDS},
                           **{k: 0 for k in COM_FIELDS}, "empty": 0, "flush": last, "last": last}
                    bad = {k: (got[k], exp[k]) for k in exp if got[k] != exp[k]}
                    assert not bad, f"view {direction} dims {dims} S={ss} last={last} (RTL, golden): {bad}"
                    assert nxt == cur, "the next pass's entry is not the box"
                    checked += 1
    await FallingEdge(dut.clk)
    dut._log.info("%d entries: the whole box as the golden table has it", checked)


BUILDS = [{"P": 1}, {"P": 5}]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_cfb_box(params):
    run_unit(__file__, {"MAX_DIM": 32, "ADDR_W": 16, "WEIGHT_W": 8, "MAX_SS_LOG2": 1, **params})

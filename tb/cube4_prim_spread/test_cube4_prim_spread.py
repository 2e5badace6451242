"""Unit testbench of rtl/cube4_prim_spread.v: a control register spread over a word.

Random control words every cycle (and resets at random for RESET = 1): one edge later
every control bit c must be on all D bits of its slice of q (q[c*D + b] = d[c] of the
last edge; after a reset edge 0 with RESET = 1). Checked on every cycle; the count of
checked cycles must be the number driven. The builds cover groups that do not divide
the word and empty last groups (D < COPIES).

The test can fail (tried with a deliberately corrupted expectation, not kept).
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from cube4_sim import rtl_sources, run_test

CYCLES = 400


@cocotb.test()
async def test_spread(dut):
    w, d, reset = int(dut.W.value), int(dut.D.value), int(dut.RESET.value)
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    Clock(dut.clk, 10, unit="ns").start(start_high=False)
    dut.rst.value = 0
    prev = None
    checked = 0
    for _ in range(CYCLES):
        await FallingEdge(dut.clk)
        if prev is not None:
            want = 0
            for c in range(w):
                if prev >> c & 1:
                    want |= ((1 << d) - 1) << (c * d)
            got = int(dut.q.value)
            assert got == want, f"q {got:#x}, expected {want:#x} (d was {prev:#x})"
            checked += 1
        ctl = int(rng.integers(0, 1 << w))
        rst = int(rng.random() < 0.05)
        dut.d.value = ctl
        dut.rst.value = rst
        prev = 0 if (rst and reset) else ctl
    assert checked == CYCLES - 1


BUILDS = [{"W": 5, "D": 68, "COPIES": 4}, {"W": 1, "D": 3, "COPIES": 4, "RESET": 1}]


@pytest.mark.parametrize("params", BUILDS, ids=lambda p: "_".join(f"{k}{v}" for k, v in p.items()))
def test_cube4_prim_spread(params):
    run_test(top="cube4_prim_spread", sources=rtl_sources(), params=params, test_module=__file__)

"""Unit testbench of rtl/cube4_prim_reg_en.v: a register loaded under a copied enable.

Random data every cycle and a random enable (en_d), with resets at random: q must take
d at an edge exactly when en_d was 1 at the edge before (and no load follows a reset
edge when RESET = 1), and hold otherwise, in every bit group. Checked on every cycle
against a Python model of the register; the count of checked cycles must be the
number driven. The builds cover groups that do not divide the word and an empty last
group (W < COPIES).

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
async def test_reg_en(dut):
    w, reset = int(dut.W.value), int(dut.RESET.value)
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    Clock(dut.clk, 10, unit="ns").start(start_high=False)
    dut.rst.value = 1
    dut.en_d.value = 0
    dut.d.value = 0
    await FallingEdge(dut.clk)
    dut.rst.value = 0
    await FallingEdge(dut.clk)       # the enable copies are 0, q is unknown until a load
    model, en_q, checked, loaded = None, 0, 0, False
    for _ in range(CYCLES):
        if loaded:
            got = int(dut.q.value)
            assert got == model, f"q {got:#x}, expected {model:#x}"
            checked += 1
        data = int.from_bytes(rng.bytes((w + 7) // 8), "little") & ((1 << w) - 1)
        en = int(rng.random() < 0.5)
        rst = int(rng.random() < 0.05)
        dut.d.value, dut.en_d.value, dut.rst.value = data, en, rst
        if en_q:                      # this edge loads with the enable registered at the last one
            model, loaded = data, True
        en_q = 0 if (rst and reset) else en
        await FallingEdge(dut.clk)
    assert checked > CYCLES // 2, f"only {checked} cycles checked"


BUILDS = [{"W": 68, "COPIES": 4}, {"W": 3, "COPIES": 4, "RESET": 0}]


@pytest.mark.parametrize("params", BUILDS, ids=lambda p: "_".join(f"{k}{v}" for k, v in p.items()))
def test_cube4_prim_reg_en(params):
    run_test(top="cube4_prim_reg_en", sources=rtl_sources(), params=params, test_module=__file__)

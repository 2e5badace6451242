"""Testbench of rtl/cube4_prim_reg_copies.v: register copies with their own enables.

A cocotb clock drives the primitive directly. Every cycle the bench sets each copy's
enable and next value at random (seeded from COCOTB_RANDOM_SEED), with a reset now and
then, and checks every copy after the clock edge against a model of COPIES registers:
copy c takes d[c] when en[c], holds otherwise, and with RESET = 1 returns to RST_VAL
on a reset (before the enable); with ENABLE = 0 every copy loads on every edge,
whatever en says (cube4_prim_copies' form). Built with three copies of a 5-bit register
with a reset value, one copy of one bit without reset, and two copies without enables.
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from cube4_sim import run_test
from cube4_sim.sources import rtl_sources

CYCLES = 400


@cocotb.test()
async def copies_follow_their_enables(dut):
    n, w, reset = int(dut.COPIES.value), int(dut.W.value), int(dut.RESET.value)
    enable = int(dut.ENABLE.value)
    rst_val = int(dut.RST_VAL.value) & ((1 << w) - 1)
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    Clock(dut.clk, 10, unit="ns").start(start_high=False)
    dut.rst.value, dut.en.value, dut.d.value = 1, 0, 0
    await RisingEdge(dut.clk)
    model = [rst_val if reset else None] * n
    checks = 0
    await FallingEdge(dut.clk)
    for _ in range(CYCLES):
        rst = int(rng.random() < 0.05)
        en = [int(rng.random() < 0.5) for _ in range(n)]
        d = [int(rng.integers(0, 1 << w)) for _ in range(n)]
        dut.rst.value = rst
        dut.en.value = sum(e << c for c, e in enumerate(en))
        dut.d.value = sum(v << (c * w) for c, v in enumerate(d))
        await RisingEdge(dut.clk)
        for c in range(n):
            if reset and rst:
                model[c] = rst_val
            elif en[c] or not enable:
                model[c] = d[c]
        await FallingEdge(dut.clk)
        q = int(dut.q.value)
        for c in range(n):
            got = (q >> (c * w)) & ((1 << w) - 1)
            if model[c] is not None:
                assert got == model[c], f"copy {c}: q = {got}, expected {model[c]}"
                checks += 1
    assert checks > CYCLES // 2, f"only {checks} checks"


PARAM_SETS = [{"COPIES": 3, "W": 5, "RESET": 1, "RST_VAL": "64'd21"}, {"COPIES": 1, "W": 1, "RESET": 0},
              {"COPIES": 2, "W": 3, "RESET": 1, "ENABLE": 0}]


@pytest.mark.parametrize("params", PARAM_SETS, ids=lambda p: "-".join(f"{k}{v}" for k, v in p.items()))
def test_cube4_prim_reg_copies(params):
    run_test(top="cube4_prim_reg_copies", sources=rtl_sources(), params=params, test_module=__file__)

"""Testbench of rtl/cube4_prim_lut_copies.v, with cube4_prim_lut4 in both of its forms.

A cocotb clock drives the primitive directly. Every cycle the bench sets each copy's four
inputs at random (seeded from COCOTB_RANDOM_SEED; each copy its own inputs, so that a copy
which took another copy's inputs fails), with a reset now and then, and checks every copy
after the clock edge against the truth table: q[c] = INIT[{d, c, b, a}] of copy c's inputs
at the edge, or RST_VAL under a reset with RESET = 1 (with RESET = 0 the reset is not
read). It also checks that every one of the sixteen input words reached every copy. The
ECP5 form (each copy's cube4_prim_lut4 an instantiated LUT4, rtl/ecp5/) runs with the
primitive's model (sim/hdl/ecp5/LUT4.v): both forms equal to the table means the
simulations of the design (generic forms) stand for the synthesized one.
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from cube4_sim import run_test
from cube4_sim.sources import RTL_FORMS, form_build_args, form_sources

CYCLES = 400


@cocotb.test()
async def copies_follow_their_table(dut):
    n = int(dut.COPIES.value)
    init, reset, rst_val = int(dut.INIT.value), int(dut.RESET.value), int(dut.RST_VAL.value)
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    Clock(dut.clk, 10, unit="ns").start(start_high=False)
    inp = getattr(dut, "in")             # (a Python keyword)
    dut.rst.value, inp.value = 0, 0
    await FallingEdge(dut.clk)
    seen = [set() for _ in range(n)]
    for _ in range(CYCLES):
        rst = int(rng.random() < 0.05)
        words = [int(w) for w in rng.integers(0, 16, n)]
        dut.rst.value = rst
        inp.value = sum(w << (4 * c) for c, w in enumerate(words))
        await RisingEdge(dut.clk)
        await FallingEdge(dut.clk)
        q = int(dut.q.value)
        for c, w in enumerate(words):
            want = rst_val if (reset and rst) else (init >> w) & 1
            got = (q >> c) & 1
            assert got == want, f"copy {c}: q = {got}, expected {want} (inputs {w:04b}, rst {rst})"
            if not rst:
                seen[c].add(w)
    for c in range(n):
        assert len(seen[c]) == 16, f"copy {c}: only {len(seen[c])} of the 16 input words were driven"


PARAM_SETS = [
    {"COPIES": 5, "INIT": 0xCD0F, "RESET": 1, "RST_VAL": 1},      # cube4_skid_peek's ready copies
    {"COPIES": 3, "INIT": 0x00AE, "RESET": 0, "RST_VAL": 0},      # cube4_prim_valid_copies' copies
    {"COPIES": 1, "INIT": 0x6996, "RESET": 1, "RST_VAL": 0},      # parity: every input matters
]


@pytest.mark.parametrize("form", RTL_FORMS)
@pytest.mark.parametrize("params", PARAM_SETS, ids=lambda p: "-".join(f"{k}{v}" for k, v in p.items()))
def test_cube4_prim_lut_copies(params, form):
    run_test(top="cube4_prim_lut_copies", sources=form_sources(form), params=params, test_module=__file__,
             build_args=form_build_args(form))

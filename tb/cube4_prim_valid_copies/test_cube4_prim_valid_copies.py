"""Testbench of rtl/cube4_prim_valid_copies.v and its ECP5 form (rtl/ecp5/).

A cocotb clock drives the primitive directly. Every cycle the bench sets the valid bit
to load (d) and each copy's ready at random (seeded from COCOTB_RANDOM_SEED; each copy
its own ready, so that a copy which took another copy's ready or the advance of another
copy fails), with a reset now and then, and checks every copy, before and after the
clock edge, against a model of a pipeline register's valid bit: adv[c] = ~q[c] |
ready[c], q[c] takes d when adv[c], holds otherwise, and returns to 0 on a reset. The
ECP5 form (each copy's next value an instantiated LUT4) runs with the primitive's model
(sim/hdl/ecp5/LUT4.v): both forms equal to the model means the simulations of the design
(generic forms) stand for the synthesized one.
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from cube4_sim import run_test
from cube4_sim.sources import RTL_FORMS, form_build_args, form_sources

CYCLES = 600


@cocotb.test()
async def copies_follow_their_ready(dut):
    n = int(dut.COPIES.value)
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    Clock(dut.clk, 10, unit="ns").start(start_high=False)
    dut.rst.value, dut.d.value, dut.ready.value = 1, 0, 0
    await RisingEdge(dut.clk)
    model = [0] * n
    seen = set()
    await FallingEdge(dut.clk)
    for _ in range(CYCLES):
        rst = int(rng.random() < 0.04)
        d = int(rng.random() < 0.6)
        ready = [int(rng.random() < 0.5) for _ in range(n)]
        dut.rst.value, dut.d.value = rst, d
        dut.ready.value = sum(r << c for c, r in enumerate(ready))
        await RisingEdge(dut.clk)
        adv = int(dut.adv.value)
        for c in range(n):
            want = int(not model[c] or ready[c])
            got = (adv >> c) & 1
            assert got == want, f"copy {c}: adv = {got}, expected {want} (q {model[c]}, ready {ready[c]})"
            seen.add((model[c], ready[c], d))
            model[c] = 0 if rst else (d if want else model[c])
        await FallingEdge(dut.clk)
        q = int(dut.q.value)
        for c in range(n):
            assert (q >> c) & 1 == model[c], f"copy {c}: q = {(q >> c) & 1}, expected {model[c]}"
    assert len(seen) == 8, f"only {sorted(seen)} of the eight (q, ready, d) cases were driven"


PARAM_SETS = [{"COPIES": 5}, {"COPIES": 1}]


@pytest.mark.parametrize("form", RTL_FORMS)
@pytest.mark.parametrize("params", PARAM_SETS, ids=lambda p: "-".join(f"{k}{v}" for k, v in p.items()))
def test_cube4_prim_valid_copies(params, form):
    run_test(top="cube4_prim_valid_copies", sources=form_sources(form), params=params, test_module=__file__,
             build_args=form_build_args(form))

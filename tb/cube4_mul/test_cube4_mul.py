"""Testbench for rtl/cube4_mul.v and its ECP5 form rtl/ecp5/cube4_mul.v.

Both forms run the same cocotb test against the Python product a * b: the generic form
(registers in the fabric) from rtl/sources.f, the ECP5 form (a MULT18X18D with its
input and output registers) with the primitive's behavioural model
(sim/hdl/ecp5/MULT18X18D.v). Both equal to the product at latency 2 (3 with OUT_FF = 1,
the fabric register after the product) means the two forms agree, so the simulations of
the whole design (generic forms) stand for the netlist synthesis builds (vendor forms).

Cycle discipline: the TB drives a, b, en on each falling edge and reads p there; a
model of the 2 + OUT_FF stages (advancing only with en = 1) says what p holds. Operands are
random over the full signed range plus the corners (most negative times most negative,
the largest product), with random en (stalls) in one test and en = 1 in the other; p
must hold across every stalled edge. Seeded per test from COCOTB_RANDOM_SEED.
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

CLK_PERIOD_NS = 10


class TB:
    """Drives cube4_mul and checks p against a (2 + OUT_FF)-stage model of a * b."""

    def __init__(self, dut) -> None:
        self.dut = dut
        self.a_w = int(dut.A_W.value)
        self.b_w = int(dut.B_W.value)
        self.p_w = self.a_w + self.b_w
        self.stages = 2 + int(dut.OUT_FF.value)
        self.rng = np.random.default_rng(cocotb.RANDOM_SEED)
        Clock(dut.clk, CLK_PERIOD_NS, unit="ns").start(start_high=False)

    def operands(self, n: int) -> list[tuple[int, int]]:
        lo_a, hi_a = -(1 << (self.a_w - 1)), (1 << (self.a_w - 1)) - 1
        lo_b, hi_b = -(1 << (self.b_w - 1)), (1 << (self.b_w - 1)) - 1
        corners = [(x, y) for x in (lo_a, -1, 0, 1, hi_a) for y in (lo_b, -1, 0, 1, hi_b)]
        rand = zip(self.rng.integers(lo_a, hi_a, n, endpoint=True).tolist(),
                   self.rng.integers(lo_b, hi_b, n, endpoint=True).tolist())
        return corners + list(rand)

    def read_p(self) -> int:
        v = int(self.dut.p.value)
        return v - (1 << self.p_w) if v >> (self.p_w - 1) else v

    async def run(self, vectors: list[tuple[int, int]], en_prob: float) -> int:
        """Drive every vector (held until an enabled edge takes it); returns the checks made."""
        dut = self.dut
        # the model: operands taken (stage 1), then the product in stages 2 .. self.stages
        stages = [None] * self.stages
        checks, pending = 0, list(vectors) + [(0, 0)] * (self.stages + 1)
        await FallingEdge(dut.clk)
        while pending:
            en = 1 if self.rng.random() < en_prob else 0
            a, b = pending[0]
            dut.a.value = a & ((1 << self.a_w) - 1)
            dut.b.value = b & ((1 << self.b_w) - 1)
            dut.en.value = en
            await FallingEdge(dut.clk)
            if en:
                prod = stages[0][0] * stages[0][1] if stages[0] else None
                stages = [(a, b), prod] + stages[1:-1]
                pending.pop(0)
            if stages[-1] is not None:
                got = self.read_p()
                assert got == stages[-1], (f"p = {got}, expected {stages[-1]} (A_W={self.a_w}, B_W={self.b_w}, "
                                           f"OUT_FF={self.stages - 2})")
                checks += 1
        return checks


@cocotb.test()
async def mul_streaming(dut):
    tb = TB(dut)
    vecs = tb.operands(400)
    assert await tb.run(vecs, en_prob=1.0) >= len(vecs)


@cocotb.test()
async def mul_random_stalls(dut):
    tb = TB(dut)
    vecs = tb.operands(400)
    assert await tb.run(vecs, en_prob=0.6) >= len(vecs)


# ---------------------------------------------------------------- pytest half
from cube4_sim import run_test  # noqa: E402
from cube4_sim.sweeps import sweep
from cube4_sim.sources import RTL_FORMS, form_build_args, form_sources  # noqa: E402

# widths the design uses (COM's T * A and w * C', GRA's view products, the lerps),
# the ECP5 form's fall-back beyond 18 bits, and the smallest
# (OUT_FF = 1: SHA's C * D and GRA's view products, and the fall-back with it)
PARAM_SETS = [{"A_W": 18, "B_W": 18}, {"A_W": 18, "B_W": 13}, {"A_W": 9, "B_W": 11, "OUT_FF": 1},
              {"A_W": 9, "B_W": 11}, {"A_W": 25, "B_W": 9, "OUT_FF": 1}, {"A_W": 25, "B_W": 9},
              {"A_W": 2, "B_W": 2}]


def _param_id(params: dict) -> str:
    return "-".join(f"{k}{v}" for k, v in params.items())


@pytest.mark.parametrize("form", RTL_FORMS)
@pytest.mark.parametrize("params", sweep(PARAM_SETS, quick=(0, 2), ids=_param_id))
def test_cube4_mul(params, form):
    run_test(top="cube4_mul", sources=form_sources(form), params=params, test_module=__file__,
             build_args=form_build_args(form))

"""Testbench for rtl/cube4_round_shift.v: bit-exact against cube4.fixed.round_shift.

cube4_lerp exercises this module only with SHIFT = WEIGHT_W and its own input
range; here it is checked on its own, over the whole signed input range:
exhaustively when IN_W is small, else the extremes, every value around each
rounding tie near zero and near the extremes, and random values.
Combinational: drive x, wait 1 ns, read y.
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.triggers import Timer

from cube4.fixed import round_shift
from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import param_id, run_rtl

MAX_MISMATCH_LOGS = 10


@cocotb.test()
async def round_shift_values(dut):
    in_w = int(dut.IN_W.value)
    shift = int(dut.SHIFT.value)
    lo, hi = -(1 << (in_w - 1)), (1 << (in_w - 1)) - 1
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    if in_w <= 12:
        xs = list(range(lo, hi + 1))
    else:
        xs = {lo, hi, 0, -1, 1}
        half = 1 << (shift - 1) if shift > 0 else 0
        for centre in (0, half, -half, lo + half, hi - half, lo, hi):
            for k in range(-3, 4):  # a few LSBs either side of every tie
                xs.add(centre + k + (1 << shift) * int(rng.integers(-2, 3)))
        xs.update(int(v) for v in rng.integers(lo, hi, size=3000, endpoint=True))
        xs = sorted(x for x in xs if lo <= x <= hi)
    dut._log.info("cube4_round_shift IN_W=%d SHIFT=%d: %d values", in_w, shift, len(xs))

    mismatches = 0
    for x in xs:
        dut.x.value = x
        await Timer(1, unit="ns")
        y = dut.y.value.to_signed()
        expected = round_shift(x, shift)  # Python ints: exact at any width
        if y != expected:
            mismatches += 1
            if mismatches <= MAX_MISMATCH_LOGS:
                dut._log.error("round_shift(%d, %d) = %d expected %d", x, shift, y, expected)
    assert mismatches == 0, f"{mismatches} of {len(xs)} mismatches against cube4.fixed.round_shift"


PARAM_SETS = [
    {"IN_W": 8, "SHIFT": 0},
    {"IN_W": 8, "SHIFT": 1},
    {"IN_W": 8, "SHIFT": 7},
    {"IN_W": 17, "SHIFT": 8},  # as inside cube4_lerp with DATA_W = WEIGHT_W = 8
    {"IN_W": 64, "SHIFT": 20},  # widest
]


@pytest.mark.parametrize("params", sweep(PARAM_SETS, quick=(3, 4), ids=param_id))
def test_cube4_round_shift(params):
    run_rtl(__file__, params)

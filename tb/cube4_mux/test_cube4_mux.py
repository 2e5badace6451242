"""Testbench for rtl/cube4_mux.v: word sel of N packed words.

Combinational: drive words and sel, wait 1 ns, read word. Every select 0 .. N - 1 with
random words (the same select with other words too, so a stuck or crossed bit fails),
and for N not a power of two the selects above N - 1, which give zero. The parameter
sets cover N = 1, a power of two, an odd N and widths that are not powers of two (the
widths whose index arithmetic would have become a multiplier).
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.triggers import Timer

from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import param_id, run_rtl

ROUNDS = 20


@cocotb.test()
async def mux_words(dut):
    n, w = int(dut.N.value), int(dut.W.value)
    sel_w = max(1, (n - 1).bit_length())
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    checked = 0
    for _ in range(ROUNDS):
        words = [int(v) for v in rng.integers(0, 1 << w, size=n, dtype=np.uint64)] if w < 64 else \
            [int.from_bytes(rng.bytes((w + 7) // 8), "little") & ((1 << w) - 1) for _ in range(n)]
        packed = sum(v << (k * w) for k, v in enumerate(words))
        dut.words.value = packed
        for sel in range(1 << sel_w):
            dut.sel.value = sel
            await Timer(1, unit="ns")
            want = words[sel] if sel < n else 0
            got = int(dut.word.value)
            assert got == want, f"N={n} W={w} sel={sel}: {got:#x}, want {want:#x}"
            checked += 1
    dut._log.info("cube4_mux N=%d W=%d: %d selects checked", n, w, checked)


PARAM_SETS = [
    {"N": 1, "W": 3},
    {"N": 8, "W": 9},     # the ray table's lane select at P = 8
    {"N": 5, "W": 18},
    {"N": 16, "W": 1},
    {"N": 3, "W": 70},
]


@pytest.mark.parametrize("params", sweep(PARAM_SETS, quick=(1, 2), ids=param_id))
def test_cube4_mux(params):
    run_rtl(__file__, params)

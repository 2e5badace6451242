"""Testbench for rtl/cube4_delay_line.v: a run-time length delay line counted in steps.

The property it must keep (its header): during step b (b counted from the last
clear, which is step 0), dout equals din of step b - L, for b >= L; between
steps dout holds. For L > RA (RA = 3 with one RAM bank, 4 with several: DEPTH
above 2048 words) the RA outputs after a clear are zero words. L = 1 .. RA + 1 take the
bypass (the RAM's write lands a cycle after its step), longer ones the RAM. clear, last and
din are driven with random values on cycles without a step: the line must
ignore them, as GRA's delay lines see them when the unit stalls.

Each cocotb test runs several "frames": a clear, then a random number of steps
with a random L (the lengths the bypass covers, L = RA + 2, the first through the
RAM, the largest, and random ones), steps at random (probability 0.7 or 1.0). One test resets in the
middle of a frame and then runs a clean frame. The testbench reads DATA_W and
DEPTH from the DUT.
"""

from __future__ import annotations

import math

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge

from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import param_id, run_rtl, start_clock, top_params

MAX_MISMATCH_LOGS = 10


class TB:
    """Drives cube4_delay_line and checks dout against the din history."""

    def __init__(self, dut) -> None:
        self.dut = dut
        self.log = dut._log
        self.data_w, self.depth = top_params(dut, "DATA_W", "DEPTH")
        aw = max(1, math.ceil(math.log2(self.depth))) if self.depth > 1 else 1
        self.ra = 4 if aw > 11 else 3
        self.rng = np.random.default_rng(cocotb.RANDOM_SEED)
        self.mismatches = 0
        self.checked = 0
        start_clock(dut)
        self.log.info("cube4_delay_line DATA_W=%d DEPTH=%d (reads %d steps ahead)",
                      self.data_w, self.depth, self.ra)

    def _rand_word(self) -> int:
        return int(self.rng.integers(0, 1 << self.data_w))

    def _drive_idle(self, length: int) -> None:
        """A cycle without a step: every other input random."""
        self.dut.step.value = 0
        self.dut.clear.value = int(self.rng.integers(0, 2))
        self.dut.last.value = int(self.rng.integers(0, 2))
        self.dut.din.value = self._rand_word()
        self.dut.len.value = length

    async def reset(self) -> None:
        self.dut.rst.value = 1
        self._drive_idle(1)
        for _ in range(2):
            await FallingEdge(self.dut.clk)
        self.dut.rst.value = 0

    def _error(self, msg: str, *args) -> None:
        self.mismatches += 1
        if self.mismatches <= MAX_MISMATCH_LOGS:
            self.log.error(msg, *args)

    async def frame(self, length: int, steps: int, step_prob: float, stop_after: int | None = None) -> None:
        """One frame: L = length, `steps` steps from a clear. With stop_after,
        return after that many cycles (the caller then resets)."""
        din_hist: list[int] = []
        b = 0          # index of the next step
        prev_dout: int | None = None
        prev_step = 0
        cycles = 0
        # len is stable from before the clear (the caller's registered length)
        self._drive_idle(length)
        for _ in range(2):
            await FallingEdge(self.dut.clk)
        while b < steps:
            dout = self.dut.dout.value.to_unsigned()
            if prev_step == 0 and prev_dout is not None and dout != prev_dout:
                self._error("L=%d: dout changed without a step before step %d", length, b)
            prev_dout = dout
            if stop_after is not None and cycles >= stop_after:
                return
            cycles += 1
            if self.rng.random() < step_prob:
                # this cycle is step b: check dout, drive the step
                if b >= length:
                    self.checked += 1
                    if dout != din_hist[b - length]:
                        self._error("L=%d step %d: dout %#x expected din(%d) = %#x",
                                    length, b, dout, b - length, din_hist[b - length])
                elif length > self.ra and 1 <= b <= self.ra:
                    self.checked += 1
                    if dout != 0:
                        self._error("L=%d step %d after a clear: dout %#x expected a zero word",
                                    length, b, dout)
                word = self._rand_word()
                din_hist.append(word)
                self.dut.step.value = 1
                self.dut.clear.value = int(b == 0)
                self.dut.last.value = int(b % length == length - 1)
                self.dut.din.value = word
                self.dut.len.value = length
                b += 1
                prev_step = 1
            else:
                self._drive_idle(length)
                prev_step = 0
            await FallingEdge(self.dut.clk)
        self._drive_idle(length)
        await FallingEdge(self.dut.clk)

    def lengths(self) -> list[int]:
        """Bypassed lengths, the first through the RAM, the largest, random ones."""
        fixed = [1, 2, 3, 4, 5, self.ra + 1, self.ra + 2, self.ra + 3, self.depth]
        rand = [int(v) for v in self.rng.integers(1, self.depth + 1, size=4)]
        return [n for n in dict.fromkeys(fixed + rand) if 1 <= n <= self.depth]

    def steps_for(self, length: int) -> int:
        return min(3 * length + 20, length + 3000)

    def finish(self) -> None:
        self.log.info("%d outputs checked", self.checked)
        assert self.mismatches == 0, f"{self.mismatches} mismatches (see log)"
        assert self.checked > 0


async def run_every_length(dut, step_prob: float) -> None:
    """Every length in turn, frame after frame without a reset between them."""
    tb = TB(dut)
    await tb.reset()
    for length in tb.lengths():
        await tb.frame(length, tb.steps_for(length), step_prob=step_prob)
    tb.finish()


@cocotb.test()
async def delay_line_streaming(dut):
    """A step on every cycle."""
    await run_every_length(dut, step_prob=1.0)


@cocotb.test()
async def delay_line_random_steps(dut):
    """Steps at random (the unit stalls), random inputs on the cycles between them."""
    await run_every_length(dut, step_prob=0.7)


@cocotb.test()
async def delay_line_reset_mid_frame(dut):
    """A reset in the middle of a frame, then a clean frame of another length."""
    tb = TB(dut)
    await tb.reset()
    big = max(tb.ra + 2, tb.depth // 2)
    await tb.frame(big, tb.steps_for(big), step_prob=0.8, stop_after=big + 7)
    await tb.reset()
    await tb.frame(tb.ra + 3, tb.steps_for(tb.ra + 3), step_prob=0.8)
    await tb.frame(big, tb.steps_for(big), step_prob=1.0)
    tb.finish()


# ----------------------------------------------------------------------------
# pytest: build and run for several parameter sets
# ----------------------------------------------------------------------------

PARAM_SETS = [
    {"DATA_W": 12, "DEPTH": 16},     # one bank, RA = 3
    {"DATA_W": 1, "DEPTH": 5},       # L = 4 the last bypassed, L = 5 the RAM's first
    {"DATA_W": 3, "DEPTH": 8},       # L = 5, 6, 7, 8 through the RAM
    {"DATA_W": 20, "DEPTH": 2048},   # one full bank
    {"DATA_W": 12, "DEPTH": 5000},   # three banks used of four, RA = 4
]


@pytest.mark.parametrize("params", sweep(PARAM_SETS, quick=(1, 4), ids=param_id))
def test_cube4_delay_line(params):
    run_rtl(__file__, params)

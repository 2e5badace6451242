"""Testbench for rtl/cube4_skid_oreg.v: a two-entry skid buffer whose out_data is a
register (the head), with the stream behaviour of cube4_skid.

Checked against a Python deque, every cycle:

* items come out in order, none lost, none duplicated, data held while out_ready is low;
* latency: an item is on out_valid one edge after the edge that took it;
* capacity: with out_ready low the buffer takes exactly two items, then in_ready is low;
* in_ready is a register: within a cycle it does not follow out_ready;
* occupancy as cube4_skid's, so that the two driven alike agree (cube4_top's COM skids):
  after every edge in_ready is "fewer than two items held" and out_valid "one held at
  least" ("in_ready 1 with 2 items held": tried with in_ready loaded from the old full
  flag, a cycle late);
* full rate: with in_valid and out_ready high, one item in and one out on every cycle;
* random valid and ready (seeded from COCOTB_RANDOM_SEED), then a drain with nothing extra
  ("item N: RTL ..., model ...": tried with the head loading the input even when the spare
  holds an item).

DATA_W 1, 40 and 256 (the range's ends and a header's width); 40 in make test.
"""

from __future__ import annotations

import cocotb
import pytest
from cocotb.triggers import Timer

from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import QueueTB, param_id, run_rtl


class TB(QueueTB):
    def __init__(self, dut) -> None:
        super().__init__(dut, empty_only_when_low=True)

    async def drive(self, valid: bool, ready: bool, data: int) -> None:
        """The cycle's inputs, with the other out_ready first: in_ready must not follow it."""
        d = self.dut
        held = len(self.q.model)
        assert int(d.in_ready.value) == (held < 2), f"in_ready {int(d.in_ready.value)} with {held} items held"
        assert int(d.out_valid.value) == (held > 0), f"out_valid {int(d.out_valid.value)} with {held} items held"
        d.in_valid.value, d.in_data.value, d.out_ready.value = int(valid), data, int(not ready)
        await Timer(1, "ns")
        ready_other = int(d.in_ready.value)
        d.out_ready.value = int(ready)
        await Timer(1, "ns")
        assert int(d.in_ready.value) == ready_other, "in_ready follows out_ready within a cycle"


@cocotb.test()
async def test_skid_oreg(dut):
    tb = TB(dut)
    await tb.reset()
    await tb.skid_checks()
    dut._log.info("cube4_skid_oreg DATA_W=%d: %d items in order", tb.data_w, tb.q.got)


BUILDS = [dict(DATA_W=40), dict(DATA_W=1), dict(DATA_W=256)]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(0,), ids=param_id))
def test_cube4_skid_oreg(params):
    run_rtl(__file__, params)

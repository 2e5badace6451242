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

from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import QueueTB, param_id, run_rtl


class TB(QueueTB):
    def __init__(self, dut) -> None:
        super().__init__(dut, empty_only_when_low=True, ready_is_register=True)

    async def drive(self, valid: bool, ready: bool, data: int) -> None:
        """The cycle's inputs, after in_ready and out_valid are checked against the count held."""
        d, held = self.dut, len(self.q.model)
        assert int(d.in_ready.value) == (held < 2), f"in_ready {int(d.in_ready.value)} with {held} items held"
        assert int(d.out_valid.value) == (held > 0), f"out_valid {int(d.out_valid.value)} with {held} items held"
        await super().drive(valid, ready, data)


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

"""Testbench for rtl/cube4_skid_peek.v (and so cube4_skid, the same buffer without the
ports nx_valid and nx_data): a two-entry skid buffer whose in_ready is a register.

Checked against a Python deque, every cycle:

* items come out in order, none lost, none duplicated, data held while out_ready is low;
* latency: an item is on out_valid one edge after the edge that took it;
* capacity: with out_ready low the buffer takes exactly two items, then in_ready is low;
* in_ready is a register: within a cycle it does not follow out_ready;
* full rate: with in_valid and out_ready high, one item in and one out on every cycle;
* random valid and ready (seeded from COCOTB_RANDOM_SEED), then a drain with nothing extra;
* the entry behind the head: nx_valid exactly when two items are held, nx_data the second
  (the one out_data offers after the head), after every edge;
* in_ready_nx before each edge is in_ready after it (QueueTB; "in_ready = ... after an
  edge with in_ready_nx = ...": tried with cube4_skid_peek's in_ready_nx = !full_q);
* in_ready's copies (in_ready_cp, READY_N of them) all equal in_ready after every edge
  ("in_ready_cp ... with in_ready ...": tried by loading copy 1 with full_d instead), and
  out_valid's (out_valid_cp, VALID_N) out_valid.

The data registers and the read pointer's copies are kept per group of 64 bits: DATA_W =
130 has three groups, each of whose bits the words below set (the sent count in the top
bits); a group whose pointer copy missed a pop returns the other entry's bits there
("item N: RTL ..., model ...": tried by tying copy 2's select to copy 0's inverse).
DATA_W 130 with three ready copies and two valid copies in make test; 1 and 64 in make
regress.
"""

from __future__ import annotations

import cocotb
import pytest

from cube4_sim.sweeps import sweep
from cube4_sim.runner import run_test
from cube4_sim.sources import rtl_sources
from cube4_sim.unit_bench import QueueTB, param_id


class TB(QueueTB):
    def __init__(self, dut) -> None:
        super().__init__(dut, empty_only_when_low=True, ready_is_register=True)
        self.peeks = 0      # cycles with a second item held (nx_data checked)

    async def cycle(self, valid: bool, ready: bool) -> tuple[bool, bool]:
        flow = await super().cycle(valid, ready)
        d, held = self.dut, list(self.q.model)
        assert int(d.nx_valid.value) == (len(held) >= 2), \
            f"nx_valid = {int(d.nx_valid.value)} with {len(held)} items held"
        if len(held) >= 2:
            assert int(d.nx_data.value) == held[1], \
                f"nx_data = {int(d.nx_data.value):#x}, the second item is {held[1]:#x}"
        self.peeks += len(held) >= 2
        n, cp = len(d.in_ready_cp), int(d.in_ready_cp.value)
        assert cp == int(d.in_ready.value) * ((1 << n) - 1), \
            f"in_ready_cp = {cp:#b} with in_ready {int(d.in_ready.value)} ({n} copies)"
        n, cp = len(d.out_valid_cp), int(d.out_valid_cp.value)
        assert cp == int(d.out_valid.value) * ((1 << n) - 1), \
            f"out_valid_cp = {cp:#b} with out_valid {int(d.out_valid.value)} ({n} copies)"
        return flow


@cocotb.test()
async def test_skid(dut):
    tb = TB(dut)
    await tb.reset()
    await tb.skid_checks()
    assert tb.peeks > 300, f"only {tb.peeks} cycles with a second item"
    dut._log.info("cube4_skid_peek DATA_W=%d: %d items in order, the second item checked in %d cycles",
                  tb.data_w, tb.q.got, tb.peeks)


BUILDS = [dict(DATA_W=130, READY_N=3, VALID_N=2), dict(DATA_W=1), dict(DATA_W=64)]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(0,), ids=param_id))
def test_cube4_skid(params):
    run_test(top="cube4_skid_peek", sources=rtl_sources(), params=params, test_module=__file__)

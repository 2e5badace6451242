"""Testbench for rtl/cube4_skid_fifo.v: a FIFO with a skid buffer at each end.

Checked against a Python deque, every cycle:

* items come out in order, none lost, none duplicated, data held while out_ready is low;
* latency: into an empty queue an item is on out_valid Q + 2 edges after the edge that
  took it (Q = 0 for the distributed-RAM queue, L + 1 for the block-RAM one, L = 1 + OUT_REG);
* capacity: with out_ready low for long, it takes exactly DEPTH + 4 items (block RAM:
  DEPTH + L + 6), then in_ready stays low; nothing is lost when it drains;
* in_ready is a register: within a cycle it does not follow out_ready;
* full rate: with in_valid and out_ready high, an item enters and one leaves on every
  cycle (from empty after the first Q + 3 cycles; from full after the pops' room has
  passed the three registered readies back to the input: 3 cycles, 4 with block RAM);
* random valid and ready (seeded from COCOTB_RANDOM_SEED), then a drain with nothing extra;
* in_ready_nx before each edge is in_ready after it (QueueTB; "in_ready = ... after an
  edge with in_ready_nx = ...": tried with cube4_skid_peek's in_ready_nx = !full_q);
* in_ready's copies (in_ready_cp, READY_N) all equal in_ready after every edge, and
  out_valid's (out_valid_cp, VALID_N) out_valid.

With either skid buffer replaced by wires the latency check fails ("an item into an empty
queue is out after 1 edges, Q + 2 = 2"; tried for each). Both queue kinds in make test,
the smallest of each in make regress.
"""

from __future__ import annotations

import cocotb
import pytest
from cocotb.triggers import Timer

from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import QueueTB, param_id, run_rtl, top_params


class TB(QueueTB):
    def __init__(self, dut) -> None:
        super().__init__(dut)
        self.depth, ram, out_reg = top_params(dut, "DEPTH", "RAM", "OUT_REG")
        lat = 1 + out_reg
        self.q_lat = lat + 1 if ram else 0                    # the queue's own edges
        self.cap = self.depth + 4 + (lat + 2 if ram else 0)
        # cycles from full until the first item enters at full rate: the pops' room passes the
        # back skid's registered ready, the queue's (block RAM: the read that makes room is
        # decided a cycle before its pop) and the front skid's
        self.from_full = 4 if ram else 3

    async def cycle(self, valid: bool, ready: bool) -> tuple[bool, bool]:
        flow = await super().cycle(valid, ready)
        d = self.dut
        n, cp = len(d.in_ready_cp), int(d.in_ready_cp.value)
        assert cp == int(d.in_ready.value) * ((1 << n) - 1), \
            f"in_ready_cp = {cp:#b} with in_ready {int(d.in_ready.value)} ({n} copies)"
        n, cp = len(d.out_valid_cp), int(d.out_valid_cp.value)
        assert cp == int(d.out_valid.value) * ((1 << n) - 1), \
            f"out_valid_cp = {cp:#b} with out_valid {int(d.out_valid.value)} ({n} copies)"
        return flow


@cocotb.test()
async def test_fifo(dut):
    tb = TB(dut)
    await tb.reset()
    edges = await tb.edges_to_out()
    assert edges == tb.q_lat + 2, f"an item into an empty queue is out after {edges} edges, Q + 2 = {tb.q_lat + 2}"
    await tb.drain()
    held = await tb.fill(tb.cap + 10)
    assert held == tb.cap, f"the queue took {held} items, expected {tb.cap}"
    # in_ready is a register: out_ready does not reach it within the cycle
    before = int(dut.in_ready.value)
    dut.out_ready.value = 1
    await Timer(1, "ns")
    assert int(dut.in_ready.value) == before == 0, "in_ready followed out_ready within the cycle"
    # full rate from full: one out every cycle, and one in every cycle once the room has come back
    flow = [await tb.cycle(True, True) for _ in range(3 * tb.cap)]
    assert all(q for _, q in flow), "not one item out per cycle from full"
    first_in = next(n for n, (p, _) in enumerate(flow) if p)
    assert all(p for p, _ in flow[first_in:]), f"not one item in per cycle from full after cycle {first_in}"
    assert first_in == tb.from_full, f"the first item in after {first_in} cycles from full, expected {tb.from_full}"
    await tb.drain()
    # full rate from empty (after the first Q + 3 cycles: the first item's Q + 2 edges)
    flow = [await tb.cycle(True, True) for _ in range(3 * tb.cap)]
    assert all(p for p, _ in flow) and all(q for _, q in flow[tb.q_lat + 3:]), "not one item a cycle from empty"
    await tb.random_traffic(20 * tb.depth + 500, tb.cap + 40)
    dut._log.info("cube4_skid_fifo DATA_W=%d DEPTH=%d: %d items in order, first in from full at %d",
                  tb.data_w, tb.depth, tb.q.got, first_in)


BUILDS = [dict(DATA_W=25, DEPTH=64, RAM=0), dict(DATA_W=34, DEPTH=64, RAM=1, OUT_REG=1, READY_N=5, VALID_N=2),
          dict(DATA_W=1, DEPTH=2, RAM=0), dict(DATA_W=70, DEPTH=4, RAM=1)]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(0, 1), ids=param_id))
def test_cube4_skid_fifo(params):
    run_rtl(__file__, params)

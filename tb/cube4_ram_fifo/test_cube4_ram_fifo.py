"""Testbench for rtl/cube4_ram_fifo.v: a deep FIFO in block RAM with a register queue of L + 2 entries.

Checked against a Python deque, every cycle:

* items come out in order, none lost, none duplicated, data held while out_ready is low
  (out_valid and out_data do not change until the item is taken);
(L = 1 + OUT_REG, the RAM's read latency)

* latency: into an empty queue an item is on out_valid L + 1 edges after its write;
* capacity: with out_ready low for long, the queue takes exactly DEPTH + L + 2 items, then
  in_ready stays low; nothing is lost when it drains;
* full rate: with in_valid and out_ready high, an item enters and one leaves on every
  cycle (from full: in after the first L + 1 cycles, in_ready being a register and the
  RAM's read that makes room decided before the first pop; from empty: out from cycle
  L + 3, the first item's write and its L + 1 edges);
* random valid and ready (seeded from COCOTB_RANDOM_SEED), then a drain with nothing extra.

With the register queue's refill condition one item looser (a read issued while three
items are held or in flight) every build fails ("item 1: RTL ..., model ...": a read
overwrites an item it has no register for); one item tighter (the two-entry queue's
condition, counted before the pop) every build fails its capacity ("the queue took 6
items, DEPTH + 3 = 7"), and that queue is one that out_ready's pop must refill in the
same cycle to keep the full rate. DATA_W 33, DEPTH 64 and the OUT_REG build of the CFB's
queue's shape in make test; the others in make regress.
"""

from __future__ import annotations

import cocotb
import pytest

from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import QueueTB, param_id, run_rtl, top_params


class TB(QueueTB):
    def __init__(self, dut) -> None:
        super().__init__(dut)
        self.depth, out_reg = top_params(dut, "DEPTH", "OUT_REG")
        self.lat = 1 + out_reg


@cocotb.test()
async def test_fifo(dut):
    tb = TB(dut)
    await tb.reset()
    edges = await tb.edges_to_out()
    assert edges == tb.lat + 1, f"an item into an empty queue is out {edges} edges after the edge that wrote it"
    await tb.drain()
    cap = tb.depth + tb.lat + 2
    held = await tb.fill(tb.depth + 10)
    assert held == cap, f"the queue took {held} items, DEPTH + L + 2 = {cap}"
    # full rate from full (in_ready is a register, and the read that makes room in the RAM
    # waits for room in the register queue: the first two cycles only take items out)
    for n in range(3 * tb.depth):
        pushed, popped = await tb.cycle(True, True)
        assert popped, f"no item out in cycle {n} at full rate"
        assert pushed or n <= tb.lat, f"no item in in cycle {n} at full rate"
    await tb.drain()
    # full rate from empty (after the first two edges)
    flow = [await tb.cycle(True, True) for _ in range(3 * tb.depth)]
    assert all(p for p, _ in flow) and all(q for _, q in flow[tb.lat + 2:]), "not one item a cycle from empty"
    await tb.random_traffic(20 * tb.depth + 500, tb.depth + 40)
    dut._log.info("cube4_ram_fifo DATA_W=%d DEPTH=%d: %d items in order", tb.data_w, tb.depth, tb.q.got)


BUILDS = [dict(DATA_W=8, DEPTH=4), dict(DATA_W=33, DEPTH=64), dict(DATA_W=1, DEPTH=1024), dict(DATA_W=100, DEPTH=8),
          dict(DATA_W=48, DEPTH=4096, OUT_REG=1), dict(DATA_W=5, DEPTH=4, OUT_REG=1)]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1, 4), ids=param_id))
def test_cube4_ram_fifo(params):
    run_rtl(__file__, params)

"""Testbench for rtl/cube4_com_ahead.v: COM's read-after-write rule by position as a
register decided a cycle ahead of the beat it is for.

The bench plays COM's input around it: a model of the input skid (two entries: the head
it offers, hd_valid and hd_hdr; whether it holds a second item, nx_valid; the header at its
input, in_hdr, which enters at the edge when the skid has room and the producer offers
one, seeded random; random bits when nothing enters, which must not matter), and R0 ..
S9, which move on every cycle (R0 the beat taken, S k S k-1; step, pos_sp, v_fly and
sp_fly of R0 .. S8). A beat offered is taken when its slot {j, pb} (the header's J and
PB fields) is in no beat of R0 .. S9 and, at random, COM's output FIFO has a credit. The
beats' slots come from four values (and then from all of them) so that a beat's slot is
often the one of the beat before it or a few before: the hazard of the skid's second item
against the head, of the item entering against the head, and against every stage. Checked
before every edge with a beat offered: hazard = the model's rule for the head. Nothing
extra: every beat made is taken, in order.

With the second item's compare against the head left out, or the entering one's, the bench
fails ("cycle N: hazard 0, the rule 1"; both tried).
"""

from __future__ import annotations

from collections import deque

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

from cube4_sim.beats import Geometry, clog2
from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import param_id, run_rtl, start_clock, top_params


class TB:
    def __init__(self, dut) -> None:
        self.dut = dut
        p, max_dim, sp_w = top_params(dut, "P", "MAX_DIM", "SP_W")
        self.geo = Geometry(p, max_dim, 0)
        self.rw, self.sp_w = max(1, clog2(max_dim)), sp_w
        self.fields = self.geo.hdr_fields
        self.rng = np.random.default_rng(cocotb.RANDOM_SEED)
        start_clock(dut)

    def header(self, j: int, pb: int) -> int:
        """A random header with the fields J and PB set."""
        h = int(self.rng.integers(0, 1 << min(62, self.geo.hdr_w)))
        h |= int(self.rng.integers(0, 2)) << (self.geo.hdr_w - 1)
        for name, v in (("j", j), ("pb", pb)):
            lo, w = self.fields[name]
            h = (h & ~(((1 << w) - 1) << lo)) | (v << lo)
        return h

    def slot(self, h: int) -> int:
        (jl, _), (pl, _) = self.fields["j"], self.fields["pb"]
        return ((((h >> jl) & ((1 << self.rw) - 1)) << self.geo.pb_w) | ((h >> pl) & ((1 << self.geo.pb_w) - 1)))

    def new_beat(self, few: bool) -> int:
        if few:                       # four slots: j, pb in {0, 1}
            return self.header(int(self.rng.integers(0, 2)), int(self.rng.integers(0, 2)))
        return self.header(int(self.rng.integers(0, 1 << self.rw)), int(self.rng.integers(0, 1 << self.geo.pb_w)))

    async def run(self, cycles: int, few: bool, p_in: float, p_credit: float) -> tuple[int, int]:
        d, rng = self.dut, self.rng
        skid: deque[int] = deque()
        stages: list[int | None] = [None] * 10      # R0, S1 .. S9: the slots held
        made, taken, hazards = [], [], 0
        for c in range(cycles):
            head = skid[0] if skid else None
            hz = head is not None and self.slot(head) in [s for s in stages if s is not None]
            take = head is not None and not hz and rng.random() < p_credit
            enter = len(skid) < 2 and rng.random() < p_in
            incoming = self.new_beat(few) if enter else int(rng.integers(0, 1 << min(62, self.geo.hdr_w)))
            d.hd_valid.value = int(head is not None)
            d.hd_hdr.value = head if head is not None else self.new_beat(few)
            d.nx_valid.value = int(len(skid) == 2)
            d.in_hdr.value = incoming
            d.take.value = int(take)
            d.step.value = int(stages[0] is not None)
            d.pos_sp.value = stages[0] if stages[0] is not None else int(rng.integers(0, 1 << self.sp_w))
            d.v_fly.value = sum(1 << (k - 1) for k in range(1, 9) if stages[k] is not None)
            d.sp_fly.value = sum((stages[k] if stages[k] is not None else int(rng.integers(0, 1 << self.sp_w)))
                                 << ((k - 1) * self.sp_w) for k in range(1, 9))
            await ReadOnly()
            if head is not None:
                got = int(d.hazard.value)
                assert got == int(hz), f"cycle {c}: hazard {got}, the rule {int(hz)}"
                hazards += int(hz)
            await FallingEdge(d.clk)
            stages = [self.slot(head) if take else None] + stages[:9]
            if take:
                taken.append(skid.popleft())
            if enter:
                skid.append(incoming)
                made.append(incoming)
        while skid or any(s is not None for s in stages):      # drain: nothing new
            head = skid[0] if skid else None
            hz = head is not None and self.slot(head) in [s for s in stages if s is not None]
            take = head is not None and not hz
            d.hd_valid.value, d.nx_valid.value, d.take.value = int(head is not None), int(len(skid) == 2), int(take)
            if head is not None:
                d.hd_hdr.value = head
            d.step.value = int(stages[0] is not None)
            d.pos_sp.value = stages[0] or 0
            d.v_fly.value = sum(1 << (k - 1) for k in range(1, 9) if stages[k] is not None)
            d.sp_fly.value = sum((stages[k] or 0) << ((k - 1) * self.sp_w) for k in range(1, 9))
            await ReadOnly()
            if head is not None:
                assert int(d.hazard.value) == int(hz), f"drain: hazard {int(d.hazard.value)}, the rule {int(hz)}"
            await FallingEdge(d.clk)
            stages = [self.slot(head) if take else None] + stages[:9]
            if take:
                taken.append(skid.popleft())
        assert taken == made, f"{len(made)} beats made, {len(taken)} taken (or out of order)"
        return len(made), hazards


@cocotb.test()
async def test_ahead(dut):
    tb = TB(dut)
    d = dut
    d.rst.value = 1
    d.hd_valid.value = d.nx_valid.value = d.take.value = d.step.value = d.v_fly.value = 0
    await FallingEdge(d.clk)
    await FallingEdge(d.clk)
    d.rst.value = 0
    total = 0
    for few, p_in, p_credit in ((True, 0.9, 1.0), (True, 0.5, 0.7), (False, 0.95, 1.0), (True, 1.0, 0.9)):
        beats, hazards = await tb.run(1500, few, p_in, p_credit)
        dut._log.info("slots %s, in %.2f, credit %.2f: %d beats, %d cycles with a hazard",
                      "few" if few else "all", p_in, p_credit, beats, hazards)
        assert beats > 120 and (hazards > 100 or not few)
        total += beats
    assert total > 1000


def _params(p: int, max_dim: int) -> dict:
    return {"P": p, "MAX_DIM": max_dim, "SP_W": max(1, clog2(max_dim)) + Geometry(p, max_dim, 0).pb_w}


BUILDS = [dict(P=8, MAX_DIM=32), dict(P=1, MAX_DIM=16), dict(P=5, MAX_DIM=128)]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(0,), ids=param_id))
def test_cube4_com_ahead(params):
    run_rtl(__file__, _params(params["P"], params["MAX_DIM"]))

"""Unit testbench of rtl/cube4_gra_pos_buf.v: one of GRA's position buffers, read, bypass
and (OUT_STAGE = 1) second bypass, against a model of its memory.

A seeded random caller reads (ld) and writes (we) a small memory, so that reads meet the
writes of their own edge often. OUT_STAGE = 0: after an edge with ld, rd_word must be the
word at the read's address with that edge's write, and hold until the next ld. OUT_STAGE = 1
keeps the caller's order (cube4_gra_beats): a read moves on at a later edge (mv); between
them the caller writes only at that edge, where it may also load the next read; after mv's
edge rd_word must be the word with the writes of the read's edge and of mv's edge, and hold
until the next mv. Every word is written once before the first read (a RAM's contents are
data, not reset). The check counts what it compared.

The test can fail: with the second bypass's hit left out (s, sd loaded from by, bd alone)
the OUT_STAGE = 1 sets fail, and with the first bypass left out (by = 0) all three (tried,
not kept).
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from cube4_sim.unit_bench import param_id, run_rtl

CYCLES = 3000


@cocotb.test()
async def test_buffer(dut):
    dw, aw, stage = (int(getattr(dut, n).value) for n in ("DATA_W", "AW", "OUT_STAGE"))
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    words = 1 << aw
    mem = [0] * words
    word = lambda: int.from_bytes(rng.bytes((dw + 7) // 8), "little") & ((1 << dw) - 1)   # noqa: E731
    Clock(dut.clk, 10, unit="ns").start(start_high=False)
    for name in ("ld", "mv", "we", "rd_addr", "wr_addr", "wr_data"):
        getattr(dut, name).value = 0
    for a in range(words):                       # every word written before it is read
        await FallingEdge(dut.clk)
        mem[a] = word()
        dut.we.value, dut.wr_addr.value, dut.wr_data.value = 1, a, mem[a]
    await FallingEdge(dut.clk)
    dut.we.value = 0
    want = None                                  # the word rd_word must show
    pend = None                                  # (OUT_STAGE = 1) the read waiting for its mv
    checked = hits = 0
    for _ in range(CYCLES + 1):
        await FallingEdge(dut.clk)
        if want is not None:                     # the outputs after the last rising edge
            got = int(dut.rd_word.value)
            assert got == want, f"OUT_STAGE={stage}: rd_word {got:#x}, model {want:#x}"
            checked += 1
        mv = stage == 1 and pend is not None and rng.random() < 0.5
        free = stage == 0 or pend is None or mv  # a write or a new read may come at this edge
        ld = free and rng.random() < 0.6
        we = free and rng.random() < 0.5
        ra = int(rng.integers(0, words))
        wa = ra if we and ld and rng.random() < 0.3 else int(rng.integers(0, words))
        if we and mv and rng.random() < 0.4:
            wa = pend                            # a write at mv's edge to the read's word
        wd = word()
        dut.ld.value, dut.mv.value, dut.we.value = int(ld), int(mv), int(we)
        dut.rd_addr.value, dut.wr_addr.value, dut.wr_data.value = ra, wa, wd
        if we:
            hits += int((ld and wa == ra) or (mv and wa == pend))
            mem[wa] = wd                         # this edge's write, which the reads below see
        if stage == 0:
            if ld:
                want = mem[ra]
        else:
            if mv:
                want = mem[pend]
                pend = None
            if ld:
                pend = ra
    assert checked > CYCLES // 4, f"only {checked} words compared"
    assert hits > CYCLES // 50, f"only {hits} writes met a read: the bypasses would not be seen"
    dut._log.info("DATA_W=%d AW=%d OUT_STAGE=%d: %d words compared, %d bypassed writes", dw, aw, stage,
                  checked, hits)


BUILDS = [{"DATA_W": 12, "AW": 2, "OUT_STAGE": 0}, {"DATA_W": 12, "AW": 2, "OUT_STAGE": 1},
          {"DATA_W": 70, "AW": 3, "OUT_STAGE": 1}]


@pytest.mark.parametrize("params", BUILDS, ids=param_id)
def test_cube4_gra_pos_buf(params):
    run_rtl(__file__, params)

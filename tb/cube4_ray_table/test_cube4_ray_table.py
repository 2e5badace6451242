"""Testbench for rtl/cube4_ray_table.v: one word per ray of the base plane in P skewed banks.

The model is the base plane itself, an array ``table[by, bx]`` (every row and column the
banks can hold). The host writes it whole through the tab_* port in the layout of
``cube4.memory.stop_table`` (the golden twin of the banks' layout). Then, on every cycle,
a random beat reads (row j, partial beam pb, the slice's steps stx <= SX and sty <= SY,
its lanes' positions t in a random order) and, on most cycles, another beat writes the
rays at random positions with random words: a beat the cycle before, the same beat, or
one that shares the row. Checked for every read, in every lane whose ray lies in the
table (a lane past it reads a word that wraps, which the header leaves to its caller):
its ray's word ``table[j - sty + SY, pb P + t + SX - stx]`` with every write issued up
to the cycle before the read, and none issued in the read's own cycle (a read sees a
write issued one cycle or more before it). Every view also rewrites the whole table
through the host port between beats, and the reads after it see the new table.

A read that meets a write of the same word at the banks' clock edge is the case block
RAM does not promise: the unit passes the new word around the banks. Without that pass
(tried, not kept), P = 5 with RATE = 2 fails with "read 6 beat 0 lane 0 (by 6, bx 18): RTL
203, model 171" and P = 1 with "read 23 beat 0 lane 0 (by 20, bx 8): RTL 111, model 132".

RATE = 2 reads the beats pb and pb + 1 and writes both; every lane of both is checked.
OUT_STAGE = 1 (the words a stage later, the decisions' tables) is read from the build and
checked at its latency. Seeded from COCOTB_RANDOM_SEED; P = 5 with RATE = 2 and P = 8 with
RATE = 2 and OUT_STAGE = 1 run in make test, the others (P = 1, 3, 8, 16; DATA_W 1 to 12;
RATE 1 and 2; OUT_STAGE 0 and 1) in make regress.
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge

from cube4.memory import stop_layout, stop_table
from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import param_id, run_rtl, start_clock, top_params

READ_LATENCY = 5        # edges from a read's fields to rd_data (one more with OUT_STAGE)
VIEWS = 4
BEATS = 400             # read beats per view


def clog2(n: int) -> int:
    return max(0, (n - 1).bit_length())


class TB:
    """The table as the base plane, and the beats that read and write it."""

    def __init__(self, dut) -> None:
        self.dut = dut
        self.log = dut._log
        self.p, self.max_dim, self.data_w, self.rate, out_stage = top_params(
            dut, "P", "MAX_DIM", "DATA_W", "RATE", "OUT_STAGE")
        self.latency = READ_LATENCY + out_stage
        self.rng = np.random.default_rng(cocotb.RANDOM_SEED)
        self.rows_w, self.cols_w = stop_layout(self.p, self.max_dim)
        self.rows, self.cols = 1 << self.rows_w, (1 << self.cols_w) * self.p
        self.nb = -(-self.max_dim // self.p)
        self.lane_w = max(1, clog2(self.p))
        self.table = np.zeros((self.rows, self.cols), dtype=np.int64)
        self.sx = self.sy = 0
        self.checked = 0
        start_clock(dut)

    def idle(self) -> None:
        d = self.dut
        for name in ("tab_we", "tab_addr", "tab_data", "rd_j", "rd_pb", "rd_tpos", "rd_stx", "rd_sty",
                     "wr_valid", "wr_j", "wr_pb", "wr_stx", "wr_sty", "wr_en", "wr_data"):
            getattr(d, name).value = 0

    async def host_write(self) -> None:
        """A new view: SX, SY, and the whole table through the host's port."""
        self.sx = int(self.rng.integers(0, self.max_dim))
        self.sy = int(self.rng.integers(0, self.max_dim))
        self.dut.sx.value, self.dut.sy.value = self.sx, self.sy
        self.table = self.rng.integers(0, 1 << self.data_w, size=(self.rows, self.cols), dtype=np.int64)
        words = stop_table(self.table, self.p, self.max_dim, self.data_w)
        for addr, word in enumerate(words):
            await FallingEdge(self.dut.clk)
            self.dut.tab_we.value, self.dut.tab_addr.value, self.dut.tab_data.value = 1, addr, word
        await FallingEdge(self.dut.clk)
        self.dut.tab_we.value = 0

    def beat(self) -> dict:
        """A random beat: row, partial beam, the slice's steps, the lanes' positions."""
        return {"j": int(self.rng.integers(0, self.max_dim)), "pb": int(self.rng.integers(0, self.nb)),
                "stx": int(self.rng.integers(0, self.sx + 1)), "sty": int(self.rng.integers(0, self.sy + 1)),
                "t": self.rng.permutation(self.p)}

    def ray(self, b: dict, t: int, r: int = 0) -> tuple[int, int]:
        """The ray at position t of beat r (partial beam pb + r) of beat ``b``."""
        return b["j"] - b["sty"] + self.sy, (b["pb"] + r) * self.p + t + self.sx - b["stx"]

    def drive_read(self, b: dict) -> None:
        d = self.dut
        d.rd_j.value, d.rd_pb.value, d.rd_stx.value, d.rd_sty.value = b["j"], b["pb"], b["stx"], b["sty"]
        d.rd_tpos.value = sum(int(t) << (q * self.lane_w) for q, t in enumerate(b["t"]))

    def drive_write(self, b: dict | None) -> list[tuple[int, int, int]]:
        """Drive a writing beat (None: no write); its writes as (by, bx, word)."""
        d = self.dut
        d.wr_valid.value = int(b is not None)
        if b is None:
            return []
        d.wr_j.value, d.wr_pb.value, d.wr_stx.value, d.wr_sty.value = b["j"], b["pb"], b["stx"], b["sty"]
        n = self.rate * self.p
        en = self.rng.random(n) < 0.6
        data = self.rng.integers(0, 1 << self.data_w, size=n)
        writes = []
        for k in range(n):
            by, bx = self.ray(b, k % self.p, k // self.p)
            en[k] &= bx < self.cols          # a position past the table writes nothing
            if en[k]:
                writes.append((by, bx, int(data[k])))
        d.wr_en.value = sum(1 << k for k in range(n) if en[k])
        d.wr_data.value = sum(int(data[k]) << (k * self.data_w) for k in range(n))
        return writes

    def check(self, n: int, b: dict, want: list) -> None:
        word = int(self.dut.rd_data.value)
        mask = (1 << self.data_w) - 1
        for k, w in enumerate(want):
            if w is None:
                continue
            r, q = divmod(k, self.p)
            got = (word >> (k * self.data_w)) & mask
            by, bx = self.ray(b, int(b["t"][q]), r)
            assert got == w, f"read {n} beat {r} lane {q} (by {by}, bx {bx}): RTL {got}, model {w}"
            self.checked += 1

    async def run_view(self) -> None:
        await self.host_write()
        pending: list = []                   # (read number, beat, expected words), oldest first
        prev_read = None
        for n in range(BEATS + self.latency):
            await FallingEdge(self.dut.clk)
            if pending and pending[0][0] == n - self.latency:
                _, b, want = pending.pop(0)
                self.check(n - self.latency, b, want)
            if n >= BEATS:
                self.dut.wr_valid.value = 0
                continue
            rb = self.beat()
            if prev_read is not None and self.rng.random() < 0.3:
                rb = dict(prev_read, t=self.rng.permutation(self.p))     # the same rays again
            self.drive_read(rb)
            # what the read returns: every write issued before this cycle
            want = [None if self.ray(rb, int(t), r)[1] >= self.cols else int(self.table[self.ray(rb, int(t), r)])
                    for r in range(self.rate) for t in rb["t"]]
            pending.append((n, rb, want))
            kind = self.rng.random()
            wb = (None if kind < 0.2 else dict(rb) if kind < 0.5
                  else dict(self.beat(), j=rb["j"], sty=rb["sty"]) if kind < 0.7 else self.beat())
            for by, bx, word in self.drive_write(wb):
                self.table[by, bx] = word
            prev_read = rb


@cocotb.test()
async def test_reads_and_writes(dut):
    """Host tables, beats reading their lanes' rays and beats writing theirs, against the model."""
    tb = TB(dut)
    tb.idle()
    for _ in range(VIEWS):
        await tb.run_view()
    tb.log.info("cube4_ray_table P=%d MAX_DIM=%d DATA_W=%d RATE=%d: %d lane reads checked", tb.p, tb.max_dim,
                tb.data_w, tb.rate, tb.checked)
    assert tb.checked > VIEWS * BEATS * tb.p * tb.rate // 4


BUILDS = [dict(P=1, MAX_DIM=16, DATA_W=8, RATE=1, OUT_STAGE=0), dict(P=5, MAX_DIM=16, DATA_W=8, RATE=2, OUT_STAGE=0),
          dict(P=8, MAX_DIM=32, DATA_W=9, RATE=1, OUT_STAGE=1), dict(P=3, MAX_DIM=8, DATA_W=1, RATE=2, OUT_STAGE=1),
          dict(P=16, MAX_DIM=32, DATA_W=12, RATE=1, OUT_STAGE=0), dict(P=8, MAX_DIM=32, DATA_W=9, RATE=2, OUT_STAGE=1),
          dict(P=1, MAX_DIM=16, DATA_W=8, RATE=2, OUT_STAGE=1)]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1, 5), ids=param_id))
def test_cube4_ray_table(params):
    run_rtl(__file__, params)

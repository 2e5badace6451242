"""Testbench for rtl/cube4_dual_read_ram.v and its ECP5 form rtl/ecp5/cube4_dual_read_ram.v.

Both forms run the same cocotb tests against a Python model of the RAM (the module's
header, 'Latency'), every parameter set at once (tb/cube4_dual_read_ram/cube4_dual_read_ram_sets.v
instantiates the RAM once per set, one build per form; each instance has a model of its own): two read ports of latency 1 + OUT_REG whose registers advance with
rd_en, a write seen one edge later, port 1 reading the word written at the same edge
returning the old word, and port 0 not reading in a cycle with wr_en (both its registers
keep their words). The ECP5 form puts each slice in a column of one to four DP16KD
(cube4_prim_ebr_column, rtl/ecp5/cube4_prim_ebr.v,
simulated with sim/hdl/ecp5/DP16KD.v) in true dual-port use, port A's address the
write's or port 0's; the parameter sets cover every block shape and the fall-back to
inferred RAM. A wrong address or data mapping of a block, a port 0 read that a write
does not suppress, or a port whose registers move without rd_en fails here.

Cycle discipline: the TB drives the inputs on each falling edge and reads both outputs
on the next falling edge. Write addresses are random over the whole depth; reads mostly
pick one of the last 16 addresses written (sometimes the one written at the same edge),
else a random one; writes come in bursts (as table loads do) and alone; the read enable
is 1, or random with probability 0.7 in the stall test. A word never written is not
checked. Seeded per test from COCOTB_RANDOM_SEED.
"""

from __future__ import annotations

import json
from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from cube4_sim.sweeps import pack_rows, set_lanes

CLK_PERIOD_NS = 10


class DualReadModel:
    """The RAM at the clock edges: mem, and per port the read and output registers."""

    def __init__(self, out_reg: int) -> None:
        self.mem: dict[int, int] = {}
        self.out_reg = out_reg
        self.rd_q: list[int | None] = [None, None]     # None: not read yet
        self.out_q: list[int | None] = [None, None]

    def edge(self, re: int, ra: tuple[int, int], we: int, wa: int, wd: int) -> None:
        for port in (0, 1):
            if re and (port == 1 or not we):        # port 0 does not read while writing
                if self.out_reg:
                    self.out_q[port] = self.rd_q[port]
                self.rd_q[port] = self.mem.get(ra[port])
        if we:
            self.mem[wa] = wd

    def rd_data(self, port: int) -> int | None:
        return self.out_q[port] if self.out_reg else self.rd_q[port]


class Lane:
    """One instance of the harness: its parameters, its model and its stimulus."""

    def __init__(self, params: dict, rng: np.random.Generator) -> None:
        self.data_w = params["DATA_W"]
        self.depth = params["DEPTH"]
        self.model = DualReadModel(params.get("OUT_REG", 1))
        self.rng = rng
        self.written: list[int] = []
        self.burst = 0                  # writes left in the current burst
        self.checks = self.held = 0

    def word(self) -> int:
        return int(self.rng.integers(0, 1 << min(self.data_w, 62))) | (
            int(self.rng.integers(0, 2)) << (self.data_w - 1))

    def read_addr(self) -> int:
        rng, written = self.rng, self.written
        if written and rng.random() < 0.8:
            return written[int(rng.integers(max(0, len(written) - 16), len(written)))]
        return int(rng.integers(0, self.depth))

    def inputs(self, re_prob: float) -> tuple[int, tuple[int, int], int, int, int]:
        """This edge's (re, (ra0, ra1), we, wa, wd)."""
        rng = self.rng
        if self.burst == 0 and rng.random() < 0.05:
            self.burst = int(rng.integers(1, 24))
        we = int(self.burst > 0 or rng.random() < 0.2)
        self.burst = max(0, self.burst - 1)
        wa = int(rng.integers(0, self.depth))
        if self.written and rng.random() < 0.2:
            wa = self.written[-1]
        ra = (self.read_addr(), self.read_addr())
        re = int(rng.random() < re_prob)
        wd = self.word()
        if we:
            self.written.append(wa)
        return re, ra, we, wa, wd

    def check(self, c: int, values: tuple, got: tuple[int, int]) -> None:
        """Applies this edge to the model and checks both ports against it."""
        m = self.model
        re, ra, we = values[0], values[1], values[2]
        before = m.rd_q[0]
        m.edge(*values)
        if we and re and before is not None and m.mem.get(ra[0]) != before:
            self.held += 1              # a port-0 read a write suppressed would differ
        for port in (0, 1):
            want = m.rd_data(port)
            if want is not None:
                assert got[port] == want, (f"cycle {c}: rd{port}_data = {got[port]:#x}, expected {want:#x} "
                                           f"(DEPTH={self.depth}, DATA_W={self.data_w})")
                self.checks += 1


class TB:
    """Drives every instance of cube4_dual_read_ram_sets and checks both read ports of each
    against its model after every edge."""

    def __init__(self, dut) -> None:
        self.dut = dut
        self.dw_max, self.aw_max, self.lanes = set_lanes(dut, "CUBE4_DUAL_READ_RAM_SETS", Lane)
        Clock(dut.clk, CLK_PERIOD_NS, unit="ns").start(start_high=False)

    async def run(self, cycles: int, re_prob: float) -> tuple[int, int]:
        """The fewest checks any instance made and the fewest checked port-0 words read
        across a write."""
        dut, dw, aw = self.dut, self.dw_max, self.aw_max
        mask = (1 << dw) - 1
        await FallingEdge(dut.clk)
        for c in range(cycles):
            ins = [lane.inputs(re_prob) for lane in self.lanes]
            re, ra0, ra1, we, wa, wd = pack_rows([(r, a0, a1, w, a, d) for r, (a0, a1), w, a, d in ins],
                                                 (1, aw, aw, 1, aw, dw))
            dut.rd_en.value, dut.rd0_addr.value, dut.rd1_addr.value = re, ra0, ra1
            dut.wr_en.value, dut.wr_addr.value, dut.wr_data.value = we, wa, wd
            await FallingEdge(dut.clk)
            rd0, rd1 = int(dut.rd0_data.value), int(dut.rd1_data.value)
            for k, (lane, values) in enumerate(zip(self.lanes, ins)):
                lane.check(c, values, ((rd0 >> (k * dw)) & mask, (rd1 >> (k * dw)) & mask))
        return min(lane.checks for lane in self.lanes), min(lane.held for lane in self.lanes)


@cocotb.test()
async def dual_read_streaming(dut):
    tb = TB(dut)
    checks, held = await tb.run(2000, re_prob=1.0)
    assert checks > 2500 and held > 20, (checks, held)


@cocotb.test()
async def dual_read_random_stalls(dut):
    tb = TB(dut)
    checks, held = await tb.run(2000, re_prob=0.7)
    assert checks > 2000 and held > 10, (checks, held)


# ---------------------------------------------------------------- pytest half
from cube4_sim import run_test  # noqa: E402
from cube4_sim.sweeps import packed_sets  # noqa: E402
from cube4_sim.sources import RTL_FORMS, form_build_args, form_sources  # noqa: E402

# the shapes of the ECP5 form (one block 1024 x 18 .. 16384 x 1 per slice; inferred
# below 128 and beyond 16384 words or without the output register)
PARAM_SETS = [
    {"DATA_W": 36, "DEPTH": 256},                   # 1024 x 18, two slices (SHA's LUT)
    {"DATA_W": 10, "DEPTH": 2048},                  # 2048 x 9
    {"DATA_W": 5, "DEPTH": 4096},                   # 4096 x 4
    {"DATA_W": 20, "DEPTH": 6145},                  # 2 x (4 deep 2048 x 9) + 8192 x 2 (SHA's map)
    {"DATA_W": 3, "DEPTH": 16384},                  # 16384 x 1
    {"DATA_W": 9, "DEPTH": 16},                     # shallow: inferred
    {"DATA_W": 7, "DEPTH": 20000},                  # deeper: inferred
    {"DATA_W": 12, "DEPTH": 300, "OUT_REG": 0},     # no output register: inferred
    {"DATA_W": 9, "DEPTH": 4096},                   # 2 deep 2048 x 9
]


HARNESS = Path(__file__).resolve().parent / "cube4_dual_read_ram_sets.v"


@pytest.mark.parametrize("form", RTL_FORMS)
def test_cube4_dual_read_ram(form):
    """Every parameter set at once: one build of the harness per form."""
    run_test(top="cube4_dual_read_ram_sets", sources=[*form_sources(form), HARNESS],
             params=packed_sets(PARAM_SETS, ("DATA_W", "DEPTH", "OUT_REG"), defaults={"OUT_REG": 1}),
             test_module=__file__, build_args=form_build_args(form),
             extra_env={"CUBE4_DUAL_READ_RAM_SETS": json.dumps(PARAM_SETS)})

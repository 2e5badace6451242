"""Testbench for rtl/cube4_sdp_ram.v and its ECP5 form rtl/ecp5/cube4_sdp_ram.v.

Both forms run the same cocotb tests against a Python model of the RAM: read latency
1 + IN_REG + (OUT_REG > 0), the read register and the output register advancing with the
(registered, with IN_REG) read enable (OUT_REG = 2: the output register with out_en, driven
at random in every set, so a form that loads it with the read enable fails there and one
that uses out_en elsewhere fails in the others), a write one edge after its inputs with WR_REG, a
read of the word written at the same edge returning the old word. The ECP5 form instantiates DP16KD block RAMs with their output
register (simulated with sim/hdl/ecp5/DP16KD.v) for 128 to 16384 words and OUT_REG = 1,
in the block's shape for the depth (1024 x 18, 2048 x 9, 4096 x 4, 8192 x 2, 16384 x 1)
or in deeper shapes stacked 2 to 4 blocks deep where that takes fewer blocks (a multiplexer
behind the output registers), so the parameter sets cover every shape, stacks of 2, 3
and 4 with their bank choice, the fall-back to inferred RAM on either side,
and IN_REG's and WR_REG's register copies. A wrong address or data mapping of a block fails here.

Cycle discipline: the TB drives the inputs on each falling edge and reads rd_data on the
next falling edge, after the rising edge the model applies. Write addresses are random
over the whole depth (so every address bit of every block is exercised); reads mostly
pick one of the last 16 addresses written (a word just written, sometimes at the same
edge), else a random one; the read enable is 1, or random with probability 0.7 in the
stall test (the output must hold across disabled edges). A word never written is not
checked. Seeded per test from COCOTB_RANDOM_SEED.
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

CLK_PERIOD_NS = 10


class RamModel:
    """The RAM at the port's clock edges (cube4_sdp_ram's header, 'Latency')."""

    def __init__(self, depth: int, in_reg: int, wr_reg: int, out_reg: int) -> None:
        self.mem: dict[int, int] = {}
        self.in_reg, self.wr_reg, self.out_reg = in_reg, wr_reg, out_reg
        self.acc_q = (0, 0, 0, 0)       # IN_REG: (re, ra, we, wa) of the last edge
        self.wr_q = (0, 0, 0)           # WR_REG: (we, wa, wd) of the last edge
        self.rd_q: int | None = None    # None: not read yet
        self.out_q: int | None = None

    def edge(self, re: int, oe: int, ra: int, we: int, wa: int, wd: int) -> None:
        if self.in_reg:
            (re, ra, we, wa), self.acc_q = self.acc_q, (re, ra, we, wa)
        if self.wr_reg:
            (we, wa, wd), self.wr_q = self.wr_q, (we, wa, wd)
        if (oe if self.out_reg == 2 else re) and self.out_reg:
            self.out_q = self.rd_q
        if re:
            self.rd_q = self.mem.get(ra)     # the old word on a same-edge write
        if we:
            self.mem[wa] = wd

    def rd_data(self) -> int | None:
        return self.out_q if self.out_reg else self.rd_q


class TB:
    """Drives cube4_sdp_ram and checks rd_data against RamModel after every edge."""

    def __init__(self, dut) -> None:
        self.dut = dut
        self.data_w = int(dut.DATA_W.value)
        self.depth = int(dut.DEPTH.value)
        self.model = RamModel(self.depth, int(dut.IN_REG.value), int(dut.WR_REG.value), int(dut.OUT_REG.value))
        self.rng = np.random.default_rng(cocotb.RANDOM_SEED)
        Clock(dut.clk, CLK_PERIOD_NS, unit="ns").start(start_high=False)

    def word(self) -> int:
        return int(self.rng.integers(0, 1 << min(self.data_w, 62))) | (
            int(self.rng.integers(0, 2)) << (self.data_w - 1))

    async def run(self, cycles: int, re_prob: float) -> int:
        dut, rng, m = self.dut, self.rng, self.model
        checks = 0
        written: list[int] = []         # recent write addresses, to read back
        await FallingEdge(dut.clk)
        for c in range(cycles):
            wa = int(rng.integers(0, self.depth))
            if written and rng.random() < 0.2:
                wa = written[-1]        # the same address twice in a row
            if written and rng.random() < 0.8:
                ra = written[int(rng.integers(max(0, len(written) - 16), len(written)))]
            else:
                ra = int(rng.integers(0, self.depth))
            re = int(rng.random() < re_prob)
            oe = int(rng.random() < 0.6)
            we = int(rng.random() < 0.5)
            wd = self.word()
            if we:
                written.append(wa)
            dut.rd_en.value, dut.out_en.value, dut.rd_addr.value = re, oe, ra
            dut.wr_en.value, dut.wr_addr.value, dut.wr_data.value = we, wa, wd
            await FallingEdge(dut.clk)
            m.edge(re, oe, ra, we, wa, wd)
            want = m.rd_data()
            if want is not None:
                got = int(dut.rd_data.value)
                assert got == want, (f"cycle {c}: rd_data = {got:#x}, expected {want:#x} "
                                     f"(DEPTH={self.depth}, DATA_W={self.data_w})")
                checks += 1
        return checks


@cocotb.test()
async def ram_streaming(dut):
    tb = TB(dut)
    assert await tb.run(1500, re_prob=1.0) > 1000


@cocotb.test()
async def ram_random_stalls(dut):
    tb = TB(dut)
    assert await tb.run(1500, re_prob=0.7) > 1000


# ---------------------------------------------------------------- pytest half
from cube4_sim import run_test  # noqa: E402
from cube4_sim.sweeps import sweep
from cube4_sim.sources import RTL_FORMS, form_build_args, form_sources  # noqa: E402

# the shapes of the ECP5 form (block RAM 1024 x 18 .. 16384 x 1, distributed RAM below
# 128 words or with DIST = 1, inferred beyond 16384), with and without IN_REG's copies and OUT_REG
PARAM_SETS = [
    {"DATA_W": 20, "DEPTH": 100, "OUT_REG": 1},                 # 1024 x 18, two slices
    {"DATA_W": 27, "DEPTH": 2048, "IN_REG": 1, "OUT_REG": 1},   # 2048 x 9, copies
    {"DATA_W": 5, "DEPTH": 4096, "OUT_REG": 1},                 # 4096 x 4
    {"DATA_W": 20, "DEPTH": 6145, "OUT_REG": 1},                # 2 x (4 deep 2048 x 9) + 8192 x 2
    {"DATA_W": 3, "DEPTH": 16384, "IN_REG": 1, "OUT_REG": 1},   # 16384 x 1
    {"DATA_W": 9, "DEPTH": 16, "OUT_REG": 1},                   # distributed RAM
    {"DATA_W": 6, "DEPTH": 20000, "OUT_REG": 1},                # deeper: inferred
    {"DATA_W": 40, "DEPTH": 64, "IN_REG": 1},                   # no output register
    {"DATA_W": 41, "DEPTH": 2048, "WR_REG": 1, "OUT_REG": 1},   # 2048 x 9, write copies
    {"DATA_W": 5, "DEPTH": 16384, "WR_REG": 1, "OUT_REG": 1},   # 16384 x 1, write copies
    {"DATA_W": 9, "DEPTH": 16, "WR_REG": 1},                    # distributed RAM
    {"DATA_W": 9, "DEPTH": 4096, "OUT_REG": 1},                 # 2 deep 2048 x 9 (the ray table)
    {"DATA_W": 34, "DEPTH": 3000, "OUT_REG": 1},                # 4 x (2 deep 2048 x 9)
    {"DATA_W": 9, "DEPTH": 5000, "WR_REG": 1, "OUT_REG": 1},    # 3 deep 2048 x 9, write copies
    {"DATA_W": 32, "DEPTH": 256, "DIST": 1},                    # distributed RAM by choice (GRA's row table)
    {"DATA_W": 74, "DEPTH": 2048, "OUT_REG": 2},                # 2048 x 9, out_en (GRA's plane A)
    {"DATA_W": 20, "DEPTH": 6145, "WR_REG": 1, "OUT_REG": 2},   # stacks: the bank choice with out_en
    {"DATA_W": 30, "DEPTH": 16, "OUT_REG": 2},                  # distributed RAM, out_en (GRA's beam)
    {"DATA_W": 34, "DEPTH": 64, "OUT_REG": 1},                  # distributed RAM, 64 words (the front end's beat bits)
    {"DATA_W": 40, "DEPTH": 16, "IN_REG": 1, "OUT_REG": 1},     # distributed RAM, copies (COM's beam buffer)
]


def _param_id(params: dict) -> str:
    return "-".join(f"{k}{v}" for k, v in params.items())


@pytest.mark.parametrize("form", RTL_FORMS)
@pytest.mark.parametrize("params", sweep(PARAM_SETS, quick=(1, 7, 8, 11, 14, 15, 16, 18, 19), ids=_param_id))
def test_cube4_sdp_ram(params, form):
    run_test(top="cube4_sdp_ram", sources=form_sources(form), params=params, test_module=__file__,
             build_args=form_build_args(form))

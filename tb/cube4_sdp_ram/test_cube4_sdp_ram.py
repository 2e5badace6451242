"""Testbench for rtl/cube4_sdp_ram.v and its ECP5 form rtl/ecp5/cube4_sdp_ram.v.

Both forms run the same cocotb tests against a Python model of the RAM, every parameter set at
once: tb/cube4_sdp_ram/cube4_sdp_ram_sets.v instantiates the RAM once per set (PARAM_SETS,
packed into its parameters), one build per form, and each instance is checked against a model
of its own on every edge: read latency
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

import json
from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from cube4_sim.sweeps import pack_rows, set_lanes

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


class Lane:
    """One instance of the harness: its parameters, its model and its stimulus."""

    def __init__(self, params: dict, rng: np.random.Generator) -> None:
        self.data_w = params["DATA_W"]
        self.depth = params["DEPTH"]
        self.model = RamModel(self.depth, params.get("IN_REG", 0), params.get("WR_REG", 0),
                              params.get("OUT_REG", 0))
        self.rng = rng
        self.written: list[int] = []    # recent write addresses, to read back
        self.checks = 0

    def word(self) -> int:
        return int(self.rng.integers(0, 1 << min(self.data_w, 62))) | (
            int(self.rng.integers(0, 2)) << (self.data_w - 1))

    def inputs(self, re_prob: float) -> tuple[int, int, int, int, int, int]:
        """This edge's (re, oe, ra, we, wa, wd)."""
        rng, written = self.rng, self.written
        wa = int(rng.integers(0, self.depth))
        if written and rng.random() < 0.2:
            wa = written[-1]            # the same address twice in a row
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
        return re, oe, ra, we, wa, wd


class TB:
    """Drives every instance of cube4_sdp_ram_sets and checks each one's rd_data against its
    RamModel after every edge."""

    def __init__(self, dut) -> None:
        self.dut = dut
        self.dw_max, self.aw_max, self.lanes = set_lanes(dut, "CUBE4_SDP_RAM_SETS", Lane)
        Clock(dut.clk, CLK_PERIOD_NS, unit="ns").start(start_high=False)

    async def run(self, cycles: int, re_prob: float) -> int:
        """The fewest checks any instance made."""
        dut, dw, aw = self.dut, self.dw_max, self.aw_max
        await FallingEdge(dut.clk)
        for c in range(cycles):
            ins = [lane.inputs(re_prob) for lane in self.lanes]
            re, oe, ra, we, wa, wd = pack_rows(ins, (1, 1, aw, 1, aw, dw))
            dut.rd_en.value, dut.out_en.value, dut.rd_addr.value = re, oe, ra
            dut.wr_en.value, dut.wr_addr.value, dut.wr_data.value = we, wa, wd
            await FallingEdge(dut.clk)
            rd = int(dut.rd_data.value)
            for k, (lane, values) in enumerate(zip(self.lanes, ins)):
                lane.model.edge(*values)
                want = lane.model.rd_data()
                if want is not None:
                    got = (rd >> (k * dw)) & ((1 << dw) - 1)
                    assert got == want, (f"cycle {c}: set {k} rd_data = {got:#x}, expected {want:#x} "
                                         f"(DEPTH={lane.depth}, DATA_W={lane.data_w})")
                    lane.checks += 1
        return min(lane.checks for lane in self.lanes)


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
from cube4_sim.sweeps import packed_sets  # noqa: E402
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
    {"DATA_W": 32, "DEPTH": 512, "WR_REG": 1, "OUT_REG": 1},    # 1024 x 18, write copies (the walk's slots)
    {"DATA_W": 32, "DEPTH": 256, "DIST": 1},                    # distributed RAM by choice (GRA's row table)
    {"DATA_W": 74, "DEPTH": 2048, "OUT_REG": 2},                # 2048 x 9, out_en (GRA's plane A)
    {"DATA_W": 20, "DEPTH": 6145, "WR_REG": 1, "OUT_REG": 2},   # stacks: the bank choice with out_en
    {"DATA_W": 30, "DEPTH": 16, "OUT_REG": 2},                  # distributed RAM, out_en (GRA's beam)
    {"DATA_W": 34, "DEPTH": 64, "OUT_REG": 1},                  # distributed RAM, 64 words (the front end's beat bits)
    {"DATA_W": 40, "DEPTH": 16, "IN_REG": 1, "OUT_REG": 1},     # distributed RAM, copies (COM's beam buffer)
]


HARNESS = Path(__file__).resolve().parent / "cube4_sdp_ram_sets.v"
FIELDS = ("DATA_W", "DEPTH", "IN_REG", "WR_REG", "OUT_REG", "DIST")


def test_packed_sets():
    p = packed_sets([{"DATA_W": 20, "DEPTH": 100, "OUT_REG": 1}, {"DATA_W": 3, "DEPTH": 16384, "IN_REG": 1}], FIELDS)
    assert p["N"] == 2 and p["DW_MAX"] == 20 and p["AW_MAX"] == 14
    assert p["DATA_WS"] == "64'h300000014" and p["IN_REGS"] == "64'h100000000"


@pytest.mark.parametrize("form", RTL_FORMS)
def test_cube4_sdp_ram(form):
    """Every parameter set at once: one build of the harness per form."""
    run_test(top="cube4_sdp_ram_sets", sources=[*form_sources(form), HARNESS],
             params=packed_sets(PARAM_SETS, FIELDS), test_module=__file__,
             build_args=form_build_args(form),
             extra_env={"CUBE4_SDP_RAM_SETS": json.dumps(PARAM_SETS)})

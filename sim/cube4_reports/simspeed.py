"""Simulation speed of cube4_top (``make simspeed``): clock cycles per second of wall time.

Renders one frame through the RTL engine (``cube4 render ... --engine rtl``, the build the
command line would use, its Verilator flags) and reads the frame's cycles and the wall time
the simulator spent in it from ``--stats`` (the frame alone: the volume load, the tables and
the Verilator build are not in it). Prints one line per run and each build's median;
writes build/reports/simspeed.json and reports/simspeed.md. The default builds are the full
build and the named builds that each leave options out, so the table says what each
option costs in simulation speed.

    python -m cube4_reports.simspeed [--pipelines 8] [--volume sphere:128] [--scene default]
                                     [--build full --build mip ...] [--runs 3]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from cube4.builds import FULL_BUILD, NAMED
from cube4.errors import UserError

from .markdown import REPO_ROOT, git_state, md_table, rtl_commit
from .synth import cli_main, progress

TAG = "simspeed"
OUT = REPO_ROOT / "build" / "reports" / "simspeed.json"
MD = REPO_ROOT / "reports" / "simspeed.md"
#: the full build, then builds that leave out options (cube4.builds NAMED)
DEFAULT_BUILDS = ("full", "noclip", "unweighted", "shaded", "rects")   # (mip and unshaded need a scene of theirs)
GOAL = 0.5e6   # cycles per second at P = 8 (the structure issue's goal)


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    ap = argparse.ArgumentParser(prog="python -m cube4_reports.simspeed", description=__doc__.splitlines()[0])
    ap.add_argument("--pipelines", type=int, default=8, help="P (default 8)")
    ap.add_argument("--volume", default="sphere:128", help="a volume the command line reads (default sphere:128)")
    ap.add_argument("--scene", default="default", help="scene name or file (default: default)")
    ap.add_argument("--build", action="append", default=None,
                    help=f"--build of cube4 render; repeat for several (default: {', '.join(DEFAULT_BUILDS)})")
    ap.add_argument("--runs", type=int, default=3, help="frames to time, each in its own simulation (default 3)")
    ap.add_argument("--json", type=Path, default=OUT, help=f"JSON output (default {OUT.relative_to(REPO_ROOT)})")
    ap.add_argument("--md", type=Path, default=MD, help=f"Markdown report (default {MD.relative_to(REPO_ROOT)})")
    args = ap.parse_args(argv)
    args.build = args.build or list(DEFAULT_BUILDS)
    return args


def build_flag(build: str) -> str:
    """The --build of cube4 render for a build: a named build (cube4.builds NAMED) as the
    NAME=0/1 pairs where it differs from the full build; anything else as given."""
    if build in NAMED and build != "full":
        return ",".join(f"{k}={v}" for k, v in NAMED[build].items() if v != FULL_BUILD[k])
    return build


def one_run(args: argparse.Namespace, build: str, tmp: Path, n: int) -> dict:
    stats_path = tmp / f"stats{n}.json"
    cmd = [sys.executable, "-m", "cube4_sim.cli", "render", args.volume, "--scene", args.scene, "--engine", "rtl",
           "--pipelines", str(args.pipelines), "--build", build_flag(build), "--stats", str(stats_path),
           "--out", str(tmp / f"image{n}.png")]
    t0 = time.perf_counter()
    res = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if res.returncode != 0:
        last = (res.stderr.strip().splitlines() or ["no message"])[-1]
        raise UserError(f"cube4 render failed (exit {res.returncode}): {last}")
    stats = json.loads(stats_path.read_text())
    return {"cycles": int(stats["cycles"]), "sim_wall_s": float(stats["sim_wall_s"]),
            "cycles_per_s": int(stats["cycles"]) / float(stats["sim_wall_s"]), "command_wall_s": wall}


def measure(args: argparse.Namespace, build: str, tmp: Path) -> dict:
    """``args.runs`` frames of one build (the first run also builds it); their median."""
    runs = []
    for n in range(args.runs):
        progress(TAG, f"build {build}, run {n + 1}/{args.runs}: {args.volume}, scene {args.scene}, "
                      f"P = {args.pipelines} ...")
        r = one_run(args, build, tmp, n)
        runs.append(r)
        print(f"{TAG}: {build}: {r['cycles']:,} cycles in {r['sim_wall_s']:.2f} s of simulation = "
              f"{r['cycles_per_s'] / 1e6:.3f} M cycles/s (the whole command {r['command_wall_s']:.1f} s)")
    median = statistics.median(r["cycles_per_s"] for r in runs)
    print(f"{TAG}: cube4_top P = {args.pipelines}, build {build}: median {median / 1e6:.3f} M cycles/s "
          f"over {len(runs)} runs")
    return {"build": build, "runs": runs, "median_cycles_per_s": median}


def markdown(args: argparse.Namespace, results: list[dict], load: tuple[float, float]) -> str:
    rows = [[f"`{r['build']}`", f"{r['runs'][0]['cycles']:,}",
             f"{statistics.median(x['sim_wall_s'] for x in r['runs']):.2f}",
             f"{r['median_cycles_per_s'] / 1e6:.3f}",
             f"{r['median_cycles_per_s'] / results[0]['median_cycles_per_s']:.2f}"] for r in results]
    return "\n".join([
        "# Simulation speed (`make simspeed`)", "",
        f"Generated by `make simspeed` (`python -m cube4_reports.simspeed`). RTL: {rtl_commit(('rtl', 'sim/hdl'))}.",
        f"cube4_top at P = {args.pipelines} renders {args.volume} (scene {args.scene}) through the RTL engine "
        f"(`cube4 render --engine rtl`, Verilator with the renders' flags, C++ at -O3, a Verilog clock, Python "
        f"waking only at the frame's end); the figure is the frame's clock cycles over the wall time the "
        f"simulator spent in it (not the volume load, the tables or the build), the median of {args.runs} "
        f"runs, each in its own simulation. Load average before and after: {load[0]:.2f}, {load[1]:.2f} "
        f"(two cores).", "",
        md_table(["build (`--build`)", "cycles per frame", "simulation s", "M cycles/s", "vs full"], rows), "",
        f"The goal for the full build at P = 8 is {GOAL / 1e6:.1f} M cycles/s. The builds are named builds "
        "of `golden/cube4/builds.py` (NAMED: `noclip` leaves out CLIP, `unweighted` PLW, `shaded` EXTREMUM and "
        "CLIP, `rects` adds slice rectangles and leaves out PLW); a row against `full` is what the options it "
        "leaves out cost in simulation speed (`rects` also walks fewer beats).", ""])


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)

    def body() -> None:
        if args.runs < 1:
            raise UserError("--runs must be at least 1")
        load0 = os.getloadavg()[0]
        with tempfile.TemporaryDirectory(prefix="cube4_simspeed_") as tmp:
            results = [measure(args, build, Path(tmp)) for build in args.build]
        load = (load0, os.getloadavg()[0])
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps({"pipelines": args.pipelines, "volume": args.volume, "scene": args.scene,
                                         "git": git_state(("rtl", "sim/hdl")), "loadavg": load,
                                         "builds": results}, indent=2) + "\n")
        args.md.parent.mkdir(parents=True, exist_ok=True)
        args.md.write_text(markdown(args, results, load))
        print(f"{TAG}: wrote {args.json} and {args.md}")

    return cli_main(TAG, body)


if __name__ == "__main__":
    sys.exit(main())

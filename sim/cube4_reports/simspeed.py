"""Simulation speed of cube4_top (``make simspeed``): clock cycles per second of wall time.

Renders one frame through the RTL engine (``cube4 render ... --engine rtl``, the build the
command line would use, its Verilator flags) and reads the frame's cycles and the wall time
the simulator spent in it from ``--stats`` (the frame alone: the volume load, the tables and
the Verilator build are not in it). Prints one line per run and their median; writes
build/reports/simspeed.json.

    python -m cube4_reports.simspeed [--pipelines 8] [--volume sphere:128] [--scene default]
                                     [--build full] [--runs 3]
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from cube4.errors import UserError

from .markdown import REPO_ROOT
from .synth import cli_main, progress

TAG = "simspeed"
OUT = REPO_ROOT / "build" / "reports" / "simspeed.json"


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    ap = argparse.ArgumentParser(prog="python -m cube4_reports.simspeed", description=__doc__.splitlines()[0])
    ap.add_argument("--pipelines", type=int, default=8, help="P (default 8)")
    ap.add_argument("--volume", default="sphere:128", help="a volume the command line reads (default sphere:128)")
    ap.add_argument("--scene", default="default", help="scene name or file (default: default)")
    ap.add_argument("--build", default="full", help="--build of cube4 render (default full)")
    ap.add_argument("--runs", type=int, default=3, help="frames to time, each in its own simulation (default 3)")
    ap.add_argument("--json", type=Path, default=OUT, help=f"JSON output (default {OUT.relative_to(REPO_ROOT)})")
    return ap.parse_args(argv)


def one_run(args: argparse.Namespace, tmp: Path, n: int) -> dict:
    stats_path = tmp / f"stats{n}.json"
    cmd = [sys.executable, "-m", "cube4_sim.cli", "render", args.volume, "--scene", args.scene, "--engine", "rtl",
           "--pipelines", str(args.pipelines), "--build", args.build, "--stats", str(stats_path),
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


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)

    def body() -> None:
        if args.runs < 1:
            raise UserError("--runs must be at least 1")
        runs = []
        with tempfile.TemporaryDirectory(prefix="cube4_simspeed_") as tmp:
            for n in range(args.runs):
                progress(TAG, f"run {n + 1}/{args.runs}: {args.volume}, scene {args.scene}, P = {args.pipelines}, "
                              f"build {args.build} ...")
                r = one_run(args, Path(tmp), n)
                runs.append(r)
                print(f"{TAG}: {r['cycles']:,} cycles in {r['sim_wall_s']:.2f} s of simulation = "
                      f"{r['cycles_per_s'] / 1e6:.3f} M cycles/s (the whole command {r['command_wall_s']:.1f} s)")
        median = statistics.median(r["cycles_per_s"] for r in runs)
        print(f"{TAG}: cube4_top P = {args.pipelines}, build {args.build}: median {median / 1e6:.3f} M cycles/s "
              f"over {len(runs)} runs")
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps({"pipelines": args.pipelines, "volume": args.volume, "scene": args.scene,
                                         "build": args.build, "runs": runs, "median_cycles_per_s": median},
                                        indent=2) + "\n")
        print(f"{TAG}: wrote {args.json}")

    return cli_main(TAG, body)


if __name__ == "__main__":
    sys.exit(main())

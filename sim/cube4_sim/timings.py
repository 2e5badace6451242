"""Where a test run's time went: the Verilator builds against the simulations.

Every simulation the runner starts appends a line to build/sim/timings.jsonl (the test,
its build directory, the seconds spent building and simulating; a build already made
costs only its up-to-date check). This sums them::

    rm -f build/sim/timings.jsonl && make test && python -m cube4_sim.timings

Seconds are wall time per worker: with two workers they add up to about twice the run's
wall time."""

from __future__ import annotations

import argparse
import json
import sys
from collections import defaultdict
from pathlib import Path

from .runner import TIMINGS


def load(path: Path) -> list[dict]:
    """The records of ``path``, one per simulation."""
    if not path.is_file():
        raise SystemExit(f"cube4_sim.timings: {path} does not exist (run the tests first)")
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


def summary(records: list[dict], top_n: int = 12) -> str:
    """A plain-text table: totals, then per top module, then the slowest builds."""
    by_top: dict[str, list[float]] = defaultdict(lambda: [0.0, 0.0, 0, set()])
    builds: dict[str, float] = defaultdict(float)
    for r in records:
        t = by_top[r["top"]]
        t[0] += r["build_s"]
        t[1] += r["sim_s"]
        t[2] += 1
        t[3].add(r["build"])
        builds[r["build"]] += r["build_s"]
    total_b = sum(t[0] for t in by_top.values())
    total_s = sum(t[1] for t in by_top.values())
    lines = [f"{len(records)} simulations, {len(builds)} builds: "
             f"build {total_b:.0f} s, simulation {total_s:.0f} s (worker seconds)",
             "", f"{'top':34} {'builds':>6} {'runs':>5} {'build s':>8} {'sim s':>8}"]
    for top, (b, s, n, dirs) in sorted(by_top.items(), key=lambda kv: -(kv[1][0] + kv[1][1])):
        lines.append(f"{top:34} {len(dirs):6d} {n:5d} {b:8.0f} {s:8.0f}")
    lines += ["", "slowest builds (seconds, the first test that made each):"]
    for name, b in sorted(builds.items(), key=lambda kv: -kv[1])[:top_n]:
        lines.append(f"  {b:7.1f}  {name}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m cube4_sim.timings", description=__doc__.split("\n\n")[0])
    ap.add_argument("path", nargs="?", type=Path, default=TIMINGS, help=f"the records (default {TIMINGS})")
    ap.add_argument("--top", type=int, default=12, help="how many of the slowest builds to list")
    args = ap.parse_args(argv)
    print(summary(load(args.path), args.top))
    return 0


if __name__ == "__main__":
    sys.exit(main())

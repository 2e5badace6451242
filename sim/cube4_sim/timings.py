"""Where a test run's time went: the Verilator builds against the simulations.

Every simulation the runner starts appends a line to build/sim/timings.jsonl (the test,
its build directory, the seconds spent building and simulating; a build already made
costs only its up-to-date check). This sums them::

    rm -f build/sim/timings.jsonl && make test && python -m cube4_sim.timings

Seconds are wall time per worker: with two workers they add up to about twice the run's
wall time. ``--against OLD.jsonl`` compares two runs on the builds they share (a build
directory is named after its parameters, not its sources): the same builds taking longer
in both their compiles and their simulations is a slower machine, not a grown suite.
reports/test_timings.jsonl keeps a fresh clone's records as such a baseline."""

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


def _totals(records: list[dict]) -> dict[str, list[float]]:
    """Per build directory: [build seconds, simulation seconds]."""
    out: dict[str, list[float]] = defaultdict(lambda: [0.0, 0.0])
    for r in records:
        out[r["build"]][0] += r["build_s"]
        out[r["build"]][1] += r["sim_s"]
    return out


def compare(new: list[dict], old: list[dict]) -> str:
    """Two runs on the builds both made: their build and simulation seconds and the ratios."""
    a, b = _totals(new), _totals(old)
    common = sorted(set(a) & set(b))
    if not common:
        return "no build in common: the runs cannot be compared"
    nb, ns = sum(a[k][0] for k in common), sum(a[k][1] for k in common)
    ob, os_ = sum(b[k][0] for k in common), sum(b[k][1] for k in common)
    def ratio(x: float, y: float) -> str:
        return f"x{x / y:.2f}" if y > 0 else "-"
    return (f"{len(common)} builds in both runs ({len(a) - len(common)} only in this one, "
            f"{len(b) - len(common)} only in the other): build {nb:.0f} s against {ob:.0f} s "
            f"({ratio(nb, ob)}), simulation {ns:.0f} s against {os_:.0f} s ({ratio(ns, os_)})")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m cube4_sim.timings", description=__doc__.split("\n\n")[0])
    ap.add_argument("path", nargs="?", type=Path, default=TIMINGS, help=f"the records (default {TIMINGS})")
    ap.add_argument("--top", type=int, default=12, help="how many of the slowest builds to list")
    ap.add_argument("--against", type=Path, metavar="OLD",
                    help="another run's records: compare the builds both made")
    args = ap.parse_args(argv)
    records = load(args.path)
    print(summary(records, args.top))
    if args.against is not None:
        print("\n" + compare(records, load(args.against)))
    return 0


if __name__ == "__main__":
    sys.exit(main())

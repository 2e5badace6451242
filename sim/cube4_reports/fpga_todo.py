"""`make fpga-todo`: place and route every build the reports need that is not measured on today's rtl/.

The builds are those `make fpga-status` lists without a result on today's rtl/ (cube4_reports.
fpga_status), and with ``--full`` the full build at P = 1, 2, 4 and 8 as well (issue 56: the
four within 10 % of each other, on one RTL commit). Each build is one
``python -m cube4_reports.fpga`` run with its three seeds one after another (``--jobs 1``),
and ``--lanes`` builds run side by side (default 2, one per core: a lane's synthesis overlaps
another lane's nextpnr, and no core waits for a build's last seed). Every run passes
``--reuse``, so a stopped ``make fpga-todo`` picks up where it stopped: a build's netlist and
each seed already routed on the same RTL, parameters and flow are kept.

The list is read again whenever a lane frees: a build that turns out not to fit at P = 8
brings the next smaller P it needs (fpga_status: the largest P that fits), which is then run.

    python -m cube4_reports.fpga_todo --list            # what would run, in order
    python -m cube4_reports.fpga_todo                   # run it all, two builds at a time
    python -m cube4_reports.fpga_todo --full --lanes 2 --timeout 2400
    python -m cube4_reports.fpga_todo --only e0k0w0b1,e0w0b1   # just these, in this order

Each run writes its report and JSON in reports/fpga/, its netlist and nextpnr logs in
build/synth/fpga/, and its progress in build/fpga_todo/<report name>.log. Afterwards refresh the tables that read them:
``make fpga-status`` and the ``--md-only`` / ``--tables-only`` forms of scenes, skipping and
report.
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

from cube4.builds import FULL_BUILD
from cube4.config import Cube4Config
from cube4.errors import UserError

from . import fmax as fmax_store
from . import fpga_status
from .markdown import REPO_ROOT
from .synth import progress

TAG = "fpga-todo"
#: the full build's P that issue 56 compares (within 10 % of each other)
FULL_P = (1, 2, 4, 8)
LOG_DIR = REPO_ROOT / "build" / "fpga_todo"


@dataclass(frozen=True)
class Job:
    """One place-and-route run: its name (the report's stem) and its fpga arguments."""

    name: str
    args: tuple[str, ...]

    @property
    def command(self) -> list[str]:
        return [sys.executable, "-m", "cube4_reports.fpga", *self.args]


def job_from_command(cmd: str) -> Job:
    """A Job from one of fpga_status's commands (``python -m cube4_reports.fpga ... --md X.md``)."""
    words = cmd.split()
    if words[:3] != ["python", "-m", "cube4_reports.fpga"] or "--md" not in words:
        raise ValueError(f"not an fpga command: {cmd}")
    md = words[words.index("--md") + 1]
    return Job(Path(md).stem, tuple(words[3:]))


def full_jobs(measured: list) -> list[Job]:
    """The full build at each of FULL_P not measured on today's rtl/ (``--full``), looked up
    and named as fpga_status does, its report full_p<P>.md at every P (docs/reports.md reads
    the four side by side; fpga_status names P = 8's full.md, the same run)."""
    needs = {p: fpga_status.Need(p, dict(FULL_BUILD), Cube4Config(pipelines=p).widths()) for p in FULL_P}
    out = []
    for s in fpga_status.statuses(needs, measured):
        if not s.current:
            job = job_from_command(fpga_status.place_command(s.need))
            args = list(job.args)
            args[args.index("--md") + 1] = f"reports/fpga/full_p{s.need.p}.md"
            out.append(Job(f"full_p{s.need.p}", tuple(args)))
    return sorted(out, key=lambda j: int(j.name.rsplit("_p", 1)[1]))


def todo(full: bool) -> list[Job]:
    """The runs still to do, in fpga_status's order (P = 8 first), the full build's first."""
    measured = fmax_store.load()
    jobs = full_jobs(measured) if full else []
    for s in fpga_status.collect(measured):
        if not s.current:
            jobs.append(job_from_command(fpga_status.place_command(s.need)))
    seen, out = set(), []
    for j in jobs:          # the full build at P = 8 may come twice, under two report names
        key = same_run(j)
        if key not in seen:
            seen.add(key)
            out.append(j)
    return out


def only(jobs: list[Job], names: list[str]) -> list[Job]:
    """The jobs named (report stems, as ``--list`` shows them), in the order named. A name
    that is not on the list (unknown, or already measured on today's rtl/) is an error."""
    by_name = {j.name: j for j in jobs}
    missing = [n for n in names if n not in by_name]
    if missing:
        raise UserError(f"not among the runs still to do: {', '.join(missing)} (see --list)")
    return [by_name[n] for n in names]


def same_run(job: Job) -> tuple[str, ...]:
    """A job's arguments without its report's name: two jobs with the same are one run."""
    a = list(job.args)
    i = a.index("--md")
    return tuple(a[:i] + a[i + 2:])


def with_flow(job: Job, timeout: int) -> list[str]:
    """The command one lane runs: seeds one at a time, earlier work reused."""
    return [*job.command, "--jobs", "1", "--reuse", "--timeout", str(timeout)]


def run(next_jobs, lanes: int, timeout: int, start=subprocess.Popen, poll_s: float = 10.0) -> list[tuple[Job, int]]:
    """Run jobs ``lanes`` at a time. ``next_jobs()`` gives the list still to do; it is read
    again whenever a lane frees, and a job already started in this run is not started twice.
    Returns (job, exit code) in the order they ended."""
    running: dict = {}            # Popen -> Job
    started: set = set()
    ended: list = []
    queue = list(next_jobs())
    try:
        while True:
            while len(running) < lanes:
                job = next((j for j in queue if j.name not in started), None)
                if job is None:
                    break
                started.add(job.name)
                LOG_DIR.mkdir(parents=True, exist_ok=True)
                log = open(LOG_DIR / f"{job.name}.log", "w")
                progress(TAG, f"start {job.name} ({len(started)} started, {len(running) + 1} running): "
                              f"log build/fpga_todo/{job.name}.log")
                running[start(with_flow(job, timeout), stdout=log, stderr=subprocess.STDOUT,
                              cwd=REPO_ROOT, start_new_session=True)] = job
                log.close()
            if not running:
                return ended
            time.sleep(poll_s)
            for proc in [p for p in running if p.poll() is not None]:
                job = running.pop(proc)
                ended.append((job, proc.returncode))
                progress(TAG, f"end {job.name}: exit {proc.returncode} ({len(ended)} ended)")
                queue = list(next_jobs())
    finally:
        for proc in running:      # stopped (Ctrl-C): stop the runs' process groups too
            if isinstance(proc.pid, int) and proc.pid > 0:
                try:
                    os.killpg(proc.pid, signal.SIGTERM)
                except (ProcessLookupError, PermissionError):
                    pass


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    ap = argparse.ArgumentParser(prog="python -m cube4_reports.fpga_todo", description=__doc__.splitlines()[0])
    ap.add_argument("--list", action="store_true", help="print the runs in order and stop")
    ap.add_argument("--full", action="store_true",
                    help=f"also the full build at P = {', '.join(map(str, FULL_P))} where not measured on today's rtl/")
    ap.add_argument("--lanes", type=int, default=2, help="builds placed and routed at a time (default 2)")
    ap.add_argument("--timeout", type=int, default=3600, help="time limit per nextpnr run in seconds (default 3600)")
    ap.add_argument("--only", default="",
                    help="comma-separated report names (as --list shows them): run just these, in this order")
    return ap.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    if args.lanes < 1:
        print("fpga_todo: --lanes must be at least 1", file=sys.stderr)
        return 2
    names = [n.strip() for n in args.only.split(",") if n.strip()]

    def still_to_do() -> list[Job]:
        jobs = todo(args.full)
        if not names:
            return jobs
        left = {j.name for j in jobs}          # a named run measured meanwhile drops out
        return only(jobs, [n for n in names if n in left])

    try:
        jobs = todo(args.full)
        if names:
            jobs = only(jobs, names)           # every name must be a run still to do
        if args.list:
            for j in jobs:
                print(" ".join(["python", "-m", "cube4_reports.fpga", *j.args]))
            return 0
        if not jobs:
            progress(TAG, "every build is measured on today's rtl/")
            return 0
        ended = run(still_to_do, args.lanes, args.timeout)
    except UserError as e:
        print(f"fpga_todo: {e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("fpga_todo: stopped; rerun to go on (each build's routed seeds are kept)", file=sys.stderr)
        return 130
    failed = [j.name for j, rc in ended if rc != 0]
    progress(TAG, f"{len(ended)} runs, {len(failed)} failed" + (f": {', '.join(failed)}" if failed else "")
             + "; refresh the tables: make fpga-status, and scenes/skipping --md-only, report --tables-only")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

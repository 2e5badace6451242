"""`make fpga-status`: the builds whose Fmax the reports' frame times need, and where each stands.

`make scenes`, `make report` and `make skipping` turn cycles into milliseconds with the
measured Fmax of the build that runs each frame (cube4_reports.fmax): a build never placed
and routed has no frame time. This lists every build those three reports name (from their
committed JSON: reports/scenes.json, reports/error_vs_runtime.json, reports/skipping.json),
with, for each, the place and route it has (reports/fpga*.json, reports/fpga/*.json):

- its Fmax (median of its seeds), or "does not fit" (the scenes report then reads the largest
  smaller P that fits, listed as a build of its own), or "not measured";
- the RTL it ran on: "as now" when rtl/ at that commit is the tree of rtl/ at HEAD, "as now
  but comments" when the two differ in comment and blank lines only, "as now in the files it
  reads" when rtl/ has changed since only in files that build does not read (the result's
  list of them, cube4_reports.fpga_files: another build's module, say), else how many
  commits have changed rtl/ since;
- against the 130 MHz goal of a build at P = 8 (issue 56: every build reaches it where it fits);
- the command that places and routes it (three seeds), its report and JSON in reports/fpga/.

    python -m cube4_reports.fpga_status              # the table, on the terminal
    python -m cube4_reports.fpga_status --todo       # the commands of the builds not measured
                                                     # on today's rtl/, one per line
    python -m cube4_reports.fpga_status --md reports/fpga_status.md

Nothing is placed or routed here; it reads JSON and git only (a second or two).
"""

from __future__ import annotations

import argparse
import json
import sys
from dataclasses import dataclass, field
from pathlib import Path

from cube4.builds import BUILD_PARAMS
from cube4.config import Cube4Config
from cube4.errors import UserError

from . import fmax as fmax_store
from .markdown import REPO_ROOT, _git, md_table
from .report import BEATS_SOURCE as NO_BUILD_SOURCE     # rows whose cycles no build runs
from .scenes import P, SMALLER_P                          # the reports' P; the smaller P a build tries
from .scenes import place_command as scenes_place_command

#: the Fmax every build should reach at P = 8 where it fits (issue 56)
GOAL_MHZ = 130.0
REPORTS = REPO_ROOT / "reports"


@dataclass
class Need:
    """One build (options, widths, P) and the reports that need its Fmax."""

    p: int
    build: dict
    widths: dict
    users: dict = field(default_factory=dict)     # report -> how many frames or rows

    @property
    def key(self) -> tuple:
        return (self.p, tuple(sorted(self.build.items())), tuple(sorted(self.widths.items())))


def _add(needs: dict, p: int, build: dict, widths: dict, user: str) -> None:
    n = Need(p, dict(build), dict(widths))
    n = needs.setdefault(n.key, n)
    n.users[user] = n.users.get(user, 0) + 1


def _read(path: Path) -> dict | None:
    """A report's JSON, None when it is not there; UserError (one line) when it is unreadable."""
    if not path.exists():
        return None
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        raise UserError(f"{path.relative_to(REPO_ROOT)} is not JSON: rerun the report that writes it") from None


def _full(build: dict) -> dict:
    return {k: int(build.get(k, 0)) for k in BUILD_PARAMS}


def scene_needs(data: dict, needs: dict) -> None:
    """make scenes: every build it lists, at P = 8."""
    for rec in data.get("builds", []):
        _add(needs, P, _full(rec["build"]), rec["widths"], "scenes")


def report_needs(data: dict, needs: dict) -> None:
    """make report: each row's build at its P and word widths (rows no build runs left out)."""
    for r in data.get("rows", []):
        if not r.get("build") or r.get("cycles_source") == NO_BUILD_SOURCE:
            continue
        widths = Cube4Config(pipelines=r["pipelines"], voxel_bits=r["voxel_bits"], weight_bits=r["weight_bits"],
                             alpha_bits=r["alpha_bits"], acc_bits=r["acc_bits"], rmap_bits=r["rmap_bits"],
                             supersample=r["supersample"]).widths()
        _add(needs, int(r["pipelines"]), fmax_store.build_from_name(r["build"]), widths, "report")


def skipping_needs(data: dict, needs: dict) -> None:
    """make skipping: the build of each RTL frame of its beat section (box, beats, termination)."""
    default = Cube4Config(pipelines=P).widths()
    for f in data.get("rtl_beats") or []:
        _add(needs, P, _full(f.get("build", {})), f.get("widths") or default, "skipping")


def smaller_p_needs(needs: dict, measured: list) -> None:
    """A build that does not fit at P = 8 needs the largest smaller P that fits (the scenes
    report's figure): each smaller P measured, and the next one to try, down to the first that fits."""
    for n in [n for n in needs.values() if n.p == P]:
        m = fmax_store.lookup(measured, P, n.build, n.widths)
        if m is None or m.fits:
            continue
        for p in SMALLER_P:
            _add(needs, p, n.build, n.widths, "largest P that fits")
            s = fmax_store.lookup(measured, p, n.build, n.widths)
            if s is None or s.fits:
                break


def rtl_tree(commit: str) -> str:
    """The tree of rtl/ at ``commit`` ('' when git does not know it)."""
    return _git("rev-parse", "--verify", "--quiet", f"{commit}^{{commit}}:rtl") if commit else ""


def comments_only(commit: str, paths: tuple[str, ...] = ("rtl",)) -> bool:
    """Whether rtl/ (or ``paths`` in it) at ``commit`` and at HEAD differ in comments and
    blank lines only (every changed line, either side, empty or a `//` comment): the same
    logic."""
    diff = _git("diff", "--unified=0", commit, "HEAD", "--", *paths)
    changed = [ln[1:].strip() for ln in diff.splitlines()
               if ln[:1] in "+-" and not ln.startswith(("+++", "---"))]
    return bool(diff) and all(not t or t.startswith("//") for t in changed)


def changed_files(commit: str) -> set[str]:
    """The files of rtl/ that differ between ``commit`` and HEAD (both names of a rename)."""
    return set(_git("diff", "--no-renames", "--name-only", commit, "HEAD", "--", "rtl").split())


def rtl_age(commit: str, head_tree: str, files: tuple[str, ...] = ()) -> str:
    """'as now', 'as now but comments', 'as now in the files it reads' (``files``: the rtl/
    files the build reads; rtl/ changed elsewhere only), 'as now but comments in the files
    it reads', 'N commits to rtl/ since', or 'unknown'."""
    c = commit.split()[0]
    tree = rtl_tree(c)
    if not tree or " with uncommitted changes" in commit:
        return "unknown" if not tree else "uncommitted changes"
    if tree == head_tree:
        return "as now"
    if comments_only(c):
        return "as now but comments"
    if files:
        read = sorted(changed_files(c) & set(files))
        if not read:
            return "as now in the files it reads"
        if comments_only(c, tuple(read)):
            return "as now but comments in the files it reads"
    n = _git("rev-list", "--count", f"{c}..HEAD", "--", "rtl")
    return f"{n} commit{'s' if n != '1' else ''} to rtl/ since" if n else "other"


def place_command(n: Need) -> str:
    """The command that places and routes ``n`` (cube4_reports.scenes' naming of its report)."""
    return scenes_place_command(n.build, n.widths, n.p)


@dataclass
class Status:
    need: Need
    measured: fmax_store.Measured | None
    age: str

    @property
    def state(self) -> str:
        m = self.measured
        if m is None:
            return "not measured"
        if not m.fits:
            return "does not fit"
        return "measured"

    @property
    def current(self) -> bool:
        return self.measured is not None and self.age.startswith("as now")

    @property
    def below_goal(self) -> bool:
        m = self.measured
        return m is not None and m.fits and m.p == P and m.fmax_mhz < GOAL_MHZ


def statuses(needs: dict, measured: list) -> list[Status]:
    head_tree = rtl_tree("HEAD")
    out = []
    for n in needs.values():
        m = fmax_store.lookup(measured, n.p, n.build, n.widths)
        out.append(Status(n, m, rtl_age(m.rtl, head_tree, m.files) if m else ""))
    return sorted(out, key=lambda s: (s.need.p != P, -s.need.p, fmax_store.build_label(s.need.build, s.need.widths)))


def table(rows: list[Status]) -> str:
    body = []
    for s in rows:
        m = s.measured
        fmax = ("—" if m is None else "does not fit" if not m.fits else
                f"{m.fmax_mhz:.1f}" + (f" (below {GOAL_MHZ:.0f})" if s.below_goal else ""))
        seeds = ", ".join(f"{f:.1f}" for f in m.fmax_seeds) if m is not None and m.fits else ""
        body.append([fmax_store.build_label(s.need.build, s.need.widths), str(s.need.p), fmax, seeds,
                     m.rtl if m else "", s.age, ", ".join(f"{u} ({k})" for u, k in sorted(s.need.users.items())),
                     f"`{place_command(s.need)}`" if not s.current else ""])
    return md_table(["build", "P", "Fmax MHz (median)", "seeds", "RTL", "rtl/ since", "needed by (frames or rows)",
                     "to measure on today's rtl/"], body, "llrrllll")


def summary(rows: list[Status]) -> str:
    now = sum(s.current for s in rows)
    older = sum(s.measured is not None and not s.current for s in rows)
    none = sum(s.measured is None for s in rows)
    nofit = sum(s.state == "does not fit" for s in rows)
    below = [s for s in rows if s.below_goal]
    return (f"{len(rows)} builds: {now} placed and routed on today's rtl/ (or one that differs in comments "
            f"only, or only in files the build does not read), {older} on an older rtl/ "
            f"(or with uncommitted changes), {none} never; {nofit} of the measured do not fit the ECP5-85F at "
            f"their P. Below {GOAL_MHZ:.0f} MHz at P = {P}: "
            + (", ".join(f"{fmax_store.build_label(s.need.build, s.need.widths)} "
                         f"{s.measured.fmax_mhz:.1f}" for s in below) or "none") + ".")


def markdown(rows: list[Status]) -> str:
    head = _git("log", "-1", "--format=%h", "--", "rtl") or "unknown"
    return "\n".join([
        "# Place and route: which builds the reports need, and where each stands",
        "",
        f"Generated by `make fpga-status` (`python -m cube4_reports.fpga_status`) with rtl/ at commit {head}; "
        "do not edit. The builds are those whose Fmax reports/scenes.md, reports/error_vs_runtime.md and "
        "reports/skipping.md turn cycles into milliseconds with (their JSON), each looked up among the "
        "committed place-and-route results (reports/fpga*.json, reports/fpga/*.json) as those reports look "
        "it up; 'rtl/ since': whether rtl/ at the run's commit is today's tree ('as now but comments': "
        "it differs in comment and blank lines only; 'in the files it reads': rtl/ has changed since only "
        "in files that build does not read, by the list of files its synthesis read, "
        "`python -m cube4_reports.fpga_files`). Each run's own report names its paths and seeds.",
        "",
        summary(rows),
        "",
        table(rows),
        ""])


def collect(measured: list | None = None) -> list[Status]:
    measured = fmax_store.load() if measured is None else measured
    needs: dict = {}
    for name, reader in (("scenes.json", scene_needs), ("error_vs_runtime.json", report_needs),
                         ("skipping.json", skipping_needs)):
        data = _read(REPORTS / name)
        if data is not None:
            reader(data, needs)
    if not needs:
        raise UserError("no report JSON under reports/ (scenes.json, error_vs_runtime.json, skipping.json): "
                        "run make scenes, make report or make skipping first")
    smaller_p_needs(needs, measured)
    return statuses(needs, measured)


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    ap = argparse.ArgumentParser(prog="python -m cube4_reports.fpga_status",
                                 description=__doc__.splitlines()[0])
    ap.add_argument("--todo", action="store_true",
                    help="print only the commands of the builds not placed and routed on today's rtl/")
    ap.add_argument("--md", help="also write the table to this Markdown file (e.g. reports/fpga_status.md)")
    return ap.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    try:
        rows = collect()
    except UserError as e:
        print(f"fpga_status: {e}", file=sys.stderr)
        return 1
    if args.todo:
        for s in rows:
            if not s.current:
                print(place_command(s.need))
        return 0
    md = markdown(rows)
    print(md)
    if args.md:
        Path(args.md).write_text(md)
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""The measured Fmax of each build: what turns a frame's cycles into milliseconds.

Every place-and-route run that writes its Markdown into reports/ (``python -m
cube4_reports.fpga``, ``make fpga``) writes its figures beside it as JSON
(reports/fpga.json beside reports/fpga.md, reports/fpga_beats.json beside
reports/fpga_beats.md), and each of its results names its build whole: the build options
(cube4.builds, every one), the word widths (VOXEL_W .. MAX_SS_LOG2, cube4.config), P, and
the run's MAX_DIM, RTL commit, seeds and their median.

A report that gives a frame time looks up the build that runs the frame: the same options,
the same widths, the same P and the speed grade the reports use. Nothing else is borrowed:
a build with no such result has no frame time, and the report says it was not measured (or
that it was placed and routed and does not fit the part). MAX_DIM is not matched (a
frame's cycles do not depend on it; the chip is built for the largest volume it renders):
the result states its own. Where several results match, the one finished last counts.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

from cube4.builds import NAMED, build_name, complete_build, parse_options
from cube4.config import Cube4Config
from cube4.errors import UserError

from .markdown import REPO_ROOT

#: the committed results: reports/fpga.json, reports/fpga_beats.json, ..., and one per build
#: of make scenes in reports/fpga/ (python -m cube4_reports.scenes --place)
RESULT_GLOBS = ("fpga*.json", "fpga/*.json")
REPORTS = REPO_ROOT / "reports"


#: the speed grade every report's frame times are at (cube4_reports.fpga's default)
SPEED = 8


@dataclass(frozen=True)
class Measured:
    """One build's place and route: its Fmax, the median of its seeds (None: it does not
    fit the part, ``fits`` False)."""

    fmax_mhz: float | None
    p: int
    build: dict
    widths: dict
    seeds: tuple[int, ...]
    fmax_seeds: tuple[float, ...]
    max_dim: int
    rtl: str            # the RTL commit the run placed and routed
    source: str         # the JSON it came from, relative to the repository
    finished: str = ""  # UTC, "YYYY-MM-DD HH:MM" ("" in a run from before the field)
    luts: int | None = None  # the median seed's resources (cube4_reports.fpga)
    ffs: int | None = None
    dsps: int | None = None
    ebrs: int | None = None
    fits: bool = True
    speed: int = SPEED
    files: tuple[str, ...] = ()  # the rtl/ files the build reads (cube4_reports.fpga_files; () unknown)

    def note(self) -> str:
        """'113.1 MHz: BEATS=1, .. at P = 8, median of 3 seeds, RTL 605bf4b (reports/fpga_beats.json)'."""
        what = f"{self.fmax_mhz:.1f} MHz" if self.fits else "does not fit the ECP5-85F"
        return (f"{what}: {build_label(self.build, self.widths)} at P = {self.p}, MAX_DIM = {self.max_dim}, "
                f"median of {len(self.seeds)} seed{'s' if len(self.seeds) != 1 else ''}, RTL {self.rtl} "
                f"({self.source})")


def _rel(path: Path) -> str:
    return str(path.relative_to(REPO_ROOT)) if path.is_relative_to(REPO_ROOT) else str(path)


def _seed_fmax(seeds) -> tuple[float, ...]:
    """Each routed seed's Fmax, from cube4_reports.fpga's [{"seed", "fmax_mhz", ..}, ..]."""
    out = []
    for s in seeds:
        f = s.get("fmax_mhz") if isinstance(s, dict) else s
        if isinstance(f, (int, float)):
            out.append(float(f))
    return tuple(out)


def read_results(path: Path) -> list[Measured]:
    """The routed, fitting results of one fpga JSON that name their build whole; a result
    from before builds were named (no "build" or "widths") is left out: it cannot be
    matched to a build. UserError (one line) on a file that is not an fpga result."""
    try:
        data = json.loads(path.read_text())
        results = data["results"]
        if not isinstance(results, list):
            raise TypeError
    except (OSError, ValueError, KeyError, TypeError):
        raise UserError(f"{_rel(path)} is not a result of python -m cube4_reports.fpga "
                        "(expected {\"results\": [...]}): rerun it or delete the file") from None
    out = []
    for r in results:
        if not isinstance(r, dict) or not isinstance(r.get("build"), dict) or not isinstance(r.get("widths"), dict):
            continue        # a result from before builds were named: it matches no build
        fits = bool(r.get("fits", False))
        if fits and r.get("fmax_median") is None:
            continue        # a failed run: nothing measured
        try:
            build, p = complete_build(r["build"]), int(r["p"])
        except (UserError, KeyError, TypeError, ValueError):
            continue        # an option this version does not know: not a build it can run
        out.append(Measured(
            fmax_mhz=float(r["fmax_median"]) if fits else None, p=p, build=build, fits=fits,
            speed=int(data.get("speed", SPEED)),
            widths={k: int(v) for k, v in r["widths"].items()},
            seeds=tuple(int(s) for s in data.get("seeds", ())),
            fmax_seeds=_seed_fmax(r.get("fmax_seeds") or ()),
            max_dim=int(data.get("max_dim", 0)),
            rtl=str(data.get("rtl_commit", "unknown")) + (" with uncommitted changes" if data.get("rtl_modified") else ""),
            source=_rel(path), finished=str(data.get("finished", "")),
            files=tuple(str(f) for f in r.get("rtl_files") or ()),
            **{k: int(r[k]) for k in ("luts", "ffs", "dsps", "ebrs") if r.get(k) is not None}))
    return out


def load(paths: list[Path] | None = None) -> list[Measured]:
    """Every measured build in ``paths`` (default: the committed reports/fpga*.json and
    reports/fpga/*.json)."""
    paths = sorted(p for g in RESULT_GLOBS for p in REPORTS.glob(g)) if paths is None else paths
    return [m for p in paths for m in read_results(p)]


def lookup(measured: list[Measured], p: int, build: dict, widths: dict) -> Measured | None:
    """The place and route of exactly this build (options, widths, P, at speed grade
    SPEED), the latest finished (``fits`` False: it does not fit); None if it was never
    placed and routed."""
    want = complete_build(build)
    hits = [m for m in measured if m.p == p and m.build == want and m.widths == dict(widths) and m.speed == SPEED]
    return max(hits, key=lambda m: m.finished) if hits else None


def build_from_name(name: str) -> dict:
    """The build a build_name() gives back: 'full', another named build, or 'K=V, ..'."""
    if name in NAMED:
        return dict(NAMED[name])
    return complete_build(parse_options(name.replace(" ", ""), "a build's name"))


def widths_text(widths: dict) -> str:
    """The word widths that differ from cube4_top's defaults, 'MAX_SS_LOG2=2' ('' for none)."""
    default = Cube4Config().widths()
    return ", ".join(f"{k}={v}" for k, v in widths.items() if default.get(k) != v)


def build_label(build: dict, widths: dict | None = None) -> str:
    """A build's name with its word widths where they differ from the defaults:
    'EXTREMUM=0, CLIP=0, VGRAD=1 (MAX_SS_LOG2=2)'."""
    w = widths_text({**Cube4Config().widths(), **(widths or {})})
    return build_name(build) + (f" ({w})" if w else "")


def unmeasured_note(p: int, build: dict, widths: dict | None = None) -> str:
    """What a table says where a build has no measured Fmax."""
    return f"not measured ({build_label(build, widths)} at P = {p} was not placed and routed)"


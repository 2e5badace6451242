"""Error against run time: ``make report`` (``python -m cube4_reports.report``).

For every configuration (the default, then one parameter varied at a time: supersampling
S, weight bits W, accumulator bits F, pipelines p) and every volume/scene pair it

* renders the float64 reference once per volume/scene (it does not depend on the
  hardware configuration except VOXEL_W, which is not varied),
* renders the golden model (bit-exact integer model of the RTL) and measures the image
  error against the reference: RMSE, max |error| and PSNR over premultiplied RGBA,
* renders through the Verilated ``cube4_top`` (one build per parameter set, cached under
  build/sim) for the measured cycles and simulation seconds, and checks that its base
  plane equals the golden one bit for bit (``bit_exact``),
* converts cycles to a frame time at the measured Fmax of the build that runs the frame
  (its options, word widths and P; cube4_reports.fmax reads the place-and-route results
  committed under reports/), or says the build was not measured: no Fmax is borrowed.

Outputs: ``<out>/error_vs_runtime.{md,csv,png,json}`` (the JSON: the run's rows, from which
``--tables-only`` rewrites the rest; committed beside the tables so that a clone can);
the Verilator/cocotb output goes to build/reports/error_vs_runtime.log.

``--no-rtl`` takes the cycles from the formula of docs/architecture.md with the empty-space box's dims instead (marked
"formula"); ``--quick`` renders one volume and five configurations.
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import hashlib
import io
import json
import math
import os
import sys
import time
from collections.abc import Iterator
from dataclasses import asdict, dataclass, replace
from datetime import datetime, timezone
from pathlib import Path
from typing import Any, TextIO

import numpy as np

from cube4.app.labelmaps import with_labels
from cube4.app.render import render
from cube4.app.volumes import load_volume
from cube4.builds import build_name, check_build
from cube4.config import Cube4Config, resolve_build
from cube4.errors import UserError
from cube4.host import config_for, image_metrics
from cube4.scene import PRESETS, Scene, load_scene

from cube4_sim.engine import register as register_rtl_engine

from . import fmax as fmax_store
from .markdown import REPO_ROOT, git_state, md_table

REPORTS_BUILD = REPO_ROOT / "build" / "reports"
DEFAULT_OUT = REPO_ROOT / "reports"
STEM = "error_vs_runtime"

#: (volume, scene) pairs. 64³ (and 41³, same build size class) keeps the RTL runs short. The
#: phantoms, then two real MRIs that ship inside nibabel (the `mri` volume resampled to
#: 64×48×24, the `mri_t1` crop at its native 33×41×25).
CASES: tuple[tuple[str, str], ...] = (("sphere:64", "default"), ("head:64", "head"), ("ml:41", "ml"),
                                      ("mri:64,48,24", "mri_skin"), ("mri_t1", "mri_t1_tissue"))
QUICK_CASES: tuple[tuple[str, str], ...] = (("sphere:64", "default"),)
#: the classification features (docs/numerics.md §23, §24) on real content, each on the build
#: its scene gets: gradient-magnitude modulation on nibabel's MRI, labels on Colin27 with the
#: AAL lobes (its label map from the scene); the default and the sweeps that change their error
FEATURE_CASES: tuple[tuple[str, str], ...] = (("mri", "mri_boundaries"), ("colin", "colin_lobes"))
FEATURE_SWEEPS: dict[str, tuple] = {"supersample": (2, 4), "subpixel": (2,)}

#: Parameter sweeps, one parameter at a time from the scene's default configuration.
SWEEPS: dict[str, tuple] = {
    "supersample": (1, 2, 4),
    "weight_bits": (4, 6, 8, 10, 12),
    "acc_bits": (8, 12, 16, 24),
    "pipelines": (1, 2, 4, 8),
    "subpixel": (2, 3, 4),
    "filter": ("mitchell", "catmull-rom", "bspline", "lanczos3"),
    "gradient": ("central", "sobel"),
    "path_weights": (False, True),
    "preview": (2, 4),
    "tau": (0.0, 1 / 256, 1 / 32, 1 / 8),
}
#: Combinations of scene keys (S, q, gradient, warp) beside the one-at-a-time sweeps: the ways
#: to buy error with run time that need more than one key. "quality" is the named preset.
COMBOS: tuple[tuple[tuple[str, Any], ...], ...] = (
    (("gradient", "central"), ("supersample", 2)),
    (("gradient", "central"), ("supersample", 4)),
    (("gradient", "central"), ("supersample", 2), ("subpixel", 2)),
    tuple(PRESETS["quality"].items()),          # the quality preset: central, S = 4, q = 2
    (("gradient", "central"), ("supersample", 4), ("subpixel", 2), ("filter", "bspline")),
    (("gradient", "central"), ("supersample", 4), ("subpixel", 3)),
    (("gradient", "sobel"), ("supersample", 4), ("subpixel", 2)),
    (("supersample", 2), ("subpixel", 2)),
)
QUICK_COMBOS = COMBOS[3:4]
#: the named presets (cube4.scene.PRESETS) as report configurations
PRESET_COMBOS = {"quality": tuple(PRESETS["quality"].items())}
QUICK_SWEEPS: dict[str, tuple] = {
    "supersample": (2,),
    "weight_bits": (4,),
    "acc_bits": (8,),
    "pipelines": (1,),
    "subpixel": (2,),
    "filter": ("mitchell",),
    "gradient": ("sobel",),
    "path_weights": (True,),
    "preview": (2,),
    "tau": (1 / 32,),
}
SHORT = {"supersample": "S", "weight_bits": "W", "acc_bits": "F", "pipelines": "p", "subpixel": "q",
         "filter": "warp", "gradient": "grad", "path_weights": "pw", "preview": "preview", "tau": "beats τ"}
#: sweeps of a scene key (the render's, not the hardware's configuration); "tau" renders
#: with beat skipping and ray termination at that threshold (skip = "beats", cube4.beats),
#: on the beat build (BEATS = 1) where one exists for the configuration
SCENE_SWEEPS = ("subpixel", "filter", "gradient", "path_weights", "preview", "tau")
#: the cycles source of a "tau" row with no beat build (its cycles: the golden schedule's beats)
BEATS_SOURCE = "golden beat walk (no build)"
#: the frame-time cell of a row whose build has no measured Fmax
NA_FMAX = "not measured"


@dataclass(frozen=True)
class Variant:
    """One configuration: the default, or one parameter changed from it."""

    varied: str  # "default", a SWEEPS key, or "combo" (value: COMBOS entry)
    value: Any

    @property
    def label(self) -> str:
        if self.varied == "combo":
            name = next((f"{k}: " for k, v in PRESET_COMBOS.items() if v == self.value), "")
            return name + " ".join(f"{SHORT[k]}={v}" for k, v in self.value)
        if self.varied == "tau":
            return f"beats τ={self.value:.4g}"
        return "default" if self.varied == "default" else f"{SHORT[self.varied]}={self.value}"

    def config(self, scene: Scene) -> Cube4Config:
        if self.varied == "combo":
            return config_for(self.scene(scene))
        if self.varied == "default" or self.varied in SCENE_SWEEPS:
            return config_for(scene)
        return config_for(scene, **{self.varied: self.value})

    def scene(self, scene: Scene) -> Scene:
        """The scene this variant renders (a scene sweep or a combination changes its keys)."""
        if self.varied == "combo":
            return replace(scene, **dict(self.value))
        if self.varied == "tau":
            return replace(scene, skip="beats", tau=float(self.value))
        if self.varied == "supersample":    # the scene's S (its default schedule: the beat schedule at every S)
            return replace(scene, supersample=self.value)
        return replace(scene, **{self.varied: self.value}) if self.varied in SCENE_SWEEPS else scene


@dataclass
class Row:
    """One (volume/scene, configuration) result; every number comes from a run."""

    volume: str
    scene: str
    varied: str
    label: str
    pipelines: int
    weight_bits: int
    acc_bits: int
    supersample: int
    voxel_bits: int
    alpha_bits: int
    rmap_bits: int
    rmse: float
    max_abs: float
    psnr: float
    rmse_rgb: float  # RMSE over R, G, B only (shading and colour)
    rmse_alpha: float  # RMSE over A only (opacity, compositing)
    golden_wall_s: float
    formula_cycles: int
    cycles: int | None = None
    cycles_source: str = "formula"  # "rtl", "formula", or "formula (RTL failed)"
    sim_wall_s: float | None = None
    sim_cycles_per_s: float | None = None
    rtl_wall_s: float | None = None  # whole RTL render incl. build check/build, packing, warp
    bit_exact: bool | None = None  # RTL base plane == golden base plane
    rtl_psnr: float | None = None
    rtl_error: str | None = None
    build: str = ""  # the build that runs the frame (cube4.builds.build_name; "" in a run from before)
    fmax_mhz: float | None = None  # that build's measured Fmax at these widths and p (cube4_reports.fmax)
    fmax_source: str | None = None  # where it was measured (fmax.Measured.note), or why there is none
    frame_time_ms: float | None = None
    d_psnr_db: float | None = None  # PSNR - PSNR of the default configuration
    cycles_ratio: float | None = None  # cycles / cycles of the default configuration
    baseplane_sha: str = ""  # identifies identical golden base planes (e.g. across p)
    subpixel: int = 1  # q: q×q sub-pixel passes per view
    filter: str = "triangle"  # the warp's filter
    gradient: str = "gra"  # the gradient estimator ([render] gradient)
    path_weights: bool = False  # [render] path_weights (numerics.md §17)
    preview: int = 1  # [render] preview: the level rendered (numerics.md §20)
    tau: float | None = None  # beat skipping's termination threshold (None: the box schedule)


# ---------------------------------------------------------------------------- configs
def variants(quick: bool) -> list[Variant]:
    """The default first, then each sweep value (the default's own value is skipped per
    scene in `case_variants`)."""
    sweeps = QUICK_SWEEPS if quick else SWEEPS
    return ([Variant("default", None)] + [Variant(k, v) for k, vals in sweeps.items() for v in vals]
            + [Variant("combo", c) for c in (QUICK_COMBOS if quick else COMBOS)])


def feature_variants() -> list[Variant]:
    """The classification features' configurations: the default, then FEATURE_SWEEPS."""
    return [Variant("default", None)] + [Variant(k, v) for k, vals in FEATURE_SWEEPS.items() for v in vals]


def case_volume(volume: str, scene: Scene, voxel_bits: int) -> np.ndarray:
    """A case's volume: with labels the labelled words of the scene's label map."""
    return with_labels(load_volume(volume, voxel_bits=voxel_bits), volume, scene, voxel_bits)


def case_variants(scene: Scene, all_variants: list[Variant]) -> list[tuple[Variant, Cube4Config]]:
    """Variants with their configurations, dropping those equal to the default."""
    default = config_for(scene)
    out: list[tuple[Variant, Cube4Config]] = []
    for v in all_variants:
        cfg = v.config(scene)
        if v.varied not in ("default", "combo") and v.varied not in SCENE_SWEEPS and cfg == default:
            continue
        out.append((v, cfg))
    return out


# ------------------------------------------------------------------------------- Fmax
def _rel(path: Path) -> Path:
    return path.relative_to(REPO_ROOT) if path.is_relative_to(REPO_ROOT) else path


def row_widths(r: Row) -> dict[str, int]:
    """The row's word widths as cube4_top's parameters."""
    return Cube4Config(pipelines=r.pipelines, voxel_bits=r.voxel_bits, weight_bits=r.weight_bits,
                       alpha_bits=r.alpha_bits, acc_bits=r.acc_bits, rmap_bits=r.rmap_bits,
                       supersample=r.supersample).widths()


def fmax_note(rows: list[Row], measured: list[fmax_store.Measured]) -> str:
    """Which measured builds the frame times use, for the Markdown report."""
    used = sorted({r.fmax_source for r in rows if r.fmax_mhz is not None or "does not fit" in (r.fmax_source or "")})
    missing = len([r for r in rows if r.fmax_mhz is None and "does not fit" not in (r.fmax_source or "")])
    if not measured:
        head = ("no build has a measured Fmax (no place-and-route result under reports/: "
                "`python -m cube4_reports.fpga --build ... --md reports/fpga_<name>.md` writes one)")
    else:
        head = ("the Fmax of the build that runs the row, at its word widths and p, median of the seeds "
                "placed and routed (`python -m cube4_reports.fpga`; its JSON beside its report in reports/)")
    text = head + (": " + "; ".join(used) if used else "")
    if missing:
        text += (f". {missing} of {len(rows)} rows run on a build that was never placed and routed: no "
                 "frame time (\"not measured\"), none borrowed from another build")
    return text


# ---------------------------------------------------------------------------- running
@contextlib.contextmanager
def output_to(log: TextIO) -> Iterator[None]:
    """Send file descriptors 1 and 2 (Verilator, make, cocotb, simulator) to the log."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = os.dup(1), os.dup(2)
    log.flush()
    try:
        os.dup2(log.fileno(), 1)
        os.dup2(log.fileno(), 2)
        yield
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        os.close(saved[0])
        os.close(saved[1])


def _sha(a: np.ndarray) -> str:
    return hashlib.sha1(np.ascontiguousarray(a).tobytes()).hexdigest()[:12]


def golden_row(vol: np.ndarray, volume: str, scene: Scene, variant: Variant, cfg: Cube4Config,
               ref_img: np.ndarray) -> tuple[Row, np.ndarray]:
    """Golden render and its error; returns the row and the golden base plane."""
    res = render(vol, scene, cfg, "golden")
    m = image_metrics(res.image, ref_img)
    err = res.image - ref_img
    d = cfg.as_dict()
    row = Row(volume=volume, scene=scene.name, varied=variant.varied, label=variant.label,
              pipelines=d["pipelines"], weight_bits=d["weight_bits"], acc_bits=d["acc_bits"],
              supersample=d["supersample"], voxel_bits=d["voxel_bits"], alpha_bits=d["alpha_bits"],
              rmap_bits=d["rmap_bits"], rmse=m["rmse"], max_abs=m["max_abs"], psnr=m["psnr"],
              rmse_rgb=float(np.sqrt(np.mean(err[..., :3] ** 2))), rmse_alpha=float(np.sqrt(np.mean(err[..., 3] ** 2))),
              golden_wall_s=res.wall_s, formula_cycles=int(res.stats["predicted_cycles"]),
              baseplane_sha=_sha(res.frame.baseplane), subpixel=scene.subpixel, filter=scene.filter,
              gradient=scene.gradient, path_weights=scene.path_weighted, preview=scene.preview,
              tau=scene.tau if scene.schedule == "beats" else None, build=build_name(resolve_build(cfg, [scene])))
    # (the build's options; its word widths are the row's S, W, F .. columns)
    if row.tau is not None:     # the beat schedule: its cycles are measured, the golden walk's beats stand in
        row.formula_cycles = int(res.stats["beats"]["walk_beats"])
    return row, res.frame.baseplane


def has_build(scene: Scene, cfg: Cube4Config) -> bool:
    """Whether the RTL has a build for this scene at these widths (cube4.builds.RULES)."""
    try:
        check_build(resolve_build(cfg, [scene]), cfg.widths())
    except UserError:
        return False
    return True


def add_rtl(row: Row, vol: np.ndarray, scene: Scene, cfg: Cube4Config, golden_base: np.ndarray,
            ref_img: np.ndarray, log: TextIO) -> None:
    """Render through the RTL; fill cycles, simulation time and the bit-exactness check.
    A failure is recorded in the row (rtl_error), not raised."""
    try:
        with output_to(log):
            res = render(vol, scene, cfg, "rtl")
    except Exception as e:  # noqa: BLE001 - any build/simulation failure is reported in the table
        row.rtl_error = (str(e).strip().splitlines() or [type(e).__name__])[0][:200]
        row.cycles, row.cycles_source = row.formula_cycles, "formula (RTL failed)"
        return
    st = res.stats
    row.cycles, row.cycles_source = int(st["cycles"]), "rtl"
    row.sim_wall_s = float(st["sim_wall_s"])
    row.sim_cycles_per_s = st["sim_cycles_per_s"]
    row.rtl_wall_s = res.wall_s
    row.bit_exact = bool(np.array_equal(res.frame.baseplane, golden_base))
    row.rtl_psnr = image_metrics(res.image, ref_img)["psnr"]


def finish_rows(rows: list[Row], measured: list[fmax_store.Measured]) -> None:
    """Frame time at the measured Fmax of each row's own build, and PSNR / cycles relative
    to each case's default."""
    defaults = {(r.volume, r.scene): r for r in rows if r.varied == "default"}
    for r in rows:
        r.fmax_mhz, r.frame_time_ms = None, None
        if not r.build:
            r.fmax_source = "the run named no build"
        elif r.cycles_source == BEATS_SOURCE:
            r.fmax_source = "no build runs it"
        else:
            build = fmax_store.build_from_name(r.build)
            m = fmax_store.lookup(measured, r.pipelines, build, row_widths(r))
            r.fmax_mhz, r.fmax_source = ((m.fmax_mhz, m.note()) if m else
                                         (None, fmax_store.unmeasured_note(r.pipelines, build, row_widths(r))))
        # a frame time for cycles the build runs: measured, or the formula of a --no-rtl run
        # (not the formula standing in for a failed RTL run, nor the beat walk's beats)
        if r.fmax_mhz and r.cycles is not None and r.cycles_source in ("rtl", "formula"):
            r.frame_time_ms = r.cycles / (r.fmax_mhz * 1e6) * 1e3
        base = defaults.get((r.volume, r.scene))
        if base is not None:
            r.d_psnr_db = r.psnr - base.psnr
            if r.cycles is not None and base.cycles:
                r.cycles_ratio = r.cycles / base.cycles


# ---------------------------------------------------------------------------- writing
def _f(x: float | None, fmt: str, none: str = "n/a") -> str:
    if x is None:
        return none
    if isinstance(x, float) and math.isinf(x):
        return "inf"
    return format(x, fmt)


def _bit_exact_text(r: Row) -> str:
    if r.rtl_error:
        return f"RTL failed: {r.rtl_error}"
    if r.bit_exact is None:
        return "n/a (no RTL)"
    return "yes" if r.bit_exact else f"**NO** (RTL PSNR {_f(r.rtl_psnr, '.2f')} dB)"


def _param_cells(r: Row) -> list[str]:
    cells = []
    combo = dict(COMBOS_BY_LABEL.get(r.label, ()))
    for key in ("supersample", "weight_bits", "acc_bits", "pipelines", "subpixel", "filter", "gradient",
                "path_weights", "preview", "tau"):
        v = {True: "yes", False: "no"}.get(getattr(r, key), str(getattr(r, key))) if key == "path_weights" \
            else "–" if key == "tau" and r.tau is None else f"{r.tau:.4g}" if key == "tau" else str(getattr(r, key))
        cells.append(f"**{v}**" if r.varied == key or key in combo else v)
    return cells


COMBOS_BY_LABEL = {Variant("combo", c).label: c for c in COMBOS}
TABLE_HEADERS = ["config", "S", "W", "F", "p", "q", "warp", "gradient", "path weights", "preview", "τ", "RMSE", "max \\|err\\|", "PSNR (dB)", "ΔPSNR (dB)", "cycles",
                 "× cycles", "source", "build", "frame time (ms) at its Fmax", "sim (s)", "sim cycles/s", "bit_exact"]


def frame_text(r: Row, fmt: str = ".4f") -> str:
    """'0.1234 @ 113.1 MHz', or why there is no frame time."""
    if r.frame_time_ms is not None:
        return f"{r.frame_time_ms:{fmt}} @ {r.fmax_mhz:.1f} MHz"
    if r.cycles_source == BEATS_SOURCE:
        return "no build"
    if r.fmax_mhz is not None:
        return f"none ({r.cycles_source} cycles)"
    return "does not fit" if r.fmax_source and "does not fit" in r.fmax_source else NA_FMAX


def markdown_table(rows: list[Row]) -> str:
    cells = []
    for r in rows:
        cells.append([
            r.label, *_param_cells(r), _f(r.rmse, ".5f"), _f(r.max_abs, ".3f"), _f(r.psnr, ".2f"),
            _f(r.d_psnr_db, "+.2f"), _f(r.cycles, ","), _f(r.cycles_ratio, ".2f"), r.cycles_source,
            r.build or "n/a", frame_text(r),
            _f(r.sim_wall_s, ".2f"), _f(r.sim_cycles_per_s, ",.0f"), _bit_exact_text(r),
        ])
    return md_table(TABLE_HEADERS, cells, "l" * len(TABLE_HEADERS))


def p_invariance_note(rows: list[Row]) -> list[str]:
    """Whether the golden base planes (and so the errors) are identical across p."""
    notes = []
    for (vol, scn) in dict.fromkeys((r.volume, r.scene) for r in rows):
        ps = [r for r in rows if (r.volume, r.scene) == (vol, scn) and r.varied in ("default", "pipelines")]
        if len(ps) < 2:
            continue
        same = len({r.baseplane_sha for r in ps}) == 1
        plist = ", ".join(str(r.pipelines) for r in sorted(ps, key=lambda r: r.pipelines))
        notes.append(f"- {vol} / {scn}: golden base planes for p = {plist} are "
                     f"{'byte-identical' if same else '**not identical**'}, so their errors are "
                     f"{'identical' if same else 'not identical'}.")
    return notes


def write_markdown(path: Path, rows: list[Row], meta: dict) -> None:
    out = io.StringIO()
    out.write("# Error against run time\n\n")
    out.write(f"Generated by `{meta['command']}` on {meta['finished']} in {meta['wall_s'] / 60:.1f} min "
              f"(commit {meta['git']['commit']}{', uncommitted changes in rtl/ or sim/hdl/' if meta['git']['rtl_dirty'] else ''}). "
              f"{'Tables and plot rewritten from that run (`--tables-only`, current Fmax) on ' + meta['tables_rewritten'] + '. ' if meta.get('tables_rewritten') else ''}"
              "Do not edit: rerun `make report`. Explained in [docs/reports.md](../docs/reports.md#error-against-run-time).\n\n")
    out.write(f"![PSNR against cycles and against milliseconds per frame]({STEM}.png)\n\n")
    out.write(budget_section(rows))
    d = next((r for r in rows if r.varied == "default"), rows[0])
    out.write(f"Each configuration is the default (`S = {d.supersample}, W = {d.weight_bits}, F = {d.acc_bits}, "
              f"p = {d.pipelines}`, V = {d.voxel_bits}, AW = {d.alpha_bits}, RMAP_BITS = {d.rmap_bits}) "
              "with one parameter changed (**bold**). Error: golden model image against the float64 reference's "
              "area truth (each pixel the mean of the picture over its square; docs/numerics.md §10), "
              "over the premultiplied RGBA of the 256×256 image (PSNR peak 1.0). "
              f"Cycles: {meta['cycles_note']}. Frame time = cycles / Fmax; {meta['fmax_note']}. "
              "sim (s): wall-clock seconds of the Verilator simulation of the frame alone "
              f"(machine load average {meta['loadavg_start']} at the start, {meta['loadavg_end']} at the end). "
              "bit_exact: the RTL base plane equals the golden one. "
              "`preview`: the scene rendered from its ½ or ¼ level (docs/numerics.md §20) through the RTL, its error "
              "against the whole volume's truth. `beats τ`: beat skipping and ray termination at transmittance τ "
              "(docs/numerics.md §19) on the beat build (BEATS = 1); where a configuration has no such "
              f"build its cycles are the front end's beats in the golden schedule (source `{BEATS_SOURCE}`), "
              "with no frame time. build: the build that runs the row (cube4.builds; the scene's smallest). "
              "The classification features on real content, each on the build its scene gets: "
              "`mri_boundaries` (gradient-magnitude modulation, docs/numerics.md §23; a GMOD build) and "
              "`colin_lobes` (labels, §24: the Colin27 T1 with the AAL atlas folded into lobes; a LABELS "
              f"build), with the sweeps {', '.join(FEATURE_SWEEPS)} only.\n\n")
    for (vol, scn) in dict.fromkeys((r.volume, r.scene) for r in rows):
        rs = [r for r in rows if (r.volume, r.scene) == (vol, scn)]
        out.write(f"## {vol}, scene `{scn}`\n\n")
        out.write(markdown_table(rs) + "\n\n")
        front = pareto([r for r in rs if r.cycles is not None])
        out.write("Non-dominated (no configuration is faster and at least as good): "
                  + ", ".join(f"{r.label} ({r.psnr:.2f} dB, {r.cycles:,} cycles)" for r in front) + ".\n\n")
    out.write(truth_section(meta.get("truth", {})))
    out.write(axis_section(meta.get("axis", [])))
    out.write(presets_section(rows))
    out.write(angle_section(load_angles()))
    notes = p_invariance_note(rows)
    failed = [r for r in rows if r.rtl_error]
    mismatched = [r for r in rows if r.bit_exact is False]
    out.write("## Checks\n\n")
    out.write("\n".join(notes) + ("\n" if notes else ""))
    if meta["rtl"]:
        built = [r for r in rows if r.tau is None]
        out.write(f"- RTL runs: {sum(r.cycles_source == 'rtl' for r in rows)} of {len(built)} succeeded "
                  f"(the {len(rows) - len(built)} rows of beat skipping, which no RTL runs, not tried); "
                  f"{len(mismatched)} base-plane mismatches against golden.\n")
        for r in failed:
            out.write(f"- RTL failed for {r.volume} {r.label}: {r.rtl_error}\n")
        ok = [r for r in rows if r.cycles_source == "rtl"]
        if ok:
            dev = [r.cycles - r.formula_cycles for r in ok]
            out.write(f"- Measured cycles minus the formula of docs/architecture.md with the empty-space box's dims: {min(dev):+d} .. {max(dev):+d}.\n")
    path.write_text(out.getvalue())


#: Views exactly along each axis against views tilted by AXIS_TILT_DEG (issue: the outline
#: on axis views): (volume, scene) pairs.
AXIS_CASES: tuple[tuple[str, str], ...] = (("head:24", "head"), ("sphere:24", "default"))
AXIS_TILT_DEG = 3.0


def _tilted(axis: np.ndarray, deg: float) -> np.ndarray:
    """The axis direction turned by deg towards the sum of the other two axes."""
    other = np.ones(3) - np.abs(axis)
    other /= np.linalg.norm(other)
    t = np.radians(deg)
    return np.cos(t) * axis + np.sin(t) * other


def axis_rows() -> list[dict]:
    """Golden model against both truths, for a view exactly along each axis and one tilted
    by AXIS_TILT_DEG from it, in the default configuration and with the quality preset
    (the truths are rendered once per view and shared)."""
    from cube4.scene import apply_preset, with_view

    out = []
    for vol_name, scn in AXIS_CASES:
        base = load_scene(scn)
        cfg = config_for(base)
        vol = load_volume(vol_name, voxel_bits=cfg.voxel_bits)
        qual = apply_preset(base, "quality")
        qcfg = config_for(qual)
        for n, sign in ((0, 1), (0, -1), (1, 1), (1, -1), (2, 1), (2, -1)):
            axis = np.zeros(3)
            axis[n] = sign
            row = {"volume": vol_name, "scene": scn, "axis": f"{'+' if sign > 0 else '-'}{'xyz'[n]}"}
            for key, d in (("axis", axis), ("tilted", _tilted(axis, AXIS_TILT_DEG))):
                sc = with_view(base, d.tolist())
                area = render(vol, sc, cfg, "reference").image
                point = render(vol, sc, cfg, "reference-point").image
                g = render(vol, sc, cfg, "golden").image
                row[f"{key}_area"] = image_metrics(g, area)["psnr"]
                row[f"{key}_point"] = image_metrics(g, point)["psnr"]
                gq = render(vol, with_view(qual, d.tolist()), qcfg, "golden").image
                row[f"{key}_quality"] = image_metrics(gq, area)["psnr"]
            out.append(row)
    return out


def axis_section(rows: list[dict]) -> str:
    """The axis-view table: PSNR along each axis and tilted, against both truths, and with
    the quality preset against the area truth."""
    if not rows:
        return ""
    body = []
    for r in rows:
        q = (f"{r['axis_quality']:.2f} | {r['tilted_quality']:.2f} | {r['axis_quality'] - r['tilted_quality']:+.2f}"
             if "axis_quality" in r else "not run | not run | —")     # a run from before the quality columns
        body.append(f"| {r['volume']}, `{r['scene']}` | {r['axis']} | {r['axis_area']:.2f} | {r['tilted_area']:.2f} | "
                    f"{r['axis_area'] - r['tilted_area']:+.2f} | {r['axis_point']:.2f} | {r['tilted_point']:.2f} | "
                    f"{r['axis_point'] - r['tilted_point']:+.2f} | {q} |")
    worst = min(r["axis_area"] - r["tilted_area"] for r in rows)
    qs = [r["axis_quality"] - r["tilted_quality"] for r in rows if "axis_quality" in r]
    worst_q = f"{min(qs):+.2f} dB" if qs else "not run"
    return ("## Views along an axis\n\n"
            f"The golden model against the area truth and the point-sampled one, for a view exactly along each axis and "
            f"one turned {AXIS_TILT_DEG:g}° from it towards the other two axes (the goal: the axis view within 2 dB of "
            f"the tilted one). The worst difference against the area truth is {worst:+.2f} dB in the default "
            f"configuration and {worst_q} with the quality preset. Why the default loses along an axis: "
            "[docs/numerics.md §11c](../docs/numerics.md).\n\n"
            "| volume | axis | default, along it (area) | tilted (area) | difference | along it (point) | tilted (point) | "
            "difference | quality, along it (area) | tilted (area) | difference |\n"
            "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n" + "\n".join(body) + "\n\n")


def budget_section(rows: list[Row]) -> str:
    """One line per volume: which configuration to use for a budget of cycles per frame
    (the non-dominated front: the best error that fits each budget)."""
    lines = ["## Which configuration for a budget", "",
             "For each volume, the non-dominated configurations in order of cycles per frame: with a budget of "
             "at least that many cycles, that one gives the best error of all configurations measured; then the "
             "same in milliseconds per frame (cycles / the measured Fmax of the build that runs it) among the "
             "configurations whose build was placed and routed.", ""]
    for (vol, scn) in dict.fromkeys((r.volume, r.scene) for r in rows):
        rs = [r for r in rows if (r.volume, r.scene) == (vol, scn)]
        front = pareto([r for r in rs if r.cycles is not None])
        if not front:
            continue
        steps = "; ".join(f"≥ {r.cycles:,} cycles: {r.label} ({r.psnr:.2f} dB)" for r in front)
        best = max(r.psnr for r in front)
        lines.append(f"- **{vol}, `{scn}`** (best {best:.2f} dB{'' if best >= GOAL_PSNR else ', below the 40 dB goal'}): "
                     + steps)
        timed = [r for r in rs if r.frame_time_ms is not None]
        if timed:
            ms = "; ".join(f"≥ {r.frame_time_ms:.3f} ms: {r.label} ({r.psnr:.2f} dB, {r.fmax_mhz:.1f} MHz)"
                           for r in pareto_ms(timed))
            lines.append(f"  - in time ({len(timed)} of {len(rs)} configurations on a measured build): {ms}")
        else:
            lines.append(f"  - in time: none of its {len(rs)} configurations runs on a build with a measured Fmax")
    return "\n".join(lines) + "\n\n"


def truth_section(truth: dict) -> str:
    """How the area truth converged on each volume."""
    if not truth:
        return ""
    lines = ["## The truth", "",
             "The reference of every table is the area truth (docs/numerics.md §10): k × k rays per pixel, k = 1, "
             "3, 9, refined where the picture is not flat, until the RMS change the next k would make (estimated by casting "
             "it for 2,048 of the refined pixels) is at most 2⁻⁹. Per volume, each step's k, the share of pixels it "
             "cast, the RMS change it made and the estimate for the next k; the seconds the truth took:", ""]
    for name, t in truth.items():
        lines.append(f"- {name}: {t['truth_steps']}; {t['wall_s']:.0f} s.")
    return "\n".join(lines) + "\n\n"


GOAL_PSNR = 40.0
#: The gradient-angle error of the bit-exact model's estimators on sphere:64, as the research
#: prototype stored it (reports/gradient_research.md): the report reads it, it measures nothing.
ANGLES_JSON = DEFAULT_OUT / "gradient_research" / "model_angles.json"
ANGLES_COMMAND = ('python scripts/research/gradients.py --est gra,vgrad_central,vgrad_sobel '
                  '--views "0,0,1;0.3,-0.45,1;1,1,1;1,0.5,0.2;-0.6,0.25,-1;0.5,0.5,1" '
                  '--json reports/gradient_research/model_angles.json')


def load_angles(path: Path | None = None) -> list[dict]:
    """The stored angle rows (ANGLES_JSON): estimator, view, S, mean and max angle (degrees)."""
    path = path or ANGLES_JSON
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError) as e:
        raise UserError(f"cannot read the stored gradient angles {_rel(path)} ({e}); `{ANGLES_COMMAND}` "
                        "writes them") from None


def presets_section(rows: list[Row]) -> str:
    """The two named presets per case: PSNR, cycles and frame time, and whether the quality
    preset reaches the 40 dB goal on every case."""
    quality = Variant("combo", PRESET_COMBOS["quality"]).label
    cells, reached = [], []
    for (vol, scn) in dict.fromkeys((r.volume, r.scene) for r in rows):
        for name, label in (("default", "default"), ("quality", quality)):
            r = next((r for r in rows if (r.volume, r.scene, r.label) == (vol, scn, label)), None)
            if r is None:
                continue
            cells.append([f"{vol}, `{scn}`", name, _f(r.psnr, ".2f"), _f(r.cycles, ","), r.build or "n/a",
                          frame_text(r, ".3f")])
            if name == "quality":
                reached.append(r.psnr >= GOAL_PSNR)
    if not cells:
        return ""
    text = ("## Presets\n\n`cube4 render --preset default` renders the scene as it is; `--preset quality` sets "
            "`[render] gradient = \"central\"` (voxel central differences, docs/numerics.md §5b), "
            "`supersample = 4`, `subpixel = 2` and `path_weights = true` (docs/numerics.md §17; the built-in "
            "scene `head_quality` is the head with it). The scene `ml` has path weights on by default: "
            "Marschner–Lobb reaches the volume's faces. "
            "Frame time: cycles / the measured Fmax of the build that runs it (\"not measured\": that build "
            "was never placed and routed).\n\n")
    text += md_table(["case", "preset", "PSNR (dB)", "cycles", "build", "frame time (ms)"], cells, "llrrll") + "\n\n"
    if reached:
        text += (f"The quality preset reaches {GOAL_PSNR:.0f} dB on {sum(reached)} of {len(reached)} cases"
                 + (" (all)" if all(reached) else "") + ".\n\n")
    return text


def angle_section(angles: list[dict]) -> str:
    """The gradient-angle table: mean angle to the analytic sphere's normals per estimator and S
    over the views, with the worst view."""
    ests = list(dict.fromkeys(a["estimator"] for a in angles))
    ss = sorted({a["S"] for a in angles})
    views = list(dict.fromkeys(tuple(a["view"]) for a in angles))
    cells = []
    for e in ests:
        sel = [a for a in angles if a["estimator"] == e]
        worst = max(sel, key=lambda a: a["mean"])
        cells.append([f"`{e}`", *(f"{np.mean([a['mean'] for a in sel if a['S'] == S]):.2f}" for S in ss),
                      f"{worst['mean']:.2f} at {_view_text(worst['view'])}, S = {worst['S']}",
                      f"{max(a['max'] for a in sel):.1f}"])
    text = ("## Gradient angle error\n\nMean angle (degrees) between each estimator's gradient and the "
            "analytic normal of sphere:64, over the inside samples within half a voxel of the surface, "
            f"averaged over the views {', '.join(_view_text(v) for v in views)} "
            "(`gra`: the paper's GRA; `vgrad_central`, `vgrad_sobel`: `[render] gradient = central / sobel`, "
            f"the bit-exact model), as stored in {_rel(ANGLES_JSON)} by the research prototype "
            "(reports/gradient_research.md, which measures more estimators).\n\n")
    return text + md_table(["estimator", *(f"S = {S}" for S in ss), "worst view mean", "largest"], cells,
                           "l" + "r" * (len(ss) + 2)) + "\n\n"


def _view_text(view) -> str:
    return "(" + ", ".join(f"{c:g}" for c in view) + ")"


def write_csv(path: Path, rows: list[Row]) -> None:
    names = list(asdict(rows[0]))
    with path.open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=names)
        w.writeheader()
        for r in rows:
            d = asdict(r)
            w.writerow({k: ("" if v is None else v) for k, v in d.items()})


def _json_safe(x: Any) -> Any:
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, dict):
        return {k: _json_safe(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_json_safe(v) for v in x]
    return x


def write_json(path: Path, rows: list[Row], meta: dict) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    data = {"meta": meta, "rows": [asdict(r) for r in rows]}
    path.write_text(json.dumps(_json_safe(data), indent=1, allow_nan=False) + "\n")


SERIES_STYLE = {  # marker, colour
    "supersample": ("o", "tab:blue"),
    "pipelines": ("D", "tab:purple"),
    "weight_bits": ("s", "tab:green"),
    "acc_bits": ("^", "tab:red"),
    "subpixel": ("v", "tab:orange"),
    "filter": ("P", "tab:brown"),
    "gradient": ("X", "tab:cyan"),
    "path_weights": ("h", "tab:olive"),
    "preview": ("<", "tab:pink"),
    "tau": (">", "tab:gray"),
}


def pareto(rs: list[Row]) -> list[Row]:
    """The non-dominated rows in (cycles, PSNR): no other row has fewer or equal cycles and a
    higher PSNR (or equal PSNR and fewer cycles); ordered by cycles."""
    front: list[Row] = []
    for r in sorted(rs, key=lambda r: (r.cycles, -r.psnr)):
        if not front or r.psnr > front[-1].psnr:
            front.append(r)
    return front


def pareto_ms(rs: list[Row]) -> list[Row]:
    """The non-dominated rows in (milliseconds per frame, PSNR), among rows with a frame time."""
    front: list[Row] = []
    for r in sorted((r for r in rs if r.frame_time_ms is not None), key=lambda r: (r.frame_time_ms, -r.psnr)):
        if not front or r.psnr > front[-1].psnr:
            front.append(r)
    return front


def _plot_time(ax: Any, rs: list[Row]) -> None:
    """PSNR against milliseconds per frame, for the rows whose build has a measured Fmax
    (each point labelled), the non-dominated ones joined; the others are counted, not drawn."""
    timed = [r for r in rs if r.frame_time_ms is not None]
    ax.set_ylabel("PSNR vs float64 reference (dB)")
    ax.set_xlabel("milliseconds per frame (cycles / the measured Fmax of the row's build)")
    ax.grid(True, which="both", alpha=0.3)
    if not timed:
        ax.text(0.5, 0.5, f"none of the {len(rs)} configurations\nruns on a build with a measured Fmax",
                ha="center", va="center", transform=ax.transAxes, fontsize=9)
        return
    for key, (marker, colour) in SERIES_STYLE.items():
        pts = [r for r in timed if r.varied == key or (key == "gradient" and r.varied == "combo")]
        if pts:
            ax.plot([r.frame_time_ms for r in pts], [r.psnr for r in pts], linestyle="none", marker=marker,
                    color=colour, alpha=0.8, label=SHORT[key])
    for r in timed:
        if r.varied == "default":
            ax.plot([r.frame_time_ms], [r.psnr], marker="*", color="black", markersize=14, zorder=5, label="default")
        ax.annotate(f"{r.label} ({r.fmax_mhz:.0f} MHz)", (r.frame_time_ms, r.psnr), textcoords="offset points",
                    xytext=(4, 4), fontsize=6)
    front = pareto_ms(timed)
    ax.plot([r.frame_time_ms for r in front], [r.psnr for r in front], linestyle="--", color="black", linewidth=1.2,
            alpha=0.7, label="non-dominated (least time for the PSNR)")
    ax.set_xscale("log", base=2)
    ax.set_title(f"{len(timed)} of {len(rs)} configurations on a measured build", fontsize=8)
    ax.legend(fontsize=6, loc="lower right", framealpha=0.6)


def _series(rs: list[Row], key: str) -> list[Row]:
    """The rows varying `key`, with the default, in order of the parameter."""
    return sorted([r for r in rs if r.varied in ("default", key)], key=lambda r: getattr(r, key))


def _plot_runtime(ax: Any, rs: list[Row]) -> None:
    """PSNR against cycles: S, p and q as annotated lines; W and F (no extra cycles) as
    bare markers at the default's cycle count; the non-dominated configurations joined."""
    for key in ("supersample", "pipelines", "subpixel"):
        marker, colour = SERIES_STYLE[key]
        series = _series(rs, key)
        ax.plot([r.cycles for r in series], [r.psnr for r in series], marker=marker, color=colour,
                label=f"{SHORT[key]} ({key})", alpha=0.8)
        for r in series:
            if r.varied == key:
                ax.annotate(f"{SHORT[key]}={getattr(r, key)}", (r.cycles, r.psnr), textcoords="offset points",
                            xytext=(4, {"supersample": 6, "pipelines": -12}.get(key, 10)), fontsize=8, color=colour)
    front = pareto(rs)
    ax.plot([r.cycles for r in front], [r.psnr for r in front], linestyle="--", color="black", linewidth=1.2,
            alpha=0.7, label="non-dominated (fewest cycles for the PSNR)")
    # the voxel gradients and the combinations of scene keys: points, labelled by their keys
    marker, colour = SERIES_STYLE["gradient"]
    pts = [r for r in rs if r.varied in ("gradient", "combo")]
    ax.plot([r.cycles for r in pts], [r.psnr for r in pts], linestyle="none", marker=marker, color=colour,
            alpha=0.8, label="gradient and combinations (grad, S, q, warp)")
    for r in pts:
        ax.annotate(r.label.replace("grad=", "").replace("quality: ", "quality "), (r.cycles, r.psnr),
                    textcoords="offset points", xytext=(-6, 5), fontsize=6, color=colour, ha="right")
    for key, what in (("preview", "preview levels (½, ¼ resolution)"),
                      ("tau", "beats and ray termination, τ")):
        marker, colour = SERIES_STYLE[key]
        pts = [r for r in rs if r.varied == key]
        ax.plot([r.cycles for r in pts], [r.psnr for r in pts], linestyle="none", marker=marker, color=colour,
                alpha=0.8, label=what)
        for r in pts:
            ax.annotate(r.label.replace("beats ", ""), (r.cycles, r.psnr), textcoords="offset points",
                        xytext=(4, -10), fontsize=6, color=colour)
    for key in ("weight_bits", "acc_bits", "filter", "path_weights"):
        marker, colour = SERIES_STYLE[key]
        pts = [r for r in rs if r.varied == key]
        ax.plot([r.cycles for r in pts], [r.psnr for r in pts], linestyle="none", marker=marker, color=colour,
                alpha=0.6, label=f"{SHORT[key]} variants (same cycles" + ("; lower row)" if key in ("weight_bits", "acc_bits") else ")"))
    for r in rs:
        if r.varied == "default":
            ax.plot([r.cycles], [r.psnr], marker="*", color="black", markersize=14, zorder=5, label="default")
    ax.set_xscale("log", base=2)
    ax.set_xlabel("cycles per frame (measured)" if any(r.cycles_source == "rtl" for r in rs) else
                  "cycles per frame (formula)")
    ax.set_ylabel("PSNR vs float64 reference (dB)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6, loc="lower right", framealpha=0.6)


def _plot_widths(ax: Any, rs: list[Row]) -> None:
    """PSNR against word width for W and F (their cycles equal the default's)."""
    for key in ("weight_bits", "acc_bits"):
        marker, colour = SERIES_STYLE[key]
        series = _series(rs, key)
        ax.plot([getattr(r, key) for r in series], [r.psnr for r in series], marker=marker, color=colour,
                label=f"{SHORT[key]} ({key})", alpha=0.8)
        for r in series:
            ax.annotate(f"{r.psnr:.2f}", (getattr(r, key), r.psnr), textcoords="offset points",
                        xytext=(3, 5 if key == "weight_bits" else -11), fontsize=7, color=colour)
    for r in rs:
        if r.varied == "default":
            ax.axhline(r.psnr, color="black", linestyle=":", linewidth=1, label="default")
    lo, hi = ax.get_ylim()
    if hi - lo < 1.0:  # at least 1 dB tall, so that noise-level differences do not look like trends
        mid = (lo + hi) / 2
        ax.set_ylim(mid - 0.5, mid + 0.5)
    ax.set_xlabel("bits (W: weights, F: accumulators); no change in cycles")
    ax.set_ylabel("PSNR vs float64 reference (dB)")
    ax.set_xticks(sorted({getattr(r, k) for r in rs for k in ("weight_bits", "acc_bits")}))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")


def write_plot(path: Path, rows: list[Row], title_note: str) -> None:
    """One column per volume/scene: PSNR against cycles (top), against milliseconds per
    frame where the row's build has a measured Fmax (middle), and against the word widths
    W and F, which cost no cycles (bottom)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cases = list(dict.fromkeys((r.volume, r.scene) for r in rows))
    fig, axes = plt.subplots(3, len(cases), figsize=(6.0 * len(cases), 14.0), squeeze=False,
                             gridspec_kw={"height_ratios": [3, 3, 2]})
    for col, case in enumerate(cases):
        rs = [r for r in rows if (r.volume, r.scene) == case and r.cycles is not None]
        _plot_runtime(axes[0][col], rs)
        axes[0][col].set_title(f"{case[0]}, scene {case[1]}")
        _plot_time(axes[1][col], rs)
        _plot_widths(axes[2][col], rs)
    fig.suptitle(f"Cube-4: image error against run time ({title_note})")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ------------------------------------------------------------------------------- main
def _loadavg() -> str:
    try:
        return " / ".join(f"{x:.1f}" for x in os.getloadavg())
    except OSError:
        return "n/a"


def _progress_line(r: Row) -> str:
    line = f"{r.volume:10s} {r.label:8s} PSNR {r.psnr:6.2f} dB  RMSE {r.rmse:.5f}  cycles {r.cycles:>9,} ({r.cycles_source})"
    if r.sim_wall_s is not None:
        line += f"  sim {r.sim_wall_s:6.2f} s  bit_exact {'yes' if r.bit_exact else 'NO'}"
    if r.rtl_error:
        line += f"  RTL FAILED: {r.rtl_error}"
    return line


def run(quick: bool, use_rtl: bool, out_dir: Path, term: TextIO) -> tuple[list[Row], dict]:
    from tqdm import tqdm

    t0 = time.perf_counter()
    fmax_store.load()  # fail early on a malformed file; read again at the end
    cases = QUICK_CASES if quick else CASES + FEATURE_CASES
    all_variants = variants(quick)
    scenes = {name: load_scene(name) for _, name in cases}
    vols = {(v, s): case_volume(v, scenes[s], config_for(scenes[s]).voxel_bits) for v, s in cases}
    plan = {case: case_variants(scenes[case[1]], all_variants) for case in cases}
    for case in FEATURE_CASES:
        if case in plan:
            plan[case] = case_variants(scenes[case[1]], feature_variants())
            all_variants += [v for v, _ in plan[case] if v not in all_variants]
    out_dir.mkdir(parents=True, exist_ok=True)
    REPORTS_BUILD.mkdir(parents=True, exist_ok=True)
    log_path = REPORTS_BUILD / f"{STEM}.log"
    if use_rtl:
        register_rtl_engine()
    meta: dict = {"loadavg_start": _loadavg(), "git": git_state(("rtl", "sim/hdl")), "rtl": use_rtl, "quick": quick,
                  "log": str(log_path.relative_to(REPO_ROOT))}

    total = len(cases) + sum(len(v) for v in plan.values())
    bar = tqdm(total=total, desc="report", unit="render", file=term, disable=None, dynamic_ncols=True)
    refs: dict[tuple[str, str], np.ndarray] = {}
    rows: list[Row] = []
    with bar, log_path.open("w") as log:
        for case in cases:
            bar.set_postfix_str(f"reference {case[0]}")
            ref = render(vols[case], scenes[case[1]], config_for(scenes[case[1]]), "reference")
            refs[case] = ref.image
            meta.setdefault("truth", {})[f"{case[0]}, scene `{case[1]}`"] = {
                k: ref.stats[k] for k in ("truth_k", "truth_change", "truth_converged", "truth_steps")}
            meta["truth"][f"{case[0]}, scene `{case[1]}`"]["wall_s"] = ref.wall_s
            bar.update()
        # Configurations outermost: every volume of a configuration reuses its RTL build.
        for variant in all_variants:
            for case in cases:
                match = [cfg for v, cfg in plan[case] if v == variant]
                if not match:
                    continue
                scene, vol = variant.scene(scenes[case[1]]), vols[case]
                bar.set_postfix_str(f"{case[0]} {variant.label}" + (" (RTL build/sim)" if use_rtl else ""))
                row, golden_base = golden_row(vol, case[0], scene, variant, match[0], refs[case])
                if use_rtl and has_build(scene, match[0]):
                    add_rtl(row, vol, scene, match[0], golden_base, refs[case], log)
                else:
                    row.cycles = row.formula_cycles
                    if row.tau is not None:
                        row.cycles_source = "golden beat walk" if has_build(scene, match[0]) else BEATS_SOURCE
                rows.append(row)
                bar.write(_progress_line(row), file=term)
                bar.update()
    if not quick:
        meta["axis"] = axis_rows()
    measured = fmax_store.load()
    finish_rows(rows, measured)
    meta.update({
        "loadavg_end": _loadavg(),
        "wall_s": time.perf_counter() - t0,
        "finished": datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "command": "make report" + (" (--quick)" if quick else "") + (" (--no-rtl)" if not use_rtl else ""),
        "cycles_note": ("measured by simulating cube4_top in Verilator (source `rtl`)" if use_rtl else
                        "from the formula of docs/architecture.md with the empty-space box's dims, not simulated (source `formula`)"),
        "fmax_note": fmax_note(rows, measured),
    })
    return rows, meta


def json_path(out_dir: Path) -> Path:
    """The run's data, beside its tables (committed under reports/ with them, so that
    ``--tables-only`` works on a clone)."""
    return out_dir / f"{STEM}.json"


def write_outputs(rows: list[Row], meta: dict, out_dir: Path) -> list[Path]:
    md, csv_p, png = (out_dir / f"{STEM}.{ext}" for ext in ("md", "csv", "png"))
    js = json_path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    write_markdown(md, rows, meta)
    write_csv(csv_p, rows)
    write_plot(png, rows, "cycles measured in RTL simulation" if meta["rtl"] else "cycles from the formula")
    write_json(js, rows, meta)
    return [md, csv_p, png, js]


def rewrite_tables(out_dir: Path) -> tuple[list[Row], dict]:
    """The rows and metadata of the last run into out_dir (see `json_path`), with the
    frame times recomputed from the builds' Fmax as measured now (cube4_reports.fmax)."""
    path = json_path(out_dir)
    try:
        data = json.loads(path.read_text())
        rows = [Row(**{k: (math.inf if k == "psnr" and v is None else v) for k, v in r.items()})
                for r in data["rows"]]
        meta = dict(data["meta"])
    except FileNotFoundError:
        raise UserError(f"{_rel(path)} does not exist: run make report first") from None
    except (OSError, ValueError, KeyError, TypeError):
        raise UserError(f"{_rel(path)} is not a report of this version: rerun make report") from None
    if not rows:
        raise UserError(f"{_rel(path)} has no rows: rerun make report")
    measured = fmax_store.load()
    finish_rows(rows, measured)
    meta["fmax_note"] = fmax_note(rows, measured)
    meta["tables_rewritten"] = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    return rows, meta


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(
        prog="python -m cube4_reports.report",
        description="Image error against the float64 reference beside run time (cycles, frame time at "
                    "the measured Fmax, simulation seconds) for S, W, F and p: make report.")
    ap.add_argument("--quick", action="store_true",
                    help="one volume (sphere:64) and five configurations: default, S=2, W=4, F=8, p=1")
    ap.add_argument("--no-rtl", action="store_true",
                    help="no Verilator: cycles from the formula of docs/architecture.md with the empty-space box's dims (marked 'formula')")
    ap.add_argument("--tables-only", action="store_true",
                    help="render nothing: rewrite the tables and plot from the last run into --out "
                         "(error_vs_runtime.json in --out) with the builds' Fmax as measured now (reports/fpga*.json)")
    ap.add_argument("--out", default=str(DEFAULT_OUT),
                    help="folder for error_vs_runtime.{md,csv,png} (default: reports/ of the repository, "
                         "with the run's data beside them in error_vs_runtime.json)")
    return ap


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    term = os.fdopen(os.dup(2), "w", buffering=1)  # survives the redirection of fd 2 during RTL runs
    try:
        out_dir = Path(args.out)
        if out_dir.exists() and not out_dir.is_dir():
            raise UserError(f"--out {args.out!r} is not a folder")
        if args.tables_only and (args.quick or args.no_rtl):
            raise UserError("--tables-only renders nothing, so --quick and --no-rtl do not apply")
        load_angles()       # the stored gradient angles the tables show: before any work
        rows, meta = rewrite_tables(out_dir) if args.tables_only else run(args.quick, not args.no_rtl, out_dir, term)
        paths = write_outputs(rows, meta, out_dir)
    except UserError as e:
        print(f"cube4 report: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("cube4 report: interrupted", file=sys.stderr)
        return 130
    except OSError as e:
        print(f"cube4 report: error: cannot write {e.filename or 'output'}: {e.strerror}", file=sys.stderr)
        return 2
    finally:
        term.close()
    bad = [r for r in rows if r.rtl_error or r.bit_exact is False]
    done = "tables rewritten" if args.tables_only else f"{len(rows)} renders in {meta['wall_s'] / 60:.1f} min"
    print(f"cube4 report: {done} -> "
          + ", ".join(str(_rel(p)) for p in paths)
          + (f"; {len(bad)} RTL failures or mismatches, see the table" if bad else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())

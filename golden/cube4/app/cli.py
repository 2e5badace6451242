"""The ``cube4`` command line.

    cube4 render VOLUME --scene S.toml --engine ENGINE --out IMG.png
                 [--baseplane BP.npy] [--stats STATS.json] [--pipelines P] [--build B]
                 [--compare-to reference|reference-point] [--dims NX,NY,NZ] [--dtype T] [--voxel-bits V]
                 [--view AZ,EL ... | --orbit N]
                 [--bricks BX,BY,BZ] [--board-dim N] [--workers N | --scheduler tcp://HOST:PORT]
                 [--no-skip | --box | --rects | --beats] [--tau T | --no-terminate] [--preview F] [--preset default|quality] [--gradient gra|central|sobel]
                 [--path-weights | --no-path-weights]
    cube4 volumes | cube4 scenes      list the built-ins

Engines: those registered with ``cube4.app.render.register_engine`` when ``main`` runs:
``reference``, ``reference-point`` and ``golden`` from this package. The installed ``cube4`` command is the
simulation package's entry point, which registers ``rtl`` (the simulated hardware) and
then runs this ``main``.

``cube4 render`` runs in stages: every input checked before any work (``_parse_inputs``:
the options, the scenes of the views, the bricks, the destinations, the build), the volume
loaded (``_load_volume``), the views rendered with their stats (``_render``), the outputs
written all or none (``_outputs``, ``write_all``), one line per view (``_summary``).

Bad input gives one line on stderr and exit status 2; nothing is written unless the
whole render succeeded (outputs go to a temporary file in the target folder first).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ..bricks import BRICK_MODES, MIN_BOARD_DIM, LocalExecutor, brick_renderer, parse_bricks
from ..config import MAX_DIM, MAX_PIPELINES, Cube4Config, parse_build, resolve_build
from ..errors import UserError
from ..host import config_for, image_metrics
from ..scene import (PRESETS, SKIP_DEFAULT, Scene, label_scene_checks, apply_preset, builtin_scene_names, load_scene,
                     with_schedule, with_view)
from ..vgrad import GRADIENTS
from ..values import int_text, real_text, shown
from ..view import POLE_Z, angles_from_direction, direction_from_angles, make_camera, up_from_angles
from .images import write_image
from .outputs import Writer, check_destination, check_destinations, write_all
from .render import RenderResult, engine_names, render, render_bricked_views, render_views
from .volumes import BUILTINS, load_volume
from .labelmaps import with_labels

IMAGE_SUFFIXES = (".png", ".exr", ".tif", ".tiff")


def _dims(text: str) -> tuple[int, int, int]:
    try:
        parts = tuple(int_text(p, "--dims") for p in text.replace("x", ",").split(","))
    except UserError:
        raise UserError(f"--dims must be NX,NY,NZ (three integers), got {shown(text)}") from None
    if len(parts) != 3:
        raise UserError(f"--dims must be NX,NY,NZ (three integers), got {text!r}")
    return parts  # type: ignore[return-value]


def _int_arg(text: str) -> int:
    """An integer option: decimal digits only (no 1_0, no spaces inside)."""
    try:
        return int_text(text, "must be an integer")
    except UserError:
        raise argparse.ArgumentTypeError(f"must be an integer, got {shown(text)}") from None


class _Once:
    """An option that may be given once: a second --out (or --build, ...) is an error,
    not a silent override."""

    def __call__(self, parser, namespace, values, option_string=None):
        seen = namespace.__dict__.setdefault("_given", {})
        if self.dest in seen:
            parser.error(f"{option_string or self.dest} given twice ({seen[self.dest]} and {option_string}): "
                         "give it once")
        seen[self.dest] = option_string
        super().__call__(parser, namespace, values, option_string)


class _StoreOnce(_Once, argparse._StoreAction):
    pass


class _StoreTrueOnce(_Once, argparse._StoreTrueAction):
    pass


class _BooleanOnce(_Once, argparse.BooleanOptionalAction):
    pass


class _Parser(argparse.ArgumentParser):
    """argparse, with its errors (a missing --out, a bad choice, a non-integer) as one
    line like every other error, instead of the usage text; options other than --view
    may be given once."""

    def __init__(self, *a, **k):
        super().__init__(*a, **k)
        self.register("action", None, _StoreOnce)
        self.register("action", "store", _StoreOnce)
        self.register("action", "store_true", _StoreTrueOnce)

    def error(self, message: str):
        raise UserError(f"{self.prog}: {message} (see {self.prog} --help)")


def _parser() -> argparse.ArgumentParser:
    ap = _Parser(prog="cube4", description="Cube-4 volume renderer (golden model, reference, RTL).")
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("render", help="render a volume with a scene into an image")
    r.add_argument("volume", help="a volume file (.raw, .nrrd, .nii[.gz]) or a built-in like sphere:64, ml:41")
    r.add_argument("--scene", default="default", help="scene TOML file or built-in scene name (default: default)")
    r.add_argument("--labels", metavar="MAP",
                   help="a label map beside the volume (.nii[.gz], .nrrd, or a built-in such as aal_lobes): "
                        "each label classified by the scene's [[label]] tables (over the scene's [labels] map)")
    r.add_argument("--engine", default="golden", choices=engine_names())
    r.add_argument("--out", required=True, help="output image (.png, .exr, .tif)")
    r.add_argument("--baseplane", help="write the exact integer base-plane RGBA (rows, cols, 4) as .npy")
    r.add_argument("--stats", help="write run statistics as JSON")
    r.add_argument("--pipelines", type=_int_arg, help=f"number of pipelines p (1..{MAX_PIPELINES})")
    r.add_argument("--build", default="scene",
                   help="the hardware build: scene (default: the smallest the scene needs), full, or "
                        "NAME=0/1 pairs of SHADING, COMPOSITING, EXTREMUM, CLIP, VGRAD (others as in full: "
                        "1, VGRAD 0); --stats names it")
    r.add_argument("--compare-to", choices=["reference", "reference-point"],
                   help="also render the reference and report the error against it: the truth, each pixel the "
                        "mean over its square (reference), or one ray through its centre (reference-point)")
    r.add_argument("--dims", help="raw volumes: NX,NY,NZ")
    r.add_argument("--dtype", help="raw volumes: uint8, uint16, int16, uint32, int32, float32, float64")
    r.add_argument("--voxel-bits", type=_int_arg, help="voxel width VOXEL_W (default: the scene's, else 8)")
    r.add_argument("--background", default="0,0,0", help="R,G,B in [0,1] behind the volume in PNG/TIFF output")
    r.add_argument("--view", action="append", metavar="AZ,EL",
                   help="render from azimuth,elevation in degrees instead of the scene's view; repeat for "
                        "several views (outputs get _000, _001, ... before the suffix, or put {n} in the name)")
    r.add_argument("--orbit", type=_int_arg, metavar="N",
                   help="render N views evenly spaced in azimuth around the scene's view (elevation kept)")
    r.add_argument("--bricks", metavar="BX,BY,BZ",
                   help="render in BX*BY*BZ bricks (sub-volumes with overlap) and composite them in order")
    r.add_argument("--board-dim", type=_int_arg, metavar="N",
                   help="largest brick (with its overlap) one board takes, voxels per axis; without --bricks "
                        "the fewest bricks that fit are used")
    r.add_argument("--workers", type=_int_arg, metavar="N",
                   help="render the bricks on a local Dask cluster of N worker processes")
    r.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                   help="render the bricks on the Dask cluster of this scheduler")
    r.add_argument("--no-skip", action="store_true",
                   help="traverse the whole volume (the fixed schedule) instead of only the box that can change "
                        "a ray; the image is the same, --stats compares the cycles")
    r.add_argument("--box", action="store_true",
                   help="traverse only the box that can change a ray, every beat of it ([render] skip = true); "
                        "the image is the same, --stats compares the cycles")
    r.add_argument("--rects", action="store_true",
                   help="within the box, each sample slice traverses only its own rectangle (slice "
                        "rectangles; S = 1); the image is the same, --stats compares the cycles")
    r.add_argument("--beats", action="store_true",
                   help="within the box, run only the beats (partial beams) that can change a ray, and end "
                        "rays that can change no more (beat skipping and ray termination): the default of a "
                        "scene that leaves [render] skip out, rendered whole; the image is the same, "
                        "--stats gives the beats skipped by cause")
    r.add_argument("--tau", type=float, metavar="T",
                   help="on the beat schedule: end a ray once its transmittance is at most T (0 <= T <= 0.5; "
                        "default 0, exact): error against run time")
    r.add_argument("--no-terminate", action="store_true",
                   help="on the beat schedule: no ray ends early (beat skipping alone; [render] terminate = false), "
                        "for comparison")
    r.add_argument("--preview", type=_int_arg, metavar="F",
                   help="render the volume at 1/F of its resolution (F = 2 or 4; [render] preview): about F³ "
                        "times fewer cycles, the same picture framing; --compare-to measures it against the "
                        "whole volume's truth")
    r.add_argument("--gradient", choices=GRADIENTS,
                   help="the gradient estimator instead of the scene's [render] gradient: gra (the paper's, on "
                        "the sample stream), central or sobel (at the voxels, interpolated by TRI)")
    r.add_argument("--path-weights", action=_BooleanOnce, default=None,
                   help="weight each ray's first and last samples by their share of the ray's path (the scene's "
                        "[render] path_weights; needs a build with PLW = 1)")
    r.add_argument("--preset", choices=tuple(PRESETS),
                   help="a named preset over the scene: default (the scene as it is) or quality (voxel central "
                        "differences, S = 4, 2x2 sub-pixel passes, path weights: 40 dB or more on the built-in "
                        "phantoms); --gradient and --path-weights still override it")
    r.add_argument("--quiet", action="store_true", help="no progress bars or summary")
    me = sub.add_parser("mesh", help="draw a mesh with a scene's camera into a geometry image ([geometry] image)")
    me.add_argument("volume", help="the volume the scene renders (its dims frame the camera)")
    me.add_argument("--scene", default="default", help="scene TOML file or built-in scene name (default: default)")
    me.add_argument("--mesh", default="needle",
                    help="a mesh file trimesh reads (.stl, .obj, .ply, ...) in the volume's voxel coordinates, "
                         "or needle (default): a needle from near a corner to just past the centre")
    me.add_argument("--out", required=True, help="the geometry image (.exr: R, G, B, A and Z)")
    sub.add_parser("volumes", help="list the built-in volumes")
    sub.add_parser("scenes", help="list the built-in scenes")
    return ap


def _check_output(path: str, suffixes: tuple[str, ...], what: str) -> Path:
    if path.endswith(("/", os.sep)) or os.path.basename(path) in ("", ".", ".."):
        raise UserError(f"{what} {shown(path, 200)} names a folder: give a file name")
    if "\0" in path:
        raise UserError(f"{what} {shown(path, 200)} holds a NUL character")
    p = Path(path)
    if p.suffix.lower() not in suffixes:
        raise UserError(f"{what} {shown(path, 200)} must end in {', '.join(suffixes)}")
    check_destination(p, what)
    return p


def _json_safe(d: dict) -> dict:
    """inf/NaN are not JSON: an identical image has PSNR null ("infinite")."""
    return {k: (None if isinstance(v, float) and not np.isfinite(v) else v) for k, v in d.items()}


def _background(text: str) -> tuple[float, float, float]:
    try:
        vals = tuple(real_text(v, "--background") for v in text.split(","))
    except UserError:
        vals = ()
    if len(vals) != 3 or not all(0.0 <= v <= 1.0 for v in vals):
        raise UserError(f"--background must be R,G,B with values in [0, 1], got {shown(text)}")
    return vals  # type: ignore[return-value]


MAX_VIEWS = 360


def _views(args: argparse.Namespace, scene: Scene) -> list[Scene]:
    """The scenes to render: the scene's own view, the --view list, or an --orbit."""
    if args.view and args.orbit is not None:
        raise UserError("--view and --orbit exclude each other")
    if args.orbit is not None:
        if not 1 <= args.orbit <= MAX_VIEWS:
            raise UserError(f"--orbit must be in 1..{MAX_VIEWS}, got {args.orbit}")
        az0, el = angles_from_direction(scene.direction)
        return [_view(scene, az0 + 360.0 * n / args.orbit, el) for n in range(args.orbit)]
    if not args.view:
        return [scene]
    if len(args.view) > MAX_VIEWS:
        raise UserError(f"at most {MAX_VIEWS} views per call, got {len(args.view)}")
    scenes = []
    for text in args.view:
        try:
            az, el = (real_text(v, "--view") for v in text.split(","))
        except (UserError, ValueError):
            raise UserError(f"--view must be AZ,EL in degrees, got {shown(text)}") from None
        if not (-360.0 <= az <= 360.0 and -90.0 <= el <= 90.0):
            raise UserError(f"--view {shown(text)}: azimuth must be in -360..360 and elevation in -90..90")
        scenes.append(_view(scene, az, el))
    return scenes


def _view(scene: Scene, az: float, el: float) -> Scene:
    """The scene from (az, el). Near the poles the picture's up comes from the angles
    themselves (up_from_angles), so that an elevation sweep turns the picture smoothly
    through 90 degrees at every azimuth; a scene's own `up` is kept."""
    d = direction_from_angles(az, el)
    near_pole = abs(d[2]) >= POLE_Z
    return with_view(scene, d, up_from_angles(az, el) if near_pole and scene.up is None else None)


def _numbered(path: Path, n: int, count: int) -> Path:
    """Output path of view n: {n} in the name is replaced, else _NNN is appended."""
    if count == 1 and "{n}" not in path.name:
        return path
    if "{n}" in path.name:
        return path.with_name(path.name.replace("{n}", f"{n:03d}"))
    return path.with_name(f"{path.stem}_{n:03d}{path.suffix}")


@dataclass
class RenderRun:
    """A ``cube4 render`` call, every input checked: where its outputs go, the scenes (one
    per view) and the hardware they run on."""

    out: Path
    baseplane: Path | None
    stats: Path | None
    background: tuple[float, float, float]
    scenes: list[Scene]
    bricks: tuple | None = None      # (grid counts or None, board dim or None) for a bricked render
    cfg: Cube4Config | None = None

    def numbered(self, path: Path, n: int) -> Path:
        return _numbered(path, n, len(self.scenes))

    def destinations(self) -> list[tuple[Path, str]]:
        """Every output file, numbered per view."""
        views = range(len(self.scenes))
        named = [(self.numbered(self.out, n), "--out") for n in views]
        if self.baseplane is not None:
            named += [(self.numbered(self.baseplane, n), "--baseplane") for n in views]
        if self.stats is not None:
            named.append((self.stats, "--stats"))
        return named


def cmd_mesh(args: argparse.Namespace) -> int:
    """Draw a mesh (or the built-in needle) with the scene's camera into a geometry image."""
    from ..geometry import check_geometry
    from .mesh import draw_mesh, load_mesh, needle_mesh, write_geometry

    out = _check_output(args.out, (".exr",), "--out")
    scene = load_scene(args.scene)
    vol = load_volume(args.volume)
    nz, ny, nx = vol.shape
    cam = make_camera((nx, ny, nz), scene.direction, scene.width, scene.height, scene.up)
    mesh = needle_mesh((nx, ny, nz)) if args.mesh == "needle" else load_mesh(args.mesh)
    geo = draw_mesh(mesh, cam)
    check_geometry(geo, cam)
    write_geometry(str(out), geo)
    print(f"cube4: mesh drawn for {args.volume} with scene {scene.name}: "
          f"{float(np.isfinite(geo.z).mean()):.1%} of the pixels -> {out}")
    return 0


def cmd_render(args: argparse.Namespace) -> int:
    """Check every input, load the volume, render, write all outputs or none, report."""
    run = _parse_inputs(args)
    vol = _load_volume(args, run.cfg, run.scenes)
    results, frames = _render(args, run, vol)
    write_all(_outputs(run, results, frames))
    if not args.quiet:
        _summary(args, run, results, frames)
    return 0


def _parse_inputs(args: argparse.Namespace) -> RenderRun:
    """Stage 1, before any work: the options, the scenes, the bricks, every destination and
    the build (one line for the first thing wrong)."""
    out, bp, st, bg = _check_options(args)
    scenes = _resolve_scenes(args)
    bricks = _brick_options(args, scenes[0])
    scenes = _scheduled(args, scenes, bricks is None)
    run = RenderRun(out, bp, st, bg, scenes, bricks=bricks)
    check_destinations(run.destinations())
    run.cfg = _hardware(args, scenes)
    return run


def _check_options(args: argparse.Namespace) -> tuple[Path, Path | None, Path | None, tuple[float, float, float]]:
    """The output names (--out, --baseplane, --stats), the background, and the options
    that need each other."""
    out = _check_output(args.out, IMAGE_SUFFIXES, "--out")
    bp = _check_output(args.baseplane, (".npy",), "--baseplane") if args.baseplane else None
    st = _check_output(args.stats, (".json",), "--stats") if args.stats else None
    bg = _background(args.background)
    if args.baseplane and args.engine.startswith("reference"):
        raise UserError("--baseplane needs a Cube-4 engine (golden or rtl); the reference has no base plane")
    if args.pipelines is not None and not 1 <= args.pipelines <= MAX_PIPELINES:
        raise UserError(f"--pipelines must be in 1..{MAX_PIPELINES}, got {args.pipelines}")
    return out, bp, st, bg


def _resolve_scenes(args: argparse.Namespace) -> list[Scene]:
    """The scene, one per view (--view, --orbit), each with the command line's changes."""
    scenes = _views(args, load_scene(args.scene))
    if sum(bool(f) for f in (args.no_skip, args.box, args.rects, args.beats)) > 1:
        raise UserError("--no-skip, --box, --rects and --beats exclude each other")
    if args.tau is not None and (args.no_skip or args.box or args.rects):
        raise UserError("--tau needs the beat schedule (ray termination), not --no-skip, --box or --rects")
    if args.no_terminate and (args.no_skip or args.box or args.rects):
        raise UserError("--no-terminate needs the beat schedule, not --no-skip, --box or --rects")
    if args.no_terminate and args.tau is not None:
        raise UserError("--no-terminate and --tau exclude each other")
    if args.tau is not None and not 0.0 <= args.tau <= 0.5:
        raise UserError(f"--tau must be in 0..0.5, got {args.tau}")
    if args.preview is not None and args.preview not in (1, 2, 4):
        raise UserError(f"--preview must be 1, 2 or 4, got {args.preview}")
    scenes = [_changed(sc, args) for sc in scenes]
    labels = scenes[0].labels
    if getattr(args, "labels", None) and labels is None:
        raise UserError(f"--labels needs a scene with [[label]] tables (each label's transfer function); "
                        f"scene {scenes[0].name} has none")
    if labels is not None and not (getattr(args, "labels", None) or labels.map):
        raise UserError(f"scene {scenes[0].name} classifies labels: give their map with --labels "
                        "(or [labels] map in the scene)")
    if labels is not None:      # the changes of the command line, checked as the scene's own
        label_scene_checks(scenes[0].mode, scenes[0].schedule, scenes[0].path_weighted, scenes[0].preview)
    return scenes


def _scheduled(args: argparse.Namespace, scenes: list[Scene], whole: bool) -> list[Scene]:
    """The scenes with their schedules written out (a scene that leaves [render] skip out:
    the beat schedule where the build and a whole-volume render run it, else the box;
    ``cube4.scene.default_schedule``); --tau and --no-terminate need the beat schedule."""
    asked = scenes[0].skip
    build = parse_build(args.build)
    scenes = [with_schedule(sc, build, whole) for sc in scenes]
    if (args.tau is not None or args.no_terminate) and scenes[0].skip != "beats":
        flag = "--tau" if args.tau is not None else "--no-terminate"
        why = (f"the scene sets [render] skip = {str(asked).lower()}" if asked != SKIP_DEFAULT else
               "this render runs the box (bricks, or a build without BEATS)")
        raise UserError(f"{flag} needs the beat schedule (--beats): {why}")
    return scenes


def _changed(scene: Scene, args: argparse.Namespace) -> Scene:
    """A scene with --no-skip, --box, --rects or --beats, then --preset, then --gradient and
    --path-weights over the preset."""
    if args.no_skip or args.box or args.rects or args.beats:
        scene = replace(scene, skip="rects" if args.rects else "beats" if args.beats else bool(args.box))
    if args.tau is not None:
        scene = replace(scene, tau=args.tau)
    if args.no_terminate:
        scene = replace(scene, terminate=False)
    if args.preview is not None:
        scene = replace(scene, preview=args.preview)
    if args.preset:
        scene = apply_preset(scene, args.preset)
    over = {k: v for k, v in (("gradient", args.gradient), ("path_weights", args.path_weights)) if v is not None}
    return replace(scene, **over) if over else scene


def _hardware(args: argparse.Namespace, scenes: list[Scene]) -> Cube4Config:
    """The hardware: the first scene's configuration (with the preset, --gradient and
    --path-weights its keys, S among them, choose it) with the command line's, on the
    build asked for; a scene that needs what the build leaves out is one line here."""
    build = parse_build(args.build)
    cfg = config_for(scenes[0], pipelines=args.pipelines, voxel_bits=args.voxel_bits,
                     build=None if build is None else tuple(build.items()))
    resolve_build(cfg, scenes)
    return cfg


def _load_volume(args: argparse.Namespace, cfg: Cube4Config, scenes: list[Scene] | None = None):
    """Stage 2: the volume, as voxels of the configuration's width; with a label map (a
    scene with labels), the labelled memory words (cube4.labels)."""
    raw_dims = _dims(args.dims) if args.dims else None
    vol = load_volume(args.volume, voxel_bits=cfg.voxel_bits, raw_dims=raw_dims, raw_dtype=args.dtype)
    return with_labels(vol, args.volume, scenes[0] if scenes else None, cfg.voxel_bits, args.labels)


def _render(args: argparse.Namespace, run: RenderRun, vol) -> tuple[list[RenderResult], list[dict]]:
    """Stage 3: every view through the engine (in bricks if asked), and each view's stats
    (with the error against the reference if asked)."""
    progress = not args.quiet and sys.stderr.isatty()
    if run.bricks is None:
        results = render_views(vol, run.scenes, run.cfg, args.engine, progress=progress)
    else:
        results = _render_bricked(args, vol, run.scenes, run.cfg, run.bricks, progress)
    frames = []
    for res, sc in zip(results, run.scenes):
        stats = dict(res.stats)
        stats["volume"] = args.volume
        stats["scene"] = run.scenes[0].name
        stats["azimuth"], stats["elevation"] = angles_from_direction(sc.direction)
        if args.compare_to:
            ref = render(vol, sc, run.cfg, args.compare_to, progress=progress)
            stats.update(image_metrics(res.image, ref.image))
            stats["reference_wall_s"] = ref.wall_s
            stats["reference"] = args.compare_to
            stats.update({k: v for k, v in ref.stats.items() if k.startswith("truth")})
        frames.append(stats)
    return results, frames


def _outputs(run: RenderRun, results: list[RenderResult], frames: list[dict]) -> list[tuple[Path, Writer]]:
    """Stage 4: what goes into each output file (written by write_all, all or none)."""
    outputs: list[tuple[Path, Writer]] = []
    for n, res in enumerate(results):
        outputs.append((run.numbered(run.out, n), lambda tmp, img=res.image, z=res.depth: write_image(tmp, img, run.background, depth=z)))
        if run.baseplane is not None and res.frame is not None:
            outputs.append((run.numbered(run.baseplane, n), lambda tmp, base=res.frame.baseplane: np.save(tmp, base)))
    if run.stats is not None:
        text = json.dumps(_stats_doc(frames), indent=2, allow_nan=False) + "\n"
        outputs.append((run.stats, lambda tmp: Path(tmp).write_text(text)))
    return outputs


def _stats_doc(frames: list[dict]) -> dict:
    """The --stats document: one view's stats, or every view's with their sums."""
    if len(frames) == 1:
        return _json_safe(frames[0])
    doc = {"views": len(frames), "frames": [_json_safe(f) for f in frames], "wall_s": sum(f["wall_s"] for f in frames)}
    if all("cycles" in f for f in frames):
        doc["cycles"] = sum(f["cycles"] for f in frames)
        doc["sim_wall_s"] = sum(f["sim_wall_s"] for f in frames)
        doc["sim_cycles_per_s"] = doc["cycles"] / doc["sim_wall_s"] if doc["sim_wall_s"] > 0 else None
    return doc


def _summary(args: argparse.Namespace, run: RenderRun, results: list[RenderResult], frames: list[dict]) -> None:
    """Stage 5: one line per view on stdout."""
    count = len(run.scenes)
    for n, (stats, res) in enumerate(zip(frames, results)):
        line = (f"cube4: {args.engine} render of {args.volume} {tuple(stats['dims'])} "
                f"in {res.wall_s:.2f} s -> {run.numbered(run.out, n)}")
        if count > 1:
            line += f" (azimuth {stats['azimuth']:.1f}, elevation {stats['elevation']:.1f})"
        if "bricks" in stats:
            b = stats["bricks"]
            line += (f" ({b['count']} bricks {'x'.join(str(c) for c in b['grid'])}, memory "
                     f"+{100 * b['memory_overhead']:.1f}%, on {b['workers']} worker"
                     f"{'s' if b['workers'] != 1 else ''}{_retries_note(b)})")
        if stats.get("skip"):
            saved = stats["cycles_saved"] / max(1, stats["fixed_schedule_cycles"])
            line += f" (empty space skipped: {100 * saved:.0f}% of the cycles)"
        if "beats" in stats:
            b = stats["beats"]
            box = max(1, b["box_beats"])
            line += (f" (beats within the box: {100 * b['run_beats'] / box:.0f}% ran, "
                     f"{100 * b['skipped_empty'] / box:.0f}% skipped empty, "
                     f"{100 * b['skipped_terminated'] / box:.0f}% skipped after their rays ended)")
        if "dram" in stats and stats["dram"].get("ideal_over_dram") is not None:
            d = stats["dram"]
            line += (f" (voxels from DRAM: {d['cycles']:,} cycles, ideal memory {d['ideal_over_dram']:.2f} of that; "
                     f"{d['mb_per_s']:.0f} of {d['peak_mb_per_s']:.0f} MB/s at {d['pipeline_mhz']} MHz)")
        if args.compare_to:
            line += (f"; vs {args.compare_to}: PSNR {stats['psnr']:.2f} dB, RMSE {stats['rmse']:.4f}, "
                     f"max {stats['max_abs']:.3f}")
        print(line)


def _brick_options(args: argparse.Namespace, scene: Scene):
    """(grid counts or None, board dim or None) when the render goes in bricks, else None;
    every option checked before any work."""
    if args.workers is not None and args.scheduler is not None:
        raise UserError("--workers and --scheduler exclude each other")
    if (args.bricks is not None or args.board_dim is not None) and scene.skip == "beats":
        raise UserError("--beats (or render.skip = \"beats\") does not run in bricks: render the volume whole")
    if (args.bricks is not None or args.board_dim is not None) and scene.depth_threshold is not None:
        raise UserError("depth out ([output] depth_threshold) is not rendered in bricks: render the volume whole")
    if args.bricks is None and args.board_dim is None:
        if args.workers is not None or args.scheduler is not None:
            raise UserError("--workers and --scheduler render bricks: give --bricks BX,BY,BZ or --board-dim N")
        return None
    counts = parse_bricks(args.bricks) if args.bricks is not None else None
    if args.board_dim is not None and not MIN_BOARD_DIM <= args.board_dim <= MAX_DIM:
        raise UserError(f"--board-dim must be in {MIN_BOARD_DIM}..{MAX_DIM} (a brick's own voxel and its "
                        f"overlap), got {args.board_dim}")
    brick_renderer(args.engine)
    if scene.mode not in BRICK_MODES:
        raise UserError(f"--bricks composes the modes {', '.join(BRICK_MODES)}, not the scene's {scene.mode!r} "
                        f"(a ray's extremum cannot be told from the partial pixels)")
    build = parse_build(args.build)
    if build is not None and not build["CLIP"]:
        raise UserError("--bricks count each brick's own samples with the window: the build needs CLIP = 1")
    if args.workers is not None and not 1 <= args.workers <= 256:
        raise UserError(f"--workers must be in 1..256, got {args.workers}")
    if args.scheduler is not None:
        from .cluster import check_scheduler

        check_scheduler(args.scheduler)
    return counts, args.board_dim


def _render_bricked(args: argparse.Namespace, vol, scenes, cfg, bricks, progress: bool):
    counts, board_dim = bricks
    if args.workers is None and args.scheduler is None:
        executor = LocalExecutor()
    else:
        from .cluster import DaskExecutor   # dask only when a cluster is asked for

        executor = DaskExecutor(workers=args.workers, scheduler=args.scheduler, quiet=True)
    with executor:
        return render_bricked_views(vol, scenes, cfg, args.engine, counts, board_dim=board_dim,
                                    executor=executor, progress=progress)


def _retries_note(b: dict) -> str:
    n = b.get("retries", 0)
    return f", {n} brick{'s' if n != 1 else ''} sent again" if n else ""


def main(argv: list[str] | None = None) -> int:
    try:
        args = _parser().parse_args(argv)
        if args.cmd == "render":
            return cmd_render(args)
        if args.cmd == "mesh":
            return cmd_mesh(args)
        if args.cmd == "volumes":
            for name, (_, desc) in sorted(BUILTINS.items()):
                print(f"{name:10s} {desc}")
            return 0
        if args.cmd == "scenes":
            print("\n".join(builtin_scene_names()))
            return 0
    except UserError as e:
        text = " ".join(str(e).split())     # one line, whatever a library's message held
        print(f"cube4: error: {text}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("cube4: interrupted", file=sys.stderr)
        return 130
    except MemoryError:
        print("cube4: error: out of memory (more than this process may use): choose a smaller volume "
              "or output, or raise the memory limit", file=sys.stderr)
        return 2
    return 1


if __name__ == "__main__":
    sys.exit(main())

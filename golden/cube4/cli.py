"""The ``cube4`` command line.

    cube4 render VOLUME --scene S.toml --engine ENGINE --out IMG.png
                 [--baseplane BP.npy] [--stats STATS.json] [--pipelines P] [--build B]
                 [--compare-to reference] [--dims NX,NY,NZ] [--dtype T] [--voxel-bits V]
                 [--view AZ,EL ... | --orbit N]
                 [--bricks BX,BY,BZ] [--board-dim N] [--workers N | --scheduler tcp://HOST:PORT]
                 [--no-skip | --rects] [--preset default|quality] [--gradient gra|central|sobel]
                 [--path-weights | --no-path-weights]
    cube4 volumes | cube4 scenes      list the built-ins

Engines: those registered with ``cube4.render.register_engine`` when ``main`` runs:
``reference`` and ``golden`` from this package. The installed ``cube4`` command is the
simulation package's entry point, which registers ``rtl`` (the simulated hardware) and
then runs this ``main``.

Bad input gives one line on stderr and exit status 2; nothing is written unless the
whole render succeeded (outputs go to a temporary file in the target folder first).
"""

from __future__ import annotations

import argparse
import json
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

from .bricks import (BRICK_MODES, MIN_BOARD_DIM, LocalExecutor, brick_renderer, parse_bricks,
                     render_bricked_views)
from .config import MAX_DIM, MAX_PIPELINES, parse_build, resolve_build
from .errors import UserError
from .outputs import Writer, check_destination, check_destinations, write_all
from .render import config_for, engine_names, image_metrics, render, render_views
from .scene import PRESETS, Scene, apply_preset, builtin_scene_names, load_scene, with_view
from .vgrad import GRADIENTS
from .view import POLE_Z, angles_from_direction, direction_from_angles, up_from_angles
from .volumes import BUILTINS, load_volume

IMAGE_SUFFIXES = (".png", ".exr", ".tif", ".tiff")


def _dims(text: str) -> tuple[int, int, int]:
    try:
        parts = tuple(int(p) for p in text.replace("x", ",").split(","))
    except ValueError:
        raise UserError(f"--dims must be NX,NY,NZ (three integers), got {text!r}") from None
    if len(parts) != 3:
        raise UserError(f"--dims must be NX,NY,NZ (three integers), got {text!r}")
    return parts  # type: ignore[return-value]


class _Parser(argparse.ArgumentParser):
    """argparse, with its errors (a missing --out, a bad choice, a non-integer) as one
    line like every other error, instead of the usage text."""

    def error(self, message: str):
        raise UserError(f"{self.prog}: {message} (see {self.prog} --help)")


def _parser() -> argparse.ArgumentParser:
    ap = _Parser(prog="cube4", description="Cube-4 volume renderer (golden model, reference, RTL).")
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("render", help="render a volume with a scene into an image")
    r.add_argument("volume", help="a volume file (.raw, .nrrd, .nii[.gz]) or a built-in like sphere:64, ml:41")
    r.add_argument("--scene", default="default", help="scene TOML file or built-in scene name (default: default)")
    r.add_argument("--engine", default="golden", choices=engine_names())
    r.add_argument("--out", required=True, help="output image (.png, .exr, .tif)")
    r.add_argument("--baseplane", help="write the exact integer base-plane RGBA (rows, cols, 4) as .npy")
    r.add_argument("--stats", help="write run statistics as JSON")
    r.add_argument("--pipelines", type=int, help=f"number of pipelines p (1..{MAX_PIPELINES})")
    r.add_argument("--build", default="scene",
                   help="the hardware build: scene (default: the smallest the scene needs), full, or "
                        "NAME=0/1 pairs of SHADING, COMPOSITING, EXTREMUM, CLIP, VGRAD (others as in full: "
                        "1, VGRAD 0); --stats names it")
    r.add_argument("--compare-to", choices=["reference"], help="also render the reference and report the error")
    r.add_argument("--dims", help="raw volumes: NX,NY,NZ")
    r.add_argument("--dtype", help="raw volumes: uint8, uint16, int16, uint32, int32, float32, float64")
    r.add_argument("--voxel-bits", type=int, help="voxel width VOXEL_W (default: the scene's, else 8)")
    r.add_argument("--background", default="0,0,0", help="R,G,B in [0,1] behind the volume in PNG/TIFF output")
    r.add_argument("--view", action="append", metavar="AZ,EL",
                   help="render from azimuth,elevation in degrees instead of the scene's view; repeat for "
                        "several views (outputs get _000, _001, ... before the suffix, or put {n} in the name)")
    r.add_argument("--orbit", type=int, metavar="N",
                   help="render N views evenly spaced in azimuth around the scene's view (elevation kept)")
    r.add_argument("--bricks", metavar="BX,BY,BZ",
                   help="render in BX*BY*BZ bricks (sub-volumes with overlap) and composite them in order")
    r.add_argument("--board-dim", type=int, metavar="N",
                   help="largest brick (with its overlap) one board takes, voxels per axis; without --bricks "
                        "the fewest bricks that fit are used")
    r.add_argument("--workers", type=int, metavar="N",
                   help="render the bricks on a local Dask cluster of N worker processes")
    r.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                   help="render the bricks on the Dask cluster of this scheduler")
    r.add_argument("--no-skip", action="store_true",
                   help="traverse the whole volume (the fixed schedule) instead of only the box that can change "
                        "a ray; the image is the same, --stats compares the cycles")
    r.add_argument("--rects", action="store_true",
                   help="within the box, each sample slice traverses only its own rectangle (slice "
                        "rectangles; S = 1); the image is the same, --stats compares the cycles")
    r.add_argument("--gradient", choices=GRADIENTS,
                   help="the gradient estimator instead of the scene's [render] gradient: gra (the paper's, on "
                        "the sample stream), central or sobel (at the voxels, interpolated by TRI)")
    r.add_argument("--path-weights", action=argparse.BooleanOptionalAction, default=None,
                   help="weight each ray's first and last samples by their share of the ray's path (the scene's "
                        "[render] path_weights; needs a build with PLW = 1)")
    r.add_argument("--preset", choices=tuple(PRESETS),
                   help="a named preset over the scene: default (the scene as it is) or quality (voxel central "
                        "differences, S = 4, 2x2 sub-pixel passes, path weights: 40 dB or more on the built-in "
                        "phantoms); --gradient and --path-weights still override it")
    r.add_argument("--quiet", action="store_true", help="no progress bars or summary")
    sub.add_parser("volumes", help="list the built-in volumes")
    sub.add_parser("scenes", help="list the built-in scenes")
    return ap


def _check_output(path: str, suffixes: tuple[str, ...], what: str) -> Path:
    p = Path(path)
    if p.suffix.lower() not in suffixes:
        raise UserError(f"{what} {path!r} must end in {', '.join(suffixes)}")
    check_destination(p, what)
    return p


def _json_safe(d: dict) -> dict:
    """inf/NaN are not JSON: an identical image has PSNR null ("infinite")."""
    return {k: (None if isinstance(v, float) and not np.isfinite(v) else v) for k, v in d.items()}


def write_image(path: str, rgba: np.ndarray, background=(0.0, 0.0, 0.0)) -> None:
    """Premultiplied RGBA -> file: EXR keeps float RGBA; PNG/TIFF get 8-bit RGB over the
    background colour."""
    import OpenImageIO as oiio

    if path.lower().endswith(".exr"):
        data, fmt = rgba.astype(np.float32), oiio.HALF
    else:
        bg = np.asarray(background, dtype=np.float64)
        rgb = rgba[..., :3] + (1.0 - rgba[..., 3:4]) * bg
        data, fmt = np.clip(rgb, 0.0, 1.0).astype(np.float32), oiio.UINT8
    buf = oiio.ImageBuf(np.ascontiguousarray(data))
    if not buf.write(path, fmt):
        raise UserError(f"cannot write image {path}: {buf.geterror()}")


def _background(text: str) -> tuple[float, float, float]:
    try:
        vals = tuple(float(v) for v in text.split(","))
    except ValueError:
        vals = ()
    if len(vals) != 3 or not all(0.0 <= v <= 1.0 for v in vals):
        raise UserError(f"--background must be R,G,B with values in [0, 1], got {text!r}")
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
            az, el = (float(v) for v in text.split(","))
        except ValueError:
            raise UserError(f"--view must be AZ,EL in degrees, got {text!r}") from None
        if not (-360.0 <= az <= 360.0 and -90.0 <= el <= 90.0):
            raise UserError(f"--view {text!r}: azimuth must be in -360..360 and elevation in -90..90")
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


def cmd_render(args: argparse.Namespace) -> int:
    out = _check_output(args.out, IMAGE_SUFFIXES, "--out")
    bp = _check_output(args.baseplane, (".npy",), "--baseplane") if args.baseplane else None
    st = _check_output(args.stats, (".json",), "--stats") if args.stats else None
    bg = _background(args.background)
    if args.baseplane and args.engine == "reference":
        raise UserError("--baseplane needs a Cube-4 engine (golden or rtl); the reference has no base plane")
    if args.pipelines is not None and not 1 <= args.pipelines <= MAX_PIPELINES:
        raise UserError(f"--pipelines must be in 1..{MAX_PIPELINES}, got {args.pipelines}")
    scene = load_scene(args.scene)
    scenes = _views(args, scene)
    if args.no_skip and args.rects:
        raise UserError("--no-skip and --rects exclude each other")
    if args.no_skip:
        scenes = [replace(sc, skip=False) for sc in scenes]
    if args.rects:
        scenes = [replace(sc, skip="rects") for sc in scenes]
    if args.preset:
        scenes = [apply_preset(sc, args.preset) for sc in scenes]
    if args.gradient:
        scenes = [replace(sc, gradient=args.gradient) for sc in scenes]
    if args.path_weights is not None:
        scenes = [replace(sc, path_weights=args.path_weights) for sc in scenes]
    scene = scenes[0]       # with the preset, --gradient, --path-weights: its keys (S among them) choose the hardware
    bricks = _brick_options(args, scene)
    count = len(scenes)
    # every destination, numbered per view, checked before any work
    named = [(_numbered(out, n, count), "--out") for n in range(count)]
    if bp is not None:
        named += [(_numbered(bp, n, count), "--baseplane") for n in range(count)]
    if st is not None:
        named.append((st, "--stats"))
    check_destinations(named)
    build = parse_build(args.build)
    cfg = config_for(scene, pipelines=args.pipelines, voxel_bits=args.voxel_bits,
                     build=None if build is None else tuple(build.items()))
    resolve_build(cfg, scenes)    # a scene that needs what the build leaves out: one line, before any work
    raw_dims = _dims(args.dims) if args.dims else None
    vol = load_volume(args.volume, voxel_bits=cfg.voxel_bits, raw_dims=raw_dims, raw_dtype=args.dtype)
    progress = not args.quiet and sys.stderr.isatty()
    if bricks is None:
        results = render_views(vol, scenes, cfg, args.engine, progress=progress)
    else:
        results = _render_bricked(args, vol, scenes, cfg, bricks, progress)
    frames = []
    for res, sc in zip(results, scenes):
        stats = dict(res.stats)
        stats["volume"] = args.volume
        stats["scene"] = scene.name
        stats["azimuth"], stats["elevation"] = angles_from_direction(sc.direction)
        if args.compare_to:
            ref = render(vol, sc, cfg, "reference", progress=progress)
            stats.update(image_metrics(res.image, ref.image))
            stats["reference_wall_s"] = ref.wall_s
        frames.append(stats)

    outputs: list[tuple[Path, Writer]] = []
    for n, res in enumerate(results):
        outputs.append((_numbered(out, n, count), lambda tmp, img=res.image: write_image(tmp, img, bg)))
        if bp is not None and res.frame is not None:
            outputs.append((_numbered(bp, n, count), lambda tmp, base=res.frame.baseplane: np.save(tmp, base)))
    if st is not None:
        if count == 1:
            doc = _json_safe(frames[0])
        else:
            doc = {"views": count, "frames": [_json_safe(f) for f in frames],
                   "wall_s": sum(f["wall_s"] for f in frames)}
            if all("cycles" in f for f in frames):
                doc["cycles"] = sum(f["cycles"] for f in frames)
                doc["sim_wall_s"] = sum(f["sim_wall_s"] for f in frames)
                doc["sim_cycles_per_s"] = doc["cycles"] / doc["sim_wall_s"] if doc["sim_wall_s"] > 0 else None
        text = json.dumps(doc, indent=2, allow_nan=False) + "\n"
        outputs.append((st, lambda tmp: Path(tmp).write_text(text)))
    write_all(outputs)
    if not args.quiet:
        for n, (stats, res) in enumerate(zip(frames, results)):
            line = (f"cube4: {args.engine} render of {args.volume} {tuple(stats['dims'])} "
                    f"in {res.wall_s:.2f} s -> {_numbered(out, n, count)}")
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
            if args.compare_to:
                line += (f"; vs reference: PSNR {stats['psnr']:.2f} dB, RMSE {stats['rmse']:.4f}, "
                         f"max {stats['max_abs']:.3f}")
            print(line)
    return 0


def _brick_options(args: argparse.Namespace, scene: Scene):
    """(grid counts or None, board dim or None) when the render goes in bricks, else None;
    every option checked before any work."""
    if args.workers is not None and args.scheduler is not None:
        raise UserError("--workers and --scheduler exclude each other")
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
        if args.cmd == "volumes":
            for name, (_, desc) in sorted(BUILTINS.items()):
                print(f"{name:10s} {desc}")
            return 0
        if args.cmd == "scenes":
            print("\n".join(builtin_scene_names()))
            return 0
    except UserError as e:
        print(f"cube4: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("cube4: interrupted", file=sys.stderr)
        return 130
    return 1


if __name__ == "__main__":
    sys.exit(main())

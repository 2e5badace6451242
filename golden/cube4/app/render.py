"""One render, any engine: volume + scene -> image-plane RGBA (+ base plane, stats).

This module owns three engines: ``reference`` (the float64 truth straight into the image
plane, each pixel the mean over its square, ``cube4.reference.converged_reference``),
``reference-point`` (the same with one ray through each pixel's centre) and ``golden`` (the bit-exact Cube-4 model, ``cube4.host.golden_view``, its base
plane warped to the image plane by OpenImageIO, ``cube4.app.warp``). Other engines are
added from outside with ``register_engine``; this package never imports them (the
``cube4`` command registers the simulated RTL, ``rtl``). ``render_bricked_views`` renders
views in bricks (``cube4.bricks``) on an executor, composited and warped.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from ..bricks import LocalExecutor, assemble, brick_tasks, check_board, counts_for_board, make_grid
from ..config import Cube4Config
from ..errors import UserError
from ..geometry import composite_over
from ..host import (ViewPlan, crop_volume, frame_clip, golden_view, host_tables, memory_volume, scene_geometry, setup_view,
                    trav_stats, view_stats)
from ..model import Frame
from ..reference import converged_reference, render_reference
from ..scene import Scene, crop_box
from ..subpixel import fine_to_base
from ..view import Camera, Traversal, warp_matrix
from .mesh import resolve_geometry
from .progress import bars
from .warp import warp_to_image


@dataclass
class RenderResult:
    engine: str
    image: np.ndarray  # (H, W, 4) premultiplied RGBA float64 in [0, 1]
    wall_s: float
    frame: Frame | None = None
    stats: dict = field(default_factory=dict)
    # depth out (numerics.md §21): (H, W, 2) float64, the threshold's and the first sample's
    # distance along the view direction from the volume's centre (voxels), NaN: none
    depth: np.ndarray | None = None


def view_image(vp: ViewPlan, frame: Frame) -> np.ndarray:
    """The frame's base plane warped to the view's image plane."""
    q = vp.scene.subpixel
    return scene_warp(frame.baseplane_float, vp.trav, vp.cam, vp.scene, pre=None if q == 1 else fine_to_base(q))


def depth_image(vp: ViewPlan, frame: Frame) -> np.ndarray:
    """The frame's depth out in the image plane (numerics.md §21): each image pixel takes
    the depths of the (fine) base-plane pixel nearest to its centre under the warp's
    inverse, unfiltered, so that no depth lies between two surfaces; NaN where that pixel
    holds none or lies outside the plane."""
    q = vp.scene.subpixel
    m = warp_matrix(vp.trav, vp.cam)
    if q > 1:
        m = m @ fine_to_base(q)
    inv = np.linalg.inv(m)
    h, w = vp.cam.height, vp.cam.width
    rr, cc = np.mgrid[0:h, 0:w]
    fx = np.floor(inv[0, 0] * cc + inv[0, 1] * rr + inv[0, 2] + 0.5).astype(np.int64)
    fy = np.floor(inv[1, 0] * cc + inv[1, 1] * rr + inv[1, 2] + 0.5).astype(np.int64)
    z = frame.depth_z
    rows, cols = z.shape[:2]
    ok = (fx >= 0) & (fx < cols) & (fy >= 0) & (fy < rows)
    out = np.full((h, w, z.shape[-1]), np.nan)
    out[ok] = z[fy[ok], fx[ok]]
    return out


def depth_stats(depth: np.ndarray, threshold: float) -> dict:
    """--stats key ``depth``: the threshold, the share of image pixels with each depth and
    their range (voxels along the view direction from the volume's centre)."""
    out = {"threshold": threshold}
    for c, name in enumerate(("passed", "first")):
        z = depth[..., c]
        seen = np.isfinite(z)
        out[name] = {"pixels": float(seen.mean()),
                     "min": float(z[seen].min()) if seen.any() else None,
                     "max": float(z[seen].max()) if seen.any() else None}
    return out


def scene_warp(base: np.ndarray, trav: Traversal, cam: Camera, scene: Scene,
               pre: np.ndarray | None = None) -> np.ndarray:
    """The base plane warped to the image as the scene's [output] asks (filter, footprint);
    ``pre``: a plane whose pixels map to ``trav``'s base-plane points by it (q×q passes)."""
    return warp_to_image(base, trav, cam, filtername=scene.filter, footprint=scene.footprint, pre=pre)


#: An engine renders one or more views of one volume:
#: (vol[z, y, x], scenes, cfg, progress) -> one RenderResult per scene, in order.
Engine = Callable[[np.ndarray, list[Scene], Cube4Config, bool], list[RenderResult]]

_ENGINES: dict[str, Engine] = {}


def register_engine(name: str, fn: Engine) -> None:
    """Make an engine available to ``render``, ``render_views`` and the command line."""
    _ENGINES[name] = fn


def engine_names() -> tuple[str, ...]:
    """The registered engines, in registration order."""
    return tuple(_ENGINES)


def _engine(name: str) -> Engine:
    if name not in _ENGINES:
        raise UserError(f"unknown engine {name!r} (engines: {', '.join(_ENGINES)})")
    return _ENGINES[name]


def render_reference_view(vol: np.ndarray, scene: Scene, cfg: Cube4Config, progress: bool = False,
                          area: bool = True) -> RenderResult:
    """The float64 reference image of one view: the area truth (``area``, the stats say
    how it converged: ``truth_k``, ``truth_change``, ``truth``) or the centre points."""
    nz, ny, nx = vol.shape
    dims = (nx, ny, nz)
    scene = replace(scene, preview=1)       # the truth of a preview level is the whole volume's
    _, cam = setup_view(dims, scene, cfg)
    name = "reference" if area else "reference-point"
    stats = view_stats(name, dims, scene, cfg)
    t0 = time.perf_counter()
    box = crop_box(scene, dims)
    scene = resolve_geometry(scene, cam)
    geo = scene_geometry(scene, cam)
    if area:
        img, conv = converged_reference(vol, cfg.voxel_bits, scene, cam, progress=bars(progress), box=box)
        stats.update(truth="area", truth_k=conv.k, truth_change=conv.change, truth_converged=conv.converged,
                     truth_steps=conv.text())
    else:
        img = render_reference(vol, cfg.voxel_bits, scene, cam, progress=bars(progress), box=box)
        stats.update(truth="point")
    return _timed(RenderResult(name, composite_over(img, geo), 0.0, stats=stats), t0)


def render_golden_view(vol: np.ndarray, scene: Scene, cfg: Cube4Config, keep_streams: bool = False,
                       progress: bool = False, rects: bool = False) -> RenderResult:
    """One view through the bit-exact model (``cube4.host.golden_view``), warped to the
    image plane; ``rects``: each frame computes only its slice rectangles (stats
    ``rect_beats``)."""
    t0 = time.perf_counter()
    nz, ny, nx = vol.shape
    scene = resolve_geometry(scene, setup_view((nx, ny, nz), scene, cfg)[1])
    vp, frame, stats = golden_view(vol, scene, cfg, keep_streams=keep_streams, progress=bars(progress), rects=rects)
    res = RenderResult("golden", composite_over(view_image(vp, frame), scene_geometry(scene, vp.cam)), 0.0,
                       frame=frame, stats=stats)
    if frame.depth_z is not None:
        res.depth = depth_image(vp, frame)
        res.stats["depth"] = depth_stats(res.depth, scene.depth_threshold)
    return _timed(res, t0)


def _timed(res: RenderResult, t0: float) -> RenderResult:
    res.wall_s = time.perf_counter() - t0
    res.stats["wall_s"] = res.wall_s
    return res


register_engine("reference", lambda vol, scenes, cfg, progress: [
    render_reference_view(vol, sc, cfg, progress) for sc in scenes])
register_engine("reference-point", lambda vol, scenes, cfg, progress: [
    render_reference_view(vol, sc, cfg, progress, area=False) for sc in scenes])
register_engine("golden", lambda vol, scenes, cfg, progress: [
    render_golden_view(vol, sc, cfg, progress=progress) for sc in scenes])


def render(
    vol: np.ndarray,
    scene: Scene,
    cfg: Cube4Config,
    engine: str,
    keep_streams: bool = False,
    progress: bool = False,
) -> RenderResult:
    """Render vol[z, y, x] (VOXEL_W-bit unsigned) with one engine; ``keep_streams``
    (golden only) keeps the model's intermediate streams in the frame."""
    if engine == "golden":
        return render_golden_view(vol, scene, cfg, keep_streams=keep_streams, progress=progress)
    return render_views(vol, [scene], cfg, engine, progress=progress)[0]


def render_views(
    vol: np.ndarray,
    scenes: list[Scene],
    cfg: Cube4Config,
    engine: str,
    progress: bool = False,
) -> list[RenderResult]:
    """Render several views (one scene each, e.g. ``scene.with_view``) of one volume.
    An engine may run them together (the RTL engine loads the volume once and runs the
    frames back to back)."""
    fn = _engine(engine)
    if not scenes:
        raise UserError("no view to render")
    return fn(vol, scenes, cfg, progress)


def render_bricked_views(vol: np.ndarray, scenes, cfg: Cube4Config, engine: str, grid_counts, *,
                         board_dim: int | None = None, executor=None, progress: bool = False) -> list:
    """Every scene's view of vol[z, y, x] rendered in bricks (``grid_counts`` bricks per
    axis of the traversed box; None: the fewest that fit ``board_dim``), composited and
    warped: one ``RenderResult`` per scene. All bricks of all views go to the
    executor at once."""
    if grid_counts is None and board_dim is None:
        raise ValueError("give the bricks per axis or the board's largest brick")
    if any(sc.subpixel != 1 for sc in scenes):
        raise UserError("--bricks renders one pass per view: set [render] subpixel = 1 in the scene")
    if any(sc.preview != 1 for sc in scenes):
        raise UserError("a preview level ([render] preview, --preview) does not run in bricks: render it whole")
    if any(sc.depth_threshold is not None for sc in scenes):
        raise UserError("depth out ([output] depth_threshold) is not rendered in bricks: render the volume whole")
    if any(sc.geometry is not None for sc in scenes):
        raise UserError("depth in ([geometry]) is not rendered in bricks: render the volume whole")
    if any(sc.labels is not None for sc in scenes):
        raise UserError("label volumes ([[label]]) are not rendered in bricks: render the volume whole")
    if any(sc.gmod is not None for sc in scenes):
        raise UserError("gradient-magnitude modulation ([gradient_modulation]) is not rendered in bricks: "
                        "render the volume whole")
    nz, ny, nx = vol.shape
    dims = (nx, ny, nz)
    executor = executor or LocalExecutor()
    t0 = time.perf_counter()
    views, all_tasks, spans = [], [], []
    for nv, sc in enumerate(scenes):
        trav, cam = setup_view(dims, sc, cfg)
        counts = tuple(grid_counts) if grid_counts is not None else counts_for_board(trav.dims, board_dim)
        grid = make_grid(trav.dims, counts)
        check_board(grid, board_dim)
        lut, rmap = host_tables(sc, cfg, trav)
        bricks, tasks = brick_tasks(crop_volume(memory_volume(vol, sc, cfg), trav), trav, cfg, lut, rmap, grid,
                                    engine=engine, mode=sc.mode, shading=sc.shaded, clip=frame_clip(sc, trav),
                                    board_dim=board_dim, vgrad=sc.voxel_gradients)
        if len(scenes) > 1:
            for t in tasks:
                t.label = f"view {nv} {t.label}"
        views.append((sc, trav, cam, grid, bricks))
        spans.append((len(all_tasks), len(all_tasks) + len(tasks)))
        all_tasks.extend(tasks)
    results = executor.run(all_tasks, progress=bars(progress))
    run_s = time.perf_counter() - t0
    ex_stats = executor.stats()
    out = []
    for (sc, trav, cam, grid, bricks), (a, b) in zip(views, spans):
        t1 = time.perf_counter()
        frame, comp_s = assemble(trav, cfg, bricks, results[a:b], sc.mode)
        img = scene_warp(frame.baseplane_float, trav, cam, sc)
        stats = view_stats(engine, dims, sc, cfg)
        stats.update(trav_stats(trav))
        res = results[a:b]
        stats["bricks"] = {
            "grid": list(grid.counts), "count": grid.size, "largest": list(grid.largest_brick()),
            "stored_voxels": grid.stored_voxels(), "memory_overhead": grid.memory_overhead,
            "brick_wall_s": sum(r.wall_s for r in res), "composite_s": comp_s, **ex_stats,
        }
        if all(r.cycles is not None for r in res):
            stats["cycles"] = sum(int(r.cycles) for r in res)
        wall = run_s / len(views) + time.perf_counter() - t1
        stats["wall_s"] = wall
        out.append(RenderResult(engine, img, wall, frame=frame, stats=stats))
    return out

"""One render, any engine: volume + scene -> image-plane RGBA (+ base plane, stats).

Engines: ``reference`` (float64 truth, straight into the image plane), ``golden`` (the
bit-exact Cube-4 model, base plane warped to the image plane by OpenImageIO) and
``rtl`` (the Verilated cube4_top, sim/cube4_sim/rtl.py).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from .config import Cube4Config
from .errors import UserError
from .model import Frame, render_frame
from .reference import render_reference
from .scene import Scene
from .tables import classification_lut, reflectance_map
from .view import Camera, Traversal, make_camera, make_traversal, warp_matrix

ENGINES = ("reference", "golden", "rtl")


@dataclass
class RenderResult:
    engine: str
    image: np.ndarray  # (H, W, 4) premultiplied RGBA float64 in [0, 1]
    wall_s: float
    frame: Frame | None = None
    stats: dict = field(default_factory=dict)


def config_for(scene: Scene, pipelines: int | None = None, **overrides) -> Cube4Config:
    """The hardware configuration a scene asks for (scene [precision], supersampling),
    with command-line overrides."""
    kw = dict(scene.precision)
    kw["supersample"] = scene.supersample
    if pipelines is not None:
        kw["pipelines"] = pipelines
    kw.update({k: v for k, v in overrides.items() if v is not None})
    return Cube4Config(**kw)


def setup_view(dims, scene: Scene, cfg: Cube4Config) -> tuple[Traversal, Camera]:
    trav = make_traversal(dims, scene.direction, cfg.weight_bits, cfg.supersample)
    cam = make_camera(dims, scene.direction, scene.width, scene.height, scene.up)
    return trav, cam


def host_tables(scene: Scene, cfg: Cube4Config, trav: Traversal) -> tuple[np.ndarray, np.ndarray]:
    """What the host writes into the LUT load ports for this view: the classification
    LUT with opacity corrected for the sample distance, and the reflectance map."""
    return classification_lut(scene, cfg, trav.sample_distance), reflectance_map(scene, cfg, trav)


def warp_to_image(base: np.ndarray, trav: Traversal, cam: Camera) -> np.ndarray:
    """Warp a float base plane (rows, cols, 4) to the image plane (H, W, 4) with
    OpenImageIO (bilinear, black outside)."""
    import OpenImageIO as oiio

    a = warp_matrix(trav, cam)  # integer pixel centres, column vectors
    # OIIO: pixel centres at +0.5, row-vector matrices (p' = p M).
    shift = np.array([[1.0, 0.0, 0.5], [0.0, 1.0, 0.5], [0.0, 0.0, 1.0]])
    unshift = np.array([[1.0, 0.0, -0.5], [0.0, 1.0, -0.5], [0.0, 0.0, 1.0]])
    m = shift @ a @ unshift
    m_row = tuple(float(x) for x in m.T.reshape(-1))  # Python floats (numpy scalars read as identity)
    src = oiio.ImageBuf(np.ascontiguousarray(base, dtype=np.float32))
    roi = oiio.ROI(0, cam.width, 0, cam.height, 0, 1, 0, 4)
    dst = oiio.ImageBufAlgo.warp(src, m_row, filtername="triangle", wrap="black", roi=roi)
    if dst.has_error:
        raise RuntimeError(f"OpenImageIO warp failed: {dst.geterror()}")
    out = dst.get_pixels(oiio.FLOAT, roi)
    return np.asarray(out, dtype=np.float64).reshape(cam.height, cam.width, 4)


def image_metrics(img: np.ndarray, ref: np.ndarray) -> dict:
    """RMSE, max |error| and PSNR (peak 1.0) over all four premultiplied RGBA channels."""
    err = img.astype(np.float64) - ref.astype(np.float64)
    rmse = float(np.sqrt(np.mean(err * err)))
    psnr = float("inf") if rmse == 0 else float(20.0 * np.log10(1.0 / rmse))
    return {"rmse": rmse, "max_abs": float(np.max(np.abs(err))), "psnr": psnr}


def _view_stats(engine: str, dims, scene: Scene, cfg: Cube4Config) -> dict:
    return {
        "engine": engine,
        "dims": list(dims),
        "pipelines": cfg.pipelines,
        "view": [float(c) for c in scene.direction],
        "config": cfg.as_dict(),
    }


def _trav_stats(trav: Traversal) -> dict:
    return {
        "major_axis": "xyz"[trav.major],
        "view_x": trav.view_x,
        "view_y": trav.view_y,
        "sample_distance": trav.sample_distance,
        "baseplane_shape": list(trav.baseplane_shape),
    }


def render(
    vol: np.ndarray,
    scene: Scene,
    cfg: Cube4Config,
    engine: str,
    keep_streams: bool = False,
    progress: bool = False,
) -> RenderResult:
    """Render vol[z, y, x] (VOXEL_W-bit unsigned) with one engine."""
    if engine not in ENGINES:
        raise UserError(f"unknown engine {engine!r} (engines: {', '.join(ENGINES)})")
    if engine == "rtl":
        return render_views(vol, [scene], cfg, engine, progress=progress)[0]
    nz, ny, nx = vol.shape
    dims = (nx, ny, nz)
    trav, cam = setup_view(dims, scene, cfg)
    stats = _view_stats(engine, dims, scene, cfg)
    t0 = time.perf_counter()
    if engine == "reference":
        img = render_reference(vol, cfg.voxel_bits, scene, cam, progress=progress)
        res = RenderResult(engine, img, 0.0, stats=stats)
    else:  # golden
        lut, rmap = host_tables(scene, cfg, trav)
        frame = render_frame(vol, trav, cfg, lut, rmap, keep_streams=keep_streams, progress=progress)
        img = warp_to_image(frame.baseplane_float, trav, cam)
        res = RenderResult(engine, img, 0.0, frame=frame, stats=stats)
        stats.update(_trav_stats(trav))
        stats["pixels"] = int(frame.pixels.size)
    res.wall_s = time.perf_counter() - t0
    stats["wall_s"] = res.wall_s
    return res


def render_views(
    vol: np.ndarray,
    scenes: list[Scene],
    cfg: Cube4Config,
    engine: str,
    progress: bool = False,
) -> list[RenderResult]:
    """Render several views (one scene each, e.g. ``scene.with_view``) of one volume.

    The ``rtl`` engine runs all of them in one simulation: the volume is loaded into
    the simulated voxel memory once and the frames run back to back, each with its
    own view registers and tables. Each result's ``wall_s`` is then its share of the
    whole run (simulation time of its frame plus an equal part of the rest)."""
    if engine not in ENGINES:
        raise UserError(f"unknown engine {engine!r} (engines: {', '.join(ENGINES)})")
    if not scenes:
        raise UserError("no view to render")
    if engine != "rtl":
        return [render(vol, sc, cfg, engine, progress=progress) for sc in scenes]

    from cube4_sim.rtl import FrameJob, baseplane_from_pixels, render_frames

    nz, ny, nx = vol.shape
    dims = (nx, ny, nz)
    t0 = time.perf_counter()
    views = [setup_view(dims, sc, cfg) for sc in scenes]
    jobs = [FrameJob(trav, *host_tables(sc, cfg, trav)) for sc, (trav, _) in zip(scenes, views)]
    outs = render_frames(vol, jobs, cfg, progress=progress, quiet=True)
    run_s = time.perf_counter() - t0
    sim_total = sum(o["sim_wall_s"] for o in outs)
    results = []
    for sc, (trav, cam), out in zip(scenes, views, outs):
        t1 = time.perf_counter()
        base = baseplane_from_pixels(out["pixels"], trav.baseplane_shape)
        frame = Frame(trav=trav, cfg=cfg, baseplane=base, pixels=out["pixels"])
        img = warp_to_image(frame.baseplane_float, trav, cam)
        cycles = int(out["cycles"])
        ideal = nx * ny * nz / cfg.pipelines
        stats = _view_stats(engine, dims, sc, cfg)
        stats.update(_trav_stats(trav))
        stats.update({
            "pixels": int(out["pixels"].size),
            "cycles": cycles,
            "ideal_cycles": ideal,
            "efficiency": ideal / cycles,
            "sim_wall_s": out["sim_wall_s"],
            "sim_cycles_per_s": cycles / out["sim_wall_s"] if out["sim_wall_s"] > 0 else None,
        })
        wall = out["sim_wall_s"] + (run_s - sim_total) / len(scenes) + time.perf_counter() - t1
        stats["wall_s"] = wall
        results.append(RenderResult(engine, img, wall, frame=frame, stats=stats))
    return results

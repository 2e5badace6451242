"""The ``rtl`` render engine: views rendered by the simulated cube4_top.

``register()`` adds it to ``cube4.render``'s engines (the ``cube4`` command and
``make report`` call it). All views of one call run in one simulation: the volume is
loaded into the simulated voxel memory once and the frames run back to back, each with
its own view registers and tables. Each result's ``wall_s`` is its share of the whole
run (simulation time of its frame plus an equal part of the rest).
"""

from __future__ import annotations

import time

import numpy as np

from cube4.bricks import register_brick_renderer
from cube4.config import Cube4Config, resolve_build
from cube4.errors import UserError
from cube4.model import PIXEL_DTYPE, Frame
from cube4.render import (RenderResult, crop_volume, frame_clip, host_tables, register_engine, schedule,
                          schedule_stats, setup_view, trav_stats, view_stats, warp_to_image)
from cube4.scene import Scene

from .rtl import FrameJob, baseplane_from_pixels, render_frames
from .errors import SimulationError

NAME = "rtl"


def render_rtl(vol: np.ndarray, scenes: list[Scene], cfg: Cube4Config, progress: bool = False) -> list[RenderResult]:
    """Render every scene's view of vol[z, y, x] through the RTL, in one simulation."""
    nz, ny, nx = vol.shape
    dims = (nx, ny, nz)
    t0 = time.perf_counter()
    build = resolve_build(cfg, scenes)      # before any simulation: one line if a scene needs more
    views = [setup_view(dims, sc, cfg) for sc in scenes]
    plans, jobs = [], []
    for sc, (trav, _) in zip(scenes, views):
        lut, rmap = host_tables(sc, cfg, trav)
        plan = schedule(crop_volume(vol, trav), sc, trav, lut, frame_clip(sc, trav))
        plans.append(plan)
        if plan.trav is not None:       # a frame in which nothing can change a ray is not run
            jobs.append(FrameJob(plan.trav, lut, rmap, mode=sc.mode, clip=plan.clip))
    try:
        outs = render_frames(vol, jobs, cfg, progress=progress, quiet=True, build=build) if jobs else []
    except SimulationError as exc:     # one line, naming the build or simulation log
        raise UserError(f"RTL engine: {exc}") from None
    run_s = time.perf_counter() - t0
    sim_total = sum(o["sim_wall_s"] for o in outs)
    results = []
    ran = iter(outs)
    for sc, (trav, cam), plan in zip(scenes, views, plans):
        t1 = time.perf_counter()
        out = next(ran) if plan.trav is not None else _no_frame()
        sub = baseplane_from_pixels(out["pixels"], plan.trav.baseplane_shape) if plan.trav is not None else None
        frame = Frame(trav=trav, cfg=cfg, baseplane=plan.place(sub), pixels=plan.place_pixels(out["pixels"]))
        img = warp_to_image(frame.baseplane_float, trav, cam)
        stats = view_stats(NAME, dims, sc, cfg)
        stats.update(trav_stats(trav))
        stats.update(schedule_stats(plan, cfg, build))
        stats.update(_cycle_stats(out, nx * ny * nz / cfg.pipelines))
        stats["build"] = dict(build)
        wall = out["sim_wall_s"] + (run_s - sim_total) / len(scenes) + time.perf_counter() - t1
        stats["wall_s"] = wall
        results.append(RenderResult(NAME, img, wall, frame=frame, stats=stats))
    return results


def _no_frame() -> dict:
    return {"pixels": np.empty(0, dtype=PIXEL_DTYPE), "cycles": 0, "sim_wall_s": 0.0}


def _cycle_stats(out: dict, ideal: float) -> dict:
    cycles = int(out["cycles"])
    return {
        "pixels": int(out["pixels"].size),
        "cycles": cycles,
        "ideal_cycles": ideal,
        "efficiency": ideal / cycles if cycles else None,
        "sim_wall_s": out["sim_wall_s"],
        "sim_cycles_per_s": cycles / out["sim_wall_s"] if out["sim_wall_s"] > 0 else None,
    }


def register() -> None:
    """Add the ``rtl`` engine to ``cube4.render``, and its brick renderer to
    ``cube4.bricks`` (by import path: a Dask worker imports it there)."""
    register_engine(NAME, render_rtl)
    register_brick_renderer(NAME, "cube4_sim.bricks:render_brick_rtl")

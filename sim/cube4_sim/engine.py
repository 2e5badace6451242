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
from cube4.model import Frame
from cube4.render import (RenderResult, frame_clip, host_tables, register_engine, scene_warp, setup_view,
                          trav_stats, view_stats)
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
    jobs = [FrameJob(trav, *host_tables(sc, cfg, trav), mode=sc.mode, clip=frame_clip(sc, trav))
            for sc, (trav, _) in zip(scenes, views)]
    try:
        outs = render_frames(vol, jobs, cfg, progress=progress, quiet=True, build=build)
    except SimulationError as exc:     # one line, naming the build or simulation log
        raise UserError(f"RTL engine: {exc}") from None
    run_s = time.perf_counter() - t0
    sim_total = sum(o["sim_wall_s"] for o in outs)
    results = []
    for sc, (trav, cam), out in zip(scenes, views, outs):
        t1 = time.perf_counter()
        base = baseplane_from_pixels(out["pixels"], trav.baseplane_shape)
        frame = Frame(trav=trav, cfg=cfg, baseplane=base, pixels=out["pixels"])
        img = scene_warp(frame.baseplane_float, trav, cam, sc)
        stats = view_stats(NAME, dims, sc, cfg)
        stats.update(trav_stats(trav))
        stats.update(_cycle_stats(out, nx * ny * nz / cfg.pipelines))
        stats["build"] = dict(build)
        wall = out["sim_wall_s"] + (run_s - sim_total) / len(scenes) + time.perf_counter() - t1
        stats["wall_s"] = wall
        results.append(RenderResult(NAME, img, wall, frame=frame, stats=stats))
    return results


def _cycle_stats(out: dict, ideal: float) -> dict:
    cycles = int(out["cycles"])
    return {
        "pixels": int(out["pixels"].size),
        "cycles": cycles,
        "ideal_cycles": ideal,
        "efficiency": ideal / cycles,
        "sim_wall_s": out["sim_wall_s"],
        "sim_cycles_per_s": cycles / out["sim_wall_s"] if out["sim_wall_s"] > 0 else None,
    }


def register() -> None:
    """Add the ``rtl`` engine to ``cube4.render``, and its brick renderer to
    ``cube4.bricks`` (by import path: a Dask worker imports it there)."""
    register_engine(NAME, render_rtl)
    register_brick_renderer(NAME, "cube4_sim.bricks:render_brick_rtl")

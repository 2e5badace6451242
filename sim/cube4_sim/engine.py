"""The ``rtl`` render engine: views rendered by the simulated cube4_top.

``register()`` adds it to ``cube4.app.render``'s engines (the ``cube4`` command and
``make report`` call it). All views of one call run in one simulation: the volume is
loaded into the simulated voxel memory once and the frames run back to back, each with
its own view registers and tables. Each result's ``wall_s`` is its share of the whole
run (simulation time of its frame plus an equal part of the rest).
"""

from __future__ import annotations

import time

import numpy as np

from cube4.app.mesh import resolve_geometry
from cube4.app.render import RenderResult, depth_image, depth_stats, register_engine, view_image
from cube4.bricks import register_brick_renderer
from cube4.beats import BeatSchedule
from cube4.config import Cube4Config, resolve_build
from cube4.cycles import has_falloff, rect_frame_cycles
from cube4.errors import UserError
from cube4.geometry import composite_over, stop_slices
from cube4.host import (assemble_view, beat_schedules, build_memory, depth_threshold, pass_rects, plan_view,
                        scene_geometry, schedule_stats, setup_view, tau_fixed, trav_stats, view_stats)
from cube4.scene import Scene, with_schedule

from .dram_core import DATA_W, DramRun, core_info
from .rtl import FrameJob, baseplane_from_pixels, depth_from_pixels, frame_rects, render_frames
from .errors import SimulationError

NAME = "rtl"


def render_rtl(vol: np.ndarray, scenes: list[Scene], cfg: Cube4Config, progress: bool = False,
               dram: DramRun | None = None) -> list[RenderResult]:
    """Render every scene's view of vol[z, y, x] through the RTL, in one simulation;
    ``dram``: with the voxel memory in the simulated DRAM (the ``rtl-dram`` engine)."""
    nz, ny, nx = vol.shape
    dims = (nx, ny, nz)
    t0 = time.perf_counter()
    # a scene that leaves [render] skip out: its default schedule on cfg.build
    scenes = [with_schedule(sc, None if cfg.build is None else dict(cfg.build), supersample=cfg.supersample)
              for sc in scenes]
    build = resolve_build(cfg, scenes)      # before any simulation: one line if a scene needs more
    if build.get("BEATS") and any(sc.schedule != "beats" for sc in scenes):
        raise UserError("a build with BEATS = 1 runs the beat schedule only: render the other scenes "
                        "separately, or give them --beats")
    scenes = [resolve_geometry(sc, setup_view(dims, sc, cfg)[1]) for sc in scenes]   # depth in: its image
    vps = [plan_view(vol, sc, cfg) for sc in scenes]
    use_rects = bool(build["RECTS"])   # one build: a RECTS build runs every view with rectangles
    jobs, owners = [], []
    geos = [scene_geometry(vp.scene, vp.cam) for vp in vps]
    for nv, vp in enumerate(vps):
        rects = pass_rects(vol, vp) if vp.scene.schedule == "rects" else [None] * len(vp.plans)
        # the beat schedule: each pass's block table bits and stops, and termination's rule
        beat_frames = (beat_schedules(vol, vp, cfg, {"tau": tau_fixed(vp.scene.tau, cfg),
                                                     "terminate": vp.scene.terminate})
                       if vp.scene.schedule == "beats" else [None] * len(vp.plans))
        geo = geos[nv]
        for n, (ps, plan) in enumerate(zip(vp.passes, vp.plans)):
            if plan.trav is not None:       # a pass in which nothing can change a ray runs no frame
                stop = None if geo is None else plan.box_stop(stop_slices(plan.whole, vp.cam, geo.z))
                bf = beat_frames[n]
                if bf is not None and stop is not None:
                    bf[0].limit_stop(stop)      # depth in on the beat schedule: the rays' stops
                jobs.append(FrameJob(plan.trav, vp.lut, vp.rmap, mode=vp.scene.mode, clip=plan.clip,
                                     rects=rects[n], depth_t=depth_threshold(vp.scene, cfg), stop_m=stop,
                                     gm=vp.gm, beats=None if bf is None else (bf[0], bf[1], bf[0].block_bits)))
                owners.append((nv, n))
    try:
        mem = build_memory(vol, scenes, cfg, build)    # the volume, or its words with voxel gradients
        outs = (render_frames(mem, jobs, cfg, progress=progress, quiet=True, build=build, dram=dram)
                if jobs else [])
    except SimulationError as exc:     # one line, naming the build or simulation log
        raise UserError(f"RTL engine: {exc}") from None
    run_s = time.perf_counter() - t0
    sim_total = sum(o["sim_wall_s"] for o in outs)
    per_view: list[dict] = [{} for _ in vps]
    for (nv, n), job, out in zip(owners, jobs, outs):
        per_view[nv][n] = (job, out)
    results = []
    for vp, ran, geo in zip(vps, per_view, geos):
        t1 = time.perf_counter()
        depth = vp.scene.depth_threshold is not None
        frame = assemble_view(vp, cfg, {n: (baseplane_from_pixels(out["pixels"], job.trav.baseplane_shape),
                                            out["pixels"]) for n, (job, out) in ran.items()},
                              {n: depth_from_pixels(out["pixels"], job.trav.baseplane_shape)
                               for n, (job, out) in ran.items()} if depth else None)
        img = composite_over(view_image(vp, frame), geo)    # the volume over the geometry (depth in)
        stats = view_stats(NAME, dims, vp.scene, cfg)
        stats.update(trav_stats(vp.trav))
        stats["baseplane_shape"] = list(frame.baseplane.shape[:2])     # the fine plane's with q > 1
        stats.update(schedule_stats(vp.plans, cfg, build))
        if use_rects:   # the frames ran the rectangles (or the whole box): their prediction
            gra = bool(build["SHADING"]) and not bool(build.get("VGRAD", 0))
            rs = [frame_rects(job, gra) for job, _ in ran.values()]
            stats["predicted_cycles"] = sum(rect_frame_cycles(r, cfg.pipelines, bool(build["SHADING"]),
                                                              bool(build.get("VGRAD", 0)), has_falloff(build))
                                            for r in rs)
            stats["cycles_saved"] = stats["fixed_schedule_cycles"] - stats["predicted_cycles"]
            stats["skip"] = True
            stats["rects"] = True
            stats["rect_com_waits"] = sum(r.com_waits(cfg.pipelines) for r in rs)
        outs_v = [out for _, out in ran.values()]
        stats.update(_cycle_stats(outs_v, nx * ny * nz / cfg.pipelines))
        if vp.scene.schedule == "beats":
            stats["beats"] = rtl_beat_stats([(job.beats[0], out) for job, out in ran.values()])
        stats["build"] = dict(build)
        if dram is not None:
            # (the golden model predicts no beat frame: its cycles depend on when rays end)
            stats["dram"] = dram_stats(outs_v, None if vp.scene.schedule == "beats" else stats.get("predicted_cycles"), dram)
        sim_s = sum(o["sim_wall_s"] for o in outs_v)
        wall = sim_s + (run_s - sim_total) / len(scenes) + time.perf_counter() - t1
        stats["wall_s"] = wall
        res = RenderResult(NAME, img, wall, frame=frame, stats=stats)
        if depth:
            res.depth = depth_image(vp, frame)
            res.stats["depth"] = depth_stats(res.depth, vp.scene.depth_threshold)
        results.append(res)
    return results


def rtl_beat_stats(frames: list) -> dict:
    """The beats a view's frames ran on the RTL and skipped, by cause: ``run_beats`` as
    cube4_top counted them (its sample beats into COM with a lane valid), ``box_beats`` the
    fixed schedule's in the frames' boxes, ``skipped_empty`` those no ray could run (the
    host's stops and the block table: the schedule without termination), and
    ``skipped_terminated`` the rest (COM found their rays done). ``frames``: each frame's
    (BeatSchedule as the host gave it, the RTL's result)."""
    box = run = free_run = 0
    for sched, out in frames:
        free = BeatSchedule(sched.trav, sched.p, sched.occ, sched.lag, terminate=False, gra=sched.gra)
        free.limit_stop(sched.stop)
        free.reported = free.M          # no report moves an end: every slice may be asked
        box += free.M * free.NJ * free.NB
        free_run += sum(int(free.run_beats(m).sum()) for m in range(free.M))
        run += int(out["beats_run"])
    return {"box_beats": box, "run_beats": run, "skipped_empty": box - free_run,
            "skipped_terminated": free_run - run, "counted_by": "rtl"}


def _cycle_stats(outs: list[dict], ideal: float) -> dict:
    """A view's measured figures, summed over its frames (one per sub-pixel pass)."""
    cycles = sum(int(o["cycles"]) for o in outs)
    sim_s = sum(o["sim_wall_s"] for o in outs)
    return {
        "pixels": sum(int(o["pixels"].size) for o in outs),
        "cycles": cycles,
        "ideal_cycles": ideal,
        "efficiency": ideal / cycles if cycles else None,
        "sim_wall_s": sim_s,
        "sim_cycles_per_s": cycles / sim_s if sim_s > 0 else None,
    }


def dram_stats(outs: list[dict], predicted: float | None, dram: DramRun) -> dict:
    """A view's figures with the voxel memory in DRAM, summed over its frames: cycles
    against the ideal memory's (the golden prediction), the bursts read and the bandwidth
    that took at the pipelines' clock, and the commands the controller sent (row opens,
    refreshes) with the share of the controller's time each took (tRCD + tRP per
    activate, tRP + tRFC per refresh: the time the DRAM could move no data for them)."""
    cycles = sum(int(o["cycles"]) for o in outs)
    reads = sum(int(o["dram_reads"]) for o in outs)
    t = core_info(dram.core)["timing_cycles"]
    seconds = cycles / (dram.clock_mhz * 1e6)
    sys_cycles = seconds * dram.core.sys_clk_hz
    acts = sum(int(o["dram_stat_act"]) for o in outs)
    refs = sum(int(o["dram_stat_ref"]) for o in outs)
    return {
        "part": dram.core.module, "controller_mhz": round(dram.core.sys_clk_hz / 1e6, 3),
        "pipeline_mhz": dram.clock_mhz,
        "cycles": cycles,
        "ideal_memory_cycles": predicted,
        "ideal_over_dram": (predicted / cycles) if predicted and cycles else None,
        "bursts_read": reads,
        "bytes_read": reads * DATA_W // 8,
        "mb_per_s": reads * DATA_W / 8 / seconds / 1e6 if seconds else None,
        "peak_mb_per_s": DATA_W / 8 / 2 * dram.core.sys_clk_hz / 1e6,     # a burst per two controller cycles
        "activates": acts,
        "refreshes": refs,
        "row_open_share": acts * (t["tRCD"] + t["tRP"]) / sys_cycles if sys_cycles else None,
        "refresh_share": refs * (t["tRP"] + t["tRFC"]) / sys_cycles if sys_cycles else None,
        **stall_causes(cycles, predicted, refs * (t["tRP"] + t["tRFC"]), acts * (t["tRCD"] + t["tRP"]),
                       dram.clock_mhz * 1e6 / dram.core.sys_clk_hz),
    }


def stall_causes(cycles: int, ideal: float | None, refresh_sys: float, row_sys: float, ratio: float) -> dict:
    """The pipelines' stall cycles (cycles beyond the ideal memory's) by cause, an
    estimate from the controller's commands: each refresh and each row open stalls the
    pipelines for the controller time it takes (in pipeline cycles: ``ratio`` of them per
    controller cycle), at most the stall there was, refreshes first; the rest is the
    DRAM's bandwidth (and latency)."""
    if not ideal:
        return {}
    stall = max(0.0, cycles - ideal)
    refresh = min(stall, refresh_sys * ratio)
    row = min(stall - refresh, row_sys * ratio)
    return {"stall_cycles": round(stall), "stall_refresh": round(refresh), "stall_row_open": round(row),
            "stall_bandwidth": round(stall - refresh - row)}


def render_rtl_dram(vol: np.ndarray, scenes: list[Scene], cfg: Cube4Config, progress: bool = False) -> list[RenderResult]:
    """The ``rtl-dram`` engine: the RTL with its voxel memory in the simulated DRAM (the
    ECPIX-5's DDR3 behind LiteDRAM's controller at 75 MHz, the pipelines at 137.7 MHz)."""
    return render_rtl(vol, scenes, cfg, progress, dram=DramRun())


def register() -> None:
    """Add the ``rtl`` and ``rtl-dram`` engines to ``cube4.app.render``, and the RTL's
    brick renderer to ``cube4.bricks`` (by import path: a Dask worker imports it there)."""
    register_engine(NAME, render_rtl)
    register_engine("rtl-dram", render_rtl_dram)
    register_brick_renderer(NAME, "cube4_sim.bricks:render_brick_rtl")

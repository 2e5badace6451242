"""Bricks through the simulated RTL: the ``rtl`` engine's brick renderer for
``cube4.bricks`` (registered by ``cube4_sim.engine.register``; a Dask worker imports it
by name).

Each brick is one board: its stored voxels are the whole of that board's voxel memory
(the brick's traversal is moved to origin (0, 0, 0)), its view registers are the whole
render's with the template's starting phase of its first slice, and its window registers
say which samples it counts. The board is a build for MAX_DIM = the task's ``board_dim``
(``--board-dim``), else for the brick's size class; the Verilator build is cached under
build/sim per parameter set, so a worker builds once and reuses it for every later brick.

The build has the window (CLIP = 1) and the datapath the brick's mode needs; a build
given in the configuration (``Cube4Config.build``) must have them, else one line.
"""

from __future__ import annotations

import dataclasses
import time

from cube4.bricks import BrickResult, BrickTask
from cube4.errors import UserError

from .errors import SimulationError
from .rtl import FrameJob, baseplane_from_pixels, render_frames

def brick_build(task: BrickTask) -> dict:
    """The build a brick needs: the window (CLIP), compositing, shading if the scene is
    shaded; the configuration's own build if it has one and has all of these."""
    shaded = int(task.shading and task.mode == "composite")
    need = {"SHADING": shaded, "COMPOSITING": 1, "EXTREMUM": 0, "CLIP": 1, "VGRAD": int(shaded and task.vgrad)}
    if task.cfg.build is None:
        return need
    build = dict(task.cfg.build)
    missing = [k for k, v in need.items() if v and not build.get(k)]
    if missing:
        raise UserError(f"RTL engine: bricks need {', '.join(f'{k} = 1' for k in missing)} in the build")
    if shaded and build["VGRAD"] != need["VGRAD"]:
        raise UserError(f"RTL engine: these bricks need VGRAD = {need['VGRAD']} in the build")
    return build


def render_brick_rtl(task: BrickTask) -> BrickResult:
    """One brick rendered by cube4_top in Verilator; returns its base plane and cycles."""
    t0 = time.perf_counter()
    build = brick_build(task)
    trav = dataclasses.replace(task.trav, origin=(0, 0, 0))   # the board holds the brick alone
    job = FrameJob(trav, task.lut, task.rmap if build["SHADING"] else None, mode=task.mode, clip=task.clip)
    try:
        (out,) = render_frames(task.vol, [job], task.cfg, quiet=True, build=build, max_dim=task.board_dim)
    except SimulationError as exc:
        raise UserError(f"RTL engine: {exc}") from None
    base = baseplane_from_pixels(out["pixels"], trav.baseplane_shape)
    return BrickResult(baseplane=base, wall_s=time.perf_counter() - t0, cycles=int(out["cycles"]),
                       extra={"sim_wall_s": out["sim_wall_s"]})

"""Bricks through the simulated RTL: the ``rtl`` engine's brick renderer for
``cube4.bricks`` (registered by ``cube4_sim.engine.register``; a Dask worker imports it
by name).

Each brick is one board: its stored voxels are the whole of that board's voxel memory
(the brick's traversal is moved to origin (0, 0, 0)), its view registers are the whole
render's with the template's starting phase of its first slice, and its window registers
say which samples it counts. The Verilator build is cached under build/sim per parameter
set and size class, so a worker builds once and reuses the build for every later brick.

The RTL needs the template's starting phase (PH0_X, PH0_Y) and the window registers for
this; ``rtl_supports_bricks`` says whether the RTL in this tree has them, and a brick
on an RTL without them is one clear error rather than a wrong picture.
"""

from __future__ import annotations

import dataclasses
import time

from cube4.bricks import BrickResult, BrickTask
from cube4.errors import UserError
from cube4.memory import top_regs
from cube4.view import make_traversal

from .errors import SimulationError
from .rtl import FrameJob, baseplane_from_pixels, render_frames

NEEDED_REGS = ("PH0_X", "PH0_Y")


def rtl_supports_bricks() -> bool:
    """Does the RTL host side program a starting phase and a window (the brick registers)?"""
    regs = top_regs(make_traversal((4, 4, 4), (0.3, 0.2, 1.0)), 1)
    return all(r in regs for r in NEEDED_REGS) and "clip" in {f.name for f in dataclasses.fields(FrameJob)}


def render_brick_rtl(task: BrickTask) -> BrickResult:
    """One brick rendered by cube4_top in Verilator; returns its base plane and cycles."""
    if not rtl_supports_bricks():
        raise UserError("RTL engine: bricks need the template's starting phase (PH0_X, PH0_Y) and the window "
                        "registers, which the RTL here does not have yet; use --engine golden")
    t0 = time.perf_counter()
    trav = dataclasses.replace(task.trav, origin=(0, 0, 0))   # the board holds the brick alone
    names = {f.name for f in dataclasses.fields(FrameJob)}
    extra = {"clip": task.clip}
    if "mode" in names:
        extra["mode"] = task.mode
    elif task.mode != "composite":
        raise UserError(f"RTL engine: mode {task.mode!r} in bricks needs an RTL with the mode register")
    if "shading" in names:
        extra["shading"] = task.shading
    job = FrameJob(trav, task.lut, task.rmap, **extra)
    try:
        (out,) = render_frames(task.vol, [job], task.cfg, quiet=True)
    except SimulationError as exc:
        raise UserError(f"RTL engine: {exc}") from None
    base = baseplane_from_pixels(out["pixels"], trav.baseplane_shape)
    return BrickResult(baseplane=base, wall_s=time.perf_counter() - t0, cycles=int(out["cycles"]),
                       extra={"sim_wall_s": out["sim_wall_s"]})

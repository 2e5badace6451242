"""Bit-exact comparison of an RTL frame (``cube4_sim.rtl.render_frames``) with the
golden model: the testbenches of the whole Cube-4 share it."""

from __future__ import annotations

import numpy as np

from cube4.config import Cube4Config
from cube4.host import crop_volume
from cube4.model import Frame, render_frame
from cube4.view import Traversal

from .rtl import baseplane_from_pixels


def assert_frame_matches_golden(vol: np.ndarray, trav: Traversal, cfg: Cube4Config, lut: np.ndarray,
                                rmap: np.ndarray | None, res: dict, label: str, mode: str = "composite",
                                clip=None, vgrad: bool = False, rects=None, depth_t: int | None = None,
                                stop_m: np.ndarray | None = None, gm: np.ndarray | None = None,
                                labels: bool = False, beats=None) -> Frame:
    """The finished rays (m, by, bx, R, G, B, A) as a set and the assembled base plane
    must equal the golden model's (vol: the whole volume, or its memory words with voxel
    gradients when ``vgrad``; trav may traverse a box in it; rmap None: an unshaded
    frame; ``rects``: its slice rectangles; ``depth_t``: depth out's threshold, whose slices
    the rays then carry; ``stop_m``: depth in's stop slices; ``gm``: gradient-magnitude
    modulation's table; ``labels``: vol holds labelled words and lut a block per label,
    cube4.labels; ``beats``: the beat schedule's (BeatSchedule before the frame, TerminationRule),
    a copy of the schedule runs); returns the golden frame."""
    import copy
    sched, rule = (None, None) if beats is None else (copy.deepcopy(beats[0]), beats[1])
    gold = render_frame(crop_volume(vol, trav), trav, cfg, lut, rmap, mode=mode, shading=rmap is not None,
                        clip=clip, vgrad=vgrad, rects=rects, depth_t=depth_t, stop_m=stop_m, gm=gm,
                        labels=labels, beats=sched, done=rule)
    want = np.sort(gold.pixels, order=["m", "by", "bx"])
    got = np.sort(res["pixels"], order=["m", "by", "bx"])
    assert got.size == want.size, f"{label}: {got.size} finished rays, golden {want.size}"
    bad = np.nonzero(got != want)[0]
    assert bad.size == 0, f"{label}: ray {got[bad[0]]} differs from golden {want[bad[0]]} ({bad.size} rays differ)"
    print(f"{label}: {got.size} finished rays bit-exact, {res['cycles']} cycles")
    base = baseplane_from_pixels(res["pixels"], trav.baseplane_shape)
    assert (base == gold.baseplane).all(), f"{label}: base plane differs"
    return gold

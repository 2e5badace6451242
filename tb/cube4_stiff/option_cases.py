"""Stiff and extreme cases for the options (issue 51, docs/numerics.md section 11b).

Each case pushes one option of the machine to its limit: the modes, path weights,
voxel gradients, q x q passes with S = 8, bricks with 12-bit voxels, a cut plane, a
crop box, opacity at its ceiling. A case is a volume and a list of scenes (one view
each, everything else in the scene); ``test_stiff_options.py`` renders every scene the
way the ``rtl`` engine does (``cube4.host.plan_view``: tables, passes, schedule) through
the RTL at P = 1 and P = 5 with random stalls, bit for bit against the golden model,
and holds the golden model against the float64 reference with the case's check.

``build``: the RTL build the case runs on (None: the full build; "vgrad": the
voxel-gradient builds tb/cube4_top also uses; "wide": VOXEL_W = 12 with S = 8, on the full build without MIP).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cube4.app.volumes import load_volume
from cube4.scene import Scene, parse_scene

#: the views of the cases: on an axis, flipped, exactly 45 degrees, oblique
AXIS, FLIP, DIAG, OBLIQUE = (0.0, 0.0, 1.0), (-1.0, 0.0, 0.0), (1.0, 1.0, 1.0), (0.3, -0.5, 1.0)


@dataclass
class OptionCase:
    name: str
    volume: np.ndarray          # [z, y, x] at the case's voxel width
    scenes: list[Scene]         # one per view
    check: str                  # "saturate", "extremum", "opaque", "constant", "bricks" or "rmse"
    bound: float | None = None  # the RMSE bound of an "rmse" check (regression bound, numerics.md 11b)
    build: str | None = None    # None (full), "vgrad", "wide"
    cfg: dict = field(default_factory=dict)   # Cube4Config fields beyond the scene's
    why: str = ""


def scene(views, *, tf, mode: str = "composite", shading: bool = True, size: int = 48,
          render: dict | None = None, **tables) -> list[Scene]:
    """One scene per view, parsed as a user's scene file: the stiff cases' lights and
    material, the transfer function (control points [x, r, g, b, a]), [render] keys and
    further tables ([crop], [cut])."""
    scenes = []
    for v in views:
        data = {
            "view": {"direction": [float(c) for c in v]},
            "output": {"width": size, "height": size},
            "material": {"ambient": 0.3, "diffuse": 0.7, "specular": 0.3, "shininess": 20.0, "shading": shading},
            "light": [{"headlight": True, "intensity": 0.8}, {"direction": [-1.0, -0.5, -1.0], "intensity": 0.4}],
            "transfer": {"points": tf},
            "render": {"mode": mode, **(render or {})},
            **tables,
        }
        scenes.append(parse_scene(data, name="stiff-option"))
    return scenes


def flat(alpha: float, rgb=(1.0, 0.6, 0.3)) -> list:
    return [[0.0, *rgb, alpha], [1.0, *rgb, alpha]]


def _const(nx: int, ny: int, nz: int, value: int) -> np.ndarray:
    return np.full((nz, ny, nx), value, dtype=np.uint16)


def xray_saturating() -> OptionCase:
    return OptionCase("xray_saturating", _const(20, 18, 16, 255),
                      scene([DIAG, AXIS, OBLIQUE], tf=flat(0.9), mode="xray"), "saturate",
                      why="X-ray of an opaque medium: every channel's sum passes 1 and saturates")


def mip_saturating() -> OptionCase:
    return OptionCase("mip_saturating", _const(20, 18, 16, 255),
                      scene([DIAG, FLIP, OBLIQUE], tf=flat(1.0, (1.0, 1.0, 1.0)), mode="mip"), "extremum",
                      why="MIP at the top of the value range, the LUT's last entry full colour and opacity")


def minip_saturating() -> OptionCase:
    tf = [[0.0, 1.0, 0.5, 0.2, 1.0], [1.0, 0.0, 0.0, 0.0, 0.0]]
    return OptionCase("minip_saturating", _const(20, 18, 16, 0),
                      scene([DIAG, AXIS, OBLIQUE], tf=tf, mode="minip", render={"skip": False}), "extremum",
                      why="MinIP at the bottom of the value range (the zero padding agrees), opacity 1")


def path_weights_one_sample() -> OptionCase:
    return OptionCase("path_weights_one_sample", _const(24, 20, 16, 128),
                      scene([DIAG, (-1.0, 1.0, -1.0)], tf=flat(0.3), shading=False,
                            render={"path_weights": True, "skip": False}), "constant",
                      why="path weights at exactly 45 degrees: rays of one sample at the box's edges "
                          "and corners, and the rays that only touch an edge")


def path_weights_grazing() -> OptionCase:
    views = [(0.002, 0.001, 1.0), (1.0, 0.9995, 0.0005)]
    return OptionCase("path_weights_grazing", _const(24, 20, 16, 128),
                      scene(views, tf=flat(0.3), shading=False, render={"path_weights": True, "skip": False}),
                      "rmse", 0.17,
                      why="path weights on rays grazing a face (0.06 and 0.03 degrees off it)")


def vgrad_constant() -> OptionCase:
    return OptionCase("vgrad_constant", _const(16, 14, 12, 128),
                      scene([AXIS, DIAG, OBLIQUE], tf=flat(0.05), render={"gradient": "central", "skip": False}), "constant",
                      build="vgrad",
                      why="voxel gradients of a constant volume: zero inside, the unshaded entry")


def vgrad_step() -> OptionCase:
    vol = np.zeros((16, 16, 16), dtype=np.uint16)
    vol[:, :, 8:] = 255
    tf = [[0.0, 1, 0.6, 0.3, 0.0], [0.5, 1, 0.6, 0.3, 0.0], [1.0, 1, 0.6, 0.3, 0.9]]
    return OptionCase("vgrad_step", vol, scene([(1.0, 0.0, 0.0), FLIP, DIAG, (0.7, 1.0, 0.3)], tf=tf,
                                               render={"gradient": "central"}), "rmse", 0.18,
                      build="vgrad",
                      why="voxel gradients of a 0 -> max step: the largest gradient a word holds")


def subpixel_q4_s8() -> OptionCase:
    vol = load_volume("head:12", voxel_bits=12)
    tf = [[0.0, 1, 1, 1, 0.0], [0.2, 1, 0.8, 0.6, 0.0], [0.5, 1, 0.9, 0.8, 0.6], [1.0, 1, 1, 1, 0.9]]
    return OptionCase("subpixel_q4_s8", vol, scene([(-1.0, 0.25, 0.6)], tf=tf, render={"subpixel": 4, "supersample": 8}), "rmse", 0.07,
                      build="wide", cfg={"voxel_bits": 12},
                      why="q = 4 sub-pixel passes (16 frames per view) at S = 8 with 12-bit voxels")


def bricks_wide_seam() -> OptionCase:
    vol = np.zeros((16, 14, 12), dtype=np.uint16)
    vol[5:11, 2:12, 2:10] = 4095              # an opaque slab across the seam at z = 8
    vol[7:9, 4:10, 4:8] = 2048                # and a softer core exactly on it
    tf = [[0.0, 1, 0.7, 0.4, 0.0], [0.4, 1, 0.7, 0.4, 0.95], [1.0, 1, 1, 1, 0.999]]
    return OptionCase("bricks_wide_seam", vol, scene([(0.3, -0.2, -1.0)], tf=tf, render={"supersample": 8}), "bricks",
                      build="wide", cfg={"voxel_bits": 12},
                      why="bricks (two along the view) with 12-bit voxels and opacity near 1 across the seam")


def cut_near_face() -> OptionCase:
    vol = load_volume("ml:20")
    eps = np.deg2rad(0.001)
    cut = {"normal": [float(np.cos(eps)), float(np.sin(eps)), 0.0], "point": [10.0, 9.0, 8.0]}
    tf = [[0.0, 1, 1, 1, 0.0], [0.4, 0.9, 0.6, 0.3, 0.0], [1.0, 1, 1, 0.9, 0.5]]
    return OptionCase("cut_near_face", vol, scene([(1.0, 0.0, 0.0), FLIP, (0.0, 1.0, 0.2), DIAG], tf=tf, cut=cut),
                      "rmse", 0.12,
                      why="a cut plane 0.001 degrees from a face, through a voxel plane (x = 10)")


def thinnest_crop() -> OptionCase:
    vol = load_volume("ml:20")
    tf = [[0.0, 1, 1, 1, 0.0], [0.4, 0.9, 0.6, 0.3, 0.0], [1.0, 1, 1, 0.9, 0.5]]
    crop = {"box": [[9, 0, 0], [10, 19, 19]]}     # two voxels thick along x, the least a box allows
    return OptionCase("thinnest_crop", vol, scene([(1.0, 0.0, 0.0), AXIS, DIAG], tf=tf, crop=crop), "rmse", 0.20,
                      why="the thinnest crop box (two voxels), seen through and along")


def smallest_volume() -> OptionCase:
    vol = np.array([[[255, 0], [0, 255]], [[0, 255], [255, 0]]], dtype=np.uint16)
    return OptionCase("smallest_volume", vol, scene([AXIS, DIAG, (-0.3, 1.0, 0.2)], tf=flat(0.8), size=16),
                      "rmse", 0.66, why="2 x 2 x 2: every sample next to the zero padding")


def opacity_ceiling() -> OptionCase:
    rng = np.random.default_rng(51)
    vol = rng.integers(0, 256, size=(12, 14, 16)).astype(np.uint16)
    return OptionCase("opacity_ceiling", vol, scene([(1.0, 0.3, 0.2), (-1.0, -1.0, 1.0)], tf=flat(1.0)), "opaque",
                      why="every LUT entry at opacity 1 - 2^-AW: two samples end every ray")


CASES = [xray_saturating, mip_saturating, minip_saturating, path_weights_one_sample, path_weights_grazing, vgrad_constant, vgrad_step,
         subpixel_q4_s8, bricks_wide_seam, cut_near_face, thinnest_crop, smallest_volume, opacity_ceiling]

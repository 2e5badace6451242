"""The stiff and extreme cases (issue 5, docs/numerics.md section 11).

Each case is a volume, a scene and a list of views chosen to push one part of the
numerics to its limit. ``tb/cube4_stiff/test_cube4_stiff.py`` renders every case
through the RTL (bit for bit against the golden model) and the golden model against
the float64 reference (within the case's stated bound).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cube4.scene import Scene, parse_scene
from cube4.app.volumes import load_volume
from cube4.reference import _box_interval



def path_lengths(trav, scene: Scene) -> np.ndarray:
    """Length inside the traversed box (trav.origin + [0, dims - 1]) of each base-plane
    pixel's reference ray (reference.reference_baseplane's rays)."""
    rows, cols = trav.baseplane_shape
    by, bx = np.mgrid[0:rows, 0:cols]
    origins = trav.baseplane_to_volume(bx.ravel(), by.ravel()) - np.asarray(trav.origin, dtype=np.float64)
    d = np.asarray(scene.direction, dtype=np.float64)
    t0, t1 = _box_interval(origins, d / np.linalg.norm(d), trav.dims)
    return np.maximum(t1 - t0, 0.0).reshape(rows, cols)


@dataclass
class Case:
    name: str
    volume: np.ndarray  # [z, y, x], 8-bit
    scene: Scene
    views: list[tuple[float, float, float]]
    rmse_bound: float | None  # regression bound on the base plane vs the reference (None: analytic checks)
    cfg: dict = field(default_factory=dict)  # Cube4Config overrides
    why: str = ""


def _scene(alpha: float | list, material: dict | None = None, size: int = 96, rgb=(1.0, 0.6, 0.3)) -> Scene:
    pts = alpha if isinstance(alpha, list) else [[0.0, *rgb, alpha], [1.0, *rgb, alpha]]
    data = {
        "output": {"width": size, "height": size},
        "material": material or {"ambient": 0.3, "diffuse": 0.7, "specular": 0.3, "shininess": 20.0},
        "light": [{"headlight": True, "intensity": 0.8}, {"direction": [-1.0, -0.5, -1.0], "intensity": 0.4}],
        "transfer": {"points": pts},
    }
    return parse_scene(data, name="stiff")


def _zeros(nx: int, ny: int, nz: int) -> np.ndarray:
    return np.zeros((nz, ny, nx), dtype=np.uint16)


def opaque_longest() -> Case:
    vol = _zeros(24, 24, 24) + 255
    return Case("opaque_longest", vol, _scene(1.0), [(1, 1, 1), (-1, 1, -1), (1, -1, -1)], None,
                why="opaque medium, sample distance sqrt(3): alpha 1 after opacity correction, "
                    "the first sample ends the ray; accumulators must not wrap")


def constant() -> Case:
    vol = _zeros(20, 16, 12) + 128
    return Case("constant", vol, _scene(0.05), [(0, 0, 1), (0, 0, -1), (1, 1, 0), (1, 0.98, 0.2)], None,
                why="zero gradients inside (the unshaded reflectance-map entry), on and next to 45 degrees")


def hard_step() -> Case:
    vol = _zeros(32, 32, 32)
    vol[:, :, 16:] = 255
    return Case("hard_step", vol, _scene([[0.0, 1, 0.6, 0.3, 0.0], [0.5, 1, 0.6, 0.3, 0.0], [1.0, 1, 0.6, 0.3, 0.9]]),
                [(1, 0, 0), (-1, 0, 0), (1, 1, 1), (0.7, 1, 0.3)], 0.11,
                why="0 -> max step: the largest gradient (no overflow in GRA) and the sharpest alpha edge")


def thin_features() -> Case:
    vol = _zeros(32, 32, 32)
    vol[:, :, 15] = 255          # a one-voxel sheet (x = 15)
    vol[:, 5, 5] = 255           # a one-voxel line along z
    vol[25, 25, 25] = 255        # a single voxel
    return Case("thin_features", vol, _scene([[0.0, 1, 1, 1, 0.0], [0.3, 1, 1, 1, 0.0], [1.0, 1, 1, 1, 1.0]]),
                [(1, 0.3, 0.2), (0.2, 1, 0.3), (1, 1, 1)], 0.36,
                why="one-voxel-thin sheet, line and point: seen face-on, edge-on and at 45 degrees")


def saturated_lut() -> Case:
    vol = load_volume("sphere:24")
    mat = {"ambient": 4.0, "diffuse": 4.0, "specular": 4.0, "shininess": 1.0}
    return Case("saturated_lut", vol, _scene(1.0, mat, rgb=(1.0, 1.0, 1.0)), [(0.3, -0.5, 1), (-1, -1, -1)],
                None,
                why="every LUT entry at full colour and opacity, reflectance map at its 4.0 ceiling: "
                    "shading saturates at 255 everywhere")


def smallest() -> Case:
    vol = np.array([[[255, 0], [0, 255]], [[0, 255], [255, 0]]], dtype=np.uint16)
    return Case("smallest", vol, _scene(0.8, size=32), [(0, 0, 1), (1, 1, 1), (-0.3, 1, 0.2)], 0.58,
                why="2x2x2, the smallest volume with a gradient: boundary handling everywhere")


def largest() -> Case:
    vol = load_volume("ml:64")
    scene = _scene([[0.0, 1, 1, 1, 0.0], [0.4, 0.9, 0.6, 0.3, 0.0], [1.0, 1, 1, 0.9, 0.5]])
    return Case("largest", vol, scene, [(-1, 1, 1)], 0.06,
                why="64^3, the largest volume the MAX_DIM = 64 build holds, at exactly 45 degrees")


def faint_thousands() -> Case:
    vol = _zeros(4, 4, 256) + 200
    scene = _scene(0.016, {"ambient": 1.0, "diffuse": 0.0, "specular": 0.0, "shininess": 1.0}, size=32,
                   rgb=(1.0, 1.0, 1.0))
    return Case("faint_thousands", vol, scene, [(0, 0, 1)], None, cfg={"supersample": 8},
                why="2041 samples (256 slices, S = 8) of opacity 8/4096 each: seed 004's case")


#: Cases that share the MAX_DIM = 64, S = 1 build of tb/cube4_top.
SHARED_BUILD = [opaque_longest, constant, hard_step, thin_features, saturated_lut, smallest, largest]

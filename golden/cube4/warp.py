"""The host's warp, as the scene states it: the filter and the footprint.

The warp resamples the float base plane into the image plane through the affine map of
``view.warp_matrix`` with a reconstruction filter (``[output] filter``, one of
``WARP_FILTERS``), black outside; OpenImageIO does the resampling
(``cube4.app.warp.warp_to_image``). The image may then be cut to the footprint of the
traversed box (``[output] footprint``): the convex polygon its eight corners project to
in the image, outside of which no ray meets the box (``footprint_mask``).
"""

from __future__ import annotations

import numpy as np

from .errors import UserError
from .view import Camera, Traversal

#: OpenImageIO 2-D filters offered for the warp (docs/scenes.md, [output] filter); each
#: keeps its OpenImageIO width in base-plane pixels (triangle: 2, bilinear interpolation)
WARP_FILTERS = ("triangle", "box", "gaussian", "sharp-gaussian", "bspline", "mitchell", "catmull-rom",
                "cubic", "blackman-harris", "lanczos3")
DEFAULT_FILTER = "triangle"

#: a pixel centre this close to the footprint's edge (in pixels) counts as inside
EDGE_TOLERANCE = 1e-6


def check_filter(name, where: str = "") -> str:
    """A warp filter name, validated: one line listing the choices if it is not one."""
    if not isinstance(name, str) or name not in WARP_FILTERS:
        raise UserError(f"{where}filter {name!r} is not a warp filter (filters: {', '.join(WARP_FILTERS)})")
    return name


def box_corners(trav: Traversal) -> np.ndarray:
    """The traversed box's eight corners (8, 3) in volume coordinates: the voxel centres
    at the ends of each axis, the box the reference clips its rays to."""
    ends = [(0.0, float(n - 1)) for n in (trav.ni, trav.nj, trav.nk)]
    ti, tj, tk = np.meshgrid(*ends, indexing="ij")
    return trav.traversal_to_volume_points(ti.ravel(), tj.ravel(), tk.ravel())


def convex_hull(pts: np.ndarray) -> np.ndarray:
    """The convex hull of 2-D points (N, 2), counter-clockwise in (x, y) without
    repeated or collinear points (Andrew's monotone chain)."""
    p = sorted({(float(x), float(y)) for x, y in pts})
    if len(p) < 3:
        return np.asarray(p, dtype=np.float64).reshape(-1, 2)

    def chain(points):
        out = []
        for q in points:
            while len(out) >= 2 and _cross(out[-2], out[-1], q) <= 0:
                out.pop()
            out.append(q)
        return out[:-1]

    return np.asarray(chain(p) + chain(p[::-1]), dtype=np.float64)


def _cross(o, a, b) -> float:
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def footprint_polygon(trav: Traversal, cam: Camera) -> np.ndarray:
    """The traversed box's projection: the convex hull (N, 2) of its projected corners
    in image-pixel coordinates (col, row), pixel centres at integers."""
    return convex_hull(cam.project(box_corners(trav)))


def footprint_mask(trav: Traversal, cam: Camera) -> np.ndarray:
    """(H, W) float64: 1 where the pixel centre lies in the box's projection (its edge
    included), else 0. A degenerate projection (no area) masks nothing."""
    poly = footprint_polygon(trav, cam)
    rows, cols = np.arange(cam.height, dtype=np.float64), np.arange(cam.width, dtype=np.float64)
    if len(poly) < 3:
        return np.ones((cam.height, cam.width))
    inside = np.ones((cam.height, cam.width), dtype=bool)
    for a, b in zip(poly, np.roll(poly, -1, axis=0)):
        # left of the edge a -> b (counter-clockwise in (col, row)), scaled to pixels
        ex, ey = b - a
        dist = (ex * (rows[:, None] - a[1]) - ey * (cols[None, :] - a[0])) / np.hypot(ex, ey)
        inside &= dist >= -EDGE_TOLERANCE
    return inside.astype(np.float64)

"""The host's warp: the float base plane resampled into the image plane.

OpenImageIO's ``warp`` resamples the base plane through the affine map of
``view.warp_matrix`` with a chosen reconstruction filter (``[output] filter``), black
outside.
"""

from __future__ import annotations

import numpy as np

from .errors import UserError
from .view import Camera, Traversal, warp_matrix

#: OpenImageIO 2-D filters offered for the warp (docs/scenes.md, [output] filter); each
#: keeps its OpenImageIO width in base-plane pixels (triangle: 2, bilinear interpolation)
WARP_FILTERS = ("triangle", "box", "gaussian", "sharp-gaussian", "bspline", "mitchell", "catmull-rom",
                "cubic", "blackman-harris", "lanczos3")
DEFAULT_FILTER = "triangle"


def check_filter(name, where: str = "") -> str:
    """A warp filter name, validated: one line listing the choices if it is not one."""
    if not isinstance(name, str) or name not in WARP_FILTERS:
        raise UserError(f"{where}filter {name!r} is not a warp filter (filters: {', '.join(WARP_FILTERS)})")
    return name


def oiio_matrix(trav: Traversal, cam: Camera) -> tuple[float, ...]:
    """``view.warp_matrix`` in OpenImageIO's convention: pixel centres at +0.5, a
    row-vector matrix (p' = p M), nine Python floats (numpy scalars read as identity)."""
    a = warp_matrix(trav, cam)
    shift = np.array([[1.0, 0.0, 0.5], [0.0, 1.0, 0.5], [0.0, 0.0, 1.0]])
    unshift = np.array([[1.0, 0.0, -0.5], [0.0, 1.0, -0.5], [0.0, 0.0, 1.0]])
    m = shift @ a @ unshift
    return tuple(float(x) for x in m.T.reshape(-1))


def warp_to_image(base: np.ndarray, trav: Traversal, cam: Camera, filtername: str = DEFAULT_FILTER) -> np.ndarray:
    """Warp a float base plane (rows, cols, 4) to the image plane (H, W, 4) with
    OpenImageIO (``filtername``, black outside)."""
    import OpenImageIO as oiio

    check_filter(filtername)
    src = oiio.ImageBuf(np.ascontiguousarray(base, dtype=np.float32))
    roi = oiio.ROI(0, cam.width, 0, cam.height, 0, 1, 0, 4)
    dst = oiio.ImageBufAlgo.warp(src, oiio_matrix(trav, cam), filtername=filtername, wrap="black", roi=roi)
    if dst.has_error:
        raise RuntimeError(f"OpenImageIO warp failed: {dst.geterror()}")
    out = dst.get_pixels(oiio.FLOAT, roi)
    return np.asarray(out, dtype=np.float64).reshape(cam.height, cam.width, 4)

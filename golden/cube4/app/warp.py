"""The host's warp with OpenImageIO: the float base plane resampled into the image plane.

OpenImageIO's ``warp`` resamples the base plane through the affine map of
``view.warp_matrix`` with the scene's reconstruction filter (``[output] filter``,
``cube4.warp.WARP_FILTERS``), black outside; with ``[output] footprint`` the image is
then cut to the traversed box's footprint (``cube4.warp.footprint_mask``).
"""

from __future__ import annotations

import numpy as np

from ..view import Camera, Traversal, warp_matrix
from ..warp import DEFAULT_FILTER, check_filter, footprint_mask


def oiio_matrix(trav: Traversal, cam: Camera, pre: np.ndarray | None = None) -> tuple[float, ...]:
    """``view.warp_matrix`` (times ``pre``, if given) in OpenImageIO's convention: pixel
    centres at +0.5, a row-vector matrix (p' = p M), nine Python floats (numpy scalars
    read as identity)."""
    a = warp_matrix(trav, cam)
    if pre is not None:
        a = a @ pre
    shift = np.array([[1.0, 0.0, 0.5], [0.0, 1.0, 0.5], [0.0, 0.0, 1.0]])
    unshift = np.array([[1.0, 0.0, -0.5], [0.0, 1.0, -0.5], [0.0, 0.0, 1.0]])
    m = shift @ a @ unshift
    return tuple(float(x) for x in m.T.reshape(-1))


def warp_to_image(base: np.ndarray, trav: Traversal, cam: Camera, filtername: str = DEFAULT_FILTER,
                  footprint: bool = False, pre: np.ndarray | None = None) -> np.ndarray:
    """Warp a float base plane (rows, cols, 4) to the image plane (H, W, 4) with
    OpenImageIO (``filtername``, black outside); with ``footprint``, every pixel whose
    centre lies outside the traversed box's projection is set to 0. ``pre`` (3×3): the
    plane's pixels map to ``trav``'s base-plane points by it (a q×q fine plane)."""
    import OpenImageIO as oiio

    check_filter(filtername)
    src = oiio.ImageBuf(np.ascontiguousarray(base, dtype=np.float32))
    roi = oiio.ROI(0, cam.width, 0, cam.height, 0, 1, 0, 4)
    dst = oiio.ImageBufAlgo.warp(src, oiio_matrix(trav, cam, pre), filtername=filtername, wrap="black", roi=roi)
    if dst.has_error:
        raise RuntimeError(f"OpenImageIO warp failed: {dst.geterror()}")
    out = dst.get_pixels(oiio.FLOAT, roi)
    img = np.asarray(out, dtype=np.float64).reshape(cam.height, cam.width, 4)
    if footprint:
        img *= footprint_mask(trav, cam)[..., None]
    return img

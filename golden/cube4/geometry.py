"""Depth in: opaque geometry drawn with the scene's camera ends the rays (docs/numerics.md §22).

VolumePro 1000 reads a depth buffer so that polygons drawn elsewhere (a surgical tool, a
probe) and the volume rendering composite correctly: a ray ends where the geometry begins,
and the geometry shows through what the volume leaves transparent.

* **The image** (``Geometry``): the depth of the geometry at each pixel centre of the
  scene's output as depth out gives it (§21: distance along the view direction from the
  volume's centre, voxels of the whole volume; +inf: no geometry), and optionally its
  premultiplied RGBA. The application makes it from the scene's ``[geometry]``: an EXR
  with a channel Z (and R, G, B, A), or a mesh it draws with the scene's camera
  (``cube4.app.mesh``: trimesh's ray casting; ``cube4 mesh`` writes the EXR).
* **Stop slices** (``stop_slices``): per base-plane pixel, the image pixel nearest to where
  the warp takes it gives z_stop, and the ray counts its sample slice m only while its
  point's depth z(m) < z_stop: ``stop = #{m : z(m) < z_stop}`` (z grows with m along the
  ray). The host computes the table per frame (each q×q pass with its own traversal) and
  the model masks ``m >= stop`` like a clip (``model.render_frame(stop_m=...)``).
* **Composite**: the picture is the volume over the geometry's colour,
  ``rgba + (1 - A) * geometry``, for the golden model and the reference alike; the
  reference ends each of its rays at its pixel's z_stop.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import UserError
from .view import Camera, Traversal, warp_matrix


@dataclass(frozen=True)
class Geometry:
    """A depth image (H, W) and, optionally, the geometry's premultiplied RGBA (H, W, 4)."""

    z: np.ndarray
    rgba: np.ndarray | None = None


def check_geometry(geo: Geometry, cam: Camera) -> None:
    """One line unless the image is the output's size and every depth lies in the view
    (finite within the volume's reach of its centre, or +inf: no geometry)."""
    h, w = geo.z.shape[:2]
    if (w, h) != (cam.width, cam.height):
        raise UserError(f"geometry image is {w}x{h}, the scene's output is {cam.width}x{cam.height}")
    reach = 0.5 * float(np.linalg.norm(np.asarray(cam.dims, dtype=np.float64))) + 1.0
    z = geo.z
    bad = ~(np.isposinf(z) | (np.isfinite(z) & (np.abs(z) <= reach)))
    if bad.any():
        r, c = (int(v) for v in np.argwhere(bad)[0])
        raise UserError(f"geometry depth {float(z[r, c])!r} at pixel ({c}, {r}) lies outside the view "
                        f"(finite within +-{reach:.1f} voxels of the volume's centre, or +inf for none)")
    if geo.rgba is not None and not (np.isfinite(geo.rgba).all() and (geo.rgba >= 0).all()
                                     and (geo.rgba <= 1).all()):
        raise UserError("geometry colour must be premultiplied RGBA in [0, 1]")


def stop_slices(trav: Traversal, cam: Camera, z_img: np.ndarray) -> np.ndarray:
    """(rows, cols) int64: per base-plane pixel of ``trav`` the number of its sample slices
    in front of the geometry, #{m : z(m) < z_stop}, z_stop the depth of the image pixel
    nearest to where the warp takes the base-plane pixel (+inf outside the image)."""
    rows, cols = trav.baseplane_shape
    by, bx = np.mgrid[0:rows, 0:cols]
    mat = warp_matrix(trav, cam)
    col = np.floor(mat[0, 0] * bx + mat[0, 1] * by + mat[0, 2] + 0.5).astype(np.int64)
    row = np.floor(mat[1, 0] * bx + mat[1, 1] * by + mat[1, 2] + 0.5).astype(np.int64)
    h, w = z_img.shape
    inside = (col >= 0) & (col < w) & (row >= 0) & (row < h)
    z_stop = np.full((rows, cols), np.inf)
    z_stop[inside] = z_img[row[inside], col[inside]]
    M = trav.num_sample_slices
    z0 = (trav.ray_point(bx, by, 0.0) - cam.centre) @ cam.direction
    dz = ((trav.ray_point(bx, by, 1.0 / trav.supersample) - cam.centre) @ cam.direction) - z0   # > 0
    with np.errstate(invalid="ignore"):
        n = np.ceil((z_stop - z0) / dz)
    n = np.where(np.isposinf(z_stop), M, n)
    return np.clip(n, 0, M).astype(np.int64)


def composite_over(rgba: np.ndarray, geo: Geometry | None) -> np.ndarray:
    """The volume's premultiplied RGBA over the geometry's colour (unchanged without one)."""
    if geo is None or geo.rgba is None:
        return rgba
    return rgba + (1.0 - rgba[..., 3:4]) * geo.rgba

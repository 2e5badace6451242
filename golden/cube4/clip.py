"""Which samples count: the composite window and the cut plane (docs/numerics.md §12).

A sample (m, j, i) of the traversal frame *counts* when it is inside the volume box
(``model.inside_mask``), inside the window and on the kept side of the cut plane. A
sample that does not count adds nothing (no colour, no opacity, no MIP candidate); rays
still pass through it and finish where they leave the box, as before. The window and the
kept half-space are convex, so the samples of a ray that count are consecutive.

* **Window** ``(i0, i1, j0, j1, m0, m1)``: half-open bounds on the sample indices; a
  brick counts only its own samples, not those of its overlap.
* **Cut plane** ``(CA, CB, CC, CD)``, signed integers: a sample counts when

      E = CA * (i * 2^W + wx(m)) + CB * (j * 2^W + wy(m)) + CC * (m * 2^(W - g)) + CD  >=  0,

  i.e. the plane is evaluated exactly, in integers, at the sample's quantised position
  (i + wx / 2^W, j + wy / 2^W, m / S), all three coordinates in units of 2^-W voxel
  (g = log2 S). ``cut_coefficients`` turns a plane given in volume
  coordinates into these coefficients: CA, CB, CC fit CUT_W = 18 signed bits, CD and E fit
  CUT_E_W = 48.

The RTL computes the same predicate (``rtl/cube4_clip.v``) from the same registers.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import UserError
from .view import Traversal

CUT_W = 18      # CA, CB, CC: signed
CUT_E_W = 48    # CD and the plane value E: signed
CUT_MAX = (1 << (CUT_W - 1)) - 1


@dataclass(frozen=True)
class Clip:
    """The samples that count (see the module text). None = no bound."""

    window: tuple[int, int, int, int, int, int] | None = None
    plane: tuple[int, int, int, int] | None = None

    def keep(self, trav: Traversal, m: int) -> np.ndarray:
        """(nj, ni) bool: the samples of slice m that the window and the plane keep."""
        nj, ni = trav.nj, trav.ni
        jj, ii = np.mgrid[0:nj, 0:ni]
        keep = np.ones((nj, ni), dtype=bool)
        if self.window is not None:
            i0, i1, j0, j1, m0, m1 = self.window
            keep &= (ii >= i0) & (ii < i1) & (jj >= j0) & (jj < j1)
            if not m0 <= m < m1:
                keep[:] = False
        if self.plane is not None:
            keep &= plane_value(self.plane, trav, m, jj, ii) >= 0
        return keep


def plane_value(plane, trav: Traversal, m: int, jj, ii) -> np.ndarray:
    """E of the samples (m, jj, ii) (integers, int64; |E| < 2^(CUT_E_W - 1))."""
    ca, cb, cc, cd = (int(c) for c in plane)
    wx, wy, _ = (int(w) for w in trav.weights(m))
    W = trav.weight_bits
    return (ca * ((np.asarray(ii, dtype=np.int64) << W) + wx)
            + cb * ((np.asarray(jj, dtype=np.int64) << W) + wy) + cc * (m << (W - trav.guard_bits)) + cd)


def move_plane(plane, start, weight_bits: int) -> tuple[int, int, int, int] | None:
    """The cut plane of a traversal whose voxel (0, 0, 0) lies at ``start`` = (i, j, k)
    of the plane's frame (a brick, the empty-space box): E's coordinates are in 2^-W
    voxel, so CD takes CA·i·2^W + CB·j·2^W + CC·k·2^W. None stays None."""
    if plane is None:
        return None
    ca, cb, cc, cd = (int(c) for c in plane)
    i0, j0, k0 = (int(c) for c in start)
    W = weight_bits
    return (ca, cb, cc, cd + ca * (i0 << W) + cb * (j0 << W) + cc * (k0 << W))


def cut_coefficients(trav: Traversal, normal, point) -> tuple[int, int, int, int]:
    """The cut plane through ``point`` (volume coordinates of the whole volume) with unit
    ``normal`` pointing into the half-space that is cut away, as (CA, CB, CC, CD) for
    ``trav``: a sample p counts when normal . (p - point) <= 0, evaluated at the
    quantised coefficients (the largest of CA, CB, CC is +-(2^(CUT_W-1) - 1))."""
    n = np.asarray(normal, dtype=np.float64)
    n = n / np.linalg.norm(n)
    c = np.asarray(point, dtype=np.float64) - np.asarray(trav.origin, dtype=np.float64)
    W = trav.weight_bits
    # volume coordinate p_ax = flip ? (n_ax - 1 - u) : u, u the traversal coordinate;
    # counts when f(u) = -normal . (p - point) >= 0, f = sum a_t u_t + e
    a = np.zeros(3)
    e = 0.0
    for t, ax in enumerate((trav.axis_i, trav.axis_j, trav.major)):
        if trav.flip[ax]:
            a[t] = n[ax]
            e -= n[ax] * ((trav.dims[ax] - 1) - c[ax])
        else:
            a[t] = -n[ax]
            e += n[ax] * c[ax]
    # E = CA (i 2^W + wx) + CB (j 2^W + wy) + CC (m 2^(W-g)) + CD  =  K 2^W f(u), u_k = m / S:
    # every coordinate in units of 2^-W voxel, so the three coefficients share one scale
    big = float(np.max(np.abs(a)))
    k = CUT_MAX / big
    ca, cb, cc = (int(np.floor(v * k + 0.5)) for v in a)
    cd = int(np.floor(e * k * (1 << W) + 0.5))
    bound = 1 << (CUT_E_W - 1)
    # the largest |E| over the box: every coordinate at most 2^W * (n + 1)
    reach = (abs(ca) * (trav.ni + 1) + abs(cb) * (trav.nj + 1) + abs(cc) * (trav.nk + 1)) * (1 << W) + abs(cd)
    if reach >= bound:
        raise UserError("cut plane: the plane lies too far from the volume (its offset does not fit the register)")
    return ca, cb, cc, cd


def check_window(window, trav: Traversal) -> None:
    """A window's bounds are sample indices of the traversal: 0 <= lo <= hi <= n per axis
    (the registers hold no more)."""
    i0, i1, j0, j1, m0, m1 = (int(v) for v in window)
    for lo, hi, n, name in ((i0, i1, trav.ni, "i"), (j0, j1, trav.nj, "j"), (m0, m1, trav.num_sample_slices, "m")):
        if not 0 <= lo <= hi <= n:
            raise UserError(f"window: {name} bounds {lo}..{hi} must satisfy 0 <= lo <= hi <= {n}")

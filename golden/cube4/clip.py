"""Which samples count: the composite window and the cut plane (docs/numerics.md §12).

A sample (m, j, i) of the traversal frame *counts* when it is inside the volume box
(``model.inside_mask``), inside the window and on the kept side of the cut plane. A
sample that does not count adds nothing (no colour, no opacity, no MIP candidate); rays
still pass through it and finish where they leave the box, as before. The window and the
kept half-space are convex, so the samples of a ray that count are consecutive.

* **Window** ``(i0, i1, j0, j1, m0, m1)``: half-open bounds on the sample indices; a
  brick counts only its own samples, not those of its overlap.
* **Crop regions** ``(I0, I1, J0, J1, M0, M1, TABLE)``: three slabs of the traversal
  frame (``crop_regions``) cut it into 3 × 3 × 3 regions, and TABLE (27 bits) keeps
  some: along i a sample at i + wx/2^W lies *below* (r = 0) when i < I0, *above* (r = 2)
  when i > I1 or i = I1 and wx > 0 (its position passes the plane I1), else *inside*
  (r = 1); along j alike with wy; along k the sample slice m (at m/S) lies below when
  m < M0 and above when m > M1 (M0, M1 in sample slices). The sample counts when bit
  r_i + 3 r_j + 9 r_k of TABLE is set. The planes are the scene's crop box's faces
  (``[crop] mode``: VTK's subvolume, fence, inverted fence, cross, inverted cross, or
  its 27 region flags), exactly at the sample's quantised position. A region set need
  not be convex: a ray's samples that count may come in several runs, which changes
  nothing (a sample that does not count adds nothing).
* **Cut plane** ``(CA, CB, CC, CD)``, signed integers: a sample counts when

      E = CA * (i * 2^W + wx(m)) + CB * (j * 2^W + wy(m)) + CC * (m * 2^(W - g)) + CD  >=  0,

  i.e. the plane is evaluated exactly, in integers, at the sample's quantised position
  (i + wx / 2^W, j + wy / 2^W, m / S), all three coordinates in units of 2^-W voxel
  (g = log2 S). ``cut_coefficients`` turns a plane given in volume
  coordinates into these coefficients: CA, CB, CC fit CUT_W = 18 signed bits, CD and E fit
  CUT_E_W = 48.
* **Slab** ``(CT, FS, FON)`` beside the plane: a sample counts only when also
  E <= CT (the slab's far face: the plane's value there is CT), and with FON = 1 its
  opacity is multiplied by the falloff weight

      f = min(min(E, CT - E) >> FS, 256)          (Q.8: 256 is one)

  in the blending modes (composite, X-ray: A' = round_shift(A f, 8) after the path
  weights; MIP and MinIP take none). ``slab_coefficients`` scales the plane so that one
  falloff width is 2^(FS + 8) units of E: f = floor(256 d / F) for a sample at d voxels
  inside the nearer face, F the falloff width.

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
CUT_T_NONE = (1 << (CUT_E_W - 1)) - 1   # CT without a slab: every E of the box lies below it


@dataclass(frozen=True)
class Clip:
    """The samples that count (see the module text). None = no bound."""

    window: tuple[int, int, int, int, int, int] | None = None
    plane: tuple[int, int, int, int] | None = None
    regions: tuple[int, int, int, int, int, int, int] | None = None
    slab: tuple[int, int, int] | None = None      # (CT, FS, FON) with ``plane``

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
            e = plane_value(self.plane, trav, m, jj, ii)
            keep &= e >= 0
            if self.slab is not None:
                keep &= e <= int(self.slab[0])
        if self.regions is not None:
            keep &= region_keep(self.regions, trav, m, jj, ii)
        return keep

    def far_plane(self) -> tuple[int, int, int, int] | None:
        """The slab's far face as a plane of its own, CT - E >= 0 (None: no slab)."""
        if self.plane is None or self.slab is None:
            return None
        ca, cb, cc, cd = (int(c) for c in self.plane)
        return (-ca, -cb, -cc, int(self.slab[0]) - cd)

    def falloff(self, trav: Traversal, m: int) -> np.ndarray | None:
        """(nj, ni) int64: the slab's falloff weight f of slice m's samples (0 .. 256; see
        the module text), or None when the frame has none (f = 256 everywhere)."""
        if self.slab is None or not int(self.slab[2]):
            return None
        ct, fs = int(self.slab[0]), int(self.slab[1])
        jj, ii = np.mgrid[0:trav.nj, 0:trav.ni]
        e = plane_value(self.plane, trav, m, jj, ii)
        return np.minimum(np.maximum(np.minimum(e, ct - e), 0) >> fs, FALL_ONE)


FALL_W = 9          # the falloff weight f: 0 .. 256 (Q.8)
FALL_SHIFT = 8
FALL_ONE = 1 << FALL_SHIFT
FALL_SH_MAX = 63    # FS: a 6-bit register


#: VTK's cropping region flags (vtkVolumeMapper): bit rx + 3 ry + 9 rz, r = 0 below the
#: box's low face along that axis, 1 within, 2 above
CROP_MODES = {
    "subvolume": 0x0002000,        # the box
    "fence": 0x2EBFEBA,            # regions within the box along at least one axis
    "inverted_fence": 0x5140145,   # within along none (the eight corners)
    "cross": 0x0417410,            # within along at least two
    "inverted_cross": 0x7BE8BEF,   # within along at most one
}
REGIONS_ALL = (1 << 27) - 1


def _region(u, lo: int, hi: int, frac):
    """0 below, 1 inside, 2 above: u the sample's integer coordinate, frac its fraction
    (non-zero: the position lies past u)."""
    u = np.asarray(u, dtype=np.int64)
    above = (u > hi) | ((u == hi) & (np.asarray(frac) > 0))
    return np.where(u < lo, 0, np.where(above, 2, 1))


def region_keep(regions, trav: Traversal, m: int, jj, ii) -> np.ndarray:
    """The samples (m, jj, ii) whose region TABLE keeps (see the module text)."""
    i0, i1, j0, j1, m0, m1, table = (int(v) for v in regions)
    wx, wy, _ = (int(w) for w in trav.weights(m))
    ri = _region(ii, i0, i1, wx)
    rj = _region(jj, j0, j1, wy)
    rm = 0 if m < m0 else (2 if m > m1 else 1)
    return ((table >> (ri + 3 * rj + 9 * rm)) & 1).astype(bool)


def _fold(table: int, axis: int, to: int) -> int:
    """``table`` with every region along ``axis`` (0: i, 1: j, 2: k) taking region ``to``'s bit."""
    out = 0
    for r in range(27):
        a = [r % 3, (r // 3) % 3, r // 9]
        a[axis] = to
        if (table >> (a[0] + 3 * a[1] + 9 * a[2])) & 1:
            out |= 1 << r
    return out


def crop_regions(trav: Traversal, lo, hi, flags: int) -> tuple[int, int, int, int, int, int, int]:
    """The crop regions of ``trav``'s frame from the box [lo, hi] (voxel coordinates of
    the whole volume, inclusive, x y z) and VTK's 27 region flags (bit rx + 3 ry + 9 rz):
    each volume axis becomes its traversal axis, a flipped axis swaps below and above."""
    S = trav.supersample
    bounds, perm, flipped = [], [], []
    for ax in (trav.axis_i, trav.axis_j, trav.major):
        a, b = int(lo[ax]) - int(trav.origin[ax]), int(hi[ax]) - int(trav.origin[ax])
        if trav.flip[ax]:
            n = int(trav.dims[ax])
            a, b = n - 1 - b, n - 1 - a
        bounds.append((a, b))
        perm.append(ax)
        flipped.append(bool(trav.flip[ax]))
    table = 0
    for r in range(27):
        t = [r % 3, (r // 3) % 3, r // 9]            # traversal axes i, j, k
        v = [0, 0, 0]                                # volume axes x, y, z
        for pos, ax in enumerate(perm):
            v[ax] = 2 - t[pos] if flipped[pos] else t[pos]
        if (int(flags) >> (v[0] + 3 * v[1] + 9 * v[2])) & 1:
            table |= 1 << r
    (i0, i1), (j0, j1), (k0, k1) = bounds
    return fit_regions((i0, i1, j0, j1, k0 * S, k1 * S, table), trav)


def fit_regions(regions, trav: Traversal) -> tuple[int, int, int, int, int, int, int]:
    """The same regions with every plane within its register's range: a low plane below
    0 is 0 (nothing lies below it either way) and above n is n; a high plane above n is n;
    a high plane below 0 puts every sample above it, so the table takes the above
    region's bits along that axis."""
    i0, i1, j0, j1, m0, m1, table = (int(v) for v in regions)
    out = []
    for axis, (a, b, n) in enumerate(((i0, i1, trav.ni), (j0, j1, trav.nj), (m0, m1, trav.num_sample_slices))):
        if b < 0:
            table = _fold(table, axis, 2)
            a, b = 0, 0
        out += [min(max(a, 0), n), min(b, n)]
    return (*out, table)


def move_regions(regions, start, supersample: int):
    """The crop regions of a traversal whose voxel (0, 0, 0) lies at ``start`` = (i, j, k)
    of the regions' frame (the empty-space box, a sub-pixel pass's box): the planes move
    by the start (k in sample slices). None stays None. ``fit_regions`` then fits them."""
    if regions is None:
        return None
    i0, i1, j0, j1, m0, m1, table = (int(v) for v in regions)
    a, b, c = (int(v) for v in start)
    return (i0 - a, i1 - a, j0 - b, j1 - b, m0 - c * supersample, m1 - c * supersample, table)


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


def _largest_coefficient(trav: Traversal, n) -> float:
    """The largest |component| of the unit normal n over the traversal's three axes."""
    return float(max(abs(n[ax]) for ax in (trav.axis_i, trav.axis_j, trav.major)))


def _reach(trav: Traversal, plane) -> int:
    """The largest |E| of ``plane`` over the box: every coordinate at most 2^W (n + 1)."""
    ca, cb, cc, cd = (int(c) for c in plane)
    return (abs(ca) * (trav.ni + 1) + abs(cb) * (trav.nj + 1) + abs(cc) * (trav.nk + 1)) * (1 << trav.weight_bits) \
        + abs(cd)


def cut_coefficients(trav: Traversal, normal, point, scale: float | None = None) -> tuple[int, int, int, int]:
    """The cut plane through ``point`` (volume coordinates of the whole volume) with unit
    ``normal`` pointing into the half-space that is cut away, as (CA, CB, CC, CD) for
    ``trav``: a sample p counts when normal . (p - point) <= 0, evaluated at the
    quantised coefficients (the largest of CA, CB, CC is +-(2^(CUT_W-1) - 1); ``scale``:
    E's units per 2^-W voxel instead, at most that)."""
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
    k = CUT_MAX / big if scale is None else float(scale)
    ca, cb, cc = (int(np.floor(v * k + 0.5)) for v in a)
    cd = int(np.floor(e * k * (1 << W) + 0.5))
    if _reach(trav, (ca, cb, cc, cd)) >= 1 << (CUT_E_W - 1):
        raise UserError("cut plane: the plane lies too far from the volume (its offset does not fit the register)")
    return ca, cb, cc, cd


def slab_coefficients(trav: Traversal, normal, center, thickness: float,
                      falloff: float = 0.0) -> tuple[tuple[int, int, int, int], tuple[int, int, int]]:
    """The slab |normal . (p - center)| <= thickness / 2 (volume coordinates of the whole
    volume, unit ``normal``) as the plane (CA, CB, CC, CD), E >= 0 on the side away from
    ``normal``'s face, and (CT, FS, FON): E <= CT on the other face, and with a falloff
    width F > 0 (voxels) the plane scaled so that F is 2^(FS + 8) units of E."""
    n = np.asarray(normal, dtype=np.float64)
    n = n / np.linalg.norm(n)
    t = float(thickness)
    face = np.asarray(center, dtype=np.float64) + 0.5 * t * n     # the face normal points out of
    W = trav.weight_bits
    big = _largest_coefficient(trav, n)
    if falloff > 0:
        # the largest FS with 2^(FS + 8 - W) / F * big <= CUT_MAX: one falloff width is
        # 2^(FS + 8) units of E exactly
        fs = int(np.floor(np.log2(CUT_MAX * float(falloff) / big))) + W - 8
        if fs < 0:
            raise UserError("slab: the falloff is too narrow for the plane's coefficients")
        if fs > FALL_SH_MAX:
            raise UserError("slab: the falloff is too wide for the falloff register")
        scale = 2.0 ** (fs + 8 - W) / float(falloff)
    else:
        fs, scale = 0, CUT_MAX / big
    plane = cut_coefficients(trav, n, face, scale=scale)
    ct = int(np.floor(scale * t * (1 << W) + 0.5))
    reach = _reach(trav, plane)
    if reach + ct >= 1 << (CUT_E_W - 1):
        raise UserError("slab: the slab lies too far from the volume or is too thick (its registers do not fit)")
    return plane, (ct, fs, int(falloff > 0))


def check_window(window, trav: Traversal) -> None:
    """A window's bounds are sample indices of the traversal: 0 <= lo <= hi <= n per axis
    (the registers hold no more)."""
    i0, i1, j0, j1, m0, m1 = (int(v) for v in window)
    for lo, hi, n, name in ((i0, i1, trav.ni, "i"), (j0, j1, trav.nj, "j"), (m0, m1, trav.num_sample_slices, "m")):
        if not 0 <= lo <= hi <= n:
            raise UserError(f"window: {name} bounds {lo}..{hi} must satisfy 0 <= lo <= hi <= {n}")


def region_cells(trav: Traversal, regions) -> np.ndarray:
    """(nz, ny, nx) bool: the cells of ``trav``'s box that reach a kept region. A cell
    spans one voxel along every axis of the traversal frame, [u, u + 1], and reaches the
    regions its span meets (along k, the sample slices m with u <= m/S <= u + 1)."""
    i0, i1, j0, j1, m0, m1, table = (int(v) for v in regions)
    S = trav.supersample
    per_axis = {}
    for ax, (lo, hi, scale) in ((trav.axis_i, (i0, i1, 1)), (trav.axis_j, (j0, j1, 1)),
                                (trav.major, (m0, m1, S))):
        n = int(trav.dims[ax])
        c = np.arange(n, dtype=np.int64)
        u = (n - 2 - c if trav.flip[ax] else c) * scale      # the cell's low corner, traversal frame
        span = scale                                          # its high corner is u + span
        per_axis[ax] = np.stack([u < lo, (u + span >= lo) & (u <= hi), u + span > hi])
    out = np.zeros((int(trav.dims[2]), int(trav.dims[1]), int(trav.dims[0])), dtype=bool)
    order = (trav.axis_i, trav.axis_j, trav.major)
    for r in range(27):
        if not (table >> r) & 1:
            continue
        t = (r % 3, (r // 3) % 3, r // 9)
        reach = {ax: per_axis[ax][t[pos]] for pos, ax in enumerate(order)}
        out |= reach[2][:, None, None] & reach[1][None, :, None] & reach[0][None, None, :]
    return out

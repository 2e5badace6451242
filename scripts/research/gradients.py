"""Gradient estimators on the sample stream: a study for the next GRA (a research
prototype, not part of the bit-exact model or of the shipped packages;
reports/gradient_research.md). Run it from the repository's root as
``python scripts/research/gradients.py``; its results are stored in
reports/gradient_research/*.json, which ``make report`` reads; its tests beside it
(``pytest scripts/research``) are not part of ``make test``.

Every estimator returns integer gradients (M, 3, nj, ni) in traversal axes (i, j, k)
for the sample stream of one traversal, like ``model.gradient_stream``; only the
direction matters to the reflectance map, so each estimator may have its own scale.

Estimators on the *sample* stream (fit the GRA position after the TRI unit):

* ``gra``    the current model (numerics.md §5): ±1 slice along the ray, S·gr - shear.
* ``ray``    (a) ±H slices along the ray (H = S: one voxel each way), gk = gr - shear.
* ``ray_s``  (b) (a) with in-slice [1,2,1] smoothing: gi/gj 2-D Sobel in the slice,
             gr smoothed 3×3 in the slice; shear correction with the Sobel gi/gj.
* ``sobel``  (c) 3×3×3 Sobel on the sheared lattice (e_i, e_j, ray step of H slices):
             gi/gj smoothed in the slice and along the ray (±H slices), gk = gr - shear.
* ``sobel_k1`` (c) but the along-ray smoothing of gi/gj uses ±1 slice (gr still ±H).
* ``tri``    (d) gk from the TRI unit's two bilinear planes (B(k0+1) - B(k0), the exact
             k-derivative of the tri-linear field, a free by-product of the z lerp),
             gi/gj central differences; ``tri_s`` the same smoothed 3×3 in the slice.

H defaults to S; ``ray_s@2`` etc. cap H at 2 (fewer slice buffers, stencil 2H/S).
Suffix ``_n`` (``ray_n``, ``sobel_n``, ...): the ±H neighbours on the lattice vector
nearest to the k axis (shear correction with the signed residual slope); ``_v``: the ±S
slices re-interpolated straight above/below the sample (no shear correction).
The recommended estimator is ``sobel_n`` (reports/gradient_research.md).

Voxel estimators (need a second set of three interpolators), for comparison:

* ``vcd``    voxel central differences, tri-linearly interpolated (= the reference's).
* ``vsobel`` voxel 3×3×3 Sobel, tri-linearly interpolated.

Measurement: ``angle_errors`` compares each estimator's direction with the analytic
radial normal of the ``sphere`` built-in at every sample within half a voxel of its
surface.
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from cube4.fixed import lerp, round_shift
from cube4.model import inside_mask, sample_stream
from cube4.view import Traversal, make_traversal

W121 = (1, 2, 1)
OFF = (-1, 0, 1)
MARGIN = 5  # in-slice zero padding of the sample stream
E = 2       # margin kept around a ray slice (3×3 smoothing of a central difference)


# ---------------------------------------------------------------- helpers
class RayStream:
    """The sample stream zero-padded by H slices in m and MARGIN samples in j and i,
    with ray-following access: ``ray(m, h)`` is slice m + h shifted so that element
    [j, i] (plus E) is the sample of the ray through (m, j, i).

    nearest: in slices m ± H the neighbour is taken on the lattice vector nearest to
    the k axis, d' = d - (RX, RY, 0), R = round(slope over H slices) in {0, 1}, so the
    residual slope VX' = VIEW_X - RX·2^W lies in [-2^(W-1), 2^(W-1)].
    vertical (H = S only): slices m ± S are re-interpolated (one bilinear lerp with the
    view-constant weights |VX'|, |VY'|) at the point straight above/below the sample,
    so that no shear correction is needed."""

    def __init__(self, samples: np.ndarray, trav: Traversal, H: int, nearest: bool = False,
                 vertical: bool = False):
        M, nj, ni = samples.shape
        self.rx = self.ry = 0
        self.vertical = vertical
        if vertical:
            assert H == trav.supersample
            nearest = True
        if nearest:
            self.rx, self.ry = (round_shift(H * v, trav.weight_bits + trav.guard_bits) for v in (trav.view_x, trav.view_y))
        one = 1 << trav.weight_bits
        f = one * (trav.supersample // H)
        self.vx, self.vy = trav.view_x - self.rx * f, trav.view_y - self.ry * f  # residual slopes, Q.W per voxel
        self.M, self.nj, self.ni, self.H, self.trav = M, nj, ni, H, trav
        self.pad = np.zeros((M + 2 * H, nj + 2 * MARGIN, ni + 2 * MARGIN), dtype=np.int64)
        self.pad[H:H + M, MARGIN:MARGIN + nj, MARGIN:MARGIN + ni] = samples
        self._m = None
        self._cache: dict = {}

    def _cut(self, m: int, h: int, dx: int, dy: int) -> np.ndarray:
        assert abs(dx) + E <= MARGIN and abs(dy) + E <= MARGIN
        sl = self.pad[self.H + m + h]
        return sl[MARGIN + dy - E:MARGIN + dy + self.nj + E, MARGIN + dx - E:MARGIN + dx + self.ni + E]

    def ray(self, m: int, h: int) -> np.ndarray:
        if self._m != m:
            self._m, self._cache = m, {}
        if h not in self._cache:
            t = self.trav
            sx0, sy0 = (int(v) for v in t.steps(m))
            sx1, sy1 = (int(v) for v in t.steps(m + h))
            dx, dy = sx1 - sx0, sy1 - sy0
            sgn = 1 if h > 0 else -1
            if abs(h) == self.H:
                dx, dy = dx - sgn * self.rx, dy - sgn * self.ry
            a = self._cut(m, h, dx, dy)
            if self.vertical and abs(h) == self.H:
                # the vertical point sits at -sgn·(VX', VY')/2^W from the lattice point
                W = t.weight_bits
                ox = -sgn * (1 if self.vx > 0 else -1)
                oy = -sgn * (1 if self.vy > 0 else -1)
                wx, wy = abs(self.vx), abs(self.vy)
                bx = self._cut(m, h, dx + ox, dy)
                a = lerp(a, bx, wx, W)
                ay = self._cut(m, h, dx, dy + oy)
                bxy = self._cut(m, h, dx + ox, dy + oy)
                a = lerp(a, lerp(ay, bxy, wx, W), wy, W)
            self._cache[h] = a
        return self._cache[h]

    def at(self, m: int, h: int, dj: int, di: int) -> np.ndarray:
        """s[ray(m, h) + (dj, di)] for every (j, i) of slice m: shape (nj, ni)."""
        a = self.ray(m, h)
        return a[E + dj:E + dj + self.nj, E + di:E + di + self.ni]


def d_i(rs: RayStream, m, h, dj=0, di=0):
    return rs.at(m, h, dj, di + 1) - rs.at(m, h, dj, di - 1)


def d_j(rs: RayStream, m, h, dj=0, di=0):
    return rs.at(m, h, dj + 1, di) - rs.at(m, h, dj - 1, di)


def shear(trav: Traversal, gi, gj, rs: "RayStream | None" = None):
    """round_shift(VX·gi + VY·gj, W): the ray's sheared part over one voxel, with
    VX = VIEW_X (- RX·2^W on the nearest-to-k lattice, then in [-2^(W-1), 2^(W-1)])."""
    vx, vy = trav.view_x, trav.view_y
    if rs is not None:
        vx, vy = (0, 0) if rs.vertical else (rs.vx, rs.vy)
    return round_shift(vx * gi + vy * gj, trav.weight_bits)


# ---------------------------------------------------------------- sample-stream estimators
def est_gra(rs: RayStream, trav: Traversal, m: int) -> np.ndarray:
    gi, gj = d_i(rs, m, 0), d_j(rs, m, 0)
    gr = rs.at(m, 1, 0, 0) - rs.at(m, -1, 0, 0)
    return np.stack([gi, gj, trav.supersample * gr - shear(trav, gi, gj)])


def est_ray(rs: RayStream, trav: Traversal, m: int, H: int) -> np.ndarray:
    """(a): gr over ±H slices, scaled by S/H to one voxel each way."""
    gi, gj = d_i(rs, m, 0), d_j(rs, m, 0)
    gr = rs.at(m, H, 0, 0) - rs.at(m, -H, 0, 0)
    return np.stack([gi, gj, (trav.supersample // H) * gr - shear(trav, gi, gj, rs)])


def _gr_smoothed(rs, m, H):
    """Σ_{dj,di} [1,2,1]⊗[1,2,1] (s[ray(m,+H)] - s[ray(m,-H)]): weight sum 16."""
    acc = 0
    for wj, dj in zip(W121, OFF):
        for wi, di in zip(W121, OFF):
            acc = acc + (wj * wi) * (rs.at(m, H, dj, di) - rs.at(m, -H, dj, di))
    return acc


def _sobel2(rs, m, h):
    """In-slice 2-D Sobel of ray slice h: (gi smoothed in j, gj smoothed in i), sum 4."""
    gi = sum(w * d_i(rs, m, h, dj=dj) for w, dj in zip(W121, OFF))
    gj = sum(w * d_j(rs, m, h, di=di) for w, di in zip(W121, OFF))
    return gi, gj


def est_ray_s(rs: RayStream, trav: Traversal, m: int, H: int) -> np.ndarray:
    """(b): 2-D Sobel gi/gj (×4 -> sum 16), gr smoothed 3×3 (sum 16)."""
    gi, gj = _sobel2(rs, m, 0)
    gi, gj = 4 * gi, 4 * gj
    gr = (trav.supersample // H) * _gr_smoothed(rs, m, H)
    return np.stack([gi, gj, gr - shear(trav, gi, gj, rs)])


def est_sobel(rs: RayStream, trav: Traversal, m: int, H: int, Hs: int | None = None) -> np.ndarray:
    """(c): 3×3×3 Sobel on the sheared lattice; gi/gj smoothed along the ray with the
    ray neighbours at ±Hs slices (Hs = H: the full Sobel), all weights sum 16."""
    Hs = H if Hs is None else Hs
    gi = gj = 0
    for w, h in zip(W121, (-Hs, 0, Hs)):
        a, b = _sobel2(rs, m, h)
        gi, gj = gi + w * a, gj + w * b
    gr = (trav.supersample // H) * _gr_smoothed(rs, m, H)
    return np.stack([gi, gj, gr - shear(trav, gi, gj, rs)])


def padded_volume(vol: np.ndarray, trav: Traversal, e: int = 1) -> np.ndarray:
    """t[k, j, i] zero-padded by e samples before and e + 1 after in j and i, 2 after in k."""
    t = trav.to_traversal(vol)
    nk, nj, ni = t.shape
    tp = np.zeros((nk + 2, nj + 1 + 2 * e, ni + 1 + 2 * e), dtype=np.int64)
    tp[:nk, e:e + nj, e:e + ni] = t
    return tp


def bilinear_planes(tp: np.ndarray, trav: Traversal, m: int) -> tuple[np.ndarray, np.ndarray]:
    """The TRI unit's two bilinear samples of slice m, planes k0 and k0 + 1 (the z
    lerp's operands), with a margin of e samples (zeros outside), int64; tp from
    padded_volume."""
    W = trav.weight_bits
    wx, wy, _ = (int(w) for w in trav.weights(m))
    k0 = m // trav.supersample

    def bil(vs):
        ax = lerp(vs[:, :-1], vs[:, 1:], wx, W)
        return lerp(ax[:-1], ax[1:], wy, W)

    return bil(tp[k0]), bil(tp[k0 + 1])


def est_tri(rs: RayStream, trav: Traversal, m: int, b0, b1, smooth: bool) -> np.ndarray:
    """(d): gk = 2 (B(k0+1) - B(k0)) (a one-voxel difference, ×2 to the scale of a
    central difference); gi/gj central differences (smooth: 2-D Sobel and gk 3×3)."""
    nj, ni = trav.nj, trav.ni
    dk = b1 - b0  # margin 1

    def at(a, dj, di):
        return a[1 + dj:1 + dj + nj, 1 + di:1 + di + ni]

    if not smooth:
        return np.stack([d_i(rs, m, 0), d_j(rs, m, 0), 2 * at(dk, 0, 0)])
    gi, gj = _sobel2(rs, m, 0)
    gk = sum(wj * wi * at(dk, dj, di) for wj, dj in zip(W121, OFF) for wi, di in zip(W121, OFF))
    return np.stack([4 * gi, 4 * gj, 2 * gk])


SAMPLE_ESTIMATORS = ("gra", "ray", "ray_s", "sobel", "sobel_k1", "ray_s@2", "sobel@2", "tri", "tri_s",
                     "ray_n", "ray_s_n", "sobel_n", "sobel_n@2", "sobel_k1_n",
                     "ray_v", "ray_s_v", "sobel_v")
VOXEL_ESTIMATORS = ("vcd", "vsobel")
#: the bit-exact model's voxel gradients ([render] gradient = central / sobel, numerics.md §5b)
MODEL_ESTIMATORS = ("vgrad_central", "vgrad_sobel")
ESTIMATORS = SAMPLE_ESTIMATORS + VOXEL_ESTIMATORS + MODEL_ESTIMATORS


def _parse(name: str, S: int) -> tuple[str, int]:
    base, _, cap = name.partition("@")
    H = S if not cap else min(S, int(cap))
    return base, H


def _nearest(base: str) -> tuple[str, bool, bool]:
    """(base, nearest, vertical) from a suffix _n (nearest lattice) or _v (vertical)."""
    if base.endswith("_n"):
        return base[:-2], True, False
    if base.endswith("_v"):
        return base[:-2], True, True
    return base, False, False


def sample_gradient_stream(name: str, samples: np.ndarray, trav: Traversal, vol: np.ndarray | None = None) -> np.ndarray:
    """Gradients (M, 3, nj, ni) int64 of one sample-stream estimator."""
    S = trav.supersample
    base, H = _parse(name, S)
    base, nearest, vertical = _nearest(base)
    rs = RayStream(samples, trav, max(H, 1), nearest, vertical)
    M = samples.shape[0]
    out = np.empty((M, 3, trav.nj, trav.ni), dtype=np.int64)
    tp = padded_volume(vol, trav) if base in ("tri", "tri_s") else None
    for m in range(M):
        if base == "gra":
            out[m] = est_gra(rs, trav, m)
        elif base == "ray":
            out[m] = est_ray(rs, trav, m, H)
        elif base == "ray_s":
            out[m] = est_ray_s(rs, trav, m, H)
        elif base == "sobel":
            out[m] = est_sobel(rs, trav, m, H)
        elif base == "sobel_k1":
            out[m] = est_sobel(rs, trav, m, H, Hs=1)
        elif base in ("tri", "tri_s"):
            b0, b1 = bilinear_planes(tp, trav, m)
            out[m] = est_tri(rs, trav, m, b0, b1, base == "tri_s")
        else:
            raise ValueError(name)
    return out


# ---------------------------------------------------------------- voxel estimators
def voxel_gradients(t: np.ndarray, sobel: bool) -> np.ndarray:
    """(3, nk, nj, ni) int64 voxel gradients of t[k, j, i] (zeros outside):
    central differences, or the 3×3×3 Sobel (weights [1,2,1] across, sum 16)."""
    nk, nj, ni = t.shape
    p = np.zeros((nk + 2, nj + 2, ni + 2), dtype=np.int64)
    p[1:-1, 1:-1, 1:-1] = t

    def sh(dk, dj, di):
        return p[1 + dk:1 + dk + nk, 1 + dj:1 + dj + nj, 1 + di:1 + di + ni]

    if not sobel:
        return np.stack([sh(0, 0, 1) - sh(0, 0, -1), sh(0, 1, 0) - sh(0, -1, 0), sh(1, 0, 0) - sh(-1, 0, 0)])
    g = np.zeros((3, nk, nj, ni), dtype=np.int64)
    for wa, a in zip(W121, OFF):
        for wb, b in zip(W121, OFF):
            w = wa * wb
            g[0] += w * (sh(a, b, 1) - sh(a, b, -1))  # gi: smoothed in k (a) and j (b)
            g[1] += w * (sh(a, 1, b) - sh(a, -1, b))  # gj: smoothed in k and i
            g[2] += w * (sh(1, a, b) - sh(-1, a, b))  # gk: smoothed in j and i
    return g


def voxel_gradient_stream(name: str, vol: np.ndarray, trav: Traversal) -> np.ndarray:
    """Voxel gradients tri-linearly interpolated at the samples (three more TRI channels,
    each the model's seven lerps on signed values), (M, 3, nj, ni) int64."""
    from cube4.model import interpolate_slice

    t = trav.to_traversal(vol).astype(np.int64)
    g = voxel_gradients(t, sobel=(name == "vsobel"))
    nk, nj, ni = t.shape
    M = trav.num_sample_slices
    out = np.empty((M, 3, nj, ni), dtype=np.int64)
    for c in range(3):
        tp = np.zeros((nk + 1, nj + 1, ni + 1), dtype=np.int64)
        tp[:nk, :nj, :ni] = g[c]
        for m in range(M):
            out[m, c] = interpolate_slice(tp, trav, m, trav.weight_bits)
    return out


def model_gradient_stream(name: str, vol: np.ndarray, trav: Traversal, voxel_bits: int = 8) -> np.ndarray:
    """The bit-exact model's voxel gradients (what TRI emits with VGRAD = 1), turned from
    the volume's axes into the traversal frame like every other estimator here,
    (M, 3, nj, ni) float64."""
    from cube4.vgrad import pack_words

    words = pack_words(vol, name.removeprefix("vgrad_"), voxel_bits)
    chans, _ = sample_stream(words, trav, voxel_bits)
    g = np.moveaxis(chans[:, 1:], 1, -1).astype(np.float64)      # (M, nj, ni, 3): x, y, z
    return np.moveaxis(trav.vector_to_traversal(g), -1, 1)


def gradient_stream(name: str, vol: np.ndarray, trav: Traversal, samples: np.ndarray | None = None) -> np.ndarray:
    if name in MODEL_ESTIMATORS:
        return model_gradient_stream(name, vol, trav)
    if name in VOXEL_ESTIMATORS:
        return voxel_gradient_stream(name, vol, trav)
    if samples is None:
        samples, _ = sample_stream(vol, trav)
    return sample_gradient_stream(name, samples, trav, vol)


# ---------------------------------------------------------------- measurement
def sample_positions(trav: Traversal) -> np.ndarray:
    """Volume coordinates (x, y, z) of every sample, (M, nj, ni, 3)."""
    M = trav.num_sample_slices
    m = np.arange(M)
    wx, wy, _ = trav.weights(m)
    one = float(1 << trav.weight_bits)
    jj, ii = np.mgrid[0:trav.nj, 0:trav.ni]
    ti = ii[None] + (wx / one)[:, None, None]
    tj = jj[None] + (wy / one)[:, None, None]
    tk = np.broadcast_to((m / trav.supersample)[:, None, None], ti.shape)
    return trav.traversal_to_volume_points(ti, tj, tk)


def to_volume_axes(trav: Traversal, g: np.ndarray) -> np.ndarray:
    """Traversal-frame vectors (..., 3) as (i, j, k) -> volume axes (x, y, z)."""
    out = np.empty(g.shape, dtype=np.float64)
    for c, ax in enumerate((trav.axis_i, trav.axis_j, trav.major)):
        out[..., ax] = -g[..., c] if trav.flip[ax] else g[..., c]
    return out


def surface_selection(trav: Traversal, centre, radius, band: float = 0.5):
    """(mask (M, nj, ni), inward normals (N, 3)) of the inside samples within ``band``
    voxel of the sphere's surface."""
    pos = sample_positions(trav)
    rel = pos - np.asarray(centre)
    r = np.linalg.norm(rel, axis=-1)
    M = trav.num_sample_slices
    inside = np.stack([inside_mask(trav, m) for m in range(M)])
    sel = inside & (np.abs(r - radius) <= band)
    return sel, -rel[sel] / r[sel][:, None]


def angles(trav: Traversal, grads: np.ndarray, sel: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """Angle (degrees) between the estimator's gradient (the density's, pointing inward)
    and the inward normal at the selected samples; a zero gradient counts as 90°."""
    g = np.moveaxis(grads, 1, -1)[sel]  # (N, 3) traversal axes
    gv = to_volume_axes(trav, g)
    n = np.linalg.norm(gv, axis=-1)
    cos = np.where(n > 0, np.sum(gv * normals, axis=-1) / np.maximum(n, 1e-30), 0.0)
    return np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))


VIEWS = ((0, 0, 1), (0.3, -0.45, 1), (1, 1, 1), (1, 0.5, 0.2), (-0.6, 0.25, -1))
SUPERSAMPLES = (1, 2, 4, 8)


def angle_table(estimators=ESTIMATORS, views=VIEWS, supersamples=SUPERSAMPLES, spec: str = "sphere:64",
                weight_bits: int = 8, log=None) -> list[dict]:
    """One row per (estimator, view, S): mean, max angle, number of samples, and the
    largest |component| (bit growth check)."""
    from cube4.app.volumes import load_volume
    from cube4.phantoms import sphere_centre, sphere_radius

    vol = load_volume(spec)
    nz, ny, nx = vol.shape
    dims = (nx, ny, nz)
    centre, radius = sphere_centre(dims), sphere_radius(dims)
    rows = []
    for view in views:
        for S in supersamples:
            trav = make_traversal(dims, view, weight_bits, S)
            samples, _ = sample_stream(vol, trav)
            sel, normals = surface_selection(trav, centre, radius)
            for name in estimators:
                t0 = time.perf_counter()
                g = gradient_stream(name, vol, trav, samples)
                a = angles(trav, g, sel, normals)
                row = {"estimator": name, "view": tuple(view), "S": S, "mean": float(a.mean()),
                       "max": float(a.max()), "n": int(a.size), "absmax": int(np.abs(g).max()),
                       "s": time.perf_counter() - t0}
                rows.append(row)
                if log:
                    log(row)
    return rows




# ---------------------------------------------------------------- the golden render with another estimator
def render_frame_with(vol: np.ndarray, trav: Traversal, cfg, lut: np.ndarray, rmap: np.ndarray, estimator: str):
    """``model.render_frame`` (composite mode, shaded, no clip) with the gradient of
    ``estimator`` in place of model.gradient; everything else is the model's code.
    Returns the base plane (rows, cols, 4) int64 Q0.ACC_W."""
    from cube4.model import composite, shade

    samples, inside = sample_stream(vol, trav)
    grads = gradient_stream(estimator, vol, trav, samples)
    one = 1 << cfg.acc_bits
    rows, cols = trav.baseplane_shape
    sxm, sym = trav.max_steps
    nj, ni = trav.nj, trav.ni
    acc = np.zeros((3, rows, cols), dtype=np.int64)
    trans = np.full((rows, cols), one, dtype=np.int64)
    for m in range(trav.num_sample_slices):
        rgba, _ = shade(samples[m], grads[m], lut, rmap, cfg.rmap_bits)
        stx, sty = (int(v) for v in trav.steps(m))
        r0, c0 = sym - sty, sxm - stx
        composite(acc[:, r0:r0 + nj, c0:c0 + ni], trans[r0:r0 + nj, c0:c0 + ni], rgba, inside[m], cfg)
    base = np.empty((rows, cols, 4), dtype=np.int64)
    base[..., :3] = np.moveaxis(acc, 0, -1)
    base[..., 3] = one - trans
    return base


def render_image(vol: np.ndarray, scene, cfg, estimator: str) -> np.ndarray:
    """The golden image of one view (whole box, no skipping, q = 1) with ``estimator``."""
    from cube4.app.warp import warp_to_image
    from cube4.host import host_tables, setup_view

    nz, ny, nx = vol.shape
    trav, cam = setup_view((nx, ny, nz), scene, cfg)
    lut, rmap = host_tables(scene, cfg, trav)
    base = render_frame_with(vol, trav, cfg, lut, rmap, estimator)
    return warp_to_image(base.astype(np.float64) / float(1 << cfg.acc_bits), trav, cam)


def analytic_gradient(spec: str, dims, pts: np.ndarray) -> np.ndarray | None:
    """The analytic gradient direction (x, y, z) of a built-in's continuous field at
    volume points (N, 3) (any positive scale), or None for a volume without one.
    sphere: inward radial; ml: the Marschner-Lobb signal's gradient."""
    from cube4.phantoms import ML_ALPHA, ML_FM, sphere_centre

    name = spec.split(":")[0]
    if name == "sphere":
        return np.asarray(sphere_centre(dims)) - pts
    if name == "ml":
        n = np.asarray(dims, dtype=np.float64)
        u = -1.0 + 2.0 * pts / (n - 1.0)
        x, y, z = u[:, 0], u[:, 1], u[:, 2]
        r = np.sqrt(x * x + y * y)
        a = 2.0 * (1.0 + ML_ALPHA)
        gz = -(np.pi / 2.0) * np.cos(np.pi * z / 2.0) / a
        dr = ML_ALPHA / a * 2.0 * np.pi * ML_FM * np.sin(2.0 * np.pi * ML_FM * np.cos(np.pi * r / 2.0)) \
            * np.sin(np.pi * r / 2.0) * (np.pi / 2.0)
        rr = np.where(r > 0, r, 1.0)
        g = np.stack([dr * x / rr, dr * y / rr, gz], axis=-1) * (2.0 / (n - 1.0))
        return g
    return None


def truth_image(vol: np.ndarray, spec: str, scene, cfg) -> np.ndarray:
    """The float64 reference with the analytic normal in place of the central
    difference (sphere: only where the reference's gradient is not flat, so the flat
    interior stays flat; ml: everywhere)."""
    from cube4 import reference as R
    from cube4.app.render import render

    nz, ny, nx = vol.shape
    dims = (nx, ny, nz)
    orig = R._trilinear

    def patched(grid, pts):
        vals = orig(grid, pts)
        if grid.shape[-1] == 4:
            g = analytic_gradient(spec, dims, pts)
            mag = np.linalg.norm(vals[:, 1:4], axis=1)
            gn = np.linalg.norm(g, axis=1)
            scale = np.where(gn > 0, (mag if spec.startswith("sphere") else 1.0) / np.maximum(gn, 1e-30), 0.0)
            vals = vals.copy()
            vals[:, 1:4] = g * scale[:, None]
        return vals

    R._trilinear = patched
    try:
        return render(vol, scene, cfg, "reference").image
    finally:
        R._trilinear = orig


PSNR_CASES = (("sphere:64", "default"), ("head:64", "head"), ("ml:41", "ml"))


def psnr_table(estimators, cases=PSNR_CASES, supersamples=SUPERSAMPLES, log=None) -> list[dict]:
    """PSNR of each estimator's golden image against the float64 reference, per scene
    and S; also the shipped golden engine (``golden``) as a check."""
    from dataclasses import replace

    from cube4.app.render import render
    from cube4.app.volumes import load_volume
    from cube4.host import config_for, image_metrics
    from cube4.scene import load_scene

    rows = []
    for spec, scene_name in cases:
        vol = load_volume(spec)
        scene0 = load_scene(scene_name)
        ref = None
        for S in supersamples:
            scene = replace(scene0, supersample=S)
            cfg = config_for(scene)
            if ref is None:
                ref = render(vol, scene, cfg, "reference").image
                truth = truth_image(vol, spec, scene, cfg) if analytic_gradient(spec, (2, 2, 2), np.zeros((1, 3))) is not None else None
            for name in estimators:
                if name == "golden":
                    img = render(vol, scene, cfg, "golden").image
                else:
                    img = render_image(vol, scene, cfg, name)
                met = image_metrics(img, ref)
                row = {"volume": spec, "scene": scene_name, "S": S, "estimator": name, **met}
                if truth is not None:
                    row["psnr_truth"] = image_metrics(img, truth)["psnr"]
                rows.append(row)
                if log:
                    log(row)
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description="angle error of gradient estimators on the analytic sphere")
    ap.add_argument("--est", default=",".join(ESTIMATORS))
    ap.add_argument("--S", default="1,2,4,8")
    ap.add_argument("--views", default=None, help="semicolon-separated x,y,z")
    ap.add_argument("--json", default=None)
    ap.add_argument("--psnr", action="store_true", help="PSNR against the reference on sphere/head/ml instead")
    a = ap.parse_args(argv)
    ests = a.est.split(",")
    Ss = tuple(int(s) for s in a.S.split(","))
    views = VIEWS if a.views is None else tuple(tuple(float(c) for c in v.split(",")) for v in a.views.split(";"))

    if a.psnr:
        rows = psnr_table(ests, supersamples=Ss, log=lambda r: print(
            f"{r['scene']:8s} S={r['S']} {r['estimator']:10s} psnr={r['psnr']:6.2f} rmse={r['rmse']:.5f}"
            f" truth={r.get('psnr_truth', float('nan')):6.2f}", flush=True))
        if a.json:
            import json
            with open(a.json, "w") as f:
                json.dump(rows, f, indent=1)
        return 0

    def log(r):
        print(f"{r['estimator']:10s} view={str(r['view']):22s} S={r['S']} mean={r['mean']:6.2f} "
              f"max={r['max']:6.2f} n={r['n']} |g|max={r['absmax']}", flush=True)

    rows = angle_table(ests, views, Ss, log=log)
    if a.json:
        import json
        with open(a.json, "w") as f:
            json.dump(rows, f, indent=1)
    print("\nmean angle (deg) over views, per S:")
    for e in ests:
        sel = [r for r in rows if r["estimator"] == e]
        per_s = [np.mean([r["mean"] for r in sel if r["S"] == S]) for S in Ss]
        print(f"{e:10s} " + " ".join(f"{v:6.2f}" for v in per_s) + f"   all {np.mean([r['mean'] for r in sel]):6.2f}"
              f"   worst view/S {max(r['mean'] for r in sel):6.2f}  max {max(r['max'] for r in sel):6.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

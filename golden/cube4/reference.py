"""The float64 reference renderer: the "true" picture that error is measured against.

A pixel of the image is the average of the picture over the pixel's square (a box
filter), not the picture at its centre: ``render_reference(samples=k)`` casts k x k rays
per pixel on a regular grid over its square and averages their premultiplied RGBA, and
``converged_reference`` raises k (1, 3, 9: each grid holds the one before it) where the
picture is not flat until the change the next k would make (RMS over premultiplied
RGBA, estimated on a sample of pixels) is at most ``TRUTH_TOL``. ``samples=1`` is the
point-sampled picture, one ray through each pixel's centre (docs/numerics.md section 10,
"the area truth").

Parallel projection straight into the final image plane (``view.Camera``), the exact
(unquantised) view direction, the same voxels, transfer function and lights as the
hardware, and fine sampling (step ``h`` <= 1/8 voxel) with the opacity corrected for
it. Conventions shared with the hardware (docs/numerics.md §9):

* the field is the tri-linear interpolant of the voxels, zero outside the grid; rays
  are clipped to the box [0, n-1]^3 spanned by the voxel centres;
* the gradient is the central difference of that field with a step of one voxel (which
  equals the tri-linear interpolant of the voxel central differences);
* the transfer function's alpha is per voxel of distance: alpha_h = 1 - (1 - alpha)^(w h);
* the midpoint rule along the ray: samples at t_in + q h, q = 0 .. n - 1, each standing
  for the stretch of its ray within h/2 of it clipped to [t_in, t_out], so w = 1 but for
  the first sample (w = 1/2) and the last (w = 1/2 + (t_out - t_last) / h; a ray of one
  sample: its length / h). The ray's path length is exact, and the error is O(h^2);
* Phong: colour = min(1, C * D + P) with D, P from ``tables.phong_terms``;
* front-to-back compositing of premultiplied colour, no early termination beyond a
  transmittance of 1e-7;
* the modes of numerics.md §13: X-ray sums the step opacities (and colours) without
  occlusion, each clamped to 1; MIP / MinIP take the extreme field value along the ray
  and classify it (colour premultiplied by opacity); unshaded compositing uses the
  transfer function's colour as it is;
* a crop box is rendered as a volume of its own placed at its origin (zero outside
  it, like the volume's own faces), and crop regions keep the samples in the regions
  their flags keep (cube4.clip; the whole volume traversed); a cut plane removes the samples p with
  normal . (p - point) > 0; a slab keeps the p with |normal . (p - center)| <= t / 2, and
  its falloff multiplies the opacity of one hardware sample (a stretch of the ray as long
  as the hardware's sample distance d, 1 / (S max |d_axis|) voxel) by
  w = clamp(inset / F, 0, 1), inset the distance inside the nearer face:
  alpha_h = 1 - (1 - w (1 - (1 - alpha)^d))^(w_q h / d);
* a labelled volume (its memory words, cube4.labels) is classified by the scene's
  [labels] resample rule: nearest (the hardware's), masked or blended (docs/numerics.md
  §24); the gradient is the values' as ever.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from .modes import is_extremum
from .progress import Progress
from .scene import Scene
from .gmod import eval_points
from .labels import label_tf, split_words
from .tables import phong_terms, unshaded_terms
from .view import Camera, Traversal


def _padded_grids(vol: np.ndarray, voxel_bits: int) -> np.ndarray:
    """(nz+2, ny+2, nx+2, 4) float64 on the grid padded by one zero voxel all round:
    the value in [0, 1] and its central differences / 2 (d/dx, d/dy, d/dz)."""
    v = vol.astype(np.float64) / float((1 << voxel_bits) - 1)
    p2 = np.pad(v, 2)
    c = (slice(1, -1),) * 3
    gx = (p2[1:-1, 1:-1, 2:] - p2[1:-1, 1:-1, :-2]) / 2.0
    gy = (p2[1:-1, 2:, 1:-1] - p2[1:-1, :-2, 1:-1]) / 2.0
    gz = (p2[2:, 1:-1, 1:-1] - p2[:-2, 1:-1, 1:-1]) / 2.0
    return np.stack([p2[c], gx, gy, gz], axis=-1)


def _trilinear(grid: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """Interpolate the padded (nz+2, ny+2, nx+2, C) grid at volume points (N, 3) = (x, y, z)
    lying in [0, n-1]; returns (N, C). The eight corners are gathered by one flat index
    each (a third of the time of indexing the 4-D grid with three arrays; same values)."""
    q = pts + 1.0  # padding offset
    i0 = np.floor(q).astype(np.int64)
    nz, ny, nx, nc = grid.shape
    i0[:, 0] = np.clip(i0[:, 0], 0, nx - 2)
    i0[:, 1] = np.clip(i0[:, 1], 0, ny - 2)
    i0[:, 2] = np.clip(i0[:, 2], 0, nz - 2)
    f = q - i0
    flat = grid.reshape(-1, nc)
    base = (i0[:, 2] * ny + i0[:, 1]) * nx + i0[:, 0]
    sy, sz = nx, ny * nx

    def at(offset: int) -> np.ndarray:
        return flat.take(base + offset, axis=0)

    fx, fy, fz = f[:, 0:1], f[:, 1:2], f[:, 2:3]
    gx, gy, gz = 1 - fx, 1 - fy, 1 - fz
    c00 = at(0) * gx + at(1) * fx
    c01 = at(sy) * gx + at(sy + 1) * fx
    c10 = at(sz) * gx + at(sz + 1) * fx
    c11 = at(sz + sy) * gx + at(sz + sy + 1) * fx
    c0 = c00 * gy + c01 * fy
    c1 = c10 * gy + c11 * fy
    return c0 * gz + c1 * fz


def _cell_corners(shape, pts: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The eight corners of each point's cell in a padded (nz+2, ny+2, nx+2) grid, as
    _trilinear reads them: flat indices (N, 8), their tri-linear weights (N, 8), and the
    corner nearest each point (N,) (per axis the upper one where the fraction is at least
    1/2, as the hardware picks a label). Corner c = 4 dz + 2 dy + dx."""
    nz, ny, nx = shape
    q = pts + 1.0
    i0 = np.floor(q).astype(np.int64)
    i0[:, 0] = np.clip(i0[:, 0], 0, nx - 2)
    i0[:, 1] = np.clip(i0[:, 1], 0, ny - 2)
    i0[:, 2] = np.clip(i0[:, 2], 0, nz - 2)
    f = q - i0
    base = (i0[:, 2] * ny + i0[:, 1]) * nx + i0[:, 0]
    idx, wts = [], []
    for dz in (0, 1):
        for dy in (0, 1):
            for dx in (0, 1):
                idx.append(base + (dz * ny + dy) * nx + dx)
                wts.append((f[:, 0] if dx else 1 - f[:, 0]) * (f[:, 1] if dy else 1 - f[:, 1])
                           * (f[:, 2] if dz else 1 - f[:, 2]))
    near = 4 * (f[:, 2] >= 0.5) + 2 * (f[:, 1] >= 0.5) + (f[:, 0] >= 0.5)
    return np.stack(idx, axis=1), np.stack(wts, axis=1), near.astype(np.int64)


def _per_label(scene: Scene, lab: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Each point's classification by its own label's transfer function: (N, 4)."""
    out = np.zeros((v.size, 4))
    for lb in np.unique(lab):
        sel = lab == lb
        out[sel] = label_tf(scene, int(lb), v[sel])
    return out


def _label_classify(scene: Scene, grid: np.ndarray, labs: np.ndarray, pts: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The classification (N, 4) RGBA (colour not premultiplied, alpha per voxel) of points
    of a labelled volume by the scene's [labels] resample (cube4.labels): ``grid`` the
    padded value grid (_padded_grids), ``labs`` the labels padded alike, ``v`` the value
    interpolated from all eight corners."""
    idx, w, near = _cell_corners(labs.shape, pts)
    lab_c = labs.reshape(-1)[idx]
    rule = scene.labels.resample
    if rule == "blended":       # each label's classification, weighted by its corners' weights
        acc = np.zeros((v.size, 4))
        for lb in np.unique(lab_c):
            wl = (w * (lab_c == lb)).sum(axis=1)
            rgba = label_tf(scene, int(lb), v)
            a = np.clip(rgba[:, 3], 0.0, 1.0) * wl
            acc[:, :3] += a[:, None] * rgba[:, :3]
            acc[:, 3] += a
        acc[:, :3] /= np.where(acc[:, 3] > 0, acc[:, 3], 1.0)[:, None]
        return acc
    lab = np.take_along_axis(lab_c, near[:, None], axis=1)[:, 0]
    if rule == "masked":        # ULTRAVIS: the corners of other labels count as zero
        vals_c = grid[..., 0].reshape(-1)[idx]
        v = (w * vals_c * (lab_c == lab[:, None])).sum(axis=1)
    return _per_label(scene, lab, v)


def _box_interval(origins: np.ndarray, d: np.ndarray, dims) -> tuple[np.ndarray, np.ndarray]:
    """Slab clipping of rays o + t d against [0, n-1]^3: (t_enter, t_exit)."""
    hi = np.asarray(dims, dtype=np.float64) - 1.0
    t0 = np.full(len(origins), -np.inf)
    t1 = np.full(len(origins), np.inf)
    for ax in range(3):
        if abs(d[ax]) < 1e-15:
            outside = (origins[:, ax] < 0) | (origins[:, ax] > hi[ax])
            t0[outside], t1[outside] = np.inf, -np.inf
            continue
        a = (0.0 - origins[:, ax]) / d[ax]
        b = (hi[ax] - origins[:, ax]) / d[ax]
        t0 = np.maximum(t0, np.minimum(a, b))
        t1 = np.minimum(t1, np.maximum(a, b))
    return t0, t1


#: The area truth's tolerance: k is raised until the image's RMS change (premultiplied
#: RGBA, peak 1) from the last k is at most this (2^-9: 54.2 dB as a PSNR).
TRUTH_TOL = 2.0 ** -9
#: The largest k the area truth casts for every refined pixel (9 x 9 = 81 rays).
TRUTH_K_MAX = 9
#: Refined pixels on which the change to the next k is estimated (the convergence test).
TRUTH_SAMPLE = 2048
#: The ks it tries: a 3k x 3k grid holds the k x k one, so every ray is reused.
TRUTH_KS = (1, 3, 9, 27)
#: A pixel is refined to the next k when the picture is not flat across it: its rays
#: (k > 1), or at k = 1 the second differences of the centre samples around it, differ
#: by more than this in some channel; also its 8 neighbours (a feature between rays).
TRUTH_EPS = 2.0 ** -8


def subpixel_offsets(k: int) -> np.ndarray:
    """The k x k positions of the box filter's rays in a pixel, (k*k, 2) as (dx, dy) in
    pixels from its centre (dy down the image): (i + 1/2) / k - 1/2 on each axis."""
    if k < 1:
        raise ValueError("samples per pixel side must be at least 1")
    t = (np.arange(k) + 0.5) / k - 0.5
    dy, dx = np.meshgrid(t, t, indexing="ij")
    return np.stack([dx.ravel(), dy.ravel()], axis=1)


def render_reference(
    vol: np.ndarray,
    voxel_bits: int,
    scene: Scene,
    cam: Camera,
    step: float = 0.125,
    progress: Progress | None = None,
    box=None,
    samples: int = 1,
) -> np.ndarray:
    """Render vol[z, y, x] into the image plane: (H, W, 4) premultiplied RGBA float64,
    each pixel the mean of samples x samples rays over its square (1: its centre).
    box = (origin, dims) of a crop box (scene.crop_box), None for the whole volume."""
    pix = np.arange(cam.height * cam.width)
    rays = _cast_pixels(vol, voxel_bits, scene, cam, step, progress, box, pix, subpixel_offsets(samples))
    return rays.mean(axis=0).reshape(cam.height, cam.width, 4)


#: rays cast by one call of cast_rays (memory against the per-step overhead of many calls)
_RAYS_PER_CAST = 1 << 19


def _cast_pixels(vol, voxel_bits, scene, cam, step, progress, box, pix, offsets) -> np.ndarray:
    """The rays of the pixels pix (flat indices) at these sub-pixel offsets:
    (len(offsets), len(pix), 4) premultiplied RGBA."""
    origins, d = cam.ray_origins()
    origins = origins[pix]
    if box is not None:
        (x0, y0, z0), (nx, ny, nz) = box
        vol = vol[z0:z0 + nz, y0:y0 + ny, x0:x0 + nx]
        origins = origins - np.asarray([x0, y0, z0], dtype=np.float64)
    n = origins.shape[0]
    out = np.zeros((len(offsets), n, 4))
    per_cast = max(1, _RAYS_PER_CAST // max(n, 1))      # offsets cast together
    for b in range(0, len(offsets), per_cast):
        shifts = [cam.pixel * (float(dx) * cam.right - float(dy) * cam.up) for dx, dy in offsets[b:b + per_cast]]
        pts = np.concatenate([origins + sh for sh in shifts])
        z_stop = None
        if scene.geometry is not None:      # depth in: each ray ends at its pixel's geometry (cube4.geometry)
            z_stop = np.tile(scene.geometry.z.ravel()[pix], len(shifts))
        rgba = cast_rays(vol, voxel_bits, scene, pts, d, step, progress, offset=None if box is None else box[0],
                         z_stop=z_stop, centre=cam.centre)
        out[b:b + len(shifts)] = rgba.reshape(len(shifts), n, 4)
    return out


@dataclass(frozen=True)
class Convergence:
    """How the area truth converged: per k cast, the fraction of the pixels cast at it,
    the image's RMS change from the k before it (None for k = 1) and the RMS change the
    next k would make, estimated on a sample of the refined pixels (None where not
    estimated); whether the last estimate met the tolerance."""

    steps: tuple[tuple[int, float, float | None, float | None], ...]
    tol: float
    converged: bool
    sample: int = 0             # refined pixels the estimate cast at the next k

    @property
    def k(self) -> int:
        return self.steps[-1][0]

    @property
    def change(self) -> float | None:
        """The accuracy claim: the estimated RMS change to the next k, else the last change."""
        last = self.steps[-1]
        return last[3] if last[3] is not None else last[2]

    def text(self) -> str:
        """One line: each step's k, fraction of pixels, change from the last k and to the next."""
        parts = []
        for k, f, c, nxt in self.steps:
            t = f"k={k}: {100 * f:.1f}% of pixels"
            t += "" if c is None else f", RMS change {c:.2e}"
            t += "" if nxt is None else f", to k={3 * k} {nxt:.2e} (estimated on {self.sample} pixels)"
            parts.append(t)
        return "; ".join(parts) + ("" if self.converged else f" (not converged to {self.tol:.2e})")


def _dilate(mask: np.ndarray) -> np.ndarray:
    """mask or any of its 8 neighbours."""
    p = np.pad(mask, 1)
    h, w = mask.shape
    out = np.zeros_like(mask)
    for dy in (0, 1, 2):
        for dx in (0, 1, 2):
            out |= p[dy:dy + h, dx:dx + w]
    return out


def _not_flat(img: np.ndarray, eps: float) -> np.ndarray:
    """(H, W) pixels where a second difference of the point image (along rows, columns
    and both diagonals, any channel) exceeds eps: where it is not locally linear."""
    p = np.pad(img, ((1, 1), (1, 1), (0, 0)), mode="edge")
    c = p[1:-1, 1:-1]
    worst = np.zeros(img.shape[:2])
    for (ay, ax), (by, bx) in (((0, 1), (2, 1)), ((1, 0), (1, 2)), ((0, 0), (2, 2)), ((0, 2), (2, 0))):
        h, w = img.shape[:2]
        dd = p[ay:ay + h, ax:ax + w] + p[by:by + h, bx:bx + w] - 2.0 * c
        worst = np.maximum(worst, np.abs(dd).max(axis=-1))
    return worst > eps


def converged_reference(
    vol: np.ndarray,
    voxel_bits: int,
    scene: Scene,
    cam: Camera,
    step: float = 0.125,
    progress: Progress | None = None,
    box=None,
    tol: float = TRUTH_TOL,
    k_max: int = TRUTH_K_MAX,
    eps: float = TRUTH_EPS,
    sample: int = TRUTH_SAMPLE,
) -> tuple[np.ndarray, Convergence]:
    """The area truth, k x k rays per pixel with k = 1, 3, 9 (at most k_max), each grid
    holding the one before it. Only pixels where the picture is not flat are refined
    (TRUTH_EPS: a flat pixel's mean is its centre's, or its rays' common value). After
    each k > 1 the RMS change that k -> 3k would make is estimated on ``sample`` of the
    refined pixels (seeded, uniform; the rest of the image counted at that mean); the image
    is accepted when the estimate is at most tol, else 3k is cast for every refined pixel.
    Returns the image and how it got there (``converged`` False when k_max stopped it)."""
    if k_max not in TRUTH_KS[1:]:
        raise ValueError(f"k_max must be one of {TRUTH_KS[1:]}")
    h, w = cam.height, cam.width
    npix = h * w
    cast = functools.partial(_cast_pixels, vol, voxel_bits, scene, cam, step, progress, box)
    first = cast(np.arange(npix), subpixel_offsets(1))[0]
    total, count = first.copy(), np.ones(npix)
    lo, hi = first.copy(), first.copy()
    img = first.reshape(h, w, 4)
    refine = _dilate(_not_flat(img, eps)).ravel()
    steps: list[tuple[int, float, float | None, float | None]] = [(1, 1.0, None, None)]
    rng = np.random.default_rng(0)
    k, est, used = 1, None, 0
    while k < k_max:
        k3 = 3 * k
        new = _new_offsets(k, k3)
        pix = np.nonzero(refine)[0]
        if pix.size:
            rays = cast(pix, new)
            total[pix] += rays.sum(axis=0)
            count[pix] += len(new)
            lo[pix] = np.minimum(lo[pix], rays.min(axis=0))
            hi[pix] = np.maximum(hi[pix], rays.max(axis=0))
        nxt = (total / count[:, None]).reshape(h, w, 4)
        change = float(np.sqrt(np.mean((nxt - img) ** 2)))
        img, k = nxt, k3
        refine = _dilate(((hi - lo).max(axis=-1) > eps).reshape(h, w)).ravel() & refine
        est, used = None, 0
        if k < TRUTH_KS[-1]:
            est, used = _estimate_next(cast, total, count, refine, k, sample, rng, npix)
        steps.append((k, pix.size / npix, change, est))
        if est is not None and est <= tol:
            break
    ok = est is not None and est <= tol
    return img, Convergence(tuple(steps), tol, ok, used)


def _new_offsets(k: int, k3: int) -> np.ndarray:
    """The offsets of the k3 grid that the k grid does not hold."""
    old = {_key(o) for o in subpixel_offsets(k)}
    return np.array([o for o in subpixel_offsets(k3) if _key(o) not in old]).reshape(-1, 2)


def _estimate_next(cast, total, count, refine, k, sample, rng, npix) -> tuple[float, int]:
    """The RMS change over the image that k -> 3k would make, from a uniform sample of the
    refined pixels (the others do not change): (estimate, pixels sampled)."""
    pix = np.nonzero(refine)[0]
    if pix.size == 0:
        return 0.0, 0
    pick = pix if pix.size <= sample else np.sort(rng.choice(pix, size=sample, replace=False))
    new = _new_offsets(k, 3 * k)
    rays = cast(pick, new)
    now = total[pick] / count[pick][:, None]
    then = (total[pick] + rays.sum(axis=0)) / (count[pick] + len(new))[:, None]
    mean_sq = float(np.mean((then - now) ** 2, axis=None))        # per value of a sampled pixel
    return float(np.sqrt(mean_sq * pix.size / npix)), int(pick.size)


def _key(o) -> tuple[float, float]:
    """A sub-pixel offset as a key that equal positions of two grids share."""
    return (round(float(o[0]), 9), round(float(o[1]), 9))


def reference_baseplane(
    vol: np.ndarray,
    voxel_bits: int,
    scene: Scene,
    trav: Traversal,
    step: float = 0.125,
    progress: Progress | None = None,
) -> np.ndarray:
    """The reference on the hardware's base-plane grid: for every base-plane pixel one ray
    along the exact view direction through the point where the pixel's (quantised)
    ray is at mid depth. (rows, cols, 4) premultiplied RGBA float64. Compared with the
    golden base plane it measures the datapath's numerics alone, without the warp's
    resampling (docs/numerics.md section 11)."""
    rows, cols = trav.baseplane_shape
    by, bx = np.mgrid[0:rows, 0:cols]
    origins = trav.baseplane_to_volume(bx.ravel(), by.ravel())
    d = np.asarray(scene.direction, dtype=np.float64)
    d = d / np.linalg.norm(d)
    (x0, y0, z0), (nx, ny, nz) = trav.origin, trav.dims
    vol = vol[z0:z0 + nz, y0:y0 + ny, x0:x0 + nx]
    origins = origins - np.asarray(trav.origin, dtype=np.float64)
    img = cast_rays(vol, voxel_bits, scene, origins, d, step, progress, offset=trav.origin)
    return img.reshape(rows, cols, 4)


def _midpoint_weights(q: int, n: np.ndarray, length: np.ndarray, step: float) -> np.ndarray:
    """The midpoint rule's weight of sample q of rays of n samples and these lengths
    (in steps): 1/2 for the first, 1/2 + the tail for the last, their sum for a ray of
    one sample (its length), 1 in between."""
    tail = (length - (n - 1) * step) / step          # in [0, 1)
    w = np.ones(n.shape)
    last = q == n - 1
    if q == 0:
        return np.where(last, tail, 0.5)
    return np.where(last, tail + 0.5, w)


def _region_kept(pts: np.ndarray, box, flags: int) -> np.ndarray:
    """The points (N, 3) of the whole volume's coordinates that the crop regions keep:
    region 0 / 1 / 2 along an axis below / within / above the box [lo, hi] (inclusive),
    VTK's flag bit rx + 3 ry + 9 rz."""
    lo, hi = (np.asarray(b, dtype=np.float64) for b in box)
    r = np.where(pts < lo, 0, np.where(pts > hi, 2, 1))
    idx = r[:, 0] + 3 * r[:, 1] + 9 * r[:, 2]
    return ((int(flags) >> idx) & 1).astype(bool)


def cast_rays(
    vol: np.ndarray,
    voxel_bits: int,
    scene: Scene,
    origins: np.ndarray,
    d: np.ndarray,
    step: float = 0.125,
    progress: Progress | None = None,
    offset=None,
    z_stop: np.ndarray | None = None,
    centre=None,
) -> np.ndarray:
    """Composite the rays o + t d (origins (N, 3) in volume coordinates, one unit
    direction d) front to back through vol[z, y, x]: (N, 4) premultiplied RGBA, in the
    scene's mode. offset: where vol's voxel (0, 0, 0) lies in the whole volume (a crop
    box), for the cut plane. z_stop (N,): depth in, a ray counts its points whose depth
    along d from ``centre`` (the whole volume's coordinates) is below it."""
    if not 0 < step <= 0.125:
        raise ValueError("reference step must be in (0, 1/8] voxel")
    nz, ny, nx = vol.shape
    labs = None
    if scene.labels is not None:        # vol holds labelled words (cube4.labels)
        vol, labs = split_words(vol, voxel_bits)
        labs = np.pad(labs, 1)
    grid = _padded_grids(vol, voxel_bits)
    t_in, t_out = _box_interval(origins, d, (nx, ny, nz))
    hit = np.nonzero(t_out >= t_in)[0]
    n_rays = origins.shape[0]
    color = np.zeros((n_rays, 3))
    trans = np.ones(n_rays)
    lights = [lt.direction for lt in scene.lights]
    eye = -d
    d0, p0 = unshaded_terms(scene)
    n_steps = np.floor((t_out[hit] - t_in[hit]) / step).astype(np.int64) + 1
    active = hit
    q = 0
    total = int(n_steps.max()) if hit.size else 0
    steps_of = np.zeros(n_rays, dtype=np.int64)
    steps_of[hit] = n_steps
    length = np.zeros(n_rays)
    length[hit] = t_out[hit] - t_in[hit]
    mode = scene.mode
    shaded = scene.shaded
    extreme = is_extremum(mode)
    value = np.full(n_rays, np.inf if mode == "minip" else -np.inf)
    asum = np.zeros(n_rays)
    if scene.cut is not None:
        cut_n, cut_p = scene.cut
        cut_p = cut_p - (np.zeros(3) if offset is None else np.asarray(offset, dtype=np.float64))
    shift = np.zeros(3) if offset is None else np.asarray(offset, dtype=np.float64)
    if scene.slab is not None:
        slab_n, slab_c, slab_t, slab_f = scene.slab
        slab_c = slab_c - shift
        # the hardware's sample distance: slices 1/S voxel apart along the major axis
        d_hw = 1.0 / (scene.supersample * float(np.max(np.abs(d))))
    while active.size:
        pts = origins[active] + (t_in[active] + q * step)[:, None] * d
        vals = _trilinear(grid, pts)
        counts = np.ones(active.size, dtype=bool)
        fall = None
        if scene.cut is not None:
            counts = (pts - cut_p) @ cut_n <= 0.0
        if scene.slab is not None:
            inset = 0.5 * slab_t - np.abs((pts - slab_c) @ slab_n)   # voxels inside the nearer face
            counts = inset >= 0.0
            if slab_f > 0:
                fall = np.clip(inset / slab_f, 0.0, 1.0)
        if z_stop is not None:
            counts &= (pts + shift - centre) @ d < z_stop[active]
        if scene.crop_regions is not None:
            counts &= _region_kept(pts + (0.0 if offset is None else np.asarray(offset, dtype=np.float64)),
                                   scene.crop, scene.crop_regions)
        if extreme:
            v = np.where(counts, vals[:, 0], value[active])
            value[active] = np.minimum(value[active], v) if mode == "minip" else np.maximum(value[active], v)
        else:
            rgba = scene.tf(vals[:, 0]) if labs is None else _label_classify(scene, grid, labs, pts, vals[:, 0])
            wq = _midpoint_weights(q, steps_of[active], length[active], step)
            a = np.clip(rgba[:, 3], 0.0, 1.0)
            if shaded:
                g = vals[:, 1:4]
                gn = np.linalg.norm(g, axis=1)
                if scene.gmod is not None:     # gradient-magnitude modulation at the exact |grad f|
                    a = a * eval_points(scene.gmod[0], gn)
            if fall is None:
                alpha = np.where(counts, 1.0 - np.power(1.0 - a, step * wq), 0.0)
            else:       # the falloff scales the opacity of one hardware sample (d_hw long)
                a_hw = fall * (1.0 - np.power(1.0 - a, d_hw))
                alpha = np.where(counts, 1.0 - np.power(1.0 - a_hw, step * wq / d_hw), 0.0)
            if shaded:
                flat = gn < 1e-12
                normals = -g / np.where(flat, 1.0, gn)[:, None]
                dd, pp = phong_terms(scene, normals, lights, eye)
                dd = np.where(flat, d0, dd)
                pp = np.where(flat, p0, pp)
                if scene.gmod is not None:     # the lighting towards unshaded as the factor falls
                    fs = eval_points(scene.gmod[1], gn)
                    dd, pp = 1.0 + fs * (dd - 1.0), fs * pp
                c = np.minimum(1.0, rgba[:, :3] * dd[:, None] + pp[:, None])
            else:
                c = rgba[:, :3]
            if mode == "xray":
                color[active] += alpha[:, None] * c
                asum[active] += alpha
            else:
                w = trans[active] * alpha
                color[active] += w[:, None] * c
                trans[active] -= w
        q += 1
        if progress is not None:
            progress("reference", q, total)
        keep = q < steps_of[active]
        if mode == "composite":
            keep &= trans[active] > 1e-7
        active = active[keep]
    if progress is not None:
        progress("reference", total, total)
    if extreme:
        out = np.zeros((n_rays, 4))
        seen = np.isfinite(value)
        rgba = scene.tf(value[seen])
        a = np.clip(rgba[:, 3], 0.0, 1.0)
        out[seen, :3] = rgba[:, :3] * a[:, None]
        out[seen, 3] = a
        return out
    if mode == "xray":
        return np.concatenate([np.minimum(1.0, color), np.minimum(1.0, asum)[:, None]], axis=1)
    return np.concatenate([color, (1.0 - trans)[:, None]], axis=1)

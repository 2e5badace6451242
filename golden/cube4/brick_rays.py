"""The rays of a whole render cut at brick boundaries (numerics.md §14): from the streams
of a monolithic frame (``render_frame(..., keep_streams=True)``) and a brick plan,

* ``composite_bound``: per base-plane pixel and channel, the bound of §14.3 on
  |bricked composite - monolithic| in LSBs of Q0.ACC_W, computed from the samples the
  ray counts and the bricks it crosses;
* ``brick_partials``: every brick's partial base plane re-composited from the whole
  render's samples by the design's rule (front to back, Q0.F; equal to the bricks'
  own renders, which is tested) or by seed 004's 8-bit framebuffer (back to front,
  premultiplied, truncating; ``FB8``), and ``composite_framebuffers`` for the latter's
  final blend of the node images.

Every sample of a ray is visited in slice order m (back to front: reverse order); a ray
has at most one sample per slice, so each slice is one vectorised step.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .bricks import Brick, BrickGrid, owner_maps
from .config import COLOR_W
from .fixed import round_shift
from .model import Frame

FB_MAX = 255  # an 8-bit framebuffer channel


def _slice_samples(frame: Frame, owner, m: int):
    """The counted samples of slice m: flat base-plane pixel, owning brick, A', C' (3, n)."""
    st, trav = frame.streams, frame.trav
    count = st["inside"][m] & st["keep"][m] if "keep" in st else st["inside"][m]
    jj, ii = np.nonzero(count)
    sx, sy = (int(v) for v in trav.steps(m))
    sxm, sym = trav.max_steps
    cols = trav.baseplane_shape[1]
    pix = (jj + sym - sy) * cols + (ii + sxm - sx)
    own = owner(m)[jj, ii]
    sh = st["shaded"][m]
    return pix, own, sh[3, jj, ii].astype(np.int64), sh[:3, jj, ii].astype(np.int64)


def _need_streams(frame: Frame) -> None:
    if not frame.streams or "shaded" not in frame.streams:
        raise ValueError("the monolithic frame must be rendered with keep_streams=True")


def composite_bound(frame: Frame, grid: BrickGrid, bricks: Sequence[Brick]) -> dict:
    """The §14.3 bound per base-plane pixel: {"a": (rows, cols), "rgb": (rows, cols, 3),
    "segments": (rows, cols) int, the bricks with a counted sample on the ray (r)}.

    With the ray's samples split into segments b = 1..r (one per brick, in ray order),
    a_s = A'/2^AW, c_s = C'/2^8, tau the monolithic transmittance and Z the exact product
    of the bricks' partial transmittances at each segment's start:

        |dA| <= (r - 1)/2 + sum_{b>=2} (1 + tau_{b-1}/2^F) K_b / 2
        |dC| <= r(r - 1)/4 + sum_{b>=2} [ D_{b-1} chi_b + (1 + Z_{b-1}/2^F) J_b / 2 ]

    K_b = sum_s prod_{l>s}(1 - a_l), J_b = sum_s [c_s (a_s K'_s + 1) + 1] (K'_s: K of the
    samples before s), chi_b = sum_s a_s c_s prod_{l<s}(1 - a_l), D_{b-1} the A bound's
    sum up to segment b - 1; sums and products over the segment's samples."""
    _need_streams(frame)
    trav, cfg = frame.trav, frame.cfg
    one = 1 << cfg.acc_bits
    rows, cols = trav.baseplane_shape
    n = rows * cols
    owner = owner_maps(trav, grid, bricks)
    cur = np.full(n, -1, dtype=np.int64)
    r = np.zeros(n, dtype=np.int64)
    tau = np.full(n, one, dtype=np.int64)          # the monolithic T (integer, exact)
    useg = np.full(n, one, dtype=np.int64)         # the segment's own T from 2^F (a brick's partial)
    z = np.full(n, float(one))                     # exact product of closed partials' T, times 2^F
    k = np.zeros(n)
    j = np.zeros((3, n))
    chi = np.zeros((3, n))
    g = np.ones(n)
    lam = np.zeros(n)
    zeta = np.zeros(n)
    dstart = np.zeros(n)
    d = np.zeros(n)
    bc = np.zeros((3, n))

    def close(p: np.ndarray) -> None:
        later = r[p] >= 2
        q = p[later]
        d[q] += (1.0 + lam[q]) * k[q] / 2.0
        bc[:, q] += dstart[q] * chi[:, q] + (1.0 + zeta[q]) * j[:, q] / 2.0
        z[p] *= useg[p] / float(one)

    def start(p: np.ndarray) -> None:
        r[p] += 1
        lam[p] = tau[p] / float(one)
        zeta[p] = z[p] / float(one)
        dstart[p] = d[p]
        k[p] = 0.0
        j[:, p] = 0.0
        chi[:, p] = 0.0
        g[p] = 1.0
        useg[p] = one

    for m in range(trav.num_sample_slices):
        pix, own, alpha, col = _slice_samples(frame, owner, m)
        if pix.size == 0:
            continue
        new = cur[pix] != own
        moved = pix[new & (cur[pix] >= 0)]
        if moved.size:
            close(moved)
        start(pix[new])
        cur[pix] = own
        a = alpha / float(1 << cfg.alpha_bits)
        c = col / float(1 << COLOR_W)
        kp = k[pix]
        j[:, pix] += c * (a * kp + 1.0) + 1.0
        chi[:, pix] += g[pix] * a * c
        k[pix] = kp * (1.0 - a) + 1.0
        g[pix] *= 1.0 - a
        tau[pix] -= round_shift(tau[pix] * alpha, cfg.alpha_bits)
        useg[pix] -= round_shift(useg[pix] * alpha, cfg.alpha_bits)
    open_ = np.nonzero(cur >= 0)[0]
    close(open_)
    rr = r.astype(np.float64)
    bound_a = np.where(r > 0, (rr - 1.0) / 2.0 + d, 0.0)
    bound_c = np.where(r > 0, rr * (rr - 1.0) / 4.0 + bc, 0.0)
    return {"a": bound_a.reshape(rows, cols), "rgb": np.moveaxis(bound_c, 0, -1).reshape(rows, cols, 3),
            "segments": r.reshape(rows, cols)}


def seam_lines(frame: Frame, grid: BrickGrid, bricks: Sequence[Brick]) -> np.ndarray:
    """(rows, cols) bool: the base-plane pixels whose ray meets a different set of bricks
    (with counted samples) than one of its four neighbours' rays: where one brick's
    partial image ends and another's begins, the lines along which seams show."""
    _need_streams(frame)
    trav = frame.trav
    rows, cols = trav.baseplane_shape
    owner = owner_maps(trav, grid, bricks)
    keys = np.random.default_rng(0).integers(1, 1 << 62, len(bricks), dtype=np.int64)
    cur = np.full(rows * cols, -1, dtype=np.int64)
    sig = np.zeros(rows * cols, dtype=np.int64)
    for m in range(trav.num_sample_slices):
        pix, own, _, _ = _slice_samples(frame, owner, m)
        new = cur[pix] != own
        sig[pix[new]] ^= keys[own[new]]     # a ray meets each brick in one run of samples
        cur[pix] = own
    sig = sig.reshape(rows, cols)
    out = np.zeros((rows, cols), dtype=bool)
    out[:, 1:] |= sig[:, 1:] != sig[:, :-1]
    out[:, :-1] |= sig[:, 1:] != sig[:, :-1]
    out[1:] |= sig[1:] != sig[:-1]
    out[:-1] |= sig[1:] != sig[:-1]
    return out & (sig != 0)


def brick_partials(frame: Frame, grid: BrickGrid, bricks: Sequence[Brick], rule: str = "design",
                   acc_bits: int | None = None) -> np.ndarray:
    """Every brick's partial base plane, in the whole base plane's coordinates,
    (len(bricks), rows, cols, 4) int64, from the whole render's counted samples:

    * ``design``: the design's compositing (numerics.md §7) in Q0.F, F = ``acc_bits``
      (default the frame's), front to back; R, G, B, A = 2^F - T;
    * ``fb8``: seed 004's 8-bit framebuffer, back to front (their eq. 1), premultiplied,
      every result truncated ("omit decimals"): the texture holds
      a8 = round(255 a) and p8 = floor(255 a c) (a = A'/2^AW, c = C'/2^8), and
      C_d = p8 + floor((255 - a8) C_d / 255), alpha_d = a8 + floor((255 - a8) alpha_d / 255).
    """
    _need_streams(frame)
    trav, cfg = frame.trav, frame.cfg
    rows, cols = trav.baseplane_shape
    n, nb = rows * cols, len(bricks)
    owner = owner_maps(trav, grid, bricks)
    order = range(trav.num_sample_slices)
    if rule == "design":
        f = cfg.acc_bits if acc_bits is None else acc_bits
        one = 1 << f
        acc = np.zeros((nb, 3, n), dtype=np.int64)
        trans = np.full((nb, n), one, dtype=np.int64)
        for m in order:
            pix, own, alpha, col = _slice_samples(frame, owner, m)
            w = round_shift(trans[own, pix] * alpha, cfg.alpha_bits)
            acc[own, :, pix] += round_shift(w[:, None] * col.T, COLOR_W)
            trans[own, pix] -= w
        out = np.empty((nb, 4, n), dtype=np.int64)
        out[:, :3] = acc
        out[:, 3] = one - trans
    elif rule == "fb8":
        fb = np.zeros((nb, 4, n), dtype=np.int64)
        for m in reversed(order):
            pix, own, alpha, col = _slice_samples(frame, owner, m)
            a = alpha / float(1 << cfg.alpha_bits)
            a8 = np.floor(a * FB_MAX + 0.5).astype(np.int64)
            p8 = np.floor(a[None] * (col / float(1 << COLOR_W)) * FB_MAX).astype(np.int64)
            src = np.concatenate([p8, a8[None]])  # (4, n)
            keep = FB_MAX - a8
            fb[own, :, pix] = src.T + (keep[:, None] * fb[own, :, pix]) // FB_MAX
        out = fb
    else:
        raise ValueError(f"rule must be 'design' or 'fb8', got {rule!r}")
    return np.moveaxis(out, 1, -1).reshape(nb, rows, cols, 4)


def composite_framebuffers(planes: np.ndarray) -> np.ndarray:
    """Seed 004's final blend: the node images (listed front to back), 8-bit premultiplied,
    blended back to front into one 8-bit framebuffer with eq. 1 (truncating)."""
    out = np.zeros(planes.shape[1:], dtype=np.int64)
    for img in planes[::-1]:
        out = img + ((FB_MAX - img[..., 3:4]) * out) // FB_MAX
    return out


def seed004_correction(alpha: float, colour: float, sr_old: float, estimated_error: float = 1.5 / FB_MAX):
    """Seed 004's Calculating_New_As_&_SR_Values: from the average opacity ``alpha`` and
    colour ``colour`` of the samples, the raised opacity As_new and the sample rate
    sr_new = sr_old log(1 - As) / log(1 - As_new) (their eq. 5), as written there
    (Estimated_Error between 1/255 and 2/255; the loop raises As*Cs in steps of 0.001
    until the truncated 8-bit product no longer loses colour). Returns (As_new, sr_new);
    both unchanged when the rule does not apply (sr_new >= sr_old)."""
    a, c = float(alpha), float(colour)
    if not (0.0 < a < 1.0 and c > 0.0):
        return a, sr_old
    ac = a * c
    for _ in range(100000):
        cd = math.floor(ac * FB_MAX) / (a * FB_MAX)
        if cd > c:
            break
        ac += 0.001
    a_new = min(ac / c + estimated_error, 1.0 - 1e-9)
    sr_new = sr_old
    root = 1.0 - 1.0 / (FB_MAX * c)
    if root < 0:          # colour below 1/255: no opacity of eq. 7 draws it
        return a, sr_old
    if a_new > 1.0 - math.sqrt(root):
        sr_new = sr_old * math.log(1.0 - a) / math.log(1.0 - a_new)
    if sr_new >= sr_old:
        return a, sr_old
    return a_new, sr_new

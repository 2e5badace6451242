"""The bit-exact Cube-4 model: the specification the RTL matches bit for bit.

Every step below is written down in ``docs/numerics.md`` (section numbers in the
comments); the RTL implements the same integer arithmetic. The model walks the volume
the way the hardware does -- sample slice by sample slice in the traversal frame
(``view.Traversal``) -- and is vectorised over each slice, so a 256^3 frame takes a
few seconds.

Streams (kept when ``keep_streams=True``), all indexed [m, j, i] in the traversal frame:

* ``samples``   tri-linear samples, unsigned VOXEL_W bits (with labels the word
  label · 2^V + value, the label the nearest corner's: numerics.md §24)
* ``inside``    the sample lies inside the volume and is composited (bool)
* ``gradients`` (gi, gj, gk), twice the central differences, signed, traversal frame
  (GRA, §5); with voxel gradients (§5b) the interpolated (g_x, g_y, g_z), volume frame
* ``rmap_index`` reflectance-map entry of the gradient direction
* ``shaded``    (R, G, B) Q0.8 and A Q0.ALPHA_W of the classified, shaded sample
* ``pixels``    finished rays in emission order: (m, by, bx, R, G, B, A) with colour and
  opacity in Q0.ACC_W (0 .. 2^ACC_W inclusive)
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .config import COLOR_W, RMAP_FRAC, Cube4Config
from .fixed import lerp, round_shift
from .gmod import gm_index, modulate
from .clip import FALL_ONE, FALL_SHIFT, Clip
from .modes import MODES, is_blend
from .pathlen import path_weighted, weight_quarters, weighted_alpha
from .progress import Progress, counted
from .slices import SliceRects
from .labels import nearest_pair, split_words
from .vgrad import unpack_words
from .view import Traversal

PIXEL_DTYPE = np.dtype(
    [("m", np.int32), ("by", np.int32), ("bx", np.int32),
     ("r", np.int64), ("g", np.int64), ("b", np.int64), ("a", np.int64),
     ("zp", np.int32), ("zf", np.int32)]   # depth out's slices (passed, first; -1: none or not tracked)
)


@dataclass
class Frame:
    """One rendered view: the base plane and (optionally) every stream."""

    trav: Traversal
    cfg: Cube4Config
    baseplane: np.ndarray  # (rows, cols, 4) int64: R, G, B, A in Q0.ACC_W, 0..2^ACC_W
    pixels: np.ndarray  # PIXEL_DTYPE, emission order
    streams: dict = field(default_factory=dict)
    # depth out (numerics.md §21), render_frame(depth_t=...): (rows, cols, 2) int64, per ray
    # the sample slice m of the sample after which it passes the opacity threshold (MIP /
    # MinIP: its held sample's) and of its first sample that adds something; -1: none
    depth_m: np.ndarray | None = None
    # the same as distances (voxels) along the view direction from the volume's centre,
    # float64, NaN: none (cube4.host.assemble_view, on the view's whole (fine) base plane)
    depth_z: np.ndarray | None = None

    @property
    def baseplane_float(self) -> np.ndarray:
        """Premultiplied RGBA in [0, 1] (float64)."""
        return self.baseplane.astype(np.float64) / float(1 << self.cfg.acc_bits)


# ---------------------------------------------------------------- numerics.md §4
def interpolate_slice(tp: np.ndarray, trav: Traversal, m: int, weight_bits: int) -> np.ndarray:
    """Tri-linear samples of sample slice m, shape (nj, ni), int32.

    tp is the traversal-frame volume zero-padded by one voxel at the high end of each
    axis, shape (nk + 1, nj + 1, ni + 1). Seven lerps, in the order x (four), y (two),
    z (one); each rounds half up (fixed.lerp). Sample (m, j, i) sits at
    (i + wx, j + wy, m / S).
    """
    k0 = m // trav.supersample
    return interpolate_pair(tp[k0], tp[k0 + 1], trav, m, weight_bits)


def interpolate_pair(lo: np.ndarray, hi: np.ndarray, trav: Traversal, m: int, weight_bits: int) -> np.ndarray:
    """``interpolate_slice`` from the two padded voxel slices it reads, k0 = m // S and
    k0 + 1 (the second only where wz > 0)."""
    wx, wy, wz = (int(w) for w in trav.weights(m))

    def bilinear(vs: np.ndarray) -> np.ndarray:
        ax = lerp(vs[:, :-1], vs[:, 1:], wx, weight_bits)  # x lerps: rows j and j + 1
        return lerp(ax[:-1], ax[1:], wy, weight_bits)  # y lerp

    s0 = bilinear(lo)
    if wz == 0:
        # lerp(s0, s1, 0) == s0 exactly; the hardware still runs the z lerp.
        return s0
    return lerp(s0, bilinear(hi), wz, weight_bits)


def rect_slice(src: np.ndarray, trav: Traversal, m: int, bounds, weight_bits: int) -> np.ndarray:
    """Sample slice m of a slice-rectangle frame (numerics.md §18): interpolated from the
    voxels of the traversed rectangle ``bounds`` = (j0, j1, i0, i1) only (zero beyond), and
    zero outside it. ``src`` is padded as for interpolate_slice."""
    k0 = m // trav.supersample
    j0, j1, i0, i1 = bounds
    lo, hi = np.zeros_like(src[k0]), np.zeros_like(src[k0])
    lo[j0:j1, i0:i1] = src[k0, j0:j1, i0:i1]
    hi[j0:j1, i0:i1] = src[k0 + 1, j0:j1, i0:i1]
    out = interpolate_pair(lo, hi, trav, m, weight_bits)
    region = np.zeros(out.shape, dtype=bool)
    region[j0:j1, i0:i1] = True
    out[~region] = 0
    return out


def label_slice(lp: np.ndarray, trav: Traversal, m: int) -> np.ndarray:
    """The labels of sample slice m (numerics.md §24, cube4.labels.nearest_pair) from the
    padded traversal-frame labels ``lp`` (as interpolate_slice's ``tp``)."""
    k0 = m // trav.supersample
    return nearest_pair(lp[k0], lp[k0 + 1], trav.weights(m), trav.weight_bits)


def inside_mask(trav: Traversal, m: int) -> np.ndarray:
    """Samples of slice m that lie inside the volume box [0, n-1]^3 (numerics.md §4):
    the last column is outside when wx > 0, the last row when wy > 0."""
    wx, wy, _ = (int(w) for w in trav.weights(m))
    mask = np.ones((trav.nj, trav.ni), dtype=bool)
    if wx:
        mask[:, -1] = False
    if wy:
        mask[-1, :] = False
    return mask


def padded_traversal(vol: np.ndarray, trav: Traversal) -> np.ndarray:
    """vol[z, y, x] in the traversal frame, zero-padded by one voxel at the high end of
    each axis (what interpolate_slice reads), int64."""
    t = trav.to_traversal(vol)
    nk, nj, ni = t.shape
    tp = np.zeros((nk + 1, nj + 1, ni + 1), dtype=np.int64)
    tp[:nk, :nj, :ni] = t
    return tp


def voxel_channels(words: np.ndarray, trav: Traversal, voxel_bits: int) -> tuple[np.ndarray, np.ndarray]:
    """Memory words (cube4.vgrad) as the padded traversal-frame value and (3, ...) signed
    gradient components (volume axes x, y, z) that TRI interpolates (numerics.md §5b)."""
    return unpack_words(padded_traversal(words, trav), voxel_bits)


def sample_stream(vol: np.ndarray, trav: Traversal, vgrad_bits: int | None = None, label_bits: int | None = None):
    """The tri-linear sample stream alone (what the RTL front end emits):
    samples (M, nj, ni) int64 and inside (M, nj, ni) bool, indexed [m, j, i].
    ``vgrad_bits`` = VOXEL_W when vol holds memory words with voxel gradients: the
    samples are then (M, 4, nj, ni), the value and the three interpolated components.
    ``label_bits`` = VOXEL_W when vol holds labelled words (cube4.labels): each sample is
    then the word label · 2^V + value, the label the nearest corner's (numerics.md §24)."""
    lp = None
    if vgrad_bits is None:
        tp, comps = padded_traversal(vol, trav), None
        if label_bits is not None:
            tp, lp = split_words(tp, label_bits)
    else:
        tp, comps = voxel_channels(vol, trav, vgrad_bits)
    nj, ni = tp.shape[1] - 1, tp.shape[2] - 1
    M = trav.num_sample_slices
    samples = np.empty((M, nj, ni) if comps is None else (M, 4, nj, ni), dtype=np.int64)
    inside = np.empty((M, nj, ni), dtype=bool)
    for m in range(M):
        s = interpolate_slice(tp, trav, m, trav.weight_bits)
        if lp is not None:
            s = s + (label_slice(lp, trav, m) << label_bits)
        if comps is None:
            samples[m] = s
        else:
            samples[m, 0] = s
            samples[m, 1:] = voxel_gradient_slice(comps, trav, m)
        inside[m] = inside_mask(trav, m)
    return samples, inside


# ---------------------------------------------------------------- numerics.md §5
def gradient_operands(prev: np.ndarray, cur: np.ndarray, nxt: np.ndarray, trav: Traversal, m: int) -> np.ndarray:
    """The samples the gradient of sample slice m is made of (GRA's window,
    rtl/cube4_gra_window.v), from sample slices m-1, m, m+1 (each zero-padded by one
    sample on every side, shape (nj + 2, ni + 2)). Returns (6, nj, ni) int64:

    hi = s[m, j, i+1]    lo = s[m, j, i-1]    up = s[m, j+1, i]    dn = s[m, j-1, i]
    fwd = s[m+1, j + Ystep(m), i + Xstep(m)]    back = s[m-1, j - oldYstep(m), i - oldXstep(m)]
    """
    nj, ni = trav.nj, trav.ni
    sx0, sy0 = (int(v) for v in trav.steps(m))
    sxf, syf = (int(v) for v in trav.steps(m + 1))
    sxb, syb = (int(v) for v in trav.steps(m - 1))
    dxf, dyf = sxf - sx0, syf - sy0  # X-step, Y-step: 0 or 1
    dxb, dyb = sx0 - sxb, sy0 - syb  # old-X-step, old-Y-step
    c = cur.astype(np.int64)
    fwd = nxt[1 + dyf:1 + dyf + nj, 1 + dxf:1 + dxf + ni].astype(np.int64)
    back = prev[1 - dyb:1 - dyb + nj, 1 - dxb:1 - dxb + ni].astype(np.int64)
    return np.stack([c[1:-1, 2:], c[1:-1, :-2], c[2:, 1:-1], c[:-2, 1:-1], fwd, back])


def gradient_of(ops: np.ndarray, trav: Traversal) -> np.ndarray:
    """(gi, gj, gk) from the operands of ``gradient_operands`` (GRA's arithmetic,
    rtl/cube4_gra_arith.v), stacked on a new first axis, int64:

    gi = hi - lo,  gj = up - dn,  gr = fwd - back
    gk = S * gr - round_shift(VIEW_X * gi + VIEW_Y * gj, W)  (the shear correction)
    """
    hi, lo, up, dn, fwd, back = (np.asarray(o, dtype=np.int64) for o in ops)
    gi, gj, gr = hi - lo, up - dn, fwd - back
    gk = trav.supersample * gr - round_shift(trav.view_x * gi + trav.view_y * gj, trav.weight_bits)
    return np.stack([gi, gj, gk])


def gradient(prev: np.ndarray, cur: np.ndarray, nxt: np.ndarray, trav: Traversal, m: int) -> np.ndarray:
    """Gradient of sample slice m from sample slices m-1, m, m+1 (each zero-padded by
    one sample on every side, shape (nj + 2, ni + 2)). Returns (3, nj, ni) int64:

    gi = s[m, j, i+1] - s[m, j, i-1]
    gj = s[m, j+1, i] - s[m, j-1, i]
    gr = s[m+1, along the ray] - s[m-1, along the ray]      (X/Y-step, old-X/Y-step)
    gk = S * gr - round_shift(VIEW_X * gi + VIEW_Y * gj, W)  (the shear correction)

    i.e. twice the central differences, in traversal-frame axes.
    """
    return gradient_of(gradient_operands(prev, cur, nxt, trav, m), trav)


def voxel_gradient_slice(comps: np.ndarray, trav: Traversal, m: int) -> np.ndarray:
    """Voxel gradients (numerics.md §5b) of sample slice m: each padded component of
    ``voxel_channels`` interpolated like the value (the same seven lerps and weights).
    Returns (3, nj, ni) int64, (g_x, g_y, g_z) in the volume's axes."""
    return np.stack([interpolate_slice(c, trav, m, trav.weight_bits) for c in comps])


def gradient_stream(samples: np.ndarray, trav: Traversal) -> np.ndarray:
    """Gradients (M, 3, nj, ni) of a whole sample stream (what the RTL GRA emits)."""
    M, nj, ni = samples.shape
    pad = np.zeros((M + 2, nj + 2, ni + 2), dtype=np.int32)
    pad[1:-1, 1:-1, 1:-1] = samples
    out = np.empty((M, 3, nj, ni), dtype=np.int64)
    for m in range(M):
        out[m] = gradient(pad[m], pad[m + 1], pad[m + 2], trav, m)
    return out


def gradient_operand_stream(samples: np.ndarray, trav: Traversal) -> np.ndarray:
    """The operands (M, 6, nj, ni) of ``gradient_operands`` for a whole sample stream
    (what GRA's window hands its arithmetic)."""
    M, nj, ni = samples.shape
    pad = np.zeros((M + 2, nj + 2, ni + 2), dtype=np.int32)
    pad[1:-1, 1:-1, 1:-1] = samples
    out = np.empty((M, 6, nj, ni), dtype=np.int64)
    for m in range(M):
        out[m] = gradient_operands(pad[m], pad[m + 1], pad[m + 2], trav, m)
    return out


# ---------------------------------------------------------------- numerics.md §6
def rmap_index(g: np.ndarray, rmap_bits: int) -> np.ndarray:
    """Reflectance-map entry of gradient directions g (3, ...) (cube map).

    Face axis f = the largest |g| (ties: i, then j, then k); face = 2 f + (g_f < 0).
    With A = |g_f| and (g_b, g_c) the other two components in axis order,
    u = min(R-1, floor((g_b + A) R / (2A))), v likewise from g_c;
    entry = face R^2 + v R + u. A zero gradient selects the last entry, 6 R^2.
    """
    r = 1 << rmap_bits
    a = np.abs(g)
    f = np.where((a[0] >= a[1]) & (a[0] >= a[2]), 0, np.where(a[1] >= a[2], 1, 2))
    big = np.take_along_axis(a, f[None], axis=0)[0]
    neg = np.take_along_axis(g, f[None], axis=0)[0] < 0
    gb = np.where(f == 0, g[1], g[0])
    gc = np.where(f == 2, g[1], g[2])
    den = np.maximum(2 * big, 1)
    u = np.minimum(r - 1, ((gb + big) * r) // den)
    v = np.minimum(r - 1, ((gc + big) * r) // den)
    idx = (2 * f + neg) * r * r + v * r + u
    return np.where(big == 0, 6 * r * r, idx)


def shade(samples: np.ndarray, grad: np.ndarray | None, lut: np.ndarray, rmap: np.ndarray | None, rmap_bits: int,
          gm: np.ndarray | None = None):
    """Classify and shade: returns (rgba (4, ...) int64, rmap index or None).

    (R, G, B, A) = LUT[sample]; (D, P) = RMAP[index(gradient)];
    C' = min(2^8 - 1, round_shift(C * D, 8) + P) for C in R, G, B; A unchanged.
    Unshaded (grad None, a build without GRA and reflectance map): C' = C.
    gm: gradient-magnitude modulation's table (cube4.gmod, numerics.md §23): D, P and A
    are modulated by the factors of the gradient's entry first.
    """
    entry = lut[samples]  # (..., 4)
    if grad is None:
        return np.moveaxis(entry.astype(np.int64), -1, 0), None
    idx = rmap_index(grad, rmap_bits)
    dp = rmap[idx]
    alpha = entry[..., 3:4]
    d, p = dp[..., 0:1], dp[..., 1:2]
    if gm is not None:
        d, p, alpha = modulate(entry, dp, gm[gm_index(grad)])
    top = (1 << COLOR_W) - 1
    col = np.minimum(top, round_shift(entry[..., :3] * d, RMAP_FRAC) + p)
    rgba = np.concatenate([col, alpha], axis=-1)
    return np.moveaxis(rgba, -1, 0), idx


# ---------------------------------------------------------------- numerics.md §7
def composite(acc: np.ndarray, trans: np.ndarray, rgba: np.ndarray, count: np.ndarray, cfg: Cube4Config) -> np.ndarray:
    """Front-to-back compositing, in place, of one slice of shaded samples.

    acc (3, ...) colour and trans (...) transmittance, Q0.ACC_W, trans starts at 2^ACC_W.
    w = round_shift(T * A, ALPHA_W);  C += round_shift(w * C', 8);  T -= w.
    0 <= w <= T, so T never wraps and C <= 2^ACC_W - T (numerics.md §7).
    A sample that does not count (outside the box, the window or the cut) has w = 0.
    """
    w = np.where(count, round_shift(trans * rgba[3], cfg.alpha_bits), 0)
    acc += round_shift(w * rgba[:3], COLOR_W)
    trans -= w
    return w


def xray(acc: np.ndarray, trans: np.ndarray, rgba: np.ndarray, count: np.ndarray, cfg: Cube4Config) -> np.ndarray:
    """X-ray (numerics.md §13), in place: the attenuation sum without occlusion.

    w = round_shift(2^ACC_W * A, ALPHA_W) (compositing's w with T held at 1);
    C = min(2^ACC_W, C + round_shift(w * C', 8));  T = max(0, T - w), so the ray's
    A = 2^ACC_W - T = min(1, sum of the counted samples' opacities).
    """
    one = 1 << cfg.acc_bits
    w = np.where(count, round_shift(one * rgba[3], cfg.alpha_bits), 0)
    np.minimum(one, acc + round_shift(w * rgba[:3], COLOR_W), out=acc)
    np.maximum(0, trans - w, out=trans)
    return w


def extremum(value: np.ndarray, held: np.ndarray, s: np.ndarray, rgba: np.ndarray, count: np.ndarray,
             minimum: bool) -> np.ndarray:
    """MIP / MinIP (numerics.md §13), in place: the ray keeps the largest (smallest)
    interpolated value of the samples that count, with that sample's classification:
    taken when s >= value (s <= value); value starts at 0 (2^VOXEL_W - 1) and held at 0,
    so a ray with no counted sample stays transparent."""
    take = count & ((s <= value) if minimum else (s >= value))
    value[take] = s[take]
    held[:, take] = rgba[:, take]
    return take


def extremum_pixel(held: np.ndarray, cfg: Cube4Config) -> np.ndarray:
    """A MIP / MinIP ray's (R, G, B, A) in Q0.ACC_W from the held classification
    (colour Q0.8, premultiplied by the host; A Q0.ALPHA_W): colour << (ACC_W - 8);
    A << (ACC_W - ALPHA_W), or round_shift(A, ALPHA_W - ACC_W) when ALPHA_W > ACC_W."""
    out = np.empty_like(held)
    out[:3] = held[:3] << (cfg.acc_bits - COLOR_W)
    d = cfg.acc_bits - cfg.alpha_bits
    out[3] = held[3] << d if d >= 0 else round_shift(held[3], -d)
    return out


# ---------------------------------------------------------------- the frame
def render_frame(
    vol: np.ndarray,
    trav: Traversal,
    cfg: Cube4Config,
    lut: np.ndarray,
    rmap: np.ndarray | None,
    keep_streams: bool = False,
    progress: Progress | None = None,
    mode: str = "composite",
    shading: bool = True,
    clip: Clip | None = None,
    vgrad: bool = False,
    rects: SliceRects | None = None,
    beats: "BeatSchedule | None" = None,
    done: "TerminationRule | None" = None,
    depth_t: int | None = None,
    stop_m: np.ndarray | None = None,
    gm: np.ndarray | None = None,
    labels: bool = False,
) -> Frame:
    """Render one view of vol[z, y, x] (unsigned VOXEL_W-bit integers) bit-exactly.

    mode: composite, xray, mip or minip (numerics.md §7, §13); shading False classifies
    only (no gradient, no reflectance map; X-ray and MIP/MinIP are never shaded);
    clip: the window and cut plane (clip.py; None: every sample of the box counts);
    vgrad: vol holds memory words with voxel gradients (cube4.vgrad.pack_words), which
    replace GRA (numerics.md §5b; the reflectance map is then in the volume's axes).
    lut: (2^V, 4) R, G, B, A, or (2^V, 8) with the path-weight columns
    (cube4.pathlen.weighted_columns): then the first and last samples of each ray that
    enters or leaves through a face in trav.faces are path-weighted (numerics.md §17;
    composite and X-ray).
    depth_t: depth out (numerics.md §21): the frame's ``depth_m``, per ray the slice after
    which T <= depth_t (MIP / MinIP: the held sample's) and the first slice whose sample
    adds something (w > 0; MIP / MinIP: the first counted sample); None: not tracked.
    stop_m: depth in (numerics.md §22): (rows, cols) per base-plane pixel, its ray counts
    the sample slices m < stop_m only (cube4.geometry.stop_slices).
    gm: gradient-magnitude modulation's table (cube4.gmod, numerics.md §23; shaded frames).
    labels: vol holds labelled words (cube4.labels.pack_words) and lut has 16 · 2^V rows:
    each sample is classified by the entry label · 2^V + value, its label the nearest
    corner's (numerics.md §24; not with slice rectangles).
    rects: slice rectangles (cube4.slices, numerics.md §18): each slice computes only its
    rectangle, and only its samples count; None: every slice is the whole box.
    beats: beat skipping (cube4.beats, numerics.md §19): samples outside the slice's
    running beats are zero, only running rays count, and ``done`` (a TerminationRule)
    ends rays; each slice's done rays are reported to ``beats``.
    """
    if rects is not None and beats is not None:
        raise ValueError("slice rectangles and beat skipping are two schedules: give one")
    if beats is not None and done is None:
        raise ValueError("beat skipping needs the termination rule (done)")
    if beats is not None and stop_m is not None:
        beats.limit_stop(stop_m)    # depth in: the geometry's stop ends the ray's run too
    if labels and (vgrad or rects is not None or not is_blend(mode)):
        raise ValueError("labels run on the fixed, box and beat schedules, in the blending modes, without voxel "
                         "gradients")
    if mode not in MODES:
        raise ValueError(f"mode must be one of {MODES}, got {mode!r}")
    shading = shading and mode == "composite"
    W = cfg.weight_bits
    one = 1 << cfg.acc_bits
    lut, path_cols = lut[:, :4], (lut[:, 4:] if path_weighted(lut, mode) else None)
    if vgrad:
        tp, comps = voxel_channels(vol, trav, cfg.voxel_bits)
    else:
        tp, comps = padded_traversal(vol, trav), None
    lp = None
    if labels:
        tp, lp = split_words(tp, cfg.voxel_bits)
    nj, ni = tp.shape[1] - 1, tp.shape[2] - 1
    M = trav.num_sample_slices
    rows, cols = trav.baseplane_shape
    sxm, sym = trav.max_steps
    blend = is_blend(mode)
    if blend:
        acc = np.zeros((3, rows, cols), dtype=np.int64)
        trans = np.full((rows, cols), one, dtype=np.int64)
    else:
        start = (1 << cfg.voxel_bits) - 1 if mode == "minip" else 0
        value = np.full((rows, cols), start, dtype=np.int64)
        held = np.zeros((4, rows, cols), dtype=np.int64)

    def sample_slice(src: np.ndarray, m: int) -> np.ndarray:
        """Slice m interpolated from ``src`` (padded, traversal frame): with rectangles,
        from the voxels slice m traverses (zero beyond), and zero outside (numerics.md §18)."""
        if beats is not None:
            return np.where(beats.run_samples(m), interpolate_slice(src, trav, m, W), 0)
        if rects is None:
            return interpolate_slice(src, trav, m, W)
        return rect_slice(src, trav, m, rects.traversed(m), W)

    def inside_of(m: int) -> np.ndarray:
        mask = inside_mask(trav, m)
        if beats is not None:
            return mask & beats.running(m)
        return mask if rects is None else mask & rects.inside(m)

    def padded(m: int) -> np.ndarray:
        sp = np.zeros((nj + 2, ni + 2), dtype=np.int64)
        if 0 <= m < M:
            sp[1:-1, 1:-1] = sample_slice(tp, m)
        return sp

    streams: dict = {}
    if keep_streams:
        streams = {
            "samples": np.zeros((M, nj, ni), dtype=np.int32),
            "inside": np.zeros((M, nj, ni), dtype=bool),
            "keep": np.zeros((M, nj, ni), dtype=bool),
            "gradients": np.zeros((M, 3, nj, ni), dtype=np.int64),
            "rmap_index": np.zeros((M, nj, ni), dtype=np.int64),
            "shaded": np.zeros((M, 4, nj, ni), dtype=np.int64),
            "falloff": np.full((M, nj, ni), FALL_ONE, dtype=np.int64),
        }
    pix_chunks = []
    zbuf = None if depth_t is None else np.full((2, rows, cols), -1, dtype=np.int64)
    prev, cur, nxt = padded(-1), padded(0), padded(1)
    jj, ii = np.mgrid[0:nj, 0:ni]
    for m in counted(range(M), progress, "golden"):
        s = cur[1:-1, 1:-1]
        inside = inside_of(m)
        keep = clip.keep(trav, m) if clip is not None else np.ones((nj, ni), dtype=bool)
        count = inside & keep
        stx, sty = (int(v) for v in trav.steps(m))
        r0, c0 = sym - sty, sxm - stx
        win = (slice(r0, r0 + nj), slice(c0, c0 + ni))
        if stop_m is not None:      # depth in: a ray counts its slices in front of the geometry
            count &= m < stop_m[win]
        if beats is not None:       # only samples that may count; a ray that is done counts no further one
            count &= beats.sample_occ(m)
            count &= ~(done.dead(acc[:, win[0], win[1]], trans[win], None) if blend
                       else done.dead(None, None, value[win]))
        if not shading:
            g = None
        elif vgrad:
            g = np.stack([sample_slice(c, m) for c in comps])   # voxel_gradient_slice, per rectangle
        else:
            g = gradient(prev, cur, nxt, trav, m)
        entry = s if lp is None else s + (label_slice(lp, trav, m) << cfg.voxel_bits)
        rgba, idx = shade(entry, g, lut, rmap, cfg.rmap_bits, gm)
        wrgba = rgba
        if path_cols is not None and trav.faces:
            wrgba = rgba.copy()   # the shaded stream keeps the LUT's A; COM weights it
            wrgba[3] = weighted_alpha(rgba[3], s, path_cols, weight_quarters(trav, m, trav.faces))
        fall = clip.falloff(trav, m) if clip is not None else None
        if fall is not None and keep_streams:
            streams["falloff"][m] = fall
        if fall is not None and blend:      # the slab's falloff weight, after the path weights (COM)
            wrgba = wrgba.copy() if wrgba is rgba else wrgba
            wrgba[3] = round_shift(wrgba[3] * fall, FALL_SHIFT)
        if mode == "composite":
            added = composite(acc[:, win[0], win[1]], trans[win], wrgba, count, cfg) > 0
        elif mode == "xray":
            added = xray(acc[:, win[0], win[1]], trans[win], wrgba, count, cfg) > 0
        else:
            added = extremum(value[win], held[:, win[0], win[1]], s, rgba, count, mode == "minip")
        if zbuf is not None:        # depth out: the first sample that adds, the threshold's
            z_pass, z_first = zbuf[0][win], zbuf[1][win]
            z_first[added & (z_first < 0)] = m
            if blend:
                z_pass[(trans[win] <= depth_t) & (z_pass < 0)] = m
            else:
                z_pass[added] = m
        if beats is not None:
            if blend:
                live_now, dead_now = done.live(acc, trans, None, None), done.dead(acc, trans, None)
            else:
                live_now, dead_now = done.live(None, None, value, held), done.dead(None, None, value)
            beats.report(m, dead_now)
        # rays whose next sample (slice m + 1, along the ray) is outside finish here
        if m + 1 < M:
            sxf, syf = (int(v) for v in trav.steps(m + 1))
            nxt_in = np.zeros((nj + 1, ni + 1), dtype=bool)
            nxt_in[:nj, :ni] = inside_of(m + 1)
            fin = inside & ~nxt_in[jj + (syf - sty), ii + (sxf - stx)]
        else:
            fin = inside.copy()     # (not the same array: the streams keep inside as it was)
        if beats is not None:       # a ray that holds nothing leaves no pixel (the base plane's zero)
            fin &= live_now[win]
        if fin.any():
            fj, fi = np.nonzero(fin)  # row-major: (j, i) order within the slice
            chunk = np.empty(fj.size, dtype=PIXEL_DTYPE)
            chunk["m"] = m
            chunk["by"], chunk["bx"] = fj + r0, fi + c0
            chunk["zp"], chunk["zf"] = ((zbuf[0][win][fin], zbuf[1][win][fin]) if zbuf is not None else (-1, -1))
            if blend:
                a_win, t_win = acc[:, win[0], win[1]], trans[win]
                chunk["r"], chunk["g"], chunk["b"] = a_win[0][fin], a_win[1][fin], a_win[2][fin]
                chunk["a"] = one - t_win[fin]
            else:
                px = extremum_pixel(held[:, win[0], win[1]][:, fin], cfg)
                chunk["r"], chunk["g"], chunk["b"], chunk["a"] = px
            pix_chunks.append(chunk)
        if keep_streams:
            streams["samples"][m] = entry
            streams["inside"][m] = inside
            streams["keep"][m] = keep
            if g is not None:
                streams["gradients"][m] = g
                streams["rmap_index"][m] = idx
            streams["shaded"][m] = rgba
        prev, cur, nxt = cur, nxt, padded(m + 2)

    base = np.empty((rows, cols, 4), dtype=np.int64)
    if blend:
        base[..., :3] = np.moveaxis(acc, 0, -1)
        base[..., 3] = one - trans
    else:
        base[:] = np.moveaxis(extremum_pixel(held, cfg), 0, -1)
    pixels = np.concatenate(pix_chunks) if pix_chunks else np.empty(0, dtype=PIXEL_DTYPE)
    return Frame(trav=trav, cfg=cfg, baseplane=base, pixels=pixels, streams=streams,
                 depth_m=None if zbuf is None else np.moveaxis(zbuf, 0, -1))

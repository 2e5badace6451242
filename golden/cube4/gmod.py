"""Gradient-magnitude modulation (docs/numerics.md §23; build option GMOD).

VolumePro 500 modulates a sample's opacity, and its lighting, by a function of the
gradient magnitude, so that homogeneous regions turn transparent and boundaries stand
out. Here a scene gives two functions of |∇f| (f the field with values in [0, 1],
per voxel of distance): ``opacity`` (A is multiplied by it) and ``shading`` (1: the
sample is lit as usual, 0: it keeps its unshaded colour; between: the diffuse term
moves towards 1 and the specular towards 0 — ULTRAVIS's "no shading below a threshold"
is a step in it).

* **The index** (``gm_index``): the hardware does not take a square root. It forms
  s = gi² + gj² + gk² exactly from the gradient it has (GRA's, or the voxel gradients,
  each component an integer), and quantises s like a floating-point number with
  ``MANT_BITS`` mantissa bits: s = 0 is entry 0; otherwise with e = floor(log2 s) and
  m the MANT_BITS bits below the leading one, entry e·2^MANT_BITS + m + 1. The bins are
  logarithmic: each spans 1/8 of an octave of s (1/16 of an octave of |g|, about 4 %),
  at every magnitude, with no register to set.
* **The table** (``gm_table``): per entry the two factors (opacity fa, shading fs),
  each 0 .. 256 (Q0.8, 256 = 1), the host's evaluation of the scene's functions at the
  bin's magnitude: |∇f| = sqrt(s) / (scale · (2^V − 1)) with s the bin's middle (its one
  integer below 2^MANT_BITS) and scale the gradient's (2 for GRA's and the central
  voxel gradient, which are twice the central difference, 8 for Sobel).
* **The rule** (``modulate``), after the reflectance-map read (§6):
  ``D' = 256 + round_shift((D − 256)·fs, 8)``, ``P' = round_shift(P·fs, 8)``,
  ``C' = min(255, round_shift(C·D', 8) + P')``, ``A' = round_shift(A·fa, 8)``:
  fa = fs = 256 leaves the sample as it was.

The float64 reference evaluates the same functions at the exact |∇f| of its own
gradient and applies them the same way (opacity per voxel of distance times fa before the
sample-distance correction; D and P blended by fs).
"""

from __future__ import annotations

import numpy as np

from .errors import UserError
from .fixed import round_shift

MANT_BITS = 3          # mantissa bits of the quantised s = |g|²
GM_ONE = 256           # a factor of 1 (Q0.8)
GMF_BITS = 9           # a factor's bits: 0 .. 256 (cube4_defs.vh GMF_W)


def sum_bits(grad_bits: int) -> int:
    """Bits of s = gi² + gj² + gk² for components of grad_bits signed bits (each |g| ≤
    2^(grad_bits − 1)): s ≤ 3·2^(2 grad_bits − 2) < 2^(2 grad_bits)."""
    return 2 * grad_bits


def table_entries(grad_bits: int) -> int:
    """Entries of the table: 0 for s = 0, then 2^MANT_BITS per bit position of s."""
    return sum_bits(grad_bits) * (1 << MANT_BITS) + 1


def gm_index(grad: np.ndarray) -> np.ndarray:
    """The table entry of each sample's gradient (3, ...) int64 (module docstring)."""
    g = np.asarray(grad, dtype=np.int64)
    s = g[0] * g[0] + g[1] * g[1] + g[2] * g[2]
    big = s > 0
    e = np.frexp(s.astype(np.float64))[1].astype(np.int64) - 1    # floor(log2 s): exact, s < 2^53
    m = np.where(e >= MANT_BITS, s >> (e - MANT_BITS).clip(0), s << (MANT_BITS - e).clip(0)) & ((1 << MANT_BITS) - 1)
    return np.where(big, e * (1 << MANT_BITS) + m + 1, 0)


def bin_magnitude(idx: np.ndarray) -> np.ndarray:
    """The |g| (in the gradient's own units) the host evaluates entry idx at: sqrt of the
    middle of the entry's range of s (its one integer when the range holds one)."""
    idx = np.asarray(idx, dtype=np.int64)
    k = np.maximum(idx - 1, 0)
    e, m = k >> MANT_BITS, k & ((1 << MANT_BITS) - 1)
    lo = (2.0 ** e) * (1.0 + m / (1 << MANT_BITS))
    width = 2.0 ** (e - MANT_BITS)
    mid = np.where(width >= 1.0, lo + 0.5 * (width - 1.0), lo)   # the integers lo .. lo + width - 1
    return np.where(idx == 0, 0.0, np.sqrt(mid))


def gradient_scale(gradient: str) -> float:
    """The hardware gradient's |g| per unit of |∇v| (v in voxel values, per voxel):
    twice the central difference (GRA, central), eight times it for Sobel (§5, §5b)."""
    return 8.0 if gradient == "sobel" else 2.0


def eval_points(points: np.ndarray | None, x: np.ndarray) -> np.ndarray:
    """A scene's piecewise-linear function [[|∇f|, factor], ...] at x (constant beyond the
    ends); None: 1 everywhere."""
    if points is None:
        return np.ones_like(np.asarray(x, dtype=np.float64))
    return np.interp(x, points[:, 0], points[:, 1])


def gm_table(opacity: np.ndarray | None, shading: np.ndarray | None, voxel_bits: int, gradient: str) -> np.ndarray:
    """(entries, 2) int64 {fa, fs} for the scene's functions (None: identity, 256)."""
    n = table_entries(voxel_bits + 5)
    mag = bin_magnitude(np.arange(n)) / (gradient_scale(gradient) * ((1 << voxel_bits) - 1))
    fa = np.clip(np.floor(eval_points(opacity, mag) * GM_ONE + 0.5), 0, GM_ONE).astype(np.int64)
    fs = np.clip(np.floor(eval_points(shading, mag) * GM_ONE + 0.5), 0, GM_ONE).astype(np.int64)
    return np.stack([fa, fs], axis=1)


def identity_table(voxel_bits: int) -> np.ndarray:
    """The table of a frame without modulation: every entry {256, 256}."""
    return np.full((table_entries(voxel_bits + 5), 2), GM_ONE, dtype=np.int64)


def modulate(entry: np.ndarray, dp: np.ndarray, factors: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(D', P', A') of samples whose LUT entry is ``entry`` (..., 4), reflectance-map word
    ``dp`` (..., 2) and table word ``factors`` (..., 2) (module docstring)."""
    fa, fs = factors[..., 0:1], factors[..., 1:2]
    d = GM_ONE + round_shift((dp[..., 0:1] - GM_ONE) * fs, 8)
    p = round_shift(dp[..., 1:2] * fs, 8)
    a = round_shift(entry[..., 3:4] * fa, 8)
    return d, p, a


def parse_points(tbl, key: str) -> np.ndarray | None:
    """[gradient_modulation] opacity / shading = [[|∇f|, factor], ...]: at least one point,
    |∇f| ascending from 0 and at most 2, factors in [0, 1]."""
    raw = tbl.get(key)
    if raw is None:
        return None
    try:
        pts = np.asarray(raw, dtype=np.float64)
    except (TypeError, ValueError):
        pts = None
    if pts is None or pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 1 or not np.isfinite(pts).all():
        raise UserError(f"scene: gradient_modulation.{key} must be [[magnitude, factor], ...] (numbers)")
    if (pts[:, 0] < 0).any() or (pts[:, 0] > 2).any() or (np.diff(pts[:, 0]) < 0).any():
        raise UserError(f"scene: gradient_modulation.{key} magnitudes must ascend within 0 .. 2 "
                        "(|gradient| of the value scaled to 0 .. 1, per voxel)")
    if (pts[:, 1] < 0).any() or (pts[:, 1] > 1).any():
        raise UserError(f"scene: gradient_modulation.{key} factors must lie in 0 .. 1")
    return pts

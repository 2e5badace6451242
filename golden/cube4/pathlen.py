"""Path-length weights of a ray's first and last samples (docs/numerics.md §17).

A ray's samples lie one sample step apart; with the midpoint rule, sample m stands for
the stretch [m - 1/2, m + 1/2] of its ray (in sample steps). The first sample inside the
volume's box stands for less or more than a step: from where the ray enters the box to
its midpoint, w = 1/2 + e_in, where e_in in [0, 1) is the distance from the entry point
to the sample. The last sample likewise has w = 1/2 + e_out. A sample of weight w has
the opacity 1 - (1 - A)^w, A the LUT's (already corrected for the step).

Where the ray enters (all in the traversal frame, the template's phase ph(m) =
(PH0 + m VIEW) mod 2^PB, PB = W + log2 S, and the step bits of cube4_cfb):

* through the k face: slice m = 0, e_in = 0;
* through the i face: lane i = 0 of a slice whose old X-step is set (the ray's previous
  sample was at i = -1): e_in = ph_x(m) / VIEW_X; the j face likewise.

Where it leaves:

* through the k face: m = M - 1, e_out = 0;
* through the i face at i = NI - 1 (the next sample is at i = NI, or at NI - 1 with a
  non-zero weight): e_out = 0; at i = NI - 2 with the X-step set and wx(m + 1) > 0:
  e_out = 1 - ph_x(m + 1) / VIEW_X; the j face likewise.

These are exactly the causes of a fresh ray and of a finished ray (numerics.md §8),
split by face. A face counts only when it is a face of the volume: a frame of an
empty-space box or a brick has interior faces, and the six FACES bits (I0, I1, J0, J1,
K0, K1 from bit 0) say which faces are the volume's (``Traversal.faces``).

The hardware quantises each fraction to quarters, rounding half up:
rq(num, VIEW) = #{k in 1, 3, 5, 7 : 8 num >= k VIEW} in 0..4 (e = num / VIEW), the
minimum over the active causes of each end, and the weight in quarters
wq = 4 + (entry ? rq_in - 2 : 0) + (exit ? rq_out - 2 : 0), clamped to 2..6
(1/2 .. 3/2; a ray of one sample, w = e_in + e_out, is clamped to at least 1/2).
wq = 4 keeps the LUT's A; 2, 3, 5, 6 read the LUT's path-weight columns
(``weighted_columns``).
"""

from __future__ import annotations

import numpy as np

from .modes import is_blend
from .tables import quantize_unit
from .view import Traversal

#: the path weights that have a LUT column, in quarters (column c of PATH_QUARTERS[c])
PATH_QUARTERS = (2, 3, 5, 6)
#: FACES bits, bit 0 first: the traversal frame's low and high faces of i, j and k
FACE_NAMES = ("I0", "I1", "J0", "J1", "K0", "K1")
ALL_FACES = (1 << len(FACE_NAMES)) - 1


def path_weighted(lut: np.ndarray, mode: str) -> bool:
    """Is a frame with this LUT in this mode path-weighted? Its LUT carries the four
    path-weight columns, and the mode integrates along the ray (composite, X-ray)."""
    return lut.shape[1] > 4 and is_blend(mode)


def weighted_columns(alpha: np.ndarray, alpha_bits: int) -> np.ndarray:
    """The LUT's path-weight columns: (2^V, 4) int64, column c = Q0.ALPHA_W of
    1 - (1 - A)^w for w = PATH_QUARTERS[c] / 4 (A the LUT's opacity column)."""
    a = np.asarray(alpha, dtype=np.float64) / float(1 << alpha_bits)
    cols = [quantize_unit(1.0 - np.power(1.0 - a, q / 4.0), alpha_bits) for q in PATH_QUARTERS]
    return np.stack(cols, axis=-1)


def quarter_bins(num, view: int):
    """rq = #{k in 1, 3, 5, 7 : 8 num >= k view}: e = num / view rounded half up to quarters."""
    num = np.asarray(num, dtype=np.int64)
    return sum((8 * num >= k * view).astype(np.int64) for k in (1, 3, 5, 7))


def _axis_terms(ph0: int, view: int, m: int, pb: int, g: int):
    """(old step into m, step out of m, wx(m + 1) > 0, rq of entry, rq of exit) of one axis."""
    one = 1 << pb
    ph_m = (ph0 + m * view) % one
    ph_n = (ph0 + (m + 1) * view) % one
    old = ((ph0 + m * view) >> pb) - ((ph0 + (m - 1) * view) >> pb)
    new = ((ph0 + (m + 1) * view) >> pb) - ((ph0 + m * view) >> pb)
    rq_in = int(quarter_bins(ph_m, view)) if view else 0
    rq_out = int(quarter_bins(view - ph_n, view)) if view else 0
    return bool(old), bool(new), (ph_n >> g) != 0, rq_in, rq_out


def weight_quarters(trav: Traversal, m: int, faces: int) -> np.ndarray:
    """The path weight wq (quarters, 2..6) of every lane (nj, ni) of sample slice m."""
    nj, ni, M = trav.nj, trav.ni, trav.num_sample_slices
    pb, g = trav.phase_bits, trav.guard_bits
    f = [bool(faces >> b & 1) for b in range(6)]
    oxs, nxs, wxn, rxi, rxo = _axis_terms(trav.phase_x, trav.view_x, m, pb, g)
    oys, nys, wyn, ryi, ryo = _axis_terms(trav.phase_y, trav.view_y, m, pb, g)
    jj, ii = np.mgrid[0:nj, 0:ni]
    big = 9
    # entry: the minimum rq over the active causes (9: none)
    rq_in = np.full((nj, ni), big, dtype=np.int64)
    if f[4] and m == 0:
        rq_in[:] = 0
    if f[0] and oxs:
        rq_in = np.where(ii == 0, np.minimum(rq_in, rxi), rq_in)
    if f[2] and oys:
        rq_in = np.where(jj == 0, np.minimum(rq_in, ryi), rq_in)
    # exit
    rq_out = np.full((nj, ni), big, dtype=np.int64)
    if f[5] and m == M - 1:
        rq_out[:] = 0
    if f[1]:
        if nxs or wxn:
            rq_out = np.where(ii == ni - 1, 0, rq_out)
        if nxs and wxn:
            rq_out = np.where(ii == ni - 2, np.minimum(rq_out, rxo), rq_out)
    if f[3]:
        if nys or wyn:
            rq_out = np.where(jj == nj - 1, 0, rq_out)
        if nys and wyn:
            rq_out = np.where(jj == nj - 2, np.minimum(rq_out, ryo), rq_out)
    wq = 4 + np.where(rq_in < big, rq_in - 2, 0) + np.where(rq_out < big, rq_out - 2, 0)
    return np.clip(wq, 2, 6)


def weighted_alpha(alpha: np.ndarray, samples: np.ndarray, columns: np.ndarray, wq: np.ndarray) -> np.ndarray:
    """A sample's opacity after its path weight: the LUT's A where wq = 4, else the
    path-weight column of wq read at the sample."""
    out = np.asarray(alpha, dtype=np.int64).copy()
    for c, q in enumerate(PATH_QUARTERS):
        sel = wq == q
        if sel.any():
            out[sel] = columns[samples[sel], c]
    return out

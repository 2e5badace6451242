"""Voxel gradients: the gradient estimated at the voxels by the host, interpolated by TRI.

The paper's GRA (numerics.md §5) differences the *sample* stream; its angle error grows
with S (numerics.md §10). The alternative here (numerics.md §5b, architecture.md
"Voxel gradients") estimates the gradient once per volume, at the voxels, and stores it
beside each voxel in the memory word; TRI interpolates the three components with the
same weights and the same seven lerps as the value. The memory image stays one image for
every view (the components are in the volume's axes x, y, z; the host builds the
reflectance map in the same axes), and the error falls with S like the value's.

Estimators ([render] gradient):

* ``central``: g_x = v[x+1] - v[x-1] (likewise y, z), voxels outside the grid are 0.
  |g| <= 2^V - 1: V + 1 bits signed, exact. Its interpolant is the float64 reference's
  gradient (reference.py), to the lerps' rounding.
* ``sobel``: the 3×3×3 Sobel, the central difference smoothed (1, 2, 1) in the two
  other axes, divided by 4 with one rounding: g_x = round_shift(sum_{b,c} w_b w_c
  (v[x+1, b, c] - v[x-1, b, c]), 2), w = (1, 2, 1); |sum| <= 16 (2^V - 1), so
  |g_x| <= 4 (2^V - 1): V + 3 bits signed. Four times the scale of ``central``.

The memory word (``pack_words``), LSB first: the value (V bits), then g_x, g_y, g_z, each
``grad_bits(V)`` = V + 3 bits, two's complement, so that a zero word (what TRI reads
outside the volume) is value 0 and gradient 0, as in the model's zero padding. TRI's
lerps are unsigned: it flips a component's sign bit on the way in (offset binary,
g + B with B = 2^(V+2)) and back on the way out, which gives the signed lerp bit for bit,
because a + B + round_shift((b - a) w, W) = (a + round_shift((b - a) w, W)) + B.
"""

from __future__ import annotations

import numpy as np

from .errors import UserError
from .fixed import round_shift

#: [render] gradient: the paper's GRA on the sample stream, or a voxel estimator
GRADIENTS = ("gra", "central", "sobel")
VOXEL_GRADIENTS = ("central", "sobel")


def grad_bits(voxel_bits: int) -> int:
    """Width of one stored component (offset binary): V + 3 bits hold either estimator."""
    return voxel_bits + 3


#: the host keeps a memory word in an int64: voxel gradients need VOXEL_W <= 13 (13 + 3 * 16 = 61 bits)
MAX_VGRAD_VOXEL_BITS = 13


def word_bits(voxel_bits: int, vgrad: bool, labels: bool = False) -> int:
    """Bits of a memory word: the voxel alone, or the voxel and three components; with
    labels (cube4.labels) the label's bits above them."""
    from .labels import LABEL_W
    return voxel_bits + (3 * grad_bits(voxel_bits) if vgrad else 0) + (LABEL_W if labels else 0)


def check_gradient(name: str, where: str = "scene: render.") -> str:
    if name not in GRADIENTS:
        raise UserError(f"{where}gradient must be one of {', '.join(GRADIENTS)}, got {name!r}")
    return name


def _shift(p: np.ndarray, axis: int, d: int) -> np.ndarray:
    """The padded array p (one zero voxel all round) read at offset d along axis,
    trimmed back to the volume's shape."""
    idx = [slice(1, -1)] * 3
    idx[axis] = slice(1 + d, p.shape[axis] - 1 + d)
    return p[tuple(idx)]


def voxel_gradients(vol: np.ndarray, kind: str) -> np.ndarray:
    """(3, nz, ny, nx) int64: (g_x, g_y, g_z) of vol[z, y, x] at every voxel (module doc)."""
    if kind not in VOXEL_GRADIENTS:
        raise ValueError(f"voxel gradient must be one of {VOXEL_GRADIENTS}, got {kind!r}")
    v = np.pad(np.asarray(vol, dtype=np.int64), 1)
    out = np.empty((3, *vol.shape), dtype=np.int64)
    for comp, axis in enumerate((2, 1, 0)):     # x, y, z are array axes 2, 1, 0
        diff = _shift(v, axis, 1) - _shift(v, axis, -1)
        if kind == "central":
            out[comp] = diff
            continue
        # (1, 2, 1) in each of the two other axes, on the difference padded with zeros
        acc = diff
        for other in (a for a in (0, 1, 2) if a != axis):
            p = np.pad(acc, [(1, 1) if a == other else (0, 0) for a in range(3)])
            lo = [slice(None)] * 3
            mid = [slice(None)] * 3
            hi = [slice(None)] * 3
            n = acc.shape[other]
            lo[other], mid[other], hi[other] = slice(0, n), slice(1, n + 1), slice(2, n + 2)
            acc = p[tuple(lo)] + 2 * p[tuple(mid)] + p[tuple(hi)]
        out[comp] = round_shift(acc, 2)
    return out


def pack_words(vol: np.ndarray, kind: str, voxel_bits: int) -> np.ndarray:
    """The memory words of vol[z, y, x] (int64, same shape): value | g_x, g_y, g_z
    (two's complement, ``grad_bits`` each)."""
    if voxel_bits > MAX_VGRAD_VOXEL_BITS:
        raise UserError(f"voxel gradients need VOXEL_W <= {MAX_VGRAD_VOXEL_BITS} (a memory word of "
                        f"{word_bits(voxel_bits, True)} bits does not fit the host's 64-bit words), got {voxel_bits}")
    return pack_channels(vol, voxel_gradients(vol, kind), voxel_bits)


def pack_channels(value: np.ndarray, comps: np.ndarray, voxel_bits: int) -> np.ndarray:
    """Words (int64) from values and (3, ...) signed components: the layout of the memory
    word, also that of TRI's interpolated output with voxel gradients."""
    gb = grad_bits(voxel_bits)
    words = np.asarray(value, dtype=np.int64).copy()
    for c in range(3):
        words |= (np.asarray(comps[c], dtype=np.int64) & ((1 << gb) - 1)) << (voxel_bits + c * gb)
    return words


def unpack_words(words: np.ndarray, voxel_bits: int) -> tuple[np.ndarray, np.ndarray]:
    """(value, (3, ...) signed components) of memory words (any shape)."""
    gb = grad_bits(voxel_bits)
    w = np.asarray(words, dtype=np.int64)
    value = w & ((1 << voxel_bits) - 1)
    half = 1 << (gb - 1)
    comps = np.stack([(((w >> (voxel_bits + c * gb)) + half) & ((1 << gb) - 1)) - half for c in range(3)])
    return value, comps

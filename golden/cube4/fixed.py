"""The shared fixed-point primitives; the RTL's ``cube4_lerp`` implements exactly these.

Vectorised over NumPy integer arrays. Callers pass signed integer arrays (int32 or
int64) wide enough for the products they form; nothing here widens silently.
"""

from __future__ import annotations


def round_shift(x, shift: int):
    """Divide by 2^shift rounding half up: floor((x + 2^(shift-1)) / 2^shift).

    Works for negative x too (arithmetic shift = floor). shift == 0 returns x.
    """
    if shift == 0:
        return x
    return (x + (1 << (shift - 1))) >> shift


def lerp(a, b, w, weight_bits: int):
    """a + round_shift((b - a) * w, W), w in [0, 2^W - 1] (Q0.W).

    The result always lies between a and b (inclusive), so it needs no wider type than
    the inputs: no bit growth. Equals a when w == 0. This is the paper's eq. (4) with
    the weight on the far sample: w*b + (1-w)*a = (b - a)*w + a.
    """
    return a + round_shift((b - a) * w, weight_bits)

"""Base-plane supersampling q×q by template phase offsets (docs/numerics.md §16).

A frame samples one ray per base-plane pixel. q×q passes of the same view, each with
the template's starting phase moved by (a/q, b/q) voxel (a, b = 0 … q − 1: the CFB's
PH0_X, PH0_Y registers), sample the rays between them; interleaved, their base planes
make one base plane of q times the resolution along both axes, which the warp maps to
the image with a scale of 1/q. Each pass is an ordinary frame (bit-exact through the
RTL; all traverse the view's empty-space box), run back to back on the volume loaded
once.

Ray position. Pass (a, b)'s pixel (bx, by) holds the ray that starts at traversal-frame
position (bx − sxm + δx, by − sym + δy), δ = phase / 2^(W+g), sxm/sym its traversal's
largest steps (view.Traversal.baseplane_to_volume). Its fine pixel is

    fx = q·(bx − sxm_a + sxm_0 + 1) + a,    fy = q·(by − sym_b + sym_0 + 1) + b

(sxm_0, sym_0: the phase-0 pass's; the + 1 keeps fx ≥ 0, since a pass's largest step
exceeds the phase-0 pass's by at most one), so fine pixel (fx, fy) is the phase-0
pass's base-plane point (fx/q − 1, fy/q − 1). The phase is δ·2^(W+g) rounded to an
integer: exact for q = 1, 2, 4; for q = 3 within 2^-(W+g+1) voxel of a third.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .view import Traversal

MAX_Q = 4


def check_q(q) -> int:
    if isinstance(q, bool) or not isinstance(q, int) or not 1 <= q <= MAX_Q:
        raise ValueError(f"q must be an integer in 1..{MAX_Q}, got {q!r}")
    return q


@dataclass(frozen=True)
class Pass:
    """One of the q×q passes: its sub-pixel index (a, b) and its traversal."""

    a: int
    b: int
    trav: Traversal


def passes(trav: Traversal, q: int) -> list[Pass]:
    """The q×q passes of a view (``trav`` at phase 0), a (along i) fastest."""
    check_q(q)
    if trav.phase_x or trav.phase_y:
        raise ValueError("the view's own traversal must start at phase 0")
    one = 1 << trav.phase_bits
    out = []
    for b in range(q):
        for a in range(q):
            ph = ((a * one + q // 2) // q, (b * one + q // 2) // q)
            out.append(Pass(a, b, replace(trav, phase_x=ph[0], phase_y=ph[1])))
    return out


def fine_shape(trav: Traversal, q: int) -> tuple[int, int]:
    """(rows, cols) of the interleaved base plane."""
    rows, cols = trav.baseplane_shape
    return q * (rows + 2), q * (cols + 2)


def fine_origin(trav: Traversal, q: int, ps: Pass) -> tuple[int, int]:
    """(row, col) of pass ``ps``'s base-plane pixel (0, 0) in the fine plane; its pixel
    (by, bx) lies at (row + q·by, col + q·bx)."""
    sxm0, sym0 = trav.max_steps
    sxm, sym = ps.trav.max_steps
    return q * (sym0 - sym + 1) + ps.b, q * (sxm0 - sxm + 1) + ps.a


def interleave(trav: Traversal, q: int, planes: list[tuple[Pass, np.ndarray]], fill=0) -> np.ndarray:
    """The q×q passes' base planes (each (rows_a, cols_a, c) of its own traversal) as one
    base plane of fine_shape(trav, q); pixels no pass holds are ``fill``."""
    first = planes[0][1]
    fine = np.full((*fine_shape(trav, q), first.shape[-1]), fill, dtype=first.dtype)
    for ps, base in planes:
        rows, cols = base.shape[:2]
        r0, c0 = fine_origin(trav, q, ps)
        fine[r0:r0 + q * rows:q, c0:c0 + q * cols:q] = base
    return fine


def fine_to_base(q: int) -> np.ndarray:
    """3×3 matrix taking fine pixel (fx, fy, 1) to the phase-0 pass's base-plane point."""
    return np.array([[1.0 / q, 0.0, -1.0], [0.0, 1.0 / q, -1.0], [0.0, 0.0, 1.0]])

"""Cycles per frame of cube4_top, the one formula the reports, the RTL engine and the docs share.

    (M·NJ + 1)·NB + 1 + NJ·NB + NB + 2 + FILL_CYCLES        (docs/architecture.md, "Cycles per frame")
    (M·NJ + 1)·NB + 1 + FILL_CYCLES_UNSHADED                 a build without shading (SHADING = 0)
    (M·NJ + 1)·NB + 1 + FILL_CYCLES_VGRAD                    voxel gradients (VGRAD = 1): no GRA

M sample slices, NJ rows, NB = ⌈NI/P⌉ partial beams per row. It holds while a slice has at least
``COM_MIN_SLICE`` beats (NJ·NB); a smaller slice makes COM wait for its own results
(rtl/cube4_com.v: a beat waits while the beat that writes its base-plane position is in flight).
"""
from __future__ import annotations

#: Pipeline fill of cube4_top: cycles beyond the stream terms, measured at 128³, P = 8
#: (``cube4 render sphere:128 --engine rtl --stats``); tb/cube4_top's phantom tests check the formula
#: against the RTL for P = 1, 4, 5, 8.
FILL_CYCLES = 50
#: The same for a build without shading: no GRA (whose last slice waits for the slice after it)
#: and a 3-stage SHA; measured the same way and checked by tb/cube4_top's build tests.
FILL_CYCLES_UNSHADED = 35
#: The same for a build with voxel gradients (VGRAD = 1): no GRA, the shaded SHA; measured the
#: same way and checked by tb/cube4_top's voxel-gradient test.
FILL_CYCLES_VGRAD = 46

#: cube4_com runs a slice of L = NJ·NB beats at one beat per cycle only if L >= this; a smaller
#: slice takes L beats per COM_MIN_SLICE cycles.
COM_MIN_SLICE = 9


def frame_cycles(m: int, nj: int, ni: int, p: int, shading: bool = True, vgrad: bool = False) -> int:
    """Cycles of one frame without stalls, for M sample slices of NJ rows of NI samples on P
    pipelines; ``shading`` False: a build without shading; ``vgrad``: a shaded build whose
    gradient comes from the voxels (no GRA)."""
    nb = -(-ni // p)
    if not shading:
        return (m * nj + 1) * nb + 1 + FILL_CYCLES_UNSHADED
    if vgrad:
        return (m * nj + 1) * nb + 1 + FILL_CYCLES_VGRAD
    return (m * nj + 1) * nb + 1 + nj * nb + nb + 2 + FILL_CYCLES



def slow_slice_factor(nj: int, ni: int, p: int) -> float:
    """How much slower than frame_cycles a frame with short slices (NJ·NB < COM_MIN_SLICE) runs, at most."""
    nb = -(-ni // p)
    return max(1.0, COM_MIN_SLICE / (nj * nb))

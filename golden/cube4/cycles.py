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
FILL_CYCLES = 62
#: The same for a build without shading: no GRA (whose last slice waits for the slice after it)
#: and a 3-stage SHA; measured the same way and checked by tb/cube4_top's build tests.
FILL_CYCLES_UNSHADED = 42
#: The same for a build with voxel gradients (VGRAD = 1): no GRA, the shaded SHA; measured the
#: same way and checked by tb/cube4_top's voxel-gradient test.
FILL_CYCLES_VGRAD = 56
#: The slab's falloff unit (SLAB = 1 with COMPOSITING = 1, rtl/cube4_sha_slab.v) makes SHA at
#: least 10 stages: a build without shading (3 stages) takes this many cycles more; a shaded
#: SHA is longer already. Checked by tb/cube4_top's slab test.
FALL_EXTRA_UNSHADED = 7
#: Gradient-magnitude modulation (GMOD = 1, shaded builds only) adds two SHA stages (m1, m2:
#: rtl/cube4_sha.v): a frame takes this many cycles more. Checked by tb/cube4_top's test.
GM_EXTRA = 2

#: cube4_com runs a slice of L = NJ·NB beats at one beat per cycle only if L >= this; a smaller
#: slice takes L beats per COM_MIN_SLICE cycles.
COM_MIN_SLICE = 11


def has_falloff(build: dict) -> bool:
    """Does the build have the slab's falloff unit (SLAB = 1 with COMPOSITING = 1)?"""
    return bool(build.get("SLAB", 0)) and bool(build.get("COMPOSITING", 1))


def has_gmod(build: dict) -> bool:
    """Does the build have gradient-magnitude modulation's stages (GMOD = 1, shaded)?"""
    return bool(build.get("GMOD", 0)) and bool(build.get("SHADING", 1))


def frame_cycles(m: int, nj: int, ni: int, p: int, shading: bool = True, vgrad: bool = False,
                 fall: bool = False, gm: bool = False) -> int:
    """Cycles of one frame without stalls, for M sample slices of NJ rows of NI samples on P
    pipelines; ``shading`` False: a build without shading; ``vgrad``: a shaded build whose
    gradient comes from the voxels (no GRA); ``fall``: the build has the slab's falloff
    unit (``has_falloff``); ``gm``: the shaded build has the modulation's stages (``has_gmod``)."""
    nb = -(-ni // p)
    if not shading:
        return (m * nj + 1) * nb + 1 + FILL_CYCLES_UNSHADED + (FALL_EXTRA_UNSHADED if fall else 0)
    extra = GM_EXTRA if gm else 0
    if vgrad:
        return (m * nj + 1) * nb + 1 + FILL_CYCLES_VGRAD + extra
    return (m * nj + 1) * nb + 1 + nj * nb + nb + 2 + FILL_CYCLES + extra



#: Pipeline fill of a cube4_top build with slice rectangles (RECTS = 1) beyond the front end's
#: beats, its empty passes and GRA's own steps (cube4.slices: beats, empty_walks, gra_steps); per
#: build kind (with GRA: one more than FILL_CYCLES, GRA holding its last beat until its walk
#: ends; without shading: FILL_CYCLES_UNSHADED), measured and checked by tb/cube4_top's
#: rectangle tests. Voxel gradients with rectangles are not run (cube4_sim.rtl refuses them).
FILL_CYCLES_RECTS = {"gra": FILL_CYCLES + 1, "unshaded": FILL_CYCLES_UNSHADED}


def rect_frame_cycles(rects, p: int, shading: bool = True, vgrad: bool = False, fall: bool = False) -> int:
    """Cycles of one slice-rectangle frame without stalls on a RECTS build (exact when
    ``rects.com_waits(p)`` is 0: no beat waits in COM)."""
    if vgrad:
        raise ValueError("slice rectangles with voxel gradients are not run")
    gra = shading
    kind = "gra" if gra else "unshaded"
    return (rects.beats(p) + rects.empty_walks(p) + (rects.gra_steps(p) if gra else 0)
            + FILL_CYCLES_RECTS[kind] + (FALL_EXTRA_UNSHADED if fall and not shading else 0))


def slow_slice_factor(nj: int, ni: int, p: int) -> float:
    """How much slower than frame_cycles a frame with short slices (NJ·NB < COM_MIN_SLICE) runs, at most."""
    nb = -(-ni // p)
    return max(1.0, COM_MIN_SLICE / (nj * nb))

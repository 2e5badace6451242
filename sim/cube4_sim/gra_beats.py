"""The interface between GRA's neighbourhood source and its window, for the unit testbenches.

``cube4_gra_lines`` (rtl/cube4_gra_lines.v) steps once per sample beat of the fixed schedule
(``BeatSchedule``: m, j, pb) and then NJ*NB + NB + 2 flush steps. In step n it shows
X = beat n with six earlier beats (a beam is NB beats, a plane NJ*NB, D = NJ*NB + NB):

    x = n    b1 = n - NB    p1 = n - NJ*NB    c = n - D    p1b2 = c - NB
    p2b1 = c - NJ*NB        p2b2 = c - NJ*NB - NB

each the beat's golden samples in its own lanes, zero past the frame's last beat (the
flush), a stale word before its first, with C's {real, header} and select flags (GSEL_* of
cube4_defs.vh, one copy per lane). ``lines_steps`` lists those steps: what
tb/cube4_gra_lines expects from the source and what tb/cube4_gra_window gives its window.
"""

from __future__ import annotations

import numpy as np

from .beats import CTRL_OSY, CTRL_SY, BeatSchedule, Geometry, pack_lanes

# bits of the centre's select flags (GSEL_* in cube4_defs.vh)
GSEL_DYB, GSEL_DYF, GSEL_YLAST, GSEL_MFIRST, GSEL_JFIRST, GSEL_DKB, GSEL_DKF = range(7)
GRA_NSEL = 7
NEIGHBOURS = ("x", "b1", "p1", "c", "p1b2", "p2b1", "p2b2")


def centre_flags(sched: BeatSchedule, n: int) -> int:
    """The select flags of beat n as the centre (GSEL_* bits)."""
    ss = sched.trav.supersample
    m, j, ctrl = int(sched.m[n]), int(sched.j[n]), int(sched.ctrl[n])
    flags = {GSEL_DKF: (m + 1) % ss == 0, GSEL_DKB: m % ss == 0, GSEL_JFIRST: j == 0, GSEL_MFIRST: m == 0,
             GSEL_YLAST: j == sched.trav.nj - 1, GSEL_DYF: (ctrl >> CTRL_SY) & 1, GSEL_DYB: (ctrl >> CTRL_OSY) & 1}
    return sum(int(bool(v)) << b for b, v in flags.items())


def lines_steps(sched: BeatSchedule, samples: np.ndarray, geo: Geometry, vw: int) -> list[dict[str, int | None]]:
    """Every step of cube4_gra_lines for one frame: the seven beats packed as lane buses,
    ``c_meta`` ({real, header} of C), ``c_sel`` (its flags), ``c_real`` (C is a sample
    beat: 1; a flush step: 0), ``sop`` and ``centre`` (C's beat index, or -1). None where
    the lines hold no defined word: an index before the frame reads a stale word (the
    window zeroes rows -1 and slice -1 by C's flags and ignores centres before the
    frame's first), a flush centre's header and flags are whatever the input register
    last held (its real bit is 0)."""
    p, n_beats, nb, nj = sched.p, len(sched), sched.nb, sched.trav.nj
    smp = sched.lanes(samples)
    hdrs = sched.headers(geo)
    plane, d = nj * nb, nj * nb + nb
    packed = [pack_lanes(smp[k], vw) for k in range(n_beats)]

    def beat(k: int) -> int | None:
        return None if k < 0 else packed[k] if k < n_beats else 0

    steps = []
    for n in range(n_beats + d + 2):
        c = n - d
        offs = {"x": n, "b1": n - nb, "p1": n - plane, "c": c, "p1b2": c - nb, "p2b1": c - plane,
                "p2b2": c - plane - nb}
        st: dict[str, int | None] = {k: beat(v) for k, v in offs.items()}
        real = 0 <= c < n_beats
        st["c_meta"] = (1 << geo.hdr_w) | hdrs[c] if real else None
        st["c_sel"] = sum(centre_flags(sched, c) << (GRA_NSEL * q) for q in range(p)) if real else None
        st["c_real"] = 1 if real else (0 if c >= n_beats else None)
        st["sop"] = int(n == 0)
        st["centre"] = c if real else -1
        steps.append(st)
    return steps

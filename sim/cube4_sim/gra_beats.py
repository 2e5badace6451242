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

from typing import NamedTuple

import numpy as np

from cube4.memory import lane_positions

from .beats import (CTRL_EOP, CTRL_OSX, CTRL_OSY, CTRL_SOP, CTRL_SX, CTRL_SY, CTRL_YLAST, BeatSchedule, Geometry,
                    pack_lanes)

# bits of the centre's select flags (GSEL_* in cube4_defs.vh)
GSEL_DYB, GSEL_DYF, GSEL_YLAST, GSEL_MFIRST, GSEL_JFIRST, GSEL_DKB, GSEL_DKF = range(7)
GRA_NSEL = 7
NEIGHBOURS = ("x", "b1", "p1", "c", "p1b2", "p2b1", "p2b2")


class WalkBeat(NamedTuple):
    """One beat of a slice-rectangle frame as the front end walks it (``walk_beats``)."""

    m: int
    j: int
    pb: int
    skew: int
    pos: np.ndarray     # i of each lane (P)
    valid: np.ndarray   # the lane's sample lies in the traversed rectangle (P, bool)
    ctrl: int           # the header's control bits (CTRL_*), EOP on the frame's last beat
    sy: int             # stepy(m + 1) - stepy(m): the Y-step forward ...
    osy: int            # ... and stepy(m) - stepy(m - 1), back
    eoss: int = 0       # the beat schedule's: the last beat of its slice (beat_schedule_beats)


def walk_beats(rects, trav, p: int) -> list[WalkBeat]:
    """The beats of a slice-rectangle frame in the order the front end walks them
    (``cube4.slices.SliceRects.walk`` of each slice, rows j, partial beams pb), with each
    beat's skew, lane positions, valid lanes and control bits, as tb/cube4_gra and
    tb/cube4_gra_walk feed them to GRA."""
    nj, ni, nk = trav.nj, trav.ni, trav.nk
    fi, fj, fk = (bool(trav.flip[a]) for a in (trav.axis_i, trav.axis_j, trav.major))
    order = []
    for m in range(rects.last() + 1):
        w = rects.walk(m, p)
        if w is not None:
            order += [(m, j, pb) for j in range(w[0], w[1]) for pb in range(w[2], w[3] + 1)]
    beats = []
    for n, (m, j, pb) in enumerate(order):
        cj = nj - 1 - (j + 1) if fj else j + 1
        ck = nk - 1 - m if fk else m
        skew = (cj + ck + sum(int(o) for o in trav.origin)) % p
        pos = lane_positions(skew, pb, p, ni, fi)
        tj0, tj1, i0, i1 = rects.traversed(m)
        valid = (pos >= i0) & (pos < i1) & (tj0 <= j < tj1)
        (sx, sy), (sx1, sy1), (sxb, syb) = (trav.steps(k) for k in (m, m + 1, m - 1))
        ysf, ysb = int(sy1 - sy), int(sy - syb)
        ctrl = ((int(sx1 - sx) << CTRL_SX) | (ysf << CTRL_SY) | (int(sx - sxb) << CTRL_OSX) | (ysb << CTRL_OSY)
                | (int(n == 0) << CTRL_SOP) | (int(n == len(order) - 1) << CTRL_EOP) | (int(j == nj - 1) << CTRL_YLAST))
        beats.append(WalkBeat(m, j, pb, skew, pos, valid, ctrl, ysf, ysb))
    return beats


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


def walk_steps(beats: list[dict], nj: int, p: int, hdr_w: int, ss: int) -> list[dict[str, int | None]]:
    """Every step of cube4_gra_walk for one frame of walk beats: ``beats`` are the input
    beats in order, each a dict with m, j, pb, hdr (the header), x (the packed samples,
    zero in lanes without a valid position), real (a lane is valid), sy and osy (its
    Y-step bits). The rule of the position buffers (rtl/cube4_gra_walk.v): the step at
    walk position (w, r, pb) shows X (an input beat, or zero on the source's own walk
    after the last beat), P1 and P2b1 = the X and C of the step at (w - 1, r, pb) where
    the previous walk (of slice w - 1) covered (r, pb), else zero, and B1, C (with its
    {real, header}), P1b2, P2b2 = the X, P1, C, P2b1 of the step at (w, r - 1, pb) after
    the walk's first row, else zero. After the last beat the source walks the rows of the
    last walk and one more (up to NJ) over its partial beams, then three steps with
    nothing (the last: fend). Returned like ``lines_steps`` (c_real: C's real bit; None:
    not defined: P1 of row NJ, which plane A does not store; the old Y-step of a frame's
    first walk), plus ``c_edge`` and ``fend``."""
    mask = ss - 1
    rec: dict[tuple[int, int, int], dict] = {}     # the words a step wrote, by position
    walks: list[dict] = []                         # each walk: m, rows, pbs, its Y-step bits

    def step(w, r, pb, x, meta, dyf, dyb, edge, prev, first_row, dead=False, fend=0):
        pg = (not dead and prev is not None and prev["m"] == w - 1 and prev["j0"] <= r <= prev["jl"]
              and prev["pb0"] <= pb <= prev["pbl"])
        bg = not dead and not first_row
        old = rec.get((w - 1, r, pb), {}) if pg else {}
        row = rec.get((w, r - 1, pb), {}) if bg else {}
        p1 = (None if r == nj else old["x"]) if pg else 0
        p1_meta = (None if r == nj else old["meta"]) if pg else 0
        st = {"x": x, "p1": p1, "p2b1": old["c"] if pg and r != 0 else 0,
              "b1": row.get("x", 0), "c": row.get("p1", 0), "p1b2": row.get("c", 0), "p2b2": row.get("p2b1", 0)}
        c_meta = row.get("meta_p1", 0)
        st["c_meta"] = c_meta
        st["c_real"] = None if c_meta is None else c_meta >> hdr_w
        flags = {GSEL_DKF: (w & mask) == 0, GSEL_DKB: ((w - 1) & mask) == 0, GSEL_JFIRST: r == 1,
                 GSEL_MFIRST: w == 1, GSEL_YLAST: r == nj, GSEL_DYF: dyf, GSEL_DYB: dyb or 0}
        st["c_sel"] = sum(int(bool(v)) << b for b, v in flags.items())
        st["c_sel_mask"] = 0 if dyb is None else (1 << GRA_NSEL) - 1
        st["c_sel_mask"] |= ((1 << GRA_NSEL) - 1) & ~(1 << GSEL_DYB)
        st["c_edge"], st["fend"], st["sop"] = edge, fend, 0
        st["centre"] = (w - 1, r - 1, pb)
        if not dead:
            rec[(w, r, pb)] = {"x": x, "meta": meta, "c": st["c"], "p1": p1, "meta_p1": p1_meta, "p2b1": st["p2b1"]}
        return st

    steps = []
    for n, b in enumerate(beats):
        m, j, pb = b["m"], b["j"], b["pb"]
        new = not walks or walks[-1]["m"] != m
        if new:
            prev = walks[-1] if walks else None
            walks.append({"m": m, "j0": j, "jl": j, "pb0": pb, "pbl": pb, "sy": b["sy"], "osy": b["osy"]})
            edge = 0b01
        else:
            prev = walks[-2] if len(walks) > 1 else None
            wk = walks[-1]
            edge = (int(pb == wk["pb0"])) | (int(pb == wk["pbl"]) << 1)
            wk["jl"] = j
            wk["pbl"] = max(wk["pbl"], pb)
        dyb = None if len(walks) < 2 else walks[-2]["osy"]
        meta = (int(b["real"]) << hdr_w) | b["hdr"]
        steps.append(step(m, j, pb, b["x"], meta, b["osy"], dyb, edge, prev, j == walks[-1]["j0"]))
    wk = walks[-1]
    last = min(wk["jl"] + 1, nj)
    for r in range(wk["j0"], last + 1):
        for pb in range(wk["pb0"], wk["pbl"] + 1):
            edge = int(pb == wk["pb0"]) | (int(pb == wk["pbl"]) << 1)
            steps.append(step(wk["m"] + 1, r, pb, 0, 0, wk["sy"], wk["osy"], edge, wk, r == wk["j0"]))
    for t in range(3):
        edge = 1 | (int(wk["pb0"] == wk["pbl"]) << 1)
        steps.append(step(wk["m"] + 1, last, wk["pb0"], 0, 0, wk["sy"], wk["osy"], edge, wk, False, dead=True,
                          fend=int(t == 2)))
    return steps


def beat_schedule_beats(bf, p: int, lag: int) -> list[WalkBeat]:
    """The sample beats of a beat-schedule frame (``beat_frames.BeatFrame``, after the
    golden frame) in the order the front end emits them (``beat_frames.expected_requests``:
    every walked beat but row 0 of slice 0 emits the sample beat of its row below), each
    with its skew, lane positions, valid lanes (below NI where the beat runs, none
    elsewhere), control bits and EOSS (the last beat of its sample slice), as tb/cube4_gra
    feeds them to GRA's beat build."""
    from .beat_frames import expected_requests
    trav = bf.trav
    nj, ni, nk = trav.nj, trav.ni, trav.nk
    fi, fj, fk = (bool(trav.flip[a]) for a in (trav.axis_i, trav.axis_j, trav.major))
    order = [(row[0], row[1], pb, leave) for _k, _j, pb, _r, emit, leave, row, *_ in expected_requests(bf, p, lag)
             if emit]
    out = []
    for n, (m, j, pb, leave) in enumerate(order):
        cj = nj - 1 - (j + 1) if fj else j + 1
        k0 = m // trav.supersample          # the sample slice's lower voxel slice
        ck = nk - 1 - k0 if fk else k0
        skew = (cj + ck + sum(int(o) for o in trav.origin)) % p
        pos = lane_positions(skew, pb, p, ni, fi)
        valid = (pos < ni) & bool(leave)
        (sx, sy), (sx1, sy1), (sxb, syb) = (trav.steps(k) for k in (m, m + 1, m - 1))
        ysf, ysb = int(sy1 - sy), int(sy - syb)
        ctrl = ((int(sx1 - sx) << CTRL_SX) | (ysf << CTRL_SY) | (int(sx - sxb) << CTRL_OSX) | (ysb << CTRL_OSY)
                | (int(n == 0) << CTRL_SOP) | (int(n == len(order) - 1) << CTRL_EOP) | (int(j == nj - 1) << CTRL_YLAST))
        eoss = int(n == len(order) - 1 or order[n + 1][0] != m)
        out.append(WalkBeat(m, j, pb, skew, pos, valid, ctrl, ysf, ysb, eoss))
    return out

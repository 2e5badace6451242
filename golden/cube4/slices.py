"""Slice rectangles: empty-space skipping finer than the box (docs/numerics.md §18).

The box of ``cube4.skip`` is one rectangle for every sample slice. Here each sample slice
m of a frame gets its own rectangle R(m) = rows [j0, j1) × columns [i0, i1) of the
traversal frame (empty where the slice holds nothing that counts), and the frame is
specified as the hardware would run it: a slice traverses only the partial beams of its
rectangle, in the same raster order. This module is the specification of that schedule;
a RECTS = 1 build of cube4_top runs it (S = 1; ``cube4 render --rects``;
docs/architecture.md, "Empty-space skipping").

What a slice computes (``model.render_frame`` with ``rects``):

* **Traversed.** Slice m traverses R(m) and, where the template steps into it (old
  Y-step, old X-step), the row j0 - 1 and the column i0 - 1 before it: the rays of R(m)'s
  first row and column come from there, and COM hands their partial results on through
  the beats at those positions (its beam buffer and the previous beat), so those beats
  must run. TRI reads the voxels of the traversed rectangle only (of both voxel slices
  a sample slice interpolates); a voxel outside reads as zero, and a sample outside is
  zero (what GRA and the gradient of a neighbour see).
* **Inside.** A sample of R(m) lies inside when its position stays within the rectangle's
  voxels: rows j0 <= j < j1 - [wy > 0], columns i0 <= i < i1 - [wx > 0] (the rule the
  box's high faces follow, numerics.md §4), and inside the frame's box. Only inside
  samples count, and they read only voxels of R(m): they are computed exactly as in the
  whole frame.
* **Rays.** A ray is inside on a run of consecutive slices (guaranteed below); it starts
  with its first inside sample (as it started, since nothing before changed it) and
  finishes, leaving on the pixel stream, with its last.

How the host chooses R(m) (``plan_rects``), for one frame (its traversal and the LUT):

1. **Counting samples.** A sample of slice m lies in the 2×2×2 cell (m // S, j, i) of
   the traversal frame, and its value lies within that cell's [min, max]; the cell is
   *busy* when a value in that range counts (``skip.busy_cells``, the same test as the
   box's, here on the traversal-frame volume) and the cut plane does not remove it whole.
2. **Needed samples.** The samples of busy cells; with GRA also those its stencil reads
   around them (slices m ± 1, rows j ± 1, columns i ± 1, a superset of the shear's
   neighbours). With voxel gradients or no gradient, the busy samples alone.
3. **Footprint.** R(m) holds every needed sample of slice m and the voxels it reads
   (rows j, j + 1, columns i, i + 1): the bounding rectangle of the needed samples grown by
   one row and one column at the high side.
4. **One run per ray.** In base-plane (ray) coordinates a ray of row ``by`` is inside
   slice m when A(m) <= by <= B(m), with A(m) = j0(m) - sy(m) and
   B(m) = j1(m) - 1 - sy(m) - [wy(m) > 0]. The host replaces A by its valley envelope
   (the larger of its running minimum from the front and from the back: non-increasing,
   then non-decreasing, never above A) and B by its peak envelope (never below B), then
   returns to j0, j1. A ray's slices are then one run, and the rectangles only grew.
   Columns alike with sx, wx. The first and last slices with anything needed bound the
   runs; slices before and after them are empty, and one between them with nothing
   needed gets the envelopes' rectangle (empty where no ray crosses it).

**GRA's walk** (``SliceRects.walk``, frames that GRA shades). GRA finishes the gradient
of sample (m, j, pb) when the beat (m + 1, j + 1, pb) arrives (it needs slice m + 1 and
row j + 1), so the front end walks, for slice m + 1, its traversed rectangle T(m + 1)
and rows T(m).j0 .. T(m).j1 over T(m)'s partial beams (row NJ, past the last, holds
no sample), and one partial beam below T(m)'s first where T(m - 1) reaches it (the
back neighbour i - 1 of a lane at t = 0 comes from the previous beat): the bounding
rectangle of the three. The beats outside T(m + 1) carry no sample (no lane valid, no
voxel read); GRA forwards only the beats of T(m). After the last slice with a rectangle
GRA walks the rest itself (cube4_gra).

Cost (``SliceRects.beats``): slice m walks its rows over its partial beams, plus one
flush beam that emits its last row when the next slice walks other partial beams or it
is the last (otherwise the next slice's first beam emits it, as in the fixed schedule);
one drain beat ends the frame. With every rectangle the whole box and no GRA, that is
the fixed schedule's (M·NJ + 1)·NB + 1 beats.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass

import numpy as np

from .clip import Clip
from .skip import busy_cells, cut_cells_traversal
from .view import Traversal


@dataclass(frozen=True)
class SliceRects:
    """The rectangles of one frame: per sample slice m, rows [j0, j1) and columns [i0, i1)
    of the traversal frame (j0 == j1: the slice is not traversed)."""

    trav: Traversal
    j0: np.ndarray
    j1: np.ndarray
    i0: np.ndarray
    i1: np.ndarray
    table_s: float = 0.0
    gra: bool = False

    def empty(self, m: int) -> bool:
        return not (0 <= m < self.j0.size) or self.j1[m] <= self.j0[m] or self.i1[m] <= self.i0[m]

    def bounds(self, m: int) -> tuple[int, int, int, int]:
        """(j0, j1, i0, i1) of slice m; (0, 0, 0, 0) where it is not traversed."""
        if self.empty(m):
            return 0, 0, 0, 0
        return int(self.j0[m]), int(self.j1[m]), int(self.i0[m]), int(self.i1[m])

    def traversed(self, m: int) -> tuple[int, int, int, int]:
        """(j0, j1, i0, i1) that slice m traverses: R(m) and, where the template steps into
        slice m (old Y-step, old X-step), the row and the column before it, whose rays'
        partial results COM hands on (module docstring); (0, 0, 0, 0) where it is empty."""
        if self.empty(m):
            return 0, 0, 0, 0
        j0, j1, i0, i1 = self.bounds(m)
        (sx, sy), (sxb, syb) = self.trav.steps(m), self.trav.steps(m - 1)
        return max(0, j0 - int(sy - syb)), j1, max(0, i0 - int(sx - sxb)), i1

    def inside(self, m: int) -> np.ndarray:
        """(nj, ni) bool: the samples of slice m inside its rectangle (module docstring);
        the caller intersects with the frame's inside mask."""
        out = np.zeros((self.trav.nj, self.trav.ni), dtype=bool)
        if self.empty(m):
            return out
        j0, j1, i0, i1 = self.bounds(m)
        wx, wy, _ = (int(w) for w in self.trav.weights(m))
        out[j0:j1 - (wy > 0), i0:i1 - (wx > 0)] = True
        return out

    def walk(self, m: int, p: int) -> tuple[int, int, int, int] | None:
        """Rows [j0, j1) and partial beams [pb0, pb1] the front end walks for slice m on P
        pipelines (None: none). Without GRA the traversed rectangle; with GRA (``gra``)
        its bounding rectangle with the walk GRA needs to finish slice m - 1 (module
        docstring, "GRA's walk"): rows T(m-1).j0 .. T(m-1).j1 (one below the rectangle,
        up to row NJ, which holds no sample) over T(m-1)'s partial beams, and one partial
        beam below T(m-1)'s first where T(m-2) reaches it."""
        cur = self.beams(m, p)
        if not self.gra:
            return cur
        prev, prev2 = self.beams(m - 1, p), self.beams(m - 2, p)
        parts = [cur] if cur is not None else []
        if prev is not None:
            parts.append((prev[0], prev[1] + 1, prev[2], prev[3]))
        if not parts:
            return None
        j0, j1 = min(b[0] for b in parts), max(b[1] for b in parts)
        pb0, pb1 = min(b[2] for b in parts), max(b[3] for b in parts)
        if prev is not None and prev2 is not None:
            pb0 = min(pb0, max(prev2[2], prev[2] - 1))
        return j0, j1, pb0, pb1

    def beams(self, m: int, p: int) -> tuple[int, int, int, int] | None:
        """The traversed rectangle of slice m as rows [j0, j1) and partial beams [pb0, pb1]."""
        if self.empty(m):
            return None
        j0, j1, i0, i1 = self.traversed(m)
        return j0, j1, i0 // p, (i1 - 1) // p

    def last(self) -> int:
        """The last slice with a rectangle (-1: none): the front end's walk ends with it."""
        live = [m for m in range(self.j0.size) if not self.empty(m)]
        return live[-1] if live else -1

    def beam_range(self, m: int, p: int) -> tuple[int, int] | None:
        """The partial beams [pb0, pb1] the front end walks for slice m (None: none)."""
        w = self.walk(m, p)
        return None if w is None else (w[2], w[3])

    def flushes(self, m: int, p: int) -> bool:
        """A flush beam emits slice m's last row: the last slice, or the next walks other
        partial beams."""
        return m == self.last() or self.beam_range(m + 1, p) != self.beam_range(m, p)

    def slice_beats(self, m: int, p: int) -> int:
        """Beats slice m takes on P pipelines: each row it walks, and a flush beam that
        emits its last row unless the next slice walks the same partial beams (then
        that slice's first beam emits it, as in the fixed schedule), each of the partial
        beams it walks."""
        w = self.walk(m, p)
        if w is None or m > self.last():
            return 0
        return (w[1] - w[0] + int(self.flushes(m, p))) * (w[3] - w[2] + 1)

    def beats(self, p: int) -> int:
        """Beats of the whole frame (every slice's, and the drain beat)."""
        total = sum(self.slice_beats(m, p) for m in range(self.j0.size))
        return total + 1 if total else 0

    def gra_steps(self, p: int) -> int:
        """The steps GRA walks on its own after the front end's last beat (cube4_gra
        RECTS = 1): the rows of the last slice's walk and one more (up to row NJ) over its
        partial beams, which finish its centres, and three that push the window empty."""
        last = self.last()
        if last < 0:
            return 0
        j0, j1, pb0, pb1 = self.walk(last, p)
        return (min(j1, self.trav.nj) - j0 + 1) * (pb1 - pb0 + 1) + 3

    def emitted(self, p: int) -> list[tuple[int, int, int, int]]:
        """The front end's sample beats (m, j, pb, cycle) in order, without stalls: pass m
        reads its walk's rows, a row leaves with the next row's beam, the last with the
        next pass's first beam or its own flush beam; an empty pass takes one cycle."""
        out, c, pend = [], 0, None
        for m in range(self.last() + 1):
            w = self.walk(m, p)
            if w is None:
                c += 1
                continue
            j0, j1, pb0, pb1 = w
            for row in range(j0, j1):
                for pb in range(pb0, pb1 + 1):
                    if row > j0:
                        out.append((m, row - 1, pb, c))
                    elif pend is not None:
                        out.append((pend[0], pend[1], pb, c))
                    c += 1
            if self.flushes(m, p):
                for pb in range(pb0, pb1 + 1):
                    out.append((m, j1 - 1, pb, c))
                    c += 1
                pend = None
            else:
                pend = (m, j1 - 1)
        return out

    def com_waits(self, p: int) -> int:
        """The beats COM would make wait, without stalls: a beat whose base-plane slot
        (j, pb) a beat fewer than COM_MIN_SLICE cycles before it wrote (cube4_com's
        read-after-write rule by position). COM sees the traversed rectangles' beats, as
        the front end emits them or, with GRA's walk, as GRA finishes them (the beat
        (m + 1, j + 1, pb) of the walk and two steps, then GRA's own steps). The frame's
        cycles are predicted exactly when this is 0; the renderer's scenes give 0, random
        sparse rectangles with slices of a few beats do not."""
        from .cycles import COM_MIN_SLICE
        em = self.emitted(p)
        if self.gra and em:
            steps = [e[3] for e in em]
            last = self.last()
            j0, j1, pb0, pb1 = self.walk(last, p)
            gen = [(last + 1, r, pb) for r in range(j0, min(j1, self.trav.nj) + 1) for pb in range(pb0, pb1 + 1)]
            steps += [steps[-1] + 1 + k for k in range(len(gen) + 3)]
            seq = [e[:3] for e in em] + gen
            arrivals = []
            for k, (m, j, pb) in enumerate(seq):
                b = self.beams(m - 1, p)
                if b is not None and b[0] <= j - 1 < b[1] and b[2] <= pb <= b[3]:
                    arrivals.append((j - 1, pb, steps[k + 2]))
        else:
            arrivals = [(j, pb, c) for m, j, pb, c in em if self.beams(m, p) is not None
                        and self.beams(m, p)[0] <= j < self.beams(m, p)[1]]
        seen, waits = {}, 0
        for j, pb, c in arrivals:
            if (j, pb) in seen and c - seen[(j, pb)] < COM_MIN_SLICE:
                waits += 1
            seen[(j, pb)] = c
        return waits

    def empty_walks(self, p: int) -> int:
        """Slices before the last that walk nothing: one idle cycle each in the front end."""
        return sum(1 for m in range(self.last()) if self.walk(m, p) is None)

    def fraction(self) -> float:
        """Samples traversed / samples of the frame."""
        t = self.trav
        area = 0
        for m in range(self.j0.size):
            j0, j1, i0, i1 = self.traversed(m)
            area += (j1 - j0) * (i1 - i0)
        return float(area) / float(t.num_sample_slices * t.nj * t.ni)


def whole_box_rects(trav: Traversal) -> SliceRects:
    """Every slice's rectangle the whole box: the fixed schedule, as a table."""
    need = np.ones((trav.num_sample_slices, trav.nj, trav.ni), dtype=bool)
    return rects_from_needed(need, trav)


def busy_traversal(vol: np.ndarray, trav: Traversal, lut: np.ndarray, mode: str,
                   clip: Clip | None = None) -> np.ndarray:
    """(nk, nj, ni) bool: the busy cells of the traversal frame (cell (k, j, i) holds the
    voxels k … k+1, j … j+1, i … i+1), less those the cut plane removes whole."""
    busy = busy_cells(np.ascontiguousarray(trav.to_traversal(vol)), lut, mode)
    if clip is not None and clip.plane is not None:
        busy &= ~cut_cells_traversal(trav, clip.plane)
    return busy


def _dilate(a: np.ndarray, axes) -> np.ndarray:
    """a grown by one cell both ways along each of ``axes`` (a box, not a cross)."""
    out = a.copy()
    for ax in axes:
        grown = out.copy()
        lo = [slice(None)] * a.ndim
        hi = [slice(None)] * a.ndim
        lo[ax], hi[ax] = slice(0, -1), slice(1, None)
        grown[tuple(lo)] |= out[tuple(hi)]
        grown[tuple(hi)] |= out[tuple(lo)]
        out = grown
    return out


def needed_samples(busy: np.ndarray, trav: Traversal, stencil: bool) -> np.ndarray:
    """(M, nj, ni) bool: the samples a frame must compute exactly (module docstring, 2)."""
    m = np.arange(trav.num_sample_slices)
    need = busy[m // trav.supersample]
    return _dilate(need, (0, 1, 2)) if stencil else need


def _envelope(v: np.ndarray, valley: bool) -> np.ndarray:
    """The valley (running minima's larger) or peak (running maxima's smaller) envelope."""
    acc = np.minimum.accumulate if valley else np.maximum.accumulate
    front, back = acc(v), acc(v[::-1])[::-1]
    return np.maximum(front, back) if valley else np.minimum(front, back)


def _axis_bounds(lo: np.ndarray, hi: np.ndarray, step: np.ndarray, frac: np.ndarray, n: int):
    """Rectangle bounds [lo, hi) of one axis made one run per ray (module docstring, 4)."""
    a = _envelope(lo - step, valley=True)
    b = _envelope(hi - 1 - step - (frac > 0), valley=False)
    lo2 = np.clip(a + step, 0, n)
    hi2 = np.clip(b + 1 + step + (frac > 0), 0, n)
    return lo2, hi2


def rects_from_needed(need: np.ndarray, trav: Traversal) -> SliceRects:
    """The rectangles that hold ``need`` (M, nj, ni) and the voxels it reads, one run per ray."""
    M, nj, ni = need.shape
    rows, cols = need.any(axis=2), need.any(axis=1)
    live = np.nonzero(rows.any(axis=1))[0]
    z = np.zeros(M, dtype=np.int64)
    if live.size == 0:
        return SliceRects(trav, z, z.copy(), z.copy(), z.copy())
    ma, mb = int(live[0]), int(live[-1]) + 1
    ms = np.arange(ma, mb)
    sx, sy = (np.asarray(s, dtype=np.int64) for s in trav.steps(ms))
    wx, wy, _ = (np.asarray(w, dtype=np.int64) for w in trav.weights(ms))

    big = 2 * (nj + ni + M) + 4      # beyond every bound: an empty slice bounds nothing

    def first_end(flags: np.ndarray, n: int):
        """Per slice: the first needed position, and one past the last plus the voxel
        read at the high side; (big, -big) where nothing is needed, which bounds nothing."""
        has = flags.any(axis=1)
        first = np.argmax(flags, axis=1)
        last = n - 1 - np.argmax(flags[:, ::-1], axis=1)
        return np.where(has, first, big), np.where(has, last + 2, -big)

    j_lo, j_hi = first_end(rows[ma:mb], nj)
    i_lo, i_hi = first_end(cols[ma:mb], ni)
    j0, j1 = _axis_bounds(j_lo, j_hi, sy, wy, nj)
    i0, i1 = _axis_bounds(i_lo, i_hi, sx, wx, ni)
    out = [z.copy() for _ in range(4)]
    for arr, val in zip(out, (j0, j1, i0, i1)):
        arr[ma:mb] = val
    return SliceRects(trav, *out)


def plan_rects(vol: np.ndarray, trav: Traversal, lut: np.ndarray, mode: str, *, gra: bool,
               clip: Clip | None = None) -> SliceRects:
    """The slice rectangles of one frame: ``vol`` its voxel values (vol[z, y, x] of
    trav.dims), ``lut`` the classification LUT loaded for it, ``gra`` whether GRA shades
    it (a shaded composite frame without voxel gradients: GRA's stencil reads the samples
    around those that count), ``clip`` its cut plane."""
    t0 = time.perf_counter()
    busy = busy_traversal(vol, trav, lut[:, :4], mode, clip)
    need = needed_samples(busy, trav, gra)
    return dataclasses.replace(rects_from_needed(need, trav), table_s=time.perf_counter() - t0, gra=gra)

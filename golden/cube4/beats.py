"""Beat skipping and ray termination: the specification (docs/numerics.md §19).

The box of ``cube4.skip`` and the slice rectangles of ``cube4.slices`` are planned per
view. Here a frame decides per beat (one partial beam of one row of one sample slice)
whether it runs, from three sources:

* **The block table** (``BlockTable``), independent of the view. The volume is cut into
  blocks of B×B×B voxels (the memory image's axes). For each block the host keeps the
  minimum and maximum voxel over the block grown by ``MARGIN`` voxels on every side
  (once per volume), and one bit per block: does a value in that range count
  (``skip.counting_values``, two reads of the LUT's prefix sum; once per transfer
  function). A sample *may count* when the block of its first voxel (i, j, m // S of the
  traversal frame, in the volume's axes) has its bit set. The margin of 2 makes that
  test cover every sample that counts and every sample the gradient of a counting
  sample reads: a sample lies in the 2×2×2 cell at its first voxel c, its gradient's
  neighbours have first voxels within ±1 of c along every axis, so a counting cell lies
  within c' − 2 … c' + 2 of each neighbour's first voxel c' whichever way the axes are
  flipped.
* **The stop** (``BeatSchedule.stop``), per ray of the base plane, per view: the slice
  after the last in which its sample may count, and with depth in (numerics.md §22) no
  later than the geometry's stop. The host computes it from the block table's bits in
  the frame and writes it with the view's registers.
* **COM's reports**, per ray, after each slice d (``TerminationRule``): *done*, no later
  sample may change it (transmittance at or below τ; X-ray also every colour saturated;
  MIP and MinIP holding the volume's largest or smallest value). A report of slice d
  brings the ray's end forward to d + lag + 1 (lag ≥ 2): the traversal, which decides
  slice m while COM is still at most lag slices behind, acts on it from slice
  d + lag + 1 on, and decides slices before it alike whether the report has arrived.

**Runs** (``BeatSchedule.running_rays``). A ray runs slice m when its first sample that
may count lies in a slice ≤ m and m lies before its end (its stop, or lag + 1 slices
after the slice COM reported it done). So each ray runs one interval of slices, as COM
needs (a ray's partial result sits at the position of its latest sample; numerics.md §18
for the rectangles' same rule): it starts fresh at its first slice that may count, and
finishes, leaving on the pixel stream, at the last slice of its interval. Only samples
of running rays that may count are counted; a done ray counts no further sample (with
τ = 0 such a sample would add nothing). Without termination every interval is known
when the frame starts (first slice, stop), and so are the frame's beats.

**Beats.** A beat *runs* when one of its lanes holds a running ray (set A), or, with
termination or depth in's stops (``limit_stop``) in a shaded frame, when it may count and
lies next to (±1 slice, row and partial beam) a beat of A (the neighbours whose samples
the gradients of A's counting samples read, where termination or the geometry ended
their own rays). Samples of beats that do not run are zero (what GRA
reads). Every sample that counts, and every sample its gradient reads, runs and is
computed from the voxels the fixed schedule uses: the base plane is the fixed
schedule's, bit for bit, at τ = 0.

**The walk.** The front end reads, for a running beat, the voxel beats its samples
interpolate: rows j and j + 1 and partial beams pb and pb + 1 (the beam-extension
neighbour) of both voxel slices. A pass that reads a voxel slice for the slice buffers
(S > 1: pass 0 and each pass k0·S + 1, as the fixed schedule) walks all of its rows, for
the passes that replay the slice may run any of its beats; the other passes walk their
running beats alone. Each walked voxel beat emits the sample beat of
the row below (its lanes valid where that beat runs), so COM sees, before each running
sample beat, the row above at its partial beam (through which its beam buffer brings the
partial results of a Y-step). COM's X-step hop takes the lane at t = 0's partial result
from the beat just before (the same row, the partial beam before): the walk also visits,
in each row, the partial beam before each beat that runs in the emitted row or the row
after, without reads where it reads nothing (``walk_rows``: the cover). The walk's beats
are those; each takes a cycle and a beat that is not walked takes none (``walk_beats``).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from .modes import MODES
from .skip import counting_values
from .view import Traversal

#: voxels a block's value range reaches beyond the block on every side (see above)
MARGIN = 2
#: default block edge B and default lag (slices between COM's report and the traversal's use)
BLOCK = 4
LAG = 4
#: the fewest rows NJ of a frame whose rays the host lets end early: the RTL's decisions
#: wait for COM's reports, and with LAG = 4 that loop is free of deadlock only when the
#: front end's walk, five rows ahead of its emitter, stays within two slices
#: (docs/architecture.md "Beat skipping and ray termination"); thinner frames run their
#: rays to their stops (exact either way)
TERM_MIN_ROWS = 3


def _axis_ranges(a: np.ndarray, axis: int, block: int, margin: int) -> tuple[np.ndarray, np.ndarray]:
    """min and max of ``a`` over windows [b·B − margin, b·B + B + margin) along ``axis``,
    clipped to the array (edge padding repeats voxels already in the window)."""
    n = a.shape[axis]
    nb = -(-n // block)
    width = block + 2 * margin
    hi_pad = nb * block + margin - n
    pad = [(0, 0)] * a.ndim
    pad[axis] = (margin, max(hi_pad, 0))
    p = np.pad(a, pad, mode="edge")
    lo = hi = None
    for o in range(width):
        idx = [slice(None)] * a.ndim
        idx[axis] = slice(o, o + nb * block, block)
        s = p[tuple(idx)]
        lo = s if lo is None else np.minimum(lo, s)
        hi = s if hi is None else np.maximum(hi, s)
    return lo, hi


@dataclass
class BlockTable:
    """The view-independent occupancy table of one volume: per block of B³ voxels, the
    value range over the block grown by MARGIN voxels; ``bits`` for one LUT. A labelled
    volume (cube4.labels: words label · 2^V + value) keeps the ranges of the values and,
    per label, the blocks whose grown region holds it (``labels``): a sample takes the
    label of one of its cell's corners and a value within the cell's range, so a block
    may count when, for a label it holds, a value in its range counts in that label's
    LUT block (numerics.md §24; a hidden label is empty space)."""

    block: int
    dims: tuple[int, int, int]          # (nx, ny, nz) of the volume
    lo: np.ndarray                      # (bz, by, bx)
    hi: np.ndarray
    build_s: float = 0.0                # host time for the ranges (once per volume)
    labels: dict | None = None          # label -> (bz, by, bx) bool: the grown block holds it

    @classmethod
    def of(cls, vol: np.ndarray, block: int = BLOCK, value_bits: int | None = None) -> "BlockTable":
        """``value_bits``: vol holds labelled words with values of that many bits."""
        if block < 1:
            raise ValueError(f"block must be at least 1, got {block}")
        t0 = time.perf_counter()
        labels = None
        if value_bits is not None:
            from .labels import split_words
            vals, labs = split_words(vol, value_bits)
            labels = {}
            for lb in np.unique(labs):
                m = (labs == lb).astype(np.int32)
                for axis in range(3):
                    _, m = _axis_ranges(m, axis, block, MARGIN)
                labels[int(lb)] = m > 0
            vol = vals
        v = vol.astype(np.int32)
        lo, hi = v, v
        for axis in range(3):
            lo, _ = _axis_ranges(lo, axis, block, MARGIN)
            _, hi = _axis_ranges(hi, axis, block, MARGIN)
        nz, ny, nx = vol.shape
        return cls(block, (nx, ny, nz), lo, hi, time.perf_counter() - t0, labels)

    def bits(self, lut: np.ndarray, mode: str) -> np.ndarray:
        """(bz, by, bx) bool: may a sample whose first voxel lies in the block count."""
        if self.labels is None:
            return self._range_bits(lut, mode)
        from .labels import lut_value_bits
        n = 1 << lut_value_bits(lut)
        out = np.zeros(self.lo.shape, dtype=bool)
        for lb, held in self.labels.items():
            out |= held & self._range_bits(lut[lb * n:(lb + 1) * n], mode)
        return out

    def _range_bits(self, lut: np.ndarray, mode: str) -> np.ndarray:
        flags = counting_values(lut, mode).astype(np.int64)
        prefix = np.concatenate([[0], np.cumsum(flags)])
        return prefix[self.hi + 1] - prefix[self.lo] > 0

    @property
    def entries(self) -> int:
        return int(self.lo.size)


def frame_occupancy(bits: np.ndarray, block: int, trav: Traversal) -> np.ndarray:
    """(nk, nj, ni) bool in ``trav``'s frame (a box placed at trav.origin of the volume):
    the bit of each voxel's block."""
    nx, ny, nz = trav.dims
    x0, y0, z0 = trav.origin
    zi = (np.arange(z0, z0 + nz) // block)[:, None, None]
    yi = (np.arange(y0, y0 + ny) // block)[None, :, None]
    xi = (np.arange(x0, x0 + nx) // block)[None, None, :]
    return np.ascontiguousarray(trav.to_traversal(bits[zi, yi, xi]))


@dataclass
class TerminationRule:
    """When a ray is done (numerics.md §19): mode, τ in Q0.ACC_W and the volume's value
    range (for MIP and MinIP)."""

    mode: str
    tau: int = 0
    one: int = 1 << 16
    vmin: int = 0
    vmax: int = 0
    enabled: bool = True
    value_bits: int = 8

    def __post_init__(self):
        if self.mode not in MODES:
            raise ValueError(f"mode must be one of {MODES}, got {self.mode!r}")
        if not 0 <= self.tau < self.one:
            raise ValueError(f"tau must be in 0 .. {self.one - 1} (Q0.ACC_W), got {self.tau}")

    def live(self, acc, trans, value, held) -> np.ndarray:
        """Per ray: its partial result is not the fresh one (a sample added to it)."""
        if self.mode in ("composite", "xray"):
            return (trans != self.one) | np.any(acc != 0, axis=0)
        fresh = (1 << self.value_bits) - 1 if self.mode == "minip" else 0
        return (value != fresh) | np.any(held != 0, axis=0)

    def dead(self, acc, trans, value) -> np.ndarray:
        """Per ray of the base plane: can no later sample change it (or, τ > 0, may none)."""
        if not self.enabled:
            shape = (trans if trans is not None else value).shape
            return np.zeros(shape, dtype=bool)
        if self.mode == "composite":
            return trans <= self.tau
        if self.mode == "xray":
            return (trans == 0) & np.all(acc == self.one, axis=0)
        return value == (self.vmax if self.mode == "mip" else self.vmin)


@dataclass
class BeatSchedule:
    """The beats of one frame (``trav``: the frame's box) and the state of its rays.

    ``occ`` (nk, nj, ni): the block table's bits in the frame. The golden model reports
    each slice's rays (``report``) before it asks for slice m + 1 … m + lag."""

    trav: Traversal
    p: int
    occ: np.ndarray
    lag: int = LAG
    terminate: bool = True
    gra: bool = True
    cut: bool = False                          # depth in cut some ray's stop (limit_stop)
    done: np.ndarray = field(init=False)      # (rows, cols): slice the ray was reported done (M: never)
    reported: int = field(init=False, default=-1)
    table_s: float = 0.0
    stop_s: float = 0.0                        # host time for the occupancy in the frame and the stops
    block_bits: np.ndarray | None = None       # the volume's block table bits (bz, by, bx) the host used
    _a: dict = field(init=False, default_factory=dict)
    _e: dict = field(init=False, default_factory=dict)

    def __post_init__(self):
        if self.lag < 2:
            raise ValueError(f"lag must be at least 2 slices, got {self.lag}")
        t = self.trav
        self.M, self.NJ, self.NI = t.num_sample_slices, t.nj, t.ni
        self.NB = -(-self.NI // self.p)
        self.rows, self.cols = t.baseplane_shape
        self.sxm, self.sym = t.max_steps
        self.done = np.full((self.rows, self.cols), self.M, dtype=np.int64)
        # per ray: the slices in which its sample may count, the first of them and the stop
        self.occ_ray = np.zeros((self.M, self.rows, self.cols), dtype=bool)
        for m in range(self.M):
            r0, c0 = self.window(m)
            self.occ_ray[m, r0:r0 + self.NJ, c0:c0 + self.NI] = self.sample_occ(m)
        self.first = first_counting(self.occ_ray)
        self.stop = last_counting(self.occ_ray) + 1
        self.end = self.stop.copy()

    def limit_stop(self, stop_m: np.ndarray) -> None:
        """Depth in: no ray runs past the geometry's stop (rows, cols) either. A ray that
        stops there before its last slice that may count leaves samples that its
        neighbours' gradients read: the beats beside A run for them (``neighbours``)."""
        if (np.asarray(stop_m) < self.stop).any():
            self.cut = True
        self.stop = np.minimum(self.stop, stop_m)
        self.end = np.minimum(self.end, self.stop)

    @property
    def neighbours(self) -> bool:
        """The beats that may count next to a beat of A run too (the view register NBR):
        in a frame with GRA where a ray may end before its last slice that may count, by
        termination or at depth in's stop, whose later samples its neighbours' gradients
        still read."""
        return self.gra and (self.terminate or self.cut)

    # --- geometry
    def window(self, m: int) -> tuple[int, int]:
        """(row, col) of slice m's sample (0, 0) in the base plane."""
        stx, sty = (int(v) for v in self.trav.steps(m))
        return self.sym - sty, self.sxm - stx

    def sample_occ(self, m: int) -> np.ndarray:
        return self.occ[m // self.trav.supersample]

    def _lanes_of(self, rays: np.ndarray, m: int) -> np.ndarray:
        """(nj, ni): the samples of slice m whose ray is set in ``rays`` (rows, cols)."""
        r0, c0 = self.window(m)
        return rays[r0:r0 + self.NJ, c0:c0 + self.NI]

    def _beats_of(self, mask: np.ndarray) -> np.ndarray:
        pad = np.zeros((self.NJ, self.NB * self.p), dtype=bool)
        pad[:, :self.NI] = mask
        return pad.reshape(self.NJ, self.NB, self.p).any(-1)

    # --- rays
    def running_rays(self, m: int) -> np.ndarray:
        """(rows, cols): rays that run slice m: first ≤ m < end. The end as of COM's report
        of slice m − lag − 1 (a later report moves it to m + 1 or beyond: the same answer)."""
        k = m - self.lag - 1
        if k > self.reported:
            raise RuntimeError(f"slice {m} needs COM's report of slice {k} (have {self.reported})")
        return (self.first <= m) & (m < self.end)

    def running(self, m: int) -> np.ndarray:
        """(nj, ni): samples of slice m whose ray runs (they are the only ones that count)."""
        if not 0 <= m < self.M:
            return np.zeros((self.NJ, self.NI), dtype=bool)
        return self._lanes_of(self.running_rays(m), m)

    def report(self, m: int, dead: np.ndarray) -> None:
        """COM's report after slice m, per ray of the base plane: ``dead``, no later sample
        may change it. A running ray's end moves to m + lag + 1."""
        if m != self.reported + 1:
            raise RuntimeError(f"reports come slice by slice: got {m} after {self.reported}")
        if self.terminate:
            new = dead & (self.done == self.M) & self.running_rays(m)
            self.done[new] = m
            self.end[new] = np.minimum(self.end[new], m + self.lag + 1)
        self.reported = m

    # --- beats
    def active_beats(self, m: int) -> np.ndarray:
        """(nj, nb): beats of slice m with a lane of a running ray (set A)."""
        if not 0 <= m < self.M:
            return np.zeros((self.NJ, self.NB), dtype=bool)
        if m not in self._a:
            self._a[m] = self._beats_of(self.running(m))
        return self._a[m]

    def run_beats(self, m: int) -> np.ndarray:
        """(nj, nb): beats of slice m that run: A, and with GRA the beats that may count
        next to a beat of A (rays that ended there still feed A's gradients)."""
        if not 0 <= m < self.M:
            return np.zeros((self.NJ, self.NB), dtype=bool)
        if m not in self._e:
            a = self.active_beats(m)
            e = a
            if self.neighbours:
                near = dilate(np.stack([self.active_beats(m - 1), a, self.active_beats(m + 1)]))[1]
                e = a | (near & self._beats_of(self.sample_occ(m)))
            self._e[m] = e
        return self._e[m]

    def run_samples(self, m: int) -> np.ndarray:
        """(nj, ni): samples of slice m in running beats."""
        b = np.repeat(self.run_beats(m), self.p, axis=1)
        return b[:, :self.NI]

    # --- the walk
    def footprint(self, beats: np.ndarray) -> np.ndarray:
        """(nj + 1, nb): the voxel beats (rows j, j + 1; partial beams pb, pb + 1) that
        the sample beats read."""
        f = np.zeros((self.NJ + 1, self.NB + 1), dtype=bool)
        f[:-1, :-1] |= beats
        f[1:, :-1] |= beats
        f[:, 1:] |= f[:, :-1].copy()
        return f[:, :self.NB]

    def reads_slice(self, m: int) -> bool:
        """Does pass m read a voxel slice for the slice buffers (S > 1: pass 0 slice 0,
        pass k0·S + 1 slice k0 + 1; the fixed schedule's passes that read the memory)?"""
        S = self.trav.supersample
        return S > 1 and (m == 0 or m % S == 1)

    def walk(self, m: int) -> np.ndarray:
        """(nj + 1, nb): the front end's beats of slice m (call after the frame). A pass
        that reads a voxel slice for the slice buffers (``reads_slice``) walks all of its
        rows: the passes that replay the slice may run any of its beats."""
        f = self.footprint(self.run_beats(m))
        if self.reads_slice(m):
            f[:self.NJ] = True
        return f


def first_counting(occ_ray: np.ndarray) -> np.ndarray:
    """(rows, cols): per ray the first slice of ``occ_ray`` (M, rows, cols) in which its
    sample may count, M where none may."""
    m = occ_ray.shape[0]
    return np.where(occ_ray.any(0), np.argmax(occ_ray, axis=0), m)


def last_counting(occ_ray: np.ndarray) -> np.ndarray:
    """(rows, cols): per ray the last slice of ``occ_ray`` (M, rows, cols) in which its
    sample may count, −1 where none may."""
    m = occ_ray.shape[0]
    return np.where(occ_ray.any(0), m - 1 - np.argmax(occ_ray[::-1], axis=0), -1)


def dilate(b: np.ndarray) -> np.ndarray:
    """(n0, n1, n2) bool grown by one along every axis, diagonals included."""
    out = b.copy()
    for axis in range(3):
        grown = out.copy()
        lo = [slice(None)] * 3
        hi = [slice(None)] * 3
        lo[axis], hi[axis] = slice(1, None), slice(None, -1)
        grown[tuple(lo)] |= out[tuple(hi)]
        grown[tuple(hi)] |= out[tuple(lo)]
        out = grown
    return out


@dataclass
class BeatStats:
    """What one frame's beat schedule ran and skipped."""

    box_beats: int          # the fixed schedule's sample beats in the frame's box (M·NJ·NB)
    run_beats: int          # sample beats that ran
    skipped_empty: int      # skipped, and would be without termination
    skipped_terminated: int  # skipped because their rays were done
    walk_beats: int         # the front end's beats (reads included)
    table_s: float = 0.0    # host: the block table (per volume and transfer function)
    stop_s: float = 0.0     # host: the rays' stops (per view)
    ray_samples: int = 0    # samples of running rays (a schedule packing them into full beats: /P beats)
    decided: dict = field(default_factory=dict)   # rate -> decided_cycles
    gra_cycles: int = 0     # GRA's beat source's cycles (gra_cycles summed; builds with GRA)

    def as_dict(self) -> dict:
        d = {k: getattr(self, k) for k in ("box_beats", "run_beats", "skipped_empty", "skipped_terminated",
                                           "walk_beats", "table_s", "stop_s", "ray_samples", "gra_cycles")}
        d["decided_cycles"] = {str(r): c for r, c in self.decided.items()}
        return d


def walk_rows(sched: BeatSchedule, with_a: bool = False) -> list[tuple]:
    """The front end's rows in order, (m, j, reads, leaves, cover): for sample slice m and
    row j the voxel beats it reads (NB bools: the walk's row j, and in row 0 also the
    previous slice's row NJ, the read that completes its last row: Y-wrap, as in the fixed
    schedule), the running beats of the sample row that leaves with them (the previous row
    in this order: row j − 1, or the previous slice's row NJ − 1), and the beats it walks
    without reads for COM (the cover: the partial beam before each running beat of the
    leaving row and of the row after it in this order, where the row reads nothing); after
    the last slice a flush row (m = M, j = 0) that reads nothing new. The walk's beats of a
    row are reads | cover. ``with_a``: a sixth entry, the leaving row's beats that hold a
    running ray (``active_beats``; the others run as GRA's neighbours only)."""
    rows = []
    nothing = np.zeros(sched.NB, dtype=bool)

    def cover(reads, leaves, after):
        either = leaves | after
        before = np.zeros_like(either)
        before[:-1] = either[1:]         # pb − 1 of a running beat
        return before & ~reads

    carry, prev, prev_a = nothing, nothing, nothing
    for m in range(sched.M):
        w, e, a = sched.walk(m), sched.run_beats(m), sched.active_beats(m)
        reads = w[0] | carry
        rows.append((m, 0, reads, prev, cover(reads, prev, e[0]), prev_a))
        rows += [(m, j, w[j], e[j - 1], cover(w[j], e[j - 1], e[j]), a[j - 1]) for j in range(1, sched.NJ)]
        carry, prev, prev_a = w[sched.NJ], e[sched.NJ - 1], a[sched.NJ - 1]
    rows.append((sched.M, 0, carry, prev, cover(carry, prev, nothing), prev_a))
    return rows if with_a else [r[:5] for r in rows]


def slice_walks(sched: BeatSchedule, rows: list | None = None) -> np.ndarray:
    """(M + 1,): the front end's beats per slice (``walk_rows``, or ``rows`` already
    taken from it), the flush row last."""
    out = np.zeros(sched.M + 1, dtype=np.int64)
    for m, _, reads, _, cover, *_ in (rows if rows is not None else walk_rows(sched)):
        out[m] += int((reads | cover).sum())
    return out


def walker_cycles(sched: BeatSchedule, rows: list | None = None) -> np.ndarray:
    """(M + 1,): cycles per slice of a walk that emits one voxel beat a cycle and spends
    one on a row that walks nothing (``walk_rows``, or ``rows``; the flush row last)."""
    out = np.zeros(sched.M + 1, dtype=np.int64)
    for m, _, reads, _, cover, *_ in (rows if rows is not None else walk_rows(sched)):
        out[m] += max(1, int((reads | cover).sum()))
    return out


def gra_cycles(sched: BeatSchedule, rows: list | None = None) -> np.ndarray:
    """(M + 1,): the cycles per slice of GRA's beat source (``cube4_gra_beats``) when it
    never waits for its input or output: the steps of slice w, rows r = 0 … NJ, are the
    sample beats that came in for (w, r) (the walk emits one for every beat it walks,
    ``walk_rows``, or ``rows`` already taken from it) with the steps the centres of slice
    w − 1 need, C(w − 1, r − 1) ∪ C(w − 1, r); a row of n ≥ 2 steps takes n cycles, of one
    step two, of none one; each slice ends with two window steps; slice M (last) steps what
    the last slice's centres need. A lower bound on the cycles of a frame through a build
    with GRA, as ``walker_cycles`` is for every build: the two units step at most once a
    cycle each. Against the box (a frame in which every beat runs) it adds row NJ and the
    two window steps to each slice, NB + 2 cycles: what makes the beat schedule slower
    than the box on small frames that skip little (docs/architecture.md)."""
    nothing = np.zeros(sched.NB, dtype=bool)
    came = {}
    for m, j, reads, _, cover, *_ in (rows if rows is not None else walk_rows(sched)):
        w, r = (m, j - 1) if j > 0 else (m - 1, sched.NJ - 1)
        if w >= 0:
            came[w, r] = reads | cover

    def c(w: int, r: int) -> np.ndarray:
        return came.get((w, r), nothing) if 0 <= r < sched.NJ else nothing

    out = np.zeros(sched.M + 1, dtype=np.int64)
    for w in range(sched.M + 1):
        for r in range(sched.NJ + 1):
            n = int((c(w, r) | c(w - 1, r - 1) | c(w - 1, r)).sum())
            out[w] += n if n >= 2 else 2 if n == 1 else 1
        out[w] += 2
    return out


def walk_beats(sched: BeatSchedule) -> int:
    """The front end's beats of a frame (``slice_walks`` summed): the figure for a front
    end that passes over a skipped beat in no cycle."""
    return int(slice_walks(sched).sum())


#: decisions per cycle of the front ends ``decided_cycles`` models in reports/skipping.md
DECIDE_RATES = (1, 2, 4)


def decided_cycles(sched: BeatSchedule, rate: int, walker: np.ndarray | None = None) -> int:
    """The front end's cycles when it decides ``rate`` beats a cycle a slice ahead of its
    walk: a slice takes at least its NJ·NB beats / rate cycles to decide and its
    ``walker_cycles`` (or ``walker``, already computed) to walk, and the two overlap."""
    if rate < 1:
        raise ValueError(f"rate must be at least 1, got {rate}")
    w = walker_cycles(sched) if walker is None else walker
    per = -(-sched.NJ * sched.NB // rate)
    return int(np.maximum(w[:-1], per).sum() + w[-1])


def schedule_stats(sched: BeatSchedule, table_s: float = 0.0) -> BeatStats:
    """The frame's counts, after the frame (every slice reported)."""
    run = sum(int(sched.run_beats(m).sum()) for m in range(sched.M))
    rows = walk_rows(sched)               # once: the walk, the walker and the decisions' cycles
    walk = int(slice_walks(sched, rows).sum())
    walker = walker_cycles(sched, rows)
    box = sched.M * sched.NJ * sched.NB
    if sched.terminate:
        free = BeatSchedule(sched.trav, sched.p, sched.occ, sched.lag, terminate=False, gra=sched.gra)
        free.limit_stop(sched.stop)    # the same stops (depth in's too); no ray ends before
        free.reported = sched.reported
        run_free = sum(int(free.run_beats(m).sum()) for m in range(free.M))
    else:
        run_free = run
    samples = sum(int(sched.running(m).sum()) for m in range(sched.M))
    decided = {r: decided_cycles(sched, r, walker) for r in DECIDE_RATES}
    return BeatStats(box, run, box - run_free, run_free - run, walk, table_s, sched.stop_s, samples, decided,
                     int(gra_cycles(sched, rows).sum()))

"""Empty-space skipping: the frame traverses only the box that can change a ray
(docs/numerics.md §15, docs/architecture.md "Empty-space skipping").

For one view, the host finds the smallest box of the traversed volume outside which no
sample can change any ray, and renders that box instead of the whole, as the crop box
and the bricks are rendered: the same view registers, the template's starting phase of
the box's first slice (``view.sub_traversal``), the cut plane moved into its frame, and
its base plane placed into the whole base plane. The image is the full schedule's bit
for bit:

* **Which values count.** A sample can change a ray only if its classification can:
  composite and X-ray, opacity > 0 (``w = round_shift(T·α, AW)`` is 0 for α = 0, so C
  and T stay as they are); MIP, a value at or above the lowest value whose LUT entry is
  not zero (a ray whose maximum lies below it ends with that zero entry either way);
  MinIP, at or below the highest such value. ``counting_values`` is that table, indexed
  by value; its prefix sum answers "does any value in [lo, hi] count" in two reads.
* **Busy cells.** A sample lies in one 2×2×2 cell of voxels and is a convex mix of them
  (every lerp stays between its ends), so its value lies in [min, max] of the cell.
  A cell is *busy* when a value in that range counts. A cell at a high face of the box
  takes its range from its voxels inside the box: a sample there that counts lies
  exactly on the face (weight 0 on the zero padding beyond it; the last column is
  outside when wx > 0, the last row when wy > 0, and the last sample slice lies on the
  last voxel slice).
* **The box** holds every busy cell with a margin: the voxels c − 1 … c + 2 of a busy
  cell at c, along every axis (tri-linear interpolation reads c … c + 1 and the
  gradient's neighbours at ±1 read c − 1 … c + 2; along a flipped axis the same range).
  So every sample that counts, and every sample its gradient reads, is computed from
  voxels inside the box exactly as in the whole volume; the samples beyond the box are
  empty and would not change any ray: rays start fresh at the box (the empty samples
  before it left them as they started) and leave it finished (the empty samples after
  it change nothing). Rays that never meet the box end as they started: zero.

The frame's cycles are the cycle formula's (``cube4.cycles``) with the box's dims: the
box is grown until a sample slice holds at least COM_MIN_SLICE beats, the least for
which the formula holds (``fit_slice``). A volume with no busy cell renders no frame at
all (0 cycles, a zero base plane).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from .clip import Clip, fit_regions, move_plane, move_regions, region_cells
from .cycles import COM_MIN_SLICE, frame_cycles
from .modes import MODES
from .view import Traversal, sub_traversal

#: voxels the box keeps below and above a busy cell's first voxel c: c - 1 ... c + 2
MARGIN_LOW = 1
MARGIN_HIGH = 2


def counting_values(lut: np.ndarray, mode: str) -> np.ndarray:
    """(2^V,) bool: the voxel values whose sample can change a ray in this mode."""
    if mode not in MODES:
        raise ValueError(f"mode must be one of {MODES}, got {mode!r}")
    n = lut.shape[0]
    if mode in ("composite", "xray"):
        return lut[:, 3] > 0
    nonzero = np.nonzero(np.any(lut != 0, axis=1))[0]
    flags = np.zeros(n, dtype=bool)
    if nonzero.size:
        if mode == "mip":
            flags[nonzero[0]:] = True
        else:
            flags[:nonzero[-1] + 1] = True
    return flags


def cell_ranges(vol: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(min, max) over each 2×2×2 cell of vol[z, y, x]; the cell at voxel c holds c and
    c + 1 along every axis, only c at a high face. Both shaped like vol."""
    nz, ny, nx = vol.shape
    pad = np.pad(vol.astype(np.int32), ((0, 1), (0, 1), (0, 1)), mode="edge")
    lo = pad[:nz, :ny, :nx].copy()
    hi = lo.copy()
    for dz in (0, 1):
        for dy in (0, 1):
            for dx in (0, 1):
                if dz or dy or dx:
                    s = pad[dz:dz + nz, dy:dy + ny, dx:dx + nx]
                    np.minimum(lo, s, out=lo)
                    np.maximum(hi, s, out=hi)
    return lo, hi


def busy_cells(vol: np.ndarray, lut: np.ndarray, mode: str, labelled: bool = False) -> np.ndarray:
    """(nz, ny, nx) bool: the cells in which a sample could change a ray. ``labelled``: vol
    holds labelled words and lut has a block per label (cube4.labels): a sample takes the
    label of one of its cell's corners, so the cell is busy when, for a label among its
    corners, a value in the cell's range counts in that label's block (numerics.md §24)."""
    if labelled:
        return _busy_labelled(vol, lut, mode)
    flags = counting_values(lut, mode).astype(np.int64)
    prefix = np.concatenate([[0], np.cumsum(flags)])
    lo, hi = cell_ranges(vol)
    return prefix[hi + 1] - prefix[lo] > 0


def _busy_labelled(words: np.ndarray, lut: np.ndarray, mode: str) -> np.ndarray:
    from .labels import lut_value_bits, split_words
    vbits = lut_value_bits(lut)
    vals, labs = split_words(words, vbits)
    lo, hi = cell_ranges(vals)
    n = 1 << vbits
    busy = np.zeros(words.shape, dtype=bool)
    for lb in np.unique(labs):
        flags = counting_values(lut[int(lb) * n:(int(lb) + 1) * n], mode).astype(np.int64)
        if not flags.any():     # a hidden label (or one that shows nothing) is empty space
            continue
        prefix = np.concatenate([[0], np.cumsum(flags)])
        present = cell_ranges((labs == lb).astype(np.int32))[1] > 0
        busy |= present & (prefix[hi + 1] - prefix[lo] > 0)
    return busy


def _cut_whole(plane, weight_bits: int, terms) -> np.ndarray:
    """Cells below the cut plane (CA, CB, CC, CD) at every corner; ``terms`` are three
    (coefficient, low corners along that output axis) in the output's axis order."""
    cd = int(plane[3])
    top = sum(max(int(c), 0) for c, _ in terms) << weight_bits
    e = [int(c) * (np.asarray(corner, dtype=np.int64) << weight_bits) for c, corner in terms]
    return e[0][:, None, None] + e[1][None, :, None] + e[2][None, None, :] + cd + top < 0


def cut_cells(trav: Traversal, plane) -> np.ndarray:
    """(nz, ny, nx) bool: the cells of ``trav``'s box that the cut plane (CA, CB, CC, CD,
    clip.py) removes whole. E is affine in the sample's position (i + wx/2^W, j + wy/2^W,
    m/S) of the traversal frame, so its largest value over a cell, a unit cube of that
    frame, is at the corner that each positive coefficient pushes up; a cell is cut when
    even that value is negative (every sample in it then has E < 0)."""
    nx, ny, nz = trav.dims
    coef = {trav.axis_i: int(plane[0]), trav.axis_j: int(plane[1]), trav.major: int(plane[2])}
    terms = []             # per volume axis z, y, x: the traversal coordinate of each cell's low corner
    for ax, n in ((2, nz), (1, ny), (0, nx)):
        c = np.arange(n, dtype=np.int64)
        terms.append((coef[ax], n - 2 - c if trav.flip[ax] else c))
    return _cut_whole(plane, trav.weight_bits, terms)


def cut_cells_traversal(trav: Traversal, plane) -> np.ndarray:
    """(nk, nj, ni) bool: ``cut_cells`` for the cells of the traversal frame (cell (k, j, i)
    has its low corner at (i, j, k))."""
    return _cut_whole(plane, trav.weight_bits, [(int(plane[2]), np.arange(trav.nk)),
                                                (int(plane[1]), np.arange(trav.nj)),
                                                (int(plane[0]), np.arange(trav.ni))])


def busy_box(busy: np.ndarray) -> tuple[tuple[int, int, int], tuple[int, int, int]] | None:
    """The box [s0, s1) (volume axes x, y, z, half-open) of the voxels the busy cells and
    their margins need, within the volume and at least 2 voxels along an axis that has 2
    (as small as a frame gets); None when no cell is busy."""
    if not busy.any():
        return None
    s0, s1 = [], []
    for ax in (2, 1, 0):          # x, y, z = numpy axes 2, 1, 0
        n = busy.shape[ax]
        others = tuple(a for a in range(3) if a != ax)
        idx = np.nonzero(busy.any(axis=others))[0]
        a, b = max(0, int(idx[0]) - MARGIN_LOW), min(n, int(idx[-1]) + MARGIN_HIGH + 1)
        if b - a < min(2, n):
            a, b = (a, a + 2) if a + 2 <= n else (n - 2, n)
        s0.append(a)
        s1.append(b)
    return tuple(s0), tuple(s1)  # type: ignore[return-value]


@dataclass(frozen=True)
class SkipPlan:
    """The schedule of one view with empty space skipped."""

    whole: Traversal                 # the traversal of the whole (scene's) box
    box: tuple | None                # ((x0, y0, z0), (x1, y1, z1)) within it; None: nothing counts
    trav: Traversal | None           # the box's traversal (None: no frame)
    offset: tuple[int, int]          # (row, col) of the box's base plane in the whole base plane
    start: tuple[int, int, int]      # (i, j, k) of the box's traversal-frame voxel (0, 0, 0) in the whole frame
    clip: Clip | None                # the whole frame's clip, moved into the box's frame
    table_s: float                   # host time to build the tables and the box

    @property
    def skips(self) -> bool:
        """Does the frame traverse less than the whole box?"""
        return self.trav is None or tuple(self.trav.dims) != tuple(self.whole.dims)

    @property
    def fraction(self) -> float:
        """Voxels traversed / voxels of the whole box."""
        if self.trav is None:
            return 0.0
        return float(np.prod(self.trav.dims)) / float(np.prod(self.whole.dims))

    def cycles(self, p: int, shading: bool, vgrad: bool = False, fall: bool = False, gm: bool = False) -> int:
        """Cycles of the frame without stalls (0: no frame); shading, vgrad, fall, gm: the
        build's (cycles.frame_cycles)."""
        if self.trav is None:
            return 0
        t = self.trav
        return frame_cycles(t.num_sample_slices, t.nj, t.ni, p, shading, vgrad, fall, gm)

    def box_volume(self, vol: np.ndarray) -> np.ndarray:
        """The box's voxels, vol[z, y, x] of the whole box (a view)."""
        (x0, y0, z0), (x1, y1, z1) = self.box
        return vol[z0:z1, y0:y1, x0:x1]

    def place(self, sub: np.ndarray | None) -> np.ndarray:
        """The whole base plane (rows, cols, 4) from the box's (None: no frame); rays that
        never meet the box are zero, as the full schedule leaves them in every mode."""
        rows, cols = self.whole.baseplane_shape
        base = np.zeros((rows, cols, 4), dtype=np.int64)
        if self.trav is not None:
            r0, c0 = self.offset
            br, bc = sub.shape[:2]
            base[r0:r0 + br, c0:c0 + bc] = sub
        return base

    def box_stop(self, stop: np.ndarray) -> np.ndarray | None:
        """The whole frame's stop slices (cube4.geometry.stop_slices, (rows, cols)) as the
        box frame's: its base-plane window, its slices counted from its first (None: no frame)."""
        if self.trav is None:
            return None
        r0, c0 = self.offset
        br, bc = self.trav.baseplane_shape
        return np.clip(stop[r0:r0 + br, c0:c0 + bc] - self.start[2] * self.whole.supersample, 0,
                       self.trav.num_sample_slices)

    def place_depth(self, sub: np.ndarray | None) -> np.ndarray:
        """The whole base plane's depth out (rows, cols, 2) from the box's (model.Frame
        depth_m; None: no frame): its slices moved to the whole frame's, -1 elsewhere."""
        rows, cols = self.whole.baseplane_shape
        out = np.full((rows, cols, 2), -1, dtype=np.int64)
        if self.trav is not None and sub is not None:
            r0, c0 = self.offset
            br, bc = sub.shape[:2]
            out[r0:r0 + br, c0:c0 + bc] = np.where(sub >= 0, sub + self.start[2] * self.whole.supersample, -1)
        return out

    def place_pixels(self, pixels: np.ndarray) -> np.ndarray:
        """The box's finished rays with base-plane addresses and slices of the whole frame."""
        out = pixels.copy()
        if self.trav is not None and out.size:
            out["by"] += self.offset[0]
            out["bx"] += self.offset[1]
            out["m"] += self.start[2] * self.whole.supersample
            for z in ("zp", "zf"):          # depth out's slices, where the ray has one
                out[z] = np.where(out[z] >= 0, out[z] + self.start[2] * self.whole.supersample, -1)
        return out


def fit_slice(box, trav: Traversal, p: int):
    """``box`` grown, within the traversed box, until a sample slice of it holds at least
    COM_MIN_SLICE beats (NJ·NB; a smaller slice makes COM wait for its own results and
    the cycle formula would not hold): rows first (along the j axis), then partial beams
    (i), one voxel at a time on alternate sides. A bigger box is as exact."""
    s0, s1 = list(box[0]), list(box[1])

    def beats() -> int:
        nj = s1[trav.axis_j] - s0[trav.axis_j]
        ni = s1[trav.axis_i] - s0[trav.axis_i]
        return nj * -(-ni // p)

    for ax in (trav.axis_j, trav.axis_i):
        n = trav.dims[ax]
        while beats() < COM_MIN_SLICE and (s0[ax] > 0 or s1[ax] < n):
            if s1[ax] < n and (s1[ax] - s0[ax]) % 2 == 0 or s0[ax] == 0:
                s1[ax] += 1
            else:
                s0[ax] -= 1
    return tuple(s0), tuple(s1)


def find_box(vol: np.ndarray, trav: Traversal, lut: np.ndarray, mode: str, p: int, clip: Clip | None = None,
             labelled: bool = False):
    """The box [s0, s1) of one view that can change a ray (None: nothing can), sized for
    P pipelines (``fit_slice``), and the host seconds it took. ``vol`` is the traversed
    box's voxels (vol[z, y, x] of trav.dims), ``lut`` the classification LUT the host
    loads for the view, ``clip`` its cut plane (cells it removes whole are not busy),
    ``labelled``: vol holds labelled words (busy_cells). It does not depend on the
    template's phase: the q×q passes of a view share it."""
    t0 = time.perf_counter()
    busy = busy_cells(vol, lut, mode, labelled)
    if clip is not None and clip.plane is not None:
        busy &= ~cut_cells(trav, clip.plane)
        if clip.slab is not None:
            busy &= ~cut_cells(trav, clip.far_plane())
    if clip is not None and clip.regions is not None:
        busy &= region_cells(trav, clip.regions)
    box = busy_box(busy)
    if box is not None:
        box = fit_slice(box, trav, p)
    return box, time.perf_counter() - t0


def plan_box(trav: Traversal, box, clip: Clip | None = None, table_s: float = 0.0) -> SkipPlan:
    """The frame of ``trav`` (the view, or one of its passes) that traverses ``box``:
    its traversal, placement and clip (``box`` None: no frame)."""
    if clip is not None and clip.window is not None:
        raise ValueError("a frame with a window of its own (a brick) is not skipped")
    if box is None:
        return SkipPlan(trav, None, None, (0, 0), (0, 0, 0), None, table_s)
    sub, offset, start = sub_traversal(trav, *box)
    moved = None
    if clip is not None and (clip.plane is not None or clip.regions is not None):
        regions = move_regions(clip.regions, start, trav.supersample)
        moved = Clip(plane=move_plane(clip.plane, start, trav.weight_bits),
                     regions=None if regions is None else fit_regions(regions, sub), slab=clip.slab)
    return SkipPlan(trav, box, sub, offset, start, moved, table_s)


def plan_skip(vol: np.ndarray, trav: Traversal, lut: np.ndarray, mode: str, clip: Clip | None = None,
              p: int = 1, labelled: bool = False) -> SkipPlan:
    """The empty-space schedule of one view on P pipelines (``find_box``, ``plan_box``)."""
    box, table_s = find_box(vol, trav, lut, mode, p, clip, labelled)
    return plan_box(trav, box, clip, table_s)

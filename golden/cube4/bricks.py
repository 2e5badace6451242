"""Sub-volume partitioning: a volume split into bricks, each rendered on its own through
the same pipeline, the partial base planes composited front to back (numerics.md §14).

* **Grid** (``BrickGrid``): the traversed box split along x, y and z into bricks that
  *own* disjoint voxel ranges ``[x0, x1)``; a brick *stores* ``[x0 - 1, x1 + 2)`` (cut at
  the volume's faces), the overlap that tri-linear interpolation and the gradients of its
  own samples need (OVERLAP_LOW, OVERLAP_HIGH; numerics.md §14.1).
* **Plan** (``plan_bricks``): per view, each brick's traversal (its stored box at its
  origin, the whole volume's view registers, the template's starting phase of its first
  slice, so that its samples are exactly the whole render's samples), its window (the
  samples it counts: the brick's own, each sample of the volume counted by exactly one
  brick), its cut plane moved into its frame, and where its base plane lies in the whole
  base plane. The plan lists the bricks front to back.
* **Over** (``over``, ``composite_tiles``): exact integer compositing of partial base
  planes at the accumulators' precision, ``front + T_front * back`` on premultiplied
  R, G, B, A in Q0.ACC_W, as a balanced tree over the front-to-back order.
* **Render** (``render_bricked``): plan, render every brick with a brick renderer
  (``golden`` here; other engines register theirs by import path, so a worker process
  can import it), composite. An executor runs the bricks: ``LocalExecutor`` one after
  the other in this process; ``cube4.app.cluster.DaskExecutor`` on a Dask cluster. The
  views of scenes, warped to images, are ``cube4.app.render.render_bricked_views``.
"""

from __future__ import annotations

import importlib
import time
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from .clip import Clip, fit_regions, move_plane, move_regions
from .config import Cube4Config
from .errors import UserError
from .fixed import round_shift
from .model import PIXEL_DTYPE, Frame, render_frame
from .modes import MODES, is_blend
from .progress import Progress, counted
from .view import Traversal, sub_traversal
from .values import int_text, shown

#: voxels a brick stores beyond its own range on the low and the high side of every axis
OVERLAP_LOW = 1
OVERLAP_HIGH = 2
MIN_BOARD_DIM = 1 + OVERLAP_LOW + OVERLAP_HIGH  # a brick's own voxel and its overlap
#: the modes whose partial base planes compose (composite: ``over``; xray: saturating sum)
BRICK_MODES = tuple(m for m in MODES if is_blend(m))   # the modes whose partial results compose by `over`
MAX_BRICKS = 4096


# ----------------------------------------------------------------------------- grid
@dataclass(frozen=True)
class BrickGrid:
    """A box of ``dims`` (nx, ny, nz) split into ``counts`` bricks per axis; ``bounds[a]``
    are the owned ranges' edges along axis a: 0 = c_0 < c_1 < ... < c_B = n."""

    dims: tuple[int, int, int]
    counts: tuple[int, int, int]
    bounds: tuple[tuple[int, ...], tuple[int, ...], tuple[int, ...]]

    @property
    def size(self) -> int:
        return self.counts[0] * self.counts[1] * self.counts[2]

    def indices(self) -> list[tuple[int, int, int]]:
        """Every brick (bx, by, bz), x fastest."""
        cx, cy, cz = self.counts
        return [(bx, by, bz) for bz in range(cz) for by in range(cy) for bx in range(cx)]

    def owned(self, index) -> tuple[tuple[int, int, int], tuple[int, int, int]]:
        """Voxels brick ``index`` owns: ((x0, y0, z0), (x1, y1, z1)), half-open."""
        lo = tuple(self.bounds[a][index[a]] for a in range(3))
        hi = tuple(self.bounds[a][index[a] + 1] for a in range(3))
        return lo, hi  # type: ignore[return-value]

    def stored(self, index) -> tuple[tuple[int, int, int], tuple[int, int, int]]:
        """Voxels brick ``index`` stores (its own plus the overlap): ((s0...), (s1...)), half-open."""
        lo, hi = self.owned(index)
        s0 = tuple(max(0, c - OVERLAP_LOW) for c in lo)
        s1 = tuple(min(n, c + OVERLAP_HIGH) for c, n in zip(hi, self.dims))
        return s0, s1  # type: ignore[return-value]

    def stored_dims(self, index) -> tuple[int, int, int]:
        s0, s1 = self.stored(index)
        return tuple(b - a for a, b in zip(s0, s1))  # type: ignore[return-value]

    def stored_voxels(self) -> int:
        """Voxels stored over all bricks (the overlap counted in every brick that holds it)."""
        return sum(int(np.prod(self.stored_dims(ix))) for ix in self.indices())

    @property
    def memory_overhead(self) -> float:
        """Stored voxels / volume voxels - 1 (Teramac Table 1's measure)."""
        return self.stored_voxels() / float(np.prod(self.dims)) - 1.0

    def largest_brick(self) -> tuple[int, int, int]:
        """The largest stored extent along each axis."""
        return tuple(max(self.stored_dims(ix)[a] for ix in self.indices()) for a in range(3))  # type: ignore


def parse_bricks(text: str) -> tuple[int, int, int]:
    """'BX,BY,BZ' (or 'BXxBYxBZ'): bricks along x, y, z, each a positive integer."""
    bad = UserError(f"--bricks must be BX,BY,BZ (three positive integers: bricks along x, y, z), got {shown(text)}")
    try:
        parts = tuple(int_text(p, "--bricks") for p in str(text).replace("x", ",").split(","))
    except UserError:
        raise bad from None
    if len(parts) != 3 or any(p < 1 for p in parts):
        raise bad
    return parts  # type: ignore[return-value]


def make_grid(dims, counts) -> BrickGrid:
    """Split a box of dims (nx, ny, nz) into counts (bx, by, bz) bricks of equal size
    (within one voxel): edge b along an axis of n voxels is floor(b * n / B)."""
    dims = tuple(int(n) for n in dims)
    counts = tuple(int(c) for c in counts)
    total = counts[0] * counts[1] * counts[2]
    if total > MAX_BRICKS:
        raise UserError(f"--bricks {counts[0]},{counts[1]},{counts[2]} makes {total} bricks; at most {MAX_BRICKS}")
    for name, n, c in zip("xyz", dims, counts):
        if c > n:
            raise UserError(f"--bricks: {c} bricks along {name} need at least {c} voxels, the volume has {n}")
    bounds = tuple(tuple(b * n // c for b in range(c + 1)) for n, c in zip(dims, counts))
    return BrickGrid(dims=dims, counts=counts, bounds=bounds)  # type: ignore[arg-type]


def counts_for_board(dims, board_dim: int) -> tuple[int, int, int]:
    """The fewest bricks per axis such that every stored brick (with its overlap) is at
    most ``board_dim`` voxels along every axis."""
    if board_dim < MIN_BOARD_DIM:
        raise UserError(f"--board-dim must be at least {MIN_BOARD_DIM} (a brick's own voxel plus its overlap), "
                        f"got {board_dim}")
    counts = []
    for n in (int(d) for d in dims):
        c = 1
        while max(make_grid((n, 1, 1), (c, 1, 1)).stored_dims((b, 0, 0))[0] for b in range(c)) > board_dim:
            c += 1
        counts.append(c)
    return tuple(counts)  # type: ignore[return-value]


def check_board(grid: BrickGrid, board_dim: int | None) -> None:
    if board_dim is None:
        return
    big = grid.largest_brick()
    if max(big) > board_dim:
        c = grid.counts
        raise UserError(f"--bricks {c[0]},{c[1]},{c[2]}: the largest brick stores {big[0]}x{big[1]}x{big[2]} voxels "
                        f"(with its overlap), more than --board-dim {board_dim}; use more bricks or leave "
                        f"--bricks out to have them chosen")


# ----------------------------------------------------------------------------- plan
@dataclass(frozen=True)
class Brick:
    """One brick of one view."""

    index: tuple[int, int, int]  # (bx, by, bz) in the grid
    trav: Traversal  # its stored box at its origin, the view's registers, its phase
    clip: Clip  # its window (the samples it counts) and the view's cut plane, in its frame
    offset: tuple[int, int]  # (row, col) of its base-plane pixel (0, 0) in the whole base plane
    start: tuple[int, int, int]  # (i, j, k) of its traversal-frame voxel (0, 0, 0) in the whole frame


def _owned_traversal(n: int, x0: int, x1: int, flip: bool, major: bool) -> tuple[int, int]:
    """Owned voxel range [x0, x1) of a volume axis as a range [A, B) of traversal-frame
    indices (sample indices along i or j; voxel slices along k), numerics.md §14.1.
    Along a flipped minor axis the range moves by one, so that the overlap a brick needs
    is [x0 - 1, x1 + 2) for either sign."""
    if not flip:
        return x0, x1
    if major:
        return n - x1, n - x0
    return (n - 1 - x1 if x1 < n else 0), (n - 1 - x0 if x0 > 0 else n)


def plan_bricks(trav: Traversal, grid: BrickGrid, clip: Clip | None = None) -> list[Brick]:
    """Each brick's traversal, window and base-plane placement for the view ``trav`` of
    the box that ``grid`` splits, front to back: sorted by the bricks' positions along
    the traversal axes k, j, i (rays run towards +i, +j, +k, so every ray meets bricks in
    this order). ``clip`` is the whole render's (its cut plane moves into every brick;
    a window of its own is not supported)."""
    if tuple(trav.dims) != tuple(grid.dims):
        raise ValueError(f"grid of {grid.dims} does not split the traversed box {trav.dims}")
    if clip is not None and clip.window is not None:
        raise ValueError("a render with a window of its own cannot be split into bricks")
    S = trav.supersample
    if trav.phase_x or trav.phase_y:
        raise ValueError("the whole render must start at phase 0")
    roles = (trav.axis_i, trav.axis_j, trav.major)
    bricks = []
    for ix in grid.indices():
        (o0, o1), (s0, s1) = grid.owned(ix), grid.stored(ix)
        bt, offset, start = sub_traversal(trav, s0, s1)
        win = []
        for role, ax in enumerate(roles):
            n, flip, st = grid.dims[ax], bool(trav.flip[ax]), start[role]
            a, b = _owned_traversal(n, o0[ax], o1[ax], flip, major=role == 2)
            # along k the window counts sample slices; the last brick's ends at its last
            # sample slice ((count - 1) S + 1 of them), not at count * S (the registers hold no more)
            win.append((a - st, b - st) if role < 2 else ((a - st) * S, min((b - st) * S, bt.num_sample_slices)))
        plane = move_plane(clip.plane if clip is not None else None, start, trav.weight_bits)
        regions = move_regions(clip.regions if clip is not None else None, start, S)
        window = (win[0][0], win[0][1], win[1][0], win[1][1], win[2][0], win[2][1])
        slab = clip.slab if clip is not None else None
        bricks.append(Brick(index=ix, trav=bt, clip=Clip(window=window, plane=plane, slab=slab,
                                                         regions=None if regions is None else fit_regions(regions, bt)),
                            offset=offset, start=start))
    return sorted(bricks, key=lambda br: br.start[::-1])


def owner_maps(trav: Traversal, grid: BrickGrid, bricks: Sequence[Brick]):
    """Which brick counts each sample of the whole render: (owner (M, nj, ni) callable by
    slice -> (nj, ni) int array of positions in ``bricks``). Built from the windows."""
    lut = {}
    for pos, br in enumerate(bricks):
        lut[br.index] = pos
    ni, nj, M = trav.ni, trav.nj, trav.num_sample_slices
    maps = []
    for role, n in enumerate((ni, nj, M)):
        own = np.full(n, -1, dtype=np.int64)
        for br in bricks:
            lo, hi = br.clip.window[2 * role], br.clip.window[2 * role + 1]
            st = br.start[role] * (trav.supersample if role == 2 else 1)
            ax = (trav.axis_i, trav.axis_j, trav.major)[role]
            idx = np.arange(max(0, lo + st), min(n, hi + st))
            prev = own[idx]
            if np.any((prev >= 0) & (prev != br.index[ax])):
                raise AssertionError("two bricks own the same samples")
            own[idx] = br.index[ax]
        if np.any(own < 0):
            raise AssertionError("a sample no brick owns")
        maps.append(own)
    own_i, own_j, own_m = maps
    counts = grid.counts
    table = np.full(counts[::-1], -1, dtype=np.int64)  # [bz, by, bx]
    for ix, pos in lut.items():
        table[ix[2], ix[1], ix[0]] = pos
    roles = (trav.axis_i, trav.axis_j, trav.major)

    def owner(m: int) -> np.ndarray:
        idx = [None, None, None]
        jj, ii = np.meshgrid(own_j, own_i, indexing="ij")
        idx[roles[0]] = ii
        idx[roles[1]] = jj
        idx[roles[2]] = np.full_like(ii, own_m[m])
        return table[idx[2], idx[1], idx[0]]

    return owner


# ----------------------------------------------------------------------------- over
@dataclass
class Tile:
    """A partial base plane placed in the whole base plane: ``rgba`` (h, w, 4) int64,
    premultiplied R, G, B, A in Q0.ACC_W, its pixel (0, 0) at (row, col)."""

    row: int
    col: int
    rgba: np.ndarray


def _union(a: Tile, b: Tile) -> tuple[int, int, int, int]:
    r0, c0 = min(a.row, b.row), min(a.col, b.col)
    r1 = max(a.row + a.rgba.shape[0], b.row + b.rgba.shape[0])
    c1 = max(a.col + a.rgba.shape[1], b.col + b.rgba.shape[1])
    return r0, c0, r1, c1


def _embed(t: Tile, r0: int, c0: int, r1: int, c1: int) -> np.ndarray:
    out = np.zeros((r1 - r0, c1 - c0, 4), dtype=np.int64)  # transparent: the identity of over
    out[t.row - r0:t.row - r0 + t.rgba.shape[0], t.col - c0:t.col - c0 + t.rgba.shape[1]] = t.rgba
    return out


def over_planes(front: np.ndarray, back: np.ndarray, acc_bits: int, mode: str = "composite") -> np.ndarray:
    """``front`` over ``back``, same shape (..., 4), premultiplied R, G, B, A in Q0.F:

        composite:  X = X_f + round_shift(T_f * X_b, F)   for X in R, G, B, A,  T_f = 2^F - A_f
        xray:       X = min(2^F, X_f + X_b)               (the saturating sum of numerics.md §13)

    Exact integers; transparent (0, 0, 0, 0) is the identity on both sides. Composite
    keeps every R, G, B <= A <= 2^F (numerics.md §14.2)."""
    one = 1 << acc_bits
    if mode == "xray":
        return np.minimum(one, front + back)
    t_front = one - front[..., 3:4]
    return front + round_shift(t_front * back, acc_bits)


def over(front: Tile, back: Tile, acc_bits: int, mode: str = "composite") -> Tile:
    """Two placed partial base planes composited (their union's bounding box)."""
    r0, c0, r1, c1 = _union(front, back)
    return Tile(r0, c0, over_planes(_embed(front, r0, c0, r1, c1), _embed(back, r0, c0, r1, c1), acc_bits, mode))


def composite_tiles(tiles: Sequence[Tile], shape: tuple[int, int], acc_bits: int,
                    mode: str = "composite") -> np.ndarray:
    """The whole base plane (rows, cols, 4) from partial base planes listed front to
    back: a balanced tree of ``over`` (neighbours in the order, level by level)."""
    level = list(tiles)
    if not level:
        return np.zeros((*shape, 4), dtype=np.int64)
    while len(level) > 1:
        nxt = [over(level[n], level[n + 1], acc_bits, mode) for n in range(0, len(level) - 1, 2)]
        if len(level) % 2:
            nxt.append(level[-1])
        level = nxt
    root = level[0]
    rows, cols = shape
    full = _embed(root, min(0, root.row), min(0, root.col), max(rows, root.row + root.rgba.shape[0]),
                  max(cols, root.col + root.rgba.shape[1]))
    r, c = -min(0, root.row), -min(0, root.col)
    base = full[r:r + rows, c:c + cols]
    if int(np.count_nonzero(full)) != int(np.count_nonzero(base)):
        raise AssertionError("a brick put colour outside the whole base plane")
    return np.ascontiguousarray(base)


# ----------------------------------------------------------------------------- brick renderers
@dataclass
class BrickTask:
    """Everything a worker needs to render one brick (picklable)."""

    target: str  # "module:function" of the brick renderer
    vol: np.ndarray  # the brick's stored voxels, vol[z, y, x] (memory words with voxel gradients)
    trav: Traversal
    cfg: Cube4Config
    lut: np.ndarray
    rmap: np.ndarray | None
    clip: Clip
    mode: str = "composite"
    shading: bool = True
    label: str = ""
    board_dim: int | None = None  # the board's MAX_DIM (None: the engine's choice)
    vgrad: bool = False  # vol holds words with voxel gradients (cube4.vgrad), shaded with them


@dataclass
class BrickResult:
    baseplane: np.ndarray  # (rows, cols, 4) int64 of the brick's traversal
    wall_s: float
    cycles: int | None = None
    worker: str = ""
    extra: dict = field(default_factory=dict)


def render_brick_golden(task: BrickTask) -> BrickResult:
    """A brick through the bit-exact model."""
    t0 = time.perf_counter()
    fr = render_frame(task.vol, task.trav, task.cfg, task.lut, task.rmap, mode=task.mode,
                      shading=task.shading, clip=task.clip, vgrad=task.vgrad)
    return BrickResult(baseplane=fr.baseplane, wall_s=time.perf_counter() - t0)


_RENDERERS: dict[str, str] = {"golden": "cube4.bricks:render_brick_golden"}


def register_brick_renderer(engine: str, target: str) -> None:
    """Make ``engine`` render bricks with the function at ``target`` ("module:function",
    imported where the brick runs, e.g. in a worker process)."""
    _RENDERERS[engine] = target


def brick_renderer(engine: str) -> str:
    if engine not in _RENDERERS:
        raise UserError(f"--bricks needs an engine that renders bricks ({', '.join(_RENDERERS)}), got {engine!r}")
    return _RENDERERS[engine]


def run_task(task: BrickTask) -> BrickResult:
    """Import the task's renderer and run it (in this process)."""
    mod, _, fn = task.target.partition(":")
    return getattr(importlib.import_module(mod), fn)(task)


class LocalExecutor:
    """Bricks one after the other in this process."""

    name = "local"
    workers = 1

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def run(self, tasks: Sequence[BrickTask], progress: Progress | None = None) -> list[BrickResult]:
        return [run_task(task) for task in counted(tasks, progress, "bricks")]

    def stats(self) -> dict:
        return {"executor": self.name, "workers": 1, "retries": 0}


# ----------------------------------------------------------------------------- a bricked render
@dataclass
class BrickedFrame:
    """A whole base plane composited from bricks, with what it took."""

    frame: Frame
    bricks: list[Brick]
    results: list[BrickResult]
    composite_s: float


def brick_tasks(vol: np.ndarray, trav: Traversal, cfg: Cube4Config, lut, rmap, grid: BrickGrid, *,
                engine: str = "golden", mode: str = "composite", shading: bool = True,
                clip: Clip | None = None, board_dim: int | None = None,
                vgrad: bool = False) -> tuple[list[Brick], list[BrickTask]]:
    """The plan of one view and one task per brick. ``vol`` is the traversed box's
    voxels (vol[z, y, x] of trav.dims; with ``vgrad`` the memory words of cube4.vgrad,
    estimated over the whole volume, so a brick's gradients need no overlap of their own);
    ``board_dim`` the boards' MAX_DIM, if given."""
    if mode not in BRICK_MODES:
        raise UserError(f"--bricks composes the modes {', '.join(BRICK_MODES)}, not {mode!r} (a ray's extremum "
                        f"cannot be told from the partial pixels)")
    target = brick_renderer(engine)
    bricks = plan_bricks(trav, grid, clip)
    tasks = []
    for br in bricks:
        (x0, y0, z0) = (o - w for o, w in zip(br.trav.origin, trav.origin))
        nx, ny, nz = br.trav.dims
        sub = np.ascontiguousarray(vol[z0:z0 + nz, y0:y0 + ny, x0:x0 + nx])
        tasks.append(BrickTask(target=target, vol=sub, trav=br.trav, cfg=cfg, lut=lut, rmap=rmap, clip=br.clip,
                               mode=mode, shading=shading, label="brick %d,%d,%d" % br.index, board_dim=board_dim,
                               vgrad=vgrad))
    return bricks, tasks


def assemble(trav: Traversal, cfg: Cube4Config, bricks: Sequence[Brick], results: Sequence[BrickResult],
             mode: str = "composite") -> tuple[Frame, float]:
    """Composite the bricks' base planes (front to back, as planned) into the whole."""
    t0 = time.perf_counter()
    tiles = [Tile(br.offset[0], br.offset[1], res.baseplane) for br, res in zip(bricks, results)]
    base = composite_tiles(tiles, trav.baseplane_shape, cfg.acc_bits, mode)
    pixels = np.empty(0, dtype=PIXEL_DTYPE)  # a bricked render has no pixel stream of its own
    return Frame(trav=trav, cfg=cfg, baseplane=base, pixels=pixels), time.perf_counter() - t0


def render_bricked(vol: np.ndarray, trav: Traversal, cfg: Cube4Config, lut, rmap, grid: BrickGrid, *,
                   engine: str = "golden", mode: str = "composite", shading: bool = True,
                   clip: Clip | None = None, executor=None, progress: Progress | None = None) -> BrickedFrame:
    """One view of the traversed box ``vol`` rendered brick by brick and composited."""
    bricks, tasks = brick_tasks(vol, trav, cfg, lut, rmap, grid, engine=engine, mode=mode, shading=shading,
                                clip=clip)
    results = (executor or LocalExecutor()).run(tasks, progress=progress)
    frame, comp_s = assemble(trav, cfg, bricks, results, mode)
    return BrickedFrame(frame=frame, bricks=bricks, results=results, composite_s=comp_s)

"""Golden frames of the beat schedule for the front end's unit testbenches
(tb/cube4_cfb_beats, tb/cube4_cfb_decide): ``render_frame(..., beats=..., done=...)`` run
to the end, so that the schedule holds every slice's decisions and COM's reports.

* ``sparse_frame``: a sparse volume (``cube4_testutil.sparse_case``: a faint background,
  one dense blob, every mode, seven views, cut planes) at S = 1 or the S asked for, its
  LUT made nearly opaque on request (COM's reports then end rays), termination on or off.
* ``slab_frame``: a nearly opaque slab in front of a dense block (tests/test_beats.py
  ``opaque_slab``), shaded, with termination: rays end in the slab and many beats run
  only as GRA's neighbours of running ones.

Each returns a ``BeatFrame``: the schedule, the traversal and the volume's block bits.
And what the benches drive and expect: the host's block table for the view
(``block_words``) and the frame's axes (``axis_regs``), COM's reports (``reports``), the
decisions (``expected_decisions``), the walk (``expected_walk``), the front end's beats
(``expected_front``: cube4_cfb_skip) and the requests (``expected_requests``: cube4_cfb).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

import cube4.beats as beats
from cube4.model import render_frame
from cube4.view import Traversal

BLOCK = 4


@dataclass
class BeatFrame:
    sched: beats.BeatSchedule
    trav: Traversal
    bits: np.ndarray            # (bz, by, bx) the block table's bits of the volume
    vol: np.ndarray | None = None   # the volume (a frame of the whole volume: its memory image)
    frame: object = None            # the golden frame, its streams kept (``beat_frame``)


def _run(vol, trav, cfg, lut, rmap, mode, shading, clip, terminate: bool, keep: bool = False,
         tau: int = 0) -> BeatFrame:
    bits = beats.BlockTable.of(vol, BLOCK).bits(lut, mode)
    occ = beats.frame_occupancy(bits, BLOCK, trav)
    sched = beats.BeatSchedule(trav, cfg.pipelines, occ, terminate=terminate, gra=shading and mode == "composite")
    rule = beats.TerminationRule(mode, tau, 1 << cfg.acc_bits, int(vol.min()), int(vol.max()),
                                 enabled=terminate, value_bits=cfg.voxel_bits)
    frame = render_frame(vol, trav, cfg, lut, rmap, mode=mode, shading=shading, clip=clip, beats=sched, done=rule,
                         keep_streams=keep)
    return BeatFrame(sched, trav, bits, vol, frame if keep else None)


def beat_frame(vol, trav, cfg, lut, rmap, mode: str, clip=None, terminate: bool = False,
               tau: int = 0) -> BeatFrame:
    """A golden frame of the beat schedule with its streams kept (unshaded: COM's benches
    take its shaded stream); ``tau`` termination's threshold (Q0.ACC_W)."""
    return _run(vol, trav, cfg, lut, rmap, mode, False, clip, terminate, keep=True, tau=tau)


def sparse_frame(seed: int, p: int, opaque: bool, terminate: bool, supersample: int = 1) -> BeatFrame:
    """The sparse case ``seed`` at P = p and S = ``supersample``."""
    from cube4_testutil import sparse_case
    vol, trav, cfg, lut, rmap, mode, shading, clip = sparse_case(seed, supersample)
    cfg = dataclasses.replace(cfg, pipelines=p)
    if opaque and mode in ("composite", "xray"):
        lut = lut.copy()
        lut[lut[:, 3] > 0, 3] = (1 << cfg.alpha_bits) - 1
    return _run(vol, trav, cfg, lut, rmap, mode, shading, clip, terminate)


def slab_frame(p: int, direction) -> BeatFrame:
    from test_beats import opaque_slab
    vol, trav, cfg, lut, rmap = opaque_slab(p, direction)
    return _run(vol, trav, cfg, lut, rmap, "composite", True, None, True)


def thin_frame(p: int, ny: int, seed: int = 0) -> BeatFrame:
    """A volume ``ny`` rows deep along j (NJ = ny) with scattered opaque voxels, seen
    z-major: a slice's rows follow each other within a few cycles, many of them without
    a running beat, so GRA's row table is read in the cycle a row's word is written
    (NJ = 1) and in the cycle after (NJ = 2); at NJ = MAX_DIM (a power of two) the
    flush row NJ has row 0's address in GRA's position buffers' planes."""
    from cube4.config import Cube4Config
    from cube4.view import make_traversal
    rng = np.random.default_rng(seed + 7 * ny)
    vol = rng.integers(0, 40, size=(9, ny, 13))
    hit = rng.random(vol.shape) < 0.12
    vol[hit] = rng.integers(100, 256, size=int(hit.sum()))
    cfg = Cube4Config(pipelines=p)
    lut = np.zeros((256, 4), dtype=np.int64)
    lut[:, :3] = rng.integers(0, 256, size=(256, 3))
    lut[60:, 3] = (1 << cfg.alpha_bits) - 1
    rmap = rng.integers(0, 1024, size=(cfg.rmap_entries, 2))
    trav = make_traversal((13, ny, 9), (0.2, -0.1, 1.0), cfg.weight_bits, 1)
    return _run(vol, trav, cfg, lut, rmap, "composite", True, None, True)


def view_frame(vol_spec: str, scene_name: str, p: int) -> BeatFrame:
    """A built-in scene's own view of a volume at P = p through the host (its empty-space
    box, the block table of the whole volume): the first pass's frame."""
    from cube4.app.volumes import load_volume
    from cube4.host import config_for, golden_view
    from cube4.scene import load_scene
    vol, sc = load_volume(vol_spec), load_scene(scene_name)
    got: list = []
    golden_view(vol, sc, config_for(sc, p), beat_skip={}, schedules=got)
    sched = got[0][0]
    return BeatFrame(sched, sched.trav, sched.block_bits)


def bits_of(row) -> int:
    """A row of bools as an integer, bit n = row[n]."""
    return sum(1 << int(i) for i in np.flatnonzero(row))


def clog2(n: int) -> int:
    return max(0, (int(n) - 1).bit_length())


def block_words(bf, nbk: int) -> dict[int, int]:
    """The block table for the view: word {kb, jb} = the bits along the frame's i axis."""
    t = bf.trav
    axes = (t.major, t.axis_j, t.axis_i)            # volume axes of the frame's k, j, i
    arr = np.transpose(bf.bits, [2 - a for a in axes])
    bk_w = max(1, clog2(nbk))
    words = {}
    for kb in range(arr.shape[0]):
        for jb in range(arr.shape[1]):
            words[(kb << bk_w) | jb] = bits_of(arr[kb, jb])
    return words


def axis_regs(bf) -> dict[str, int]:
    """base and flip of the frame's i, j, k axes in the volume."""
    t = bf.trav
    regs = {}
    for name, a in (("bi", t.axis_i), ("bj", t.axis_j), ("bk", t.major)):
        flip = bool(t.flip[a])
        regs[f"{name}_flip"] = int(flip)
        regs[f"{name}_base"] = t.origin[a] + (t.dims[a] - 1 if flip else 0)
    return regs


def reports(bf, p: int, lag: int) -> dict[int, list[tuple[int, int, int, int, dict[int, int]]]]:
    """Per slice d, COM's writes: (j, pb, stx, sty, {position: end}) for its rays done then."""
    s, t = bf.sched, bf.trav
    sxm, sym = t.max_steps
    out: dict[int, dict] = {}
    for by, bx in zip(*np.nonzero(s.done < s.M)):
        d = int(s.done[by, bx])
        if s.stop[by, bx] <= d + lag + 1:     # soon: the stop ends the ray first, COM writes nothing
            continue
        stx, sty = (int(v) for v in t.steps(d))
        j, i = int(by) - sym + sty, int(bx) - sxm + stx
        beat = out.setdefault(d, {}).setdefault((j, i // p, stx, sty), {})
        beat[i % p] = d + lag + 1
    return {d: [(j, pb, stx, sty, ends) for (j, pb, stx, sty), ends in sorted(b.items())] for d, b in out.items()}


def expected_decisions(bf, p: int, lag: int):
    """Per beat in order: (m, j, pb, run, fresh, last, soon) as position masks; per row (A, OCC)."""
    s, t = bf.sched, bf.trav
    sxm, sym = t.max_steps
    lane, rows = [], []
    for m in range(s.M):
        run = s.running(m)
        stx, sty = (int(v) for v in t.steps(m))
        r0, c0 = sym - sty, sxm - stx
        first = s.first[r0:r0 + s.NJ, c0:c0 + s.NI] == m
        last = s.stop[r0:r0 + s.NJ, c0:c0 + s.NI] <= m + 1
        soon = s.stop[r0:r0 + s.NJ, c0:c0 + s.NI] <= m + lag + 1
        care = s.done[r0:r0 + s.NJ, c0:c0 + s.NI] >= m        # soon counts up to the ray's done slice
        for j in range(s.NJ):
            for pb in range(s.NB):
                cols = slice(pb * p, min((pb + 1) * p, s.NI))
                if run[j, cols].any():
                    lane.append((m, j, pb, bits_of(run[j, cols]), bits_of(run[j, cols] & first[j, cols]),
                                 bits_of(run[j, cols] & last[j, cols]), bits_of(run[j, cols] & soon[j, cols]),
                                 bits_of(care[j, cols])))
        occ = s._beats_of(s.sample_occ(m))
        rows += [(bits_of(a), bits_of(o)) for a, o in zip(s.active_beats(m), occ)]
    return lane, rows


def expected_walk(sched) -> list[tuple[int, int, int, int, int, int, int, int, int, int]]:
    """(m, j, pb, read, leave, in_a, tok, eor, eos, last) of every beat of the walk
    (beats.walk_rows): each beat of a row's reads | cover in order of partial beam (read:
    it is one of the reads; the cover's beats read nothing); a row that walks nothing gives
    one beat that reads nothing, a marker on a slice's last row, on row 0 of every slice but
    the first (it completes the previous slice's last row) and on the flush row, a token
    (tok) on any other; eor on a row's last beat, eos on a slice's, last on the frame's."""
    out = []
    for m, j, reads, leaves, cover, in_a in beats.walk_rows(sched, with_a=True):
        row = [(m, j, int(pb), int(reads[pb]), int(leaves[pb]), int(in_a[pb]), 0, 0, 0, 0)
               for pb in np.flatnonzero(reads | cover)]
        end = 1 if m == sched.M else 0
        eos = 1 if (j == sched.NJ - 1 and not end) else 0
        if not row:
            row = [(m, j, 0, 0, 0, 0, int(not (eos or end or (j == 0 and m > 0))), 0, 0, 0)]
        row[-1] = row[-1][:7] + (1, eos, end)
        out += row
    return out


def expected_front(bf, p: int, lag: int) -> list[tuple]:
    """Per walk beat of cube4_cfb_skip: (m, j, pb, read, leave, tok, eor, eos, last, bits, care)
    with the leaving beat's position bits {soon, last, fresh, run} (zero where none
    leaves or it runs as GRA's neighbour only) and the mask of the bits that are checked
    (soon counts up to the ray's done slice)."""
    s = bf.sched
    lane, _ = expected_decisions(bf, p, lag)
    by_beat = {w[:3]: w for w in lane}
    full = (1 << (4 * p)) - 1
    out = []
    for m, j, pb, read, leave, in_a, tok, eor, eos, last in expected_walk(s):
        src = (m, j - 1, pb) if j > 0 else (m - 1, s.NJ - 1, pb)
        bits, care = 0, full
        if leave and in_a:
            w = by_beat[src]
            bits = w[3] | w[4] << p | w[5] << (2 * p) | w[6] << (3 * p)
            care = full >> p | w[7] << (3 * p)
        out.append((m, j, pb, read, leave, tok, eor, eos, last, bits, care))
    return out


def expected_requests(bf, p: int, lag: int) -> list[tuple]:
    """The request beats of cube4_cfb's beat build: one per walk beat but the tokens (rows
    that walk nothing), as (k, j, pb, reads, emit, leave, emitted (m, j), eop, eos, bits,
    care), a push beat after each slice's last beat and the drain beat after the frame's
    (neither reads nor emits), and a push beat after each sample slice's last beat too (the
    last beat of row 0 of a slice but the first). The flush row reads nothing; every request
    emits the sample beat of the row below (its lanes valid where it runs, ``leave``), but
    never a beat of slice -1 (row 0 of slice 0)."""
    s = bf.sched
    out = []
    for m, j, pb, read, leave, tok, eor, eos, last, bits, care in expected_front(bf, p, lag):
        if tok:
            continue
        row = (m, j - 1) if j > 0 else (m - 1, s.NJ - 1)
        out.append((m, j, pb, int(read and m < s.M), int(row[0] >= 0), leave, row, last, eos, bits, care))
        if (eos or (eor and j == 0 and 0 < m < s.M)) and not last:
            out.append((None, None, None, 0, 0, 0, None, 0, 0, 0, 0))     # the push beat
    out.append((None, None, None, 0, 0, 0, None, 0, 0, 0, 0))     # the drain beat
    return out


class HostCom:
    """The host and COM around the front end's units in a bench (tb/cube4_cfb_decide,
    tb/cube4_cfb_skip), one frame:

    * ``load``: the frame's registers and axes, the block table for the view and the ray
      table with every ray's stop, through the host's ports;
    * ``drive`` (each cycle, inputs set after the falling edge): the next slice's steps
      on st_*, and COM's reports: those of slice d are queued once the unit has finished
      slice d (``finished`` slices), a random delay (0 .. ``delay`` cycles) later written
      one beat a cycle on rep_*, and ``com_m`` counts the slices written whole;
    * ``taken`` (in the read-only phase): whether the steps were taken.
    """

    def __init__(self, dut, bf: BeatFrame, p: int, max_dim: int, m_w: int, lag: int, rng, delay: int) -> None:
        self.dut, self.bf, self.p, self.max_dim, self.m_w = dut, bf, p, max_dim, m_w
        self.rng, self.delay = rng, delay
        self.reps = reports(bf, p, lag)
        self.st_n, self.com_m, self.queue = 0, 0, []     # queue: [cycle due, its writes]

    async def load(self) -> None:
        from cocotb.triggers import FallingEdge

        from cube4.memory import stop_table
        d, s, t = self.dut, self.bf.sched, self.bf.trav
        if hasattr(d, "nbr_en"):
            d.nbr_en.value = int(s.neighbours)
        axes = axis_regs(self.bf)
        if hasattr(d, "blk_base"):          # cube4_cfb: the frame and the flips from the view registers
            dim_w = clog2(self.max_dim + 1)
            d.blk_base.value = sum(axes[f"{a}_base"] << (n * dim_w) for n, a in enumerate(("bi", "bj", "bk")))
        else:
            d.ni.value, d.nj.value, d.nb.value, d.nm.value = s.NI, s.NJ, s.NB, s.M
            d.sx.value, d.sy.value = t.max_steps
            for name, val in axes.items():
                getattr(d, name).value = val
        for addr, word in block_words(self.bf, -(-self.max_dim // BLOCK)).items():
            d.blk_we.value, d.blk_addr.value, d.blk_data.value = 1, addr, word
            await FallingEdge(d.clk)
        d.blk_we.value = 0
        for addr, word in enumerate(stop_table(s.stop, self.p, self.max_dim, self.m_w)):
            d.tab_we.value, d.tab_addr.value, d.tab_data.value = 1, addr, word
            await FallingEdge(d.clk)
        d.tab_we.value = 0

    def drive(self, cycle: int, finished: int) -> None:
        d, s, t = self.dut, self.bf.sched, self.bf.trav
        if hasattr(d, "st_valid"):          # (cube4_cfb makes the steps itself)
            d.st_valid.value = int(self.st_n < s.M)
            if self.st_n < s.M:
                d.st_x.value, d.st_y.value = (int(v) for v in t.steps(self.st_n))
        while finished > self.com_m + len(self.queue) and self.com_m + len(self.queue) < s.M:
            dd = self.com_m + len(self.queue)
            self.queue.append([cycle + int(self.rng.integers(0, self.delay + 1)), list(self.reps.get(dd, []))])
        write = None
        if self.queue and cycle >= self.queue[0][0]:
            if self.queue[0][1]:
                write = self.queue[0][1].pop(0)
            if not self.queue[0][1]:
                self.queue.pop(0)
                self.com_m += 1
        d.rep_valid.value = int(write is not None)
        if write is not None:
            j, pb, stx, sty, ends = write
            d.rep_j.value, d.rep_pb.value, d.rep_stx.value, d.rep_sty.value = j, pb, stx, sty
            d.rep_en.value = sum(1 << q for q in ends)
            d.rep_end.value = sum(e << (q * self.m_w) for q, e in ends.items())
        d.com_m.value = self.com_m

    def taken(self) -> None:
        if hasattr(self.dut, "st_valid") and int(self.dut.st_valid.value) and int(self.dut.st_ready.value):
            self.st_n += 1

"""Beats of the Cube-4 streams, built from the golden model and decoded from the RTL.

One place for the beat order, the stream header and the lane packing that
TRI -> GRA -> SHA -> COM share (rtl/cube4_defs.vh), used by the unit testbenches:

* ``Geometry`` mirrors the derived widths and the header layout (CUBE4_GEOMETRY)
  for the build's P, MAX_DIM and MAX_SS_LOG2.
* ``BeatSchedule`` is the sample stream's beat order for one view: for m in
  0..M-1, for j in 0..NJ-1, for pb in 0..NB-1 one beat whose lane q holds the
  position i = pb * P + lane_pos(q, skew); with each beat's header fields (m, j,
  pb, skew, control bits, lane valid, lane inside), computed from the traversal
  alone (golden ``Traversal.steps``, ``memory.lane_positions``), and ``lanes``,
  which gathers any golden [m, j, i] array into the beats' lanes.
* ``pack_lanes`` / ``unpack_lanes`` turn per-lane integers into the flat lane
  buses of the RTL (lane q in bits [q*w +: w]) and back, signed or not.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cube4.memory import lane_positions
from cube4.view import Traversal

# control bits of the header (CTRL_* in cube4_defs.vh)
CTRL_SX, CTRL_SY, CTRL_OSX, CTRL_OSY, CTRL_SOP, CTRL_EOP, CTRL_YLAST = range(7)


def clog2(n: int) -> int:
    """Verilog $clog2: bits to count 0..n-1 (0 for n <= 1)."""
    return max(0, (int(n) - 1).bit_length())


@dataclass(frozen=True)
class Geometry:
    """Derived widths and the stream header layout of cube4_defs.vh (CUBE4_GEOMETRY)."""

    p: int
    max_dim: int
    max_ss_log2: int = 0

    @property
    def dim_w(self) -> int:
        return clog2(self.max_dim + 1)

    @property
    def nbmax(self) -> int:
        return -(-self.max_dim // self.p)

    @property
    def pb_w(self) -> int:
        return clog2(self.nbmax) if self.nbmax > 1 else 1

    @property
    def lane_w(self) -> int:
        return clog2(self.p) if self.p > 1 else 1

    @property
    def m_w(self) -> int:
        return clog2((self.max_dim - 1) * (1 << self.max_ss_log2) + 2)

    @property
    def hdr_fields(self) -> dict[str, tuple[int, int]]:
        """Header field -> (LSB position, width), LSB first."""
        p = self.p
        widths = [("inside", p), ("lval", p), ("keep", p), ("ctrl", 7), ("skew", self.lane_w), ("pb", self.pb_w),
                  ("j", self.dim_w), ("m", self.m_w)]
        out, pos = {}, 0
        for name, w in widths:
            out[name] = (pos, w)
            pos += w
        return out

    @property
    def hdr_w(self) -> int:
        pos, w = self.hdr_fields["m"]
        return pos + w

    def pack_header(self, fields: dict[str, int]) -> int:
        """Header fields (lane masks as integers) -> the HDR_W-bit header."""
        word = 0
        for name, (pos, w) in self.hdr_fields.items():
            v = int(fields[name])
            assert 0 <= v < (1 << w), f"header field {name} = {v} does not fit {w} bits"
            word |= v << pos
        return word

    def unpack_header(self, word: int) -> dict[str, int]:
        return {name: (int(word) >> pos) & ((1 << w) - 1) for name, (pos, w) in self.hdr_fields.items()}


def pack_lanes(values, width: int) -> int:
    """Per-lane integers (lane 0 first; negative ones two's complement) -> a lane bus."""
    mask = (1 << width) - 1
    word = 0
    for q, v in enumerate(values):
        word |= (int(v) & mask) << (q * width)
    return word


def pack_fields(values, width: int) -> int:
    """Unsigned fields of ``width`` bits, the first in the top bits (as the Verilog
    concatenation {a, b, ...}) -> a bus; a value that does not fit is an error."""
    word = 0
    for v in values:
        if not 0 <= int(v) < 1 << width:
            raise ValueError(f"field value {int(v)} does not fit in {width} bits")
        word = (word << width) | int(v)
    return word


def unpack_lanes(word: int, p: int, width: int, signed: bool = False, stride: int | None = None) -> np.ndarray:
    """A lane bus -> per-lane integers (lane 0 first): lane q is ``width`` bits at
    q * ``stride`` (default ``width``); shift ``word`` first to pick a field of a lane."""
    mask = (1 << width) - 1
    step = width if stride is None else stride
    vals = np.array([(int(word) >> (q * step)) & mask for q in range(p)], dtype=np.int64)
    if signed:
        vals = np.where(vals >= (1 << (width - 1)), vals - (1 << width), vals)
    return vals


def mask_bits(flags) -> int:
    """Per-lane booleans -> a lane mask (lane q = bit q)."""
    return sum(1 << q for q, f in enumerate(flags) if f)


class BeatSchedule:
    """The sample stream's beats of one view, in the order the hardware emits them."""

    def __init__(self, trav: Traversal, p: int, inside: np.ndarray, keep: np.ndarray | None = None,
                 rects=None, order=None) -> None:
        """inside: golden ``sample_stream`` inside flags, [m, j, i]; keep: the samples
        that count (golden ``Clip.keep`` per slice, [m, j, i]; None: all); rects: slice
        rectangles (cube4.slices.SliceRects): the beats of each slice's traversed
        rectangle (what GRA forwards), its positions valid (None: the whole box). order:
        the beats as (m, j, pb, runs) lists (the beat schedule's sample beats,
        beat_frames.expected_requests): positions valid only in the beats that run."""
        self.trav, self.p = trav, p
        M, nj, ni, nk = trav.num_sample_slices, trav.nj, trav.ni, trav.nk
        self.nb = nb = -(-ni // p)
        runs = None
        if order is not None:
            self.m, self.j, self.pb, runs = (np.array([o[c] for o in order], dtype=np.int64) for c in range(4))
            n = len(order)
            idx = np.arange(n)
        elif rects is None:
            n = M * nj * nb
            idx = np.arange(n)
            self.m, self.j, self.pb = idx // (nj * nb), (idx // nb) % nj, idx % nb
        else:
            order = [(m, j, pb) for m in range(M) if rects.beams(m, p) is not None
                     for j in range(*rects.beams(m, p)[:2])
                     for pb in range(rects.beams(m, p)[2], rects.beams(m, p)[3] + 1)]
            self.m, self.j, self.pb = (np.array([o[c] for o in order], dtype=np.int64) for c in range(3))
            n = len(order)
            idx = np.arange(n)
        fi, fj, fk = (bool(trav.flip[a]) for a in (trav.axis_i, trav.axis_j, trav.major))
        # skew: banks (c_i + c_j + c_k) mod p of the row above (j + 1) in the lower voxel
        # slice, in the whole volume (a box at trav.origin: its i offset included)
        k0 = self.m // trav.supersample
        cj = np.where(fj, nj - 1 - (self.j + 1), self.j + 1)
        ck = np.where(fk, nk - 1 - k0, k0)
        self.skew = (cj + ck + sum(trav.origin)) % p
        self.pos = np.stack([lane_positions(int(s), int(b), p, ni, fi) for s, b in zip(self.skew, self.pb)])
        self.lval = self.pos < ni
        if runs is not None:
            self.lval &= runs[:, None].astype(bool)
        if rects is not None:   # the traversed rectangle's columns
            lo = np.array([rects.traversed(int(m))[2] for m in self.m])
            hi = np.array([rects.traversed(int(m))[3] for m in self.m])
            self.lval &= (self.pos >= lo[:, None]) & (self.pos < hi[:, None])
        self.lins = self.lanes(inside).astype(bool)
        self.lkeep = self.lval if keep is None else self.lanes(keep).astype(bool) & self.lval
        sx, sy = trav.steps(self.m)
        sx1, sy1 = trav.steps(self.m + 1)
        sxb, syb = trav.steps(self.m - 1)
        self.ctrl = ((sx1 - sx) << CTRL_SX | (sy1 - sy) << CTRL_SY | (sx - sxb) << CTRL_OSX
                     | (sy - syb) << CTRL_OSY | (idx == 0) << CTRL_SOP | (idx == n - 1) << CTRL_EOP
                     | (self.j == nj - 1) << CTRL_YLAST)

    def __len__(self) -> int:
        return len(self.m)

    def lanes(self, stream: np.ndarray) -> np.ndarray:
        """A golden [m, j, i] (or [m, c, j, i] -> per c) array gathered into the beats'
        lanes, shape (beats, P) (or (beats, c, P)); 0 in lanes with no position."""
        ii = np.minimum(self.pos, self.trav.ni - 1)
        mm, jj = self.m[:, None], self.j[:, None]
        if stream.ndim == 4:
            vals = stream[mm[:, None], np.arange(stream.shape[1])[None, :, None], jj[:, None], ii[:, None, :]]
            return np.where(self.lval[:, None, :], vals, 0)
        return np.where(self.lval, stream[mm, jj, ii], 0)

    def headers(self, geo: Geometry) -> list[int]:
        """The HDR_W-bit header of every beat."""
        return [geo.pack_header({"inside": mask_bits(self.lins[n]), "lval": mask_bits(self.lval[n]),
                                 "keep": mask_bits(self.lkeep[n]),
                                 "ctrl": int(self.ctrl[n]), "skew": int(self.skew[n]),
                                 "pb": int(self.pb[n]), "j": int(self.j[n]), "m": int(self.m[n])})
                for n in range(len(self))]

    def describe(self, n: int, q: int | None = None) -> str:
        """Where beat n (and lane q) sits: for mismatch messages."""
        s = f"beat {n} (m={self.m[n]}, j={self.j[n]}, pb={self.pb[n]}"
        if q is not None:
            s += f", lane {q}: i={self.pos[n, q]}"
        return s + ")"

"""The CFB's schedule as golden beats, for the unit testbenches of cube4_cfb's units
(tb/cube4_cfb_*).

``cfb_walk`` lists the states of one frame of cube4_cfb in order, one per state advance:
the run beats of each pass (its walk's rows and partial beams, ``cube4.slices``), the flush
beam of a pass that flushes, one cycle for an empty pass, and the drain beat; with what the
state does (ends a row, ends the pass) and the row it emits (``SliceRects.emitted``'s
order). Without rectangles every pass walks the whole box and only the last flushes
(docs/architecture.md "Front end"). ``read_terms`` gives a read beat's address terms as the
traversal unit keeps them (``cube4.memory``: the row start A_j and c_j mod P, A_k and
c_k mod P, the partial-beam term), and ``read_addresses`` the address each bank must read.
"""

from __future__ import annotations

from dataclasses import dataclass

from cube4.memory import _axis_addr, _row_start, address_of, bank_of, frontend_regs


@dataclass
class CfbState:
    """One state of the CFB (one advance)."""

    kind: str                  # "run", "flush", "empty" (a pass with no walk), "drain"
    m: int                     # the pass
    j: int                     # the row walked (the pass's last row in its flush beam)
    pb: int                    # the partial beam
    sb: int = 0                # the slot j * NB + pb (the flush beam: its first row's)
    row: bool = False          # the beat ends a row that is not the pass's last
    pass_end: bool = False     # the pass's last run beat (or its empty cycle)
    pass_done: bool = False    # the state moves on to the next pass (or the drain beat)
    last: bool = False         # the pass ends the frame
    emit: tuple | None = None  # (m, j) of the row the beat emits
    read: int | None = None    # the voxel slice it reads (None: no read)


def _walks(trav, p: int, rects):
    """Per pass: (rows [j0, j1), partial beams [pb0, pb1], flushes, rows that read) or None."""
    M, nb = trav.num_sample_slices, _nb(trav, p)
    if rects is None:
        return [((0, trav.nj), (0, nb - 1), m == M - 1, (0, trav.nj)) for m in range(M)]
    out = []
    for m in range(rects.last() + 1):
        w = rects.walk(m, p)
        tj0, tj1 = rects.traversed(m)[:2]
        out.append(None if w is None else ((w[0], w[1]), (w[2], w[3]), rects.flushes(m, p), (tj0, tj1)))
    return out


def _nb(trav, p: int) -> int:
    return -(-trav.ni // p)


def read_slice(trav, m: int) -> int | None:
    """The voxel slice pass m reads: pass 0 its lower slice, pass k0*S + 1 the upper
    k0 + 1 (S > 1), every pass its own with S = 1 (docs/architecture.md "Front end")."""
    s = trav.supersample
    k0, r = divmod(m, s)
    if s == 1 or m == 0:
        return k0
    return k0 + 1 if r == 1 else None


def cfb_walk(trav, p: int, rects=None) -> list[CfbState]:
    """The states of one frame, in order (rects: cube4.slices.SliceRects, S = 1)."""
    walks, nb = _walks(trav, p, rects), _nb(trav, p)
    out: list[CfbState] = []
    pend = None
    for m, w in enumerate(walks):
        last = m == len(walks) - 1
        if w is None:
            out.append(CfbState("empty", m, 0, 0, pass_end=True, pass_done=True))
            continue
        (j0, j1), (pb0, pb1), flush, (tj0, tj1) = w
        k = read_slice(trav, m)
        for j in range(j0, j1):
            for pb in range(pb0, pb1 + 1):
                emit = (m, j - 1) if j > j0 else pend
                end = j == j1 - 1 and pb == pb1
                out.append(CfbState("run", m, j, pb, j * nb + pb, row=pb == pb1 and not end, pass_end=end,
                                    pass_done=end and not flush, last=last, emit=emit,
                                    read=k if tj0 <= j < tj1 else None))
        pend = None if flush else (m, j1 - 1)
        if flush:
            for pb in range(pb0, pb1 + 1):
                out.append(CfbState("flush", m, j1 - 1, pb, j0 * nb + pb, pass_done=pb == pb1, last=last, emit=(m, j1 - 1)))
    out.append(CfbState("drain", len(walks) - 1, 0, 0))
    return out


def read_terms(trav, p: int, k: int, j: int, pb: int, addr_w: int) -> dict[str, int]:
    """The address terms of a read beat (voxel slice k, row j, partial beam pb): aj, ak, pbx
    (modulo 2^addr_w) and the skew (c_j + c_k) mod P (the box at the volume's origin)."""
    regs = frontend_regs(trav, p)
    fk = bool(trav.flip[trav.major])
    ck = trav.nk - 1 - k if fk else k
    aj, rj = _row_start(trav, p, trav.dims, j)
    fi = bool(trav.flip[trav.axis_i])
    pbx = regs["I_A0"] - pb * regs["I_PB"] if fi else pb * regs["I_PB"]
    mask = (1 << addr_w) - 1
    return {"aj": aj & mask, "ak": _axis_addr(trav.major, ck, trav.dims, p) & mask, "pbx": pbx & mask,
            "skew": (rj + ck % p) % p}


def read_addresses(trav, p: int, k: int, j: int, pb: int, i_range=None) -> list[int | None]:
    """Per bank: the address it must read for the read beat (k, j, pb), None where it reads
    nothing (padding, or outside the positions [lo, hi) of ``i_range``)."""
    lo, hi = (0, trav.ni) if i_range is None else i_range
    addr: list[int | None] = [None] * p
    for i in range(max(lo, pb * p), min(hi, pb * p + p)):
        x, y, z = (int(c) for c in trav.traversal_to_volume_points(i, j, k))
        addr[int(bank_of(x, y, z, p))] = int(address_of(x, y, z, trav.dims, p))
    return addr


def tag_offsets(p: int, max_dim: int, ss_log2: int, weight_w: int) -> dict[str, int]:
    """Bit offsets of the CFB beat tag's fields (cube4_defs.vh CUBE4_TAG_LAYOUT), "F1" the
    width of the fields below the lane masks and "W" the tag's."""
    from .beats import Geometry, clog2

    geo = Geometry(p, max_dim, ss_log2)
    off, pos = {}, 0
    for name, w in (("STEPS", 4), ("YLAST", 1), ("SKEW", geo.lane_w), ("J", geo.dim_w), ("M", geo.m_w),
                    ("WZ", weight_w), ("WY", weight_w), ("WX", weight_w), ("PB", geo.pb_w),
                    ("SB", clog2(max_dim * geo.nbmax)), ("K0ODD", 1), ("UUSE", 1), ("UMEM", 1), ("LMEM", 1),
                    ("BBWE", 1), ("YWRAP", 1), ("EOP", 1), ("SOP", 1), ("EMIT", 1), ("LWRAP", p), ("LNBR", p),
                    ("LVAL", p), ("LINL", p)):
        off[name], pos = pos, pos + w
    off["F1"], off["W"] = off["LWRAP"], pos
    return off


def template(trav, m: int) -> tuple[int, int, int, int]:
    """The template of pass m as cube4_cfb_tmpl gives it: wx, wy, wz (``Traversal.weights``)
    and the steps {old Y, old X, Y, X} (``Traversal.steps`` m-1 -> m, m -> m+1) as 4 bits."""
    wx, wy, wz = (int(w) for w in trav.weights(m))
    (sx0, sy0), (sx1, sy1), (sx2, sy2) = (trav.steps(k) for k in (m - 1, m, m + 1))
    return wx, wy, wz, int(sx2 - sx1) | int(sy2 - sy1) << 1 | int(sx1 - sx0) << 2 | int(sy1 - sy0) << 3

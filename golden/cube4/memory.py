"""Skewed voxel memory and the front end's view registers: the host side of the RTL.

One implementation, used by the tests, the RTL render engine and anyone who wants to
know where a voxel lives (docs/architecture.md, "Voxel memory"):

* **Skew (Teramac eq. 1):** voxel (x, y, z) lives in bank ``(x + y + z) mod p``. Any
  ``p`` consecutive voxels along any axis fall in ``p`` different banks, so a partial
  beam along x, y or z is read in one cycle, conflict free, for every view.
* **Partition (eq. 2, generalised):** within a bank the address is
  ``floor(x / p) + NBX * (y + ny * z)`` with ``NBX = ceil(nx / p)``. Each beam along x
  occupies ``NBX`` words of every bank, as in eq. 2 (``n / p`` words), but the words are
  ordered by ``floor(x / p)`` rather than by ``floor(((x + y + z) mod n) / p)``, so a
  partial beam is always x-contiguous and beam extension only ever needs the next
  partial beam (eq. 2's order wraps x around inside a partial beam). x is padded to
  ``NBX * p`` with zeros; y and z need no padding, and any nx, ny, nz work with any p.

**Other axis orders** (``order``, the volume axes from the image's fastest to its
slowest; default ``XYZ`` = (0, 1, 2), the layout above): the same layout of the volume
with its axes permuted, ``floor(c_f / p) + NBF * (c_m + n_m * c_s)``, the bank unchanged
(the skew is symmetric in x, y, z). A DRAM build keeps three images
(docs/architecture.md, "Voxel memory in DRAM"): each view reads the one ordered
(i, j, k), its traversal's axes, so that it reads its slices as one run of columns.

``frontend_regs`` turns a ``view.Traversal`` into the register values the CFB needs
(start coordinates, per-axis address strides, partial-beam counts); ``lane_positions``
says which sample position each pipeline lane of an output beat holds.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .clip import CUT_E_W, CUT_T_NONE, CUT_W, REGIONS_ALL, check_window  # the cut plane's register widths (cube4_defs.vh)
from .errors import UserError
from .modes import MODE_CODES
from .view import Traversal


XYZ = (0, 1, 2)


def check_order(order) -> tuple[int, int, int]:
    """An image's axis order: a permutation of the volume axes 0, 1, 2 (x, y, z), from
    the fastest to the slowest."""
    order = tuple(int(a) for a in order)
    if sorted(order) != [0, 1, 2]:
        raise ValueError(f"an image's axis order is a permutation of (0, 1, 2), got {order}")
    return order


def words_per_bank(dims, p: int, order=XYZ) -> int:
    """Words each bank needs for a volume of dims (nx, ny, nz)."""
    f, m, s = (int(dims[a]) for a in check_order(order))
    return -(-f // p) * m * s


def bank_of(x, y, z, p: int):
    """Bank (= pipeline) holding voxel (x, y, z)."""
    return (np.asarray(x) + np.asarray(y) + np.asarray(z)) % p


def address_of(x, y, z, dims, p: int, order=XYZ):
    """Word address of voxel (x, y, z) inside its bank (in the image of axis order ``order``)."""
    order = check_order(order)
    if order != XYZ:
        c = (x, y, z)
        return address_of(*(c[a] for a in order), tuple(dims[a] for a in order), p)
    nx, ny, _ = (int(n) for n in dims)
    nbx = -(-nx // p)
    return np.asarray(x) // p + nbx * (np.asarray(y) + ny * np.asarray(z))


def pack_volume(vol: np.ndarray, p: int, order=XYZ) -> np.ndarray:
    """Bank images of vol[z, y, x]: array (p, words_per_bank) of the voxel values (in the
    image of axis order ``order``)."""
    order = check_order(order)
    if order != XYZ and vol.ndim == 3:
        # vol's array axis of volume axis a is 2 - a: the image's (slow, mid, fast)
        return pack_volume(np.transpose(vol, [2 - a for a in order[::-1]]), p)
    if vol.ndim != 3:
        raise UserError(f"a volume must be 3-D, got shape {vol.shape}")
    if not 1 <= p <= 64:
        raise UserError(f"p must be in 1..64, got {p}")
    nz, ny, nx = vol.shape
    nbx = -(-nx // p)
    vp = np.zeros((nz, ny, nbx * p), dtype=np.int64)
    vp[:, :, :nx] = vol
    z, y, x = np.meshgrid(np.arange(nz), np.arange(ny), np.arange(nbx * p), indexing="ij")
    banks = np.zeros((p, nbx * ny * nz), dtype=np.int64)
    banks[bank_of(x, y, z, p), x // p + nbx * (y + ny * z)] = vp
    return banks


def unpack_volume(banks: np.ndarray, dims) -> np.ndarray:
    """Inverse of pack_volume: vol[z, y, x] from the bank images."""
    p = banks.shape[0]
    nx, ny, nz = (int(n) for n in dims)
    z, y, x = np.meshgrid(np.arange(nz), np.arange(ny), np.arange(nx), indexing="ij")
    return banks[bank_of(x, y, z, p), address_of(x, y, z, dims, p)]


def load_image(banks: np.ndarray) -> np.ndarray:
    """The voxel memory's load image: word a of bank q at position a * p + q, the order
    in which the simulation harnesses stream it through the load port."""
    return np.asarray(banks).T.reshape(-1)


def write_hex(path: str | Path, words, bits: int) -> Path:
    """Write unsigned words (Python ints above 63 bits) as a ``$readmemh`` image, one word per line, ``ceil(bits / 4)``
    hex digits each. The file is written under a temporary name and renamed into place,
    so a reader never sees half a file."""
    path = Path(path)
    # words wider than 63 bits come as Python ints (dtype object)
    words = np.asarray(words, dtype=object if bits > 63 else np.int64).reshape(-1)
    if words.size and (min(words) < 0 or int(max(words)) >> bits):
        raise ValueError(f"{path.name}: a word does not fit in {bits} unsigned bits")
    digits = -(-bits // 4)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text("".join(f"{int(v):0{digits}x}\n" for v in words))
    tmp.replace(path)
    return path


# ----------------------------------------------------------------- view registers
def _axis_addr(axis: int, c: int, dims, p: int, order=XYZ) -> int:
    """Address contribution of coordinate c along a volume axis."""
    f, m, _ = order
    nbf = -(-int(dims[f]) // p)
    pos = order.index(axis)
    return (c // p, nbf * c, nbf * int(dims[m]) * c)[pos]


def _axis_strides(axis: int, dims, p: int, order=XYZ) -> tuple[int, int]:
    """(LIN, BLK): address change for a unit step that stays inside / crosses a
    p-block of the coordinate. Linear axes (the image's y, z) have LIN == BLK; its x has (0, 1)."""
    f, m, _ = order
    nbf = -(-int(dims[f]) // p)
    pos = order.index(axis)
    return ((0, 1), (nbf, nbf), (nbf * int(dims[m]), nbf * int(dims[m])))[pos]


def _row_start(trav: Traversal, p: int, dims, j: int, order=XYZ) -> tuple[int, int]:
    """(A_j, c_j mod P) of traversal row j as the CFB keeps them (J_A0 and J_R0 at row 0):
    the j axis's address term, with the i axis's start address joined when i is not
    flipped; the residue, with the box's i offset joined when j is not the x axis."""
    org = tuple(int(c) for c in trav.origin)
    ai, aj = trav.axis_i, trav.axis_j
    fi, fj = bool(trav.flip[ai]), bool(trav.flip[aj])
    cj = org[aj] + (trav.nj - 1 - j if fj else j)
    a_i0 = 0 if fi else _axis_addr(ai, org[ai], dims, p, order)
    r = cj % p if aj == order[0] else (cj % p + org[ai]) % p
    return _axis_addr(aj, cj, dims, p, order) + a_i0, r


def frontend_regs(trav: Traversal, p: int, vol_dims=None, order=XYZ, base: int = 0) -> dict[str, int]:
    """Register values of cube4_frontend for one view (docs/architecture.md, "CFB").

    The host computes them the way it computes VIEW_X / VIEW_Y: a handful of
    additions and multiplications per frame, none per voxel. ``vol_dims`` are the dims
    of the volume in memory (default trav.dims): a crop box or a brick (trav.origin,
    trav.dims) is traversed inside it by start addresses and lane residues alone.
    ``order``: the axis order of the image the frame reads, at word ``base`` of every
    bank (a DRAM build holds three images one after the other).
    """
    box = tuple(int(n) for n in trav.dims)
    dims = box if vol_dims is None else tuple(int(n) for n in vol_dims)
    org = tuple(int(c) for c in trav.origin)
    if any(o + b > d for o, b, d in zip(org, box, dims)):
        raise UserError(f"the traversed box {box} at {org} does not fit the volume {dims}")
    ni, nj, nk = trav.ni, trav.nj, trav.nk
    ai, aj, ak = trav.axis_i, trav.axis_j, trav.major
    fi, fj, fk = (bool(trav.flip[a]) for a in (ai, aj, ak))
    ck0 = org[ak] + (nk - 1 if fk else 0)       # start coordinates in the volume
    ci0 = org[ai] + (ni - 1 if fi else 0)
    order = check_order(order)
    j_lin, j_blk = _axis_strides(aj, dims, p, order)
    k_lin, k_blk = _axis_strides(ak, dims, p, order)
    i_lin, i_blk = _axis_strides(ai, dims, p, order)
    i_block = ai == order[0]  # the image's fastest axis: address is floor(c / p)
    # The skew is (c_i + c_j + c_k) mod p with lane t at c_i = org_i + t (flipped:
    # org_i + ni - 1 - t): the box's i offset joins the residue of an axis that is not x
    # (y and z have LIN == BLK, so their residue only feeds the skew).
    a_j0, r_j = _row_start(trav, p, dims, 0, order)
    r_k = ck0 % p if aj != order[0] else (ck0 % p + org[ai]) % p
    # The i axis's start address: flipped, I_A0 (the CFB counts down from it); not
    # flipped the CFB starts at 0, so it joins J_A0 (_row_start).
    if fi:
        i_rt = (ci0 % p) if i_block else p - 1
    else:
        i_rt = (p - 1 - org[ai] % p) if i_block else p - 1
    return {
        "NI": ni,
        "NJ": nj,
        "NK": nk,
        "NB": -(-ni // p),
        "FLIP_I": int(fi),
        "FLIP_J": int(fj),
        "FLIP_K": int(fk),
        "SS_LOG2": trav.guard_bits,
        "VIEW_X": trav.view_x,
        "VIEW_Y": trav.view_y,
        # axis j (beam index): start coordinate mod p, start address, strides
        "J_R0": r_j,
        "J_A0": a_j0,
        "J_LIN": j_lin,
        "J_BLK": j_blk,
        # axis k (slices)
        "K_R0": r_k,
        "K_A0": _axis_addr(ak, ck0, dims, p, order) + base,
        "K_LIN": k_lin,
        "K_BLK": k_blk,
        # axis i (along the beam): address = I_A0 +/- (pb * I_PB + t * I_LIN + [t > I_RT])
        "I_A0": _axis_addr(ai, ci0, dims, p, order) if fi else 0,
        "I_PB": i_blk if i_block else i_lin * p,
        "I_LIN": 0 if i_block else i_lin,
        "I_RT": i_rt,
        "I_R1": (ni - 1) % p,
    }


def top_regs(trav: Traversal, p: int, vol_dims=None, mode: str = "composite", clip=None,
             path_weights: bool = False, depth_t: int | None = None, order=XYZ,
             base: int = 0, beats=None) -> dict[str, int]:
    """Registers of cube4_top: the front end's plus the base-plane offsets
    SX, SY = stepx(M-1), stepy(M-1) (numerics.md section 8), the mode, the template's
    starting phase, the window and cut plane (clip.Clip; None: every sample counts), and
    FACES: the box's faces that are the volume's when the frame is path-weighted
    (numerics.md section 17), else 0.
    Signed registers (CUT_*) are given as their two's-complement bit patterns.
    ``order``, ``base``: the image the frame reads and where (frontend_regs); ``beats``:
    the beat schedule's (BeatSchedule, TerminationRule) (beat_regs)."""
    regs = frontend_regs(trav, p, vol_dims, order, base)
    regs["SX"], regs["SY"] = trav.max_steps
    regs["MODE"] = MODE_CODES[mode]
    regs["PH0_X"], regs["PH0_Y"] = trav.phase_x, trav.phase_y
    M = trav.num_sample_slices
    window = (0, trav.ni, 0, trav.nj, 0, M) if clip is None or clip.window is None else clip.window
    check_window(window, trav)
    for name, v in zip(("WIN_I0", "WIN_I1", "WIN_J0", "WIN_J1", "WIN_M0", "WIN_M1"), window):
        regs[name] = int(v)
    regions = (0, 0, 0, 0, 0, 0, REGIONS_ALL) if clip is None or clip.regions is None else clip.regions
    for name, v in zip(("CR_I0", "CR_I1", "CR_J0", "CR_J1", "CR_M0", "CR_M1"), regions[:6]):
        regs[name] = int(v)
    regs["CR_HIDE"] = REGIONS_ALL & ~int(regions[6])      # the regions that do not count
    plane = (0, 0, 0, 0) if clip is None or clip.plane is None else clip.plane
    for name, v, w in zip(("CUT_A", "CUT_B", "CUT_C", "CUT_D"), plane, (CUT_W, CUT_W, CUT_W, CUT_E_W)):
        regs[name] = int(v) & ((1 << w) - 1)
    slab = (CUT_T_NONE, 0, 0) if clip is None or clip.slab is None else clip.slab
    for name, v in zip(("CUT_T", "FALL_SH", "FALL_ON"), slab):
        regs[name] = int(v)
    regs["DEPTH_T"] = 0 if depth_t is None else int(depth_t)     # depth out's threshold on T (ZOUT)
    regs["FACES"] = int(trav.faces) if path_weights else 0
    regs.update(beat_regs(trav, beats))
    return regs


def beat_regs(trav: Traversal, beats=None) -> dict[str, int]:
    """The beat schedule's view registers (BEATS = 1; cube4_defs.vh): BB_I, BB_J, BB_K the
    frame's i, j, k axes' bases in the volume (the coordinate of traversal index 0, the
    block table's reads count from it up, or down where the axis is flipped), NBR the
    neighbour term, TERM, TAU, VMIN, VMAX ray termination's rule. ``beats``: the frame's
    (BeatSchedule, TerminationRule); None: all 0."""
    regs = dict.fromkeys(("BB_I", "BB_J", "BB_K", "NBR", "TERM", "TAU", "VMIN", "VMAX"), 0)
    if beats is None:
        return regs
    sched, rule = beats
    for name, a in (("BB_I", trav.axis_i), ("BB_J", trav.axis_j), ("BB_K", trav.major)):
        regs[name] = int(trav.origin[a] + (trav.dims[a] - 1 if trav.flip[a] else 0))
    regs["NBR"] = int(sched.neighbours)
    regs["TERM"] = int(rule.enabled)
    regs["TAU"], regs["VMIN"], regs["VMAX"] = int(rule.tau), int(rule.vmin), int(rule.vmax)
    return regs


def rect_table(trav: Traversal, rects, p: int, addr_w: int, vol_dims=None) -> list[dict[str, int]]:
    """The rectangle table of cube4_cfb (RECTS = 1; cube4_defs.vh CUBE4_RECT_LAYOUT) for
    the slice rectangles ``rects`` (cube4.slices.SliceRects) of ``trav``: one entry per
    sample slice, the fields as lower-case names of the harness ports (rt_*)."""
    if trav.supersample != 1:
        raise UserError("slice rectangles run with S = 1 only (the slice buffers replay whole slices)")
    box = tuple(int(n) for n in trav.dims)
    dims = box if vol_dims is None else tuple(int(n) for n in vol_dims)
    regs = frontend_regs(trav, p, vol_dims)
    nb, mask = regs["NB"], (1 << addr_w) - 1
    fi = bool(trav.flip[trav.axis_i])
    table = []
    last = rects.last()
    for m in range(trav.num_sample_slices):
        walk = rects.walk(m, p) if m <= last else None
        if walk is None:
            table.append({"empty": 1, **{k: 0 for k in RECT_FIELDS if k != "empty"}})
            continue
        j0, j1, pb0, pbl = walk
        tj0, tj1, i0, i1 = rects.traversed(m)   # (0, 0, 0, 0): a walk with no sample (no lane valid)
        jin, _, iin, _ = rects.bounds(m)
        aj0, rj0 = _row_start(trav, p, dims, j0)
        pbx0 = regs["I_A0"] - pb0 * regs["I_PB"] if fi else pb0 * regs["I_PB"]
        table.append({"empty": 0, "flush": int(rects.flushes(m, p)), "last": int(m == last),
                      "j0": j0, "jl": j1 - 1, "j_in": jin, "pb0": pb0, "pbl": pbl,
                      "i_lo": i0, "i_in": iin, "i_hi": i1, "aj0": aj0 & mask, "rj0": rj0,
                      "pbx0": pbx0 & mask, "pbp0": pb0 * p, "sb0": j0 * nb + pb0,
                      "sbrow": nb - (pbl - pb0), "tj0": tj0, "tjl": max(tj1 - 1, 0),
                      **_inside_fields(trav, rects, m)})
    return table


def _inside_fields(trav: Traversal, rects, m: int) -> dict[str, int]:
    """COM's fields of slice m's entry: whether it has an inside rectangle (INS), its high
    sides J_HI, I_HIN (SliceRects.inside: less a row / column where wy / wx > 0; its low
    sides are J_IN, I_IN) and its steps."""
    stx, sty = (int(v) for v in trav.steps(m))
    wx, wy, _ = (int(w) for w in trav.weights(m))
    j0, j1, i0, i1 = rects.bounds(m)
    j_hi, i_hin = j1 - 1 - (wy > 0), i1 - 1 - (wx > 0)
    ins = not rects.empty(m) and j_hi >= j0 and i_hin >= i0
    return {"ins": int(ins), "j_hi": max(j_hi, 0), "i_hin": max(i_hin, 0), "stx": stx, "sty": sty}


#: the fields of a rectangle-table entry (rt_<name> ports of the harnesses)
RECT_FIELDS = ("empty", "flush", "last", "j0", "jl", "j_in", "pb0", "pbl", "i_lo", "i_in", "i_hi", "aj0", "rj0",
               "pbx0", "pbp0", "sb0", "sbrow", "tj0", "tjl", "j_hi", "i_hin", "stx", "sty", "ins")


def lane_positions(skew: int, pb: int, p: int, ni: int, flip_i: bool) -> np.ndarray:
    """Position i held by each lane q of a beat with the given skew and partial beam.

    Lane q holds the position whose bank is q: t = (q - skew) mod p, or for a flipped
    i axis t = ((ni - 1) + skew - q) mod p; i = pb * p + t. Positions >= ni are padding.
    """
    q = np.arange(p)
    t = (((ni - 1) + skew - q) if flip_i else (q - skew)) % p
    return pb * p + t


def stop_layout(p: int, max_dim: int) -> tuple[int, int]:
    """(ROWS_W, COLS_W) of the stop table (cube4_defs.vh CUBE4_STOP_LAYOUT): a base plane
    has at most 2 max_dim - 1 rows and columns; a bank's word is {by, bx div p}."""
    rows_w = (2 * max_dim - 1).bit_length()
    cols = -(-2 * max_dim // p)
    return rows_w, max(1, (cols - 1).bit_length())


def stop_table(stop: np.ndarray | None, p: int, max_dim: int, m_bits: int) -> list[int]:
    """Depth in's stop table (ZIN = 1, rtl/cube4_com_stop.v, docs/numerics.md §22): per
    address {by [ROWS_W], bx div p [COLS_W]} one word of p banks, bank b = the stop slice of
    pixel (by, bx = (bx div p) p + b) at bits [b m_bits, (b + 1) m_bits). ``stop``: (rows,
    cols) stop slices of the frame's base plane (cube4.geometry.stop_slices, 0 .. M), None:
    no geometry. Words of no pixel, and every word without geometry, hold 2^m_bits - 1 (no
    slice reaches it)."""
    rows_w, cols_w = stop_layout(p, max_dim)
    none = (1 << m_bits) - 1
    table = np.full((1 << rows_w, 1 << cols_w, p), none, dtype=np.int64)
    if stop is not None:
        rows, cols = stop.shape
        if rows > 1 << rows_w or -(-cols // p) > 1 << cols_w:
            raise ValueError(f"a {rows}x{cols} base plane does not fit the stop table of MAX_DIM = {max_dim}")
        if stop.size and (stop.min() < 0 or stop.max() > none):
            raise ValueError(f"stop slices must lie in 0 .. {none} ({m_bits} bits)")
        padded = np.full((rows, -(-cols // p) * p), none, dtype=np.int64)
        padded[:, :cols] = stop
        table[:rows, :padded.shape[1] // p] = padded.reshape(rows, -1, p)
    shifts = np.arange(p, dtype=object) * m_bits
    flat = table.reshape(-1, p).astype(object)
    return [int(sum(int(v) << int(s) for v, s in zip(row, shifts))) for row in flat]

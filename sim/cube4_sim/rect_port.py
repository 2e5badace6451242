"""The rectangle table's write port of the harnesses (rect_we, rect_addr and one rt_<field>
port per field of CUBE4_RECT_LAYOUT), driven from cocotb."""

from __future__ import annotations

from cube4.memory import RECT_FIELDS, rect_table

from .beats import Geometry, clog2


async def write_rect_table(dut, trav, rects, p: int, addr_w: int) -> None:
    """Write the table of ``rects`` (cube4.memory.rect_table), one entry a clock, then
    leave the port idle."""
    from cocotb.triggers import RisingEdge   # only in a simulation: the host side imports no cocotb

    for m, entry in enumerate(rect_table(trav, rects, p, addr_w)):
        for name, val in entry.items():
            getattr(dut, "rt_" + name).value = int(val)
        dut.rect_addr.value = m
        dut.rect_we.value = 1
        await RisingEdge(dut.clk)
    dut.rect_we.value = 0


def rect_layout(p: int, max_dim: int, addr_w: int) -> list[tuple[str, int]]:
    """(field, width) of a rectangle-table entry, LSB first (cube4_defs.vh CUBE4_RECT_LAYOUT)."""
    geo = Geometry(p, max_dim, 0)
    dim, pbw, lane = geo.dim_w, geo.pb_w, geo.lane_w
    iw = clog2(max_dim + 2 * p + 1)
    sbw = clog2(max_dim * geo.nbmax)
    widths = {"empty": 1, "flush": 1, "last": 1, "j0": dim, "jl": dim, "j_in": dim, "pb0": pbw, "pbl": pbw,
              "i_lo": dim, "i_in": dim, "i_hi": dim, "aj0": addr_w, "rj0": lane, "pbx0": addr_w, "pbp0": iw,
              "sb0": sbw, "sbrow": sbw, "tj0": dim, "tjl": dim, "j_hi": dim, "i_hin": dim, "stx": dim,
              "sty": dim, "ins": 1}
    return [(name, widths[name]) for name in RECT_FIELDS]


def rect_words(trav, rects, p: int, max_dim: int, addr_w: int, vol_dims=None) -> list[int]:
    """The table of ``rects`` as MAX_DIM words of RECT_W bits (entries past the frame's
    slices zero): the image cube4_top_harness loads with the tables."""
    layout = rect_layout(p, max_dim, addr_w)
    words = [rect_word(entry, layout) for entry in rect_table(trav, rects, p, addr_w, vol_dims)]
    if len(words) > max_dim:
        raise ValueError(f"{len(words)} slices do not fit a table of {max_dim} entries")
    return words + [0] * (max_dim - len(words))


def rect_word(entry: dict[str, int], layout: list[tuple[str, int]]) -> int:
    """One table entry (field -> value) as a RECT_W-bit word (``rect_layout``)."""
    word, pos = 0, 0
    for name, w in layout:
        v = int(entry[name])
        if not 0 <= v < (1 << w):
            raise ValueError(f"rectangle table field {name} = {v} does not fit {w} bits")
        word |= v << pos
        pos += w
    return word


def rect_width(p: int, max_dim: int, addr_w: int) -> int:
    return sum(w for _, w in rect_layout(p, max_dim, addr_w))

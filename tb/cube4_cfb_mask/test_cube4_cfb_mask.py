"""Unit testbench of rtl/cube4_cfb_mask.v: the CFB's beat pipeline and lane masks.

The states of golden frames (``cube4_sim.cfb_walk`` over random ``cube4.slices``
rectangles and the whole box, their entries from ``cube4.memory.rect_table``) are offered
as the control unit gives them: issue, the read row's lane positions (``read_terms``'
skew, on t1 one stage later as cube4_cfb_addr gives them), the emitted row's skew, pass
bounds and row flags, random tag fields. The request stream is taken with seeded random
stalls (req_ready) and must carry exactly the issued beats, in order, each with its fields
unchanged and the lane bits of the tag layout (cube4_defs.vh) from the golden positions
(``cube4.memory.lane_positions``):

* rden   the read row's position is in [I_LO, I_HI) of the pass;
* LVAL   the emitted row holds samples and its position is in [I_LO, I_HI) of its pass;
* LNBR   position + 1 < I_HI;  LWRAP  the lane's t is P - 1;  LINL  inside from I_IN.

After the frame the request stream stays empty and busy falls.
"""

from __future__ import annotations

import cocotb
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

import cube4.slices as slices
from cube4.memory import lane_positions, rect_table
from cube4.view import make_traversal
from cube4_sim.beats import mask_bits, pack_lanes
from cube4_sim.cfb_walk import cfb_walk, read_terms, tag_offsets
from cube4_sim.rect_port import rect_layout, rect_word
from cube4_sim.unit_bench import UnitBench, param_id, run_unit
from cube4_sim.sweeps import sweep

VIEWS = [((0.3, -0.45, 1.0), (13, 9, 6)), ((-0.6, 0.25, -1.0), (11, 10, 5)), ((1.0, -0.4, 0.7), (9, 12, 6))]


def beat_inputs(trav, p: int, aw: int, st, table, rng, f1: int) -> dict:
    """The control unit's outputs for state st (and the read row's lane positions)."""
    fi = bool(trav.flip[trav.axis_i])
    e = table[st.m]
    skew_rd = read_terms(trav, p, st.read, st.j, st.pb, aw)["skew"] if st.read is not None else int(rng.integers(p))
    me, je = st.emit if st.emit else (st.m, int(rng.integers(trav.nj)))
    pe = table[me]
    wy = int(trav.weights(me)[1])
    use_prev = int(me != st.m or st.kind == "flush")
    return {"issue": int(st.kind != "empty"), "fields": mask_bits(rng.integers(0, 2, f1)), "pbp": st.pb * p,
            "rd": int(st.read is not None), "use_prev": use_prev,
            "skew_out": read_terms(trav, p, me, je + 1, st.pb, aw)["skew"],
            "rowv": int(st.emit is not None and pe["tj0"] <= je <= pe["tjl"]),
            "rowin": int(st.emit is not None and je >= pe["j_in"] and not (je == pe["tjl"] and wy > 0)),
            "p_ilo": pe["i_lo"], "p_iin": pe["i_in"], "p_ihi": pe["i_hi"], "_e": e, "_pe": pe,
            "_t_rd": lane_positions(skew_rd, 0, p, trav.ni, fi), "_pb": st.pb}


def expected(trav, p: int, b: dict, off: dict) -> tuple[int, int]:
    """(rden, tag) of a beat from the golden lane positions."""
    fi = bool(trav.flip[trav.axis_i])
    e, pb = b["_e"], b["_pb"]
    bo = b["_pe"] if b["use_prev"] else e
    pos_rd = pb * p + b["_t_rd"]
    pos = lane_positions(b["skew_out"], pb, p, trav.ni, fi)
    rden = b["rd"] & (pos_rd >= e["i_lo"]) & (pos_rd < e["i_hi"])
    lval = b["rowv"] & (pos >= bo["i_lo"]) & (pos < bo["i_hi"])
    lnbr = pos + 1 < bo["i_hi"]
    lwrap = pos - pb * p == p - 1
    linl = b["rowin"] & (pos >= bo["i_in"])
    tag = (b["fields"] | mask_bits(lwrap) << off["LWRAP"] | mask_bits(lnbr) << off["LNBR"]
           | mask_bits(lval) << off["LVAL"] | mask_bits(linl) << off["LINL"])
    return mask_bits(rden), tag


async def play(dut, bench, trav, p: int, aw: int, table: list[dict], rects, off: dict, stall: float) -> int:
    layout = rect_layout(p, int(dut.MAX_DIM.value), aw)
    beats = [beat_inputs(trav, p, aw, st, table, bench.rng, off["F1"]) for st in cfb_walk(trav, p, rects)]
    want = [expected(trav, p, b, off) for b in beats if b["issue"]]
    got, k, s1, quiet = [], 0, None, 0
    # the first entry an edge before the first beat: with RECTS = 0 it is the box, a view
    # constant the unit registers (cube4_cfb_box's NI, as the view registers are stable
    # before a frame starts)
    if beats:
        dut.rt_cur.value = rect_word(beats[0]["_e"], layout)
        await FallingEdge(dut.clk)
    while quiet < 20:
        await FallingEdge(dut.clk)
        b = beats[k] if k < len(beats) else None
        dut.idle.value = int(b is None)
        dut.issue.value = 0 if b is None else b["issue"]
        if b is not None:
            for name, val in b.items():
                if not name.startswith("_") and name != "issue":
                    getattr(dut, name).value = val
            dut.rt_cur.value = rect_word(b["_e"], layout)
        dut.t1.value = 0 if s1 is None else pack_lanes(s1["_t_rd"], max(1, (p - 1).bit_length()))
        ready = int(b is None or bench.rng.random() >= stall)
        dut.req_ready.value = ready * ((1 << len(dut.req_ready)) - 1)   # its equal copies
        await ReadOnly()
        if ready and int(dut.req_valid.value):
            got.append((int(dut.req_rden.value), int(dut.req_tag.value)))
            n = len(got) - 1
            assert n < len(want), f"beat {n}: more than the {len(want)} issued beats"
            assert got[n] == want[n], (f"beat {n} (rden, tag): RTL ({got[n][0]:#x}, {got[n][1]:#x}), "
                                       f"golden ({want[n][0]:#x}, {want[n][1]:#x})")
        adv = int(dut.advance.value)         # CFB_ADV_N copies, all equal
        assert adv in (0, (1 << len(dut.advance)) - 1), f"advance's copies differ: {adv:#b}"
        if adv and b is not None:
            s1, k = b, k + 1
        quiet = quiet + 1 if b is None else 0
    assert len(got) == len(want), f"{len(got)} beats out, {len(want)} issued"
    assert not int(dut.busy.value), "busy after the frame"
    await FallingEdge(dut.clk)
    return len(want)


@cocotb.test()
async def test_mask(dut):
    p, md, aw, w = (int(getattr(dut, n).value) for n in ("P", "MAX_DIM", "ADDR_W", "WEIGHT_W"))
    off = tag_offsets(p, md, int(dut.MAX_SS_LOG2.value), w)
    bench = UnitBench(dut)
    await bench.reset({"idle": 1, "issue": 0, "req_ready": 0})
    total = 0
    for n, (direction, dims) in enumerate(VIEWS):
        trav = make_traversal(dims, direction, w, 1)
        bench.set_view(trav, p)
        stall = (0.0, 0.3, 0.6)[n % 3]
        whole = rect_table(trav, slices.whole_box_rects(trav), p, aw)
        total += await play(dut, bench, trav, p, aw, whole, None, off, stall)
        for density in (0.05, 0.3) if int(dut.RECTS.value) else ():
            need = bench.rng.random((trav.num_sample_slices, trav.nj, trav.ni)) < density
            rects = slices.rects_from_needed(need, trav)
            if rects.last() >= 0:
                total += await play(dut, bench, trav, p, aw, rect_table(trav, rects, p, aw), rects, off, stall)
    dut._log.info("%d beats: read enables and lane bits as the golden positions", total)


BUILDS = [{"P": 1, "RECTS": 0}, {"P": 5, "RECTS": 1}]   # RECTS = 0: whole-box frames only


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_cfb_mask(params):
    run_unit(__file__, {"MAX_DIM": 32, "ADDR_W": 16, "WEIGHT_W": 8, "MAX_SS_LOG2": 0, **params})

"""Unit testbench of rtl/cube4_cfb_addr.v: the CFB's address unit.

The read beats of golden frames (``cube4_sim.cfb_walk``: every row and partial beam a pass
reads, the voxel slice it reads) enter with their address terms as ``cube4.memory`` keeps
them (``read_terms``: A_j, A_k, the partial-beam term, the skew) and move through the
unit's three stages under a seeded random advance (stalls hold them). Checked on every
cycle against the golden memory layout:

* s1 (t1): lane q's position t, ``cube4.memory.lane_positions``;
* the output register: bank q's address is ``cube4.memory.address_of`` of the voxel it
  holds (``read_addresses``) wherever the beat reads it;
* at the end every beat came out of the output register once, in order.

Views: every major axis, flipped axes, S = 2 (the read passes only), P = 1 and P = 5.
"""

from __future__ import annotations

import cocotb
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

from cube4.memory import lane_positions
from cube4.view import make_traversal
from cube4_sim.beats import unpack_lanes
from cube4_sim.cfb_walk import cfb_walk, read_addresses, read_terms
from cube4_sim.unit_bench import UnitBench, param_id, run_unit
from cube4_sim.sweeps import sweep

VIEWS = [((0.3, -0.45, 1.0), (13, 9, 4), 1), ((-0.6, 0.25, -1.0), (11, 10, 3), 2),
         ((1.0, 0.4, -0.7), (9, 12, 3), 1), ((-0.5, -1.0, 0.5), (10, 4, 11), 1)]


def check_beat(dut, trav, p: int, aw: int, lane_w: int, beat, where: str) -> None:
    k, j, pb = beat
    fi = bool(trav.flip[trav.axis_i])
    if where == "s1":
        t = unpack_lanes(int(dut.t1.value), p, lane_w)
        want = lane_positions(read_terms(trav, p, k, j, pb, aw)["skew"], 0, p, trav.ni, fi)
        assert (t == want).all(), f"beat {beat} s1: lane positions {t.tolist()}, golden {want.tolist()}"
        return
    got = unpack_lanes(int(dut.addr.value), p, aw)
    want = read_addresses(trav, p, k, j, pb)
    bad = [q for q in range(p) if want[q] is not None and int(got[q]) != want[q]]
    assert not bad, f"beat {beat} bank {bad[0]}: address {int(got[bad[0]])}, memory.py {want[bad[0]]}"


async def play(dut, bench, trav, p: int, aw: int, lane_w: int, stall: float) -> int:
    beats = [(s.read, s.j, s.pb) for s in cfb_walk(trav, p) if s.read is not None]
    pipe = [None, None, None]             # the beats in s1, s2, the output register
    out, k = [], 0
    while k < len(beats) or any(b is not None for b in pipe):
        await FallingEdge(dut.clk)
        cur = beats[k] if k < len(beats) else None
        if cur is not None:
            for name, val in read_terms(trav, p, *cur, aw).items():
                getattr(dut, "skew_rd" if name == "skew" else name).value = val
        adv = int(bench.rng.random() >= stall)
        dut.advance.value = adv
        await ReadOnly()
        if pipe[0] is not None:
            check_beat(dut, trav, p, aw, lane_w, pipe[0], "s1")
        if pipe[2] is not None:
            check_beat(dut, trav, p, aw, lane_w, pipe[2], "out")
        if adv:
            if pipe[2] is not None:
                out.append(pipe[2])
            pipe = [cur, pipe[0], pipe[1]]
            k += cur is not None
    assert out == beats, f"{len(out)} beats left the output register, {len(beats)} entered"
    await FallingEdge(dut.clk)
    return len(beats)


@cocotb.test()
async def test_addr(dut):
    p, aw, w = (int(getattr(dut, n).value) for n in ("P", "ADDR_W", "WEIGHT_W"))
    lane_w = max(1, (p - 1).bit_length())
    bench = UnitBench(dut)
    dut.advance.value = 0
    total = 0
    for n, (direction, dims, ss) in enumerate(VIEWS):
        trav = make_traversal(dims, direction, w, ss)
        await FallingEdge(dut.clk)
        bench.set_view(trav, p)
        await bench.cycles(2)          # the lane table follows I_LIN, I_RT
        total += await play(dut, bench, trav, p, aw, lane_w, (0.0, 0.3, 0.6)[n % 3])
    dut._log.info("%d read beats: every bank's address as memory.py", total)


BUILDS = [{"P": 1}, {"P": 5}]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_cfb_addr(params):
    run_unit(__file__, {"MAX_DIM": 32, "ADDR_W": 16, "WEIGHT_W": 8, "MAX_SS_LOG2": 1, **params})

"""Unit testbench of rtl/cube4_gra_arith.v: GRA's arithmetic, bit for bit.

The DUT is ``cube4_gra_arith_harness.v``: cube4_gra_arith with its view registers as
ports and a Verilog clock. The operands are the golden ones (``cube4.model.
gradient_operand_stream``: hi, lo, up, dn, fwd, back of every sample of a random
volume's sample stream) followed by corner operands (each 0 or 2^V - 1), P lanes per
beat, gj given as up - dn; each beat carries a random header. Beats are given with
random gaps in in_v (random data in the gaps); every beat announced by out_v_d is read
a cycle later and checked, in order, against ``cube4.model.gradient_of``: header,
sample, gi, gj, gk of every lane. After the last beat the bench runs 20 more cycles
and requires that exactly as many beats came out as went in.

Views: three directions, S = 1, 2 and 4 (P = 5 build) or 1 and 2 (P = 1), each with its
own gap probability, in one simulation per build.
"""

from __future__ import annotations


import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

from cube4.model import gradient_of, gradient_operand_stream, sample_stream
from cube4.view import make_traversal
from cube4_sim.beats import Geometry, pack_lanes, unpack_lanes
from cube4_sim.unit_bench import UnitBench, param_id, run_unit
from cube4_sim.sweeps import sweep


# (direction, log2 S, gap probability)
VIEWS = [((0.3, -0.45, 1.0), 0, 0.0), ((-0.6, 0.25, -1.0), 1, 0.4), ((1.0, 0.4, -0.7), 2, 0.7)]
OPS = ("in_hi", "in_lo", "in_gj", "in_fwd", "in_back")


def corner_operands(vw: int, p: int) -> np.ndarray:
    """Every combination of 0 and 2^vw - 1 for the six operands (6, 64), padded to whole beats."""
    top = (1 << vw) - 1
    combos = np.array([[(n >> k) & 1 for k in range(6)] for n in range(64)], dtype=np.int64).T * top
    pad = (-combos.shape[1]) % p
    return np.concatenate([combos, np.zeros((6, pad), dtype=np.int64)], axis=1)


def beats_of(ops: np.ndarray, p: int) -> np.ndarray:
    """(6, N) operands into (N / P, 6, P) beats (N padded with zero samples to whole beats)."""
    pad = (-ops.shape[1]) % p
    ops = np.concatenate([ops, np.zeros((6, pad), dtype=np.int64)], axis=1)
    return ops.reshape(6, -1, p).transpose(1, 0, 2)


@cocotb.test()
async def test_arith_stream(dut):
    """Golden operands in (random gaps), golden (gi, gj, gk) out, nothing extra."""
    p, vw, w = int(dut.P.value), int(dut.VOXEL_W.value), int(dut.WEIGHT_W.value)
    geo = Geometry(p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
    gw, dw = vw + 5, vw + 1
    bench = UnitBench(dut)
    d = dut
    await bench.reset({"in_v": 0})
    dims = (7, 6, 5)
    vol = bench.rng.integers(0, 1 << vw, size=dims[::-1], dtype=np.int64)
    for direction, ss_log2, gap in VIEWS:
        if ss_log2 > geo.max_ss_log2:
            continue
        trav = make_traversal(dims, direction, w, 1 << ss_log2)
        samples, _ = sample_stream(vol, trav)
        ops = gradient_operand_stream(samples, trav).transpose(1, 0, 2, 3).reshape(6, -1)
        beats = np.concatenate([beats_of(ops, p), beats_of(corner_operands(vw, p), p)])
        want = [gradient_of(b, trav) for b in beats]                     # (3, P) each
        hdrs = [int(h) for h in bench.rng.integers(0, 1 << min(geo.hdr_w, 62), size=len(beats))]
        smp = bench.rng.integers(0, 1 << vw, size=(len(beats), p))
        bench.set_view(trav, p)
        await bench.cycles(2)
        got, k, announced, quiet = [], 0, False, 0
        while quiet < 20:
            await FallingEdge(d.clk)
            give = k < len(beats) and bench.rng.random() >= gap
            if give:
                b = beats[k]
                vals = {"in_hi": pack_lanes(b[0], vw), "in_lo": pack_lanes(b[1], vw),
                        "in_gj": pack_lanes(want[k][1], dw), "in_fwd": pack_lanes(b[4], vw),
                        "in_back": pack_lanes(b[5], vw), "in_s": pack_lanes(smp[k], vw), "in_hdr": hdrs[k]}
                k += 1
            else:   # junk in the gaps: it must not come out
                vals = {n: int(bench.rng.integers(0, 1 << min(len(bench.sig(n)), 62))) for n in OPS + ("in_s", "in_hdr")}
            for name, val in vals.items():
                bench.sig(name).value = val
            d.in_v.value = int(give)
            await ReadOnly()
            if announced:
                got.append({n: int(bench.sig(n).value) for n in ("out_hdr", "out_sample", "out_gi", "out_gj", "out_gk")})
            announced = bool(int(d.out_v_d.value))
            if k == len(beats) and not give:
                quiet += 1
        await FallingEdge(d.clk)
        d.in_v.value = 0
        assert len(got) == len(beats), f"{len(got)} beats out, {len(beats)} in"
        bad = 0
        for n, (g, e) in enumerate(zip(got, want)):
            if g["out_hdr"] != hdrs[n]:
                bench.log.error("beat %d: header %#x, expected %#x", n, g["out_hdr"], hdrs[n])
                bad += 1
            rtl = [unpack_lanes(g["out_sample"], p, vw)] + [unpack_lanes(g["out_" + c], p, gw, signed=True)
                                                         for c in ("gi", "gj", "gk")]
            for name, r, x in zip(("sample", "gi", "gj", "gk"), rtl, [smp[n], *e]):
                for q in np.nonzero(r != x)[0]:
                    if bad < 8:
                        bench.log.error("%s beat %d lane %d: RTL %d, golden %d", name, n, q, r[q], x[q])
                    bad += 1
        assert bad == 0, f"{bad} values differ from the golden model"
        bench.log.info("view %s S=%d gap %.1f: %d beats bit-exact", direction, 1 << ss_log2, gap, len(got))


BUILDS = [{"P": 1, "VOXEL_W": 8, "MAX_SS_LOG2": 1}, {"P": 5, "VOXEL_W": 12, "MAX_SS_LOG2": 2}]


@pytest.mark.parametrize("build", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_gra_arith(build):
    run_unit(__file__, {**build, "MAX_DIM": 16}, "test_arith_stream")

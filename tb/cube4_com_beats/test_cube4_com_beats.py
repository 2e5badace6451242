"""Unit testbench of rtl/cube4_com_beats.v: COM's slice geometry on the beat schedule.

For golden frames of the beat schedule (``cube4_sim.beat_frames.beat_frame``: sparse
volumes, a LUT zero below the blob's values, views of every class, termination in every
other frame) the sample beats the front end emits (``expected_requests``: the running
beats, the cover, the row above and each slice's marker) are offered with their position
bits through a model of COM's input skid (two entries: the head offered, in_valid and
in_hdr; the second, nx_valid; the header at its input, sk_hdr, random when no
beat enters), beats entering it with seeded random gaps, taken (take) only when the golden
read-after-write rule allows (no beat of the same slot {j, pb} in R0 .. S9), and played
through R0 and S1 as cube4_com_seq gives them. Each beat enters the input queue (q_push,
q_hdr, q_eoss) one to three beats ahead of its offer, at seeded random times, and its
q_geo comes back with the offer as c_geo, as cube4_com's skid buffer gives it. Checked on
every beat against the golden model:

* offered: hazard (a register decided a cycle ahead, cube4_com_ahead) = a beat of the
  offered beat's slot is in R0 .. S9 (these frames never offer a beat of the slot of the
  beat just taken, so the look-ahead's compares against the head are not reached here,
  tried: tb/cube4_com_ahead plays them);
* R0: the slot {j, pb}, pb; stepx(m), stepy(m) (``Traversal.steps``); the template's
  phases of slices m and m + 1 (the path weights'); per lane (its position t by
  ``tpos``) the bits fresh and soon of its ray;
* S1: per lane whose ray runs, "next": its ray runs the next slice (not bit last) and the
  next sample (m + 1, j + dyf, i + dxf) is inside the box (``model.inside_mask``); the
  path weights' m = M - 1, wx(m + 1) > 0, wy(m + 1) > 0 (``Traversal.weights``);
* S4: col1 = the beat before it is the row above at the same partial beam.

With MAX_SS_LOG2 = 2 one frame runs at S = 2 and one at S = 4 (the last slice M − 1 =
(NK − 1)·S). Every beat offered must be taken and checked (the count is compared). With the steps
frozen at their frame's first slice (tried, not kept), P = 5 fails with "beat 156 (m=3,
j=3, pb=0) R0 (slot, pb, stx, sty): RTL (24, 0, 0, 0), golden (24, 0, 0, 1)".
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

from cube4.config import Cube4Config
from cube4.model import inside_mask
from cube4.view import make_traversal
from cube4_sim.beat_frames import beat_frame, expected_requests
from cube4_sim.beats import BeatSchedule, Geometry, clog2, mask_bits, pack_lanes, unpack_lanes
from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import UnitBench, param_id, run_unit

from cube4.beats import LAG  # noqa: E402  (the DUT's default, CUBE4_BEAT_LAG)
VIEWS = [(0.3, -0.45, 1.0), (-0.6, 0.25, -1.0), (1.0, 0.4, -0.7), (0.5, 1.0, 0.5), (-0.2, -1.0, -0.9),
         (1.0, 1.0, 1.0), (0.0, 0.0, -1.0)]


def frame_beats(bench, trav, p: int, terminate: bool):
    """A golden beat frame of a sparse volume: its emitted sample beats (a BeatSchedule in
    their order) and each beat's position bits."""
    cfg = Cube4Config(pipelines=p, supersample=trav.supersample)
    nx, ny, nz = trav.dims
    vol = bench.rng.integers(0, 64, size=(nz, ny, nx))
    vol[nz // 4: nz // 2 + 2, ny // 4: ny // 2 + 2, nx // 4: nx // 2 + 2] = bench.rng.integers(64, 256)
    lut = np.zeros((256, 4), dtype=np.int64)
    lut[64:, :3] = bench.rng.integers(0, 256, size=(192, 3))
    lut[64:, 3] = (1 << cfg.alpha_bits) - 1 if terminate else bench.rng.integers(1, 1 << 10, size=192)
    bf = beat_frame(vol, trav, cfg, lut, None, "composite", terminate=terminate)
    reqs = [w for w in expected_requests(bf, p, LAG) if w[4]]
    order = [(w[6][0], w[6][1], w[2], 1) for w in reqs]        # every lane with a position
    sched = BeatSchedule(trav, p, np.ones((trav.num_sample_slices, trav.nj, trav.ni), dtype=bool), order=order)
    return sched, [w[9] for w in reqs]


async def play(dut, bench, trav, sched, bits, p: int, geo: Geometry, iw: int, gap: float) -> int:
    M = trav.num_sample_slices
    hdrs = sched.headers(geo)
    n, m, j, pb, pos = len(sched), sched.m, sched.j, sched.pb, sched.pos
    sx, sy = trav.steps(m)
    sxf, syf = trav.steps(m + 1)
    dxf, dyf = sxf - sx, syf - sy
    t = np.where(sched.lval, pos - pb[:, None] * p, 0)
    bit = lambda b, k, q: bool((bits[b] >> (k * p + int(t[b, q]))) & 1)   # noqa: E731 (k: 0 run .. 3 soon)
    fresh = np.array([[bit(b, 1, q) for q in range(p)] for b in range(n)])
    soon = np.array([[bit(b, 3, q) for q in range(p)] for b in range(n)])
    last = np.array([[bit(b, 2, q) for q in range(p)] for b in range(n)])
    run = np.array([[bit(b, 0, q) for q in range(p)] for b in range(n)])
    nxt = np.zeros((n, p), dtype=bool)
    for b in range(n):
        if m[b] + 1 < M:
            ins = inside_mask(trav, int(m[b]) + 1)
            for q in range(p):
                i, jj = int(pos[b, q] + dxf[b]), int(j[b] + dyf[b])
                nxt[b, q] = not last[b, q] and i < trav.ni and jj < trav.nj and bool(ins[jj, i])
    one = 1 << trav.phase_bits
    phases = [((trav.phase_x + k * trav.view_x) % one, (trav.phase_y + k * trav.view_y) % one,
               (trav.phase_x + (k + 1) * trav.view_x) % one, (trav.phase_y + (k + 1) * trav.view_y) % one)
              for k in (int(x) for x in m)]
    s1_geo = [(int(k == M - 1), *(int(w > 0) for w in trav.weights(k + 1)[:2])) for k in (int(x) for x in m)]
    slot = (j << geo.pb_w) | pb
    eoss = np.append(m[1:] != m[:-1], True)       # each beat: the last of its slice
    col1 = np.zeros(n, dtype=bool)
    col1[1:] = (m[1:] == m[:-1]) & (pb[1:] == pb[:-1]) & (j[1:] == j[:-1] + 1)
    sp_w = clog2(int(dut.MAX_DIM.value)) + geo.pb_w
    geo_w = len(dut.q_geo)
    r0, k, c, offering = {}, 0, 0, False
    checked = 0
    geos, pushed = {}, 0      # the queue: each beat's q_geo, pushed a cycle or more before it is offered
    ins = 0                   # beats that entered the input skid (it holds beats k .. ins - 1)
    while k < n or any(x >= c - 5 for x in r0):
        await FallingEdge(dut.clk)
        b0, b1, b4 = r0.get(c), r0.get(c - 1), r0.get(c - 4)
        fly = [r0.get(c - s) for s in range(1, 10)]
        dut.step.value = int(b0 is not None)
        dut.v_fly.value = mask_bits([b is not None for b in fly])
        dut.sp_fly.value = sum(int(slot[b]) << (s * sp_w) for s, b in enumerate(fly) if b is not None)
        if b0 is not None:
            dut.r0_m.value, dut.r0_j.value, dut.r0_pb.value = int(m[b0]), int(j[b0]), int(pb[b0])
            dut.tpos.value = pack_lanes(t[b0], max(1, clog2(p)))
        if b1 is not None:
            dut.f1_ipos.value = pack_lanes(pos[b1], iw)
            dut.f1_j.value = int(j[b1])
            dut.f1_dxf.value, dut.f1_dyf.value = int(dxf[b1]), int(dyf[b1])
        push = pushed < min(n, k + 3) and bench.rng.random() >= gap / 2
        dut.q_push.value = int(push)
        dut.q_hdr.value = hdrs[pushed] if push else int(bench.rng.integers(0, 1 << geo.hdr_w))
        dut.q_eoss.value = int(eoss[pushed]) if push else int(bench.rng.integers(0, 2))
        held = ins - k
        enter = ins < pushed and held < 2 and bench.rng.random() >= gap   # beat ins enters the skid
        offering = held > 0
        hz = offering and any(b is not None and slot[b] == slot[k] for b in [b0] + fly)
        take = offering and not hz
        rnd = lambda: int(bench.rng.integers(0, 1 << geo.hdr_w))   # noqa: E731
        dut.in_valid.value, dut.take.value = int(offering), int(take)
        dut.nx_valid.value = int(held == 2)
        dut.sk_hdr.value = hdrs[ins] if enter else rnd()
        dut.in_hdr.value = hdrs[k] if offering else rnd()
        dut.in_bits.value = int(bits[k]) if offering else int(bench.rng.integers(0, 1 << (4 * p)))
        dut.c_geo.value = geos[k] if offering else int(bench.rng.integers(0, 1 << geo_w))
        await ReadOnly()
        if push:
            geos[pushed] = int(dut.q_geo.value)
            pushed += 1
        if offering:
            assert int(dut.hazard.value) == int(hz), (f"{sched.describe(k)} offered: hazard {int(dut.hazard.value)}, "
                                                      f"golden {int(hz)}")
        if b0 is not None:
            got = (int(dut.pos_sp.value), int(dut.pos_pb.value), int(dut.stx.value), int(dut.sty.value))
            want = (int(slot[b0]), int(pb[b0]), int(sx[b0]), int(sy[b0]))
            assert got == want, f"{sched.describe(b0)} R0 (slot, pb, stx, sty): RTL {got}, golden {want}"
            got = tuple(int(x.value) for x in (dut.ph_x, dut.ph_y, dut.phn_x, dut.phn_y))
            assert got == phases[b0], f"{sched.describe(b0)} R0 phases (m, m + 1): RTL {got}, golden {phases[b0]}"
            for name, sig, gold in (("fresh", dut.fresh, fresh), ("soon", dut.soon_0, soon)):
                lanes = unpack_lanes(int(sig.value), p, 1).astype(bool)
                bad = np.flatnonzero(sched.lval[b0] & (lanes != gold[b0]))
                assert bad.size == 0, f"{sched.describe(b0, bad[0])}: {name} {lanes[bad[0]]}, golden {gold[b0][bad[0]]}"
            checked += 1
        if b1 is not None:
            nx = unpack_lanes(int(dut.nx_in.value), p, 1).astype(bool)
            bad = np.flatnonzero(sched.lval[b1] & run[b1] & (nx != nxt[b1]))   # (COM reads it where a ray runs)
            assert bad.size == 0, f"{sched.describe(b1, bad[0])}: next {nx[bad[0]]}, golden {nxt[b1][bad[0]]}"
            got = tuple(int(x.value) for x in (dut.f1_klast, dut.f1_wxn, dut.f1_wyn))
            assert got == s1_geo[b1], f"{sched.describe(b1)} S1 (last, wxn, wyn): RTL {got}, golden {s1_geo[b1]}"
        if b4 is not None:
            assert int(dut.col1_4.value) == col1[b4], f"{sched.describe(b4)}: col1 {int(dut.col1_4.value)}"
        if take:
            r0[c + 1] = k
            k += 1
        ins += int(enter)
        c += 1
    await FallingEdge(dut.clk)
    dut.q_push.value = 0
    assert checked == n, f"{checked} of {n} beats checked"
    return n


@cocotb.test()
async def test_beats(dut):
    p, max_dim, ss_log2 = int(dut.P.value), int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value)
    geo = Geometry(p, max_dim, ss_log2)
    iw = clog2(max_dim + 2 * p + 1)   # cube4_defs.vh IW
    bench = UnitBench(dut)
    await bench.reset({"q_push": 0, "step": 0, "v_fly": 0, "in_valid": 0, "nx_valid": 0, "take": 0})
    dims = (max(20, 2 * p + 3), 16, 12)
    frames = 0
    for n, direction in enumerate(VIEWS * 2):
        ss = {3: 2, 6: 4}.get(n, 1) if ss_log2 >= 2 else 1     # S = 2 and 4 on two frames
        trav = make_traversal(dims, direction, int(dut.WEIGHT_W.value), ss, phase=(n * 37 % 256, n * 91 % 256))
        sched, bits = frame_beats(bench, trav, p, terminate=n % 2 == 1)
        bench.set_view(trav, p)
        await bench.cycles(2)
        gap = (0.0, 0.3, 0.6, 0.1)[n % 4]
        beats = await play(dut, bench, trav, sched, bits, p, geo, iw, gap)
        frames += 1
        dut._log.info("view %s S=%d gap %.1f: %d beats right", direction, ss, gap, beats)
    assert frames == 2 * len(VIEWS)


BUILDS = [{"P": 5, "MAX_SS_LOG2": 2}, {"P": 1}, {"P": 8}]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(0,), ids=param_id))
def test_cube4_com_beats(params):
    run_unit(__file__, {"MAX_DIM": 32, **params})

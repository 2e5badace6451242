"""Unit testbench of rtl/cube4_com_seq.v: COM's sequencer, cycle by cycle.

The golden shaded stream's headers (``cube4.model.render_frame`` with random tables, a
window and / or cut plane; ``cube4_sim.beats.BeatSchedule``) are offered with seeded
random gaps in valid, against a random FIFO credit and a random hazard (the stalls);
the slice geometry's inputs are played as cube4_com_walk gives them (R0: slot, pb,
stepx(m), stepy(m) from ``Traversal.steps``, per lane "fresh" at random; S1: per lane
"next inside", false exactly where the golden frame finishes a ray, random where the
lane holds no inside sample). Checked on every cycle:

* in_ready = credit and no hazard; take = in_valid and in_ready (and the input stream's
  rules, cube4_stream_check);
* R0: m, j, pb, sop, first, the back steps, each lane's i (the schedule's positions);
  S1: i, j, the next steps; the valid bit of every stage S1 .. S10 and the slots of
  S1 .. S10, pb at S1 and S2, S4's back steps, voxel-slice change, t0 and fresh, S6's
  and S7's "counts" (inside and KEEP);
* S10: push (the beat finishes a ray or is the frame's last) or give (it does not);
  S11: the finished-ray mask (the golden frame's finished rays), m, by = j - stepy(m) +
  SY, bx = i - stepx(m) + SX per lane, eop;
* the mode registers.

At the end every beat must have been taken once and pushed or given once, and nothing
pushed beyond the golden count.

The test can fail (tried with a deliberately corrupted expectation, not kept).
"""

from __future__ import annotations


import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

from cube4.config import Cube4Config
from cube4.model import render_frame
from cube4.view import make_traversal
from cube4_sim.beats import BeatSchedule, Geometry, clog2, mask_bits, pack_lanes, unpack_lanes
from cube4_sim.unit_bench import UnitBench, param_id, random_clip, run_unit
from cube4_sim.sweeps import sweep


# (direction, gap, credit low, hazard, mode, clip)
VIEWS = [((0.3, -0.45, 1.0), 0.0, 0.0, 0.0, "composite", None),
         ((-0.6, 0.25, -1.0), 0.3, 0.2, 0.1, "mip", "cut"),
         ((1.0, 0.4, -0.7), 0.5, 0.1, 0.3, "xray", "window"),
         ((0.5, 1.0, 0.5), 0.2, 0.3, 0.2, "minip", "window+cut")]
MODE_BITS = {"composite": (0, 0, 0), "xray": (1, 0, 0), "mip": (0, 1, 0), "minip": (0, 1, 1)}


def golden_frame(rng, trav, cfg, mode: str, clip):
    dims = trav.dims
    vol = rng.integers(0, 256, size=dims[::-1], dtype=np.int64)
    lut = np.concatenate([rng.integers(0, 256, size=(256, 3)), rng.integers(0, 1 << 10, size=(256, 1))], axis=1)
    rmap = rng.integers(0, 1024, size=(cfg.rmap_entries, 2), dtype=np.int64)
    return render_frame(vol, trav, cfg, lut, rmap, keep_streams=True, mode=mode, clip=clip)


def finished_mask(frame) -> np.ndarray:
    """[m, j, i]: the golden frame's rays that finish at that sample."""
    trav, pix = frame.trav, frame.pixels
    sxm, sym = trav.max_steps
    stx, sty = trav.steps(pix["m"].astype(np.int64))
    fin = np.zeros((trav.num_sample_slices, trav.nj, trav.ni), dtype=bool)
    fin[pix["m"], pix["by"] - (sym - sty), pix["bx"] - (sxm - stx)] = True
    return fin


async def play(dut, bench, frame, p: int, geo: Geometry, sp_w: int, gap, credit_low, hazard) -> int:
    trav, rng = frame.trav, bench.rng
    sched = BeatSchedule(trav, p, frame.streams["inside"], frame.streams["keep"])
    hdrs = sched.headers(geo)
    n, m, j, pb, pos = len(sched), sched.m, sched.j, sched.pb, sched.pos
    iw, bx_w = clog2(geo.max_dim + 2 * p + 1), geo.dim_w + 1
    sx, sy = trav.steps(m)
    sxb, syb = trav.steps(m - 1)
    sxf, syf = trav.steps(m + 1)
    sxm, sym = trav.max_steps
    ins = sched.lval & sched.lins
    fin = sched.lanes(finished_mask(frame)).astype(bool) & sched.lval
    nx_in = np.where(ins, ~fin, rng.random((n, p)) < 0.5)
    fresh = rng.random((n, p)) < 0.5
    keep5 = rng.random((n, p)) < 0.8          # depth in's ok, given at S5 (cube4_com_stop)
    slot = (j * sched.nb + pb) % (1 << sp_w)
    bmask = (1 << bx_w) - 1
    r0, k, c, offering = {}, 0, 0, False
    pushes = gives = 0
    while k < n or any(t >= c - 12 for t in r0):
        await FallingEdge(dut.clk)
        b = {s: r0.get(c - s) for s in range(0, 12)}
        if b[0] is not None:
            dut.pos_sp.value, dut.pos_pb.value = int(slot[b[0]]), int(pb[b[0]])
            dut.fresh.value = mask_bits(fresh[b[0]])
            dut.stx.value, dut.sty.value = int(sx[b[0]]), int(sy[b[0]])
        if b[1] is not None:
            dut.nx_in.value = mask_bits(nx_in[b[1]])
        if b[5] is not None:
            dut.keep_5.value = mask_bits(keep5[b[5]])
        if not offering and k < n and rng.random() >= gap:
            offering = True
            dut.in_hdr.value = hdrs[k]
        credit, hz = int(rng.random() >= credit_low), int(rng.random() < hazard)
        dut.in_valid.value, dut.credit.value, dut.hazard.value = int(offering), credit, hz
        await ReadOnly()
        ready = int(dut.in_ready.value)
        assert ready == int(credit and not hz), f"cycle {c}: in_ready {ready} with credit {credit}, hazard {hz}"
        assert int(dut.take.value) == int(offering and ready), f"cycle {c}: take {int(dut.take.value)}"
        v_s = int(dut.v_s.value)
        want_v = mask_bits([b[s] is not None for s in range(1, 11)])
        assert v_s == want_v, f"cycle {c}: stage valid bits {v_s:010b}, expected {want_v:010b}"
        assert int(dut.step.value) == int(b[0] is not None) and int(dut.step_c.value) == (3 if b[0] is not None else 0)
        if (x := b[0]) is not None:
            got = [int(getattr(dut, s).value) for s in ("r0_m", "r0_j", "r0_pb", "sop", "first", "dxb", "dyb")]
            want = [m[x], j[x], pb[x], int(x == 0), int(j[x] == 0 and pb[x] == 0), sx[x] - sxb[x], sy[x] - syb[x]]
            assert got == [int(w) for w in want], f"{sched.describe(x)} R0 (m j pb sop first dxb dyb): {got} {want}"
            assert (unpack_lanes(int(dut.ipos.value), p, iw) == pos[x]).all(), f"{sched.describe(x)}: ipos"
            tpos = unpack_lanes(int(dut.tpos.value), p, geo.lane_w)
            assert (tpos == pos[x] - pb[x] * p).all(), f"{sched.describe(x)}: tpos {tpos}"
        if (x := b[1]) is not None:
            got = [int(dut.f1_j.value), int(dut.f1_dxf.value), int(dut.f1_dyf.value), int(dut.pb_rd.value)]
            assert got == [j[x], sxf[x] - sx[x], syf[x] - sy[x], pb[x]], f"{sched.describe(x)} S1: {got}"
            assert (unpack_lanes(int(dut.f1_ipos.value), p, iw) == pos[x]).all(), f"{sched.describe(x)}: f1_ipos"
        if (x := b[2]) is not None:
            assert int(dut.pb_wr.value) == pb[x], f"{sched.describe(x)}: S2 pb {int(dut.pb_wr.value)}"
        for s in range(1, 10):
            if (x := b[s]) is not None:
                got = (int(dut.sp_fly.value) >> ((s - 1) * sp_w)) & ((1 << sp_w) - 1)
                assert got == slot[x], f"{sched.describe(x)}: S{s} slot {got}, expected {slot[x]}"
        if (x := b[4]) is not None:
            got = [int(getattr(dut, s).value) for s in ("dxb4", "dyb4", "dkb4", "t0_4", "fresh_4")]
            want = [sx[x] - sxb[x], sy[x] - syb[x], int(m[x] % trav.supersample == 0),
                    mask_bits(pos[x] - pb[x] * p == 0), mask_bits(fresh[x])]
            assert got == [int(w) for w in want], f"{sched.describe(x)} S4 (dxb dyb dkb t0 fresh): {got} {want}"
        for s, name in ((6, "cnt_6"), (7, "cnt_7")):
            if (x := b[s]) is not None:
                want = mask_bits(ins[x] & sched.lkeep[x] & keep5[x])
                assert int(getattr(dut, name).value) == want, f"{sched.describe(x)}: {name}"
        if (x := b[10]) is not None:
            out = bool(fin[x].any()) or x == n - 1
            got = (int(dut.push_d.value), int(dut.give.value))
            assert got == (int(out), int(not out)), f"{sched.describe(x)} S10 (push, give): {got}"
            assert int(dut.sp_wr.value) == slot[x], f"{sched.describe(x)}: S10 slot"
            pushes, gives = pushes + out, gives + (not out)
        else:
            assert int(dut.push_d.value) == 0 and int(dut.give.value) == 0, f"cycle {c}: push / give without a beat"
        if (x := b[11]) is not None:
            got = [int(dut.fin_o.value), int(dut.m_o.value), int(dut.by_o.value), int(dut.eop_o.value)]
            want = [mask_bits(fin[x]), int(m[x]), int(j[x] - sy[x] + sym) & bmask, int(x == n - 1)]
            assert got == want, f"{sched.describe(x)} S11 (fin m by eop): RTL {got}, golden {want}"
            bx = unpack_lanes(int(dut.bx_o.value), p, bx_w)
            want_bx = (pos[x] - sx[x] + sxm) & bmask
            bad = np.flatnonzero(fin[x] & (bx != want_bx))
            assert bad.size == 0, f"{sched.describe(x, bad[0])}: bx {bx[bad[0]]}, golden {want_bx[bad[0]]}"
        if offering and ready:
            r0[c + 1] = k
            k, offering = k + 1, False
        c += 1
    await FallingEdge(dut.clk)
    dut.in_valid.value = 0
    want_push = int(sum(fin[x].any() or x == n - 1 for x in range(n)))
    assert len(r0) == n and pushes == want_push and pushes + gives == n, (
        f"{len(r0)} of {n} beats taken, {pushes} pushed (golden {want_push}), {gives} given")
    return pushes


@cocotb.test()
async def test_sequencer(dut):
    p, max_dim = int(dut.P.value), int(dut.MAX_DIM.value)
    geo = Geometry(p, max_dim, int(dut.MAX_SS_LOG2.value))
    sp_w = clog2(max_dim * geo.nbmax)
    cfg = Cube4Config(pipelines=p)
    bench = UnitBench(dut)
    await bench.reset({"in_valid": 0, "credit": 0, "hazard": 0})
    dims = (max(11, 2 * p + 3), max(9, p + 4), max(8, p + 2))
    for n, (direction, gap, credit_low, hazard, mode, clip_kind) in enumerate(VIEWS):
        ss = (1 << int(dut.MAX_SS_LOG2.value)) if n % 2 else 1
        trav = make_traversal(dims, direction, 8, ss, phase=(n * 37 % 256, n * 91 % 256))
        clip = random_clip(trav, clip_kind, bench.rng)
        frame = golden_frame(bench.rng, trav, cfg, mode, clip)
        bench.set_view(trav, p, mode, clip)
        await bench.cycles(2)
        await FallingEdge(dut.clk)
        got = tuple(int(getattr(dut, s).value) for s in ("mode_xray", "mode_ext", "mode_min"))
        assert got == MODE_BITS[mode], f"{mode}: mode registers (xray, ext, min) {got}"
        pushes = await play(dut, bench, frame, p, geo, sp_w, gap, credit_low, hazard)
        dut._log.info("view %s %s clip %s S=%d gap %.1f: %d pixel beats, %d finished rays", direction, mode,
                      clip_kind, ss, gap, pushes, len(frame.pixels))


# T_R0 = 1: the lanes' positions registered at R0 (the BEATS builds'), at a P that is
# not a power of two (lane_pos wraps by P)
BUILDS = [{"P": 1, "MAX_SS_LOG2": 1}, {"P": 5}, {"P": 3, "T_R0": 1}]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(1,), ids=param_id))  # P = 1: make regress (make test runs the top at P = 1)
def test_cube4_com_seq(params):
    run_unit(__file__, {"MAX_DIM": 32, **params})

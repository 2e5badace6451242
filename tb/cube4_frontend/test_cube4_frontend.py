"""Testbench for the Cube-4 front end: cube4_cfb + cube4_voxel_mem + cube4_tri.

The DUT is ``cube4_frontend_harness.v`` (beside this file): the front end, the skewed voxel
memory loaded through its load port from a ``$readmemh`` image
(``cube4.memory``: ``pack_volume``, the one host packer, and ``write_hex``), random stall injection
on the memory request, the memory response and the sample output (LFSRs in
Verilog), and a dump of every sample beat to a text file, read strictly
(``cube4_sim.dump.frame_bounds``: no beat outside its frame). Python only sets
registers, pulses ``load`` / ``start`` and waits for ``load_done`` / ``done``, so
whole frames run at compiled-model speed.

Every frame is checked against the golden model (``cube4.model.sample_stream``):
beat order (m, j, pb), the skew of each beat against the memory layout (bank
(x + y + z) mod P), each lane's validity, sample value and inside flag bit for
bit, and the control bits (start, end, y-last, X/Y-steps and old X/Y-steps).
Views: all three major axes with all eight sign combinations, exactly 45
degrees, exactly on an axis, next to 45 degrees, supersampled passes where the
build allows; half the frames with random stalls on every port. Two volumes
per build (non-cubic, random voxels over the full range) are loaded one after
the other, and several views are rendered from each load.

Reproduce a failure with the printed COCOTB_RANDOM_SEED.
"""

from __future__ import annotations

import dataclasses
import json
import os
import time
from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, First, ReadOnly, RisingEdge, Timer

from cube4.memory import frontend_regs, lane_positions, load_image, pack_volume, top_regs, write_hex
import cube4.slices as slices
from cube4.model import gradient_stream, inside_mask, padded_traversal, rect_slice, sample_stream
from cube4.view import make_traversal
from cube4_sim import BUILD_ROOT, SIM_HDL_DIR, rtl_sources, run_test
from cube4_sim.beat_frames import HostCom, expected_requests, slab_frame, sparse_frame
from cube4_sim.beats import Geometry
from cube4_sim.dump import BEAT, LAST, START, frame_bounds
from cube4_sim.rect_port import write_rect_table
from cube4_sim.sweeps import regress, sweep
from cube4_sim.unit_bench import param_id

HERE = Path(__file__).resolve().parent   # the harness sits beside this file

CLK_NS = 10
MAX_MISMATCH_LOGS = 8
from cube4.beats import LAG as BEAT_LAG  # noqa: E402  (the beat schedule's lag, CUBE4_BEAT_LAG)
#: How far each sample dump has been read, across the cocotb tests of one simulation
#: (the harness opens the file once; each test reads on from where the last one stopped).
_DUMP_POS: dict[Path, int] = {}

SOURCES = [
    *rtl_sources(),
    SIM_HDL_DIR / "cube4_sim_clock.v",
    SIM_HDL_DIR / "cube4_sim_stall.v",
    HERE / "cube4_frontend_harness.v",
]


# --------------------------------------------------------------------------- checks
def line_kinds(lines: list[str]) -> np.ndarray:
    """START, BEAT or LAST (control bit 5, eop) per dump line, for frame_bounds."""
    return np.array([START if line == "start" else (LAST if (int(line.split()[4], 16) >> 5) & 1 else BEAT)
                     for line in lines], dtype=np.int64)


def parse_beats(lines: list[str], p: int, vw: int) -> dict[str, np.ndarray]:
    """Dump lines -> arrays: m, j, pb, skew, ctrl (n,), lval, lins, smp (n, p),
    grad (n, 3, p) signed (zero when the build has no GRA)."""
    n = len(lines)
    head = np.zeros((n, 5), dtype=np.int64)
    lval = np.zeros((n, p), dtype=bool)
    lins = np.zeros((n, p), dtype=bool)
    smp = np.zeros((n, p), dtype=np.int64)
    grad = np.zeros((n, 3, p), dtype=np.int64)
    bts = np.zeros(n, dtype=object)      # {eos, bits}: the beat build's (0 otherwise)
    mask = (1 << vw) - 1
    gw = vw + 5
    gmask = (1 << gw) - 1
    bits = np.arange(p)
    for r, line in enumerate(lines):
        f = line.split()
        head[r] = (int(f[0]), int(f[1]), int(f[2]), int(f[3]), int(f[4], 16))
        lv, li, s = int(f[5], 16), int(f[6], 16), int(f[7], 16)
        lval[r] = (lv >> bits) & 1
        lins[r] = (li >> bits) & 1
        smp[r] = [(s >> (q * vw)) & mask for q in range(p)]
        bts[r] = int(f[9], 16) if len(f) > 9 else 0
        g = int(f[8], 16)
        for c in range(3):  # {gi, gj, gk}: gi in the top bits
            gc = g >> ((2 - c) * p * gw)
            grad[r, c] = [(gc >> (q * gw)) & gmask for q in range(p)]
    grad = np.where(grad >= (1 << (gw - 1)), grad - (1 << gw), grad)
    return {"m": head[:, 0], "j": head[:, 1], "pb": head[:, 2], "skew": head[:, 3],
            "ctrl": head[:, 4], "lval": lval, "lins": lins, "smp": smp, "grad": grad, "bits": bts}


def check_frame(beats: dict[str, np.ndarray], vol: np.ndarray, trav, p: int, log, gra: bool = False) -> None:
    """Compare one frame's sample (and, with GRA, gradient) beats with the golden
    model; raise on mismatch."""
    gold, gin = sample_stream(vol, trav)
    M, nj, ni = gold.shape
    nk = trav.nk
    nb = -(-ni // p)
    n = len(beats["m"])
    assert n == M * nj * nb, f"{n} sample beats, expected M*NJ*NB = {M}*{nj}*{nb} = {M * nj * nb}"
    idx = np.arange(n)
    exp = {"m": idx // (nj * nb), "j": (idx // nb) % nj, "pb": idx % nb}
    for key, want in exp.items():
        bad = np.nonzero(beats[key] != want)[0]
        assert bad.size == 0, f"beat {bad[0]}: {key} = {beats[key][bad[0]]}, expected {want[bad[0]]} (order m, j, pb)"

    # skew: lane q holds the position whose bank (c_i + c_j + c_k) mod p is q, for the
    # row above the sample (j + 1) of the pass's lower voxel slice k0 = m // S
    fi, fj, fk = (bool(trav.flip[a]) for a in (trav.axis_i, trav.axis_j, trav.major))
    k0 = exp["m"] // trav.supersample
    cj = np.where(fj, nj - 1 - (exp["j"] + 1), exp["j"] + 1)
    ck = np.where(fk, nk - 1 - k0, k0)
    want_skew = (cj + ck) % p
    bad = np.nonzero(beats["skew"] != want_skew)[0]
    assert bad.size == 0, f"beat {bad[0]}: skew {beats['skew'][bad[0]]}, expected {want_skew[bad[0]]}"

    pos = np.stack([lane_positions(int(s), int(b), p, ni, fi) for s, b in zip(beats["skew"], beats["pb"])]) \
        if n else np.zeros((0, p), dtype=np.int64)
    valid = pos < ni
    bad = np.nonzero(beats["lval"] != valid)
    assert bad[0].size == 0, f"beat {bad[0][0]} lane {bad[1][0]}: lane_valid wrong"
    mm = np.broadcast_to(exp["m"][:, None], pos.shape)
    jj = np.broadcast_to(exp["j"][:, None], pos.shape)
    ii = np.minimum(pos, ni - 1)
    g = np.where(valid, gold[mm, jj, ii], 0)
    gi = np.where(valid, gin[mm, jj, ii], False)
    got = np.where(valid, beats["smp"], 0)
    bad = np.argwhere((got != g) | (beats["lins"] != gi))
    if bad.size:
        for r, q in bad[:MAX_MISMATCH_LOGS]:
            log.error("sample (m=%d, j=%d, i=%d) lane %d: RTL %d inside %d, golden %d inside %d",
                      exp["m"][r], exp["j"][r], pos[r, q], q, beats["smp"][r, q], beats["lins"][r, q],
                      g[r, q], gi[r, q])
        raise AssertionError(f"{len(bad)} sample mismatches against the golden model")

    if gra:
        ggold = gradient_stream(gold, trav)  # (M, 3, nj, ni)
        for c, name in enumerate(("gi", "gj", "gk")):
            want_g = np.where(valid, ggold[mm, c, jj, ii], 0)
            got_g = np.where(valid, beats["grad"][:, c, :], 0)
            bad = np.argwhere(got_g != want_g)
            if bad.size:
                for r, q in bad[:MAX_MISMATCH_LOGS]:
                    log.error("%s (m=%d, j=%d, i=%d) lane %d: RTL %d, golden %d", name, exp["m"][r],
                              exp["j"][r], pos[r, q], q, got_g[r, q], want_g[r, q])
                raise AssertionError(f"{len(bad)} {name} mismatches against the golden model")

    # control bits: {y_last, eop, sop, old_y, old_x, y, x}
    ctrl = beats["ctrl"]
    m = exp["m"]
    sx, sy = trav.steps(m)
    sx1, sy1 = trav.steps(m + 1)
    sxb, syb = trav.steps(m - 1)
    want = ((sx1 - sx) | ((sy1 - sy) << 1) | ((sx - sxb) << 2) | ((sy - syb) << 3)
            | ((idx == 0) << 4) | ((idx == n - 1) << 5) | ((exp["j"] == nj - 1) << 6))
    bad = np.nonzero(ctrl != want)[0]
    assert bad.size == 0, f"beat {bad[0]}: control bits {ctrl[bad[0]]:07b}, expected {want[bad[0]]:07b}"


def check_beat_frame(beats: dict[str, np.ndarray], bf, p: int, log) -> None:
    """Compare one beat-schedule frame's sample beats with the golden model: one per
    request that emits (``beat_frames.expected_requests``), in order, its slice, row and
    partial beam the emitted row's; where its sample beat runs, every lane below NI valid
    with the fixed schedule's sample and inside bit (the walk read what it interpolates),
    else no lane valid; the control bits of its slice and row, SOP on the first and EOP on
    the last; its position bits, EOS and EOSS (the last beat of its sample slice)."""
    trav, s = bf.trav, bf.sched
    gold, gin = sample_stream(bf.vol, trav)
    ni, nj, nk = trav.ni, trav.nj, trav.nk
    want = [w for w in expected_requests(bf, p, BEAT_LAG) if w[4]]
    n = len(beats["m"])
    assert n == len(want), f"{n} sample beats, golden {len(want)}"
    fi, fj, fk = (bool(trav.flip[a]) for a in (trav.axis_i, trav.axis_j, trav.major))
    for r, (_k, _j, pb, _reads, _emit, leave, (m, j), _eop, eos, bits, care) in enumerate(want):
        where = f"sample beat {r} (m={m}, j={j}, pb={pb})"
        got = (int(beats["m"][r]), int(beats["j"][r]), int(beats["pb"][r]))
        assert got == (m, j, pb), f"{where}: RTL (m, j, pb) = {got}"
        cj = nj - 1 - (j + 1) if fj else j + 1
        k0 = m // trav.supersample          # the sample slice's lower voxel slice
        ck = nk - 1 - k0 if fk else k0
        assert int(beats["skew"][r]) == (cj + ck) % p, f"{where}: skew {beats['skew'][r]}"
        pos = lane_positions(int(beats["skew"][r]), pb, p, ni, fi)
        valid = (pos < ni) & bool(leave)
        ii = np.minimum(pos, ni - 1)
        assert (beats["lval"][r] == valid).all(), f"{where}: lane_valid {beats['lval'][r]}, golden {valid}"
        g = np.where(valid, gold[m, j, ii], 0)
        gi = valid & gin[m, j, ii]
        smp = np.where(valid, beats["smp"][r], 0)
        if (smp != g).any() or (beats["lins"][r] != gi).any():
            log.error("%s: RTL samples %s inside %s, golden %s inside %s", where, smp, beats["lins"][r], g, gi)
            raise AssertionError(f"{where}: samples or inside bits differ from the golden model")
        sx, sy = (int(v) for v in trav.steps(m))
        sx1, sy1 = (int(v) for v in trav.steps(m + 1))
        sxb, syb = (int(v) for v in trav.steps(m - 1))
        ctrl = ((sx1 - sx) | ((sy1 - sy) << 1) | ((sx - sxb) << 2) | ((sy - syb) << 3)
                | ((r == 0) << 4) | ((r == n - 1) << 5) | ((j == nj - 1) << 6))
        assert int(beats["ctrl"][r]) == ctrl, f"{where}: control bits {int(beats['ctrl'][r]):07b}, golden {ctrl:07b}"
        got_bits = int(beats["bits"][r])
        assert (got_bits >> (4 * p)) & 1 == eos, f"{where}: EOS {(got_bits >> (4 * p)) & 1}, golden {eos}"
        eoss = int(r == n - 1 or want[r + 1][6][0] != m)    # the last beat of its sample slice
        assert got_bits >> (4 * p + 1) == eoss, f"{where}: EOSS {got_bits >> (4 * p + 1)}, golden {eoss}"
        assert got_bits & care == bits & care, f"{where}: bits {got_bits & ((1 << 4 * p) - 1):#x}, golden {bits:#x}"


def check_rect_frame(beats: dict[str, np.ndarray], vol: np.ndarray, trav, rects, p: int, log,
                     gra: bool = False) -> None:
    """Compare one slice-rectangle frame's sample beats with the golden model
    (numerics.md §18): each slice's walked rows and partial beams in order
    (SliceRects.walk: with GRA beyond the traversed rectangle), the lanes of its
    traversed positions valid, samples from the rectangle's voxels (model.rect_slice),
    inside per its rectangle, and the control bits (y-last: row NJ - 1)."""
    tp = padded_traversal(vol, trav)
    order, gin, ylast = [], {}, []
    zero_filled = np.zeros((trav.num_sample_slices, trav.nj, trav.ni), dtype=np.int64)
    for m in range(rects.last() + 1):
        walk = rects.walk(m, p)
        if walk is None:
            continue
        b = rects.traversed(m)
        if not rects.empty(m):
            zero_filled[m] = rect_slice(tp, trav, m, b, trav.weight_bits)
        gin[m] = inside_mask(trav, m) & rects.inside(m)
        # GRA forwards only the beats of the traversed rectangle
        rows, pbs = (walk[:2], walk[2:]) if not gra else (None, None)
        if gra:
            t = rects.beams(m, p)
            if t is None:
                continue
            rows, pbs = t[:2], t[2:]
        for j in range(rows[0], rows[1]):
            for pb in range(pbs[0], pbs[1] + 1):
                order.append((m, j, pb, b))
                ylast.append(j == trav.nj - 1)
    grads = gradient_stream(zero_filled, trav) if gra else None
    n = len(beats["m"])
    assert n == len(order), f"{n} sample beats, expected {len(order)}"
    fi, fj, fk = (bool(trav.flip[a]) for a in (trav.axis_i, trav.axis_j, trav.major))
    nj, ni, nk = trav.nj, trav.ni, trav.nk
    bad = 0
    for r, (m, j, pb, b) in enumerate(order):
        got = (int(beats["m"][r]), int(beats["j"][r]), int(beats["pb"][r]))
        assert got == (m, j, pb), f"beat {r}: (m, j, pb) = {got}, expected {(m, j, pb)}"
        cj = nj - 1 - (j + 1) if fj else j + 1
        ck = nk - 1 - m if fk else m
        assert beats["skew"][r] == (cj + ck) % p, f"beat {r}: skew {beats['skew'][r]}"
        pos = lane_positions(int(beats["skew"][r]), pb, p, ni, fi)
        valid = (pos >= b[2]) & (pos < b[3]) & (b[0] <= j < b[1])
        assert (beats["lval"][r] == valid).all(), f"beat {r} (m={m}, j={j}, pb={pb}): lane_valid wrong"
        ii, jc = np.minimum(pos, ni - 1), min(j, nj - 1)
        want = np.where(valid, zero_filled[m][jc, ii], 0)
        want_in = np.where(valid, gin[m][jc, ii], False)
        have = np.where(valid, beats["smp"][r], 0)
        if gra:
            for c, name in enumerate(("gi", "gj", "gk")):
                want_g = np.where(valid, grads[m][c, jc, ii], 0)
                for q in np.nonzero(np.where(valid, beats["grad"][r][c], 0) != want_g)[0]:
                    if bad < MAX_MISMATCH_LOGS:
                        log.error("%s (m=%d, j=%d, i=%d) lane %d: RTL %d, golden %d", name, m, j, pos[q], q,
                                  beats["grad"][r][c][q], want_g[q])
                    bad += 1
        for q in np.nonzero((have != want) | (beats["lins"][r] != want_in))[0]:
            if bad < MAX_MISMATCH_LOGS:
                log.error("sample (m=%d, j=%d, i=%d) lane %d: RTL %d inside %d, golden %d inside %d",
                          m, j, pos[q], q, beats["smp"][r][q], beats["lins"][r][q], want[q], want_in[q])
            bad += 1
    assert bad == 0, f"{bad} sample mismatches against the golden model"
    ms = np.array([o[0] for o in order])
    sx, sy = trav.steps(ms)
    sx1, sy1 = trav.steps(ms + 1)
    sxb, syb = trav.steps(ms - 1)
    idx = np.arange(n)
    want = ((sx1 - sx) | ((sy1 - sy) << 1) | ((sx - sxb) << 2) | ((sy - syb) << 3)
            | ((idx == 0) << 4) | ((idx == n - 1) << 5) | (np.array(ylast, dtype=np.int64) << 6))
    badc = np.nonzero(beats["ctrl"] != want)[0]
    assert badc.size == 0, f"beat {badc[0]}: control bits {beats['ctrl'][badc[0]]:07b}, expected {want[badc[0]]:07b}"


def view_set(rng: np.random.Generator, max_ss_log2: int) -> list[tuple[tuple[float, float, float], int]]:
    """(direction, supersample) pairs: every major axis and sign combination,
    exact 45 degrees, on-axis, next to 45 degrees, and supersampled views."""
    views = []
    for major in range(3):
        for signs in range(8):
            d = [0.0, 0.0, 0.0]
            for ax in range(3):
                mag = 1.0 if ax == major else float(rng.uniform(0.05, 0.95))
                d[ax] = -mag if (signs >> ax) & 1 else mag
            views.append((tuple(d), 1))
    views += [((1.0, 1.0, 1.0), 1), ((-1.0, 1.0, -1.0), 1), ((1.0, -1.0, 0.3), 1),
              ((0.0, 0.0, 1.0), 1), ((0.0, -1.0, 0.0), 1), ((-1.0, 0.0, 0.0), 1),
              ((0.999, 1.0, 0.5), 1), ((1.0, 0.0, 1.0), 1)]
    for g in range(1, max_ss_log2 + 1):
        views += [((0.3, -0.7, 1.0), 1 << g), ((-1.0, 0.45, -0.2), 1 << g), ((1.0, 1.0, -1.0), 1 << g)]
    return views


def volume_dims(p: int, max_dim: int) -> tuple[tuple[int, int, int], tuple[int, int, int]]:
    """Two non-cubic volumes per build, with several partial beams along every axis."""
    a = (min(max_dim, max(13, 3 * p + 1)), min(max_dim, max(11, 2 * p + 3)), min(max_dim, max(9, p + 6)))
    b = (min(max_dim, max(7, p + 2)), min(max_dim, max(15, 2 * p + 5)), min(max_dim, max(12, 3 * p - 1)))
    return a, b


# --------------------------------------------------------------------------- cocotb side
class TB:
    """Drives cube4_frontend_harness: load, configure, start, wait, check."""

    def __init__(self, dut) -> None:
        self.dut = dut
        self.log = dut._log
        self.p = int(dut.P.value)
        self.vw = int(dut.VOXEL_W.value)
        self.w = int(dut.WEIGHT_W.value)
        self.max_dim = int(dut.MAX_DIM.value)
        self.depth = int(dut.DEPTH.value)
        self.max_ss_log2 = int(dut.MAX_SS_LOG2.value)
        self.gra = bool(int(dut.OPT_GRA.value))
        self.rects = bool(int(dut.RECTS.value))
        self.beats = bool(int(dut.BEATS.value))
        self.memfile = Path(os.environ["CUBE4_FE_MEMFILE"])
        self.dumpfile = Path(os.environ["CUBE4_FE_DUMP"])
        self.rng = np.random.default_rng(cocotb.RANDOM_SEED)
        self.log.info("front end P=%d VOXEL_W=%d W=%d MAX_DIM=%d DEPTH=%d MAX_SS_LOG2=%d, seed %d",
                      self.p, self.vw, self.w, self.max_dim, self.depth, self.max_ss_log2,
                      cocotb.RANDOM_SEED)

    async def cycles(self, n: int) -> None:
        for _ in range(n):
            await RisingEdge(self.dut.clk)

    async def reset(self) -> None:
        d = self.dut
        d.rst.value = 1
        d.start.value = 0
        d.load.value = 0
        d.load_words.value = 0
        d.stall_req.value = 0
        d.stall_rsp.value = 0
        d.stall_out.value = 0
        d.dump_en.value = 1
        d.rect_we.value = 0
        for name in ("blk_base", "nbr_en", "blk_we", "tab_we", "rep_valid", "rep_en", "com_m"):
            getattr(d, name).value = 0
        d.seed.value = cocotb.RANDOM_SEED & 0xFFFFFFFF   # the Verilog stall generators' seed
        await self.cycles(4)
        d.rst.value = 0
        await self.cycles(2)

    async def load(self, vol: np.ndarray) -> None:
        """Pack the volume (cube4.memory), write its load image and stream it in
        through the load port."""
        banks = pack_volume(vol, self.p)
        words = banks.shape[1]
        assert words <= self.depth, f"volume needs {words} words per bank, DEPTH = {self.depth}"
        write_hex(self.memfile, load_image(banks), self.vw)
        self.dut.load_words.value = words
        self.dut.load.value = 1
        await RisingEdge(self.dut.clk)
        self.dut.load.value = 0
        res = await First(RisingEdge(self.dut.load_done), Timer((words + 100) * CLK_NS, unit="ns"))
        assert int(self.dut.load_done.value) == 1, "load did not finish"
        del res

    async def write_rects(self, trav, rects) -> None:
        """The rectangle table of ``rects`` (cube4.memory.rect_table), one entry a cycle."""
        await write_rect_table(self.dut, trav, rects, self.p, int(self.dut.ADDR_W.value))
        await self.cycles(3)

    async def frame(self, vol: np.ndarray, trav, stalls=(0, 0, 0), after_reset: bool = False,
                    dumped: bool = True, rects=None) -> tuple[dict, int, float]:
        """Render one view; returns (beats, cycles, wall seconds of the simulation).
        ``after_reset``: a frame reset in mid-frame precedes this one in the dump;
        ``dumped``: False when dump_en is 0 (the dump has the start marker only);
        ``rects``: the frame's slice rectangles (a RECTS build; default the whole box)."""
        d = self.dut
        for key, val in frontend_regs(trav, self.p).items():
            getattr(d, "cfg_" + key.lower()).value = int(val)
        d.cfg_ph0_x.value, d.cfg_ph0_y.value = trav.phase_x, trav.phase_y   # a box starts at its own phase
        if self.rects:
            await self.write_rects(trav, rects if rects is not None else whole_box(trav, self.gra))
        d.stall_req.value, d.stall_rsp.value, d.stall_out.value = stalls
        await RisingEdge(d.clk)
        d.start.value = 1
        await RisingEdge(d.clk)
        d.start.value = 0
        M, nj, ni = trav.num_sample_slices, trav.nj, trav.ni
        beats = (M * nj + 1) * -(-ni // self.p) + 1 + (nj + 1) * -(-ni // self.p) + 1
        slow = 1.0 / max(1e-3, min(1 - s / 256 for s in stalls)) ** 3
        t0 = time.perf_counter()
        await First(RisingEdge(d.done), Timer(int((beats * slow * 4 + 1000) * CLK_NS), unit="ns"))
        wall = time.perf_counter() - t0
        await RisingEdge(d.clk)
        await ReadOnly()
        assert int(d.busy.value) == 0, f"frame did not finish within the time limit ({beats} beats)"
        cycles = int(d.cycles.value)
        await Timer(1, unit="ns")   # leave the read-only phase: callers drive inputs next
        with self.dumpfile.open() as fh:
            fh.seek(_DUMP_POS.get(self.dumpfile, 0))
            text = fh.read()
            _DUMP_POS[self.dumpfile] = fh.tell()
        lines = text.splitlines()
        unfinished = [True] * after_reset + [not dumped]
        a, b = frame_bounds(line_kinds(lines), unfinished, "sample dump")[-1]
        assert dumped or a == b, f"sample dump: {b - a} beats of a frame run with dump_en = 0"
        return parse_beats(lines[a:b], self.p, self.vw), cycles, wall

    async def beat_frame(self, bf, stalls=(0, 0, 0), delay: int = 0) -> tuple[dict, int]:
        """Render one frame of the beat schedule (a BEATS build): the volume loaded, the
        view's registers, the host's tables and COM's reports (``beat_frames.HostCom``:
        slice d's reports once d's EOS has reached the sink, a random delay of up to
        ``delay`` cycles later); returns (beats, cycles)."""
        d, trav = self.dut, bf.trav
        assert tuple(trav.origin) == (0, 0, 0) and bf.vol is not None, "a frame of the whole volume"
        await self.load(bf.vol)
        for key, val in top_regs(trav, self.p).items():    # the steps' SX, SY and PH0 too
            if hasattr(d, "cfg_" + key.lower()):
                getattr(d, "cfg_" + key.lower()).value = int(val)
        host = HostCom(d, bf, self.p, self.max_dim, Geometry(self.p, self.max_dim, self.max_ss_log2).m_w,
                       BEAT_LAG, self.rng, delay)
        await FallingEdge(d.clk)
        await host.load()
        d.stall_req.value, d.stall_rsp.value, d.stall_out.value = stalls
        d.start.value = 1
        await FallingEdge(d.clk)
        d.start.value = 0
        cycle, started = 0, False
        while True:
            host.drive(cycle, int(d.eos_count.value) if started else 0)
            await FallingEdge(d.clk)
            cycle += 1
            busy = int(d.busy.value)
            started = started or bool(busy)
            if started and not busy:
                break
            assert cycle < 400000, "the frame did not finish"
        cycles = int(d.cycles.value)
        await self.cycles(3)
        with self.dumpfile.open() as fh:
            fh.seek(_DUMP_POS.get(self.dumpfile, 0))
            text = fh.read()
            _DUMP_POS[self.dumpfile] = fh.tell()
        lines = text.splitlines()
        a, b = frame_bounds(line_kinds(lines), [False], "sample dump")[-1]
        return parse_beats(lines[a:b], self.p, self.vw), cycles

    async def render_and_check(self, vol, direction, supersample, stalls, after_reset: bool = False) -> int:
        trav = make_traversal(vol.shape[::-1], direction, self.w, supersample)
        beats, cycles, _ = await self.frame(vol, trav, stalls, after_reset)
        check_frame(beats, vol, trav, self.p, self.log, self.gra)
        await RisingEdge(self.dut.clk)
        return cycles


def whole_box(trav, gra: bool = False):
    """Slice rectangles that are the whole box in every slice (the fixed schedule; with
    ``gra``, GRA's walk of it)."""
    box = slices.rects_from_needed(np.ones((trav.num_sample_slices, trav.nj, trav.ni), dtype=bool), trav)
    return dataclasses.replace(box, gra=gra)


def rect_cycles(rects, p: int, gra: bool) -> int:
    """A rectangle frame's cycles but the fill: the front end's beats, one per empty
    slice before the last, and GRA's own steps after the last beat."""
    return rects.beats(p) + rects.empty_walks(p) + (rects.gra_steps(p) if gra else 0)


def random_volume(rng, dims, vw) -> np.ndarray:
    nx, ny, nz = dims
    return rng.integers(0, 1 << vw, size=(nz, ny, nx), dtype=np.int64)


@cocotb.test()
async def test_views(dut):
    """Two volumes, every view class, with and without stalls, bit-exact."""
    tb = TB(dut)
    await tb.reset()
    dims_a, dims_b = volume_dims(tb.p, tb.max_dim)
    views = view_set(tb.rng, tb.max_ss_log2)
    stall_sets = [(0, 0, 0), (70, 70, 70), (0, 0, 200), (200, 0, 0), (0, 200, 30)]
    for vi, dims in enumerate((dims_a, dims_b)):
        vol = random_volume(tb.rng, dims, tb.vw)
        await tb.load(vol)
        subset = views if vi == 0 else views[::3]
        for n, (direction, ss) in enumerate(subset):
            stalls = stall_sets[n % len(stall_sets)]
            cycles = await tb.render_and_check(vol, direction, ss, stalls)
            tb.log.info("dims %s view %s S=%d stalls %s: %d cycles, bit-exact",
                        dims, direction, ss, stalls, cycles)


@cocotb.test()
async def test_rect_views(dut):
    """A RECTS build: frames of slice rectangles (cube4.slices from random needed
    samples, sparse to dense) at every view class, with and without stalls: the sample
    stream as numerics.md §18 specifies it, bit for bit; without stalls the frame takes
    its beats, one cycle per empty slice before its last one and the whole box's fill,
    exactly (the frame ends with its last slice that is not empty)."""
    tb = TB(dut)
    if not tb.rects:
        return
    await tb.reset()
    dims, _ = volume_dims(tb.p, tb.max_dim)
    vol = random_volume(tb.rng, dims, tb.vw)
    await tb.load(vol)
    views = [v for v, ss in view_set(tb.rng, 0)][::2] + [(1.0, 1.0, 1.0), (1.0, -1.0, 0.0)]
    stall_sets = [(0, 0, 0), (70, 70, 70), (0, 0, 200), (200, 0, 0)]
    fill = None
    for n, direction in enumerate(views):
        trav = make_traversal(dims, direction, tb.w, 1)
        if fill is None:                # the whole box's pipeline fill on this build
            beats, cycles, _ = await tb.frame(vol, trav)
            fill = cycles - rect_cycles(whole_box(trav, tb.gra), tb.p, tb.gra)
        density = (0.01, 0.05, 0.3)[n % 3]
        need = tb.rng.random((trav.num_sample_slices, trav.nj, trav.ni)) < density
        # every other view with GRA's walk (rows and partial beams beyond the rectangles)
        rects = dataclasses.replace(slices.rects_from_needed(need, trav), gra=tb.gra or n % 2 == 1)
        if rects.beats(tb.p) == 0:
            continue
        stalls = stall_sets[n % len(stall_sets)]
        beats, cycles, _ = await tb.frame(vol, trav, stalls, rects=rects)
        check_rect_frame(beats, vol, trav, rects, tb.p, tb.log, tb.gra)
        if stalls == (0, 0, 0):
            want = rect_cycles(rects, tb.p, tb.gra) + fill
            assert cycles == want, f"view {direction}: {cycles} cycles, expected {want}"
        tb.log.info("view %s rectangles (%.0f%% of the samples) stalls %s: %d cycles, bit-exact",
                    direction, 100 * rects.fraction(), stalls, cycles)
        await RisingEdge(dut.clk)


@cocotb.test()
async def test_rect_scene(dut):
    """CUBE4_FE_RECT_SCENE = 'volume,scene' (a RECTS build): the scene's frame with its
    empty-space box and the slice rectangles within it, as the renderer plans it
    (cube4.host.plan_view, pass_rects), through the front end without stalls: the
    sample stream bit for bit, and the cycles against beats + empty slices + the fill
    (measured on the box's fixed schedule, not dumped). Results to CUBE4_FE_BENCH_OUT."""
    spec = os.environ.get("CUBE4_FE_RECT_SCENE")
    if not spec:
        return
    import dataclasses

    from cube4.host import config_for, crop_volume, pass_rects, plan_view
    from cube4.scene import load_scene
    from cube4.app.volumes import load_volume

    tb = TB(dut)
    await tb.reset()
    vol_spec, scene_name = spec.split(",")
    whole = load_volume(vol_spec)
    scene = load_scene(scene_name)
    vp = plan_view(whole, scene, config_for(scene, tb.p))
    plan, rects = vp.plans[0], pass_rects(whole, vp)[0]
    box = np.ascontiguousarray(plan.box_volume(crop_volume(whole, vp.trav))).astype(np.int64)
    trav = dataclasses.replace(plan.trav, origin=(0, 0, 0))   # the box is the volume loaded
    rects = dataclasses.replace(rects, trav=trav)
    await tb.load(box)
    dut.dump_en.value = 0
    _, full_cycles, _ = await tb.frame(box, trav, rects=whole_box(trav, tb.gra), dumped=False)
    dut.dump_en.value = 1
    fill = full_cycles - rect_cycles(whole_box(trav, tb.gra), tb.p, tb.gra)
    rects = dataclasses.replace(rects, gra=tb.gra)   # a GRA build walks for GRA (unshaded scenes too)
    beats, cycles, wall = await tb.frame(box, trav, rects=rects)
    check_rect_frame(beats, box, trav, rects, tb.p, tb.log, tb.gra)
    predicted = rect_cycles(rects, tb.p, tb.gra) + fill
    assert cycles == predicted, f"{cycles} cycles, predicted {predicted}"
    nz, ny, nx = whole.shape
    res = {"volume": vol_spec, "scene": scene_name, "p": tb.p, "gra": tb.gra, "box_dims": list(trav.dims),
           "cycles": cycles, "predicted_cycles": predicted, "box_fixed_cycles": full_cycles,
           "n3_over_p": nx * ny * nz / tb.p, "sim_wall_s": wall}
    tb.log.info("RECT %s %s P=%d: front end %d cycles (predicted %d), box %d, n^3/P %.0f, bit-exact",
                vol_spec, scene_name, tb.p, cycles, predicted, full_cycles, res["n3_over_p"])
    out = os.environ.get("CUBE4_FE_BENCH_OUT")
    if out:
        Path(out).write_text(json.dumps(res, indent=2) + "\n")


@cocotb.test()
async def test_reset_mid_frame(dut):
    """A reset in the middle of a frame, then a clean frame from the same memory."""
    tb = TB(dut)
    await tb.reset()
    dims, _ = volume_dims(tb.p, tb.max_dim)
    vol = random_volume(tb.rng, dims, tb.vw)
    await tb.load(vol)
    trav = make_traversal(dims, (0.4, -0.3, 1.0), tb.w, 1)
    for key, val in frontend_regs(trav, tb.p).items():
        getattr(dut, "cfg_" + key.lower()).value = int(val)
    if tb.rects:
        await tb.write_rects(trav, whole_box(trav))
    dut.start.value = 1
    await RisingEdge(dut.clk)
    dut.start.value = 0
    await tb.cycles(37)
    dut.rst.value = 1
    await tb.cycles(3)
    dut.rst.value = 0
    await tb.cycles(2)
    await tb.render_and_check(vol, (0.4, -0.3, 1.0), 1, (40, 40, 40), after_reset=True)


@cocotb.test()
async def test_frame_cycles(dut):
    """One frame of a cubic random volume of MAX_DIM^3 (or the CUBE4_FE_BENCH_DIM
    given), no stalls: bit-exact, and cycles against the nx*ny*nz/P ideal."""
    tb = TB(dut)
    await tb.reset()
    n = int(os.environ.get("CUBE4_FE_BENCH_DIM", "0")) or min(tb.max_dim, 32)
    dims = (n, n, n)
    vol = random_volume(tb.rng, dims, tb.vw)
    await tb.load(vol)
    results = []
    for direction in ((0.0, 0.0, 1.0), (0.6, -0.35, 1.0)):
        trav = make_traversal(dims, direction, tb.w, 1)
        beats, cycles, _ = await tb.frame(vol, trav)
        check_frame(beats, vol, trav, tb.p, tb.log, tb.gra)
        # the same frame again without the sample dump: the simulator's own speed
        dut.dump_en.value = 0
        _, cycles2, wall = await tb.frame(vol, trav, dumped=False)
        dut.dump_en.value = 1
        assert cycles2 == cycles, f"the same frame took {cycles} and then {cycles2} cycles"
        ideal = n * n * n / tb.p
        res = {"p": tb.p, "dims": list(dims), "direction": list(direction), "cycles": cycles,
               "ideal_cycles": ideal, "efficiency": ideal / cycles,
               "overhead_cycles": cycles - ideal, "sim_wall_s": wall,
               "sim_cycles_per_s": cycles / wall if wall > 0 else None}
        results.append(res)
        tb.log.info("FRAME %d^3 P=%d view %s: %d cycles, ideal %.0f, efficiency %.5f, "
                    "%.2f M simulated cycles/s", n, tb.p, direction, cycles, ideal, ideal / cycles,
                    cycles / wall / 1e6)
        # exactly the documented schedule: (M*NJ + 1)*NB + 1 beats plus a fixed fill
        nb = -(-trav.ni // tb.p)
        fill = cycles - ((trav.num_sample_slices * trav.nj + 1) * nb + 1)
        if tb.rects:  # the whole box from the table (with GRA, GRA's walk of it and its own steps)
            fill = cycles - rect_cycles(whole_box(trav, tb.gra), tb.p, tb.gra)
        elif tb.gra:  # GRA finishes the last slice with NJ*NB + NB + 2 zero steps
            fill -= trav.nj * nb + nb + 2
        # (26 cycles without GRA, 32 or 33 with cube4_gra after it: its output FIFO's input
        # register, the register before its multipliers and its window's beats; TRI's lerps
        # are four stages each, cube4_lerp LATENCY 4)
        limit = 33 if tb.gra else 28
        assert 0 <= fill <= limit, f"pipeline fill of {fill} cycles: the schedule has bubbles"
        await RisingEdge(dut.clk)
    out = os.environ.get("CUBE4_FE_BENCH_OUT")
    if out:
        Path(out).write_text(json.dumps(results, indent=2) + "\n")


# --------------------------------------------------------------------------- pytest side
# every P from 1 to 16, 8- and 12-bit voxels, supersampling on some builds, the gradient
# unit after the front end (OPT_GRA). All in make regress: make test runs each of the
# units on its own and the whole chain through cube4_top (P = 1 and 5)
BUILDS = [
    dict(P=1, VOXEL_W=8, MAX_DIM=32, MAX_SS_LOG2=1, OPT_GRA=1),
    dict(P=2, VOXEL_W=8, MAX_DIM=32, MAX_SS_LOG2=0, OPT_GRA=1),
    dict(P=4, VOXEL_W=12, MAX_DIM=32, MAX_SS_LOG2=2, OPT_GRA=1),
    dict(P=5, VOXEL_W=8, MAX_DIM=32, MAX_SS_LOG2=1, OPT_GRA=1),
    dict(P=8, VOXEL_W=8, MAX_DIM=64, MAX_SS_LOG2=3, OPT_GRA=1),
    dict(P=16, VOXEL_W=12, MAX_DIM=64, MAX_SS_LOG2=0, OPT_GRA=1),
]


def _params(P: int, VOXEL_W: int, MAX_DIM: int, MAX_SS_LOG2: int, OPT_GRA: int = 0,  # noqa: N803
            RECTS: int = 0, BEATS: int = 0) -> dict[str, int]:
    """The harness's parameters: a voxel memory that holds a MAX_DIM^3 volume."""
    words = -(-MAX_DIM // P) * MAX_DIM * MAX_DIM
    addr_w = max(1, (words - 1).bit_length())
    return {"P": P, "VOXEL_W": VOXEL_W, "MAX_DIM": MAX_DIM, "MAX_SS_LOG2": MAX_SS_LOG2,
            "DEPTH": words, "ADDR_W": addr_w, "OPT_GRA": OPT_GRA, "RECTS": RECTS, "BEATS": BEATS}


def _run(params: dict, testcase, extra_env: dict | None = None) -> None:
    # one folder per build and process: two tests of one build may run at once
    key = "_".join(f"{k}{v}" for k, v in params.items())
    work = BUILD_ROOT / "frontend_io" / f"{key}_pid{os.getpid()}"
    work.mkdir(parents=True, exist_ok=True)
    env = {"CUBE4_FE_MEMFILE": str(work / "mem.hex"), "CUBE4_FE_DUMP": str(work / "samples.txt")}
    env.update(extra_env or {})
    run_test(
        top="cube4_frontend_harness",
        sources=SOURCES,
        params=params,
        test_module=__file__,
        testcase=testcase,
        timing=True,
        extra_env=env,
        plusargs=[f"+CUBE4_MEMFILE={env['CUBE4_FE_MEMFILE']}", f"+CUBE4_DUMP={env['CUBE4_FE_DUMP']}"],
    )


@cocotb.test()
async def test_beat_views(dut):
    """A beat build (BEATS = 1): golden frames of the beat schedule (beat_frames: two
    nearly opaque slabs, shaded, rays ending in them; sparse volumes in every mode, their
    LUT nearly opaque every other frame, termination off every third; with MAX_SS_LOG2 = 2
    three more at S = 2 and 4, whose passes between the reading ones take their voxels
    from TRI's slice buffers) through CFB, the memory and TRI with stalls on every port:
    every sample beat as check_beat_frame."""
    tb = TB(dut)
    if not tb.beats:
        return
    await tb.reset()
    seeds = [sd for sd in range(200) if sd % 3 == 0][:6]
    cases = [("slab", v, 1) for v in ((0.2, -0.1, 1.0), (1.0, 1.0, 1.0))] + [("sparse", sd, 1) for sd in seeds]
    if tb.max_ss_log2 >= 2:
        cases += [("sparse", sd, ss) for sd, ss in ((1, 2), (4, 4), (13, 4))]
    stall_sets = [(0, 0, 0), (70, 70, 70), (0, 0, 200), (200, 0, 0), (0, 200, 30)]
    frames = 0
    for n, (kind, arg, ss) in enumerate(cases):
        bf = (slab_frame(tb.p, arg) if kind == "slab"
              else sparse_frame(arg, tb.p, opaque=n % 2 == 0, terminate=n % 3 != 2, supersample=ss))
        if max(bf.trav.dims) > tb.max_dim:
            continue
        stalls = stall_sets[n % len(stall_sets)]
        beats, cycles = await tb.beat_frame(bf, stalls, delay=(0, 40, 400)[n % 3])
        check_beat_frame(beats, bf, tb.p, tb.log)
        frames += 1
        tb.log.info("%s %s S=%d: %d slices of %dx%d beats, stalls %s: %d sample beats in %d cycles bit-exact",
                    kind, arg, ss, bf.sched.M, bf.sched.NJ, bf.sched.NB, stalls, len(beats["m"]), cycles)
    assert frames >= 4, f"only {frames} frames fit MAX_DIM = {tb.max_dim}"


@pytest.mark.parametrize("build", sweep(BUILDS, quick=(), ids=param_id))
def test_cube4_frontend(build):
    _run(_params(**build), ["test_views", "test_reset_mid_frame", "test_frame_cycles"])


#: slice-rectangle builds (RECTS = 1, S = 1): P = 1, 5 and 8 without GRA, P = 8 with GRA
#: (GRA's rectangle build has its own testbench, and cube4_top's runs at P = 1 and 8)
RECT_BUILDS = [dict(P=1, VOXEL_W=8, MAX_DIM=32, MAX_SS_LOG2=0, OPT_GRA=0, RECTS=1),
               dict(P=5, VOXEL_W=12, MAX_DIM=32, MAX_SS_LOG2=0, OPT_GRA=0, RECTS=1),
               dict(P=8, VOXEL_W=8, MAX_DIM=64, MAX_SS_LOG2=0, OPT_GRA=0, RECTS=1),
               dict(P=8, VOXEL_W=8, MAX_DIM=64, MAX_SS_LOG2=0, OPT_GRA=1, RECTS=1)]


@pytest.mark.parametrize("build", sweep(RECT_BUILDS, quick=(), ids=param_id))
def test_cube4_frontend_rects(build):
    """The rectangle build: slice rectangles, the whole box as the fixed schedule
    (every view class, stalls), a reset in mid-frame, and the cycles of both."""
    _run(_params(**build), ["test_rect_views", "test_views", "test_reset_mid_frame", "test_frame_cycles"])


def frontend_rect_scene(vol_spec: str, scene: str, p: int, max_dim: int, out: Path, gra: bool = True) -> dict:
    """A scene's slice-rectangle frame through the RTL front end and, with ``gra``,
    GRA (test_rect_scene); returns its results (also written to ``out``)."""
    out.parent.mkdir(parents=True, exist_ok=True)
    _run(_params(p, 8, max_dim, 0, int(gra), 1), "test_rect_scene",
         {"CUBE4_FE_RECT_SCENE": f"{vol_spec},{scene}", "CUBE4_FE_BENCH_OUT": str(out)})
    return json.loads(out.read_text())


@regress
def test_cube4_frontend_rect_scene():
    """A scene through a P = 8 rectangle build: bit-exact, and the cycles as predicted.
    By default the head phantom at 48³ (on the MAX_DIM = 64 build of the P = 8 rectangle
    test); CUBE4_RECT_SCENE_CASE = 'volume,scene,MAX_DIM' chooses another (make skipping
    runs the goal case, head:128), with its results in build/reports/frontend_rects.json."""
    vol_spec, scene, max_dim = os.environ.get("CUBE4_RECT_SCENE_CASE", "head:48,head,64").split(",")
    res = frontend_rect_scene(vol_spec, scene, 8, int(max_dim), BUILD_ROOT / "reports" / "frontend_rects.json")
    assert res["cycles"] == res["predicted_cycles"] < res["box_fixed_cycles"]


@regress
def test_cube4_frontend_cycles_128():
    """128^3, P = 8 (a MAX_DIM = 128 build of its own: make regress, and make bench runs it):
    bit-exact frames and cycles per frame against nx*ny*nz/P (printed, and written to
    build/reports/frontend_cycles.json)."""
    report = BUILD_ROOT / "reports" / "frontend_cycles.json"
    report.parent.mkdir(parents=True, exist_ok=True)
    _run(_params(8, 8, 128, 0), "test_frame_cycles",
         {"CUBE4_FE_BENCH_DIM": "128", "CUBE4_FE_BENCH_OUT": str(report)})
    for r in json.loads(report.read_text()):
        print(f"front end 128^3 P=8 view {r['direction']}: {r['cycles']} cycles, ideal {r['ideal_cycles']:.0f}, "
              f"efficiency {r['efficiency']:.5f}, {r['sim_cycles_per_s'] / 1e6:.2f} M cycles/s simulated")


#: beat builds (BEATS = 1; S = 2 and 4 too with MAX_SS_LOG2 = 2): P = 8 in make test,
#: P = 1 and 5 in make regress
BEAT_BUILDS = [dict(P=8, VOXEL_W=8, MAX_DIM=32, MAX_SS_LOG2=2, BEATS=1),
               dict(P=1, VOXEL_W=8, MAX_DIM=32, MAX_SS_LOG2=0, BEATS=1),
               dict(P=5, VOXEL_W=12, MAX_DIM=32, MAX_SS_LOG2=0, BEATS=1)]


@pytest.mark.parametrize("build", sweep(BEAT_BUILDS, quick=(0,), ids=param_id))
def test_cube4_frontend_beats(build):
    """The beat build: golden frames of the beat schedule, sample for sample."""
    _run(_params(**build), ["test_beat_views"])

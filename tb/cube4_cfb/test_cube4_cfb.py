"""Unit test of the CFB address unit (rtl/cube4_cfb.v) against the memory layout.

The CFB alone, with a cocotb clock and random back-pressure on its request port
(checked every cycle: a stalled beat must hold). Every read beat is checked
against ``cube4.memory`` directly, not against a model of the CFB: for read beat
r (slice k, beam j, partial beam pb in traversal order) lane q must read exactly
the voxel of that partial beam whose bank (x + y + z) mod P is q, at
``address_of(x, y, z)``, and padding lanes must not read. Over a frame every voxel
is read exactly once. All six major directions with both signs of both minor
slopes (24 views, plus 45-degree and on-axis views), non-cubic volumes, P = 1, 5, 16.

The rectangle build (RECTS = 1, P = 1, 5, 8) runs the same frames from a table that
holds the whole box, and frames of random slice rectangles (``cube4.slices``): each
pass reads exactly its traversed rectangle, and the frame issues the beats that
``SliceRects.beats`` counts (flush beams where the next slice walks other partial beams).
"""

from __future__ import annotations

from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

import cube4.slices as slices
from cube4.memory import address_of, bank_of, frontend_regs, top_regs
from cube4.view import make_traversal
from cube4_sim import rtl_sources, run_test
from cube4_sim.sweeps import sweep
from cube4_sim.beat_frames import HostCom, expected_requests, slab_frame, sparse_frame
from cube4_sim.beats import Geometry
from cube4_sim.rect_port import write_rect_table

HERE = Path(__file__).resolve().parent   # the harness sits beside this file


def expected_lanes(trav, p: int, k: int, j: int, pb: int, i_range=None) -> tuple[list[int | None], list[tuple]]:
    """Per lane: the address it must read (None: must not read), and the voxel;
    ``i_range``: the positions [lo, hi) the beat reads (default the whole beam)."""
    dims = trav.dims
    lo, hi = (0, trav.ni) if i_range is None else i_range
    addr: list[int | None] = [None] * p
    vox: list[tuple] = [()] * p
    for t in range(p):
        i = pb * p + t
        if not lo <= i < hi:
            continue
        c = [0, 0, 0]
        for coord, ax in ((i, trav.axis_i), (j, trav.axis_j), (k, trav.major)):
            c[ax] = dims[ax] - 1 - coord if trav.flip[ax] else coord
        q = int(bank_of(*c, p))
        assert addr[q] is None, "two positions of a partial beam in one bank: skew broken"
        addr[q] = int(address_of(*c, dims, p))
        vox[q] = tuple(c)
    return addr, vox


def slice_read(m: int, s: int) -> tuple[bool, bool, int]:
    """Pass m's read from the memory (as cube4_cfb_trav): its lower voxel slice (pass 0,
    or every pass at S = 1), its upper slice (pass k0·S + 1, S > 1), and which slice."""
    if s == 1:
        return True, False, m
    if m == 0:
        return True, False, 0
    return False, m % s == 1, m // s + 1


async def reset(dut):
    Clock(dut.clk, 10, unit="ns").start(start_high=False)
    dut.rst.value = 1
    dut.start.value = 0
    dut.req_ready.value = 0
    dut.rect_we.value = 0
    for _ in range(3):
        await RisingEdge(dut.clk)
    dut.rst.value = 0


async def run_frame(dut, trav, rng, p: int, aw: int, expected_reads, rects=None) -> int:
    """Set the registers (and the rectangle table), run one frame under random
    back-pressure, check every read beat against ``expected_reads`` (a list of
    (k, j, pb, (lo, hi))) and that every voxel they name is read once; returns the
    beats issued."""
    for key, val in frontend_regs(trav, p).items():
        getattr(dut, "cfg_" + key.lower()).value = int(val)
    if rects is not None:
        await write_rect_table(dut, trav, rects, p, aw)
        await FallingEdge(dut.clk)
    await FallingEdge(dut.clk)
    dut.start.value = 1
    await FallingEdge(dut.clk)
    dut.start.value = 0
    reads = beats = 0
    seen = np.zeros(trav.dims[::-1], dtype=np.int64)
    held = None
    while True:
        ready = int(rng.random() < 0.7)
        dut.req_ready.value = ready
        await RisingEdge(dut.clk)
        valid = int(dut.req_valid.value)
        if valid:
            beat = (int(dut.req_addr.value), int(dut.req_rden.value), int(dut.tag_m.value),
                    int(dut.tag_pb.value), int(dut.tag_emit.value))
            if held is not None:
                assert beat == held, "request changed while stalled"
            held = None if ready else beat
        if valid and ready:
            beats += 1
            addr_v, rden, _, _, _ = beat
            is_read = int(dut.tag_lower_mem.value) or int(dut.tag_upper_mem.value)
            if is_read:
                assert reads < len(expected_reads), f"more than {len(expected_reads)} read beats"
                k, j, pb, i_range = expected_reads[reads]
                want, vox = expected_lanes(trav, p, k, j, pb, i_range)
                for q in range(p):
                    en = (rden >> q) & 1
                    a = (addr_v >> (q * aw)) & ((1 << aw) - 1)
                    assert en == (want[q] is not None), \
                        f"view {trav.direction} read beat {reads} (k={k}, j={j}, pb={pb}) lane {q}: rden {en}"
                    if en:
                        assert a == want[q], (f"view {trav.direction} (k={k}, j={j}, pb={pb}) lane {q}: "
                                              f"address {a}, voxel {vox[q]} is at {want[q]}")
                        x, y, z = vox[q]
                        seen[z, y, x] += 1
                reads += 1
            else:
                assert rden == 0, "a beat without a memory read enables a bank"
        if not int(dut.busy.value) and not valid:
            break
    assert reads == len(expected_reads), f"{reads} read beats, expected {len(expected_reads)}"
    want_seen = np.zeros_like(seen)
    for k, j, pb, i_range in expected_reads:
        for v in expected_lanes(trav, p, k, j, pb, i_range)[1]:
            if v:
                want_seen[v[2], v[1], v[0]] += 1
    assert (seen == want_seen).all() and want_seen.max(initial=0) <= 1, \
        f"view {trav.direction}: voxels read {seen.min()}..{seen.max()} times"
    return beats


def fixed_reads(trav, p: int):
    nb = -(-trav.ni // p)
    return [(k, j, pb, None) for k in range(trav.nk) for j in range(trav.nj) for pb in range(nb)]


@cocotb.test()
async def test_addresses(dut):
    p = int(dut.P.value)
    w = int(dut.WEIGHT_W.value)
    aw = int(dut.ADDR_W.value)
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    await reset(dut)
    views = []
    for major in range(3):
        for signs in range(8):
            d = [(-1.0 if (signs >> a) & 1 else 1.0) * (1.0 if a == major else float(rng.uniform(0.1, 0.9)))
                 for a in range(3)]
            views.append((tuple(d), 1))
    views += [((1.0, 1.0, 1.0), 1), ((0.0, 0.0, -1.0), 1), ((-1.0, 0.0, 0.0), 1), ((0.3, 1.0, -0.2), 2)]
    dims_list = [(2 * p + 3, p + 4, 5), (p + 1, 3 * p - 1 if p > 1 else 4, 3)]
    rects_build = bool(int(dut.RECTS.value))
    if int(dut.BEATS.value):
        return                          # the beat build: test_beats
    for dims in dims_list:
        for direction, ss in views:
            if rects_build and ss != 1:
                continue                # slice rectangles run with S = 1
            trav = make_traversal(dims, direction, w, ss)
            # a rectangle build takes the whole box from its table
            whole = slices.rects_from_needed(np.ones((trav.num_sample_slices, trav.nj, trav.ni), dtype=bool), trav)
            beats = await run_frame(dut, trav, rng, p, aw, fixed_reads(trav, p), whole if rects_build else None)
            nb = -(-trav.ni // p)
            assert beats == (trav.num_sample_slices * trav.nj + 1) * nb + 1, f"{beats} beats"
    dut._log.info("P=%d: %d views x %d volumes, every voxel read once at its address%s", p, len(views),
                  len(dims_list), " (the whole box from the rectangle table)" if rects_build else "")


@cocotb.test()
async def test_slice_rectangles(dut):
    """RECTS = 1: random slice rectangles (cube4.slices from random needed samples, and
    the whole box), every view class: each pass reads exactly the rows, partial beams
    and positions of its traversed rectangle, each voxel of them once, in order, and
    the frame issues slices.schedule_beats beats (flush beams, the drain beat)."""
    if not int(dut.RECTS.value):
        return
    p = int(dut.P.value)
    w = int(dut.WEIGHT_W.value)
    aw = int(dut.ADDR_W.value)
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    await reset(dut)
    views = [(0.3, -0.45, 1.0), (-0.6, 0.25, -1.0), (1.0, 1.0, 1.0), (1.0, -1.0, 0.0), (-1.0, -0.8, 0.2),
             (0.5, 1.0, 0.5), (0.0, 0.0, 1.0), (0.9, 0.2, 0.0)]
    frames = 0
    for dims in [(2 * p + 5, p + 7, 9), (3 * p + 2, 2 * p + 3, 6)]:
        for direction in views:
            trav = make_traversal(dims, direction, w, 1)
            for density in (0.02, 0.2, 1.0):
                need = rng.random((trav.num_sample_slices, trav.nj, trav.ni)) < density
                rects = slices.rects_from_needed(need, trav)
                if rects.beats(p) == 0:
                    continue            # nothing to traverse: the host runs no frame
                reads = []
                for m in range(trav.num_sample_slices):
                    rng_pb = rects.beam_range(m, p)
                    if rng_pb is None:
                        continue
                    j0, j1, i0, i1 = rects.traversed(m)
                    reads += [(m, j, pb, (i0, i1)) for j in range(j0, j1) for pb in range(rng_pb[0], rng_pb[1] + 1)]
                beats = await run_frame(dut, trav, rng, p, aw, reads, rects)
                assert beats == rects.beats(p), f"view {direction}: {beats} beats, expected {rects.beats(p)}"
                frames += 1
    dut._log.info("P=%d: %d frames with slice rectangles, every read and beat as specified", p, frames)


from cube4.beats import LAG  # noqa: E402  (the DUT's default, CUBE4_BEAT_LAG)
SLAB_VIEWS = [(0.2, -0.1, 1.0), (1.0, 1.0, 1.0)]


@cocotb.test()
async def test_beats(dut):
    """BEATS = 1: golden frames of the beat schedule (cube4_sim.beat_frames: two nearly
    opaque slabs, shaded, rays ending in them; sparse volumes in every mode, their LUT
    nearly opaque every other frame, termination off every third) through the whole CFB:
    the bench plays the host (the view's registers, the block table, the ray table's
    stops) and COM (each slice's reports a random delay after the walk's EOS), and takes
    the requests with random ready; in a build with MAX_SS_LOG2 = 2 three more frames at
    S = 2 and 4. Every request beat, in order: the walk's beat
    (cube4_sim.beat_frames.expected_requests, tokens issue nothing), the voxel beat it
    needs (BBWE) and where from: the memory in a pass that reads a voxel slice (pass 0 its
    lower slice, LMEM; with S > 1 pass k0·S + 1 its upper slice k0 + 1, UMEM), the slice
    buffers in the others (the slices' parity K0ODD, UUSE where m mod S > 0), with its
    reads checked lane by lane against the memory layout (``cube4.memory``, as
    test_addresses) at that slice, the
    sample beat it emits (EMIT where the leaving beat runs, and at each slice's last beat
    and the frame's, with EOP; its slice and row: the row below, or the previous slice's
    last), its position bits and EOS; a push beat after each slice's last beat, one drain
    beat after the frame's, and nothing else."""
    if not int(dut.BEATS.value):
        return
    p, aw, max_dim = int(dut.P.value), int(dut.ADDR_W.value), int(dut.MAX_DIM.value)
    m_w = Geometry(p, max_dim, int(dut.MAX_SS_LOG2.value)).m_w
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    for name in ("nbr_en", "blk_we", "tab_we", "rep_valid", "rep_en", "com_m", "blk_base"):
        getattr(dut, name).value = 0
    await reset(dut)
    seeds = [sd for sd in range(200) if sd % 3 == 0][:6]
    cases = [("slab", v, 1) for v in SLAB_VIEWS] + [("sparse", sd, 1) for sd in seeds]
    if int(dut.MAX_SS_LOG2.value) >= 2:
        cases += [("sparse", sd, ss) for sd, ss in ((1, 2), (4, 4), (13, 4))]
    frames = 0
    for n, (kind, arg, ss) in enumerate(cases):
        bf = (slab_frame(p, arg) if kind == "slab"
              else sparse_frame(arg, p, opaque=n % 2 == 0, terminate=n % 3 != 2, supersample=ss))
        s, trav = bf.sched, bf.trav
        if max(trav.dims) > max_dim:
            continue
        assert tuple(trav.origin) == (0, 0, 0), "the bench reads the whole volume"
        for key, val in top_regs(trav, p).items():      # the steps' SX, SY and PH0 too
            getattr(dut, "cfg_" + key.lower()).value = int(val)
        stall, delay = ((0.0, 0.0), (0.3, 1.0), (0.5, 0.2), (0.1, 0.05))[n % 4]
        host = HostCom(dut, bf, p, max_dim, m_w, LAG, rng, int(delay * s.NJ * s.NB))
        await FallingEdge(dut.clk)      # the host's writes start between edges
        await host.load()
        await FallingEdge(dut.clk)
        dut.start.value = 1
        await FallingEdge(dut.clk)
        dut.start.value = 0
        want = expected_requests(bf, p, LAG)
        got, walked, cycle, held = 0, 0, 0, None
        while True:
            host.drive(cycle, walked)
            ready = int(rng.random() >= stall)
            dut.req_ready.value = ready
            await RisingEdge(dut.clk)
            valid = int(dut.req_valid.value)
            if valid:
                beat = (int(dut.req_addr.value), int(dut.req_rden.value), int(dut.tag_m.value),
                        int(dut.tag_j.value), int(dut.tag_pb.value), int(dut.tag_emit.value),
                        int(dut.tag_eop.value), int(dut.req_bits.value), int(dut.req_eos.value),
                        (int(dut.tag_bbwe.value), int(dut.tag_lower_mem.value), int(dut.tag_upper_mem.value),
                         int(dut.tag_uuse.value), int(dut.tag_k0odd.value)))
                if held is not None:
                    assert beat == held, "request changed while stalled"
                held = None if ready else beat
            if valid and ready:
                assert got < len(want), f"{kind} {arg}: more than {len(want)} request beats"
                m, j, pb, need, emit, _leave, row, eop, eos, bits, care = want[got]
                addr_v, rden, tm, tj, tpb, temit, teop, rbits, reos, src = beat
                where = f"{kind} {arg} S={ss} view {trav.direction} beat {got} (m={m}, j={j}, pb={pb})"
                assert (temit, teop, reos) == (emit, eop, eos), \
                    f"{where}: (emit, eop, eos) = {(temit, teop, reos)}, golden {(emit, eop, eos)}"
                lower, upper, k = slice_read(m, ss) if need else (False, False, None)
                if need:        # (a beat that needs nothing: only BBWE and the memory's flags count)
                    want_src = (1, int(lower), int(upper), int(m % ss != 0), (m // ss) % 2)
                else:
                    want_src = (0, 0, 0) + src[3:]
                assert src == want_src, f"{where}: (BBWE, LMEM, UMEM, UUSE, K0ODD) {src}, golden {want_src}"
                reads = need and (lower or upper)
                if emit:
                    assert (tm, tj, tpb) == (*row, pb), f"{where}: emits ({tm}, {tj}, {tpb}), golden {(*row, pb)}"
                assert rbits & care == bits & care, f"{where}: bits {rbits:#x}, golden {bits:#x} (mask {care:#x})"
                if reads:
                    lanes, vox = expected_lanes(trav, p, k, j, pb)
                    for q in range(p):
                        en = (rden >> q) & 1
                        assert en == (lanes[q] is not None), f"{where} lane {q}: rden {en}"
                        a = (addr_v >> (q * aw)) & ((1 << aw) - 1)
                        assert not en or a == lanes[q], f"{where} lane {q}: address {a}, voxel {vox[q]} is at {lanes[q]}"
                else:
                    assert rden == 0, f"{where}: a beat without a read enables a bank"
                walked += eos
                got += 1
            await FallingEdge(dut.clk)
            cycle += 1
            if not int(dut.busy.value) and not valid and got == len(want):
                break
            assert cycle < 200000, f"{kind} {arg}: the frame stalled ({got} of {len(want)} beats)"
        for _ in range(20):
            await RisingEdge(dut.clk)
            assert not int(dut.req_valid.value), "a request after the drain beat"
        frames += 1
        dut._log.info("%s %s S=%d: %d slices of %dx%d beats, %d rays reported done, stall %.1f: %d requests "
                      "in %d cycles as specified", kind, arg, ss, s.M, s.NJ, s.NB, int((s.done < s.M).sum()),
                      stall, got, cycle)
    assert frames >= 4, f"only {frames} frames fit MAX_DIM = {max_dim}"


# P = 2, 4 and 8 are covered by the front-end builds (tb/cube4_frontend), which
# check every sample and therefore every address too.
@pytest.mark.parametrize("p", sweep([1, 5, 16], quick=(1,)))
def test_cube4_cfb(p):
    run_test(
        top="cube4_cfb_harness",
        sources=[*rtl_sources(), HERE / "cube4_cfb_harness.v"],
        params={"P": p, "MAX_DIM": 64, "ADDR_W": 16, "MAX_SS_LOG2": 1},
        test_module=__file__,
    )


@pytest.mark.parametrize("p", sweep([1, 5, 8], quick=()))
def test_cube4_cfb_rects(p):
    """The rectangle build (RECTS = 1): the whole-box frames as the fixed build's, and
    slice rectangles."""
    run_test(
        top="cube4_cfb_harness",
        sources=[*rtl_sources(), HERE / "cube4_cfb_harness.v"],
        params={"P": p, "MAX_DIM": 64, "ADDR_W": 16, "MAX_SS_LOG2": 1, "RECTS": 1},
        test_module=__file__,
    )


@pytest.mark.parametrize("params", sweep([dict(P=8, RATE=2, MAX_SS_LOG2=2), dict(P=1, RATE=1), dict(P=5, RATE=2, MAX_SS_LOG2=2)],
                                         quick=(0,),
                                         ids=lambda d: "-".join(f"{k}{v}" for k, v in d.items())))
def test_cube4_cfb_beats(params):
    """The beat build (BEATS = 1): the walk's beats into requests (test_beats), S = 1 and,
    with MAX_SS_LOG2 = 2, S = 2 and 4."""
    run_test(
        top="cube4_cfb_harness",
        sources=[*rtl_sources(), HERE / "cube4_cfb_harness.v"],
        params={"MAX_DIM": 32, "ADDR_W": 16, "BEATS": 1, **params},
        test_module=__file__,
    )

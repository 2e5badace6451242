"""Unit testbench of rtl/cube4_gra.v: the gradient stream, bit for bit.

The DUT is ``cube4_gra_harness.v``: cube4_gra with its view registers as
ports, a Verilog clock and a cube4_stream_check on the input and the output
stream. The input is the golden sample stream (``cube4.model.sample_stream``)
turned into beats in the hardware's order (``cube4_sim.beats.BeatSchedule``: m,
j, pb; lane q holds i = pb * P + lane_pos(q, skew); header with m, j, pb, skew,
control bits, lane valid and lane inside), offered with random gaps in valid;
the output is taken with random ready (``cube4_sim.unit_bench``, seeded from
COCOTB_RANDOM_SEED). Checked per output beat, in order:

* the header equals the input beat's header (GRA passes it through), field by field;
* the sample and gi, gj, gk of every lane that holds a position equal the golden
  ``gradient_stream`` at (m, j, i);
* exactly M * NJ * NB beats come out: none missing, none extra in the 300
  cycles after the last one (GRA's flush steps must not emit).

Views: z-major with j flipped, z-major with i and k flipped, x-major with k
flipped (at least two with a flipped axis), each with other stalls, in one
simulation per build (views follow each other without a reset), at P = 1, P = 5
and P = 8; the P = 8 build (MAX_SS_LOG2 = 1) runs the views supersampled (S = 2).
With LABELS = 1 (make regress: P = 1 with S = 2, P = 5) each voxel has a random label
(cube4.labels): the sample beats carry the nearest corner's label above the value, the
gradients are of the values, and each output sample carries its centre's label.

The test can fail (tried with deliberately corrupted expectations, not kept):
with the golden gk of lane 0 of beat 40 raised by one, P = 1 fails with
"gk beat 40 (m=0, j=3, pb=7, lane 0: i=7): RTL 89, golden 90" and "1 gk lanes
differ from the golden model"; expecting one beat fewer fails with "N output
beats, expected N-1: 1 extra beat(s) within 300 cycles of the last one".
"""

from __future__ import annotations

import dataclasses

import cocotb
import numpy as np
import pytest

import cube4.slices as slices
from cocotb.triggers import FallingEdge, ReadOnly
from cube4.model import gradient_stream, inside_mask, padded_traversal, rect_slice, sample_stream
from cube4.view import make_traversal
from cube4_sim.sweeps import sweep
from cube4.labels import LABEL_W, MAX_LABELS, pack_words as pack_labels
from cube4_sim.beats import CTRL_EOP, BeatSchedule, Geometry, mask_bits, pack_lanes, unpack_lanes
from cube4_sim.gra_beats import beat_schedule_beats, walk_beats
from cube4_sim.unit_bench import UnitBench, check_headers, check_lanes, param_id, run_unit


# (direction, input gap probability, output stall probability)
VIEWS = [((0.3, -0.45, 1.0), 0.0, 0.0), ((-0.6, 0.25, -1.0), 0.3, 0.4), ((1.0, 0.4, -0.7), 0.6, 0.2)]
OUTPUTS = ["out_hdr", "out_sample", "out_gi", "out_gj", "out_gk"]


def volume_dims(p: int) -> tuple[int, int, int]:
    """Small and non-cubic, with several partial beams along every axis."""
    return (max(11, 2 * p + 3), max(9, p + 4), max(8, p + 2))


@cocotb.test()
async def test_gradient_stream(dut):
    """Golden sample beats in, gradient beats out, bit for bit, with stalls."""
    p, vw, w = int(dut.P.value), int(dut.VOXEL_W.value), int(dut.WEIGHT_W.value)
    geo = Geometry(p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
    gw = vw + 5
    bench = UnitBench(dut)
    await bench.reset({"in_valid": 0, "out_ready": 0, "in_eoss": 0})
    dims = volume_dims(p)
    vol = bench.rng.integers(0, 1 << vw, size=dims[::-1], dtype=np.int64)
    labelled = bool(int(dut.LABELS.value))
    sw = vw + (LABEL_W if labelled else 0)      # a sample: {label, value}
    if labelled:    # a random label per voxel: GRA carries the centre's beside its sample
        vol = pack_labels(vol, bench.rng.integers(0, MAX_LABELS, size=vol.shape), vw)
    ss = 1 << geo.max_ss_log2
    for direction, gap, stall in VIEWS:
        trav = make_traversal(dims, direction, w, ss)
        samples, inside = sample_stream(vol, trav, label_bits=vw if labelled else None)
        sched = BeatSchedule(trav, p, inside)
        hdrs = sched.headers(geo)
        smp = sched.lanes(samples)
        grads = sched.lanes(gradient_stream(samples & ((1 << vw) - 1), trav))  # (beats, 3, P), of the values
        inputs = [{"in_hdr": hdrs[n], "in_sample": pack_lanes(smp[n], sw)} for n in range(len(sched))]
        bench.set_view(trav, p)
        await bench.cycles(2)
        got = await bench.run_stream(inputs, len(sched), OUTPUTS, gap, stall)
        check_headers([b["out_hdr"] for b in got], hdrs, geo, sched, bench.log, "gradient stream")
        check_lanes(np.stack([unpack_lanes(b["out_sample"], p, sw) for b in got]), smp, sched.lval, sched,
                    bench.log, "sample")
        for c, name in enumerate(("gi", "gj", "gk")):
            rtl = np.stack([unpack_lanes(b["out_" + name], p, gw, signed=True) for b in got])
            check_lanes(rtl, grads[:, c, :], sched.lval, sched, bench.log, name)
        bench.log.info("dims %s view %s S=%d gap %.1f stall %.1f: %d gradient beats bit-exact",
                       dims, direction, ss, gap, stall, len(got))


BUILDS = [dict(P=1, VOXEL_W=8, MAX_SS_LOG2=0), dict(P=5, VOXEL_W=8, MAX_SS_LOG2=0),
          dict(P=8, VOXEL_W=12, MAX_SS_LOG2=1), dict(P=1, VOXEL_W=8, MAX_SS_LOG2=1, LABELS=1),
          dict(P=5, VOXEL_W=12, MAX_SS_LOG2=0, LABELS=1)]


@pytest.mark.parametrize("build", sweep(BUILDS, quick=(1,), ids=param_id))
def test_cube4_gra(build):
    run_unit(__file__, {**build, "MAX_DIM": 32}, "test_gradient_stream")


# --------------------------------------------------------------------------- slice rectangles
def walk_frame(rects, trav, p: int, geo: Geometry, vw: int):
    """A slice-rectangle frame as GRA's input walks it (cube4.slices.SliceRects.walk, the
    beats the front end emits: outside the traversed rectangles no lane valid and zero
    samples) and the output expected: the beats of the traversed rectangles, in order,
    with their headers (EOP on the last of them) and golden samples and gradients."""
    M, nj, ni = trav.num_sample_slices, trav.nj, trav.ni
    samples = np.zeros((M, nj, ni), dtype=np.int64)
    inside = np.zeros((M, nj, ni), dtype=bool)
    for m in range(M):
        if not rects.empty(m):
            samples[m] = rect_slice(trav_src[0], trav, m, rects.traversed(m), trav.weight_bits)
            inside[m] = inside_mask(trav, m) & rects.inside(m)
    grads = gradient_stream(samples, trav)
    inputs, outputs = [], []
    for b in walk_beats(rects, trav, p):
        jc, ii = min(b.j, nj - 1), np.minimum(b.pos, ni - 1)
        smp = np.where(b.valid, samples[b.m, jc, ii], 0)
        lins = b.valid & inside[b.m, jc, ii]
        fields = {"inside": mask_bits(lins), "lval": mask_bits(b.valid), "keep": mask_bits(b.valid), "ctrl": b.ctrl,
                  "skew": b.skew, "pb": b.pb, "j": b.j, "m": b.m}
        inputs.append({"in_hdr": geo.pack_header(fields), "in_sample": pack_lanes(smp, vw)})
        if b.valid.any():
            outputs.append((fields, b.valid, smp, np.where(b.valid[None, :], grads[b.m][:, jc, ii], 0),
                            (b.m, b.j, b.pb), b.pos))
    if outputs:   # the output's EOP: its last beat (the input's may lie outside the rectangles)
        for fields, *_ in outputs:
            fields["ctrl"] &= ~(1 << CTRL_EOP)
        outputs[-1][0]["ctrl"] |= 1 << CTRL_EOP
    return inputs, outputs


trav_src = [None]   # the padded traversal-frame volume of the frame being built (walk_frame)


def check_walk_outputs(got, outputs, geo, p: int, vw: int, log) -> None:
    gw = vw + 5
    bad = 0
    for n, (b, (fields, valid, smp, g, where, pos)) in enumerate(zip(got, outputs)):
        have = geo.unpack_header(b["out_hdr"])
        if have != {k: int(v) for k, v in fields.items()}:
            raise AssertionError(f"output beat {n} (m, j, pb = {where}): header {have}, expected {fields}")
        rtl = [unpack_lanes(b["out_sample"], p, vw)] + [unpack_lanes(b["out_" + c], p, gw, signed=True)
                                                     for c in ("gi", "gj", "gk")]
        want = [smp] + [g[c] for c in range(3)]
        for name, r, w in zip(("sample", "gi", "gj", "gk"), rtl, want):
            for q in np.nonzero(valid & (r != w))[0]:
                if bad < 8:
                    log.error("%s beat %d (m, j, pb = %s) lane %d (i = %d): RTL %d, golden %d", name, n, where, q,
                              pos[q], r[q], w[q])
                bad += 1
    assert bad == 0, f"{bad} lanes differ from the golden model"


async def interrupted_frame(bench, inputs, n: int) -> None:
    """Offer the first n beats of a frame with the output always ready, then reset."""
    d = bench.dut
    d.out_ready.value = 1
    k = 0
    while k < n:
        await FallingEdge(d.clk)
        for name, val in inputs[k].items():
            bench.sig(name).value = val
        d.in_valid.value = 1
        await ReadOnly()
        if int(d.in_ready.value):
            k += 1
    await FallingEdge(d.clk)
    await bench.reset({"in_valid": 0, "out_ready": 0, "in_eoss": 0})


async def play_walk(bench, trav, p: int, inputs, outputs, n: int, cut: bool, geo, vw: int) -> list:
    """One walk frame through GRA: the view's registers, with ``cut`` first the frame cut
    off by a reset half-way (the next one must not see its words), then the frame with
    gaps and stalls on every other n, its outputs checked (check_walk_outputs)."""
    bench.set_view(trav, p)
    await bench.cycles(2)
    if cut:
        await interrupted_frame(bench, inputs, len(inputs) // 2)
    gap, stall = (0.0, 0.0) if n % 2 == 0 else (0.3, 0.4)
    got = await bench.run_stream(inputs, len(outputs), OUTPUTS, gap, stall)
    check_walk_outputs(got, outputs, geo, p, vw, bench.log)
    return got


@cocotb.test()
async def test_rect_walks(dut):
    """Slice-rectangle frames (RECTS = 1): GRA's walk in (the traversed rectangles and the
    rows and partial beams beyond them that GRA needs), the rectangles' gradient beats
    out, bit for bit against the golden gradient of the zero-filled slices, with random
    gaps and stalls, frames back to back, a reset in mid-frame, nothing extra."""
    p, vw, w = int(dut.P.value), int(dut.VOXEL_W.value), int(dut.WEIGHT_W.value)
    geo = Geometry(p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
    bench = UnitBench(dut)
    await bench.reset({"in_valid": 0, "out_ready": 0, "in_eoss": 0})
    dims = volume_dims(p)
    vol = bench.rng.integers(0, 1 << vw, size=dims[::-1], dtype=np.int64)
    views = [v for v, _, _ in VIEWS] + [(1.0, 1.0, 1.0), (-1.0, 1.0, 0.0)]
    frames = 0
    for n, direction in enumerate(views * 2):
        trav = make_traversal(dims, direction, w, 1)
        trav_src[0] = padded_traversal(vol, trav)
        density = (0.004, 0.02, 0.1)[n % 3]
        need = bench.rng.random((trav.num_sample_slices, trav.nj, trav.ni)) < density
        rects = dataclasses.replace(slices.rects_from_needed(need, trav), gra=True)
        if rects.last() < 0:
            continue
        inputs, outputs = walk_frame(rects, trav, p, geo, vw)
        got = await play_walk(bench, trav, p, inputs, outputs, n, n == 3, geo, vw)
        frames += 1
        bench.log.info("view %s: %d walk beats in, %d rectangle beats out, bit-exact (%.0f%% of the samples)",
                       direction, len(inputs), len(got), 100 * rects.fraction())
    assert frames >= 6, f"only {frames} frames had a rectangle"


RECT_BUILDS = [dict(P=1, VOXEL_W=8), dict(P=5, VOXEL_W=8), dict(P=8, VOXEL_W=12)]


@pytest.mark.parametrize("build", sweep(RECT_BUILDS, quick=(), ids=param_id))
def test_cube4_gra_rects(build):
    run_unit(__file__, {**build, "MAX_DIM": 32, "RECTS": 1}, "test_rect_walks")


# --------------------------------------------------------------------------- the beat schedule
def beat_walk_frame(bf, p: int, geo: Geometry, vw: int):
    """A beat-schedule frame (numerics.md §19) as GRA's input: the front end's sample beats
    (``beat_schedule_beats``: lanes valid where the beat runs, fixed-schedule samples there,
    zero elsewhere), and the output expected: every input beat, in order, with its header,
    and the golden gradient of the slices with every sample outside the running beats zero
    (what GRA reads for them) on its valid lanes."""
    trav, s = bf.trav, bf.sched
    gold, gin = sample_stream(bf.vol, trav)
    run = np.stack([s.run_samples(m) for m in range(s.M)])
    grads = gradient_stream(np.where(run, gold, 0), trav)
    inputs, outputs = [], []
    for b in beat_schedule_beats(bf, p, beats_lag()):
        ii = np.minimum(b.pos, trav.ni - 1)
        smp = np.where(b.valid, gold[b.m, b.j, ii], 0)
        lins = b.valid & gin[b.m, b.j, ii]
        fields = {"inside": mask_bits(lins), "lval": mask_bits(b.valid), "keep": mask_bits(b.valid), "ctrl": b.ctrl,
                  "skew": b.skew, "pb": b.pb, "j": b.j, "m": b.m}
        inputs.append({"in_hdr": geo.pack_header(fields), "in_sample": pack_lanes(smp, vw), "in_eoss": b.eoss})
        outputs.append((fields, b.valid, smp, np.where(b.valid[None, :], grads[b.m][:, b.j, ii], 0),
                        (b.m, b.j, b.pb), b.pos))
    return inputs, outputs


def beats_lag() -> int:
    from cube4.beats import LAG
    return LAG


@cocotb.test()
async def test_beat_walks(dut):
    """Beat-schedule frames (BEATS = 1): the front end's sample beats in (golden frames:
    opaque slabs whose rays end, so beats run as GRA's neighbours only; sparse shaded
    volumes with and without termination; volumes one and two rows deep, NJ = 1 and 2,
    whose row table is read as a row's word is written and one cycle after, and one
    MAX_DIM rows deep, whose row NJ (the flush row) has row 0's plane address, so the
    planes' writes must keep to their rows (plane A 0 .. NJ - 1, plane B 1 .. NJ); with
    MAX_SS_LOG2 = 2 three sparse frames at S = 2 and 4, whose k neighbours lie between
    voxel slices or not), every beat out in order with its header, the gradients bit for
    bit against the golden gradient of the zero-filled slices, random gaps and stalls,
    frames back to back, a reset in mid-frame, nothing extra."""
    from cube4_sim.beat_frames import slab_frame, sparse_frame, thin_frame
    from cube4_testutil import sparse_case
    p, vw = int(dut.P.value), int(dut.VOXEL_W.value)
    geo = Geometry(p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
    bench = UnitBench(dut)
    await bench.reset({"in_valid": 0, "out_ready": 0, "in_eoss": 0})
    seeds = [sd for sd in range(60) if sparse_case(sd)[6] and sparse_case(sd)[5] == "composite"][:6]
    cases = [("slab", (0.2, -0.1, 1.0)), ("slab", (1.0, 1.0, 1.0)), ("slab", (-1.0, 0.3, 0.5))]
    cases += [("sparse", sd) for sd in seeds]
    cases += [("thin", 1), ("thin", 2)]     # the row table read as its word is written, and one cycle after
    cases += [("thin", int(dut.MAX_DIM.value))]   # NJ = MAX_DIM: row NJ's plane address is row 0's
    ss = {}
    if int(dut.MAX_SS_LOG2.value) >= 2:     # S = 2 and 4 (the seeds' own shaded composite frames)
        more = [sd for sd in range(60, 200) if sparse_case(sd)[6] and sparse_case(sd)[5] == "composite"][:3]
        ss = dict(zip(more, (2, 4, 4)))
        cases += [("sparse", sd) for sd in more]
    frames = 0
    for n, (kind, arg) in enumerate(cases):
        if kind == "slab":
            bf = slab_frame(p, arg)
        elif kind == "thin":
            bf = thin_frame(p, arg)
        else:
            bf = sparse_frame(arg, p, opaque=n % 2 == 0, terminate=n % 3 != 2, supersample=ss.get(arg, 1))
        if max(bf.trav.dims) > int(dut.MAX_DIM.value):
            continue
        inputs, outputs = beat_walk_frame(bf, p, geo, vw)
        await play_walk(bench, bf.trav, p, inputs, outputs, n, n == 4, geo, vw)
        frames += 1
        running = sum(int(b.any()) for _, b, *_ in outputs)
        bench.log.info("%s %s S=%d: %d beats in and out (%d running) of %d in the box, bit-exact",
                       kind, arg, bf.trav.supersample, len(outputs), running, bf.sched.M * bf.sched.NJ * bf.sched.NB)
    assert frames >= 6, f"only {frames} frames fit"


BEAT_BUILDS = [dict(P=8, VOXEL_W=8, MAX_SS_LOG2=2), dict(P=1, VOXEL_W=8), dict(P=5, VOXEL_W=12, MAX_SS_LOG2=2)]


@pytest.mark.parametrize("build", sweep(BEAT_BUILDS, quick=(0,), ids=param_id))
def test_cube4_gra_beats(build):
    run_unit(__file__, {**build, "MAX_DIM": 32, "BEATS": 1}, "test_beat_walks")


def test_cube4_gra_beats_ecp5():
    """The beat walk on the vendor layer's forms: the position buffers' planes (128 words
    at P = 8, MAX_DIM = 32) are DP16KD block RAMs whose output registers load as a step's
    words move on (cube4_sdp_ram OUT_REG = 2), the beam buffer a RAM of the fabric."""
    run_unit(__file__, {"P": 8, "VOXEL_W": 8, "MAX_DIM": 32, "BEATS": 1}, "test_beat_walks", form="ecp5")

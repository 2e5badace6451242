"""Unit testbench of rtl/cube4_com.v: the finished-ray (pixel) stream, bit for bit.

The DUT is ``cube4_com_harness.v``: cube4_com with its view registers as
ports, a Verilog clock and a cube4_stream_check on the input and the output
stream. The input is the golden shaded stream: ``cube4.model.render_frame`` with
random tables and ``keep_streams=True`` gives the shaded samples (R, G, B, A) and
the inside flags, turned into beats in the hardware's order with their headers
(``cube4_sim.beats.BeatSchedule``), offered with random gaps in valid; the output
is taken with random ready (``cube4_sim.unit_bench``, seeded from
COCOTB_RANDOM_SEED).

The expected output is derived from the same frame's finished rays
(``render_frame(...).pixels``, PIXEL_DTYPE): ray (m, by, bx) finishes at sample
(m, j, i) with j = by - SY + stepy(m), i = bx - SX + stepx(m). COM emits one
pixel beat per input beat that finishes at least one ray, in input order, plus
the frame's last beat (eop) whether or not it finishes one. Checked per pixel
beat, in order: m, by, the lane mask and eop exactly; bx and R, G, B, A in every
masked lane; and exactly that many beats, none extra in the 300 cycles after the
last one. So a COM bug shows as the beat, lane and (m, j, i) where it appears,
not as "ray X differs" at the end of a frame.

Views: z-major with j flipped, z-major with i and k flipped, x-major with k
flipped, y-major, z-major with every axis flipped, each with other stalls,
tables, a mode (composite, X-ray, MIP, MinIP: those of the build) and a window
and / or cut plane (the header's KEEP) and a starting phase, one simulation per
build (no reset between views), at P = 1, 5 and 8 (ACC_W 16 and 24), and the
builds with one datapath only (COMPOSITING or EXTREMUM 0; ACC_W 8 < ALPHA_W 16
for MIP's A rounding).

Path weights (PLW = 1 builds at P = 1, 5 and 8): random path-weight columns are
written through the lut_* port before every view (random, not 1 - (1 - A)^w, so
a wrong column or a wrong weight class shows), and the blending views run with
FACES = all six faces, or a random subset (a box with interior faces); the golden
frame weights with the same columns and faces. With the x-exit's bin taken from
the phase of slice m instead of m + 1 (tried, not kept), P = 1 fails with
"R beat 306 (m=3, j=0, pb=9, lane 0: i=9): RTL 8813, golden 8925".

Slice rectangles (RECTS = 1 builds at P = 1, 3, 5 and 8): the beats of random
rectangles (cube4.slices) with the table written through the rect_* port, against
``render_frame(..., rects=...)``; sparse sets give slices of one or two beats. With
the read-after-write rule by position switched off, or the "row above is the previous
beat" case of one-partial-beam rectangles (tried, not kept), P = 1 fails with
"1 R lanes differ from the golden model, first at beat 12 (m=6, j=2, pb=7, lane 0:
i=7)" and "... first at beat 25 (m=6, j=7, pb=0, lane 0: i=7)".

The test can fail (tried with a deliberately corrupted expectation, not kept):
with the golden G of the first finished ray raised by one, P = 1 fails with
"G beat 10 (m=0, j=0, pb=10, lane 0: i=10): RTL 10168, golden 10169" and
"1 G lanes differ from the golden model".
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest

from dataclasses import replace

import cube4.slices as slices
from cube4.config import Cube4Config
from cube4.memory import stop_table
from cube4.model import inside_mask, render_frame
from cube4.pathlen import ALL_FACES
from cube4.view import make_traversal
from cube4_sim.sweeps import sweep
from cube4_sim.beats import BeatSchedule, Geometry, mask_bits, pack_lanes, unpack_lanes
from cocotb.triggers import ReadOnly, RisingEdge

from cube4_sim.beat_frames import beat_frame, expected_requests, reports
from cube4_sim.rect_port import write_rect_table
from cube4_sim.unit_bench import UnitBench, check_lanes, param_id, random_clip, run_unit


# (direction, input gap probability, output stall probability, mode, clip, phase)
VIEWS = [((0.3, -0.45, 1.0), 0.0, 0.0, "composite", None, (0, 0)),
         ((-0.6, 0.25, -1.0), 0.3, 0.4, "mip", "cut", (0, 0)),
         ((1.0, 0.4, -0.7), 0.6, 0.2, "xray", "window", (77, 200)),
         ((0.5, 1.0, 0.5), 0.2, 0.3, "minip", "window+cut", (255, 3)),
         ((-0.2, -1.0, -0.9), 0.1, 0.1, "composite", "window+cut", (128, 128))]
BLEND = ("composite", "xray")
OUTPUTS = ["out_mask", "out_m", "out_by", "out_bx", "out_rgba", "out_eop"]
from cube4.beats import LAG as BEAT_LAG  # noqa: E402  (the beat schedule's lag, CUBE4_BEAT_LAG)
CHANNELS = ("R", "G", "B", "A")


def volume_dims(p: int) -> tuple[int, int, int]:
    """Small and non-cubic, with several partial beams along every axis."""
    return (max(11, 2 * p + 3), max(9, p + 4), max(8, p + 2))


def random_tables(rng, cfg: Cube4Config) -> tuple[np.ndarray, np.ndarray]:
    """LUT with low opacities (rays run through many samples) and a random RMAP."""
    n = 1 << cfg.voxel_bits
    lut = np.empty((n, 4), dtype=np.int64)
    lut[:, :3] = rng.integers(0, 256, size=(n, 3))
    lut[:, 3] = rng.integers(0, 1 << (cfg.alpha_bits - 2), size=n)
    rmap = rng.integers(0, 1024, size=(cfg.rmap_entries, 2), dtype=np.int64)
    return lut, rmap


def finished_rays(frame) -> tuple[np.ndarray, np.ndarray]:
    """The golden finished rays as [m, j, i] arrays: finished flag and (4, M, nj, ni) R, G, B, A."""
    trav = frame.trav
    M, nj, ni = trav.num_sample_slices, trav.nj, trav.ni
    sxm, sym = trav.max_steps
    pix = frame.pixels
    stx, sty = trav.steps(pix["m"].astype(np.int64))
    j = pix["by"] - (sym - sty)
    i = pix["bx"] - (sxm - stx)
    fin = np.zeros((M, nj, ni), dtype=bool)
    rgba = np.zeros((4, M, nj, ni), dtype=np.int64)
    fin[pix["m"], j, i] = True
    for c, key in enumerate("rgba"):
        rgba[c, pix["m"], j, i] = pix[key]
    assert fin.sum() == len(pix), "two golden rays finish at the same sample"
    return fin, rgba


def expected_pixel_beats(frame, sched: BeatSchedule, ends=None) -> dict[str, np.ndarray]:
    """Per expected pixel beat: the schedule's beat, mask (beats, P), m, by, eop, and per
    lane bx and R, G, B, A. ``ends`` (beats, P): the lanes whose rays end there (the beat
    schedule: a beat with one leaves a pixel beat, its mask the rays that hold something);
    None: the lanes of finished rays."""
    trav = frame.trav
    fin, rgba = finished_rays(frame)
    lanes_fin = sched.lanes(fin).astype(bool) & sched.lval
    if ends is None:
        ends = lanes_fin
    assert not (lanes_fin & ~ends).any(), "a golden ray finishes where the bits do not end it"
    last = len(sched) - 1
    beat = np.array([n for n in range(len(sched)) if ends[n].any() or n == last])
    sxm, sym = trav.max_steps
    stx, sty = trav.steps(sched.m[beat])
    return {"beat": beat, "mask": lanes_fin[beat], "m": sched.m[beat], "by": sched.j[beat] - sty + sym,
            "bx": sched.pos[beat] - stx[:, None] + sxm, "eop": beat == last,
            "rgba": sched.lanes(np.moveaxis(rgba, 0, 1))[beat]}  # (beats, 4, P)


def shaded_beats(frame, sched: BeatSchedule, geo: Geometry, aw: int, vw: int) -> list[dict[str, int]]:
    """The golden frame's shaded stream as COM's input beats, in the schedule's order:
    header, {R, G, B, A} per lane and the sample per lane."""
    hdrs = sched.headers(geo)
    shaded = sched.lanes(frame.streams["shaded"])  # [m, c, j, i] -> (beats, 4, P)
    words = (shaded[:, 0] << (16 + aw)) | (shaded[:, 1] << (8 + aw)) | (shaded[:, 2] << aw) | shaded[:, 3]
    smp = sched.lanes(frame.streams["samples"])
    return [{"in_hdr": hdrs[k], "in_rgba": pack_lanes(words[k], 24 + aw), "in_sample": pack_lanes(smp[k], vw)}
            for k in range(len(sched))]


def check_pixel_beats(got: list[dict[str, int]], exp: dict[str, np.ndarray], sched, p: int, bx_w: int,
                      acc_w: int, log) -> None:
    """Every pixel beat against the golden one: m, by, mask, eop; bx and RGBA per masked lane."""
    beat = exp["beat"]
    for key in ("m", "by", "eop"):
        rtl = np.array([[b["out_" + key]] for b in got], dtype=np.int64)
        check_lanes(rtl, exp[key].astype(np.int64)[:, None], np.ones_like(rtl, dtype=bool), sched, log,
                    f"pixel {key}", beat)
    rtl_mask = np.array([[b["out_mask"]] for b in got], dtype=np.int64)
    want_mask = np.array([[mask_bits(f)] for f in exp["mask"]], dtype=np.int64)
    check_lanes(rtl_mask, want_mask, np.ones_like(rtl_mask, dtype=bool), sched, log, "pixel lane mask", beat)
    rtl_bx = np.stack([unpack_lanes(b["out_bx"], p, bx_w) for b in got])
    check_lanes(rtl_bx, exp["bx"], exp["mask"], sched, log, "pixel bx", beat)
    cw = acc_w + 1
    for c, name in enumerate(CHANNELS):   # lane q = {R, G, B, A}, ACC_W + 1 bits each
        rtl = np.stack([unpack_lanes(b["out_rgba"] >> ((3 - c) * cw), p, cw, stride=4 * cw) for b in got])
        check_lanes(rtl, exp["rgba"][:, c], exp["mask"], sched, log, name, beat)


def build_of(dut):
    """The harness's build: P, ALPHA_W, ACC_W, its geometry, configuration, VOXEL_W and
    the modes of its datapaths."""
    p, aw, acc_w = int(dut.P.value), int(dut.ALPHA_W.value), int(dut.ACC_W.value)
    geo = Geometry(p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
    cfg = Cube4Config(pipelines=p, weight_bits=int(dut.WEIGHT_W.value), alpha_bits=aw, acc_bits=acc_w)
    modes = [m for m in ("composite", "xray") if int(dut.COMPOSITING.value)]
    modes += [m for m in ("mip", "minip") if int(dut.EXTREMUM.value)]
    return p, aw, acc_w, geo, cfg, int(dut.VOXEL_W.value), modes


@cocotb.test()
async def test_pixel_stream(dut):
    """Golden shaded beats in, finished-ray beats out, bit for bit, with stalls."""
    p, aw, acc_w, geo, cfg, vw, modes = build_of(dut)
    plw = int(dut.PLW.value) != 0
    bench = UnitBench(dut)
    await bench.reset({"in_valid": 0, "out_ready": 0, "lut_we": 0})
    dims = volume_dims(p)
    vol = bench.rng.integers(0, 1 << cfg.voxel_bits, size=dims[::-1], dtype=np.int64)
    for n, (direction, gap, stall, mode, clip_kind, phase) in enumerate(VIEWS):
        if mode not in modes:   # the build's other datapath: the same view in one of its modes
            mode = modes[n % len(modes)]
        ss = 1 << int(dut.MAX_SS_LOG2.value)
        phase = tuple((ph * ss + n) % (1 << (cfg.weight_bits + ss.bit_length() - 1)) for ph in phase)
        trav = make_traversal(dims, direction, cfg.weight_bits, ss, phase=phase)
        lut, rmap = random_tables(bench.rng, cfg)
        if mode == "xray":   # opaque, bright samples: the sums saturate at 1 on many rays
            lut[:, :3] = bench.rng.integers(128, 256, size=(lut.shape[0], 3))
            lut[:, 3] = bench.rng.integers(0, 1 << aw, size=lut.shape[0])
        clip = random_clip(trav, clip_kind, bench.rng)
        weighted = plw and mode in BLEND
        if weighted:
            cols = bench.rng.integers(0, 1 << aw, size=(lut.shape[0], 4), dtype=np.int64)
            await write_columns(bench, dut, cols, aw)
            lut = np.concatenate([lut, cols], axis=1)
            faces = ALL_FACES if n % 2 == 0 else int(bench.rng.integers(1, ALL_FACES))
            trav = replace(trav, faces=faces)
        frame = render_frame(vol, trav, cfg, lut, rmap, keep_streams=True, mode=mode, clip=clip)
        sched = BeatSchedule(trav, p, frame.streams["inside"], frame.streams["keep"])
        inputs = shaded_beats(frame, sched, geo, aw, vw)
        exp = expected_pixel_beats(frame, sched)
        bench.set_view(trav, p, mode, clip, path_weights=weighted)
        await bench.cycles(2)
        got = await bench.run_stream(inputs, len(exp["beat"]), OUTPUTS, gap, stall)
        check_pixel_beats(got, exp, sched, p, geo.dim_w + 1, acc_w, bench.log)
        bench.log.info("dims %s view %s %s clip %s gap %.1f stall %.1f faces %s: %d pixel beats, %d finished "
                       "rays bit-exact", dims, direction, mode, clip_kind, gap, stall,
                       f"{trav.faces:06b}" if weighted else "-", len(got), len(frame.pixels))


@cocotb.test()
async def test_rect_pixel_stream(dut):
    """Slice rectangles (RECTS = 1): the beats of each slice's traversed rectangle in
    (what GRA forwards), the table written through the rect_* port, finished-ray beats
    out bit for bit against the golden frame with the same rectangles, with random gaps
    and stalls, every mode of the build, views with flipped axes, 45 degrees and an axis,
    sparse and dense rectangles, and slices of one or two beats (the read-after-write
    rule by position)."""
    p, aw, acc_w, geo, cfg, vw, modes = build_of(dut)
    bench = UnitBench(dut)
    await bench.reset({"in_valid": 0, "out_ready": 0, "lut_we": 0, "rect_we": 0})
    dims = volume_dims(p)
    vol = bench.rng.integers(0, 1 << cfg.voxel_bits, size=dims[::-1], dtype=np.int64)
    views = [v[0] for v in VIEWS] + [(1.0, 1.0, 1.0), (0.0, 0.0, -1.0)]
    frames = 0
    for n, direction in enumerate(views * 2):
        mode = modes[n % len(modes)]
        trav = make_traversal(dims, direction, cfg.weight_bits, 1, phase=(n * 37 % 256, n * 91 % 256))
        lut, rmap = random_tables(bench.rng, cfg)
        density = (0.002, 0.01, 0.05, 0.3)[n % 4]
        need = bench.rng.random((trav.num_sample_slices, trav.nj, trav.ni)) < density
        rects = slices.rects_from_needed(need, trav)
        if rects.last() < 0:
            continue
        clip = random_clip(trav, (None, "window", "cut")[n % 3], bench.rng)
        frame = render_frame(vol, trav, cfg, lut, rmap, keep_streams=True, mode=mode, clip=clip, rects=rects)
        sched = BeatSchedule(trav, p, frame.streams["inside"], frame.streams["keep"], rects=rects)
        inputs = shaded_beats(frame, sched, geo, aw, vw)
        exp = expected_pixel_beats(frame, sched)
        bench.set_view(trav, p, mode, clip)
        await write_rect_table(dut, trav, rects, p, int(dut.ADDR_W.value))
        await bench.cycles(2)
        gap, stall = ((0.0, 0.0), (0.3, 0.4), (0.6, 0.2), (0.1, 0.1))[n % 4]
        got = await bench.run_stream(inputs, len(exp["beat"]), OUTPUTS, gap, stall)
        check_pixel_beats(got, exp, sched, p, geo.dim_w + 1, acc_w, bench.log)
        frames += 1
        bench.log.info("dims %s view %s %s rectangles %.0f%% of the samples gap %.1f stall %.1f: %d pixel beats, "
                       "%d finished rays bit-exact", dims, direction, mode, 100 * rects.fraction(), gap, stall,
                       len(got), len(frame.pixels))
    assert frames >= 8, f"only {frames} frames had a rectangle"


STOP_DRAWS = 16


def random_stop(rng, trav) -> np.ndarray:
    """A stop table (cube4.memory.stop_table's input): each base-plane pixel's stop slice
    uniform in 0 .. M, a quarter of them M or 0."""
    M = trav.num_sample_slices
    rows, cols = trav.baseplane_shape
    stop = rng.integers(0, M + 1, size=(rows, cols))
    edge = rng.random((rows, cols))
    stop[edge < 0.125] = 0
    stop[edge > 0.875] = M
    return stop


@cocotb.test()
async def test_stop_pixel_stream(dut):
    """Depth in (ZIN = 1): a random stop table per view written through the stop_* port
    (cube4.memory.stop_table: each base-plane pixel's stop slice uniform in 0 .. M, a
    quarter of them M or 0), the golden shaded stream in, finished-ray beats out bit for
    bit against ``render_frame(..., stop_m=...)``, every mode of the build, the five views
    with their gaps, stalls, windows and cut planes."""
    p, aw, acc_w, geo, cfg, vw, modes = build_of(dut)
    bench = UnitBench(dut)
    await bench.reset({"in_valid": 0, "out_ready": 0, "lut_we": 0, "stop_we": 0})
    dims = volume_dims(p)
    vol = bench.rng.integers(0, 1 << cfg.voxel_bits, size=dims[::-1], dtype=np.int64)
    ss = 1 << int(dut.MAX_SS_LOG2.value)
    for n, (direction, gap, stall, mode, clip_kind, phase) in enumerate(VIEWS):
        mode = mode if mode in modes else modes[n % len(modes)]
        trav = make_traversal(dims, direction, cfg.weight_bits, ss, phase=(phase[0] * ss, phase[1] * ss))
        lut, rmap = random_tables(bench.rng, cfg)
        clip = random_clip(trav, clip_kind, bench.rng)
        unstopped = render_frame(vol, trav, cfg, lut, rmap, mode=mode, clip=clip)
        for _ in range(STOP_DRAWS):  # a small window can leave every ray's samples before its stop
            stop = random_stop(bench.rng, trav)
            frame = render_frame(vol, trav, cfg, lut, rmap, keep_streams=True, mode=mode, clip=clip, stop_m=stop)
            if not np.array_equal(unstopped.baseplane, frame.baseplane):
                break
        else:
            raise AssertionError(f"{STOP_DRAWS} random stop tables changed no ray")
        sched = BeatSchedule(trav, p, frame.streams["inside"], frame.streams["keep"])
        inputs = shaded_beats(frame, sched, geo, aw, vw)
        exp = expected_pixel_beats(frame, sched)
        bench.set_view(trav, p, mode, clip)
        for a, word in enumerate(stop_table(stop, p, geo.max_dim, geo.m_w)):
            dut.stop_we.value, dut.stop_addr.value, dut.stop_data.value = 1, a, word
            await bench.cycles(1)
        dut.stop_we.value = 0
        await bench.cycles(2)
        got = await bench.run_stream(inputs, len(exp["beat"]), OUTPUTS, gap, stall)
        check_pixel_beats(got, exp, sched, p, geo.dim_w + 1, acc_w, bench.log)
        bench.log.info("dims %s view %s %s clip %s gap %.1f stall %.1f: %d pixel beats, %d finished rays with "
                       "their stop slices bit-exact", dims, direction, mode, clip_kind, gap, stall, len(got),
                       len(frame.pixels))


async def collect_reports(dut, p: int, m_w: int, out: list) -> None:
    """Every cycle: COM's report (rep_*) as (d, j, pb, stx, sty, position, end) per
    position it writes, d = end - LAG - 1."""
    while True:
        await RisingEdge(dut.clk)
        await ReadOnly()
        if int(dut.rep_valid.value):
            en, ends = int(dut.rep_en.value), int(dut.rep_end.value)
            j, pb, stx, sty = (int(getattr(dut, n).value) for n in ("rep_j", "rep_pb", "rep_stx", "rep_sty"))
            for t in range(p):
                if (en >> t) & 1:
                    end = (ends >> (t * m_w)) & ((1 << m_w) - 1)
                    out.append((end - BEAT_LAG - 1, j, pb, stx, sty, t, end))


def sparse_volume(rng, dims, vw: int, thick: bool = False) -> np.ndarray:
    """A faint background (values below 64) with one dense blob (64 and up): a LUT that is
    zero below 64 leaves most blocks empty. ``thick``: the blob is two thirds of each axis."""
    nx, ny, nz = dims
    vol = rng.integers(0, 64, size=(nz, ny, nx), dtype=np.int64) << max(0, vw - 8)
    c = [int(rng.integers(n // 4, n - n // 4)) for n in (nz, ny, nx)]
    r = [max(2, n // (3 if thick else 6)) for n in (nz, ny, nx)]
    sl = tuple(slice(max(0, a - b), a + b) for a, b in zip(c, r))
    vol[sl] = rng.integers(64, 256, size=vol[sl].shape) << max(0, vw - 8)
    return vol


@cocotb.test()
async def test_beat_pixel_stream(dut):
    """BEATS = 1: golden frames of the beat schedule (sparse volumes, a LUT that is zero
    below the blob's values; every mode of the build, the views with their windows and
    cut planes, S = 1, and with MAX_SS_LOG2 = 2 one frame at S = 2 and one at S = 4;
    termination in every other frame, at tau = 0 with an opaque LUT or
    at a random tau > 0): COM takes the sample beats the front end emits
    (beat_frames.expected_requests: the running beats with their lanes valid, the cover,
    the row above and each slice's marker with none), with each beat's position bits
    {soon, last, fresh, run} on in_bits and EOSS (its slice's last) on in_eoss; out, bit
    for bit, a pixel beat for every beat in which a running ray ends (bit last), its mask the rays that hold something (the golden
    frame's pixels), and the frame's last beat."""
    if not int(dut.BEATS.value):
        return
    p, aw, acc_w, geo, cfg, vw, modes = build_of(dut)
    bench = UnitBench(dut)
    await bench.reset({"in_valid": 0, "out_ready": 0, "lut_we": 0, "rect_we": 0, "stop_we": 0, "in_bits": 0,
                       "in_eoss": 0, "frame_start": 0, "term_en": 0, "term_tau": 0, "term_vmin": 0, "term_vmax": 0})
    dims = (max(24, 2 * p + 3), 20, 16)     # larger than volume_dims: blocks of 4 that skip
    frames = 0
    blend_ends = 0          # composite frames that terminated so far
    for n, (direction, gap, stall, mode, clip_kind, phase) in enumerate(VIEWS * 2):
        mode = modes[(n // 2) % len(modes)]   # each mode with termination off and on
        ss = {3: 2, 6: 4}.get(n, 1) if int(dut.MAX_SS_LOG2.value) >= 2 else 1
        trav = make_traversal(dims, direction, cfg.weight_bits, ss, phase=phase)
        terminate = n % 2 == 1
        # every other composite frame that terminates: a threshold tau > 0 (half of T or
        # more) on the random LUT and a thick blob, so rays end at their first samples
        # anywhere in it: COM reports most, and those near their stops it does not (the
        # done state alone keeps their later samples out); else tau = 0, opaque where it
        # counts
        tau = 0
        if terminate and mode == "composite":
            tau = int(bench.rng.integers(1 << (acc_w - 1), 1 << acc_w)) if blend_ends % 2 else 0
            blend_ends += 1
        vol = sparse_volume(bench.rng, dims, cfg.voxel_bits, thick=tau > 0)
        lut, rmap = random_tables(bench.rng, cfg)
        lut[: (64 << max(0, cfg.voxel_bits - 8))] = 0
        if terminate and not tau:       # rays end (COM reports them done)
            lut[lut[:, 3] > 0, 3] = (1 << aw) - 1
        clip = random_clip(trav, clip_kind, bench.rng)
        bf = beat_frame(vol, trav, replace(cfg, supersample=ss), lut, rmap, mode, clip,
                        terminate=terminate, tau=tau)
        reqs = [w for w in expected_requests(bf, p, BEAT_LAG) if w[4]]
        order = [(w[6][0], w[6][1], w[2], w[5]) for w in reqs]
        frame = bf.frame
        sched = BeatSchedule(trav, p, frame.streams["inside"], frame.streams["keep"], order=order)
        inputs = shaded_beats(frame, sched, geo, aw, vw)
        for k, w in enumerate(reqs):
            inputs[k]["in_bits"] = w[9]
            inputs[k]["in_eoss"] = int(k == len(reqs) - 1 or reqs[k + 1][6][0] != w[6][0])   # its slice's last
        # the lanes whose ray ends at the beat (before the pixel's "holds something"
        # rule): inside and running, and its next sample (m + 1, j + dyf, i + dxf) not
        # (the golden frame's inside stream: the box, and the ray's run, its end moved
        # by COM's reports)
        M, ins_s = trav.num_sample_slices, frame.streams["inside"]
        nxt_in = np.zeros_like(sched.lval)
        for k in range(len(reqs)):
            m, j = int(sched.m[k]), int(sched.j[k])
            if m + 1 >= M:
                continue
            dxf, dyf = (int(a) - int(b) for a, b in zip(trav.steps(m + 1), trav.steps(m)))
            for q in range(p):
                i = int(sched.pos[k, q]) + dxf
                nxt_in[k, q] = j + dyf < trav.nj and i < trav.ni and bool(ins_s[m + 1, j + dyf, i])
        ends = ~nxt_in & sched.lval & sched.lins
        exp = expected_pixel_beats(frame, sched, ends)
        bench.set_view(trav, p, mode, clip)
        dut.term_en.value, dut.term_tau.value = int(terminate), tau
        dut.term_vmin.value, dut.term_vmax.value = int(vol.min()), int(vol.max())
        dut.frame_start.value = 1
        await bench.cycles(1)
        dut.frame_start.value = 0
        await bench.cycles(1)
        reps = []
        mon = cocotb.start_soon(collect_reports(dut, p, geo.m_w, reps))
        got = await bench.run_stream(inputs, len(exp["beat"]), OUTPUTS, gap, stall)
        mon.cancel()
        check_pixel_beats(got, exp, sched, p, geo.dim_w + 1, acc_w, bench.log)
        want = {(d, j, pb, stx, sty, pos, end) for d, beats_d in reports(bf, p, BEAT_LAG).items()
                for j, pb, stx, sty, ends in beats_d for pos, end in ends.items()}
        assert set(reps) == want, (f"view {direction} {mode}: reports RTL - golden {sorted(set(reps) - want)[:4]}, "
                                   f"golden - RTL {sorted(want - set(reps))[:4]}")
        assert len(reps) == len(set(reps)), "a ray reported twice"
        assert int(dut.com_m.value) == trav.num_sample_slices, f"com_m {int(dut.com_m.value)} after the frame"
        frames += 1
        box = trav.num_sample_slices * trav.nj * -(-trav.ni // p)
        bench.log.info("dims %s S=%d view %s %s clip %s tau %d gap %.1f stall %.1f: %d of %d beats in (%d run), %d "
                       "pixel beats, %d finished rays bit-exact, %d rays reported done", dims, ss, direction, mode, clip_kind,
                       tau if terminate else -1, gap, stall, len(reqs), box, sum(w[5] for w in reqs), len(got), len(frame.pixels), len(reps))
    assert frames >= 8


async def write_columns(bench, dut, cols: np.ndarray, aw: int) -> None:
    """Write the path-weight columns (2^V, 4) through the lut_* port, one entry per cycle."""
    for a in range(cols.shape[0]):
        dut.lut_we.value = 1
        dut.lut_addr.value = a
        dut.lut_data.value = sum(int(cols[a, c]) << (c * aw) for c in range(4))
        await bench.cycles(1)
    dut.lut_we.value = 0


# ACC_W 8 < ALPHA_W 16 with both datapaths makes the buffer word the extremum's ({v, R, G,
# B, A} wider than {R, G, B, T}); MAX_SS_LOG2 = 1 runs the views at S = 2 with phases up
# to 2^(W+1); make test runs the extremum alone (P = 3), COM's units on their own and
# the whole COM through cube4_top (P = 1 and 5); make regress all and the
# slice-rectangle builds
BUILDS = [dict(P=1, ALPHA_W=12, ACC_W=16, COMPOSITING=1, EXTREMUM=1, MAX_SS_LOG2=0, PLW=1),
          dict(P=5, ALPHA_W=12, ACC_W=16, COMPOSITING=1, EXTREMUM=1, MAX_SS_LOG2=1, PLW=1),
          dict(P=8, ALPHA_W=16, ACC_W=24, COMPOSITING=1, EXTREMUM=1, MAX_SS_LOG2=0, PLW=1),
          dict(P=5, ALPHA_W=12, ACC_W=16, COMPOSITING=1, EXTREMUM=0, MAX_SS_LOG2=0, PLW=0),
          dict(P=3, ALPHA_W=16, ACC_W=8, COMPOSITING=0, EXTREMUM=1, MAX_SS_LOG2=0, PLW=0),
          dict(P=3, ALPHA_W=16, ACC_W=8, COMPOSITING=1, EXTREMUM=1, MAX_SS_LOG2=0, PLW=0)]


# slice-rectangle builds: P = 1, 5, 8 (both datapaths), one with the extremum only
RECT_BUILDS = [dict(P=1, ALPHA_W=12, ACC_W=16, COMPOSITING=1, EXTREMUM=1),
               dict(P=5, ALPHA_W=12, ACC_W=16, COMPOSITING=1, EXTREMUM=1),
               dict(P=8, ALPHA_W=16, ACC_W=24, COMPOSITING=1, EXTREMUM=1),
               dict(P=3, ALPHA_W=16, ACC_W=8, COMPOSITING=0, EXTREMUM=1)]


# beat-schedule builds (BEATS = 1, PLW = 0): P = 8 (MAX_SS_LOG2 = 2: S = 2 and 4 too) in
# make test; 1, 5 and the extremum alone in make regress
BEAT_BUILDS = [dict(P=8, ALPHA_W=16, ACC_W=24, COMPOSITING=1, EXTREMUM=1, MAX_SS_LOG2=2),
               dict(P=1, ALPHA_W=12, ACC_W=16, COMPOSITING=1, EXTREMUM=1),
               dict(P=5, ALPHA_W=12, ACC_W=16, COMPOSITING=1, EXTREMUM=1),
               dict(P=3, ALPHA_W=16, ACC_W=8, COMPOSITING=0, EXTREMUM=1)]


@pytest.mark.parametrize("build", sweep(BEAT_BUILDS, quick=(0,), ids=param_id))
def test_cube4_com_beats(build):
    run_unit(__file__, {**build, "MAX_DIM": 32, "BEATS": 1, "PLW": 0}, "test_beat_pixel_stream")


@pytest.mark.parametrize("build", sweep(RECT_BUILDS, quick=(), ids=param_id))
def test_cube4_com_rects(build):
    run_unit(__file__, {**build, "MAX_DIM": 32, "RECTS": 1, "PLW": 0}, "test_rect_pixel_stream")


# depth-in builds: P = 1, 5 with S = 2 (make test), 8 with ACC_W 24
STOP_BUILDS = [dict(P=1, ALPHA_W=12, ACC_W=16, COMPOSITING=1, EXTREMUM=1, MAX_SS_LOG2=0, PLW=0),
               dict(P=5, ALPHA_W=12, ACC_W=16, COMPOSITING=1, EXTREMUM=1, MAX_SS_LOG2=1, PLW=0),
               dict(P=8, ALPHA_W=16, ACC_W=24, COMPOSITING=1, EXTREMUM=1, MAX_SS_LOG2=0, PLW=0)]


@pytest.mark.parametrize("build", sweep(STOP_BUILDS, quick=(0,), ids=param_id))
def test_cube4_com_stop(build):
    run_unit(__file__, {**build, "MAX_DIM": 32, "ZIN": 1}, "test_stop_pixel_stream")


@pytest.mark.parametrize("build", sweep(BUILDS, quick=(4,), ids=param_id))
def test_cube4_com(build):
    run_unit(__file__, {**build, "MAX_DIM": 32}, "test_pixel_stream")

"""Unit testbench of rtl/cube4_sha.v: the shaded stream, bit for bit.

The DUT is ``cube4_sha_harness.v``: cube4_sha with its table load ports,
a Verilog clock and a cube4_stream_check on the input and the output stream.
Before every view the testbench writes new random tables through the load ports
(a LUT of 2^VOXEL_W entries {R, G, B, A} and a reflectance map of 6 R^2 + 1
entries {D, P}, over their full ranges). The input is the golden gradient
stream: samples (``cube4.model.sample_stream``) and gradients
(``gradient_stream``) turned into beats in the hardware's order with their
headers (``cube4_sim.beats.BeatSchedule``), offered with random gaps in valid;
the output is taken with random ready (``cube4_sim.unit_bench``, seeded from
COCOTB_RANDOM_SEED). Checked per output beat, in order:

* the header equals the input beat's header (SHA passes it through), field by field;
* R', G', B' and A of every lane that holds a position equal the golden
  ``shade`` at (m, j, i), and out_idx equals the golden ``rmap_index``;
* exactly M * NJ * NB beats come out: none missing, none extra in the 300
  cycles after the last one.

Views: z-major with j flipped, z-major with i and k flipped, x-major with k
flipped, each with other stalls and tables, one simulation per build (no reset
between views), at P = 1, 5 and 8 with different VOXEL_W, ALPHA_W and RMAP_BITS.
With LABELS = 1 each voxel has a random label (cube4.labels), the samples carry the
nearest corner's label above the value, the LUT has a block of 2^VOXEL_W entries per
label, and out_sample carries the value alone.

The test can fail (tried with a deliberately corrupted expectation, not kept):
with the golden A of lane 0 of beat 40 raised by one, P = 1 fails with
"A beat 40 (m=0, j=3, pb=7, lane 0: i=7): RTL 364, golden 365" and "1 A lanes
differ from the golden model".
"""

from __future__ import annotations


import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge

from cube4.clip import FALL_ONE, FALL_W, Clip, slab_coefficients
from cube4.gmod import GMF_BITS, GM_ONE, table_entries
from cube4.labels import LABEL_W, MAX_LABELS, pack_words as pack_labels
from cube4.model import gradient_stream, sample_stream, shade
from cube4.view import make_traversal
from cube4_sim.sweeps import sweep
from cube4_sim.beats import BeatSchedule, Geometry, pack_lanes, unpack_lanes
from cube4_sim.unit_bench import UnitBench, check_headers, check_lanes, param_id, run_unit


# (direction, input gap probability, output stall probability)
VIEWS = [((0.3, -0.45, 1.0), 0.0, 0.0), ((-0.6, 0.25, -1.0), 0.3, 0.4), ((1.0, 0.4, -0.7), 0.6, 0.2)]
OUTPUTS = ["out_hdr", "out_rgba", "out_idx", "out_sample", "out_fall"]
CHANNELS = ("R", "G", "B", "A")


def volume_dims(p: int) -> tuple[int, int, int]:
    """Small and non-cubic, with several partial beams along every axis."""
    return (max(11, 2 * p + 3), max(9, p + 4), max(8, p + 2))


def view_slab(trav, dims, n: int) -> Clip:
    """View n's slab: a thin one with a falloff wider than half of it (no weight reaches
    one), a thick one with a narrow falloff, or a hard one (FALL_ON = 0), each tilted."""
    centre = tuple((d - 1) / 2 for d in dims)
    thickness, falloff = ((2.5, 1.75), (6.0, 0.75), (4.0, 0.0))[n % 3]
    plane, slab = slab_coefficients(trav, (0.4, -0.7, 0.6), centre, thickness, falloff)
    return Clip(plane=plane, slab=slab)


def random_tables(rng, vw: int, aw: int, rmap_bits: int) -> tuple[np.ndarray, np.ndarray]:
    """LUT (2^VOXEL_W, 4): R, G, B Q0.8, A Q0.ALPHA_W; RMAP (6 R^2 + 1, 2): D, P Q2.8."""
    n = 1 << vw
    lut = np.empty((n, 4), dtype=np.int64)
    lut[:, :3] = rng.integers(0, 256, size=(n, 3))
    lut[:, 3] = rng.integers(0, 1 << aw, size=n)
    rmap = rng.integers(0, 1024, size=(6 * (1 << (2 * rmap_bits)) + 1, 2), dtype=np.int64)
    return lut, rmap


async def load_tables(dut, lut: np.ndarray, rmap: np.ndarray, aw: int) -> None:
    """Write both tables through the load ports, one entry of each per cycle."""
    for a in range(max(len(lut), len(rmap))):
        await FallingEdge(dut.clk)
        dut.lut_we.value = int(a < len(lut))
        if a < len(lut):
            r, g, b, al = (int(v) for v in lut[a])
            dut.lut_addr.value = a
            dut.lut_data.value = (r << (16 + aw)) | (g << (8 + aw)) | (b << aw) | al
        dut.rmap_we.value = int(a < len(rmap))
        if a < len(rmap):
            dut.rmap_addr.value = a
            dut.rmap_data.value = (int(rmap[a, 0]) << 10) | int(rmap[a, 1])
    await FallingEdge(dut.clk)
    dut.lut_we.value = 0
    dut.rmap_we.value = 0


async def load_gm_table(dut, gm: np.ndarray) -> None:
    """Write the modulation table {fa, fs} through gm_*, one entry per cycle."""
    for a, (fa, fs) in enumerate(gm):
        await FallingEdge(dut.clk)
        dut.gm_we.value, dut.gm_addr.value = 1, a
        dut.gm_data.value = (int(fa) << GMF_BITS) | int(fs)
    await FallingEdge(dut.clk)
    dut.gm_we.value = 0


def split_rgba(words: list[int], p: int, aw: int) -> np.ndarray:
    """out_rgba words -> (beats, 4, P): R, G, B, A per lane."""
    lanes = np.stack([unpack_lanes(wd, p, 24 + aw) for wd in words])
    return np.stack([lanes >> (16 + aw), (lanes >> (8 + aw)) & 255, (lanes >> aw) & 255,
                     lanes & ((1 << aw) - 1)], axis=1)


@cocotb.test()
async def test_shaded_stream(dut):
    """Golden gradient beats in, shaded beats out, bit for bit, with stalls."""
    p, vw = int(dut.P.value), int(dut.VOXEL_W.value)
    aw, rb = int(dut.ALPHA_W.value), int(dut.RMAP_BITS.value)
    geo = Geometry(p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
    gw, ri_w = vw + 5, 2 * rb + 3
    shading = bool(int(dut.SHADING.value))   # 0: classification only, C' = C
    bench = UnitBench(dut)
    await bench.reset({"in_valid": 0, "out_ready": 0, "lut_we": 0, "rmap_we": 0, "gm_we": 0})
    gmod = shading and bool(int(dut.GMOD.value))
    labelled = bool(int(dut.LABELS.value))
    sw = vw + (LABEL_W if labelled else 0)      # a sample: {label, value}
    dims = volume_dims(p)
    vol = bench.rng.integers(0, 1 << vw, size=dims[::-1], dtype=np.int64)
    vol[:, :, : dims[0] // 2] = vol[0, 0, 0]    # a flat half: gradient zero (the map's last entry)
    if labelled:    # a random label per voxel: the LUT's blocks
        vol = pack_labels(vol, bench.rng.integers(0, MAX_LABELS, size=vol.shape), vw)
    slab = bool(int(dut.SLAB.value)) and bool(int(dut.COMPOSITING.value))
    ss = 1 << int(dut.MAX_SS_LOG2.value)
    for n_view, (direction, gap, stall) in enumerate(VIEWS):
        trav = make_traversal(dims, direction, 8, ss)
        clip = view_slab(trav, dims, n_view) if slab else None
        bench.set_view(trav, p, clip=clip)
        lut, rmap = random_tables(bench.rng, sw, aw, rb)     # with labels a block per label
        await load_tables(dut, lut, rmap, aw)
        gm = None
        if gmod:    # random factors over their range, a quarter of them 256 (the identity)
            gm = bench.rng.integers(0, GM_ONE + 1, size=(table_entries(gw), 2))
            gm[bench.rng.random(gm.shape) < 0.25] = GM_ONE
            await load_gm_table(dut, gm)
        samples, inside = sample_stream(vol, trav, label_bits=vw if labelled else None)
        values = samples & ((1 << vw) - 1)      # (without labels: the samples)
        grads = gradient_stream(values, trav)  # (M, 3, nj, ni)
        rgba, idx = shade(samples, np.moveaxis(grads, 1, 0) if shading else None, lut, rmap, rb, gm)
        if idx is None:
            idx = np.zeros_like(samples)     # (M, nj, ni); out_idx is 0 without shading
        sched = BeatSchedule(trav, p, inside)
        hdrs = sched.headers(geo)
        smp, g = sched.lanes(samples), sched.lanes(grads)
        inputs = [{"in_hdr": hdrs[n], "in_sample": pack_lanes(smp[n], sw), "in_gi": pack_lanes(g[n, 0], gw),
                   "in_gj": pack_lanes(g[n, 1], gw), "in_gk": pack_lanes(g[n, 2], gw)} for n in range(len(sched))]
        got = await bench.run_stream(inputs, len(sched), OUTPUTS, gap, stall)
        check_headers([b["out_hdr"] for b in got], hdrs, geo, sched, bench.log, "shaded stream")
        want = sched.lanes(np.moveaxis(rgba, 0, 1))  # (beats, 4, P)
        rtl = split_rgba([b["out_rgba"] for b in got], p, aw)
        for c, name in enumerate(CHANNELS):
            check_lanes(rtl[:, c], want[:, c], sched.lval, sched, bench.log, name)
        if shading:
            bench.log.info("%d samples read the zero gradient's entry", int((idx == len(rmap) - 1).sum()))
        rtl_idx = np.stack([unpack_lanes(b["out_idx"], p, ri_w) for b in got])
        check_lanes(rtl_idx, sched.lanes(idx), sched.lval, sched, bench.log, "reflectance-map index")
        rtl_smp = np.stack([unpack_lanes(b["out_sample"], p, vw) for b in got])
        carried = sched.lanes(values) if int(dut.CARRY_SAMPLE.value) else np.zeros_like(smp)
        check_lanes(rtl_smp, carried, sched.lval, sched, bench.log, "sample (passed through, or 0)")
        fall = np.full(samples.shape, FALL_ONE, dtype=np.int64)
        if clip is not None and clip.falloff(trav, 0) is not None:
            fall = np.stack([clip.falloff(trav, m) for m in range(trav.num_sample_slices)])
        rtl_fall = np.stack([unpack_lanes(b["out_fall"], p, FALL_W) for b in got])
        check_lanes(rtl_fall, sched.lanes(fall), sched.lval, sched, bench.log, "falloff weight (or 256)")
        if clip is not None:
            bench.log.info("slab %s: falloff weights %d .. %d", clip.slab, int(fall.min()), int(fall.max()))
        bench.log.info("dims %s view %s gap %.1f stall %.1f: %d shaded beats bit-exact",
                       dims, direction, gap, stall, len(got))


# make test: P = 5 unshaded with 12-bit voxels and the slab's falloff (S = 4), and P = 5 shaded with
# gradient-magnitude modulation (RMAP_BITS = 2: the factors come just in time, S = 2; every view
# with a random table) and labels (a LUT block per label, read at {label, value});
# make regress all
BUILDS = [dict(P=1, VOXEL_W=8, ALPHA_W=12, RMAP_BITS=5, SHADING=1, CARRY_SAMPLE=1),
          dict(P=5, VOXEL_W=8, ALPHA_W=12, RMAP_BITS=3, SHADING=1, CARRY_SAMPLE=0),
          dict(P=8, VOXEL_W=12, ALPHA_W=16, RMAP_BITS=4, SHADING=1, CARRY_SAMPLE=1),
          dict(P=1, VOXEL_W=8, ALPHA_W=12, RMAP_BITS=5, SHADING=0, CARRY_SAMPLE=1),
          dict(P=5, VOXEL_W=12, ALPHA_W=16, RMAP_BITS=5, SHADING=0, CARRY_SAMPLE=0),
          dict(P=5, VOXEL_W=8, ALPHA_W=12, RMAP_BITS=2, SHADING=1, CARRY_SAMPLE=1, SLAB=1, MAX_SS_LOG2=1),
          dict(P=5, VOXEL_W=12, ALPHA_W=16, RMAP_BITS=5, SHADING=0, CARRY_SAMPLE=0, SLAB=1, MAX_SS_LOG2=2),
          dict(P=5, VOXEL_W=8, ALPHA_W=12, RMAP_BITS=2, SHADING=1, CARRY_SAMPLE=1, GMOD=1, MAX_SS_LOG2=1, LABELS=1),
          dict(P=1, VOXEL_W=12, ALPHA_W=16, RMAP_BITS=5, SHADING=1, CARRY_SAMPLE=0, GMOD=1, SLAB=1),
          dict(P=8, VOXEL_W=8, ALPHA_W=12, RMAP_BITS=5, SHADING=1, CARRY_SAMPLE=1, GMOD=1),
          dict(P=1, VOXEL_W=8, ALPHA_W=12, RMAP_BITS=5, SHADING=0, CARRY_SAMPLE=1, LABELS=1)]


@pytest.mark.parametrize("build", sweep(BUILDS, quick=(6, 7), ids=param_id))
def test_cube4_sha(build):
    run_unit(__file__, {"MAX_DIM": 32, "MAX_SS_LOG2": 0, **build}, "test_shaded_stream")

"""Unit testbench of rtl/cube4_tri.v: the sample stream, bit for bit.

TRI's input is the memory's response beats: the voxels of P banks and
cube4_cfb's tag (weights, slots, buffer controls). The one exact source of those
beats is cube4_cfb reading cube4_voxel_mem, so the DUT
(``cube4_tri_harness.v``) contains both in front of TRI, with a seeded
Verilog stall generator (cube4_sim_stall, seed = COCOTB_RANDOM_SEED) on the
memory request and one on the memory response, which is TRI's input; TRI's
output is taken by Python with random ready (``cube4_sim.unit_bench``). This is
TRI's own testbench in that the check is on TRI's output stream alone, against
the golden ``sample_stream``, with stalls on its input and its output; a
cube4_stream_check watches TRI's input and output streams. (The front-end
testbench, tb/cube4_frontend, covers CFB, memory and TRI as one.)

Checked per output beat, in order, against ``cube4_sim.beats.BeatSchedule``
(m, j, pb order; lane q holds i = pb * P + lane_pos(q, skew)):

* the header: m, j, pb, skew, the control bits, lane valid and lane inside;
* the sample of every lane that holds a position (golden ``sample_stream``);
* exactly M * NJ * NB beats come out: none missing, none extra in the 300
  cycles after the last one.

Views: z-major with j flipped, z-major with i and k flipped, x-major with k
flipped, each with other stalls, in one simulation per build (one volume
load, no reset between views), at P = 1, P = 5 and P = 8; the P = 8 build
(MAX_SS_LOG2 = 1) runs the views supersampled (S = 2).

With VGRAD = 1 the memory holds the words of golden ``cube4.vgrad`` (each voxel and its
gradient; the P = 5 build Sobel, the P = 8 build central differences) and every
lane's whole word is checked: the sample and the three interpolated components.
With LABELS = 1 the memory holds labelled words (golden ``cube4.labels``, labels in
blocks with boundaries along every axis) and every lane's word is the sample with the
nearest corner's label above it.

The test can fail (tried with a deliberately corrupted expectation, not kept):
with the golden sample of lane 0 of beat 40 raised by one, P = 1 fails with
"sample beat 40 (m=0, j=3, pb=7, lane 0: i=7): RTL 102, golden 103" and
"1 sample lanes differ from the golden model"; with the gradient components' sign-bit
flip moved one bit down (the RTL's FLIP at CW - 2), P = 5 with VGRAD fails with
"sample beat 27 (m=1, j=0, pb=0, lane 0: i=2): RTL 109403761495, golden 109403718231".
"""

from __future__ import annotations


import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge

from cube4.memory import pack_volume
from cube4.model import sample_stream
from cube4.labels import MAX_LABELS, pack_words as pack_labels
from cube4.vgrad import pack_channels, pack_words, word_bits
from cube4.view import make_traversal
from cube4_sim.sweeps import sweep
from cube4_sim.beats import BeatSchedule, Geometry, pack_lanes, unpack_lanes
from cube4_sim.unit_bench import UnitBench, check_headers, check_lanes, param_id, random_clip, run_unit


# (direction, memory-request stall /256, TRI-input stall /256, output stall probability)
# (direction, memory-request stall, memory-response stall, output stall probability,
#  window / cut plane (the header's KEEP), starting phase, crop box (origin, dims) or None)
VIEWS = [((0.3, -0.45, 1.0), 0, 0, 0.0, None, (0, 0), None),
         ((-0.6, 0.25, -1.0), 60, 120, 0.4, "window+cut", (0, 0), None),
         ((1.0, 0.4, -0.7), 0, 200, 0.2, "cut+regions", (101, 250), None),
         ((0.5, 1.0, 0.5), 30, 30, 0.3, "window", (5, 77), ((3, 2, 1), (7, 6, 6))),
         ((-0.2, -1.0, -0.9), 0, 60, 0.1, "regions", (200, 9), ((1, 3, 2), (9, 5, 5))),
         # no slope along i (wx = 0 on every slice): samples lie on a region's high face
         ((0.0, 0.3, 1.0), 0, 0, 0.2, "regions", (0, 0), None)]
OUTPUTS = ["out_hdr", "out_sample"]
DEPTH, ADDR_W = 4096, 12


def volume_dims(p: int) -> tuple[int, int, int]:
    """Small and non-cubic, with several partial beams along every axis."""
    return (max(11, 2 * p + 3), max(9, p + 4), max(8, p + 2))


async def load_volume(dut, vol: np.ndarray, p: int, vw: int) -> None:
    """Pack the volume (cube4.memory, the one host packer) and write it through the
    memory's load port, one word per bank per cycle."""
    banks = pack_volume(vol, p)
    assert banks.shape[1] <= DEPTH, f"volume needs {banks.shape[1]} words per bank, DEPTH = {DEPTH}"
    for a in range(banks.shape[1]):
        await FallingEdge(dut.clk)
        dut.ld_valid.value = 1
        dut.ld_addr.value = a
        dut.ld_data.value = pack_lanes(banks[:, a], vw)
        assert int(dut.ld_ready.value) == 1, "the memory's load port is not ready"
    await FallingEdge(dut.clk)
    dut.ld_valid.value = 0


@cocotb.test()
async def test_sample_stream(dut):
    """Memory beats through a stalled input, sample beats out with random ready, bit for bit."""
    p, vw, w = int(dut.P.value), int(dut.VOXEL_W.value), int(dut.WEIGHT_W.value)
    geo = Geometry(p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
    ss = 1 << geo.max_ss_log2
    bench = UnitBench(dut)
    dut.seed.value = cocotb.RANDOM_SEED & 0xFFFFFFFF
    await bench.reset({"out_ready": 0, "start": 0, "ld_valid": 0, "stall_req": 0, "stall_in": 0})
    dims = volume_dims(p)
    vol = bench.rng.integers(0, 1 << vw, size=dims[::-1], dtype=np.int64)
    vgrad, labelled = bool(int(dut.VGRAD.value)), bool(int(dut.LABELS.value))
    if vgrad:       # the voxel-gradient words: Sobel at P = 5, central differences otherwise
        vol = pack_words(vol, "sobel" if p == 5 else "central", vw)
    if labelled:    # labels in blocks of 2 x 3 x 1 voxels: boundaries in every axis
        zz, yy, xx = np.mgrid[0:dims[2], 0:dims[1], 0:dims[0]]
        blocks = bench.rng.integers(0, MAX_LABELS, size=(dims[2] + 1, dims[1] // 3 + 1, dims[0] // 2 + 1))
        vol = pack_labels(vol, blocks[zz, yy // 3, xx // 2], vw)
    ww = word_bits(vw, vgrad, labelled)
    await load_volume(dut, vol, p, ww)
    clip_on = bool(int(dut.CLIP.value))
    for direction, stall_req, stall_in, stall, clip_kind, phase, crop in VIEWS:
        origin, box = crop if crop else ((0, 0, 0), dims)
        phase = tuple(ph % (1 << (w + geo.max_ss_log2)) for ph in phase)
        trav = make_traversal(box, direction, w, ss, phase=phase, origin=origin)
        x0, y0, z0 = origin
        samples, inside = sample_stream(vol[z0:z0 + box[2], y0:y0 + box[1], x0:x0 + box[0]], trav,
                                        vw if vgrad else None, vw if labelled else None)
        if vgrad:   # (M, 4, nj, ni) -> the words TRI emits
            samples = pack_channels(samples[:, 0], np.moveaxis(samples[:, 1:], 1, 0), vw)
        clip = random_clip(trav, clip_kind, bench.rng) if clip_on else None
        keep = None if clip is None else np.stack([clip.keep(trav, m) for m in range(trav.num_sample_slices)])
        sched = BeatSchedule(trav, p, inside, keep)
        hdrs = sched.headers(geo)
        bench.set_view(trav, p, clip=clip, vol_dims=dims)
        dut.stall_req.value, dut.stall_in.value = stall_req, stall_in
        await FallingEdge(dut.clk)
        dut.start.value = 1
        await FallingEdge(dut.clk)
        dut.start.value = 0
        got = await bench.run_stream(None, len(sched), OUTPUTS, 0.0, stall)
        check_headers([b["out_hdr"] for b in got], hdrs, geo, sched, bench.log, "sample stream")
        check_lanes(np.stack([unpack_lanes(b["out_sample"], p, ww) for b in got]), sched.lanes(samples),
                    sched.lval, sched, bench.log, "sample")
        bench.log.info("dims %s box %s view %s S=%d phase %s clip %s stalls req %d in %d out %.1f: "
                       "%d sample beats bit-exact", dims, crop, direction, ss, phase, clip_kind if clip_on else None,
                       stall_req, stall_in, stall, len(got))


# all in make regress: make test runs TRI's units on their own (tb/cube4_tri_*) and the
# whole TRI through cube4_top (P = 1 and 5)
BUILDS = [dict(P=1, VOXEL_W=8, MAX_SS_LOG2=0, CLIP=1, VGRAD=0), dict(P=5, VOXEL_W=8, MAX_SS_LOG2=0, CLIP=1, VGRAD=0),
          dict(P=8, VOXEL_W=12, MAX_SS_LOG2=1, CLIP=1, VGRAD=0), dict(P=5, VOXEL_W=8, MAX_SS_LOG2=0, CLIP=0, VGRAD=0),
          dict(P=1, VOXEL_W=8, MAX_SS_LOG2=1, CLIP=1, VGRAD=1), dict(P=5, VOXEL_W=8, MAX_SS_LOG2=0, CLIP=1, VGRAD=1),
          dict(P=8, VOXEL_W=12, MAX_SS_LOG2=1, CLIP=0, VGRAD=1),
          dict(P=1, VOXEL_W=8, MAX_SS_LOG2=1, CLIP=1, VGRAD=0, LABELS=1),
          dict(P=5, VOXEL_W=8, MAX_SS_LOG2=0, CLIP=1, VGRAD=0, LABELS=1),
          dict(P=8, VOXEL_W=12, MAX_SS_LOG2=1, CLIP=0, VGRAD=0, LABELS=1)]


@pytest.mark.parametrize("build", sweep(BUILDS, quick=(), ids=param_id))
def test_cube4_tri(build):
    run_unit(__file__, {**build, "MAX_DIM": 32, "DEPTH": DEPTH, "ADDR_W": ADDR_W}, "test_sample_stream", blocks=("cube4_sim_stall.v",))

"""Whole Cube-4 (rtl/cube4_top.v) against the golden model, bit for bit.

Through ``cube4_sim.rtl.render_frames`` (the same path as ``cube4 render --engine
rtl``): the volume is packed and loaded once, the tables are written through the
load ports before every frame, and frames with different views run back to back
without a reset. Per frame, the finished-ray stream (m, by, bx, R, G, B, A) must
equal the golden model's as a set (the hardware emits a slice's rays in lane
order), and the base plane assembled from it must equal the golden base plane.
Random tables exercise every LUT and reflectance-map entry path; random holds on
every internal stream and a random pixel-port ready check that stalls change
nothing; one frame is reset part way and then rendered cleanly.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from cube4.builds import named
from cube4.config import Cube4Config
from cube4.view import make_traversal
from cube4.app.volumes import load_volume
from cube4_sim.golden_check import assert_frame_matches_golden
from cube4.cycles import frame_cycles
from cube4_sim.rtl import FrameJob, baseplane_from_pixels, render_frames
from cube4_sim.sweeps import regress, sweep

VIEWS = [
    (0.3, -0.45, 1.0), (-0.6, 0.25, -1.0), (1.0, 0.4, -0.7), (-1.0, -0.8, 0.2),
    (0.5, 1.0, 0.5), (-0.2, -1.0, -0.9), (1.0, 1.0, 1.0), (0.0, 0.0, 1.0), (1.0, -1.0, 0.0),
]


def random_tables(rng, cfg: Cube4Config):
    n = 1 << cfg.voxel_bits
    lut = np.empty((n, 4), dtype=np.int64)
    lut[:, :3] = rng.integers(0, 256, size=(n, 3))
    lut[:, 3] = rng.integers(0, 1 << (cfg.alpha_bits - 2), size=n)  # keep rays going for a while
    rmap = rng.integers(0, 1024, size=(cfg.rmap_entries, 2), dtype=np.int64)
    return lut, rmap


check = assert_frame_matches_golden


@pytest.mark.parametrize("p", sweep([1, 4, 5, 8], quick=(0, 2)))
def test_random_volumes_all_views(p):
    rng = np.random.default_rng(p)
    cfg = Cube4Config(pipelines=p)
    dims = (13 + p, 11, 9 + p // 2)
    nx, ny, nz = dims
    vol = rng.integers(0, 256, size=(nz, ny, nx))
    jobs = []
    for n, d in enumerate(VIEWS):
        trav = make_traversal(dims, d, cfg.weight_bits, 1)
        lut, rmap = random_tables(rng, cfg)
        jobs.append(FrameJob(trav, lut, rmap, stall=(0, 60, 0, 120)[n % 4], stall_out=(0, 0, 90, 60)[n % 4],
                             reset_after_cycles=200 if n == 3 else 0))
    results = render_frames(vol, jobs, cfg, max_dim=64)  # share the phantoms' builds
    for n, (job, res) in enumerate(zip(jobs, results)):
        check(vol, job.trav, cfg, job.lut, job.rmap, res, f"P={p} view {VIEWS[n]}")


@pytest.mark.parametrize("p", sweep([5, 8], quick=(0,)))
def test_short_slices(p):
    """Slices of fewer than COM_MIN_SLICE beats (NJ*NB) at P = 5 and 8: COM's read-after-write rule
    makes such a beat wait for the beat one slice back to be written, so the frames stay bit-exact
    (a slice of COM_MIN_SLICE - 1 beats let through reads a word before it is written) and take
    more cycles than the formula, by at most slow_slice_factor; a slice of COM_MIN_SLICE beats
    takes exactly the formula's cycles."""
    from cube4.cycles import COM_MIN_SLICE, slow_slice_factor

    rng = np.random.default_rng(31)
    cfg = Cube4Config(pipelines=p)
    # (dims (x, y, z), view, beats per slice L = NJ * ceil(NI / P), stalls); NI = P: one beat per line
    cases = [((p, 10, 12), (0.2, 0.3, 1.0), COM_MIN_SLICE - 1, False),
             ((12, p, 10), (1.0, 0.3, 0.2), COM_MIN_SLICE - 1, True),
             ((p, 11, 12), (-0.3, 0.2, -1.0), COM_MIN_SLICE, False),
             ((3, 3, 6), (0.2, 0.3, 1.0), 3, False)]
    for dims, view, beats, stall in cases:
        nx, ny, nz = dims
        vol = rng.integers(0, 256, size=(nz, ny, nx))
        trav = make_traversal(dims, view, cfg.weight_bits, 1)
        assert trav.nj * -(-trav.ni // p) == beats, (dims, view, trav.nj, trav.ni)
        lut, rmap = random_tables(rng, cfg)
        job = FrameJob(trav, lut, rmap, stall=60 if stall else 0, stall_out=90 if stall else 0)
        res = render_frames(vol, [job], cfg, max_dim=64)[0]       # the build of the tests above
        label = f"P={p} {dims} view {view}: {beats} beats per slice"
        check(vol, trav, cfg, lut, rmap, res, label)
        if stall:
            continue
        formula = frame_cycles(trav.num_sample_slices, trav.nj, trav.ni, p)
        print(f"{label}: {res['cycles']} cycles, formula {formula}")
        if beats >= COM_MIN_SLICE:
            assert res["cycles"] == formula, (label, res["cycles"], formula)
        else:
            assert formula < res["cycles"] <= formula * slow_slice_factor(trav.nj, trav.ni, p), (label, res["cycles"])


@pytest.mark.parametrize("p", sweep([5, 1], quick=(0,)))
def test_one_beat_slices_supersampled(p):
    """Supersampled slices of one beat (NJ = 1, NI <= P): each sample slice's beat reads the
    slice buffers' slot that the beat before it, one slice back, wrote at the edge of the
    read (TRI's slice buffers are read as a beat is taken, cube4_tri_src); the frames stay
    bit-exact, with stalls too. Without the slice buffers' bypass P = 5, S = 4 fails here
    ("rays differ"; tried)."""
    rng = np.random.default_rng(41 + p)
    cfg = Cube4Config(pipelines=p, supersample=4)   # one build (MAX_SS_LOG2 = 2) for S = 4 and S = 2
    for s, dims, view, stall in [(4, (min(p, 4), 1, 5), (0.2, 0.3, 1.0), False),
                                 (2, (p, 1, 6), (0.2, 0.3, 1.0), False),
                                 (4, (min(p, 4), 1, 5), (0.1, -0.2, 1.0), True)]:
        nx, ny, nz = dims
        vol = rng.integers(0, 256, size=(nz, ny, nx))
        trav = make_traversal(dims, view, cfg.weight_bits, s)
        assert trav.nj * -(-trav.ni // p) == 1, (dims, view, trav.nj, trav.ni)
        lut, rmap = random_tables(rng, cfg)
        job = FrameJob(trav, lut, rmap, stall=60 if stall else 0, stall_out=90 if stall else 0)
        res = render_frames(vol, [job], cfg, max_dim=64)[0]
        check(vol, trav, cfg, lut, rmap, res, f"P={p} S={s} {dims} view {view}: one beat per slice")


@pytest.mark.parametrize("p", sweep([1, 4, 5, 8], quick=(0, 2)))
@pytest.mark.parametrize("name", ["sphere:64", "ml:64", "head:64"])
def test_phantoms(name, p):
    """Sphere, Marschner-Lobb and the head phantom, scene tables, bit-exact base planes."""
    render_phantom(name, p)


@regress
@pytest.mark.parametrize(("name", "p"), [("sphere:128", 8), ("ml:128", 1), ("head:128", 5), ("head:128", 4)])
def test_phantoms_128(name, p):
    """The same at 128^3 (builds with MAX_DIM = 128, four of their own: `make regress`):
    each phantom once, each P once."""
    render_phantom(name, p)


def render_phantom(name: str, p: int) -> None:
    """Render one phantom with its scene's tables through the RTL; check it bit for bit
    against the golden model and its cycle count against the formula."""
    from cube4.host import host_tables, setup_view
    from cube4.scene import load_scene

    cfg = Cube4Config(pipelines=p)
    vol = load_volume(name, voxel_bits=cfg.voxel_bits)
    scene = load_scene("head" if name.startswith("head") else ("ml" if name.startswith("ml") else "default"))
    nz, ny, nx = vol.shape
    trav, _ = setup_view((nx, ny, nz), scene, cfg)
    lut, rmap = host_tables(scene, cfg, trav)
    res = render_frames(vol, [FrameJob(trav, lut, rmap)], cfg)[0]
    check(vol, trav, cfg, lut, rmap, res, name)
    ideal = nx * ny * nz / p
    print(f"{name} P={p}: {res['cycles']} cycles, ideal {ideal:.0f}, efficiency {ideal / res['cycles']:.4f}")
    # the cycles formula of docs/architecture.md (and of the reports), exactly, for an unstalled frame
    assert res["cycles"] == frame_cycles(trav.num_sample_slices, trav.nj, trav.ni, p), res["cycles"]


def test_cli_rtl_baseplane_equals_golden(tmp_path):
    """`cube4 render --engine rtl` writes the golden engine's base plane bit for bit,
    and STATS.json with the cycle and speed figures; with --quiet it prints nothing
    (the Verilator build and simulator output go to build.log / sim.log)."""
    import json
    import subprocess
    import sys

    exe = [sys.executable, "-m", "cube4_sim.cli"]  # what the installed `cube4` runs
    for eng in ("rtl", "golden"):   # the full build at P = 5 that the phantoms' tests build too
        run = subprocess.run([*exe, "render", "sphere:48", "--engine", eng, "--pipelines", "5", "--build", "full",
                              "--quiet", "--baseplane",
                              str(tmp_path / f"{eng}.npy"), "--stats", str(tmp_path / f"{eng}.json"),
                              "--out", str(tmp_path / f"{eng}.png")], check=True, capture_output=True, text=True)
        assert run.stdout == "" and run.stderr == "", (eng, run.stdout[-2000:], run.stderr[-2000:])
    a, b = np.load(tmp_path / "rtl.npy"), np.load(tmp_path / "golden.npy")
    assert a.shape == b.shape and (a == b).all(), "RTL base plane differs from the golden engine's"
    st = json.loads((tmp_path / "rtl.json").read_text())
    for key in ("cycles", "ideal_cycles", "sim_cycles_per_s", "wall_s"):
        assert st[key] and st[key] > 0, key
    # empty-space skipping: the measured cycles are the golden model's prediction for the box,
    # below n^3/P here; the fixed schedule's are above it
    assert st["cycles"] == st["predicted_cycles"] < st["ideal_cycles"] <= st["fixed_schedule_cycles"]


def test_cli_rtl_dram(tmp_path):
    """`cube4 render --engine rtl-dram` (the voxel memory in the simulated DRAM) writes the
    golden engine's base plane bit for bit, and --stats has the DRAM's figures: more cycles
    than the ideal memory's prediction (P = 8 wants twice the DRAM's bandwidth), every burst
    of the frame's box read once at most, bandwidth below the peak."""
    import json
    import subprocess
    import sys

    exe = [sys.executable, "-m", "cube4_sim.cli"]
    for eng in ("rtl-dram", "golden"):   # the full build at P = 8 that test_dram_frames builds too
        subprocess.run([*exe, "render", "sphere:48", "--engine", eng, "--pipelines", "8", "--build", "full",
                        "--quiet", "--baseplane", str(tmp_path / f"{eng}.npy"), "--stats", str(tmp_path / f"{eng}.json"),
                        "--out", str(tmp_path / f"{eng}.png")], check=True, capture_output=True, text=True)
    a, b = np.load(tmp_path / "rtl-dram.npy"), np.load(tmp_path / "golden.npy")
    assert a.shape == b.shape and (a == b).all(), "the DRAM build's base plane differs from the golden engine's"
    d = json.loads((tmp_path / "rtl-dram.json").read_text())["dram"]
    assert d["cycles"] > d["ideal_memory_cycles"] > 0
    assert 0.3 < d["ideal_over_dram"] < 1.0
    assert 0 < d["mb_per_s"] < d["peak_mb_per_s"]
    assert d["bursts_read"] * 16 == d["bytes_read"] and d["refreshes"] > 0


def test_cli_rtl_failed_build_is_one_line(tmp_path):
    """A Verilator build that fails (here: an option Verilator does not know) ends the
    command with one line naming the build log, exit status 2, no traceback, no output."""
    import os
    import subprocess
    import sys

    env = {**os.environ, "CUBE4_VERILATOR_ARGS": "--no-such-verilator-option"}
    out = tmp_path / "x.png"
    run = subprocess.run([sys.executable, "-m", "cube4_sim.cli", "render", "sphere:16", "--engine", "rtl",
                          "--quiet", "--out", str(out)], capture_output=True, text=True, env=env)
    assert run.returncode == 2, run.stderr[-2000:]
    err = run.stderr.strip()
    assert "\n" not in err and "Traceback" not in err, err[-2000:]
    assert "Verilator build failed" in err and "build.log" in err, err
    assert not out.exists()


@pytest.mark.parametrize(("build", "mode", "clip", "shaded", "needs"), [
    ({"CLIP": 0}, "composite", True, False, "CLIP = 1"),
    ({"EXTREMUM": 0}, "mip", False, False, "EXTREMUM = 1"),
    ({"SHADING": 0, "COMPOSITING": 0, "CLIP": 0}, "xray", False, False, "COMPOSITING = 1"),
    ({"SHADING": 0}, "composite", False, True, "SHADING = 1")])
def test_rtl_refuses_a_frame_its_build_lacks(build, mode, clip, shaded, needs):
    """A frame that needs what its build leaves out (a window or cut plane without CLIP, a
    mode without its datapath, shading without GRA) is one clear error before anything
    is built: the RTL would otherwise render it without, silently."""
    from cube4.clip import Clip
    from cube4.errors import UserError

    cfg = Cube4Config(pipelines=1)
    vol = np.full((6, 5, 4), 100)
    trav = make_traversal((4, 5, 6), (0.3, 0.2, 1.0), cfg.weight_bits, 1)
    lut, rmap = random_tables(np.random.default_rng(0), cfg)
    job = FrameJob(trav, lut, rmap if shaded else None, mode=mode,
                   clip=Clip(window=(0, 4, 0, 5, 0, 3)) if clip else None)
    with pytest.raises(UserError, match=needs):
        render_frames(vol, [job], cfg, max_dim=8, build=build)


def test_cli_rtl_several_views_in_one_simulation(tmp_path):
    """`cube4 render --engine rtl --view ... --view ...` renders every view in one
    simulation (volume loaded once) and each base plane equals the golden engine's."""
    import json
    import subprocess
    import sys

    exe = [sys.executable, "-m", "cube4_sim.cli"]  # what the installed `cube4` runs
    views = ["-150,35", "0,90", "75,-10"]  # y-major mixed signs, exactly on the z axis, x-major
    for eng in ("rtl", "golden"):
        args = [*exe, "render", "ml:41", "--scene", "ml", "--engine", eng, "--quiet",
                "--pipelines", "5", "--build", "full",     # the phantoms' P = 5 build
                "--baseplane", str(tmp_path / f"{eng}.npy"), "--stats", str(tmp_path / f"{eng}.json"),
                "--out", str(tmp_path / f"{eng}.png")]
        for v in views:
            args.append(f"--view={v}")
        subprocess.run(args, check=True)
    for n in range(len(views)):
        a, b = np.load(tmp_path / f"rtl_{n:03d}.npy"), np.load(tmp_path / f"golden_{n:03d}.npy")
        assert a.shape == b.shape and (a == b).all(), f"view {views[n]}: RTL base plane differs from golden"
        assert (tmp_path / f"rtl_{n:03d}.png").is_file()
    st = json.loads((tmp_path / "rtl.json").read_text())
    assert st["views"] == len(views) and len(st["frames"]) == len(views)
    assert st["cycles"] == sum(f["cycles"] for f in st["frames"]) > 0
    assert len({f["major_axis"] for f in st["frames"]}) == 3


@pytest.mark.parametrize("p", sweep([1, 3], quick=()))
def test_synthesis_form(p):
    """The RTL as synthesis reads it: the vendor layer's forms (rtl/ecp5/) in place of the
    generic ones, with the behavioural models of the primitives they instantiate
    (sim/hdl/ecp5/). cube4_sdp_ram's ECP5 form stores words deeper than 2048 as 4-, 2- or
    1-bit slices with register copies per two slices; the generic form keeps one
    word-wide memory (Verilator evaluates one wide array much faster than many narrow
    ones). cube4_mul's ECP5 form is a MULT18X18D with its input and output registers
    (TRI's lerps, GRA's view products, SHA's and COM's products). SHA's tables
    (cube4_dual_read_ram) are block RAMs read by two lanes, one through the port that
    writes. Built at P = 1 (COM's slice buffer: 4096 words, 4-bit slices; SHA's one lane
    alone on its tables) and P = 3 (a pair of lanes and a lane alone): a phantom and
    random stalled frames with new tables each must still match the golden model bit
    for bit."""
    from cube4.host import host_tables, setup_view
    from cube4.scene import load_scene

    cfg = Cube4Config(pipelines=p)
    vol = load_volume("sphere:64", voxel_bits=cfg.voxel_bits)
    nz, ny, nx = vol.shape
    trav, _ = setup_view((nx, ny, nz), load_scene("default"), cfg)
    lut, rmap = host_tables(load_scene("default"), cfg, trav)
    rng = np.random.default_rng(11)
    jobs = [FrameJob(trav, lut, rmap)]
    for n, d in enumerate(VIEWS[:3 if p == 1 else 1]):
        t = make_traversal((nx, ny, nz), d, cfg.weight_bits, 1)
        lt, rm = random_tables(rng, cfg)
        jobs.append(FrameJob(t, lt, rm, stall=60, stall_out=90 if (n or p > 1) else 0))
    results = render_frames(vol, jobs, cfg, rtl_form="ecp5")
    for n, (job, res) in enumerate(zip(jobs, results)):
        check(vol, job.trav, cfg, job.lut, job.rmap, res, f"SYNTHESIS RAMs, frame {n}")


# ---------------------------------------------------------------- modes, builds, crop, cut
# named builds (cube4.builds): every mode and crop box on the full build at P = 1 and 5;
# each smaller build a scene would choose once (the shaded one at P = 8 shares its
# Verilator build with the command-line test's ml:41, whose scene needs exactly it).
# make test runs the MIP-only build at P = 5 (P = 1 in make regress); EXTREMUM = 0 runs
# there on the stiff cases' 12-bit build (tb/cube4_stiff) and the voxel-gradient build at P = 1
MODE_RUNS = [("full", 1), ("full", 5), ("unshaded", 5), ("mip", 1), ("mip", 5), ("shaded", 8)]


def mode_frames(rng, cfg: Cube4Config, dims, build: dict) -> list[FrameJob]:
    """Frames for a build: every mode it has, shaded and unshaded compositing, a crop box,
    a cut plane, a window and crop regions (where the build has CLIP), starting phases, stalls, and
    one frame reset in mid-frame; the last frame unstalled (its cycles are checked)."""
    from cube4_sim.unit_bench import random_clip

    nx, ny, nz = dims
    modes = [m for m in ("composite", "xray") if build["COMPOSITING"]]
    modes += [m for m in ("mip", "minip") if build["EXTREMUM"]]
    jobs = []
    for n, d in enumerate(VIEWS[:7]):
        mode = modes[n % len(modes)]
        shaded = bool(build["SHADING"]) and mode == "composite" and n % 2 == 0
        crop = n in (2, 6)    # frame 6 is unstalled: the crop box's cycles are checked
        origin = (2, 1, 1) if crop else (0, 0, 0)
        box = (nx - 4, ny - 3, nz - 2) if crop else dims
        phase = ((37 * n) % 256, (101 * n) % 256)
        trav = make_traversal(box, d, cfg.weight_bits, 1, phase=phase, origin=origin)
        lut, rmap = random_tables(rng, cfg)
        if mode in ("mip", "minip"):
            lut[:, 3] = rng.integers(0, 1 << cfg.alpha_bits, size=lut.shape[0])
        kind = ("cut", "window+regions", "window+cut", "regions", "cut+regions", "window", "regions")[n]
        clip = random_clip(trav, kind, rng) if build["CLIP"] else None
        jobs.append(FrameJob(trav, lut, rmap if shaded else None, mode=mode, clip=clip,
                             stall=(0, 60, 0, 120, 30, 0, 0)[n], stall_out=(0, 0, 90, 60, 0, 40, 0)[n],
                             reset_after_cycles=150 if n == 3 else 0))
    return jobs


@pytest.mark.parametrize(("name", "p"), sweep(MODE_RUNS, quick=(0, 1, 4), ids=lambda r: f"{r[0]}-{r[1]}"))
def test_modes_builds_crop_cut(name, p):
    """Every mode of a build, crop boxes, cut planes, windows and crop regions, bit-exact, with random
    stalls and a reset in mid-frame; the cycles of unstalled frames against the formula
    (a crop box: the box's dims)."""
    rng = np.random.default_rng(100 + p)
    cfg = Cube4Config(pipelines=p)
    build = named(name)
    dims = (12 + p, 11, 10)
    nx, ny, nz = dims
    vol = rng.integers(1, 256, size=(nz, ny, nx))    # no zero: MinIP sees the volume, not the air
    jobs = mode_frames(rng, cfg, dims, build)
    results = render_frames(vol, jobs, cfg, max_dim=64, build=build)
    for n, (job, res) in enumerate(zip(jobs, results)):
        label = f"{name} P={p} view {n} {job.mode} box {job.trav.origin}+{job.trav.dims}"
        check(vol, job.trav, cfg, job.lut, job.rmap, res, label, mode=job.mode, clip=job.clip)
        if not (job.stall or job.stall_out or job.reset_after_cycles):
            t = job.trav
            want = frame_cycles(t.num_sample_slices, t.nj, t.ni, p, bool(build["SHADING"]))
            assert res["cycles"] == want, (label, res["cycles"], want)


# ---------------------------------------------------------------- empty-space skipping
SKIP_VIEWS = [(1.0, 1.0, 1.0), (1.0, -1.0, 0.0), (0.3, -0.45, 1.0), (-0.6, 0.25, -1.0), (-0.2, -1.0, -0.9)]


def skip_frames(rng, cfg: Cube4Config, vol: np.ndarray):
    """One frame per view with the box schedule of cube4.skip: composite (shaded and not),
    X-ray, MIP, MinIP; stalls on three, a reset in mid-frame on one, the others unstalled.
    Returns (jobs, plans)."""
    from cube4.skip import plan_skip

    nz, ny, nx = vol.shape
    jobs, plans = [], []
    for n, d in enumerate(SKIP_VIEWS):
        mode = ("composite", "xray", "mip", "minip", "composite")[n]
        trav = make_traversal((nx, ny, nz), d, cfg.weight_bits, 1)
        lut, rmap = random_tables(rng, cfg)
        if mode == "minip":
            lut[50:] = 0         # values below the faint voxels count
        else:
            lut[:150] = 0        # the faint voxels are empty space
        if n == 4:
            lut[:200] = 0       # only the densest voxels count: a small box, grown to a full-rate slice
        plan = plan_skip(vol, trav, lut, mode, p=cfg.pipelines)
        assert plan.fraction < 0.6, (d, plan.box)
        jobs.append(FrameJob(plan.trav, lut, rmap if n in (0, 4) else None, mode=mode, clip=plan.clip,
                             stall=(0, 60, 0, 120, 0)[n], stall_out=(0, 0, 90, 60, 0)[n],
                             reset_after_cycles=150 if n == 1 else 0))
        plans.append(plan)
    return jobs, plans


@pytest.mark.parametrize("p", sweep([1, 5, 8], quick=(0, 1)))
def test_skip_schedule(p):
    """Empty-space skipping through the RTL: each frame traverses only its box (in the one
    memory image of the whole volume); its rays are the golden model's box frame bit for bit,
    its base plane placed in the whole equals the golden fixed schedule's, with random
    stalls and a reset in mid-frame; unstalled frames take exactly the predicted cycles."""
    from cube4.model import render_frame

    rng = np.random.default_rng(200 + p)
    cfg = Cube4Config(pipelines=p)
    nx, ny, nz = 21, 18, 20
    vol = rng.integers(50, 150, size=(nz, ny, nx))           # faint: empty for the tables below
    vol[5:12, 9:15, 4:13] = rng.integers(0, 200, size=(7, 6, 9))   # one dense block
    vol[8, 11, 7] = 230                                          # and one voxel denser still
    jobs, plans = skip_frames(rng, cfg, vol)
    results = render_frames(vol, jobs, cfg, max_dim=64)      # the full build of the tests above
    for n, (job, plan, res) in enumerate(zip(jobs, plans, results)):
        label = f"skip P={p} view {SKIP_VIEWS[n]} {job.mode} box {plan.box}"
        check(vol, job.trav, cfg, job.lut, job.rmap, res, label, mode=job.mode, clip=job.clip)
        full = render_frame(vol, plan.whole, cfg, job.lut, job.rmap, mode=job.mode, shading=job.rmap is not None)
        placed = plan.place(baseplane_from_pixels(res["pixels"], job.trav.baseplane_shape))
        assert (placed == full.baseplane).all(), f"{label}: differs from the fixed schedule"
        if not (job.stall or job.stall_out or job.reset_after_cycles):
            assert res["cycles"] == plan.cycles(p, True), (label, res["cycles"], plan.cycles(p, True))


# ---------------------------------------------------------------- slice rectangles
@pytest.mark.parametrize("p, shading", sweep([(1, 1), (5, 1), (8, 1), (5, 0)], quick=(1,)))
def test_slice_rectangles(p, shading):
    """Slice rectangles through the RTL (RECTS = 1): each frame runs the rectangles the
    host plans within its box (cube4.slices.plan_rects; GRA's walk on a build with GRA);
    its rays are the golden model's rectangle frame bit for bit, and its base plane placed
    in the whole equals the golden fixed schedule's, with random stalls and a reset in
    mid-frame; unstalled frames take exactly the predicted cycles
    (cube4.cycles.rect_frame_cycles) where no beat waits in COM (SliceRects.com_waits;
    otherwise at least those), and the fixed schedule runs as a whole-box table too.
    Builds: with GRA at P = 1, 5, 8, and without shading at P = 5 (make test: with GRA at
    P = 5)."""
    from cube4.model import render_frame
    from cube4.cycles import rect_frame_cycles
    from cube4.slices import plan_rects
    from cube4_sim.rtl import frame_rects

    rng = np.random.default_rng(300 + p)
    cfg = Cube4Config(pipelines=p)
    nx, ny, nz = 21, 18, 20
    vol = rng.integers(50, 150, size=(nz, ny, nx))
    vol[5:12, 9:15, 4:13] = rng.integers(0, 200, size=(7, 6, 9))
    vol[8, 11, 7] = 230
    jobs, plans = skip_frames(rng, cfg, vol)
    for job, plan in zip(jobs, plans):
        if not shading:
            job.rmap = None
        job.rects = plan_rects(plan.box_volume(vol), plan.trav, job.lut, job.mode, gra=job.rmap is not None,
                               clip=plan.clip)
    first = jobs[0]
    jobs.append(FrameJob(plans[0].whole, first.lut, first.rmap, mode=first.mode))   # the whole box, as a table
    plans.append(None)
    build = {"RECTS": 1, "SHADING": shading}
    results = render_frames(vol, jobs, cfg, max_dim=64, build=build)
    exact = 0
    for n, (job, plan, res) in enumerate(zip(jobs, plans, results)):
        label = f"rects P={p} view {n} {job.mode}"
        check(vol, job.trav, cfg, job.lut, job.rmap, res, label, mode=job.mode, clip=job.clip,
              rects=job.rects)
        if plan is not None:
            full = render_frame(vol, plan.whole, cfg, job.lut, job.rmap, mode=job.mode, shading=job.rmap is not None)
            placed = plan.place(baseplane_from_pixels(res["pixels"], job.trav.baseplane_shape))
            assert (placed == full.baseplane).all(), f"{label}: differs from the fixed schedule"
        if not (job.stall or job.stall_out or job.reset_after_cycles):
            rects = frame_rects(job, bool(shading))
            want = rect_frame_cycles(rects, p, bool(shading))
            if rects.com_waits(p) == 0:
                assert res["cycles"] == want, (label, res["cycles"], want)
                exact += 1
            else:
                assert res["cycles"] >= want, (label, res["cycles"], want)
    assert exact >= 2, f"only {exact} frames had their cycles checked exactly"


# ---------------------------------------------------------------- voxel gradients
# (P, S, estimator, build: SHADING, COMPOSITING, EXTREMUM, CLIP, VGRAD)
VGRAD_RUNS = [(1, 1, "sobel", (1, 1, 0, 0, 1)), (5, 1, "central", (1, 1, 1, 1, 1)), (8, 2, "central", (1, 1, 1, 1, 1))]


@pytest.mark.parametrize(("p", "s", "kind", "bits"), sweep(VGRAD_RUNS, quick=(0, 1), ids=lambda r: f"p{r[0]}-s{r[1]}-{r[2]}"))
def test_voxel_gradients(p, s, kind, bits):
    """Voxel gradients (VGRAD = 1, numerics.md §5b): the memory holds each voxel with its
    gradient (cube4.vgrad), TRI interpolates all four channels and SHA shades with them.
    Shaded frames at seven views ((1, 1, 1) and a 45° view among them), one unshaded frame
    (the identity map on this build), a crop box, a cut plane, random stalls and a reset in
    mid-frame, bit for bit against the golden model; unstalled frames take the predicted
    cycles."""
    from cube4.vgrad import pack_words
    from cube4_sim.unit_bench import random_clip

    rng = np.random.default_rng(300 + p)
    cfg = Cube4Config(pipelines=p, supersample=s)
    build = dict(zip(("SHADING", "COMPOSITING", "EXTREMUM", "CLIP", "VGRAD"), bits))
    dims = (12 + p, 11, 10)
    nx, ny, nz = dims
    vol = rng.integers(0, 256, size=(nz, ny, nx))
    words = pack_words(vol, kind, cfg.voxel_bits)
    jobs = []
    for n, d in enumerate(VIEWS[:7] + [(1.0, -1.0, 0.0)]):
        crop = n == 2
        origin = (2, 1, 1) if crop else (0, 0, 0)
        box = (nx - 4, ny - 3, nz - 2) if crop else dims
        trav = make_traversal(box, d, cfg.weight_bits, s, origin=origin)
        lut, rmap = random_tables(rng, cfg)
        clip = random_clip(trav, "cut", rng) if build["CLIP"] and n == 5 else None
        jobs.append(FrameJob(trav, lut, None if n == 4 else rmap, clip=clip,
                             stall=(0, 60, 0, 120, 30, 0, 0, 0)[n], stall_out=(0, 0, 90, 60, 0, 40, 0, 0)[n],
                             reset_after_cycles=150 if n == 3 else 0))
    results = render_frames(words, jobs, cfg, max_dim=64, build=build)
    for n, (job, res) in enumerate(zip(jobs, results)):
        label = f"voxel gradients ({kind}) P={p} S={s} view {n} box {job.trav.origin}+{job.trav.dims}"
        check(words, job.trav, cfg, job.lut, job.rmap, res, label, clip=job.clip, vgrad=True)
        if not (job.stall or job.stall_out or job.reset_after_cycles):
            t = job.trav
            want = frame_cycles(t.num_sample_slices, t.nj, t.ni, p, True, True)
            assert res["cycles"] == want, (label, res["cycles"], want)


# ---------------------------------------------------------------- q x q sub-pixel passes
@pytest.mark.parametrize(("p", "q"), sweep([(1, 2), (5, 3), (8, 2)], quick=(0, 1)))
def test_subpixel_passes(p, q):
    """Base-plane supersampling: the q×q passes of a view (template phases a/q, b/q, each
    with its empty-space box) run back to back in one simulation on the volume loaded
    once, with random stalls on some; every pass is the golden model's frame bit for bit,
    and the interleaved plane equals the golden engine's."""
    from cube4.app.render import render
    from cube4.host import assemble_view, plan_view
    from cube4.scene import load_scene

    cfg = Cube4Config(pipelines=p)
    vol = load_volume("head:24", voxel_bits=cfg.voxel_bits)
    scene = dataclasses.replace(load_scene("head"), subpixel=q)
    vp = plan_view(vol, scene, cfg)
    jobs, index = [], []
    for n, plan in enumerate(vp.plans):
        if plan.trav is not None:
            jobs.append(FrameJob(plan.trav, vp.lut, vp.rmap, clip=plan.clip, stall=(0, 60, 0, 120)[n % 4],
                                 stall_out=(0, 0, 90, 0)[n % 4]))
            index.append(n)     # the pass it renders
    assert len(jobs) == q * q
    results = render_frames(vol, jobs, cfg, max_dim=64)
    for job, res in zip(jobs, results):
        check(vol, job.trav, cfg, job.lut, job.rmap, res, f"P={p} q={q} phase {job.trav.phase_x, job.trav.phase_y}")
    runs = {n: (baseplane_from_pixels(res["pixels"], job.trav.baseplane_shape), res["pixels"])
            for n, job, res in zip(index, jobs, results)}
    frame = assemble_view(vp, cfg, runs)
    gold = render(vol, scene, cfg, "golden").frame
    assert (frame.baseplane == gold.baseplane).all(), "interleaved plane differs from the golden engine's"


@pytest.mark.parametrize(("p", "q"), sweep([(8, 2), (5, 3)], quick=(0,)))
def test_subpixel_beats(p, q):
    """The q×q passes of a view on the beat schedule (BEATS = 1) at S = 4: each pass its
    own beat frame (its box's block occupancy and rays' stops), the head phantom's shaded
    scene with its LUT made opaque where it counts, so rays end (τ = 0); random stalls on some
    passes and a reset in mid-frame on one. Every pass is the golden beat frame bit for
    bit, the beats that ran are the golden frame's, some ray ended early, and the
    interleaved plane equals the fixed schedule's."""
    import copy

    from cube4.host import assemble_view, beat_schedules, crop_volume, plan_view
    from cube4.model import render_frame
    from cube4.scene import load_scene

    cfg = Cube4Config(pipelines=p, supersample=4)
    vol = load_volume("head:24", voxel_bits=cfg.voxel_bits)
    vp = plan_view(vol, dataclasses.replace(load_scene("head"), subpixel=q, skip="beats", supersample=4), cfg)
    lut = vp.lut.copy()
    lut[lut[:, 3] > 0, 3] = (1 << cfg.alpha_bits) - 1
    vp = dataclasses.replace(vp, lut=lut)
    jobs, gold, index = [], [], []
    for n, (plan, bf) in enumerate(zip(vp.plans, beat_schedules(vol, vp, cfg, {"tau": 0, "terminate": True}))):
        if plan.trav is None:
            continue
        sched, rule = bf
        assert rule.enabled, "the head's passes are tall enough to end rays"
        jobs.append(FrameJob(plan.trav, vp.lut, vp.rmap, clip=plan.clip, beats=(copy.deepcopy(sched), rule, sched.block_bits),
                             stall=(0, 60, 0, 120)[n % 4], stall_out=(0, 0, 90, 0)[n % 4],
                             reset_after_cycles=400 if n == 1 else 0))
        gold.append((sched, rule))
        index.append(n)
    assert len(jobs) == q * q
    # the build of test_beat_frames_shaded (modulation and slab in it, off in these frames): one build for both
    results = render_frames(vol, jobs, cfg, max_dim=32, build={"BEATS": 1, "SHADING": 1, "VGRAD": 0, "GMOD": 1, "SLAB": 1})
    ended = 0
    for job, (sched, rule), res in zip(jobs, gold, results):
        label = f"beats P={p} S=4 q={q} phase {job.trav.phase_x, job.trav.phase_y}"
        check(vol, job.trav, cfg, job.lut, job.rmap, res, label, clip=job.clip, beats=(sched, rule))
        ran = copy.deepcopy(sched)
        render_frame(crop_volume(vol, job.trav), job.trav, cfg, job.lut, job.rmap, clip=job.clip, beats=ran, done=rule)
        run = sum(int(ran.run_beats(m).sum()) for m in range(ran.M))
        assert res["beats_run"] == run, f"{label}: {res['beats_run']} beats ran on the RTL, golden {run}"
        ended += int((ran.done < ran.M).sum())
    assert ended > 0, "no ray ended early: the test would not see termination"
    runs = {n: (baseplane_from_pixels(res["pixels"], job.trav.baseplane_shape), res["pixels"])
            for n, job, res in zip(index, jobs, results)}
    fixed = {}
    for n, job in zip(index, jobs):
        f = render_frame(crop_volume(vol, job.trav), job.trav, cfg, vp.lut, vp.rmap, clip=job.clip)
        fixed[n] = (f.baseplane, f.pixels)
    a, b = assemble_view(vp, cfg, runs), assemble_view(vp, cfg, fixed)
    assert (a.baseplane == b.baseplane).all(), "the beat schedule's interleaved plane differs from the fixed schedule's"


# ---------------------------------------------------------------- path-length weights
@pytest.mark.parametrize(("p", "s"), sweep([(1, 1), (5, 1), (8, 1), (5, 2)], quick=(0, 1)))
def test_path_weights(p, s):
    """Path-length weights (PLW, numerics.md §17): the LUT's path-weight columns are written
    through the load port with the LUT, and COM weights the first and last samples of the
    rays that enter or leave through the faces in FACES. Composite frames at six views
    ((1, 1, 1) and a 45° view among them), an X-ray frame, a MIP frame (never weighted), a
    crop box, two boxes inside the volume with interior faces (FACES from sub_traversal),
    random stalls and a reset in mid-frame, bit for bit against the golden model;
    unstalled frames take the predicted cycles (the weights add none)."""
    from cube4.pathlen import weighted_columns
    from cube4.view import sub_traversal

    rng = np.random.default_rng(400 + p)
    cfg = Cube4Config(pipelines=p, supersample=s)
    dims = (12 + p, 11, 10)
    nx, ny, nz = dims
    vol = rng.integers(0, 256, size=(nz, ny, nx))
    views = [VIEWS[0], VIEWS[1], (1.0, 1.0, 1.0), (1.0, -1.0, 0.0), VIEWS[2], VIEWS[4], VIEWS[5], VIEWS[3],
             (-0.7, 0.6, 1.0)]
    modes = ["composite"] * 6 + ["xray", "mip", "composite"]
    jobs = []
    for n, (d, mode) in enumerate(zip(views, modes)):
        trav = make_traversal(dims, d, cfg.weight_bits, s)
        if n == 2:        # a crop box: a volume of its own, all six faces its own
            trav = make_traversal((nx - 4, ny - 3, nz - 2), d, cfg.weight_bits, s, origin=(2, 1, 1))
        elif n in (4, 8):  # boxes inside the traversal: some faces interior
            s0, s1 = ((1, 0, 2), (nx, ny - 2, nz)) if n == 4 else ((0, 2, 0), (nx - 3, ny, nz - 3))
            trav, _, _ = sub_traversal(trav, s0, s1)
            assert 0 < trav.faces < 63
        lut, rmap = random_tables(rng, cfg)
        lut[:, 3] = rng.integers(0, 1 << cfg.alpha_bits, size=lut.shape[0])  # opaque too: columns differ most
        lut = np.concatenate([lut, weighted_columns(lut[:, 3], cfg.alpha_bits)], axis=1)
        jobs.append(FrameJob(trav, lut, rmap if mode == "composite" else None, mode=mode,
                             stall=(0, 60, 0, 120, 30, 0, 0, 0, 0)[n], stall_out=(0, 0, 90, 60, 0, 40, 0, 0, 0)[n],
                             reset_after_cycles=150 if n == 3 else 0))
    results = render_frames(vol, jobs, cfg, max_dim=64)
    for n, (job, res) in enumerate(zip(jobs, results)):
        label = f"path weights P={p} S={s} view {views[n]} {job.mode} faces {job.trav.faces:06b}"
        gold = check(vol, job.trav, cfg, job.lut, job.rmap, res, label, mode=job.mode)
        if n == 0:   # the weights change this frame: the test sees them
            from cube4.model import render_frame
            from cube4.host import crop_volume
            unweighted = render_frame(crop_volume(vol, job.trav), job.trav, cfg, job.lut[:, :4], job.rmap)
            assert (unweighted.baseplane != gold.baseplane).any(), f"{label}: the weights changed nothing"
        if not (job.stall or job.stall_out or job.reset_after_cycles):
            t = job.trav
            want = frame_cycles(t.num_sample_slices, t.nj, t.ni, p, True, False)
            assert res["cycles"] == want, (label, res["cycles"], want)


@pytest.mark.parametrize("p", [1, 5])
def test_preview_level_frames(p):
    """A preview level (cube4.levels, [render] preview = 2) through the full build: the
    host's level in memory, its frames at three views (45° and (1, 1, 1) among them)
    bit-exact against the golden model with random stalls and a reset in mid-frame, and
    the unstalled frame's cycles those of the level's box (the builds the mode tests use)."""
    from cube4.host import build_memory, level_of, plan_view
    from cube4.scene import load_scene, with_view

    vol = load_volume("head:40")
    cfg = Cube4Config(pipelines=p)
    build = named("full")
    jobs, scenes = [], []
    for n, d in enumerate([(1.0, 1.0, 1.0), (1.0, -1.0, 0.0), (0.3, -0.45, 1.0)]):
        sc = dataclasses.replace(with_view(load_scene("head"), d), preview=2)
        vp = plan_view(vol, sc, cfg)
        (ps, plan), = vp.jobs()
        jobs.append(FrameJob(plan.trav, vp.lut, vp.rmap, mode=sc.mode, clip=plan.clip,
                             stall=(40, 0, 0)[n], stall_out=(0, 70, 0)[n], reset_after_cycles=(0, 120, 0)[n]))
        scenes.append(sc)
    mem = build_memory(vol, scenes, cfg, build)
    assert mem.shape == (20, 20, 20)
    results = render_frames(mem, jobs, cfg, max_dim=64, build=build)
    level = level_of(vol, scenes[0])
    for n, (job, res) in enumerate(zip(jobs, results)):
        check(level, job.trav, cfg, job.lut, job.rmap, res, f"preview P={p} view {n}", mode=job.mode, clip=job.clip)
    t = jobs[2].trav
    assert results[2]["cycles"] == frame_cycles(t.num_sample_slices, t.nj, t.ni, p, True)


# ---------------------------------------------------------------- the cut slab
SLAB_VIEWS = [(1.0, -1.0, 0.0), (1.0, 1.0, 1.0), (0.3, -0.45, 1.0), (-0.6, 0.25, -1.0), (-0.2, -1.0, -0.9),
              (1.0, 0.4, -0.7)]


@pytest.mark.parametrize(("p", "s", "shading"), sweep([(1, 1, 0), (5, 2, 1), (8, 1, 1), (5, 1, 0)], quick=(1,)))
def test_slab_frames(p, s, shading):
    """The cut slab (SLAB = 1, numerics.md §12) on the feature build (DEPTH_BUILD: the full build with
    SLAB, ZOUT, ZIN and GMOD; or the slab's unshaded
    build): the far face in CLIP, the falloff weights in SHA, COM's multiply after the path
    weights. Six views (45° and (1, 1, 1) among them): composite (shaded where the build
    shades), X-ray, MIP (the slab bounds the samples, no falloff), a path-weighted frame
    with a hard slab, the box schedule of cube4.skip (cells beyond either face are not
    traversed), random stalls and a reset in mid-frame, bit for bit against the golden
    model; unstalled frames take the predicted cycles (an unshaded SHA is longer by the
    falloff unit), and the falloff changes the picture (the test sees it)."""
    from cube4.builds import complete_build
    from cube4.clip import Clip, slab_coefficients
    from cube4.cycles import has_falloff, has_gmod
    from cube4.host import crop_volume
    from cube4.model import render_frame
    from cube4.pathlen import weighted_columns
    from cube4.skip import plan_skip

    rng = np.random.default_rng(500 + p)
    cfg = Cube4Config(pipelines=p, supersample=s)
    build = DEPTH_BUILD if shading else {"SLAB": 1, "SHADING": 0}   # shaded: the feature build (depth too)
    depth_t = (1 << cfg.acc_bits) // 3 if shading else None
    dims = (12 + p, 11, 10)
    nx, ny, nz = dims
    vol = rng.integers(0, 256, size=(nz, ny, nx))
    modes = ["composite", "composite", "xray", "mip", "composite", "composite"]
    slabs = [(5.0, 2.0), (3.0, 1.5), (6.0, 1.0), (4.0, 1.0), (4.0, 0.0), (3.0, 1.0)]
    normals = [(0.5, -0.8, 0.3), (0.0, 0.0, 1.0), (1.0, 0.2, -0.4), (-0.3, 1.0, 0.5), (0.6, 0.6, -0.5),
               (0.1, 0.0, 1.0)]
    centre = ((nx - 1) / 2, (ny - 1) / 2, (nz - 1) / 2)
    jobs = []
    for n, (d, mode) in enumerate(zip(SLAB_VIEWS, modes)):
        trav = make_traversal(dims, d, cfg.weight_bits, s)
        plane, slab = slab_coefficients(trav, normals[n], centre, *slabs[n])
        clip = Clip(plane=plane, slab=slab)
        lut, rmap = random_tables(rng, cfg)
        lut[:, 3] = rng.integers(0, 1 << cfg.alpha_bits, size=lut.shape[0])   # opaque too
        if n == 4 and complete_build(build)["PLW"]:       # path weights with a hard slab
            lut = np.concatenate([lut, weighted_columns(lut[:, 3], cfg.alpha_bits)], axis=1)
        if n == 5:       # the box schedule: cells beyond either face are not traversed
            lut[:60] = 0
            plan = plan_skip(vol, trav, lut, mode, clip=clip, p=p)
            assert plan.box is not None and plan.fraction < 1.0, plan.box
            trav, clip = plan.trav, plan.clip
        shaded = bool(shading) and mode == "composite" and n in (0, 4, 5)
        jobs.append(FrameJob(trav, lut, rmap if shaded else None, mode=mode, clip=clip, depth_t=depth_t,
                             stall=(0, 60, 0, 120, 30, 0)[n], stall_out=(0, 0, 90, 60, 0, 0)[n],
                             reset_after_cycles=150 if n == 3 else 0))
    results = render_frames(vol, jobs, cfg, max_dim=64, build=build)
    fall = has_falloff({"COMPOSITING": 1, **build})
    for n, (job, res) in enumerate(zip(jobs, results)):
        label = f"slab P={p} S={s} view {SLAB_VIEWS[n]} {job.mode} slab {job.clip.slab}"
        gold = check(vol, job.trav, cfg, job.lut, job.rmap, res, label, mode=job.mode, clip=job.clip,
                     depth_t=job.depth_t)
        if n == 0:   # the falloff changes this frame: the test sees it
            hard = Clip(plane=job.clip.plane, slab=(job.clip.slab[0], 0, 0))
            other = render_frame(crop_volume(vol, job.trav), job.trav, cfg, job.lut, job.rmap, mode=job.mode,
                                 shading=job.rmap is not None, clip=hard)
            assert (other.baseplane != gold.baseplane).any(), f"{label}: the falloff changed nothing"
        if not (job.stall or job.stall_out or job.reset_after_cycles):
            t = job.trav
            want = frame_cycles(t.num_sample_slices, t.nj, t.ni, p, bool(shading), False, fall,
                                has_gmod({"SHADING": shading, **build}))
            assert res["cycles"] == want, (label, res["cycles"], want)


# ---------------------------------------------------------------- depth out and in
# one build for depth out, depth in, gradient-magnitude modulation, label volumes and the
# shaded slab frames (each frame without geometry loads a table that stops no ray, each
# without modulation the identity table, each without labels reads label 0's block; the
# modulation's two SHA stages are in every frame's cycles; a frame without a slab has its
# falloff off; labels need PLW = 0: the path-weighted slab frame runs on the unshaded build)
DEPTH_BUILD = {"ZOUT": 1, "ZIN": 1, "GMOD": 1, "SLAB": 1, "LABELS": 1, "PLW": 0}


# the depth tests' six frames: (view, mode), a crop box at 2, the box schedule at 5
DEPTH_VIEWS = [((1.0, -1.0, 0.0), "composite"), ((1.0, 1.0, 1.0), "composite"), ((0.3, -0.45, 1.0), "xray"),
               ((-0.6, 0.25, -1.0), "mip"), ((-0.2, -1.0, -0.9), "minip"), ((1.0, 0.4, -0.7), "composite")]
DEPTH_STALLS = ((0, 60, 0, 120, 30, 0), (0, 0, 90, 60, 0, 0))     # per frame: stall, stall_out


def depth_frames(p: int, s: int, seed: int, alpha_bits_less: int):
    """The depth tests' volume (empty space at three faces, for the box schedule's frame)
    and per frame of DEPTH_VIEWS: (view, mode, traversal, the whole frame's traversal,
    LUT, reflectance map or None, clip, skip plan or None). Frame 2 traverses a crop
    box, frame 5 the empty-space box of a LUT clear below 80; frames 0 and 5 are shaded;
    the LUT's opacities stay below 2^(ALPHA_W - alpha_bits_less)."""
    from cube4.skip import plan_skip

    rng = np.random.default_rng(seed)
    cfg = Cube4Config(pipelines=p, supersample=s)
    dims = (12 + p, 11, 10)
    nx, ny, nz = dims
    vol = rng.integers(0, 256, size=(nz, ny, nx))
    vol[:2], vol[:, :2], vol[:, :, -3:] = 0, 0, 0
    frames = []
    for n, (d, mode) in enumerate(DEPTH_VIEWS):
        if n == 2:
            trav = make_traversal((nx - 4, ny - 3, nz - 2), d, cfg.weight_bits, s, origin=(2, 1, 1))
        else:
            trav = make_traversal(dims, d, cfg.weight_bits, s)
        lut, rmap = random_tables(rng, cfg)
        lut[:, 3] = rng.integers(0, 1 << (cfg.alpha_bits - alpha_bits_less), size=lut.shape[0])
        whole, clip, plan = trav, None, None
        if n == 5:      # the box's slices and base plane moved to the whole frame's
            lut[:80] = 0
            plan = plan_skip(vol, trav, lut, mode, p=p)
            assert plan.box is not None and plan.fraction < 1.0, plan.box
            trav, clip = plan.trav, plan.clip
        frames.append((d, mode, trav, whole, lut, rmap if n in (0, 5) else None, clip, plan))
    return cfg, vol, frames, rng


@pytest.mark.parametrize(("p", "s"), sweep([(1, 1), (5, 2), (8, 1)], quick=(0, 1)))
def test_depth_out_frames(p, s):
    """Depth out (ZOUT = 1, numerics.md §21): every finished ray carries the slice where its
    transmittance first reached DEPTH_T and the slice of its first sample that added
    something (MIP / MinIP: its held and its first counted sample), bit for bit against the
    golden model: composite (shaded and not), X-ray, MIP, MinIP, a crop box and the box
    schedule (slices of the whole frame), six views with 45° and (1, 1, 1), random stalls
    and a reset in mid-frame; the depths are not all equal (the test sees them), and the
    unstalled frames take the predicted cycles (of this build: cycles.GM_EXTRA with it)."""
    cfg, vol, frames, _ = depth_frames(p, s, 600 + p, 1)
    one = 1 << cfg.acc_bits
    thresholds = [one // 2, one // 10, one // 4, 0, 0, one * 3 // 4]
    jobs = [FrameJob(trav, lut, rmap, mode=mode, clip=clip, depth_t=thresholds[n], stall=DEPTH_STALLS[0][n],
                     stall_out=DEPTH_STALLS[1][n], reset_after_cycles=150 if n == 3 else 0)
            for n, (_, mode, trav, _, lut, rmap, clip, _) in enumerate(frames)]
    results = render_frames(vol, jobs, cfg, max_dim=64, build=DEPTH_BUILD)
    for n, (job, res) in enumerate(zip(jobs, results)):
        label = f"depth out P={p} S={s} view {frames[n][0]} {job.mode} DEPTH_T {job.depth_t}"
        check(vol, job.trav, cfg, job.lut, job.rmap, res, label, mode=job.mode, clip=job.clip, depth_t=job.depth_t)
        px = res["pixels"]
        assert (px["zp"] >= 0).any() and (px["zf"] >= 0).any(), label
        assert len(np.unique(px["zf"][px["zf"] >= 0])) > 1, label
        if not (job.stall or job.stall_out or job.reset_after_cycles):
            t = job.trav
            assert res["cycles"] == frame_cycles(t.num_sample_slices, t.nj, t.ni, p, True, gm=True), label


@pytest.mark.parametrize(("p", "s"), sweep([(1, 1), (5, 2), (8, 1)], quick=(0, 1)))
def test_depth_in_frames(p, s):
    """Depth in (ZIN = 1, numerics.md §22): each frame's stop table (a tilted surface with
    a step and a hole, so that rays stop at many slices, at 0 and never) through the stop_*
    port; every finished ray and the base plane bit for bit against the golden model with
    the same stop slices: composite (shaded and not), X-ray, MIP, MinIP, a crop box and the
    box schedule (the whole frame's table cut to the box, ``SkipPlan.box_stop``), six views
    with 45° and (1, 1, 1), random stalls and a reset in mid-frame, depth out alongside; the
    stops change every frame's picture (the test sees them), and the unstalled frames take
    the cycles the golden model predicts (those of the schedule: depth in ends no traversal)."""
    from cube4.host import crop_volume
    from cube4.model import render_frame
    from cube4.modes import is_blend

    cfg, vol, frames, rng = depth_frames(p, s, 700 + p, 2)
    one = 1 << cfg.acc_bits
    jobs = []
    for n, (_, mode, trav, whole, lut, rmap, clip, plan) in enumerate(frames):
        stop = surface_stops(whole, rng)
        if plan is not None:       # the whole frame's table cut to the box
            stop = plan.box_stop(stop)
        jobs.append(FrameJob(trav, lut, rmap, mode=mode, clip=clip, stop_m=stop,
                             depth_t=one // 3 if is_blend(mode) else 0, stall=DEPTH_STALLS[0][n],
                             stall_out=DEPTH_STALLS[1][n], reset_after_cycles=150 if n == 3 else 0))
    results = render_frames(vol, jobs, cfg, max_dim=64, build=DEPTH_BUILD)
    for n, (job, res) in enumerate(zip(jobs, results)):
        label = f"depth in P={p} S={s} view {frames[n][0]} {job.mode}"
        gold = check(vol, job.trav, cfg, job.lut, job.rmap, res, label, mode=job.mode, clip=job.clip,
                     depth_t=job.depth_t, stop_m=job.stop_m)
        free = render_frame(crop_volume(vol, job.trav), job.trav, cfg, job.lut, job.rmap, mode=job.mode,
                            shading=job.rmap is not None, clip=job.clip)
        assert (free.baseplane != gold.baseplane).any(), f"{label}: the stop slices changed nothing"
        if not (job.stall or job.stall_out or job.reset_after_cycles):
            t = job.trav
            assert res["cycles"] == frame_cycles(t.num_sample_slices, t.nj, t.ni, p, True, gm=True), label


def surface_stops(trav, rng) -> np.ndarray:
    """(rows, cols) stop slices of a tilted surface through the middle of the frame with a
    step along the columns and a hole (rays that never stop), a row that stops at once and
    a little noise: rays end at many different slices."""
    rows, cols = trav.baseplane_shape
    M = trav.num_sample_slices
    by, bx = np.mgrid[0:rows, 0:cols]
    z = M * (0.35 + 0.3 * by / max(rows - 1, 1)) + np.where(bx > cols // 2, M // 5, 0)
    z = z + rng.integers(-1, 2, size=z.shape)
    stop = np.clip(np.round(z), 0, M).astype(np.int64)
    stop[rows // 3:rows // 2, cols // 4:cols // 2] = M      # a hole: no geometry
    stop[-1] = 0                                             # geometry in front of the volume
    return stop


# ---------------------------------------------------------------- gradient-magnitude modulation
# (P, S, voxel gradients): make test P = 1 and 5 (S = 2) with GRA, make regress P = 8 with Sobel
GM_RUNS = [(1, 1, None), (5, 2, None), (8, 1, "sobel")]


@pytest.mark.parametrize(("p", "s", "kind"), sweep(GM_RUNS, quick=(0, 1), ids=lambda r: f"p{r[0]}-s{r[1]}-{r[2]}"))
def test_gradient_modulation_frames(p, s, kind):
    """Gradient-magnitude modulation (GMOD = 1, numerics.md §23): each frame's table of
    {fa, fs} through the load port (random factors, a step as ULTRAVIS's threshold, and the
    identity), SHA's modulated A, D and P bit for bit against the golden model through
    cube4_top: six views with 45° and (1, 1, 1), a crop box, random stalls and a reset in
    mid-frame, GRA's gradient or the voxels'; the modulation changes the picture, and the
    unstalled frames take the predicted cycles (two SHA stages more: cycles.GM_EXTRA)."""
    from cube4.gmod import GM_ONE, gm_table, identity_table, table_entries
    from cube4.host import crop_volume
    from cube4.model import render_frame
    from cube4.vgrad import pack_words

    rng = np.random.default_rng(800 + p)
    cfg = Cube4Config(pipelines=p, supersample=s)
    build = {"GMOD": 1, "VGRAD": 1} if kind else DEPTH_BUILD     # GRA's: the depth tests' build
    dims = (12 + p, 11, 10)
    nx, ny, nz = dims
    vol = rng.integers(0, 256, size=(nz, ny, nx))
    mem = pack_words(vol, kind, cfg.voxel_bits) if kind else vol
    n_gm = table_entries(cfg.voxel_bits + 5)
    tables = [rng.integers(0, GM_ONE + 1, size=(n_gm, 2)),
              gm_table(np.array([[0.0, 0.0], [0.02, 0.0], [0.021, 1.0]]), np.array([[0.0, 0.0], [0.05, 1.0]]),
                       cfg.voxel_bits, kind or "gra"),
              identity_table(cfg.voxel_bits)]
    jobs = []
    views = [(1.0, -1.0, 0.0), (1.0, 1.0, 1.0), (0.3, -0.45, 1.0), (-0.6, 0.25, -1.0), (-0.2, -1.0, -0.9),
             (1.0, 0.4, -0.7)]
    depth_t = None if kind else (1 << cfg.acc_bits) // 3     # the depth build tracks depth out too
    for n, d in enumerate(views):
        if n == 2:      # a crop box
            trav = make_traversal((nx - 4, ny - 3, nz - 2), d, cfg.weight_bits, s, origin=(2, 1, 1))
        else:
            trav = make_traversal(dims, d, cfg.weight_bits, s)
        lut, rmap = random_tables(rng, cfg)
        jobs.append(FrameJob(trav, lut, rmap, gm=tables[(0, 1, 0, 1, 0, 2)[n]], depth_t=depth_t,
                             stall=(0, 60, 0, 120, 30, 0)[n], stall_out=(0, 0, 90, 60, 0, 0)[n],
                             reset_after_cycles=150 if n == 3 else 0))
    results = render_frames(mem, jobs, cfg, max_dim=64, build=build)
    for n, (job, res) in enumerate(zip(jobs, results)):
        label = f"gradient modulation P={p} S={s} {kind or 'gra'} view {views[n]}"
        gold = check(mem, job.trav, cfg, job.lut, job.rmap, res, label, vgrad=bool(kind), gm=job.gm,
                     depth_t=job.depth_t)
        if n < 5:       # not the identity table: the modulation changes the frame
            plain = render_frame(crop_volume(mem, job.trav), job.trav, cfg, job.lut, job.rmap, vgrad=bool(kind))
            assert (plain.baseplane != gold.baseplane).any(), f"{label}: the modulation changed nothing"
        if not (job.stall or job.stall_out or job.reset_after_cycles):
            t = job.trav
            want = frame_cycles(t.num_sample_slices, t.nj, t.ni, p, True, bool(kind), gm=True)
            assert res["cycles"] == want, (label, res["cycles"], want)


# ---------------------------------------------------------------- label volumes
LABEL_VIEWS = [((1.0, -1.0, 0.0), "composite"), ((1.0, 1.0, 1.0), "composite"), ((0.3, -0.45, 1.0), "xray"),
               ((-0.6, 0.25, -1.0), "composite"), ((0.5, 0.25, 1.0), "xray"), ((1.0, 0.4, -0.7), "composite")]


def label_volume(rng, dims, voxel_bits: int):
    """Random values with labels in blocks of 2 x 3 x 2 voxels (boundaries between them in
    every axis, at every phase of the weights), and label 0 in a shell at three faces
    (hidden by the frames' LUT: the box schedule leaves it out): labelled words."""
    from cube4.labels import MAX_LABELS, pack_words

    nx, ny, nz = dims
    vol = rng.integers(0, 1 << voxel_bits, size=(nz, ny, nx))
    blocks = rng.integers(1, MAX_LABELS, size=(nz // 2 + 1, ny // 3 + 1, nx // 2 + 1))
    zz, yy, xx = np.mgrid[0:nz, 0:ny, 0:nx]
    labels = blocks[zz // 2, yy // 3, xx // 2]
    labels[(xx < 3) | (yy < 2) | (zz >= nz - 2)] = 0
    return pack_words(vol, labels, voxel_bits)


@pytest.mark.parametrize(("p", "s"), sweep([(1, 1), (5, 2), (8, 1)], quick=(0, 1)))
def test_label_frames(p, s):
    """Label volumes (LABELS = 1, numerics.md §24) on the feature build (DEPTH_BUILD): the
    label in the memory word, TRI's nearest-corner pick, GRA carrying it beside the
    sample, SHA's LUT read at {label, value}, bit for bit against the golden model: six
    views with 45° and (1, 1, 1), composite shaded and unshaded, X-ray, a crop box, the box
    schedule of a hidden label (cube4.skip: label 0 is empty space), random stalls and a
    reset in mid-frame; the labels change the picture (each frame against the same LUT
    without its per-label blocks), and the unstalled frames take the predicted cycles.
    The view (0.5, 0.25, 1) puts weights at exactly one half: with the golden pick's ties
    going down (w > 2^(W-1)) P = 1 fails with "labels P=1 S=1 view (-0.6, 0.25, -1.0)
    composite: ray (6, 3, 13, 5468, 2602, 2042, 8432, -1, 2) differs from golden (6, 3, 13,
    0, 0, 0, 0, -1, -1) (66 rays differ)" (tried, not kept)."""
    from cube4.host import crop_volume
    from cube4.labels import MAX_LABELS, split_words
    from cube4.model import render_frame
    from cube4.skip import plan_skip

    rng = np.random.default_rng(900 + p)
    cfg = Cube4Config(pipelines=p, supersample=s)
    dims = (12 + p, 11, 10)
    nx, ny, nz = dims
    words = label_volume(rng, dims, cfg.voxel_bits)
    n = 1 << cfg.voxel_bits
    depth_t = (1 << cfg.acc_bits) // 3      # the feature build tracks depth out too
    jobs, views = [], []
    for k, (d, mode) in enumerate(LABEL_VIEWS):
        if k == 2:      # a crop box
            trav = make_traversal((nx - 4, ny - 3, nz - 2), d, cfg.weight_bits, s, origin=(2, 1, 1))
        else:
            trav = make_traversal(dims, d, cfg.weight_bits, s)
        blocks = [random_tables(rng, cfg) for _ in range(MAX_LABELS)]
        lut = np.concatenate([b[0] for b in blocks], axis=0)
        lut[0:n] = 0                                    # label 0 hidden
        lut[7 * n:8 * n] = 0                            # and label 7
        rmap = blocks[0][1] if mode == "composite" and k != 3 else None    # frame 3 unshaded
        if k == 5:      # the box schedule: the hidden shell is not traversed
            plan = plan_skip(words, trav, lut, mode, p=p, labelled=True)
            assert plan.box is not None and plan.fraction < 1.0, plan.box
            trav = plan.trav
        views.append(d)
        jobs.append(FrameJob(trav, lut, rmap, mode=mode, depth_t=depth_t, stall=(0, 60, 0, 120, 30, 0)[k],
                             stall_out=(0, 0, 90, 60, 0, 0)[k], reset_after_cycles=150 if k == 3 else 0))
    results = render_frames(words, jobs, cfg, max_dim=64, build=DEPTH_BUILD)
    values = split_words(words, cfg.voxel_bits)[0]
    for k, (job, res) in enumerate(zip(jobs, results)):
        label = f"labels P={p} S={s} view {views[k]} {job.mode}"
        gold = check(words, job.trav, cfg, job.lut, job.rmap, res, label, mode=job.mode, depth_t=job.depth_t,
                     labels=True)
        one = render_frame(crop_volume(values, job.trav), job.trav, cfg, job.lut[5 * n:6 * n], job.rmap,
                           mode=job.mode, shading=job.rmap is not None)
        assert (one.baseplane != gold.baseplane).any(), f"{label}: the labels changed nothing"
        if not (job.stall or job.stall_out or job.reset_after_cycles):
            t = job.trav
            want = frame_cycles(t.num_sample_slices, t.nj, t.ni, p, True, False, True, True)
            assert res["cycles"] == want, (label, res["cycles"], want)


# ---------------------------------------------------------------- the voxel memory in DRAM
DRAM_VIEWS = [(0.3, -0.45, 1.0), (1.0, 0.4, -0.7), (1.0, 1.0, 1.0), (-1.0, -0.8, 0.2), (1.0, -1.0, 0.0),
              (-0.2, -1.0, -0.9)]


@pytest.mark.parametrize("p", sweep([8, 1], quick=(0,)))
def test_dram_frames(p):
    """The voxel memory in the generated DRAM (LiteDRAM's controller and memory model,
    MT41K256M16 timings, its timing checker fatal) behind cube4_dram_fetch, on its own
    75 MHz clock, the pipelines at 137.7 MHz: six views (45° among them, (1, 1, 1); each
    reads the image of its major axis), composite shaded and not, X-ray, MIP, MinIP, the
    box schedule on one, random stalls on three, a reset in mid-frame with reads in
    flight; every frame bit-exact. Every frame lasts more than two refresh intervals,
    and the controller's refresh count rises during each. The bursts a frame reads stay
    near its image's (at most 1.25 times; rows padded to whole bursts,
    cube4_sim.rtl.dram_image): a view that read an image of another axis order would
    read several bursts a beat, many times that."""
    from cube4.skip import plan_skip
    from cube4_sim.dram_core import DramRun, core_info

    rng = np.random.default_rng(300 + p)
    cfg = Cube4Config(pipelines=p)
    dims = (37, 30, 26) if p == 8 else (19, 16, 14)
    nx, ny, nz = dims
    vol = rng.integers(0, 256, size=(nz, ny, nx))
    vol[: nz // 3] //= 3                                  # a faint third: the box schedule skips it
    dram = DramRun()
    jobs = []
    for n, d in enumerate(DRAM_VIEWS):
        mode = ("composite", "xray", "mip", "minip", "composite", "composite")[n]
        trav = make_traversal(dims, d, cfg.weight_bits, 1)
        lut, rmap = random_tables(rng, cfg)
        clip = None
        if n == 5:
            lut[:90] = 0
            trav, clip = (lambda plan: (plan.trav, plan.clip))(plan_skip(vol, trav, lut, mode, p=p))
        jobs.append(FrameJob(trav, lut, rmap if n in (0, 5) else None, mode=mode, clip=clip,
                             stall=(0, 60, 0, 120, 0, 40)[n], stall_out=(0, 0, 90, 60, 0, 0)[n],
                             reset_after_cycles=300 if n == 3 else 0))
    results = render_frames(vol, jobs, cfg, max_dim=64, dram=dram)
    t_refi_ns = core_info(dram.core)["timing_cycles"]["tREFI"] * 1e3 / (dram.core.sys_clk_hz / 1e6)
    clk_ns = 1e3 / dram.clock_mhz
    per = 1 << ((128 // (p * cfg.voxel_bits)).bit_length() - 1)
    for n, (job, res) in enumerate(zip(jobs, results)):
        label = f"DRAM P={p} view {DRAM_VIEWS[n]} {job.mode}"
        check(vol, job.trav, cfg, job.lut, job.rmap, res, label, mode=job.mode, clip=job.clip)
        ideal = frame_cycles(job.trav.num_sample_slices, job.trav.nj, job.trav.ni, p)   # the full build
        print(f"{label}: {res['cycles']} cycles (ideal memory {ideal}), {res['dram_reads']} bursts read")
        assert res["cycles"] * clk_ns > 2 * t_refi_ns, f"{label}: shorter than two refresh intervals"
        assert res["dram_stat_ref"] >= 1, f"{label}: no refresh fell in the frame"
        nf, others = (nx, ny * nz) if job.trav.axis_i == 0 else (ny, nx * nz)
        image_bursts = -(-(-(-nf // p)) // per) * others     # rows padded to whole bursts
        assert res["dram_reads"] <= 1.25 * image_bursts, (label, res["dram_reads"], image_bursts)


# ---------------------------------------------------------------- beat skipping
@pytest.mark.parametrize("p", sweep([8, 1, 5], quick=(0,)))
def test_beat_frames(p):
    beat_frames(p, shaded=False, zout=True, labels=True)


@pytest.mark.parametrize("p", sweep([8, 1, 5], quick=(0,)))
def test_beat_frames_shaded(p):
    """As test_beat_frames, in a shaded build (GRA on the beat schedule) with gradient
    modulation (GMOD = 1): composite frames with the reflectance map, and termination in
    every other frame, where beats run as GRA's neighbours only; their modulation tables
    random, a step and the identity in turn; the unshaded modes in the same build."""
    beat_frames(p, shaded=True, gmod=True, slab=True)


@pytest.mark.parametrize("p", sweep([5, 1], quick=(0,)))
def test_beat_frames_vgrad(p):
    """As test_beat_frames_shaded, in a build with voxel gradients (VGRAD = 1: TRI
    interpolates the memory words' gradients, no GRA) and gradient modulation."""
    beat_frames(p, shaded=True, vgrad=True, gmod=True)


def test_beat_frames_thin():
    """Frames one and two rows deep (NJ = 1, 2: crop boxes of one volume, rows along y and
    along x) through the shaded beat build, P = 8: GRA's row table is read as a row's word
    is written and in the cycle after (NJ = 1 failed here before the row NJ word was taken
    as written). Their rays run to their stops: the host lets rays end early only in frames
    of TERM_MIN_ROWS rows or more (the decisions' wait for COM's reports deadlocks in
    thinner ones), as the last frame here, with random stalls. Each frame's rays are the
    golden beat-schedule frame's bit for bit and its plane the fixed schedule's."""
    import copy

    import cube4.beats as beats
    from cube4.host import crop_volume
    from cube4.model import render_frame

    p = 8
    rng = np.random.default_rng(808)
    cfg = Cube4Config(pipelines=p, supersample=4)    # MAX_SS_LOG2 = 2, as the shaded build; frames at S = 1
    vol = rng.integers(0, 64, size=(9, 6, 12))
    hit = rng.random(vol.shape) < 0.3
    vol[hit] = rng.integers(64, 256, size=int(hit.sum()))
    boxes = [((12, 1, 9), (0, 2, 0), (1.0, 1.0, 1.0)), ((12, 2, 9), (0, 3, 0), (1.0, 1.0, 1.0)),
             ((10, 6, 1), (1, 0, 6), (1.0, 0.4, -0.7)), ((10, 6, 2), (1, 0, 4), (-1.0, 0.4, 0.7)),
             ((12, 6, 9), (0, 0, 0), (0.3, -0.45, 1.0))]
    jobs, gold = [], []
    for n, (dims, origin, direction) in enumerate(boxes):
        trav = make_traversal(dims, direction, cfg.weight_bits, 1, origin=origin)
        terminate = trav.nj >= beats.TERM_MIN_ROWS
        lut, rmap = random_tables(rng, cfg)
        lut[:64] = 0
        if terminate:
            lut[lut[:, 3] > 0, 3] = (1 << cfg.alpha_bits) - 1
        bits = beats.BlockTable.of(vol, beats.BLOCK).bits(lut, "composite")
        sched = beats.BeatSchedule(trav, p, beats.frame_occupancy(bits, beats.BLOCK, trav), terminate=terminate,
                                   gra=True)
        rule = beats.TerminationRule("composite", 0, 1 << cfg.acc_bits, int(vol.min()), int(vol.max()),
                                     enabled=terminate, value_bits=cfg.voxel_bits)
        jobs.append(FrameJob(trav, lut, rmap, mode="composite", beats=(copy.deepcopy(sched), rule, bits),
                             stall=(0, 40)[n % 2], stall_out=(0, 30)[n % 2]))
        gold.append((sched, rule))
    assert sorted({j.trav.nj for j in jobs})[:2] == [1, 2], "the frames must include NJ = 1 and NJ = 2"
    build = {"BEATS": 1, "SHADING": 1, "VGRAD": 0, "GMOD": 1, "SLAB": 1}   # (test_beat_frames_shaded's build)
    results = render_frames(vol, jobs, cfg, max_dim=32, build=build)
    for n, (job, (sched, rule), res) in enumerate(zip(jobs, gold, results)):
        label = f"thin frame {n}: NJ = {job.trav.nj}, NI = {job.trav.ni}{' terminated' if rule.enabled else ''}"
        frame = check(vol, job.trav, cfg, job.lut, job.rmap, res, label, mode="composite", beats=(sched, rule))
        fixed = render_frame(crop_volume(vol, job.trav), job.trav, cfg, job.lut, job.rmap, mode="composite",
                             shading=True)
        assert (frame.baseplane == fixed.baseplane).all(), f"{label}: differs from the fixed schedule"
        assert fixed.baseplane.any(), f"{label}: an empty image (the frame would test nothing)"
        print(f"{label}: {res['cycles']} cycles")


#: frames of beat_frames at S > 1 (the others at S = 1): view (1, 1, 1), the 45° view
#: (1, -1, 0), the frame reset in mid-frame and one more at S = 4, one at S = 2
BEAT_FRAME_S = {1: 4, 2: 4, 4: 2, 6: 4, 8: 4}


def beat_frames(p: int, shaded: bool, vgrad: bool = False, gmod: bool = False, zout: bool = False,
                slab: bool = False, labels: bool = False) -> None:
    """The beat schedule through the RTL (BEATS = 1, unshaded; S = 1, and S = 4 on the
    frames of BEAT_FRAME_S, 2 on one: MAX_SS_LOG2 = 2): a sparse volume
    (a faint background, a dense blob; a LUT that is zero below the blob's values), views
    of every class and every mode, with ray termination in every other frame (its LUT
    opaque where it counts at tau = 0; on some composite frames a random tau > 0 with the
    LUT as drawn); the host writes each frame's block table and its rays' stops.
    Path weights on two frames in three (the build has PLW = 1: the LUT's weighted columns
    beside it) and a crop box whose faces cut the blob on every third (the first frame's
    weights change its plane). Each frame's rays are the
    golden beat-schedule frame's bit for bit, and its base plane the fixed schedule's, with
    random stalls on every stream and a reset in mid-frame; the beats that ran
    (cube4_top's count) are the golden frame's, and an unstalled frame takes more cycles
    than the walker's and, with GRA, than GRA's beat source's (beats.walker_cycles,
    beats.gra_cycles: each steps at most once a cycle). Depth in on every third frame (a surface's
    stop slices: the ray table's stops, no stop table in COM), which changes some frame's
    plane. ``gmod``: the build modulates by the
    gradient's magnitude (GMOD = 1), each shaded frame with its own table (the factors are
    at most 1, so the block table from the LUT still covers every sample that counts), and
    the modulation changes some frame's plane. ``zout``: depth out (ZOUT = 1) on every
    frame, its threshold varied (the extremum modes': 0), the rays' two slices bit for bit
    (with the countdown above them in the buffer word), not all equal. ``slab``: the cut
    slab (SLAB = 1) with its falloff on every third frame (the block table from the LUT
    covers it: the slab only takes samples away), which changes some frame's plane.
    ``labels``: the build has label volumes (LABELS = 1, so PLW = 0: no path weights) and
    runs label_beat_frames after these frames."""
    from cube4.clip import Clip, slab_coefficients
    import copy

    from cube4.gmod import GM_ONE, gm_table, table_entries

    import cube4.beats as beats
    from cube4.model import render_frame
    from cube4.host import crop_volume
    from cube4.pathlen import path_weighted, weighted_columns

    rng = np.random.default_rng(800 + p)
    cfg = Cube4Config(pipelines=p, supersample=4)    # the build: MAX_SS_LOG2 = 2
    nx, ny, nz = 24, 20, 16
    vol = rng.integers(0, 64, size=(nz, ny, nx))
    vol[5:11, 6:14, 8:17] = rng.integers(64, 256, size=(6, 8, 9))
    modes = ["composite", "xray", "mip", "minip"]
    if shaded:   # composite shaded, with and without termination, and each unshaded mode once
        modes = ["composite", "composite", "composite", "xray", "composite", "mip", "composite", "minip"]
    gm_tables = [rng.integers(0, GM_ONE + 1, size=(table_entries(cfg.voxel_bits + 5), 2)),
                 gm_table(np.array([[0.0, 0.0], [0.02, 0.0], [0.021, 1.0]]), np.array([[0.0, 0.0], [0.05, 1.0]]),
                          cfg.voxel_bits, "central" if vgrad else "gra"),
                 None]        # the identity
    jobs, gold = [], []
    for n, direction in enumerate(VIEWS):         # (1, 1, 1) and the 45° (1, -1, 0) among them
        # (unshaded: each mode on two frames in a row, without and with termination)
        mode = modes[n % len(modes)] if shaded else modes[(n // 2) % len(modes)]
        terminate = n % 2 == 1 or (shaded and n % 4 == 0)
        # a threshold tau > 0 (half of T or more) on some composite frames that terminate,
        # their LUT as drawn (rays end at various depths; those near their stops are not
        # reported); tau = 0 with an opaque LUT on the others
        tau = int(rng.integers(1 << (cfg.acc_bits - 1), 1 << cfg.acc_bits)) \
            if terminate and mode == "composite" and n % 3 == 1 else 0
        box = n % 3 == 0      # a crop box whose faces cut the blob (the weights' faces through it)
        ss = BEAT_FRAME_S.get(n, 1)   # S = 4 on (1, 1, 1), the 45° view and the reset frame; 2 on one
        trav = make_traversal((10, 10, 8) if box else (nx, ny, nz), direction, cfg.weight_bits, ss,
                              phase=(n * 37 % 256, n * 91 % 256), origin=(10, 8, 7) if box else (0, 0, 0))
        lut, rmap = random_tables(rng, cfg)
        rmap = rmap if shaded and mode == "composite" else None
        lut[:64] = 0
        if terminate and not tau:
            lut[lut[:, 3] > 0, 3] = (1 << cfg.alpha_bits) - 1
        if n % 3 != 2 and not labels:    # path weights on two frames in three (the weighted columns beside the LUT)
            lut = np.concatenate([lut, weighted_columns(lut[:, 3], cfg.alpha_bits)], axis=1)
        bits = beats.BlockTable.of(vol, beats.BLOCK).bits(lut, mode)
        sched = beats.BeatSchedule(trav, p, beats.frame_occupancy(bits, beats.BLOCK, trav), terminate=terminate,
                                   gra=rmap is not None and not vgrad)
        rule = beats.TerminationRule(mode, tau, 1 << cfg.acc_bits, int(vol.min()), int(vol.max()),
                                     enabled=terminate, value_bits=cfg.voxel_bits)
        gm = gm_tables[n % 3] if gmod and rmap is not None else None
        stop = surface_stops(trav, rng) if n % 3 == 2 else None     # depth in (a geometry's stops)
        depth_t = ((1 << cfg.acc_bits) * (n % 4 + 1) // 6 if mode in ("composite", "xray") else 0) if zout else None
        clip = None
        if slab and n % 3 == 1:     # a slab through the blob, soft faces (whole-volume frames)
            plane, sl = slab_coefficients(trav, ((0.5, -0.8, 0.3), (0.1, 0.0, 1.0), (1.0, 0.2, -0.4))[n // 3 % 3],
                                          (12.0, 10.0, 8.0), 3.0, 1.5)
            clip = Clip(plane=plane, slab=sl)
        job = FrameJob(trav, lut, rmap, mode=mode, beats=(copy.deepcopy(sched), rule, bits), gm=gm, stop_m=stop,
                       depth_t=depth_t, clip=clip,
                       stall=(0, 40, 0, 90)[n % 4], stall_out=(0, 0, 60, 30)[n % 4],
                       reset_after_cycles=500 if n == 2 else 0)
        jobs.append(job)
        gold.append((sched, rule))
    mem = vol
    if vgrad:       # the memory words hold each voxel's gradient too (the block table: its value)
        from cube4.vgrad import pack_words
        mem = pack_words(vol, "central", cfg.voxel_bits)
    build = {"BEATS": 1, "SHADING": int(shaded), "VGRAD": int(vgrad), **({"GMOD": 1} if gmod else {}),
             **({"ZOUT": 1} if zout else {}), **({"SLAB": 1} if slab else {}),
             **({"LABELS": 1, "PLW": 0} if labels else {})}
    results = render_frames(mem, jobs, cfg, max_dim=32, build=build)
    modulated = stopped = falloff = 0
    zs: set[int] = set()
    for n, (job, (sched, rule), res) in enumerate(zip(jobs, gold, results)):
        label = (f"beats P={p} S={job.trav.supersample} view {n} {job.mode}{' shaded' if job.rmap is not None else ''}"
                 f"{' (voxel gradients)' if vgrad else ''}{' terminated' if rule.enabled else ''}"
                 f"{f' at tau {rule.tau}' if rule.tau else ''}"
                 f"{' path-weighted' if path_weighted(job.lut, job.mode) else ''}"
                 f"{' modulated' if job.gm is not None else ''}{' depth in' if job.stop_m is not None else ''}{' slab' if job.clip is not None else ''}")
        frame = check(mem, job.trav, cfg, job.lut, job.rmap, res, label, mode=job.mode, beats=(sched, rule),
                      vgrad=vgrad, gm=job.gm, stop_m=job.stop_m, depth_t=job.depth_t, clip=job.clip)
        if zout:
            px = res["pixels"]
            zs.update(int(z) for z in px["zf"][px["zf"] >= 0])
        box_mem = crop_volume(mem, job.trav)
        fixed = render_frame(box_mem, job.trav, cfg, job.lut, job.rmap, mode=job.mode, shading=job.rmap is not None,
                             vgrad=vgrad, gm=job.gm, stop_m=job.stop_m, clip=job.clip)
        if job.clip is not None:
            hard = render_frame(box_mem, job.trav, cfg, job.lut, job.rmap, mode=job.mode,
                                shading=job.rmap is not None, vgrad=vgrad, gm=job.gm,
                                clip=Clip(plane=job.clip.plane, slab=(job.clip.slab[0], 0, 0)))
            falloff += int((hard.baseplane != fixed.baseplane).any())
        if job.stop_m is not None:
            free = render_frame(box_mem, job.trav, cfg, job.lut, job.rmap, mode=job.mode,
                                shading=job.rmap is not None, vgrad=vgrad, gm=job.gm)
            stopped += int((free.baseplane != fixed.baseplane).any())
        if job.gm is not None:
            plain = render_frame(box_mem, job.trav, cfg, job.lut, job.rmap, mode=job.mode, shading=True, vgrad=vgrad)
            modulated += int((plain.baseplane != fixed.baseplane).any())
        ran = copy.deepcopy(sched)     # the golden frame's beats that ran: the RTL's count agrees
        render_frame(box_mem, job.trav, cfg, job.lut, job.rmap, mode=job.mode, shading=job.rmap is not None,
                     beats=ran, done=rule, vgrad=vgrad, gm=job.gm, stop_m=job.stop_m, clip=job.clip)
        run = sum(int(ran.run_beats(m).sum()) for m in range(ran.M))
        assert res["beats_run"] == run, f"{label}: {res['beats_run']} beats ran on the RTL, golden {run}"
        if not rule.enabled:
            assert (frame.baseplane == fixed.baseplane).all(), f"{label}: differs from the fixed schedule"
        if n == 0 and not labels:   # a weighted frame whose weights change its plane: the test sees them
            assert path_weighted(job.lut, job.mode)
            plain = render_frame(box_mem, job.trav, cfg, job.lut[:, :4], job.rmap, mode=job.mode,
                                 shading=job.rmap is not None, vgrad=vgrad)
            assert (plain.baseplane != fixed.baseplane).any(), f"{label}: the path weights changed nothing"
        box = job.trav.num_sample_slices * job.trav.nj * -(-job.trav.ni // p)
        rows = beats.walk_rows(ran)
        walker = int(beats.walker_cycles(ran, rows).sum())
        gra = int(beats.gra_cycles(ran, rows).sum()) if build["SHADING"] and not vgrad else 0
        print(f"{label}: {res['cycles']} cycles, the fixed schedule's beats {box}, "
              f"the walker's cycles {walker}, GRA's {gra or '(no GRA)'}")
        if not (job.stall or job.stall_out or job.reset_after_cycles):
            # the walk and GRA's beat source step at most once a cycle: lower bounds
            assert res["cycles"] > max(walker, gra), (label, res["cycles"], walker, gra)
    assert not gmod or modulated, "the modulation changed no frame: the test would not see it"
    assert stopped, "the stop slices changed no frame: the test would not see depth in"
    assert not zout or len(zs) > 1, "depth out: the rays' first slices are all equal"
    assert not slab or falloff, "the slab's falloff changed no frame: the test would not see it"
    if labels:
        label_beat_frames(p, cfg, rng, build)


def label_beat_frames(p: int, cfg: Cube4Config, rng, build: dict) -> None:
    """Labelled words (label_volume: blocks of random labels, label 0 in a shell) on the
    beat schedule in ``build`` (BEATS = 1, LABELS = 1): the host's block table keeps the
    blocks of each label (``BlockTable.of(..., value_bits)``), labels 0 and 7 hidden;
    composite and X-ray, termination on two frames of three, random stalls: every ray is
    the golden beat frame's, the beats that ran are its, some beats were skipped, the
    frame without termination is the fixed schedule's, and the labels change a picture."""
    import copy

    import cube4.beats as beats
    from cube4.host import crop_volume
    from cube4.labels import MAX_LABELS, split_words
    from cube4.model import render_frame

    dims = (24, 20, 16)
    words = label_volume(rng, dims, cfg.voxel_bits)
    values = split_words(words, cfg.voxel_bits)[0]
    n = 1 << cfg.voxel_bits
    table = beats.BlockTable.of(words, beats.BLOCK, value_bits=cfg.voxel_bits)
    cases = [(VIEWS[6], "composite", False), (VIEWS[8], "xray", True), (VIEWS[0], "composite", True)]
    jobs, gold = [], []
    for k, (direction, mode, terminate) in enumerate(cases):
        trav = make_traversal(dims, direction, cfg.weight_bits, 1)
        lut = np.concatenate([random_tables(rng, cfg)[0] for _ in range(MAX_LABELS)], axis=0)
        lut[0:n] = 0                                    # label 0 hidden
        lut[7 * n:8 * n] = 0                            # and label 7
        if terminate:
            lut[lut[:, 3] > 0, 3] = (1 << cfg.alpha_bits) - 1
        bits = table.bits(lut, mode)
        sched = beats.BeatSchedule(trav, p, beats.frame_occupancy(bits, beats.BLOCK, trav), terminate=terminate,
                                   gra=False)
        rule = beats.TerminationRule(mode, 0, 1 << cfg.acc_bits, int(values.min()), int(values.max()),
                                     enabled=terminate, value_bits=cfg.voxel_bits)
        jobs.append(FrameJob(trav, lut, None, mode=mode, beats=(copy.deepcopy(sched), rule, bits),
                             depth_t=(1 << cfg.acc_bits) // 3 if build.get("ZOUT") else None,
                             stall=(0, 50, 0)[k], stall_out=(0, 0, 70)[k]))
        gold.append((sched, rule))
    results = render_frames(words, jobs, cfg, max_dim=32, build=build)
    skipped = changed = 0
    for k, (job, (sched, rule), res) in enumerate(zip(jobs, gold, results)):
        label = f"beats P={p} labels view {k} {job.mode}{' terminated' if rule.enabled else ''}"
        check(words, job.trav, cfg, job.lut, None, res, label, mode=job.mode, beats=(sched, rule), labels=True,
              depth_t=job.depth_t)
        box = crop_volume(words, job.trav)
        ran = copy.deepcopy(sched)
        render_frame(box, job.trav, cfg, job.lut, None, mode=job.mode, shading=False, beats=ran, done=rule,
                     labels=True)
        run = sum(int(ran.run_beats(m).sum()) for m in range(ran.M))
        assert res["beats_run"] == run, f"{label}: {res['beats_run']} beats ran on the RTL, golden {run}"
        skipped += int(run < ran.M * ran.NJ * ran.NB)
        fixed = render_frame(box, job.trav, cfg, job.lut, None, mode=job.mode, shading=False, labels=True)
        if not rule.enabled:
            assert (baseplane_from_pixels(res["pixels"], job.trav.baseplane_shape) == fixed.baseplane).all(), \
                f"{label}: differs from the fixed schedule"
        plain = render_frame(crop_volume(values, job.trav), job.trav, cfg, job.lut[n:2 * n], None, mode=job.mode,
                             shading=False)
        changed += int((plain.baseplane != fixed.baseplane).any())
    assert skipped and changed, (skipped, changed)

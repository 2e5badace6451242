"""Beat skipping and ray termination (cube4.beats, docs/numerics.md §19): the specification.

At τ = 0 the base plane is the fixed schedule's bit for bit in every mode, view (45° and
(1, 1, 1) among them), S, P, block size, with cut planes, crop boxes, path weights, voxel
gradients and q × q passes; every ray that leaves with a value leaves once, with the
fixed schedule's value. The rules that make it exact are needed (without them the same
checks fail); τ > 0 changes a ray by at most τ per channel."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from cube4_testutil import rays_agree, sparse_case

import cube4.beats as beats
from cube4.app.volumes import load_volume
from cube4.host import config_for, golden_view
from cube4.model import render_frame
from cube4.scene import load_scene

SEEDS = range(40)


def schedule(vol, trav, cfg, lut, mode, shading, block=4, lag=2, terminate=True, p=None, tau=0):
    table = beats.BlockTable.of(vol, block)
    occ = beats.frame_occupancy(table.bits(lut, mode), block, trav)
    sched = beats.BeatSchedule(trav, p or cfg.pipelines, occ, lag, terminate=terminate,
                               gra=shading and mode == "composite")
    rule = beats.TerminationRule(mode, tau, 1 << cfg.acc_bits, int(vol.min()), int(vol.max()),
                                 enabled=terminate, value_bits=cfg.voxel_bits)
    return sched, rule


def opaque(lut, mode, cfg):
    """The case's LUT with every counting entry nearly opaque (rays end in a few samples)."""
    lut = lut.copy()
    if mode in ("composite", "xray"):
        counts = lut[:, 3] > 0
        lut[counts, 3] = (1 << cfg.alpha_bits) - 1
    return lut


def frames(seed: int, block=4, p=None, make_opaque=False, tau=0, **kw):
    vol, trav, cfg, lut, rmap, mode, shading, clip = sparse_case(seed)
    if p is not None:
        cfg = dataclasses.replace(cfg, pipelines=p)
    if make_opaque:
        lut = opaque(lut, mode, cfg)
    args = dict(mode=mode, shading=shading, clip=clip)
    full = render_frame(vol, trav, cfg, lut, rmap, **args)
    sched, rule = schedule(vol, trav, cfg, lut, mode, shading, block, tau=tau, **kw)
    part = render_frame(vol, trav, cfg, lut, rmap, beats=sched, done=rule, **args)
    return full, part, sched


def mismatches(seeds, **kw) -> list[int]:
    bad = []
    for seed in seeds:
        full, part, _ = frames(seed, **kw)
        if not (np.array_equal(full.baseplane, part.baseplane) and rays_agree(full, part)):
            bad.append(seed)
    return bad


@pytest.mark.parametrize("block, p", [(1, 1), (2, 5), (4, 4), (4, 8), (8, 5)])
def test_beat_skipping_is_bit_exact(block, p):
    """Every mode, shaded and unshaded, S = 1, 2, 4, seven views, cut planes: the base
    plane and the rays are the fixed schedule's, and most frames run fewer beats."""
    assert mismatches(SEEDS, block=block, p=p) == []
    fewer = 0
    for seed in SEEDS[:12]:
        _, _, sched = frames(seed, block=block, p=p)
        st = beats.schedule_stats(sched)
        assert st.run_beats + st.skipped_empty + st.skipped_terminated == st.box_beats
        fewer += st.run_beats < st.box_beats
    assert fewer >= 6, fewer


def opaque_slab(p: int, direction):
    """A nearly opaque slab in front of a dense block, seen through the slab: rays end in
    the slab, and the block behind it is skipped for that cause."""
    from cube4.config import Cube4Config
    from cube4.view import make_traversal
    rng = np.random.default_rng(p)
    vol = rng.integers(0, 40, size=(24, 18, 20))
    vol[3:9, :, :] = 200
    vol[12:20, 4:14, 4:16] = rng.integers(100, 256, size=(8, 10, 12))
    cfg = Cube4Config(pipelines=p)
    lut = np.zeros((256, 4), dtype=np.int64)
    lut[:, :3] = rng.integers(0, 256, size=(256, 3))
    lut[60:, 3] = (1 << cfg.alpha_bits) - 1
    rmap = rng.integers(0, 1024, size=(cfg.rmap_entries, 2))
    return vol, make_traversal((20, 18, 24), direction, cfg.weight_bits, 1), cfg, lut, rmap


@pytest.mark.parametrize("p", [1, 5, 8])
@pytest.mark.parametrize("direction", [(0.2, -0.1, 1.0), (1.0, 1.0, 1.0), (0.0, 1.0, 1.0)])
def test_termination_is_bit_exact(p, direction):
    """Nearly opaque content: COM ends rays early, the beats behind them are skipped for
    that cause, and the image is the fixed schedule's (the sparse cases with opaque
    blobs too)."""
    vol, trav, cfg, lut, rmap = opaque_slab(p, direction)
    full = render_frame(vol, trav, cfg, lut, rmap)
    sched, rule = schedule(vol, trav, cfg, lut, "composite", True)
    part = render_frame(vol, trav, cfg, lut, rmap, beats=sched, done=rule)
    assert np.array_equal(full.baseplane, part.baseplane) and rays_agree(full, part)
    st = beats.schedule_stats(sched)
    assert st.skipped_terminated > 0.05 * st.box_beats, st
    assert mismatches(SEEDS[:20], p=p, make_opaque=True) == []


def test_each_rule_is_needed(monkeypatch):
    """Without the neighbours that feed GRA, or with rays that start a slice after their
    first sample that may count, some images change: the exactness tests can fail."""
    seeds = [s for s in SEEDS if sparse_case(s)[6] and sparse_case(s)[5] == "composite"]
    orig = beats.BeatSchedule.run_beats

    def no_neighbours(self, m):
        return self.active_beats(m)
    monkeypatch.setattr(beats.BeatSchedule, "run_beats", no_neighbours)
    assert mismatches(seeds, make_opaque=True, block=1), "dropping GRA's neighbours changed no image"
    monkeypatch.setattr(beats.BeatSchedule, "run_beats", orig)

    orig_first = beats.first_counting
    monkeypatch.setattr(beats, "first_counting", lambda occ: orig_first(occ) + 1)
    assert mismatches(SEEDS, make_opaque=True), "starting each ray a slice late changed no image"


def translucent_front(p: int, direction):
    """Faint content in the front half only, seen from the front: no ray's transmittance
    runs out, but nothing behind the content counts, so its rays stop there."""
    vol, trav, cfg, lut, rmap = opaque_slab(p, direction)
    vol = vol.copy()
    vol[12:, :, :] = 0
    lut = lut.copy()
    lut[60:, 3] = 40                            # about 1 % opacity a sample
    return vol, trav, cfg, lut, rmap


@pytest.mark.parametrize("p", [1, 8])
def test_stop_ends_translucent_rays(p, monkeypatch):
    """A ray ends at the slice after the last in which its sample may count (its stop):
    translucent rays end behind their content, far fewer beats run than with every ray
    running to the box's far face, and the image is the fixed schedule's. A stop at the
    first slice that may count instead of the last changes it (a stop a slice or two early
    does not: the block table's margin reaches past the content)."""
    vol, trav, cfg, lut, rmap = translucent_front(p, (0.2, -0.1, 1.0))
    full = render_frame(vol, trav, cfg, lut, rmap)
    sched, rule = schedule(vol, trav, cfg, lut, "composite", True)
    assert int(full.baseplane[..., 3].max()) < (1 << 16) - 1     # no ray is opaque
    part = render_frame(vol, trav, cfg, lut, rmap, beats=sched, done=rule)
    assert np.array_equal(full.baseplane, part.baseplane) and rays_agree(full, part)
    st = beats.schedule_stats(sched)
    assert st.skipped_terminated == 0, st
    orig = beats.last_counting
    monkeypatch.setattr(beats, "last_counting", lambda occ: np.full(occ.shape[1:], occ.shape[0] - 1))
    sched, rule = schedule(vol, trav, cfg, lut, "composite", True)
    render_frame(vol, trav, cfg, lut, rmap, beats=sched, done=rule)
    assert st.run_beats < 0.8 * beats.schedule_stats(sched).run_beats
    monkeypatch.setattr(beats, "last_counting", lambda occ: occ.shape[0] - 1 - orig(occ[::-1]))
    sched, rule = schedule(vol, trav, cfg, lut, "composite", True)
    early = render_frame(vol, trav, cfg, lut, rmap, beats=sched, done=rule)
    assert not np.array_equal(full.baseplane, early.baseplane)


def test_geometry_stop_ends_rays():
    """Depth in: a wall through the volume's centre stops every ray there; with beats the
    image is the fixed schedule's, with termination and without (then the beats beside
    the running ones run for the gradients: the neighbour term, as with termination), and
    the beats behind the wall are skipped."""
    from test_geometry import scene_with, wall
    vol = load_volume("head:24")
    sc = scene_with(None)
    cfg = config_for(sc, 8)
    cut = scene_with(wall(sc, cfg, (24, 24, 24), 0.0))
    _, fixed, _ = golden_view(vol, dataclasses.replace(cut, skip=False), cfg)
    for opts in ({}, {"terminate": False}):
        _, ended, st = golden_view(vol, cut, cfg, beat_skip=opts)
        _, _, st_free = golden_view(vol, sc, cfg, beat_skip=opts)
        assert np.array_equal(fixed.baseplane, ended.baseplane), opts
        assert st["beats"]["run_beats"] < 0.9 * st_free["beats"]["run_beats"], (opts, st["beats"], st_free["beats"])


def test_decided_cycles():
    """A front end deciding r beats a cycle: never fewer cycles than the walk, the walker's
    cycles (a beat a cycle, a cycle for a row that reads nothing) when r covers a slice in
    a cycle, and fewer cycles the more it decides."""
    _, _, sched = frames(3)
    walk = beats.walk_beats(sched)
    walker = int(beats.walker_cycles(sched).sum())
    rows = beats.walk_rows(sched)
    assert len(rows) == sched.M * sched.NJ + 1 and walker == walk + sum(not (r[2] | r[4]).any() for r in rows)
    got = [beats.decided_cycles(sched, r) for r in (1, 2, 4, 1 << 20)]
    assert got[-1] == walker and all(a >= b for a, b in zip(got, got[1:])) and got[0] >= sched.NJ * sched.NB
    assert got[0] >= walker >= walk, got
    with pytest.raises(ValueError, match="rate"):
        beats.decided_cycles(sched, 0)


@pytest.mark.parametrize("direction", [(0.0, 0.0, 1.0), (0.6, -0.35, 1.0), (1.0, 1.0, 1.0)])
def test_gra_cycles(direction):
    """GRA's beat source: where every beat runs, each slice's NJ rows of NB steps, row NJ
    (the previous slice's centres: NB steps, none in slice 0) and two window steps, and
    slice M after the last; on a sparse frame never fewer cycles than the beats that came
    in, and one more a row where a row has no step."""
    from cube4.view import make_traversal

    trav = make_traversal((21, 11, 9), direction, 8, 1)
    sched = beats.BeatSchedule(trav, 8, np.ones((trav.num_sample_slices, trav.nj, trav.ni), dtype=bool),
                               terminate=False)
    sched.reported = sched.M - 1        # no ray ends: every report is "running"
    m, nj, nb = sched.M, sched.NJ, sched.NB
    assert nb >= 2 and all(sched.run_beats(k).all() for k in range(m))
    got = beats.gra_cycles(sched)
    assert got[0] == nj * nb + 1 + 2 and (got[1:] == (nj + 1) * nb + 2).all(), got
    _, _, sparse = frames(3)
    rows = beats.walk_rows(sparse)
    per = beats.gra_cycles(sparse, rows)
    came = sum(int((r[2] | r[4]).sum()) for r in rows)
    assert len(per) == sparse.M + 1 and per.sum() >= came + 2 * (sparse.M + 1)
    st = beats.schedule_stats(sparse)
    assert st.as_dict()["gra_cycles"] == per.sum()


def test_tau_bounds_the_change():
    """τ > 0 ends rays whose transmittance is at or below τ: some rays change, none by
    more than τ in any channel (what the ray would still have gathered is at most T)."""
    tau = 1 << 12
    changed = 0
    for seed in SEEDS:
        if sparse_case(seed)[5] != "composite":
            continue
        full, part, _ = frames(seed, make_opaque=False, tau=tau)
        d = np.abs(full.baseplane - part.baseplane)
        assert d.max() <= tau, (seed, d.max())
        changed += bool(d.any())
    assert changed >= 1


def test_bad_parameters():
    vol, trav, cfg, lut, _, mode, shading, _ = sparse_case(0)
    with pytest.raises(ValueError, match="lag"):
        schedule(vol, trav, cfg, lut, mode, shading, lag=1)
    with pytest.raises(ValueError, match="block"):
        beats.BlockTable.of(vol, 0)
    with pytest.raises(ValueError, match="tau"):
        beats.TerminationRule("composite", tau=1 << 16, one=1 << 16)
    with pytest.raises(ValueError, match="mode"):
        beats.TerminationRule("sum")


def test_block_table_ranges():
    """Each block's range is the min and max of its voxels grown by MARGIN on every side."""
    rng = np.random.default_rng(3)
    vol = rng.integers(0, 256, size=(11, 9, 14))
    t = beats.BlockTable.of(vol, 4)
    for bz, by, bx in np.ndindex(t.lo.shape):
        sl = tuple(slice(max(0, 4 * b - beats.MARGIN), 4 * b + 4 + beats.MARGIN) for b in (bz, by, bx))
        assert t.lo[bz, by, bx] == vol[sl].min() and t.hi[bz, by, bx] == vol[sl].max()


@pytest.mark.parametrize("spec, scene, extra", [
    ("head:24", "head_quality", {}),               # S = 4, q = 2, path weights
    ("head:24", "head", {"gradient": "central"}),  # voxel gradients
    ("head:24", "head_cut", {"crop": ((2, 3, 1), (20, 19, 22))}),   # crop box and cut plane
    ("mri:32,24,12", "mri_skin", {}),
    ("mri:32,24,12", "mri_mip", {}),
    ("head:24", "head_xray", {}),
])
def test_scenes_are_bit_exact(spec, scene, extra):
    """Built-in scenes through the host (every pass's frame in its empty-space box, the
    block table of the whole volume): the image is the fixed schedule's."""
    vol = load_volume(spec)
    sc = dataclasses.replace(load_scene(scene), **extra)
    for p in (1, 5, 8):
        cfg = config_for(sc, p)
        _, f0, _ = golden_view(vol, sc, cfg)
        _, f1, st = golden_view(vol, sc, cfg, beat_skip={"block": 4})
        assert np.array_equal(f0.baseplane, f1.baseplane), (scene, p)
        b = st["beats"]
        assert b["run_beats"] <= b["box_beats"] and b["walk_beats"] >= b["run_beats"]


def test_cli_beats_and_stats(tmp_path):
    """--beats gives the same base plane as --no-skip and --stats the beats by cause; a
    scene that leaves [render] skip out runs the beat schedule (--tau then works without
    --beats), with the quality preset (S = 4) too, and the box in bricks and on a build
    without BEATS; --tau with --box or where the render runs the box, a τ out of range or
    in bricks are one line each."""
    import json
    import subprocess
    import sys

    def run(*extra, check=True):
        st, bp = tmp_path / "s.json", tmp_path / "b.npy"
        r = subprocess.run([sys.executable, "-m", "cube4_sim.cli", "render", "mri:48,36,20", "--scene", "mri_skin",
                            "--out", str(tmp_path / "x.png"), "--baseplane", str(bp), "--stats", str(st),
                            "--quiet", *extra], capture_output=True, text=True, check=check)
        return r if not check else (json.loads(st.read_text()), np.load(bp))

    (on, b_on), (_, b_off) = run("--beats"), run("--no-skip")
    assert np.array_equal(b_on, b_off)
    b = on["beats"]
    assert b["skipped_terminated"] > 0 and b["skipped_empty"] > 0
    assert b["run_beats"] + b["skipped_empty"] + b["skipped_terminated"] == b["box_beats"]
    _, b_tau = run("--beats", "--tau", "0.05")
    assert 0 < np.abs(b_tau - b_off).max() <= int(0.05 * (1 << 16)) + 1
    default, b_default = run()          # the scene leaves [render] skip out: the beat schedule
    assert np.array_equal(b_default, b_off) and default["beats"] == {**on["beats"], "table_s": default["beats"]["table_s"],
                                                                    "stop_s": default["beats"]["stop_s"]}
    assert np.array_equal(run("--tau", "0.05")[1], b_tau)
    boxed, b_box = run("--box")
    assert np.array_equal(b_box, b_off) and "beats" not in boxed and boxed["skip"]
    for extra in (("--bricks", "2,1,1"), ("--build", "full")):
        st, _ = run(*extra)     # the box: bricks, a build without BEATS
        assert "beats" not in st and st.get("skip", "bricks" in st), extra
    quality, b_quality = run("--preset", "quality")      # S = 4 (q = 2, path weights): the beat schedule
    assert quality["beats"]["skipped_empty"] > 0
    assert np.array_equal(b_quality, run("--preset", "quality", "--no-skip")[1])
    for extra, msg in ((("--box", "--tau", "0.1"), "--tau needs the beat schedule (ray termination), not"),
                       (("--bricks", "2,1,1", "--no-terminate"), "--no-terminate needs the beat schedule (--beats): "
                                                                 "this render runs the box"),
                       (("--box", "--beats"), "--no-skip, --box, --rects and --beats exclude each other"),
                       (("--beats", "--bricks", "2,1,1"), "does not run in bricks"),
                       (("--beats", "--tau", "0.7"), "--tau must be in 0..0.5")):
        r = run(*extra, check=False)
        assert r.returncode != 0 and msg in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr


def test_skipping_report_beat_rows():
    """make skipping's beat section on small volumes: four views, images identical,
    fewer beats with termination on an opaque surface, τ and block rows, its Markdown."""
    from cube4_reports import skipping

    rows = skipping.beat_rows("mri:32,24,12", "mri_skin")
    assert len(rows) == 4 and all(r["identical"] for r in rows)
    assert any(r["ended"]["run_beats"] < r["free"]["run_beats"] for r in rows)
    taus = skipping.tau_rows("mri:32,24,12", "mri_skin")
    assert taus[0]["rmse"] == 0 and taus[-1]["beats"]["run_beats"] <= taus[0]["beats"]["run_beats"]
    blocks = skipping.block_rows("head:24", "head")
    assert [b["block"] for b in blocks] == skipping.BLOCKS
    front = [{"volume": "head:128", "scene": "head", "rate": 2, "n3_over_p": 262144.0, "cycles": 130367,
              "decided_cycles": 129661, "walk_beats": 123419}]
    text = skipping.write_beats_md(rows, taus, blocks, front)
    assert "mri:32,24,12" in text and "identical" in text and "DIFFERENT" not in text
    assert "| head:128, scene head | 2 | 130,367 | 0.497 | 129,661 | 0.495 | 0.471 |" in text


def test_skipping_report_rtl_beat_lines(tmp_path):
    """The beat section's RTL table: a frame time only where the build that ran the frame
    (its options and widths, P = 8) was placed and routed; no other build's clock."""
    import json

    from cube4.builds import complete_build
    from cube4.config import Cube4Config
    from cube4_reports import fmax, skipping

    box = {"SHADING": 1, "COMPOSITING": 1}
    frames = [{"volume": "mri:128", "scene": "mri_skin", "schedule": s, "cycles": c, "n3_over_p": 262144.0,
               "beats": None if s == "box" else {"run_beats": 70000}, "build": {**box, "BEATS": int(s != "box")},
               "identical": True} for s, c in (("box", 140000), ("beats + termination", 97000))]
    widths = Cube4Config().widths()
    off = {"EXTREMUM": 0, "CLIP": 0, "PLW": 0, "SLAB": 0, "ZOUT": 0, "ZIN": 0, "GMOD": 0, "LABELS": 0, "VGRAD": 0,
           "RECTS": 0}
    f = tmp_path / "fpga_x.json"
    f.write_text(json.dumps({"seeds": [1, 2, 3], "rtl_commit": "abc1234", "max_dim": 128, "results": [
        {"p": 8, "fmax_median": 140.0, "fits": True, "build": complete_build({**box, **off, "BEATS": 0}),
         "widths": widths},
        {"p": 8, "fmax_median": 99.0, "fits": True, "build": complete_build({**box, **off, "BEATS": 1}),
         "widths": {**widths, "ACC_W": 24}}]}))      # another width: not the frame's build
    text = "\n".join(skipping.rtl_beat_lines(frames, fmax.load([f])))
    assert "140.0 MHz [1]" in text and "1.00 ms" in text and "not measured" in text and "0.267" in text
    assert "99.0" not in text and "- [1] 140.0 MHz: " in text and "median of 3 seeds, RTL abc1234" in text
    assert "not measured" in "\n".join(skipping.rtl_beat_lines(frames, []))
"""Empty-space skipping (cube4.skip, docs/numerics.md §15): the box schedule gives the
fixed schedule's base plane bit for bit in every mode, view, S, with cut planes and crop
boxes; its margins are needed (with one voxel less the images differ); the cycles follow
the box; the switch and the statistics of the command line."""

from __future__ import annotations

import dataclasses
import json
import subprocess
import sys

import numpy as np
import pytest
from cube4_testutil import SKIP_VIEWS as VIEWS, make_scene, sparse_case

import cube4.skip as skip
from cube4.app.render import render
from cube4.clip import Clip, cut_coefficients
from cube4.config import Cube4Config
from cube4.cycles import frame_cycles
from cube4.errors import UserError
from cube4.model import render_frame
from cube4.builds import FULL_BUILD
from cube4.scene import SKIP_DEFAULT, parse_scene, with_schedule
from cube4.view import make_traversal

def skipped_baseplane(vol, trav, cfg, lut, rmap, mode, shading, clip):
    plan = skip.plan_skip(vol, trav, lut, mode, clip)
    sub = None
    if plan.trav is not None:
        sub = render_frame(plan.box_volume(vol), plan.trav, cfg, lut, rmap, mode=mode, shading=shading,
                           clip=plan.clip).baseplane
    return plan, plan.place(sub)


def mismatches(seeds) -> list[int]:
    bad = []
    for seed in seeds:
        vol, trav, cfg, lut, rmap, mode, shading, clip = sparse_case(seed)
        full = render_frame(vol, trav, cfg, lut, rmap, mode=mode, shading=shading, clip=clip).baseplane
        _, base = skipped_baseplane(vol, trav, cfg, lut, rmap, mode, shading, clip)
        if not np.array_equal(base, full):
            bad.append(seed)
    return bad


SEEDS = range(40)


def test_box_schedule_is_bit_exact():
    """Every mode, shaded and unshaded, S = 1, 2, 4, seven views (45° and (1, 1, 1)
    among them), cut planes: the box's base plane placed in the whole equals the fixed
    schedule's, and the box is smaller than the volume in every case."""
    assert mismatches(SEEDS) == []
    for seed in SEEDS:
        vol, trav, cfg, lut, rmap, mode, shading, clip = sparse_case(seed)
        assert skip.plan_skip(vol, trav, lut, mode, clip).fraction < 1.0, seed


@pytest.mark.parametrize(("name", "value"), [("MARGIN_LOW", 0), ("MARGIN_HIGH", 1)])
def test_each_margin_is_needed(monkeypatch, name, value):
    """One voxel less of margin on either side changes some of the same cases' images:
    the exactness test above can fail."""
    monkeypatch.setattr(skip, name, value)
    assert mismatches(SEEDS), f"{name} = {value} changed no image"


def test_cells_at_the_high_faces_ignore_the_padding():
    """A cell at a high face takes its range from its voxels in the box, not the zero
    padding: a MinIP of bright voxels (zero would count) skips everything."""
    vol = np.full((6, 7, 8), 200)
    lut = np.zeros((256, 4), dtype=np.int64)
    lut[:100] = 1
    assert not skip.busy_cells(vol, lut, "minip").any()
    vol[5, 6, 7] = 50                       # the last voxel counts: its own cell and 7 neighbours
    busy = skip.busy_cells(vol, lut, "minip")
    assert busy.sum() == 8 and busy[5, 6, 7] and busy[4, 5, 6]


def test_counting_values_per_mode():
    lut = np.zeros((16, 4), dtype=np.int64)
    lut[5, 0] = 9          # colour, no opacity
    lut[9, 3] = 1
    assert list(np.nonzero(skip.counting_values(lut, "composite"))[0]) == [9]
    assert list(np.nonzero(skip.counting_values(lut, "xray"))[0]) == [9]
    assert list(np.nonzero(skip.counting_values(lut, "mip"))[0]) == list(range(5, 16))
    assert list(np.nonzero(skip.counting_values(lut, "minip"))[0]) == list(range(0, 10))
    assert not skip.counting_values(np.zeros((16, 4), dtype=np.int64), "mip").any()


def test_nothing_counts_no_frame():
    """A frame in which no sample counts renders nothing, and its base plane (zero) is the
    fixed schedule's."""
    vol, trav, cfg, lut, rmap, mode, shading, clip = sparse_case(0)
    lut[:, 3] = 0
    plan, base = skipped_baseplane(vol, trav, cfg, lut, rmap, "composite", True, None)
    assert plan.trav is None and plan.cycles(4, True) == 0
    full = render_frame(vol, trav, cfg, lut, rmap, mode="composite").baseplane
    assert np.array_equal(base, full) and not base.any()


def test_cycles_follow_the_box():
    vol, trav, cfg, lut, rmap, mode, shading, clip = sparse_case(3)
    plan = skip.plan_skip(vol, trav, lut, mode, clip)
    t = plan.trav
    assert tuple(b - a for a, b in zip(*plan.box)) == t.dims
    assert plan.cycles(5, True) == frame_cycles(t.num_sample_slices, t.nj, t.ni, 5, True)
    assert plan.cycles(5, False) < plan.cycles(5, True)


TF = {"points": [[0, 0, 0, 0, 0], [0.3, 0.2, 0.4, 0.9, 0.0], [0.5, 0.9, 0.6, 0.3, 0.3], [1, 1, 1, 1, 0.6]]}


@pytest.mark.parametrize("extra", [{}, {"crop": {"box": [[3, 2, 4], [26, 28, 25]]}},
                                   {"cut": {"normal": [1, 1, 0], "point": [14, 16, 15]}},
                                   {"render": {"supersample": 2}}, {"render": {"mode": "mip"}},
                                   {"material": {"shading": False}}])
def test_scene_renders_equal_with_and_without_skip(extra):
    """Through cube4.app.render: the head-like sphere's image and base plane with the box
    schedule equal the fixed schedule's; the statistics count the cycles saved."""
    from cube4_testutil import sphere_volume

    vol = np.zeros((30, 32, 28), dtype=np.uint16)
    vol[:24, 4:28, 2:26] = sphere_volume(24)[:, :, :]
    doc = {"transfer": TF, "view": {"azimuth": 35.0, "elevation": 40.0}, "output": {"width": 48}}
    for key, val in extra.items():
        doc.setdefault(key, {}).update(val)
    scene = parse_scene(doc)
    cfg = Cube4Config(pipelines=4, supersample=scene.supersample)
    on = render(vol, scene, cfg, "golden")
    off = render(vol, dataclasses.replace(scene, skip=False), cfg, "golden")
    assert np.array_equal(on.frame.baseplane, off.frame.baseplane)
    assert np.array_equal(on.image, off.image)
    assert on.stats["skip"] and not off.stats["skip"]
    assert on.stats["cycles_saved"] > 0 and off.stats["cycles_saved"] == 0
    assert on.stats["predicted_cycles"] + on.stats["cycles_saved"] == off.stats["predicted_cycles"]


def test_scene_key_must_be_a_bool():
    with pytest.raises(UserError, match="render.skip must be true, false, \"rects\" or \"beats\""):
        parse_scene({"render": {"skip": "no"}})
    assert parse_scene({"render": {"skip": False}}).skip is False
    assert parse_scene({"render": {"skip": "rects"}}).skip == "rects"
    assert parse_scene({"render": {"skip": "beats", "tau": 0.01}}).tau == 0.01
    with pytest.raises(UserError, match="render.tau"):
        parse_scene({"render": {"skip": "beats", "tau": 0.9}})
    sc = make_scene()       # [render] skip left out: the beat schedule, rendered whole (at every S)
    assert sc.skip == SKIP_DEFAULT and sc.schedule == "beats"
    assert dataclasses.replace(sc, supersample=4).schedule == "beats"
    assert with_schedule(sc, whole=False).skip is True and with_schedule(sc).skip == "beats"
    assert with_schedule(sc, build=FULL_BUILD).skip is True
    assert with_schedule(sc, supersample=2).skip == "beats"    # S from the configuration: any
    assert with_schedule(dataclasses.replace(sc, skip=False), build={"BEATS": 1}).skip is False
    with pytest.raises(UserError, match="render.skip must be true"):
        parse_scene({"render": {"skip": SKIP_DEFAULT}})     # the default has no spelling of its own


def test_cli_no_skip_and_stats(tmp_path):
    """--no-skip gives the fixed schedule and the same base plane; --stats reports the
    box, the predicted cycles of both schedules and the cycles saved."""
    def run(*extra):
        st = tmp_path / f"s{len(extra)}.json"
        bp = tmp_path / f"b{len(extra)}.npy"
        subprocess.run([sys.executable, "-m", "cube4.app.cli", "render", "head:48", "--scene", "head", "--out",
                        str(tmp_path / "x.png"), "--baseplane", str(bp), "--stats", str(st), "--quiet", *extra],
                       check=True)
        return json.loads(st.read_text()), np.load(bp)

    (on, b_on), (off, b_off) = run(), run("--no-skip")
    assert np.array_equal(b_on, b_off)
    assert on["skip"] and on["cycles_saved"] > 0 and on["skip_fraction"] < 1
    assert not off["skip"] and off["cycles_saved"] == 0
    assert on["fixed_schedule_cycles"] == off["predicted_cycles"]


@pytest.mark.parametrize("p", [1, 5, 8])
def test_small_boxes_grow_to_a_full_rate_slice(p):
    """One busy voxel: the box grows (rows, then partial beams) until a sample slice has
    COM_MIN_SLICE beats, so that the cycle formula holds; the image stays exact."""
    from cube4.cycles import COM_MIN_SLICE

    rng = np.random.default_rng(p)
    cfg = Cube4Config(pipelines=p)
    vol = rng.integers(0, 100, size=(20, 18, 21))
    vol[10, 9, 11] = 200
    lut = np.zeros((256, 4), dtype=np.int64)
    lut[150:] = rng.integers(1, 256, size=(106, 4))
    for d in VIEWS:
        trav = make_traversal((21, 18, 20), d, cfg.weight_bits, 1)
        plan = skip.plan_skip(vol, trav, lut, "composite", p=p)
        t = plan.trav
        assert t.nj * -(-t.ni // p) >= COM_MIN_SLICE, (d, t.dims)
        assert plan.fraction < 0.5
        full = render_frame(vol, trav, cfg, lut, None, shading=False).baseplane
        sub = render_frame(plan.box_volume(vol), t, cfg, lut, None, shading=False).baseplane
        assert np.array_equal(plan.place(sub), full), d


def test_skip_flag_and_streams():
    """A box as large as the volume skips nothing (stats say so); keep_streams renders the
    fixed schedule, so the streams are indexed by the frame's own traversal; with q > 1
    it refuses."""
    from cube4_testutil import sphere_volume

    from cube4.app.render import render_golden_view

    dense = parse_scene({"transfer": {"points": [[0, 0, 0, 0, 0.2], [1, 1, 1, 1, 0.5]]}, "output": {"width": 32}})
    vol = sphere_volume(16)
    cfg = Cube4Config(pipelines=4)
    st = render(vol, dense, cfg, "golden").stats
    assert st["skip"] is False and st["skip_fraction"] == 1.0 and st["cycles_saved"] == 0
    sparse = parse_scene({"transfer": TF, "output": {"width": 32}})
    big = np.zeros((24, 24, 24), dtype=np.uint16)
    big[4:20, 4:20, 4:20] = vol
    assert render(big, sparse, cfg, "golden").stats["skip"] is True
    res = render_golden_view(big, sparse, cfg, keep_streams=True)
    t = res.frame.trav
    assert res.frame.streams["samples"].shape == (t.num_sample_slices, t.nj, t.ni) == (24, 24, 24)
    with pytest.raises(ValueError, match="subpixel must be 1"):
        render_golden_view(big, dataclasses.replace(sparse, subpixel=2), cfg, keep_streams=True)


def test_skipping_report_rows(tmp_path):
    """make skipping's measurement on a small volume: four views, images identical, the
    cycles of both schedules, and its Markdown; --md-only rewrites it from the run's JSON
    beside it (committed under reports/, so that a clone can)."""
    from cube4_reports import skipping

    rows = skipping.measure("sphere:24", "default", True)
    assert len(rows) == 4
    for r in rows:
        assert r["bit_identical"] and r["predicted_cycles"] < r["fixed_schedule_cycles"]
        assert r["rect_bit_identical"] and r["rect_beats"] < r["predicted_cycles"]
    text = skipping.write_md(rows, None, {"git": "test"})
    assert "sphere:24" in text and "identical" in text and "DIFFERENT" not in text
    assert "With the voxel memory in DRAM" not in text
    frame = {"part": "MT41K256M16", "controller_mhz": 75.0, "pipeline_mhz": 137.7, "peak_mb_per_s": 600.0,
             "ideal_memory_cycles": 1000, "cycles": 2000, "ideal_over_dram": 0.5, "bursts_read": 30,
             "mb_per_s": 550.0, "stall_refresh": 10, "stall_row_open": 20, "stall_bandwidth": 970,
             "bit_identical_to_fixed_golden": False}
    dram = skipping.write_md(rows, None, {"git": "test"}, None, [dict(frame, schedule="box")])
    line = next(x for x in dram.splitlines() if x.startswith("| box |"))
    assert line.startswith("| box | 1,000 | 2,000 | 0.500 |") and "| 10 / 20 / 970 | DIFFERENT |" in line
    with pytest.raises(SystemExit, match="run make skipping first"):
        skipping.main(["--md-only", "--out", str(tmp_path)])
    run = {"meta": {"git": "test"}, "rows": rows, "rtl": None, "rtl_rects": None, "rtl_dram": None,
           "front_end": [], "beats": [], "taus": [], "blocks": [], "rtl_beats": []}
    (tmp_path / "skipping.json").write_text(json.dumps(run))
    assert skipping.main(["--md-only", "--out", str(tmp_path)]) == 0
    assert (tmp_path / "skipping.md").read_text() == text


@pytest.mark.parametrize("d", VIEWS)
def test_cut_cells_against_the_corners(d):
    """A cell is cut whole exactly when E < 0 at all eight of its corners (E is affine in
    the sample position; its largest value over the cell is at a corner), evaluated here
    one corner at a time in the traversal frame."""
    rng = np.random.default_rng(7)
    dims = (7, 6, 5)
    trav = make_traversal(dims, d, 8, 1)
    plane = cut_coefficients(trav, rng.normal(size=3), rng.uniform(0, 6, size=3))
    got = skip.cut_cells(trav, plane)
    ca, cb, cc, cd = plane
    W = trav.weight_bits
    for z in range(dims[2]):
        for y in range(dims[1]):
            for x in range(dims[0]):
                vals = []
                for dz in (0, 1):
                    for dy in (0, 1):
                        for dx in (0, 1):
                            u = {}
                            for ax, c, dc in ((0, x, dx), (1, y, dy), (2, z, dz)):
                                v = c + dc
                                u[ax] = (dims[ax] - 1 - v) if trav.flip[ax] else v
                            vals.append(ca * (u[trav.axis_i] << W) + cb * (u[trav.axis_j] << W)
                                        + cc * (u[trav.major] << W) + cd)
                assert got[z, y, x] == (max(vals) < 0), (x, y, z)


def test_cut_plane_shrinks_the_box():
    """head_cut: the cut removes half the head, the box follows, the image is the same."""
    from cube4.app.volumes import load_volume
    from cube4.host import config_for, plan_view
    from cube4.scene import load_scene

    vol = load_volume("head:48")
    scene = load_scene("head_cut")
    cfg = config_for(scene, 8)
    cut = plan_view(vol, scene, cfg).plans[0].fraction
    uncut = plan_view(vol, dataclasses.replace(scene, cut=None), cfg).plans[0].fraction
    assert cut < 0.8 * uncut, (cut, uncut)
    on, off = render(vol, scene, cfg, "golden"), render(vol, dataclasses.replace(scene, skip=False), cfg, "golden")
    assert np.array_equal(on.frame.baseplane, off.frame.baseplane)


@pytest.mark.parametrize("direction", [(0.3, -0.45, 1.0), (1.0, 1.0, 1.0), (1.0, -1.0, 0.0)])
def test_path_weights_with_skipping(direction):
    """Material on some of the volume's faces and not on others: the empty-space box has
    volume faces and interior faces (FACES from sub_traversal), and the path-weighted
    frame with the box schedule equals the fixed schedule's bit for bit."""
    rng = np.random.default_rng(7)
    vol = np.zeros((24, 26, 22), dtype=np.uint16)
    vol[:18, 5:, :15] = rng.integers(60, 256, size=(18, 21, 15))
    doc = {"transfer": TF, "view": {"direction": list(direction)}, "output": {"width": 40},
           "render": {"path_weights": True}}
    scene = parse_scene(doc)
    cfg = Cube4Config(pipelines=4)
    on = render(vol, scene, cfg, "golden")
    off = render(vol, dataclasses.replace(scene, skip=False), cfg, "golden")
    plain = render(vol, dataclasses.replace(scene, skip=False, path_weights=False), cfg, "golden")
    assert on.stats["cycles_saved"] > 0
    assert np.array_equal(on.frame.baseplane, off.frame.baseplane)
    assert not np.array_equal(off.frame.baseplane, plain.frame.baseplane)

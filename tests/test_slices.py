"""Slice rectangles (cube4.slices, docs/numerics.md §18), the specification of skipping
finer than the box: each sample slice computes only its own rectangle. The base plane is
the fixed schedule's bit for bit in every mode, view, S, with cut planes; each ray leaves
once, with the fixed schedule's value; each ray is inside on one run of slices; the
stencil and the envelopes are needed (without them the same checks fail); with every
rectangle the whole box the beats are the fixed schedule's."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from cube4_testutil import SKIP_VIEWS, rays_agree, sparse_case

import cube4.slices as slices
from cube4.app.render import render, render_golden_view
from cube4.app.volumes import load_volume
from cube4.config import Cube4Config
from cube4.cycles import FILL_CYCLES_UNSHADED, frame_cycles
from cube4.host import config_for, crop_volume, memory_volume, pass_rects, plan_view
from cube4.model import inside_mask, render_frame
from cube4.scene import load_scene
from cube4.view import make_traversal

SEEDS = range(40)


def frames(seed: int, gra=None):
    """The fixed schedule's frame and the slice rectangles' frame of one sparse case."""
    vol, trav, cfg, lut, rmap, mode, shading, clip = sparse_case(seed)
    uses_gra = shading and mode == "composite"
    rects = slices.plan_rects(vol, trav, lut, mode, gra=uses_gra if gra is None else gra, clip=clip)
    kw = dict(mode=mode, shading=shading, clip=clip)
    full = render_frame(vol, trav, cfg, lut, rmap, **kw)
    part = render_frame(vol, trav, cfg, lut, rmap, rects=rects, **kw)
    return full, part, rects


def mismatches(seeds, gra=None) -> list[int]:
    bad = []
    for seed in seeds:
        full, part, _ = frames(seed, gra)
        if not (np.array_equal(full.baseplane, part.baseplane) and rays_agree(full, part)):
            bad.append(seed)
    return bad


def test_slice_rects_are_bit_exact():
    """Every mode, shaded and unshaded, S = 1, 2, 4, seven views (45° and (1, 1, 1) among
    them), cut planes: the rectangles' base plane and rays are the fixed schedule's, and
    the rectangles hold fewer samples than the box in most cases."""
    assert mismatches(SEEDS) == []
    smaller = sum(frames(seed)[2].fraction() < 1.0 for seed in SEEDS)
    assert smaller >= len(SEEDS) // 2, smaller


def test_gra_stencil_is_needed():
    """Rectangles of the counting samples alone (no room for GRA's stencil) change some
    shaded images: the exactness test can fail."""
    shaded = [s for s in SEEDS if sparse_case(s)[6] and sparse_case(s)[5] == "composite"]
    assert mismatches(shaded, gra=False), "dropping the stencil changed no image"


def two_blobs():
    """Two dense blobs on the same rays with empty slices between them, seen along z."""
    vol = np.zeros((30, 16, 16), dtype=np.int64)
    vol[3:7, 4:9, 4:9] = 200
    vol[22:26, 7:12, 7:12] = 120
    lut = np.zeros((256, 4), dtype=np.int64)
    lut[100:] = (200, 150, 100, 40)
    trav = make_traversal((16, 16, 30), (0.2, 0.15, 1.0), 8, 1)
    return vol, trav, lut


def test_envelopes_are_needed(monkeypatch):
    """Without the envelopes the rectangles shrink between the blobs and grow again: the
    rays that cross both leave twice, and the picture loses the second blob behind the
    first. With them every ray leaves once and the image is exact."""
    vol, trav, lut = two_blobs()
    cfg = Cube4Config(pipelines=4)
    full = render_frame(vol, trav, cfg, lut, None, shading=False)

    def with_rects():
        rects = slices.plan_rects(vol, trav, lut, "composite", gra=False)
        return render_frame(vol, trav, cfg, lut, None, shading=False, rects=rects)

    assert np.array_equal(with_rects().baseplane, full.baseplane) and rays_agree(full, with_rects())
    monkeypatch.setattr(slices, "_envelope", lambda v, valley: v)
    bad = with_rects()
    assert not rays_agree(full, bad)


def ray_runs_ok(rects: slices.SliceRects) -> bool:
    """Every ray (base-plane pixel) is inside on one run of consecutive slices."""
    t = rects.trav
    rows, cols = t.baseplane_shape
    sxm, sym = t.max_steps
    state = np.zeros((rows, cols), dtype=np.int8)   # 0 before, 1 in the run, 2 after

    for m in range(t.num_sample_slices):
        sx, sy = (int(v) for v in t.steps(m))
        ins = np.zeros((rows, cols), dtype=bool)
        ins[sym - sy:sym - sy + t.nj, sxm - sx:sxm - sx + t.ni] = inside_mask(t, m) & rects.inside(m)
        if (ins & (state == 2)).any():
            return False
        state[(state == 1) & ~ins] = 2
        state[ins] = 1
    return True


@pytest.mark.parametrize("direction", SKIP_VIEWS)
@pytest.mark.parametrize("S", [1, 2, 4])
def test_each_ray_runs_once(direction, S):
    """Random sets of needed samples (sparse specks, several per slice): the rectangles
    hold them with the voxels they read, and each ray is inside on one run of slices."""
    rng = np.random.default_rng(S)
    for _ in range(6):
        dims = tuple(int(n) for n in rng.integers(5, 14, size=3))
        trav = make_traversal(dims, direction, 8, S)
        need = rng.random((trav.num_sample_slices, trav.nj, trav.ni)) < 0.01
        rects = slices.rects_from_needed(need, trav)
        for m in range(trav.num_sample_slices):
            js, is_ = np.nonzero(need[m])
            if js.size:
                j0, j1, i0, i1 = rects.bounds(m)
                assert j0 <= js.min() and min(trav.nj, js.max() + 2) <= j1, (m, rects.bounds(m), js, is_)
                assert i0 <= is_.min() and min(trav.ni, is_.max() + 2) <= i1, (m, rects.bounds(m), js, is_)
        assert ray_runs_ok(rects)


@pytest.mark.parametrize("p", [1, 5, 8])
def test_whole_box_is_the_fixed_schedule(p):
    """Everything needed: every rectangle is the whole box, and the beats are the fixed
    schedule's, (M·NJ + 1)·NB + 1 (the cycle formula less its fill and GRA's flush)."""
    trav = make_traversal((13, 11, 9), (0.3, -0.45, 1.0), 8, 2)
    M = trav.num_sample_slices
    rects = slices.rects_from_needed(np.ones((M, trav.nj, trav.ni), dtype=bool), trav)
    nb = -(-trav.ni // p)
    assert rects.beats(p) == (M * trav.nj + 1) * nb + 1
    assert rects.beats(p) == frame_cycles(M, trav.nj, trav.ni, p, shading=False) - FILL_CYCLES_UNSHADED
    assert rects.fraction() == 1.0


@pytest.mark.parametrize("scene_name", ["head", "head_unshaded", "head_cut", "head_minip", "head_quality"])
def test_head_scenes(scene_name):
    """The head phantom's scenes (GRA, unshaded, a cut plane, MinIP, voxel gradients with
    S = 4): within the empty-space box, the rectangles' frame equals the box's frame bit
    for bit, in fewer beats than the box's cycles wherever the box is not already tight."""
    vol = load_volume("head:64")
    scene = load_scene(scene_name)
    cfg = config_for(scene, 4)
    vp = plan_view(vol, dataclasses.replace(scene, subpixel=1), cfg)
    plan, rects = vp.plans[0], pass_rects(vol, vp)[0]
    mem = plan.box_volume(crop_volume(memory_volume(vol, scene, cfg), vp.trav))
    kw = dict(mode=scene.mode, shading=scene.shaded, clip=plan.clip, vgrad=scene.voxel_gradients)
    box = render_frame(mem, plan.trav, cfg, vp.lut, vp.rmap, **kw)
    part = render_frame(mem, plan.trav, cfg, vp.lut, vp.rmap, rects=rects, **kw)
    assert np.array_equal(box.baseplane, part.baseplane)
    assert rays_agree(box, part)
    if scene.mode != "minip":          # MinIP counts most values: the box is the rectangles
        assert rects.beats(cfg.pipelines) < plan.cycles(cfg.pipelines, scene.shaded, scene.voxel_gradients)


def test_golden_engine_with_rects():
    """The golden engine's rects switch: the view's image and base plane as with the box
    schedule and with the fixed schedule, and the beats in the stats (q×q passes: one
    set of rectangles per pass)."""
    vol = load_volume("head:48")
    scene = dataclasses.replace(load_scene("head"), subpixel=2, skip=True)     # the box
    cfg = config_for(scene, 8)
    on = render_golden_view(vol, scene, cfg, rects=True)
    box = render(vol, scene, cfg, "golden")
    fixed = render(vol, dataclasses.replace(scene, skip=False), cfg, "golden")
    assert np.array_equal(on.frame.baseplane, box.frame.baseplane)
    assert np.array_equal(on.frame.baseplane, fixed.frame.baseplane)
    assert np.array_equal(on.image, box.image)
    assert 0 < on.stats["rect_beats"] < box.stats["predicted_cycles"]


@pytest.mark.parametrize("direction", SKIP_VIEWS)
@pytest.mark.parametrize("p", [1, 5, 8])
def test_gra_walk(direction, p):
    """GRA's walk (SliceRects.walk with gra): every slice up to the last walks its own
    traversed rectangle and the rows T(m-1).j0 .. T(m-1).j1 over T(m-1)'s partial beams
    (at most row NJ), and the partial beam below T(m-1)'s first where T(m-2) reaches it;
    nothing more than their bounding rectangle. Without GRA the walk is the traversed
    rectangle. The beats count the walks; GRA's own steps finish the last slice."""
    rng = np.random.default_rng(7 * p)
    trav = make_traversal((13, 11, 9), direction, 8, 1)
    for density in (0.003, 0.02, 0.2):
        need = rng.random((trav.num_sample_slices, trav.nj, trav.ni)) < density
        plain = slices.rects_from_needed(need, trav)
        walked = dataclasses.replace(plain, gra=True)
        last = plain.last()
        for m in range(last + 1):
            t, prev, prev2 = plain.beams(m, p), plain.beams(m - 1, p), plain.beams(m - 2, p)
            assert plain.walk(m, p) == t
            w = walked.walk(m, p)
            parts = [b for b in (t, prev and (prev[0], min(prev[1] + 1, trav.nj + 1), prev[2], prev[3]))
                     if b is not None]
            if not parts:
                assert w is None
                continue
            want = [min(b[0] for b in parts), max(b[1] for b in parts),
                    min(b[2] for b in parts), max(b[3] for b in parts)]
            if prev is not None and prev2 is not None:
                want[2] = min(want[2], max(prev2[2], prev[2] - 1))
            assert w == tuple(want), (m, w, want)
            assert w[1] <= trav.nj + 1
        if last >= 0:
            assert walked.beats(p) >= plain.beats(p)
            j0, j1, pb0, pb1 = walked.walk(last, p)
            assert walked.gra_steps(p) == (min(j1, trav.nj) - j0 + 1) * (pb1 - pb0 + 1) + 3
            assert len(walked.emitted(p)) == sum((w[1] - w[0]) * (w[3] - w[2] + 1)
                                                  for w in (walked.walk(m, p) for m in range(last + 1)) if w)


@pytest.mark.parametrize("scene_name", ["head", "head_unshaded", "head_xray"])
def test_head_scenes_need_no_com_wait(scene_name):
    """On the head phantom's scenes no beat waits in COM (SliceRects.com_waits): the cycle
    prediction of a rectangle frame (cycles.rect_frame_cycles) is exact there."""
    vol = load_volume("head:64")
    scene = load_scene(scene_name)
    vp = plan_view(vol, scene, config_for(scene, 8))
    rects = dataclasses.replace(pass_rects(vol, vp)[0], gra=scene.shaded)
    assert rects.com_waits(8) == 0

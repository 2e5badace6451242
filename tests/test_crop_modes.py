"""Crop modes (cube4.clip, docs/numerics.md §12): the box's three slabs cut the volume into
27 regions and VTK's flags keep some. The traversal-frame regions equal the rule in the
volume's own coordinates at every sample's position for every view (flips, 45°,
(1, 1, 1)); sub-frames (the empty-space box, bricks) keep the same samples; the
empty-space box skips what no kept region reaches, with the same image; the golden
model stays near the float64 reference; bad scenes are one line."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from cube4_testutil import SKIP_VIEWS, psnr_vs_point

from cube4.app.render import render, render_bricked_views
from cube4.app.volumes import load_volume
from cube4.clip import CROP_MODES, Clip, crop_regions, fit_regions, move_regions, region_keep
from cube4.config import Cube4Config
from cube4.errors import UserError
from cube4.host import config_for, golden_view
from cube4.scene import load_scene, parse_scene
from cube4.view import make_traversal, sub_traversal


def volume_position(trav, m, jj, ii):
    """Each sample's position in volume coordinates (x, y, z): (N, 3) float."""
    wx, wy, _ = (int(w) for w in trav.weights(m))
    W = trav.weight_bits
    u = {trav.axis_i: ii + wx / (1 << W), trav.axis_j: jj + wy / (1 << W),
         trav.major: np.full(ii.shape, m / trav.supersample)}
    out = []
    for ax in range(3):
        n = trav.dims[ax]
        out.append(trav.origin[ax] + ((n - 1) - u[ax] if trav.flip[ax] else u[ax]))
    return np.stack(out, axis=-1)


def kept_by_rule(pos, lo, hi, flags):
    r = np.where(pos < np.asarray(lo), 0, np.where(pos > np.asarray(hi), 2, 1))
    return ((flags >> (r[..., 0] + 3 * r[..., 1] + 9 * r[..., 2])) & 1).astype(bool)


@pytest.mark.parametrize("direction", SKIP_VIEWS + [(-1.0, 1.0, -1.0), (0.2, -1.0, -0.3)])
@pytest.mark.parametrize("S", [1, 2, 4])
def test_regions_follow_the_volume_rule(direction, S):
    """Every sample of every slice: the traversal-frame regions keep it exactly when the
    rule in volume coordinates does, for each mode and random flags."""
    rng = np.random.default_rng(S)
    dims = (9, 7, 11)
    trav = make_traversal(dims, direction, 8, S)
    lo, hi = (2, 1, 3), (6, 4, 7)
    for flags in list(CROP_MODES.values()) + [int(rng.integers(0, 1 << 27)) for _ in range(3)]:
        regions = crop_regions(trav, lo, hi, flags)
        jj, ii = np.mgrid[0:trav.nj, 0:trav.ni]
        for m in range(trav.num_sample_slices):
            got = region_keep(regions, trav, m, jj, ii)
            want = kept_by_rule(volume_position(trav, m, jj, ii), lo, hi, flags)
            assert np.array_equal(got, want), (flags, m)


@pytest.mark.parametrize("direction", SKIP_VIEWS)
def test_sub_frames_keep_the_same_samples(direction):
    """A box inside the frame (the empty-space box, a brick) with the regions moved and
    fitted keeps the samples the whole frame keeps there, planes outside it included."""
    rng = np.random.default_rng(5)
    dims = (12, 10, 9)
    trav = make_traversal(dims, direction, 8, 2)
    for _ in range(6):
        flags = int(rng.integers(0, 1 << 27))
        lo = tuple(int(rng.integers(0, n)) for n in dims)
        hi = tuple(int(rng.integers(a, n)) for a, n in zip(lo, dims))
        whole = crop_regions(trav, lo, hi, flags)
        s0 = tuple(int(rng.integers(0, n - 3)) for n in dims)
        s1 = tuple(int(rng.integers(a + 2, n + 1)) for a, n in zip(s0, dims))
        sub, _, start = sub_traversal(trav, s0, s1)
        part = fit_regions(move_regions(whole, start, 2), sub)
        i0, j0, k0 = start
        for m in range(sub.num_sample_slices):
            jj, ii = np.mgrid[0:sub.nj, 0:sub.ni]
            got = region_keep(part, sub, m, jj, ii)
            want = region_keep(whole, trav, m + k0 * 2, jj + j0, ii + i0)
            assert np.array_equal(got, want)


def crop_scene(mode: str, scene="head", **extra):
    sc = load_scene(scene)
    return dataclasses.replace(sc, crop=((4, 5, 6), (14, 13, 12)), crop_regions=CROP_MODES[mode], **extra)


@pytest.mark.parametrize("mode", ["fence", "inverted_fence", "cross", "inverted_cross"])
def test_skipping_and_bricks_keep_the_image(mode):
    """The empty-space box (which drops the cells no kept region reaches) and bricks give
    the fixed schedule's base plane."""
    vol = load_volume("head:20")
    sc = crop_scene(mode)
    cfg = config_for(sc, 4)
    _, full, st_full = golden_view(vol, dataclasses.replace(sc, skip=False), cfg)
    _, boxed, st_box = golden_view(vol, sc, cfg)
    assert np.array_equal(full.baseplane, boxed.baseplane)
    assert st_box["predicted_cycles"] <= st_full["predicted_cycles"]
    whole = render(vol, sc, cfg, "golden")
    (bricked,) = render_bricked_views(vol, [sc], cfg, "golden", (2, 1, 2))
    assert np.abs(whole.image - bricked.image).max() < 2e-3


def test_inverted_fence_skips_the_middle():
    """With only the corners kept and the rest of the volume empty, the box is smaller."""
    vol = load_volume("head:32")
    sc = dataclasses.replace(load_scene("head"), crop=((0, 0, 0), (20, 20, 20)),
                             crop_regions=CROP_MODES["subvolume"])
    cfg = config_for(sc, 4)
    _, _, st = golden_view(vol, sc, cfg)
    _, _, st_all = golden_view(vol, dataclasses.replace(sc, crop=None, crop_regions=None), cfg)
    assert st["predicted_cycles"] < st_all["predicted_cycles"]


def test_golden_near_the_reference():
    """A crop mode costs no accuracy: PSNR against the reference (its centre points) as
    without the mode, within 3 dB; and the mode changes the picture."""
    vol = load_volume("head:32")
    sc = dataclasses.replace(load_scene("head"), width=48, height=48,
                             crop=((8, 6, 10), (22, 26, 20)), crop_regions=CROP_MODES["inverted_cross"])
    cfg = config_for(sc, 4)
    plain = dataclasses.replace(sc, crop=None, crop_regions=None)

    assert psnr_vs_point(vol, sc, cfg) > psnr_vs_point(vol, plain, cfg) - 3.0
    assert np.abs(render(vol, sc, cfg, "golden").image - render(vol, plain, cfg, "golden").image).max() > 0.05


def test_scene_keys():
    box = {"box": [[1, 2, 3], [5, 6, 7]]}
    assert parse_scene({"crop": dict(box)}).crop_regions is None
    assert parse_scene({"crop": {**box, "mode": "subvolume"}}).crop_regions is None
    assert parse_scene({"crop": {**box, "mode": "cross"}}).crop_regions == CROP_MODES["cross"]
    assert parse_scene({"crop": {**box, "regions": 5}}).crop_regions == 5
    for bad, msg in (({**box, "mode": "donut"}, "crop.mode must be one of"),
                     ({**box, "regions": 1 << 27}, "crop.regions must be an integer"),
                     ({**box, "regions": 3, "mode": "fence"}, "not both"),
                     ({"mode": "fence"}, "need crop.box")):
        with pytest.raises(UserError, match=msg):
            parse_scene({"crop": bad})


def test_clip_keeps_regions_with_window_and_plane():
    """Regions combine with the window and the plane (AND)."""
    trav = make_traversal((8, 8, 8), (0.3, 0.2, 1.0), 8, 1)
    regions = crop_regions(trav, (2, 2, 2), (5, 5, 5), CROP_MODES["fence"])
    c = Clip(window=(0, 4, 0, 8, 0, 8), regions=regions)
    jj, ii = np.mgrid[0:8, 0:8]
    for m in range(8):
        assert np.array_equal(c.keep(trav, m), region_keep(regions, trav, m, jj, ii) & (ii < 4))


def test_crop_modes_need_the_clip_unit():
    """A scene with crop regions gets a build with CLIP = 1; the crop box alone does not."""
    from cube4.config import scene_build
    assert scene_build([crop_scene("cross")])["CLIP"] == 1
    plain = dataclasses.replace(load_scene("head"), crop=((4, 5, 6), (14, 13, 12)))
    assert scene_build([plain])["CLIP"] == 0


def test_builtin_scenes_of_each_mode():
    """A built-in scene per crop mode (head_crop_<mode>), each the same scene with its mode;
    subvolume traverses the box alone (no regions, no clip unit)."""
    from cube4.config import scene_build
    base = load_scene("head_crop_inverted_cross")
    for mode in ("subvolume", "fence", "inverted_fence", "cross", "inverted_cross"):
        sc = load_scene(f"head_crop_{mode}")
        assert sc.crop == base.crop and np.array_equal(sc.tf_points, base.tf_points), mode
        assert sc.crop_regions == (None if mode == "subvolume" else CROP_MODES[mode]), mode
        assert scene_build([sc])["CLIP"] == int(mode != "subvolume"), mode

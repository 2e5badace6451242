"""Preview levels (cube4.levels, docs/numerics.md §20): the level is the rounded mean of
each F³ block; its camera puts every level voxel where the block it stands for is; a
preview frames the same picture in about F³ times fewer cycles, near the full
resolution's; the reference stays the whole volume's truth; bad requests are one line."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from cube4.app.render import render, render_bricked_views
from cube4.app.volumes import load_volume
from cube4.errors import UserError
from cube4.host import config_for, golden_view
from cube4.levels import level_dims, level_volume
from cube4.scene import load_scene, parse_scene
from cube4.view import level_camera, make_camera


@pytest.mark.parametrize("shape", [(8, 8, 8), (7, 10, 5), (1, 3, 9)])
@pytest.mark.parametrize("f", [2, 4])
def test_level_is_the_rounded_block_mean(shape, f):
    rng = np.random.default_rng(f)
    vol = rng.integers(0, 4096, size=shape).astype(np.uint16)
    lv = level_volume(vol, f)
    assert lv.dtype == vol.dtype and lv.shape == tuple(-(-n // f) for n in shape)
    for z, y, x in np.ndindex(lv.shape):
        zz = [min(c, shape[0] - 1) for c in range(f * z, f * z + f)]
        yy = [min(c, shape[1] - 1) for c in range(f * y, f * y + f)]
        xx = [min(c, shape[2] - 1) for c in range(f * x, f * x + f)]
        block = vol[np.ix_(zz, yy, xx)].astype(np.int64)
        assert lv[z, y, x] == (2 * block.sum() + block.size) // (2 * block.size)


@pytest.mark.parametrize("dims", [(64, 64, 64), (33, 41, 25)])
@pytest.mark.parametrize("f", [2, 4])
def test_level_camera_puts_each_voxel_at_its_block(dims, f):
    cam = make_camera(dims, (0.3, -0.5, 0.8), 200, 150)
    lcam = level_camera(cam, level_dims(dims, f), f)
    rng = np.random.default_rng(0)
    u = rng.uniform(0, 20, size=(50, 3))
    assert np.allclose(lcam.project(u), cam.project(f * u + (f - 1) / 2.0))


def test_preview_frames_the_same_picture_in_fewer_cycles():
    """head:64 at ½ and ¼: about 8× and 64× fewer cycles than the fixed schedule, the alpha
    centroid within a pixel of the full resolution's, the picture near it."""
    vol = load_volume("head:64")
    sc = dataclasses.replace(load_scene("head"), width=96, height=96)
    cfg = config_for(sc, 4)
    full = render(vol, sc, cfg, "golden")

    def centroid(img):
        a = img[..., 3]
        yy, xx = np.mgrid[0:a.shape[0], 0:a.shape[1]]
        return np.array([(xx * a).sum(), (yy * a).sum()]) / a.sum()

    for f, most in ((2, 1 / 6), (4, 1 / 40)):
        pv = render(vol, dataclasses.replace(sc, preview=f), cfg, "golden")
        assert pv.stats["preview"] == f and pv.stats["traversed_box"]["dims"] == [64 // f] * 3
        assert pv.stats["predicted_cycles"] < most * full.stats["fixed_schedule_cycles"]
        assert np.abs(centroid(pv.image) - centroid(full.image)).max() < 1.0
        err = pv.image - full.image
        assert -20 * np.log10(np.sqrt(np.mean(err * err))) > 20.0


def test_reference_is_the_whole_volume():
    """The reference engine renders the volume itself: a preview is measured against the
    full resolution's truth."""
    vol = load_volume("head:16")
    sc = dataclasses.replace(load_scene("head"), width=32, height=32)
    cfg = config_for(sc, 4)
    a = render(vol, sc, cfg, "reference-point").image
    b = render(vol, dataclasses.replace(sc, preview=2), cfg, "reference-point").image
    assert np.array_equal(a, b)


def test_bad_requests():
    vol = load_volume("head:16")
    sc = load_scene("head")
    cfg = config_for(sc, 4)
    with pytest.raises(UserError, match="render.preview must be one of 1, 2, 4"):
        parse_scene({"render": {"preview": 3}})
    assert parse_scene({"render": {"preview": 4}}).preview == 4
    with pytest.raises(UserError, match="renders the whole volume"):
        golden_view(vol, dataclasses.replace(load_scene("head_minip"), preview=2), cfg)
    with pytest.raises(UserError, match="does not run in bricks"):
        render_bricked_views(vol, [dataclasses.replace(sc, preview=2)], cfg, "golden", (2, 1, 1))
    with pytest.raises(UserError, match="one preview level"):
        from cube4.host import build_memory
        build_memory(vol, [sc, dataclasses.replace(sc, preview=2)], cfg, {"VGRAD": 0})


def test_builtin_preview_scene():
    """head_preview is head at its ½ level: the same scene otherwise."""
    pv, full = load_scene("head_preview"), load_scene("head")
    assert pv.preview == 2
    for f in dataclasses.fields(full):
        if f.name not in ("preview", "name"):
            a, b = getattr(pv, f.name), getattr(full, f.name)
            assert repr(a) == repr(b), f.name

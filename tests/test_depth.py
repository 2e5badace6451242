"""Depth out (docs/numerics.md §21): per ray the slice after which its opacity passes the
scene's threshold and the slice of its first sample that adds something (MIP / MinIP: the
held sample's and the first counted sample's), as distances along the view direction from
the volume's centre, in the image by the nearest base-plane pixel. The front face of a
hard-edged cube lies where it is, from every side; the empty-space box and the q×q passes
keep the depths; a ray passes exactly when its base-plane opacity reaches the threshold;
bad keys and engines that do not write depth are one line."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from cube4.app.render import render, render_bricked_views
from cube4.app.volumes import load_volume
from cube4.errors import UserError
from cube4.host import config_for, depth_threshold, golden_view
from cube4.scene import parse_scene

CUBE_SCENE = {
    "output": {"width": 64, "depth_threshold": 0.5},
    "light": [{"headlight": True}],
    "transfer": {"points": [[0.0, 0, 0, 0, 0.0], [0.3, 1, 1, 1, 0.0], [0.6, 1, 1, 1, 0.95], [1.0, 1, 1, 1, 0.95]]},
}


def cube_scene(direction, **extra):
    return dataclasses.replace(parse_scene({**CUBE_SCENE, "view": {"direction": list(direction)}}), **extra)


@pytest.mark.parametrize("direction", [(0.0, 0.0, 1.0), (0.0, 0.0, -1.0), (1.0, 0.0, 0.0), (0.0, -1.0, 0.0),
                                       (0.05, 0.03, 1.0)])
def test_cube_front_face(direction):
    """cube:32 fills [8, 24) along every axis: viewed along an axis its front face lies 8 voxels
    before the centre (15.5), less half a voxel where the interpolant rises; the passed depth
    at the image centre is within one sample of it, and the first sample is not behind it."""
    vol = load_volume("cube:32")
    sc = cube_scene(direction)
    res = render(vol, sc, config_for(sc, 4), "golden")
    h, w = res.depth.shape[:2]
    passed, first = res.depth[h // 2, w // 2]
    assert abs(passed - (-7.5)) <= 1.0, passed
    assert first <= passed + 1e-9
    assert res.stats["depth"]["passed"]["pixels"] > 0.05     # the face: 16² of the image's ~55² voxels


def test_depth_follows_the_baseplane_opacity():
    """A ray has a passed depth exactly when its base-plane A reaches the threshold, and its
    first sample never lies behind its passed depth; the box schedule and the q×q passes
    give the fixed schedule's depths."""
    vol = load_volume("head:24")
    sc = cube_scene((0.3, -0.45, 1.0))
    sc = dataclasses.replace(sc, tf_points=np.array([[0, 0, 0, 0, 0], [0.2, 1, 0.5, 0.3, 0.1], [1, 1, 1, 1, 0.6]]))
    cfg = config_for(sc, 4)
    _, fixed, _ = golden_view(vol, dataclasses.replace(sc, skip=False), cfg)
    _, boxed, _ = golden_view(vol, sc, cfg)
    assert np.array_equal(np.isnan(fixed.depth_z), np.isnan(boxed.depth_z))
    assert np.allclose(np.nan_to_num(fixed.depth_z), np.nan_to_num(boxed.depth_z))
    t = (1 << cfg.acc_bits) - fixed.baseplane[..., 3]
    assert np.array_equal(np.isfinite(fixed.depth_z[..., 0]), t <= depth_threshold(sc, cfg))
    both = np.isfinite(fixed.depth_z).all(axis=-1)
    assert both.any() and (fixed.depth_z[both, 1] <= fixed.depth_z[both, 0] + 1e-9).all()
    _, fine, _ = golden_view(vol, dataclasses.replace(sc, subpixel=2), cfg)
    assert fine.depth_z.shape[:2] == fine.baseplane.shape[:2]
    assert np.isfinite(fine.depth_z[..., 0]).sum() > 3 * np.isfinite(fixed.depth_z[..., 0]).sum()


def test_mip_depth_is_the_held_sample():
    """MIP: the passed depth is the held (largest) sample's slice, the first the first counted one,
    on the box and on the beat schedule (whose rays, holding the volume's largest value, would
    end at the first of the cube's largest: with depth out MIP ends none)."""
    vol = load_volume("cube:24")
    for skip in (True, "beats"):
        sc = dataclasses.replace(cube_scene((0.0, 0.0, 1.0), mode="mip"), skip=skip)
        res = render(vol, sc, config_for(sc, 4), "golden")
        h, w = res.depth.shape[:2]
        passed, first = res.depth[h // 2, w // 2]
        assert first < passed and abs(passed - 5.5) <= 1.0, (skip, first, passed)   # the last of the cube's largest


def test_keys_and_engines():
    assert parse_scene({"output": {"depth_threshold": 0.25}}).depth_threshold == 0.25
    assert parse_scene({}).depth_threshold is None
    for bad in (0, 1.5, "x"):
        with pytest.raises(UserError, match="output.depth_threshold"):
            parse_scene({"output": {"depth_threshold": bad}})
    vol = load_volume("cube:16")
    sc = cube_scene((0.0, 0.0, 1.0))
    with pytest.raises(UserError, match="not rendered in bricks"):
        render_bricked_views(vol, [sc], config_for(sc, 1), "golden", (2, 1, 1))


def test_exr_has_the_depth_channels(tmp_path):
    import OpenImageIO as oiio
    from cube4.app.images import write_image

    rgba = np.zeros((4, 5, 4))
    depth = np.full((4, 5, 2), np.nan)
    depth[1, 2] = (3.0, 2.5)
    write_image(str(tmp_path / "d.exr"), rgba, depth=depth)
    buf = oiio.ImageBuf(str(tmp_path / "d.exr"))
    assert tuple(buf.spec().channelnames) == ("R", "G", "B", "A", "Z", "Zfirst")
    px = buf.get_pixels(oiio.FLOAT)
    assert tuple(px[1, 2, 4:]) == (3.0, 2.5) and np.isinf(px[0, 0, 4])

"""The cut slab (cube4.clip, docs/numerics.md §12): two parallel faces and a linear falloff of
opacity inside each. The traversal-frame registers keep a sample exactly when its position
in volume coordinates lies within the slab, for every view (flips, 45°, (1, 1, 1)) and S;
the falloff weight is floor(256 d / F) of the distance d inside the nearer face, up to the
rounding of the plane's coefficients; the empty-space box drops the cells beyond either face
with the same image, bricks keep it; the golden model stays near the float64 reference; the
scene's keys and their errors are one line; the build a slab scene gets has SLAB = 1."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from cube4_testutil import SKIP_VIEWS, psnr_vs_point

from cube4.app.render import render, render_bricked_views
from cube4.app.volumes import load_volume
from cube4.clip import FALL_ONE, Clip, slab_coefficients
from cube4.config import scene_build
from cube4.errors import UserError
from cube4.host import config_for, golden_view
from cube4.scene import load_scene, parse_scene
from cube4.view import make_traversal
from test_crop_modes import volume_position


def slab_distance(pos, normal, centre):
    n = np.asarray(normal, dtype=np.float64)
    n = n / np.linalg.norm(n)
    return (pos - np.asarray(centre, dtype=np.float64)) @ n


@pytest.mark.parametrize("direction", SKIP_VIEWS + [(-1.0, 1.0, -1.0), (0.2, -1.0, -0.3)])
@pytest.mark.parametrize("S", [1, 2, 4])
def test_slab_follows_the_volume_rule(direction, S):
    """Every sample: kept exactly when |n . (p - c)| <= t / 2 (but within a hair of a face,
    where the quantised plane decides), and its falloff weight within one step of
    256 (t / 2 - |n . (p - c)|) / F."""
    dims = (9, 7, 11)
    trav = make_traversal(dims, direction, 8, S)
    normal, centre = (0.4, -0.7, 0.55), (4.2, 3.1, 5.3)
    for thickness, falloff in ((4.0, 1.5), (2.5, 2.0), (6.0, 0.0)):
        plane, slab = slab_coefficients(trav, normal, centre, thickness, falloff)
        clip = Clip(plane=plane, slab=slab)
        jj, ii = np.mgrid[0:trav.nj, 0:trav.ni]
        for m in range(trav.num_sample_slices):
            inset = 0.5 * thickness - np.abs(slab_distance(volume_position(trav, m, jj, ii), normal, centre))
            keep = clip.keep(trav, m)
            sure = np.abs(inset) > 1e-3
            assert np.array_equal(keep[sure], inset[sure] >= 0), (thickness, m)
            f = clip.falloff(trav, m)
            if falloff == 0:
                assert f is None
                continue
            want = np.clip(FALL_ONE * inset / falloff, 0, FALL_ONE)
            assert np.abs(f[keep] - want[keep]).max() <= 1.01, (thickness, m)


def slab_scene(thickness=8.0, falloff=3.0, **extra):
    sc = load_scene("head_slab")
    n, c, _, _ = sc.slab
    return dataclasses.replace(sc, slab=(n, c * 20 / 64, thickness, falloff), **extra)


def test_skipping_and_bricks_keep_the_image():
    """The empty-space box (which drops the cells beyond either face) and bricks give the
    fixed schedule's base plane; the slab saves cycles."""
    vol = load_volume("head:20")
    sc = dataclasses.replace(slab_scene(6.0, 2.0), slab=((0.1, 0.0, 1.0), (9.5, 9.5, 9.5), 6.0, 2.0))
    cfg = config_for(sc, 4)
    _, full, st_full = golden_view(vol, dataclasses.replace(sc, skip=False), cfg)
    _, boxed, st_box = golden_view(vol, sc, cfg)
    assert np.array_equal(full.baseplane, boxed.baseplane)
    _, _, st_all = golden_view(vol, dataclasses.replace(sc, slab=None), cfg)
    assert st_box["predicted_cycles"] < st_all["predicted_cycles"]
    whole = render(vol, sc, cfg, "golden")
    (bricked,) = render_bricked_views(vol, [sc], cfg, "golden", (2, 1, 2))
    assert np.abs(whole.image - bricked.image).max() < 2e-3


def test_golden_near_the_reference():
    """The slab and its falloff cost no accuracy: PSNR against the reference (its centre
    points) at least that of the scene without them less 3 dB; and the falloff changes the
    picture."""
    vol = load_volume("head:32")
    sc = slab_scene(width=48, height=48)
    sc = dataclasses.replace(sc, slab=(sc.slab[0], np.array([15.5, 15.5, 15.5]), 8.0, 3.0))
    cfg = config_for(sc, 4)
    plain = dataclasses.replace(sc, slab=None)
    hard = dataclasses.replace(sc, slab=(*sc.slab[:3], 0.0))

    assert psnr_vs_point(vol, sc, cfg) > psnr_vs_point(vol, plain, cfg) - 3.0
    assert np.abs(render(vol, sc, cfg, "golden").image - render(vol, hard, cfg, "golden").image).max() > 0.02


def test_scene_keys():
    base = {"normal": [0, 0, 1], "center": [1, 2, 3], "thickness": 4}
    n, c, t, f = parse_scene({"slab": dict(base)}).slab
    assert (t, f) == (4.0, 0.0) and np.allclose(c, (1, 2, 3))
    assert parse_scene({"slab": {**base, "falloff": 1.5}}).slab[3] == 1.5
    for bad, msg in (({**base, "thickness": 0}, "slab.thickness must be > 0"),
                     ({**base, "falloff": 0.01}, "slab.falloff must be 0 or at least"),
                     ({"normal": [0, 0, 1], "center": [1, 2, 3]}, r"\[slab\] needs normal, center and thickness"),
                     ({**base, "width": 3}, "slab")):
        with pytest.raises(UserError, match=msg):
            parse_scene({"slab": bad})
    with pytest.raises(UserError, match=r"give \[cut\] or \[slab\], not both"):
        parse_scene({"slab": base, "cut": {"normal": [0, 0, 1], "point": [1, 1, 1]}})


def test_slab_needs_its_build():
    """A slab scene gets SLAB = 1 (and CLIP = 1); a cut plane does not need SLAB."""
    b = scene_build([slab_scene()])
    assert b["SLAB"] == 1 and b["CLIP"] == 1
    assert scene_build([load_scene("head_cut")])["SLAB"] == 0


def test_preview_refuses_a_slab():
    vol = load_volume("head:16")
    sc = dataclasses.replace(slab_scene(), preview=2)
    with pytest.raises(UserError, match=r"leave out \[crop\], \[cut\], \[slab\] and \[geometry\]"):
        golden_view(vol, sc, config_for(sc, 1))

"""Voxel gradients (cube4.vgrad, docs/numerics.md §5b): the memory word, the estimators'
bounds, the bit-exact model against the reference's estimator, and that skipping,
bricks, sub-pixel passes and the command line keep them exact."""

from __future__ import annotations

import dataclasses
import json
import subprocess
import sys

import numpy as np
import pytest
from cube4_testutil import BRICK_TF, brick_volume, make_scene, sphere_volume

from cube4.app.render import render, render_bricked_views
from cube4.app.volumes import load_volume
from cube4.bricks import make_grid, plan_bricks
from cube4.config import Cube4Config
from cube4.errors import UserError
from cube4.host import config_for, host_tables, image_metrics
from cube4.model import render_frame
from cube4.scene import load_scene
from cube4.vgrad import grad_bits, pack_words, unpack_words, voxel_gradients, word_bits
from cube4.view import make_traversal

VIEWS = [(0.3, -0.45, 1.0), (1.0, 1.0, 1.0), (-1.0, 0.5, 0.2), (1.0, -1.0, 0.0)]


@pytest.mark.parametrize("bits", [8, 12, 13])
@pytest.mark.parametrize("kind", ["central", "sobel"])
def test_word_round_trip_and_bounds(bits, kind):
    """The extreme volume (a checkerboard of 0 and full scale) reaches each estimator's
    bound, which fits the stored component; the word unpacks to what was packed."""
    top = (1 << bits) - 1
    z, y, x = np.indices((6, 7, 8))
    vol = np.where((x + y + z) % 2 == 0, 0, top)
    vol[:, :, :4] = top                     # a step as well: Sobel's largest sum
    g = voxel_gradients(vol, kind)
    bound = top if kind == "central" else 4 * top
    assert np.abs(g).max() == bound
    assert bound < 1 << (grad_bits(bits) - 1)
    words = pack_words(vol, kind, bits)
    assert int(words.max()).bit_length() <= word_bits(bits, True)
    value, comps = unpack_words(words, bits)
    assert np.array_equal(value, vol) and np.array_equal(comps, g)


def test_wide_voxels_are_refused():
    with pytest.raises(UserError, match="VOXEL_W <= 13"):
        pack_words(np.zeros((2, 2, 2), dtype=np.int64), "central", 14)


def test_sobel_is_central_smoothed():
    """Sobel = central differences smoothed (1, 2, 1) across, /4 with one rounding;
    on a linear ramp both are exact (Sobel 4x central)."""
    z, y, x = np.indices((9, 9, 9))
    ramp = 3 * x + 5 * y + 7 * z
    c = voxel_gradients(ramp, "central")[:, 2:-2, 2:-2, 2:-2]
    s = voxel_gradients(ramp, "sobel")[:, 2:-2, 2:-2, 2:-2]
    assert np.array_equal(c[0], np.full_like(c[0], 6)) and np.array_equal(c[2], np.full_like(c[2], 14))
    assert np.array_equal(s, 4 * c)


def _scene(gradient: str, **render_keys):
    return make_scene(render={"gradient": gradient, **render_keys}, transfer=BRICK_TF,
                      light=[{"direction": [1, -1, -1]}])


@pytest.mark.parametrize("gradient", ["central", "sobel"])
def test_skipping_and_subpixel_stay_exact(gradient):
    """The empty-space box and the q×q passes read the same memory words: the base plane
    with skipping equals the fixed schedule's, at several views and S."""
    vol = np.pad(sphere_volume(16).astype(np.int64), ((6, 2), (4, 5), (3, 7)))     # empty space around
    for n, d in enumerate(VIEWS):
        sc = dataclasses.replace(_scene(gradient), direction=np.asarray(d, float) / np.linalg.norm(d),
                                 supersample=(1, 2)[n % 2])
        cfg = config_for(sc, 4)
        a = render(vol, sc, cfg, "golden")
        b = render(vol, dataclasses.replace(sc, skip=False), cfg, "golden")
        assert a.stats["skip"] and a.stats["predicted_cycles"] < b.stats["predicted_cycles"]
        assert np.array_equal(a.frame.baseplane, b.frame.baseplane), d
    q2 = dataclasses.replace(_scene(gradient), subpixel=2)
    r = render(vol, q2, config_for(q2, 4), "golden")
    assert r.stats["frames"] == 4 and r.stats["build"]["VGRAD"] == 1


def test_bricks_read_the_whole_volumes_gradients():
    """Bricks cut from the whole volume's words: every sample a brick counts has the
    monolithic sample's interpolated gradient and shaded RGBA bit for bit (the gradients
    need no brick overlap of their own); the bricked render runs on a VGRAD build."""
    vol = brick_volume().astype(np.int64)
    sc = _scene("sobel")
    cfg = Cube4Config(pipelines=4, supersample=2)
    nz, ny, nx = vol.shape
    words = pack_words(vol, "sobel", cfg.voxel_bits)
    trav = make_traversal((nx, ny, nz), (-1.0, 0.5, 0.2), cfg.weight_bits, 2)
    lut, rmap = host_tables(sc, cfg, trav)
    mono = render_frame(words, trav, cfg, lut, rmap, keep_streams=True, vgrad=True)
    for br in plan_bricks(trav, make_grid(trav.dims, (2, 2, 1))):
        x0, y0, z0 = br.trav.origin
        bx, by, bz = br.trav.dims
        fr = render_frame(words[z0:z0 + bz, y0:y0 + by, x0:x0 + bx], br.trav, cfg, lut, rmap, keep_streams=True,
                          clip=br.clip, vgrad=True)
        mm, jj, ii = np.nonzero(fr.streams["keep"] & fr.streams["inside"])
        i0, j0, k0 = br.start
        at = (mm + k0 * 2, jj + j0, ii + i0)
        for name in ("gradients", "shaded"):
            assert np.array_equal(fr.streams[name][mm, :, jj, ii], mono.streams[name][at[0], :, at[1], at[2]])
    (bricked,) = render_bricked_views(vol, [sc], config_for(sc, 4), "golden", (2, 2, 1))
    assert bricked.stats["bricks"]["count"] == 4


def test_central_converges_with_s_where_gra_does_not():
    """Against the reference (whose gradient is the interpolant of voxel central
    differences): central differences at the voxels gain with S; the paper's GRA loses."""
    vol = load_volume("sphere:32")
    psnr = {}
    for gradient in ("gra", "central"):
        for s in (1, 4):
            sc = dataclasses.replace(load_scene("default"), gradient=gradient, supersample=s, width=128, height=128)
            cfg = config_for(sc, 4)
            img = render(vol, sc, cfg, "golden").image
            ref = render(vol, sc, cfg, "reference-point").image
            psnr[gradient, s] = image_metrics(img, ref)["psnr"]
    assert psnr["central", 4] > psnr["central", 1] > psnr["gra", 1] > psnr["gra", 4], psnr


def test_cli_gradient_switch(tmp_path):
    stats = tmp_path / "s.json"
    cmd = [sys.executable, "-m", "cube4.app.cli", "render", "sphere:24", "--gradient", "sobel", "--out",
           str(tmp_path / "a.png"), "--stats", str(stats), "--quiet"]
    subprocess.run(cmd, check=True)
    st = json.loads(stats.read_text())
    assert st["build"]["VGRAD"] == 1 and st["build"]["SHADING"] == 1
    bad = subprocess.run([*cmd[:-5], "--out", str(tmp_path / "b.png"), "--build", "full"],
                         capture_output=True, text=True)
    assert bad.returncode != 0 and "takes its gradient from voxel gradients" in bad.stderr
    assert len(bad.stderr.strip().splitlines()) == 1


def test_quality_preset():
    """--preset quality sets voxel central differences, S = 4 and 2×2 passes (the scene
    head_quality is the head with it); an unknown preset is one line."""
    from cube4.scene import apply_preset

    head = load_scene("head")
    q = apply_preset(head, "quality")
    assert (q.gradient, q.supersample, q.subpixel) == ("central", 4, 2)
    hq = load_scene("head_quality")
    assert (hq.gradient, hq.supersample, hq.subpixel) == (q.gradient, q.supersample, q.subpixel)
    assert apply_preset(head, "default") == head
    with pytest.raises(UserError, match="preset must be one of"):
        apply_preset(head, "best")


def test_cli_preset_sets_the_hardware(tmp_path):
    """--preset quality reaches the configuration too: S = 4 and four passes per view."""
    stats = tmp_path / "s.json"
    subprocess.run([sys.executable, "-m", "cube4.app.cli", "render", "sphere:16", "--preset", "quality", "--out",
                    str(tmp_path / "a.png"), "--stats", str(stats), "--quiet"], check=True)
    st = json.loads(stats.read_text())
    assert st["config"]["supersample"] == 4 and st["frames"] == 4 and st["build"]["VGRAD"] == 1

"""Rendering modes, unshaded compositing, crop boxes, cut planes, windows and builds in the
golden model and the reference, checked against independent computations of what
docs/numerics.md sections 12 and 13 specify."""

from __future__ import annotations

import dataclasses
import subprocess
import sys

from dataclasses import replace

import numpy as np
import pytest
from cube4_testutil import make_scene, random_volume, sphere_volume

from cube4.app.render import render
from cube4.clip import Clip, cut_coefficients, plane_value
from cube4.builds import FULL_BUILD
from cube4.config import Cube4Config, parse_build, resolve_build, scene_build
from cube4.errors import UserError
from cube4.host import config_for, host_tables, image_metrics, setup_view
from cube4.model import render_frame, sample_stream
from cube4.scene import load_scene
from cube4.tables import classification_lut, extremum_lut
from cube4.view import make_traversal

VIEWS = [(0.3, -0.45, 1.0), (-1.0, 0.4, -0.7), (0.5, 1.0, 0.5), (1.0, 1.0, 1.0)]


def random_lut(rng, cfg: Cube4Config) -> np.ndarray:
    n = 1 << cfg.voxel_bits
    lut = np.empty((n, 4), dtype=np.int64)
    lut[:, :3] = rng.integers(0, 256, size=(n, 3))
    lut[:, 3] = rng.integers(0, 1 << cfg.alpha_bits, size=n)
    return lut


@pytest.mark.parametrize("d", VIEWS)
def test_unshaded_equals_shaded_with_the_identity_map(d):
    """C' = C: the unshaded frame equals the shaded frame on a reflectance map of D = 1.0,
    P = 0 (what the host loads into a build with shading), bit for bit."""
    rng = np.random.default_rng(1)
    cfg = Cube4Config(pipelines=4)
    vol = random_volume((9, 10, 11), seed=2)
    trav = make_traversal((11, 10, 9), d)
    lut = random_lut(rng, cfg)
    ident = np.zeros((cfg.rmap_entries, 2), dtype=np.int64)
    ident[:, 0] = 256
    a = render_frame(vol, trav, cfg, lut, None, shading=False)
    b = render_frame(vol, trav, cfg, lut, ident)
    assert np.array_equal(a.baseplane, b.baseplane) and np.array_equal(a.pixels, b.pixels)


@pytest.mark.parametrize("mode", ["mip", "minip"])
@pytest.mark.parametrize("d", VIEWS)
def test_extremum_is_the_classified_extreme_sample(mode, d):
    """MIP / MinIP: each finished ray's pixel is the LUT entry of the largest (smallest)
    sample along it, colour << (F - 8), A << (F - AW), found here by walking every ray's
    samples independently of the model's slice loop."""
    rng = np.random.default_rng(3)
    cfg = Cube4Config(pipelines=2)
    vol = random_volume((8, 9, 10), seed=4)
    trav = make_traversal((10, 9, 8), d)
    lut = random_lut(rng, cfg)
    frame = render_frame(vol, trav, cfg, lut, None, mode=mode)
    samples, inside = sample_stream(vol, trav)
    sxm, sym = trav.max_steps
    best: dict = {}
    for m in range(trav.num_sample_slices):
        stx, sty = (int(v) for v in trav.steps(m))
        for j, i in zip(*np.nonzero(inside[m])):
            key = (j - sty + sym, i - stx + sxm)
            v = int(samples[m, j, i])
            if key not in best or (v > best[key] if mode == "mip" else v < best[key]):
                best[key] = v
    assert len(best) == frame.pixels.size
    sh = cfg.acc_bits - cfg.alpha_bits
    for px in frame.pixels:
        e = lut[best[(px["by"], px["bx"])]]
        want = [e[0] << (cfg.acc_bits - 8), e[1] << (cfg.acc_bits - 8), e[2] << (cfg.acc_bits - 8), e[3] << sh]
        assert [px["r"], px["g"], px["b"], px["a"]] == want


def test_xray_sums_opacities_and_saturates():
    """X-ray: a ray's A is min(2^F, sum of w = round_shift(2^F A, AW)) over its samples,
    independent of their order; colour saturates at 2^F too."""
    cfg = Cube4Config(pipelines=1)
    n = 12
    vol = np.full((n, 4, 4), 200, dtype=np.uint16)
    trav = make_traversal((4, 4, n), (0.0, 0.0, 1.0))
    for a in (30, 600, 4000):
        lut = np.zeros((256, 4), dtype=np.int64)
        lut[200] = (255, 128, 0, a)
        frame = render_frame(vol, trav, cfg, lut, None, mode="xray")
        one = 1 << cfg.acc_bits
        w = (one * a + (1 << (cfg.alpha_bits - 1))) >> cfg.alpha_bits
        px = frame.baseplane[0, 0]
        assert px[3] == min(one, n * w), a
        assert px[0] == min(one, n * ((w * 255 + 128) >> 8)), a


@pytest.mark.parametrize("d", VIEWS)
def test_crop_box_is_the_subvolume_at_its_place(d):
    """A crop box renders as the box's voxels traversed as a volume of their own, and the
    scene's crop goes through render() (camera of the whole volume)."""
    rng = np.random.default_rng(5)
    cfg = Cube4Config(pipelines=3)
    vol = random_volume((14, 13, 12), seed=6)
    lut = random_lut(rng, cfg)
    lo, hi = (2, 3, 1), (9, 11, 10)
    box = tuple(b - a + 1 for a, b in zip(lo, hi))
    trav = make_traversal(box, d, origin=lo)
    sub = vol[lo[2]:hi[2] + 1, lo[1]:hi[1] + 1, lo[0]:hi[0] + 1]
    a = render_frame(sub, trav, cfg, lut, None, shading=False)
    b = render_frame(sub.copy(), make_traversal(box, d), cfg, lut, None, shading=False)
    assert np.array_equal(a.baseplane, b.baseplane)     # origin moves the picture, not the bits
    sc = make_scene(view={"direction": list(d)}, crop={"box": [list(lo), list(hi)]},
                    material={"shading": False})
    smooth = sphere_volume(14)
    res = render(smooth, sc, config_for(sc, 3), "golden")
    assert res.stats["traversed_box"] == {"origin": list(lo), "dims": list(box)}
    ref = render(smooth, sc, config_for(sc, 3), "reference-point")
    # 24 to 31 dB uncropped on this 14^3 sphere; the box's cut faces cost up to 5 dB more
    # (the bilinear warp spreads the base plane about a voxel past a face: issue of the warp)
    assert image_metrics(res.image, ref.image)["psnr"] > 22.0


@pytest.mark.parametrize(("W", "S"), [(8, 2), (12, 1), (8, 8), (4, 1)])
def test_cut_plane_keeps_one_side(W, S):
    """The cut plane's integer test agrees with the float plane at every sample farther
    than 1/1000 voxel from it (the quantisation tilts the plane by less than 2^-16 voxel
    per voxel, 6e-4 voxel across this box), and both sides hold samples."""
    trav = make_traversal((20, 18, 16), (0.4, -0.7, 1.0), W, S)
    normal = np.array([0.3, -0.5, 0.8])
    point = np.array([9.0, 8.5, 7.5])
    plane = cut_coefficients(trav, normal, point)
    n = normal / np.linalg.norm(normal)
    kept = lost = 0
    for m in range(0, trav.num_sample_slices, 3):
        jj, ii = np.mgrid[0:trav.nj, 0:trav.ni]
        wx, wy, _ = (int(w) for w in trav.weights(m))
        e = plane_value(plane, trav, m, jj, ii)
        pts = trav.traversal_to_volume_points(ii + wx / 2.0**W, jj + wy / 2.0**W, np.full(ii.shape, m / S))
        f = (pts - point) @ n
        sure = np.abs(f) > 1e-3
        assert np.array_equal((e >= 0)[sure], (f <= 0)[sure])
        kept += int((e >= 0).sum())
        lost += int((e < 0).sum())
    assert kept and lost
    keep = Clip(plane=plane).keep(trav, 5)
    assert keep.dtype == bool and keep.shape == (trav.nj, trav.ni)


def test_window_counts_only_its_samples():
    """Samples outside the window add nothing: a window that splits the slices in two,
    composited as two frames' transmittances, equals the whole frame's where only one
    part has samples, and two disjoint windows cover every counted sample once."""
    cfg = Cube4Config(pipelines=2)
    vol = random_volume((10, 8, 9), seed=7)
    trav = make_traversal((9, 8, 10), (0.2, 0.1, 1.0))
    lut = random_lut(np.random.default_rng(8), cfg)
    M = trav.num_sample_slices
    full = render_frame(vol, trav, cfg, lut, None, mode="xray")
    a = render_frame(vol, trav, cfg, lut, None, mode="xray", clip=Clip(window=(0, 9, 0, 8, 0, 4)))
    b = render_frame(vol, trav, cfg, lut, None, mode="xray", clip=Clip(window=(0, 9, 0, 8, 4, M)))
    one = 1 << cfg.acc_bits
    sat = full.baseplane[..., 3] < one     # X-ray sums: exact where nothing saturates
    assert np.array_equal((a.baseplane[..., 3] + b.baseplane[..., 3])[sat], full.baseplane[..., 3][sat])


def test_scene_builds_and_build_errors():
    head = load_scene("head")
    # a scene that leaves [render] skip out runs the beat schedule (BEATS = 1), at every S
    assert scene_build([head]) == {"SHADING": 1, "COMPOSITING": 1, "EXTREMUM": 0, "CLIP": 0, "VGRAD": 0,
                                   "PLW": 0, "SLAB": 0, "ZOUT": 0, "ZIN": 0, "GMOD": 0, "LABELS": 0, "RECTS": 0, "BEATS": 1}
    assert scene_build([replace(head, skip=True)])["BEATS"] == 0
    assert scene_build([replace(head, supersample=2)])["BEATS"] == 1
    assert scene_build([load_scene("mri_mip")]) == {"SHADING": 0, "COMPOSITING": 0, "EXTREMUM": 1, "CLIP": 0,
                                                    "VGRAD": 0, "PLW": 0, "SLAB": 0, "ZOUT": 0, "ZIN": 0, "GMOD": 0, "LABELS": 0, "RECTS": 0, "BEATS": 1}
    assert scene_build([load_scene("head_quality")])["BEATS"] == 1      # S = 4 too
    assert scene_build([load_scene("ml")])["PLW"] == 1               # path-weighted
    assert scene_build([replace(load_scene("ml"), mode="mip")])["PLW"] == 0
    assert scene_build([load_scene("head_cut")])["CLIP"] == 1
    assert parse_build("full") == FULL_BUILD and parse_build("scene") is None
    assert parse_build("shading=0,compositing=0") == {"SHADING": 0, "COMPOSITING": 0, "EXTREMUM": 1, "CLIP": 1,
                                                      "VGRAD": 0, "PLW": 0, "SLAB": 0, "ZOUT": 0, "ZIN": 0, "GMOD": 0, "LABELS": 0, "RECTS": 0, "BEATS": 0}
    for bad, msg in [("SHADING=2", "NAME=0/1"), ("FOO=1", "NAME=0/1"),
                     ("COMPOSITING=0,EXTREMUM=0", "no rendering mode"), ("COMPOSITING=0", "only compositing"),
                     ("SHADING=0,VGRAD=1", "VGRAD = 1 needs SHADING"),
                     ("COMPOSITING=0,SHADING=0,PLW=1", "PLW = 1 needs COMPOSITING"),
                     ("SLAB=1,CLIP=0", "SLAB = 1 needs CLIP"),
                     ("LABELS=1,PLW=1", "LABELS = 1 needs VGRAD = 0 and PLW = 0")]:
        with pytest.raises(UserError, match=msg):
            parse_build(bad)
    cfg = config_for(head, 4, build=tuple(parse_build("SHADING=0").items()))
    with pytest.raises(UserError, match="scene head needs shading"):
        resolve_build(cfg, [head])
    cfg = config_for(head, 4, build=tuple(parse_build("PLW=0").items()))
    with pytest.raises(UserError, match="scene ml needs path-length weights"):
        resolve_build(cfg, [load_scene("ml")])
    cfg = config_for(head, 4, build=tuple(parse_build("full").items()))
    with pytest.raises(UserError, match="scene head_slab needs the cut slab"):
        resolve_build(cfg, [load_scene("head_slab")])
    # the gradient's source: one per build
    sobel, central = replace(head, gradient="sobel"), replace(head, gradient="central")
    assert scene_build([sobel])["VGRAD"] == 1
    assert scene_build([replace(sobel, shading=False)])["VGRAD"] == 0      # unshaded: no gradient
    for scenes, msg in [([head, sobel], "cannot mix"), ([sobel, central], "one voxel gradient")]:
        with pytest.raises(UserError, match=msg):
            scene_build(scenes)
    with pytest.raises(UserError, match="takes its gradient from voxel gradients"):
        resolve_build(config_for(sobel, 4, build=tuple(FULL_BUILD.items())), [sobel])
    with pytest.raises(UserError, match="takes its gradient from GRA"):
        resolve_build(config_for(head, 4, build=tuple(parse_build("VGRAD=1").items())), [head])


def test_scene_keys_and_errors():
    sc = make_scene(render={"mode": "minip"}, crop={"box": [[1, 2, 3], [5, 6, 7]]},
                    cut={"normal": [0, 0, 1], "point": [1, 2, 3]}, material={"shading": False})
    assert sc.mode == "minip" and sc.crop == ((1, 2, 3), (5, 6, 7)) and not sc.shaded
    for kw, msg in [({"render": {"mode": "dvr"}}, "not supported"),
                    ({"crop": {"box": [[1, 2], [3, 4]]}}, "crop.box must be"),
                    ({"crop": {"box": [[5, 2, 3], [1, 6, 7]]}}, "0 <= x0 <= x1"),
                    ({"cut": {"normal": [0, 0, 1]}}, "needs both"),
                    ({"cut": {"normal": [0, 0, 0], "point": [1, 1, 1]}}, "zero"),
                    ({"material": {"shading": "no"}}, "true or false")]:
        with pytest.raises(UserError, match=msg):
            make_scene(**kw)
    big = make_scene(crop={"box": [[0, 0, 0], [40, 5, 5]]})
    with pytest.raises(UserError, match="reaches outside the volume"):
        setup_view((16, 16, 16), big, config_for(big, 1))


@pytest.mark.parametrize("name", ["head_unshaded", "head_cut", "head_xray", "head_minip", "mri_mip"])
def test_builtin_mode_scenes_against_the_reference(name):
    """Every built-in mode scene renders on its volume close to the float64 reference."""
    vol_name = "mri" if name == "mri_mip" else "head:64"
    from cube4.app.volumes import load_volume

    vol = load_volume(vol_name)
    sc = dataclasses.replace(load_scene(name), width=96, height=96)
    cfg = config_for(sc, 4)
    g = render(vol, sc, cfg, "golden")
    r = render(vol, sc, cfg, "reference-point")
    assert g.image[..., 3].max() > 0.1          # the picture is not empty
    assert image_metrics(g.image, r.image)["psnr"] > 24.0


def test_mip_lut_is_premultiplied():
    sc = make_scene(render={"mode": "mip"}, transfer={"points": [[0, 1, 1, 1, 0.5], [1, 1, 1, 1, 0.5]]})
    cfg = config_for(sc, 1)
    lut = extremum_lut(sc, cfg)
    assert lut[0, 0] == 128 and lut[0, 3] == 2048
    trav, _ = setup_view((8, 8, 8), sc, cfg)
    assert np.array_equal(host_tables(sc, cfg, trav)[0], lut)
    assert host_tables(sc, cfg, trav)[1] is None          # never shaded: no reflectance map
    comp = classification_lut(make_scene(), cfg, 1.0)
    assert comp.shape == lut.shape


def test_cli_build_given_by_hand_fails_before_any_work(tmp_path):
    """A scene that needs what --build leaves out stops with one line, exit status 2,
    before the volume is read or any model is built."""
    out = tmp_path / "x.png"
    run = subprocess.run([sys.executable, "-m", "cube4_sim.cli", "render", "no-such-volume.raw", "--scene", "head",
                          "--engine", "rtl", "--build", "SHADING=0", "--out", str(out)],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 2
    err = run.stderr.strip()
    assert "\n" not in err and "needs shading" in err and "SHADING = 0" in err, err
    assert not out.exists()


def test_sphere_reference_modes_agree_with_golden():
    """The sphere in every mode: golden against the reference, a loose sanity bound."""
    vol = sphere_volume(32)
    for mode in ("xray", "mip", "composite"):
        sc = make_scene(render={"mode": mode}, transfer={"points": [[0, 0, 0, 0, 0], [1, 1, 0.8, 0.6, 0.2]]})
        cfg = config_for(sc, 2)
        g, r = render(vol, sc, cfg, "golden"), render(vol, sc, cfg, "reference-point")
        assert image_metrics(g.image, r.image)["psnr"] > 28.0, mode

"""Path-length weights of a ray's first and last samples (cube4.pathlen, numerics.md §17)
and the midpoint rule of the reference."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from cube4.app.render import render
from cube4.app.volumes import load_volume
from cube4.config import Cube4Config
from cube4.host import config_for, image_metrics
from cube4.model import inside_mask, render_frame
from cube4.pathlen import ALL_FACES, weight_quarters, weighted_columns
from cube4.scene import load_scene
from cube4.tables import classification_lut
from cube4.view import make_traversal, sub_traversal

DIRECTIONS = [(-0.814, -0.47, -0.342), (0.3, 0.9, 0.2), (1.0, 0.5, 0.999), (0.1, 0.05, 1.0), (0.0, 0.0, 1.0),
              (1.0, 1.0, 1.0), (1.0, -1.0, 0.0)]


def ray_sums(trav, faces=ALL_FACES):
    """Per base-plane ray: the sum of its samples' weights (in steps), its sample count,
    and its exact length inside the box [0, n-1]^3 in steps (from the template)."""
    nj, ni, M = trav.nj, trav.ni, trav.num_sample_slices
    rows, cols = trav.baseplane_shape
    sxm, sym = trav.max_steps
    wsum, cnt = np.zeros((rows, cols)), np.zeros((rows, cols), dtype=np.int64)
    for m in range(M):
        inside = inside_mask(trav, m)
        stx, sty = (int(v) for v in trav.steps(m))
        r0, c0 = sym - sty, sxm - stx
        wq = weight_quarters(trav, m, faces)
        wsum[r0:r0 + nj, c0:c0 + ni] += np.where(inside, wq / 4.0, 0.0)
        cnt[r0:r0 + nj, c0:c0 + ni] += inside
    by, bx = np.mgrid[0:rows, 0:cols]
    one = float(1 << trav.phase_bits)
    u0, v0 = bx - sxm + trav.phase_x / one, by - sym + trav.phase_y / one
    t0, t1 = np.zeros(u0.shape), np.full(u0.shape, M - 1.0)
    for p0, vv, n in ((u0, trav.view_x / one, ni), (v0, trav.view_y / one, nj)):
        if vv == 0:
            t0 = np.where((p0 < 0) | (p0 > n - 1), np.inf, t0)
        else:
            t0, t1 = np.maximum(t0, -p0 / vv), np.minimum(t1, (n - 1 - p0) / vv)
    return wsum, cnt, np.where(t1 >= t0, t1 - t0, 0.0)


@pytest.mark.parametrize("s", [1, 4])
@pytest.mark.parametrize("d", DIRECTIONS)
def test_weights_give_the_path_length(d, s):
    """Every ray of two samples or more: the weights sum to its length inside the box
    within the quantisation (each end rounded to a quarter: 1/8 + 1/8), while the
    unweighted count overshoots by about one step."""
    for phase in ((0, 0), (100 * s, 37 * s)):
        trav = make_traversal((13, 11, 9), d, 8, s, phase=phase)
        wsum, cnt, length = ray_sums(trav)
        many = cnt >= 2
        assert many.sum() > 20
        # the template's inside rule truncates the phase to W bits: at S > 1 a sample up to
        # (S - 1) / VIEW steps outside the box counts as inside
        views = [v for v in (trav.view_x, trav.view_y) if v]
        tol = 0.25 + ((s - 1) / min(views) if views else 0.0)
        assert np.abs(wsum - length)[many].max() <= tol + 1e-9, (d, s, phase)
        # n samples, n - 1 steps between the first and the last, less than a step beyond each
        assert ((length >= cnt - 1 - (tol - 0.25) - 1e-9) & (length < cnt + 1))[many].all()
        # the unweighted sum (n) is off by several times more
        assert np.mean(np.abs(wsum - length)[many]) * 4 < np.mean(np.abs(cnt - length)[many])


def test_no_faces_no_weights():
    """FACES = 0 (a frame that is not path-weighted): weight 1 everywhere."""
    trav = make_traversal((13, 11, 9), (0.3, 0.9, 0.2), 8, 1)
    for m in range(trav.num_sample_slices):
        assert (weight_quarters(trav, m, 0) == 4).all()


def test_sub_traversal_faces():
    """A box's face is the volume's exactly where it lies on the traversed box's face."""
    trav = make_traversal((13, 11, 9), (0.0, 0.0, 1.0), 8, 1)   # i = x, j = y, k = z, no flips
    sub, _, _ = sub_traversal(trav, (0, 2, 3), (13, 11, 7))
    assert sub.faces == 0b001011   # I0, I1, J1; K0 and K1 interior; J0 interior
    flipped = make_traversal((13, 11, 9), (0.0, 0.0, -1.0), 8, 1)   # k runs down z
    sub, _, _ = sub_traversal(flipped, (0, 0, 0), (13, 11, 5))
    assert sub.faces & 0b110000 == 0b100000   # z = 0 is the traversal's high k face


def test_columns():
    """The path-weight columns: 1 - (1 - A)^w for w = 1/2, 3/4, 5/4, 3/2, ordered, and
    0 and the top stay put."""
    a = np.array([0, 1, 100, 2048, 4000, 4095])
    cols = weighted_columns(a, 12)
    assert (cols[0] == 0).all()
    assert (np.diff(cols, axis=1) >= 0).all()
    assert (cols[:, 0] <= a).all() and (cols[:, 3] >= a).all()
    assert cols[3, 0] == round(4096 * (1 - np.sqrt(0.5)))


def test_no_effect_where_the_faces_are_empty():
    """The sphere's faces are transparent: the weighted frame is the unweighted one, bit for bit."""
    vol = load_volume("sphere:32")
    cfg = Cube4Config()
    trav = make_traversal(vol.shape[::-1], (0.3, -0.45, 1.0), 8, 1)
    scene = load_scene("default")
    lut = classification_lut(scene, cfg, trav.sample_distance)
    both = np.concatenate([lut, weighted_columns(lut[:, 3], cfg.alpha_bits)], axis=1)
    a = render_frame(vol, trav, cfg, lut, None, shading=False)
    b = render_frame(vol, trav, cfg, both, None, shading=False)
    assert (a.baseplane == b.baseplane).all()


def test_weights_reduce_error_on_ml():
    """Marschner-Lobb reaches the volume's faces: the weighted image is closer to the
    reference (its own midpoint rule) than the unweighted one, by at least 0.5 dB."""
    vol = load_volume("ml:41")
    scene = load_scene("ml")
    assert scene.path_weights
    cfg = config_for(scene, 8)
    ref = render(vol, scene, cfg, "reference-point").image
    on = image_metrics(render(vol, scene, cfg, "golden").image, ref)["psnr"]
    off = image_metrics(render(vol, replace(scene, path_weights=False), cfg, "golden").image, ref)["psnr"]
    assert on > off + 0.5, (on, off)


def test_reference_path_length():
    """The reference's midpoint rule: a uniform slab viewed along an axis has opacity
    1 - (1 - a)^(n - 1) over its n - 1 voxels of path, to the step's rounding."""
    from cube4.reference import cast_rays
    n, a = 6, 0.3
    vol = np.full((n, n, n), 255, dtype=np.int64)
    scene = replace(load_scene("default"), shading=False,
                    tf_points=np.array([[0, 1, 1, 1, a], [1, 1, 1, 1, a]], float))
    origins = np.array([[2.5, 2.5, -3.0], [1.0, 4.0, -3.0]])
    out = cast_rays(vol, 8, scene, origins, np.array([0.0, 0.0, 1.0]))
    assert np.allclose(out[:, 3], 1 - (1 - a) ** (n - 1), atol=1e-12)


def test_cli_path_weights(tmp_path):
    """--path-weights / --no-path-weights override the scene; the build must have PLW."""
    import json
    import subprocess
    import sys
    stats = tmp_path / "s.json"
    base = [sys.executable, "-m", "cube4.app.cli", "render", "ml:16", "--scene", "ml", "--quiet", "--stats", str(stats)]
    subprocess.run([*base, "--out", str(tmp_path / "a.png")], check=True)
    st = json.loads(stats.read_text())
    assert st["path_weights"] and st["build"]["PLW"] == 1
    subprocess.run([*base, "--no-path-weights", "--out", str(tmp_path / "b.png")], check=True)
    st = json.loads(stats.read_text())
    assert not st["path_weights"] and st["build"]["PLW"] == 0
    bad = subprocess.run([*base, "--out", str(tmp_path / "c.png"), "--build", "PLW=0"], capture_output=True, text=True)
    assert bad.returncode != 0 and "needs path-length weights" in bad.stderr
    assert len(bad.stderr.strip().splitlines()) == 1

"""The float64 reference against an analytic answer, and the Cube-4 model against the
reference on the built-in scenes."""

from __future__ import annotations

import numpy as np
import pytest
from cube4_testutil import make_scene

from cube4.app.render import render
from cube4.app.volumes import load_volume
from cube4.host import config_for
from cube4.phantoms import sphere_centre, sphere_radius
from cube4.scene import load_scene
from cube4.view import make_camera

ALPHA = 0.05  # per voxel of distance


def test_reference_sphere_matches_analytic_chord_opacity():
    """Constant-opacity sphere, no shading: pixel opacity = 1 - (1 - a)^L with L the chord
    length. The 0.5 iso-surface of the antialiased sphere is the sphere of radius R; the
    steep transfer-function ramp (0.45..0.55) and the trilinear field move the effective
    surface by a fraction of a voxel, so we allow 0.01 in opacity away from the rim."""
    n = 48
    vol = load_volume(f"sphere:{n}")
    scene = make_scene(
        view={"direction": [0.3, -0.5, 0.81]},
        material={"ambient": 1.0, "diffuse": 0.0, "specular": 0.0},
        transfer={"points": [[0, 1, 1, 1, 0], [0.45, 1, 1, 1, 0], [0.55, 1, 1, 1, ALPHA], [1, 1, 1, 1, ALPHA]]},
    )
    cfg = config_for(scene)
    img = render(vol, scene, cfg, "reference").image
    cam = make_camera((n, n, n), scene.direction, scene.width, scene.height)
    origins, d = cam.ray_origins()
    c = np.asarray(sphere_centre((n, n, n)))
    R = sphere_radius((n, n, n))
    rel = origins - c
    perp = np.linalg.norm(rel - (rel @ d)[:, None] * d, axis=1).reshape(img.shape[:2])
    chord = 2.0 * np.sqrt(np.maximum(0.0, R * R - perp**2))
    expect = 1.0 - (1.0 - ALPHA) ** chord
    core = perp < 0.9 * R
    outside = perp > R + 1.5
    err = np.abs(img[..., 3] - expect)
    assert err[core].max() < 0.01, err[core].max()
    assert img[..., 3][outside].max() == 0.0
    # colour is white premultiplied: R = G = B = A
    assert np.allclose(img[..., 0], img[..., 3], atol=1e-9)


# (volume, scene, supersample, PSNR floor in dB). Measured on this machine: sphere 34.9,
# head 34.1, ml 26.6 (S=1) and 30.5 (S=2). The floors sit ~2 dB below: the model's error
# is dominated by the architecture (base plane at one-voxel spacing warped bilinearly to
# the image; samples one slice apart against the reference's 1/8 voxel), not by the
# precision (12-bit voxels or weights, or a finer reflectance map, change < 0.1 dB).
CASES = [
    ("sphere:64", "default", 1, 32.5),
    ("head:64", "head", 1, 32.0),
    ("ml:41", "ml", 1, 24.0),
    ("ml:41", "ml", 2, 28.0),
]


@pytest.mark.parametrize("volume,scene_name,ss,floor", CASES)
def test_golden_model_against_reference(volume, scene_name, ss, floor):
    scene = load_scene(scene_name)
    scene.supersample = ss
    cfg = config_for(scene)
    vol = load_volume(volume, voxel_bits=cfg.voxel_bits)
    golden = render(vol, scene, cfg, "golden")
    ref = render(vol, scene, cfg, "reference")
    from cube4.host import image_metrics

    m = image_metrics(golden.image, ref.image)
    assert m["psnr"] > floor, m
    # and the pictures are not trivially empty
    assert ref.image[..., 3].max() > 0.2

"""The host's warp (cube4.warp): the [output] filter chooses OpenImageIO's reconstruction
filter (triangle by default, the bilinear warp bit for bit)."""

from __future__ import annotations

import numpy as np
import pytest
from cube4_testutil import make_scene

from cube4.cli import main
from cube4.errors import UserError
from cube4.render import config_for, render, setup_view
from cube4.scene import parse_scene, with_view
from cube4.view import warp_matrix
from cube4.volumes import load_volume
from cube4.warp import WARP_FILTERS, warp_to_image

OBLIQUE = {"direction": [0.4, -0.7, 0.5]}


def _bilinear_warp(base, trav, cam):
    """The warp written out on its own: OpenImageIO's triangle filter, black outside."""
    import OpenImageIO as oiio

    shift = np.array([[1.0, 0.0, 0.5], [0.0, 1.0, 0.5], [0.0, 0.0, 1.0]])
    unshift = np.array([[1.0, 0.0, -0.5], [0.0, 1.0, -0.5], [0.0, 0.0, 1.0]])
    m = shift @ warp_matrix(trav, cam) @ unshift
    roi = oiio.ROI(0, cam.width, 0, cam.height, 0, 1, 0, 4)
    dst = oiio.ImageBufAlgo.warp(oiio.ImageBuf(base.astype(np.float32)), tuple(float(x) for x in m.T.reshape(-1)),
                                 filtername="triangle", wrap="black", roi=roi)
    return np.asarray(dst.get_pixels(oiio.FLOAT, roi), dtype=np.float64).reshape(cam.height, cam.width, 4)


def _golden(vol, scene):
    nz, ny, nx = vol.shape
    cfg = config_for(scene)
    trav, cam = setup_view((nx, ny, nz), scene, cfg)
    return render(vol, scene, cfg, "golden"), trav, cam


def test_scene_defaults():
    sc = make_scene()
    assert sc.filter == "triangle"


def test_default_filter_is_the_bilinear_warp_bit_for_bit():
    vol = load_volume("sphere:16")
    res, trav, cam = _golden(vol, make_scene(view=OBLIQUE, output={"width": 64}))
    assert np.array_equal(res.image, _bilinear_warp(res.frame.baseplane_float, trav, cam))


@pytest.mark.parametrize("name", WARP_FILTERS)
def test_every_filter_renders(name):
    vol = load_volume("ml:12")
    res, trav, cam = _golden(vol, make_scene(view=OBLIQUE, output={"width": 48, "filter": name}))
    img = res.image
    assert img.shape == (48, 48, 4) and np.all(np.isfinite(img)) and img[..., 3].max() > 0.1
    triangle = warp_to_image(res.frame.baseplane_float, trav, cam)
    assert np.array_equal(img, triangle) == (name == "triangle")   # the name reaches OpenImageIO


@pytest.mark.parametrize("value", ["bilinear", "Triangle", "", 3, ["box"]])
def test_bad_filter_is_one_line(value):
    with pytest.raises(UserError) as exc:
        parse_scene({"output": {"filter": value}})
    msg = str(exc.value)
    assert "\n" not in msg and msg.startswith("scene: output.filter") and ", ".join(WARP_FILTERS) in msg


def test_bad_filter_on_the_command_line(tmp_path, capsys):
    s = tmp_path / "s.toml"
    s.write_text('[output]\nwidth = 32\nfilter = "nearest"\n')
    rc = main(["render", "sphere:8", "--scene", str(s), "--quiet", "--out", str(tmp_path / "o.png")])
    err = capsys.readouterr().err
    assert rc == 2 and err.startswith("cube4: error: scene: output.filter 'nearest'") and err.count("\n") == 1, err


def test_filter_follows_the_view():
    sc = make_scene(output={"width": 32, "filter": "mitchell"})
    assert with_view(sc, [1.0, 0.2, 0.1]).filter == "mitchell"

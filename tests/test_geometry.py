"""Depth in (cube4.geometry, docs/numerics.md §22): opaque geometry drawn with the scene's
camera ends the rays. A ray counts exactly its samples in front of its pixel's depth; a
wall in front of everything leaves only the wall, one behind everything changes nothing;
the box schedule and the q×q passes keep the image; the golden model stays near the
reference with the geometry; `cube4 mesh` draws the needle into an EXR that renders as the
scene's own mesh does; a depth image of the wrong size or with values outside the view,
and engines that do not run it, are one line."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from cube4_testutil import psnr_vs_point

from cube4.app.cli import main
from cube4.app.mesh import load_geometry, resolve_geometry, write_geometry
from cube4.app.render import render, render_bricked_views
from cube4.app.volumes import load_volume
from cube4.errors import UserError
from cube4.geometry import Geometry, stop_slices
from cube4.host import config_for, golden_view, setup_view
from cube4.scene import load_scene, parse_scene


def scene_with(geo: Geometry | None, **extra):
    sc = dataclasses.replace(load_scene("head"), width=48, height=48, **extra)
    return dataclasses.replace(sc, geometry=geo)


def wall(sc, cfg, dims, z: float, color=(0.8, 0.1, 0.1)) -> Geometry:
    _, cam = setup_view(dims, sc, cfg)
    rgba = np.zeros((cam.height, cam.width, 4))
    rgba[..., :3], rgba[..., 3] = color, 1.0
    return Geometry(z=np.full((cam.height, cam.width), float(z)), rgba=rgba)


@pytest.mark.parametrize("direction", [(0.3, -0.45, 1.0), (1.0, 1.0, 1.0), (-1.0, 0.2, 0.1)])
def test_stop_slices_split_each_ray_at_its_depth(direction):
    """Every base-plane ray: its points in slices m < stop lie in front of the geometry's
    depth at its pixel, the others not (a tilted depth image)."""
    sc = dataclasses.replace(scene_with(None), direction=np.asarray(direction) / np.linalg.norm(direction), supersample=2)
    cfg = config_for(sc, 4)
    trav, cam = setup_view((20, 20, 20), sc, cfg)
    rr, cc = np.mgrid[0:cam.height, 0:cam.width]
    z_img = 0.1 * (cc - cam.width / 2) - 0.05 * (rr - cam.height / 2)
    stop = stop_slices(trav, cam, z_img)
    rows, cols = trav.baseplane_shape
    by, bx = np.mgrid[0:rows, 0:cols]
    from cube4.view import warp_matrix
    mat = warp_matrix(trav, cam)
    col = np.floor(mat[0, 0] * bx + mat[0, 1] * by + mat[0, 2] + 0.5).astype(int)
    row = np.floor(mat[1, 0] * bx + mat[1, 1] * by + mat[1, 2] + 0.5).astype(int)
    ok = (col >= 0) & (col < cam.width) & (row >= 0) & (row < cam.height)
    for m in range(trav.num_sample_slices):
        z = (trav.ray_point(bx, by, m / trav.supersample) - cam.centre) @ cam.direction
        zs = np.where(ok, z_img[np.clip(row, 0, cam.height - 1), np.clip(col, 0, cam.width - 1)], np.inf)
        sure = ~np.isclose(z, zs, rtol=0, atol=1e-9)        # a tie is the float's to break
        assert np.array_equal((m < stop)[sure], (z < zs)[sure]), m
    assert ((stop > 0) & (stop < trav.num_sample_slices)).any()     # some rays end inside the volume


def test_walls_in_front_and_behind():
    """A wall before the volume leaves only the wall; one behind it shows where the volume
    is transparent, and is the scene without geometry where the volume is opaque; +inf
    everywhere changes nothing."""
    vol = load_volume("head:20")
    sc = scene_with(None)
    cfg = config_for(sc, 4)
    dims = (20, 20, 20)
    plain = render(vol, sc, cfg, "golden").image
    front = render(vol, scene_with(wall(sc, cfg, dims, -17.0)), cfg, "golden").image
    assert np.allclose(front, wall(sc, cfg, dims, -17.0).rgba)
    behind = render(vol, scene_with(wall(sc, cfg, dims, 17.0)), cfg, "golden").image
    assert np.allclose(behind, plain + (1 - plain[..., 3:4]) * wall(sc, cfg, dims, 17.0).rgba)
    none = Geometry(z=np.full((48, 48), np.inf))
    assert np.array_equal(render(vol, scene_with(none), cfg, "golden").image, plain)


def test_schedules_keep_the_image_and_the_reference_agrees():
    """A wall through the centre: the box schedule gives the fixed schedule's base plane, q = 2
    runs, and the golden model is as near the reference (centre points) as without it."""
    vol = load_volume("head:24")
    sc = scene_with(None)
    cfg = config_for(sc, 4)
    geo = wall(sc, cfg, (24, 24, 24), 0.0)
    cut = scene_with(geo)
    _, fixed, _ = golden_view(vol, dataclasses.replace(cut, skip=False), cfg)
    _, boxed, _ = golden_view(vol, cut, cfg)
    assert np.array_equal(fixed.baseplane, boxed.baseplane)
    golden_view(vol, dataclasses.replace(cut, subpixel=2), cfg)

    assert psnr_vs_point(vol, cut, cfg) > psnr_vs_point(vol, sc, cfg) - 3.0
    assert np.abs(render(vol, cut, cfg, "golden").image - render(vol, sc, cfg, "golden").image).max() > 0.05


def test_mesh_command_and_image_scene(tmp_path):
    """cube4 mesh draws the needle into an EXR; a scene naming that image renders as the
    scene with mesh = "needle"."""
    exr = tmp_path / "needle.exr"
    assert main(["mesh", "head:24", "--scene", "head", "--out", str(exr)]) == 0
    geo = load_geometry(str(exr))
    assert np.isfinite(geo.z).any() and geo.rgba is not None
    vol = load_volume("head:24")
    base = load_scene("head")
    cfg = config_for(base, 4)
    a = render(vol, dataclasses.replace(base, geometry=("image", str(exr))), cfg, "golden").image
    b = render(vol, dataclasses.replace(base, geometry=("mesh", "needle")), cfg, "golden").image
    assert np.abs(a - b).max() < 1e-3       # the EXR holds the needle in 32-bit floats


def test_bad_geometry_is_one_line(tmp_path):
    vol = load_volume("head:16")
    sc = load_scene("head")
    cfg = config_for(sc, 1)
    _, cam = setup_view((16, 16, 16), sc, cfg)
    small = tmp_path / "small.exr"
    write_geometry(str(small), Geometry(z=np.zeros((10, 12))))
    with pytest.raises(UserError, match=r"geometry image is 12x10, the scene's output is 256x256"):
        resolve_geometry(dataclasses.replace(sc, geometry=("image", str(small))), cam)
    far = tmp_path / "far.exr"
    z = np.full((cam.height, cam.width), np.inf)
    z[3, 4] = 1e5
    write_geometry(str(far), Geometry(z=z))
    with pytest.raises(UserError, match=r"at pixel \(4, 3\) lies outside the view"):
        resolve_geometry(dataclasses.replace(sc, geometry=("image", str(far))), cam)
    # the RTL engine checks the image before it builds or writes anything
    out = tmp_path / "never.png"
    scene_file = tmp_path / "far.toml"
    scene_file.write_text(f'[geometry]\nimage = "{far}"\n')
    from cube4_sim.cli import main as cube4_main     # the cube4 command, with the RTL engine
    assert cube4_main(["render", "head:16", "--scene", str(scene_file), "--engine", "rtl", "--out", str(out)]) != 0
    assert not out.exists()
    with pytest.raises(UserError, match="has no channel Z"):
        plain = tmp_path / "plain.exr"
        from cube4.app.images import write_image
        write_image(str(plain), np.zeros((4, 4, 4)))
        load_geometry(str(plain))
    with pytest.raises(UserError, match=r"\[geometry\] takes image"):
        parse_scene({"geometry": {"image": "a.exr", "mesh": "needle"}})
    with pytest.raises(UserError, match="not rendered in bricks"):
        render_bricked_views(vol, [dataclasses.replace(sc, geometry=("mesh", "needle"))], cfg, "golden", (2, 1, 1))
    with pytest.raises(UserError, match=r"leave out \[crop\], \[cut\], \[slab\] and \[geometry\]"):
        render(vol, dataclasses.replace(sc, geometry=("mesh", "needle"), preview=2), cfg, "golden")

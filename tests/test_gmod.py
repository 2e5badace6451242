"""Gradient-magnitude modulation (cube4.gmod, docs/numerics.md §23): the table's index
against its definition, the rule's end points (identity, clear, unshaded), the table the
host builds from a scene, the golden model against the reference, scene keys and their
errors, and the build it gets."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from cube4.app.render import render, render_bricked_views
from cube4.app.volumes import load_volume
from cube4.config import scene_build
from cube4.errors import UserError
from cube4.gmod import (GM_ONE, MANT_BITS, bin_magnitude, gm_index, gm_table, gradient_scale, identity_table,
                        table_entries)
from cube4.host import config_for, image_metrics
from cube4.model import shade
from cube4.scene import load_scene, parse_scene

GW = 13     # GRA's gradient bits at V = 8


def index_by_definition(s: int) -> int:
    if s == 0:
        return 0
    e = s.bit_length() - 1
    return e * (1 << MANT_BITS) + (((s << MANT_BITS) >> e) & ((1 << MANT_BITS) - 1)) + 1


def test_index_is_the_floating_point_of_the_squared_magnitude():
    rng = np.random.default_rng(5)
    lim = 1 << (GW - 1)
    g = rng.integers(-lim, lim, size=(3, 4000))
    g[:, :50] = rng.integers(-3, 4, size=(3, 50))           # small magnitudes: exact bins
    g[:, 50] = 0
    g[:, 51] = -lim                                           # the largest s
    idx = gm_index(g)
    s = (g.astype(object) ** 2).sum(axis=0)
    assert [int(i) for i in idx] == [index_by_definition(int(v)) for v in s]
    assert idx.max() < table_entries(GW) and idx[50] == 0
    # the magnitude the host evaluates an entry at falls in that entry (every entry some s reaches)
    for v in [*range(1, 3000), *(1 << e for e in range(12, 2 * GW - 1)), 3 << (2 * GW - 4)]:
        k = index_by_definition(v)
        mag = float(bin_magnitude(np.array([k]))[0])
        assert index_by_definition(int(round(mag * mag))) == k, (v, k, mag)


def test_rule_end_points():
    """The identity table changes nothing; fa = 0 clears every sample; fs = 0 leaves the
    unshaded colour (D' = 256, P' = 0)."""
    rng = np.random.default_rng(6)
    lut = rng.integers(0, 256, size=(256, 4))
    lut[:, 3] = rng.integers(0, 1 << 12, size=256)
    rmap = rng.integers(0, 1024, size=(6 * 32 * 32 + 1, 2))
    smp = rng.integers(0, 256, size=(40,))
    grad = rng.integers(-4000, 4000, size=(3, 40))
    plain, _ = shade(smp, grad, lut, rmap, 5)
    same, _ = shade(smp, grad, lut, rmap, 5, identity_table(8))
    assert np.array_equal(plain, same)
    clear = identity_table(8)
    clear[:, 0] = 0
    assert (shade(smp, grad, lut, rmap, 5, clear)[0][3] == 0).all()
    unlit = identity_table(8)
    unlit[:, 1] = 0
    got, _ = shade(smp, grad, lut, rmap, 5, unlit)
    assert np.array_equal(got[:3], lut[smp, :3].T) and np.array_equal(got[3], lut[smp, 3])


def test_table_from_the_scene_functions():
    """Entry k holds the function at the bin's |grad f|: a step at 0.02 (per voxel, values
    in 0 .. 1) lands between the entries around 0.02 * scale * 255."""
    step = np.array([[0.0, 0.0], [0.02, 0.0], [0.0200001, 1.0]])
    for grad in ("gra", "sobel"):
        t = gm_table(step, None, 8, grad)
        mag = bin_magnitude(np.arange(table_entries(GW))) / (gradient_scale(grad) * 255)
        assert np.array_equal(t[:, 0], np.where(mag > 0.0200001, GM_ONE, 0))
        assert (t[:, 1] == GM_ONE).all()


@pytest.fixture(scope="module")
def head32():
    return load_volume("head:32")


def boundary_scene(**kw):
    sc = dataclasses.replace(load_scene("head_cut"), cut=None, width=96, height=96)
    return dataclasses.replace(sc, gmod=(np.array([[0.0, 0.0], [0.01, 0.0], [0.06, 1.0]]),
                                         np.array([[0.0, 0.0], [0.02, 1.0]])), **kw)


def test_golden_near_the_reference(head32):
    """The golden model against the point-sampled reference, with the modulation as without:
    within 3 dB of its distance without (the index's bins and GRA's gradient against the
    exact |grad f|), and the modulation changes the picture."""
    sc = boundary_scene()
    cfg = config_for(sc, 4)
    plain = dataclasses.replace(sc, gmod=None)
    gm_g = render(head32, sc, cfg, "golden").image
    gm_r = render(head32, sc, cfg, "reference-point").image
    pl_g = render(head32, plain, cfg, "golden").image
    pl_r = render(head32, plain, cfg, "reference-point").image
    with_gm, without = image_metrics(gm_g, gm_r)["psnr"], image_metrics(pl_g, pl_r)["psnr"]
    print(f"golden vs reference-point: {with_gm:.2f} dB with the modulation, {without:.2f} dB without")
    assert with_gm >= without - 3.0
    assert image_metrics(gm_r, pl_r)["psnr"] < 40.0      # the reference sees the modulation too


def test_scene_keys_and_errors(head32):
    sc = parse_scene({"gradient_modulation": {"opacity": [[0, 0], [0.1, 1]]}})
    assert sc.gmod[1] is None and scene_build([sc])["GMOD"] == 1
    assert scene_build([load_scene("head")])["GMOD"] == 0
    for bad, msg in (({"gradient_modulation": {"opacity": [[0.2, 0], [0.1, 1]]}}, "must ascend"),
                     ({"gradient_modulation": {"opacity": [[0, 1.5]]}}, "factors must lie in 0 .. 1"),
                     ({"gradient_modulation": {"opacity": "x"}}, r"\[\[magnitude, factor\], ...\]"),
                     ({"gradient_modulation": {"alpha": [[0, 1]]}}, "unknown key"),
                     ({"gradient_modulation": {"opacity": [[0, 1]]}, "render": {"mode": "mip"}}, "shaded composite"),
                     ({"gradient_modulation": {"opacity": [[0, 1]]}, "material": {"shading": False}},
                      "shaded composite")):
        with pytest.raises(UserError, match=msg):
            parse_scene(bad)
    sc = boundary_scene(path_weights=True)
    with pytest.raises(UserError, match="does not combine with path weights"):
        render(head32, sc, config_for(sc, 4), "golden")
    with pytest.raises(UserError, match="not rendered in bricks"):
        render_bricked_views(head32, [boundary_scene()], config_for(sc, 4), "golden", (2, 1, 1))

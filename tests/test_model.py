"""The bit-exact model against its own specification (docs/numerics.md), checked by
independent scalar re-computation and by invariances the spec implies."""

from __future__ import annotations

import math

import numpy as np
import pytest
from cube4_testutil import make_scene, random_volume

from cube4.config import Cube4Config
from cube4.fixed import lerp, round_shift
from cube4.host import config_for, host_tables
from cube4.model import gradient, inside_mask, interpolate_slice, render_frame, rmap_index
from cube4.view import make_traversal


def test_round_shift_is_round_half_up():
    x = np.arange(-40, 41)
    for s in (1, 2, 3):
        expect = np.floor(x / 2**s + 0.5).astype(np.int64)
        assert np.array_equal(round_shift(x, s), expect)
    assert np.array_equal(round_shift(x, 0), x)


def test_lerp_stays_between_endpoints_and_rounds():
    rng = np.random.default_rng(0)
    a = rng.integers(0, 4096, 5000)
    b = rng.integers(0, 4096, 5000)
    w = rng.integers(0, 256, 5000)
    out = lerp(a, b, w, 8)
    assert np.all(out >= np.minimum(a, b)) and np.all(out <= np.maximum(a, b))
    assert np.array_equal(out, a + np.floor((b - a) * w / 256 + 0.5).astype(np.int64))


@pytest.mark.parametrize("W,S", [(8, 1), (8, 2), (8, 4), (6, 8), (4, 1)])
def test_template_closed_form_equals_incremental_rule(W, S):
    """The paper's rule: VIEW_X added modulo 2^(W+g) per sample slice, step on carry."""
    trav = make_traversal((40, 30, 50), (0.37, -0.61, 0.7), W, S)
    g = S.bit_length() - 1
    phase_x = phase_y = 0
    step_x = step_y = 0
    for m in range(trav.num_sample_slices):
        wx, wy, wz = trav.weights(m)
        sx, sy = trav.steps(m)
        assert (int(wx), int(wy)) == (phase_x >> g, phase_y >> g)
        assert (int(sx), int(sy)) == (step_x, step_y)
        assert int(wz) == (m % S) << (W - g)
        phase_x += trav.view_x
        phase_y += trav.view_y
        step_x += phase_x >> (W + g)
        step_y += phase_y >> (W + g)
        phase_x &= (1 << (W + g)) - 1
        phase_y &= (1 << (W + g)) - 1


def _sample_scalar(t, i, j, m, trav, W):
    """One sample by the spec, scalar: 4 x-lerps, 2 y-lerps, 1 z-lerp on zero-padded voxels."""
    nk, nj, ni = t.shape

    def v(k, jj, ii):
        return int(t[k, jj, ii]) if k < nk and jj < nj and ii < ni else 0

    wx, wy, wz = (int(q) for q in trav.weights(m))
    k = m // trav.supersample
    x = [[lerp(v(k + dz, j + dy, i), v(k + dz, j + dy, i + 1), wx, W) for dy in (0, 1)] for dz in (0, 1)]
    y = [lerp(x[dz][0], x[dz][1], wy, W) for dz in (0, 1)]
    return lerp(y[0], y[1], wz, W)


@pytest.mark.parametrize("S", [1, 2])
def test_interpolation_matches_scalar_spec(S):
    vol = random_volume((9, 7, 11), bits=12, seed=3)
    trav = make_traversal((11, 7, 9), (0.3, 0.45, -0.8), 8, S)
    t = trav.to_traversal(vol)
    nk, nj, ni = t.shape
    tp = np.zeros((nk + 1, nj + 1, ni + 1), dtype=np.int32)
    tp[:nk, :nj, :ni] = t
    for m in range(trav.num_sample_slices):
        s = interpolate_slice(tp, trav, m, 8)
        for j in range(nj):
            for i in range(ni):
                assert s[j, i] == _sample_scalar(t, i, j, m, trav, 8)


def test_gradient_of_linear_ramp_is_exact_inside():
    """f = 3x + 5y + 7z (voxels) in volume axes -> 2x the central differences = (6, 10, 14)
    at interior samples, for a view in each octant with every major axis."""
    n = 24
    z, y, x = np.mgrid[:n, :n, :n]
    vol = (3 * x + 5 * y + 7 * z).astype(np.uint16)
    for d in [(0.2, 0.3, 0.9), (-0.9, 0.3, -0.2), (0.3, -0.9, 0.25), (0.5, 0.5, 0.70710678)]:
        trav = make_traversal((n, n, n), d, 8, 1)
        t = trav.to_traversal(vol)
        tp = np.zeros((n + 1,) * 3, dtype=np.int32)
        tp[:n, :n, :n] = t

        def padded(m):
            sp = np.zeros((n + 2, n + 2), dtype=np.int32)
            sp[1:-1, 1:-1] = interpolate_slice(tp, trav, m, 8)
            return sp

        m = n // 2
        g = gradient(padded(m - 1), padded(m), padded(m + 1), trav, m)
        inner = g[:, 4:-4, 4:-4]
        expect_vol = np.array([6, 10, 14])
        # in traversal axes (i, j, k) with the flips applied
        exp = [(-1 if trav.flip[a] else 1) * expect_vol[a] for a in (trav.axis_i, trav.axis_j, trav.major)]
        for c in range(3):
            assert np.abs(inner[c] - exp[c]).max() <= 2, (d, c, np.unique(inner[c]))


def test_rmap_index_faces_and_zero():
    r = 8
    g = np.array([[5, -5, 0, 0, 0, 0, 0], [0, 0, 3, -3, 0, 0, 0], [1, 1, 1, 1, 9, -9, 0]])
    idx = rmap_index(g, 3)
    faces = idx // (r * r)
    assert list(faces[:6]) == [0, 1, 2, 3, 4, 5]
    assert idx[6] == 6 * r * r
    # u, v of an axis-aligned gradient are the centre cells
    assert idx[4] % (r * r) == (r // 2) * r + r // 2


def _frame(vol, direction, **cfgkw):
    scene = make_scene(view={"direction": list(direction)}, light=[{"headlight": True}])
    cfg = config_for(scene, **cfgkw)
    nz, ny, nx = vol.shape
    trav = make_traversal((nx, ny, nz), scene.direction, cfg.weight_bits, cfg.supersample)
    lut, rmap = host_tables(scene, cfg, trav)
    return render_frame(vol, trav, cfg, lut, rmap, keep_streams=True), trav


@pytest.mark.parametrize("axis", [0, 1, 2])
def test_axis_flip_gives_the_same_base_plane(axis):
    """Flipping the volume along an axis and the view with it leaves the traversal-frame
    volume unchanged, so the base plane must be identical bit for bit."""
    vol = random_volume((14, 12, 10), seed=5)
    d = np.array([0.35, -0.5, 0.79])
    f1, _ = _frame(vol, d)
    d2 = d.copy()
    d2[axis] = -d2[axis]
    f2, _ = _frame(np.flip(vol, axis=2 - axis), d2)
    assert np.array_equal(f1.baseplane, f2.baseplane)


@pytest.mark.parametrize("direction", [(0, 0, 1), (1, 1, 1), (1, 0, 1), (-0.2, 0.9, 0.3), (0.01, -0.02, -1)])
def test_pixel_stream_covers_each_ray_once(direction):
    vol = random_volume((10, 13, 11), seed=7)
    f, trav = _frame(vol, direction)
    px = f.pixels
    keys = px["by"].astype(np.int64) * 10_000 + px["bx"]
    assert np.unique(keys).size == keys.size, "a pixel was emitted twice"
    # every ray that received an inside sample is emitted, with its final value
    touched = np.zeros(trav.baseplane_shape, dtype=bool)
    sxm, sym = trav.max_steps
    for m in range(trav.num_sample_slices):
        sx, sy = (int(v) for v in trav.steps(m))
        jj, ii = np.nonzero(inside_mask(trav, m))
        touched[jj + sym - sy, ii + sxm - sx] = True
    assert touched.sum() == px.size
    bp = f.baseplane
    for ch, name in enumerate("rgba"):
        assert np.array_equal(bp[px["by"], px["bx"], ch], px[name])
    assert np.all(bp[~touched] == np.array([0, 0, 0, 0]))
    # emission order: by slice of the last sample, then row-major within the slice
    order = np.lexsort((px["bx"], px["by"], px["m"]))
    assert np.array_equal(order, np.arange(px.size))


def test_accumulators_never_wrap_on_opaque_media():
    """Fully opaque white at the longest sample distance: T >= 0, C <= 2^ACC_W."""
    vol = np.full((16, 16, 16), 255, dtype=np.uint16)
    scene = make_scene(view={"direction": [1, 1, 1]}, material={"ambient": 4.0, "diffuse": 0.0, "specular": 4.0},
                       transfer={"points": [[0, 1, 1, 1, 1], [1, 1, 1, 1, 1]]})
    cfg = config_for(scene)
    trav = make_traversal((16, 16, 16), scene.direction, cfg.weight_bits, 1)
    assert math.isclose(trav.sample_distance, math.sqrt(3), rel_tol=1e-9)
    lut, rmap = host_tables(scene, cfg, trav)
    f = render_frame(vol, trav, cfg, lut, rmap)
    one = 1 << cfg.acc_bits
    assert f.baseplane.min() >= 0 and f.baseplane.max() <= one
    assert np.all(f.baseplane[..., :3] <= f.baseplane[..., 3:4])


def test_thousands_of_faint_samples_accumulate():
    """Seed 004's failure case: n samples of tiny opacity a composite to 1 - (1 - a)^n
    (here within 1%), where 8-bit accumulation would lose them entirely."""
    n = 2000
    vol = np.full((n, 3, 3), 200, dtype=np.uint16)
    scene = make_scene(view={"direction": [0, 0, 1]}, material={"ambient": 1.0, "diffuse": 0.0, "specular": 0.0},
                       transfer={"points": [[0, 1, 1, 1, 0.002], [1, 1, 1, 1, 0.002]]})
    cfg = config_for(scene)
    trav = make_traversal((3, 3, n), scene.direction, cfg.weight_bits, 1)
    lut, rmap = host_tables(scene, cfg, trav)
    a_q = lut[200, 3] / (1 << cfg.alpha_bits)
    f = render_frame(vol, trav, cfg, lut, rmap)
    got = f.baseplane[1, 1, 3] / (1 << cfg.acc_bits)
    expect = 1 - (1 - a_q) ** n
    assert abs(got - expect) / expect < 0.01, (got, expect)
    # with only 8 accumulator bits the same frame loses most of it (seed 004's seams)
    cfg8 = config_for(scene, acc_bits=8)
    f8 = render_frame(vol, trav, cfg8, lut, rmap)
    got8 = f8.baseplane[1, 1, 3] / 256
    assert abs(got8 - expect) / expect > 0.5, (got8, expect)


def test_config_rejects_bad_values():
    from cube4.errors import UserError

    for kw in ({"pipelines": 0}, {"pipelines": 65}, {"voxel_bits": 3}, {"supersample": 3}, {"acc_bits": 40}):
        with pytest.raises(UserError):
            Cube4Config(**kw)

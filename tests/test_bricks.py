"""Sub-volume partitioning (numerics.md §14): bricks rendered on their own and composited
front to back equal the monolithic render within the proven bound; every sample counted
once and computed bit for bit as in the whole render; seed 004's 8-bit framebuffer seams."""

from __future__ import annotations

import math

import numpy as np
import pytest
from cube4_testutil import BRICK_TF, brick_volume, make_scene

from cube4.brick_rays import (brick_partials, composite_bound, composite_framebuffers, seam_lines,
                              seed004_correction)
from cube4.bricks import (OVERLAP_HIGH, OVERLAP_LOW, Tile, composite_tiles, counts_for_board, make_grid, over_planes,
                          owner_maps, parse_bricks, plan_bricks, render_bricked)
from cube4.clip import Clip, check_window, cut_coefficients
from cube4.config import Cube4Config
from cube4.errors import UserError
from cube4.host import host_tables
from cube4.model import render_frame
from cube4.view import make_traversal

VIEWS = [(0.3, -0.5, 1.0), (-1.0, 0.2, -0.7), (0.6, 1.0, -0.45), (1.0, 1.0, 1.0), (-0.2, -0.1, -1.0), (0.0, 0.0, 1.0)]
GRIDS = [(2, 2, 2), (3, 1, 2), (1, 3, 3)]
TF = BRICK_TF


def _setup(vol, direction, supersample=1, scene=None):
    nz, ny, nx = vol.shape
    cfg = Cube4Config(supersample=supersample)
    sc = scene or make_scene(transfer=TF)
    trav = make_traversal((nx, ny, nz), direction, cfg.weight_bits, supersample)
    lut, rmap = host_tables(sc, cfg, trav)
    return cfg, trav, lut, rmap


def _placed(brick, base, shape):
    """A brick's base plane embedded in the whole base plane (what lies outside must be empty)."""
    t = composite_tiles([Tile(brick.offset[0], brick.offset[1], base)], shape, 16)
    return t


# ------------------------------------------------------------------ grid, overlap, plan
def test_grid_owned_and_stored_ranges():
    g = make_grid((10, 7, 5), (3, 2, 1))
    assert g.bounds == ((0, 3, 6, 10), (0, 3, 7), (0, 5))
    assert g.owned((1, 1, 0)) == ((3, 3, 0), (6, 7, 5))
    assert g.stored((1, 1, 0)) == ((3 - OVERLAP_LOW, 3 - OVERLAP_LOW, 0), (6 + OVERLAP_HIGH, 7, 5))
    assert g.stored((0, 0, 0)) == ((0, 0, 0), (3 + OVERLAP_HIGH, 3 + OVERLAP_HIGH, 5))
    # Teramac Table 1's layout: 128^3 in p x p x 128 bricks; 3 voxels shared per inner boundary
    for p in (8, 16, 32, 64):
        g = make_grid((128, 128, 128), (128 // p, 128 // p, 1))
        per_axis = 128 + (OVERLAP_LOW + OVERLAP_HIGH) * (128 // p - 1)
        assert g.stored_voxels() == per_axis * per_axis * 128
    assert counts_for_board((512, 512, 512), 256) == (3, 3, 3)  # two bricks of 256 + overlap do not fit
    assert counts_for_board((254, 100, 40), 256) == (1, 1, 1)
    assert max(make_grid((512,) * 3, (3, 3, 3)).largest_brick()) <= 256


@pytest.mark.parametrize("text", ["2,1", "0,1,1", "a,b,c", "2,2,2,2", "-1,2,2", ""])
def test_parse_bricks_rejects(text):
    with pytest.raises(UserError, match="--bricks must be BX,BY,BZ"):
        parse_bricks(text)


def test_too_many_bricks_for_the_volume():
    with pytest.raises(UserError, match="8 bricks along y need at least 8 voxels"):
        make_grid((16, 7, 16), (1, 8, 1))


@pytest.mark.parametrize("supersample", [1, 2, 8])
@pytest.mark.parametrize("direction", VIEWS)
def test_every_sample_owned_by_exactly_one_brick(direction, supersample):
    """The windows partition the samples (owner_maps checks overlaps and gaps), and a
    brick's window lies inside its own traversal, away from its stored edges by the
    overlap the gradients need (one sample on each side unless at the volume's face)."""
    trav = make_traversal((18, 21, 24), direction, 8, supersample)
    for counts in GRIDS:
        grid = make_grid(trav.dims, counts)
        bricks = plan_bricks(trav, grid)
        owner_maps(trav, grid, bricks)
        for br in bricks:
            i0, i1, j0, j1, m0, m1 = br.clip.window
            bt = br.trav
            assert (bt.view_x, bt.view_y, bt.major, bt.flip) == (trav.view_x, trav.view_y, trav.major, trav.flip)
            for lo, hi, n, start, full in ((i0, i1, bt.ni, br.start[0], trav.ni), (j0, j1, bt.nj, br.start[1], trav.nj)):
                assert lo >= 0 or start == 0
                assert lo >= 1 or start == 0
                assert hi <= n - 2 or start + n == full
            assert m0 >= supersample or br.start[2] == 0
            assert m1 <= bt.num_sample_slices - 1 or br.start[2] + bt.nk == trav.nk
            check_window(br.clip.window, bt)   # what the window registers hold (S > 1: the last brick's m1)
        # front to back: a ray moves to bricks later in the list only
        pos = [br.start[::-1] for br in bricks]
        assert pos == sorted(pos)


# ------------------------------------------------------------------ bit-exact samples
@pytest.mark.parametrize("supersample", [1, 2])
def test_brick_samples_are_the_monolithic_samples(supersample):
    """Every sample a brick counts has the monolithic sample's value, gradient and shaded
    RGBA, bit for bit (the template's phase per brick), and the bricks count exactly
    the samples the whole render counts."""
    vol = brick_volume()
    for direction, counts in ((VIEWS[1], (2, 2, 2)), (VIEWS[2], (3, 1, 2)), (VIEWS[4], (1, 3, 3))):
        cfg, trav, lut, rmap = _setup(vol, direction, supersample)
        mono = render_frame(vol, trav, cfg, lut, rmap, keep_streams=True)
        grid = make_grid(trav.dims, counts)
        counted = 0
        for br in plan_bricks(trav, grid):
            x0, y0, z0 = br.trav.origin
            nx, ny, nz = br.trav.dims
            fr = render_frame(vol[z0:z0 + nz, y0:y0 + ny, x0:x0 + nx], br.trav, cfg, lut, rmap, keep_streams=True,
                              clip=br.clip)
            mm, jj, ii = np.nonzero(fr.streams["keep"] & fr.streams["inside"])
            i0, j0, k0 = br.start
            at = (mm + k0 * supersample, jj + j0, ii + i0)
            assert mono.streams["inside"][at].all()
            assert np.array_equal(fr.streams["samples"][mm, jj, ii], mono.streams["samples"][at])
            for name in ("gradients", "shaded"):
                assert np.array_equal(fr.streams[name][mm, :, jj, ii], mono.streams[name][at[0], :, at[1], at[2]])
            counted += mm.size
        assert counted == int(mono.streams["inside"].sum())


# ------------------------------------------------------------------ composite against monolithic
def _check_within_bound(vol, direction, counts, supersample=1, scene=None, clip=None):
    cfg, trav, lut, rmap = _setup(vol, direction, supersample, scene)
    mono = render_frame(vol, trav, cfg, lut, rmap, keep_streams=True, clip=clip)
    grid = make_grid(trav.dims, counts)
    bf = render_bricked(vol, trav, cfg, lut, rmap, grid, clip=clip)
    bound = composite_bound(mono, grid, bf.bricks)
    diff = np.abs(bf.frame.baseplane - mono.baseplane)
    assert np.all(diff[..., 3] <= bound["a"] + 1e-6), (direction, counts)
    assert np.all(diff[..., :3] <= bound["rgb"] + 1e-6), (direction, counts)
    # nothing differs where the ray stays in one brick: its partial is the whole ray
    assert not diff[bound["segments"] <= 1].any()
    # the design's re-composite of the whole render's samples, brick by brick, is each brick's own render
    parts = brick_partials(mono, grid, bf.bricks)
    for n, (br, res) in enumerate(zip(bf.bricks, bf.results)):
        assert np.array_equal(parts[n], _placed(br, res.baseplane, trav.baseplane_shape))
    return diff, bound


@pytest.mark.parametrize("supersample", [1, 2])
@pytest.mark.parametrize("direction", VIEWS)
def test_bricked_composite_within_bound(direction, supersample):
    vol = brick_volume()
    worst = 0.0
    for counts in GRIDS:
        diff, bound = _check_within_bound(vol, direction, counts, supersample)
        crossed = bound["segments"] >= 2
        assert crossed.any()
        worst = max(worst, float(diff.max()))
    assert worst > 0      # the bricks' roundings do differ from the whole render's: the check has teeth


def test_one_brick_is_the_monolithic_render():
    vol = brick_volume()
    cfg, trav, lut, rmap = _setup(vol, VIEWS[2], 2)
    mono = render_frame(vol, trav, cfg, lut, rmap)
    bf = render_bricked(vol, trav, cfg, lut, rmap, make_grid(trav.dims, (1, 1, 1)))
    assert np.array_equal(bf.frame.baseplane, mono.baseplane)


def test_xray_bricks_are_exact():
    """X-ray's saturating sum composes exactly: bricked == monolithic, bit for bit."""
    vol = brick_volume()
    sc = make_scene(transfer=TF, render={"mode": "xray"})
    cfg, trav, lut, rmap = _setup(vol, VIEWS[0], 1, sc)
    mono = render_frame(vol, trav, cfg, lut, None, mode="xray", shading=False)
    bf = render_bricked(vol, trav, cfg, lut, None, make_grid(trav.dims, (2, 2, 2)), mode="xray", shading=False)
    assert mono.baseplane[..., 3].max() > 0
    assert np.array_equal(bf.frame.baseplane, mono.baseplane)


def test_cut_plane_moves_into_the_bricks():
    """A cut plane (evaluated in each brick's frame) keeps the same samples as in the whole."""
    vol = brick_volume()
    cfg, trav, lut, rmap = _setup(vol, VIEWS[1])
    clip = Clip(plane=cut_coefficients(trav, (1.0, 0.4, -0.3), (9.0, 10.0, 12.0)))
    for counts in ((2, 2, 2), (1, 3, 3)):
        _check_within_bound(vol, VIEWS[1], counts, clip=clip)


def test_views_with_a_crop_box_and_a_cut_plane():
    """render_bricked_views: the scene's crop box is split into bricks (their origins in
    the whole volume), its cut plane moves into them; the composite is within the bound
    of the monolithic render of the same box, and the picture is warped like it."""
    from cube4.app.render import render_bricked_views, render_golden_view
    from cube4.host import frame_clip, setup_view
    vol = brick_volume()
    sc = make_scene(transfer=TF, crop={"box": [[2, 3, 1], [16, 19, 22]]},
                    cut={"normal": [1.0, 0.2, 0.5], "point": [9.0, 11.0, 12.0]}, view={"direction": [0.4, -1, 0.3]})
    cfg = Cube4Config()
    (res,) = render_bricked_views(vol, [sc], cfg, "golden", (2, 2, 2))
    whole = render_golden_view(vol, sc, cfg, keep_streams=True)
    nz, ny, nx = vol.shape
    trav, _ = setup_view((nx, ny, nz), sc, cfg)
    assert trav.origin == (2, 3, 1) and trav.dims == (15, 17, 22)
    grid = make_grid(trav.dims, (2, 2, 2))
    bricks = plan_bricks(trav, grid, frame_clip(sc, trav))
    assert min(br.trav.origin for br in bricks) == (2, 3, 1)
    bound = composite_bound(whole.frame, grid, bricks)
    diff = np.abs(res.frame.baseplane - whole.frame.baseplane)
    assert (bound["segments"] >= 2).any() and whole.frame.streams["keep"].sum() < whole.frame.streams["inside"].sum()
    assert np.all(diff[..., 3] <= bound["a"] + 1e-6) and np.all(diff[..., :3] <= bound["rgb"] + 1e-6)
    assert np.abs(res.image - whole.image).max() < 1e-3
    assert res.stats["bricks"]["grid"] == [2, 2, 2] and res.stats["traversed_box"]["origin"] == [2, 3, 1]


def test_no_constant_bound_per_boundary():
    """Why §14.3's bound grows with the samples after a boundary: one opaque-ish sample
    (T = 6144/65536 after it), then 550 samples of opacity 1/4096, split into two bricks
    along z. The whole render's T then falls by one LSB per sample (round(6144/4096) =
    2, then round(T/4096) = 1 for T >= 2048), the brick's by a sixteenth of that, so the
    two differ by hundreds of LSBs across one boundary -- and the bricked result is the
    one closer to the exact product. The bound holds."""
    nz = 1100
    vol = np.full((nz, 2, 2), 10, dtype=np.uint16)
    vol[549] = 20
    vol[550:] = 30
    cfg = Cube4Config()
    trav = make_traversal((2, 2, nz), (0, 0, 1), 8, 1)
    lut = np.zeros((256, 4), dtype=np.int64)
    lut[:, :3] = 255
    lut[20, 3] = 3712                      # 65536 - 16 * 3712 = 6144
    lut[30, 3] = 1
    mono = render_frame(vol, trav, cfg, lut, None, keep_streams=True, shading=False)
    grid = make_grid(trav.dims, (1, 1, 2))
    assert grid.bounds[2] == (0, 550, 1100)
    bf = render_bricked(vol, trav, cfg, lut, None, grid, shading=False)
    a_mono, a_brick = mono.baseplane[0, 0, 3], bf.frame.baseplane[0, 0, 3]
    exact = 65536 - 6144 * (1 - 1 / 4096) ** 550
    assert abs(int(a_mono) - int(a_brick)) > 200
    assert abs(a_brick - exact) < 2 < abs(a_mono - exact)
    bound = composite_bound(mono, grid, bf.bricks)
    assert bound["segments"][0, 0] == 2
    assert abs(int(a_mono) - int(a_brick)) <= bound["a"][0, 0]


def test_over_identity_order_and_invariant():
    """Transparent is the identity on both sides; the result keeps R, G, B <= A <= 2^F;
    over is not commutative (order matters)."""
    rng = np.random.default_rng(7)
    f = 16
    one = 1 << f
    def partial(n):
        a = rng.integers(0, one + 1, n)
        c = (rng.integers(0, one + 1, (3, n)) * a) // one
        return np.stack([*c, a], axis=-1)
    x, y = partial(5000), partial(5000)
    zero = np.zeros_like(x)
    assert np.array_equal(over_planes(x, zero, f), x) and np.array_equal(over_planes(zero, x, f), x)
    out = over_planes(x, y, f)
    assert (out[:, :3] <= out[:, 3:4]).all() and (out[:, 3] <= one).all()
    assert not np.array_equal(out, over_planes(y, x, f))
    # exact in the reals up to the rounding of T_f * X_b: within 1/2 LSB
    exact = x + (one - x[:, 3:4]) * y / one
    assert np.abs(out - exact).max() <= 0.5


# ------------------------------------------------------------------ seed 004: 8-bit framebuffer seams
def _faint_setup(supersample):
    """A slab of faint material (per voxel opacity 0.03, colour 0.4), seen obliquely
    through a split along x: rays near the split cross two bricks."""
    vol = np.zeros((24, 12, 32), dtype=np.uint16)
    vol[2:22, 1:11, 2:30] = 200
    sc = make_scene(transfer={"points": [[0, 0, 0, 0, 0], [0.5, 0.4, 0.4, 0.4, 0.03], [1, 0.4, 0.4, 0.4, 0.03]]},
                    material={"shading": False})
    nz, ny, nx = vol.shape
    cfg = Cube4Config(supersample=supersample)
    trav = make_traversal((nx, ny, nz), (0.45, 0.1, 1.0), 8, supersample)
    lut, _ = host_tables(sc, cfg, trav)
    mono = render_frame(vol, trav, cfg, lut, None, keep_streams=True, shading=False)
    grid = make_grid(trav.dims, (2, 1, 1))
    return vol, cfg, trav, lut, mono, grid


def test_seed004_seams_in_an_8bit_framebuffer():
    vol, cfg, trav, lut, mono, grid = _faint_setup(4)
    bricks = plan_bricks(trav, grid)
    segments = composite_bound(mono, grid, bricks)["segments"]
    crossed = segments >= 2
    hit = mono.baseplane[..., 3] > 0
    assert crossed.any() and (hit & ~crossed).any()
    lines = seam_lines(mono, grid, bricks)          # where rays in one brick meet rays in two
    assert lines.any() and not (lines & (segments == 0)).any()
    assert (lines & crossed).any() and (lines & (segments == 1)).any()
    # their per-sample premultiplied colour is below 1/255: an 8-bit framebuffer draws none of it
    a = mono.streams["shaded"][:, 3][mono.streams["inside"]] / 4096.0
    assert (a * 0.4 * 255).max() < 1
    one_node = composite_framebuffers(brick_partials(mono, make_grid(trav.dims, (1, 1, 1)),
                                                     plan_bricks(trav, make_grid(trav.dims, (1, 1, 1))), "fb8"))
    nodes = composite_framebuffers(brick_partials(mono, grid, bricks, "fb8"))
    design = mono.baseplane / 65536.0
    assert one_node[..., :3].max() == 0 and design[..., 0].max() > 0.1
    # the seam: the 8-bit composite of two nodes differs from one node's only where rays cross the split
    seam = np.abs(nodes - one_node).max(axis=-1)
    assert seam[~crossed].max() == 0 and seam[crossed].max() >= 3
    # the design's accumulators: the bricked composite is within its bound of the whole (a few 2^-16)
    bf = render_bricked(vol, trav, cfg, lut, None, grid, shading=False)
    assert np.abs(bf.frame.baseplane - mono.baseplane).max() <= 8


def test_seed004_correction_raises_opacity_and_lowers_the_rate():
    """Their eq. 4/5 rule: fewer, more opaque samples; at S = 1 instead of 4 the 8-bit
    framebuffer keeps some colour, and the bricked 8-bit composite comes closer to the
    design's monolithic render at the original rate."""
    a_new, sr_new = seed004_correction(0.0076, 0.4, 4.0)
    assert a_new > 0.0076 and sr_new < 4.0
    assert math.isclose(1 - (1 - 0.0076) ** (4.0 / sr_new), a_new, rel_tol=1e-9)   # eq. 4 and 5 agree
    errs = {}
    ref = _faint_setup(4)[4].baseplane / 65536.0
    for s in (4, 1):
        _, _, trav, _, mono, grid = _faint_setup(s)
        fb = composite_framebuffers(brick_partials(mono, grid, plan_bricks(trav, grid), "fb8")) / 255.0
        errs[s] = float(np.sqrt(np.mean((fb - ref) ** 2)))
    assert errs[1] < errs[4]


@pytest.mark.parametrize("direction", [VIEWS[0], VIEWS[3]])
def test_path_weighted_xray_bricks_are_exact(direction):
    """Path weights (numerics.md §17) compose: a brick weighs only the ends on the volume's
    faces (its FACES from sub_traversal), so X-ray bricks equal the monolithic render bit
    for bit with the weights on, and the weights do change that render."""
    vol = brick_volume()
    sc = make_scene(transfer=TF, render={"mode": "xray", "path_weights": True})
    cfg, trav, lut, rmap = _setup(vol, direction, 1, sc)
    assert lut.shape[1] == 8
    mono = render_frame(vol, trav, cfg, lut, None, mode="xray", shading=False)
    plain = render_frame(vol, trav, cfg, lut[:, :4], None, mode="xray", shading=False)
    assert not np.array_equal(mono.baseplane, plain.baseplane)
    bf = render_bricked(vol, trav, cfg, lut, None, make_grid(trav.dims, (2, 2, 2)), mode="xray", shading=False)
    assert np.array_equal(bf.frame.baseplane, mono.baseplane)

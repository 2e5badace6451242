"""Bricks through the simulated RTL: every brick's base plane from cube4_top (its own
voxels as a board's whole memory, the template's starting phase PH0_X/Y, the window
registers) equals the golden model's brick, bit for bit, so the RTL composite is the
golden composite, within the §14 bound of the monolithic render.

The boards are the full build at P = 5 and MAX_DIM = 64 that tb/cube4_top also uses, so
`make test` builds it once for both; the voxel-gradient boards (a build of their own) run in
`make regress`."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from cube4_testutil import BRICK_TF, brick_volume, make_scene

from cube4.brick_rays import composite_bound
from cube4.bricks import Tile, brick_tasks, composite_tiles, make_grid, render_brick_golden, render_bricked
from cube4.builds import FULL_BUILD
from cube4.config import Cube4Config
from cube4.host import host_tables
from cube4.model import render_frame
from cube4.view import make_traversal
from cube4_sim.bricks import render_brick_rtl
from cube4_sim.engine import register

BOARD_CFG = Cube4Config(pipelines=5, build=tuple(FULL_BUILD.items()))
BOARD_DIM = 64


def test_rtl_bricks_equal_golden_bricks():
    register()
    vol = brick_volume()
    nz, ny, nx = vol.shape
    cfg = BOARD_CFG
    trav = make_traversal((nx, ny, nz), (-1.0, 0.2, -0.7), cfg.weight_bits, 1)
    lut, rmap = host_tables(make_scene(transfer=BRICK_TF), cfg, trav)
    grid = make_grid(trav.dims, (2, 1, 2))
    bricks, tasks = brick_tasks(vol, trav, cfg, lut, rmap, grid, engine="rtl", board_dim=BOARD_DIM)
    assert any(br.trav.phase_x or br.trav.phase_y for br in bricks)    # the starting phase is exercised
    tiles = []
    for br, task in zip(bricks, tasks):
        rtl = render_brick_rtl(task)
        golden = render_brick_golden(dataclasses.replace(task, target="cube4.bricks:render_brick_golden"))
        assert np.array_equal(rtl.baseplane, golden.baseplane), br.index
        assert rtl.cycles and rtl.cycles > 0
        tiles.append(Tile(br.offset[0], br.offset[1], rtl.baseplane))
    composite = composite_tiles(tiles, trav.baseplane_shape, cfg.acc_bits)
    assert np.array_equal(composite, render_bricked(vol, trav, cfg, lut, rmap, grid).frame.baseplane)
    mono = render_frame(vol, trav, cfg, lut, rmap, keep_streams=True)
    bound = composite_bound(mono, grid, bricks)
    diff = np.abs(composite - mono.baseplane)
    assert diff.max() > 0
    assert np.all(diff[..., 3] <= bound["a"] + 1e-6) and np.all(diff[..., :3] <= bound["rgb"] + 1e-6)


def test_rtl_bricks_on_two_workers_share_one_build():
    """Two worker processes simulate the same cached build at once: each reads its own
    results file (with one shared file about every other frame lost a brick's results,
    which then ran again), and the composite is the golden one."""
    from cube4.app.cluster import DaskExecutor
    from cube4.app.volumes import load_volume
    from cube4.bricks import assemble
    from cube4.scene import load_scene

    register()
    vol = load_volume("head:32")
    scene = load_scene("head")
    cfg = BOARD_CFG
    trav = make_traversal((32, 32, 32), scene.direction, cfg.weight_bits, 1)
    lut, rmap = host_tables(scene, cfg, trav)
    grid = make_grid(trav.dims, (2, 1, 2))    # four bricks: two at a time on each worker
    bricks, tasks = brick_tasks(vol, trav, cfg, lut, rmap, grid, engine="rtl", board_dim=BOARD_DIM)
    with DaskExecutor(workers=2, timeout=240) as ex:
        results = ex.run(tasks)
        stats = ex.stats()
    assert stats["retries"] == 0
    assert len({r.worker for r in results}) == 2          # both workers simulated
    frame, _ = assemble(trav, cfg, bricks, results)
    assert np.array_equal(frame.baseplane, render_bricked(vol, trav, cfg, lut, rmap, grid).frame.baseplane)


@pytest.mark.regress
def test_rtl_bricks_with_voxel_gradients():
    """Bricks of a voxel-gradient scene through the RTL (the boards a VGRAD build, each
    loaded with its brick of the whole volume's words): the composited base plane equals
    the golden bricked render's, bit for bit."""
    from cube4.app.render import render_bricked_views
    from cube4.host import config_for

    register()
    vol = brick_volume()
    sc = dataclasses.replace(make_scene(transfer=BRICK_TF, light=[{"direction": [1, -1, -1]}]),
                             gradient="sobel")
    cfg = config_for(sc, 4)
    (rtl,) = render_bricked_views(vol, [sc], cfg, "rtl", (2, 1, 1), board_dim=BOARD_DIM)
    (gold,) = render_bricked_views(vol, [sc], cfg, "golden", (2, 1, 1))
    assert rtl.stats["bricks"]["count"] == 2
    assert np.array_equal(rtl.frame.baseplane, gold.frame.baseplane)

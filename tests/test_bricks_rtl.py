"""Bricks through the simulated RTL: every brick's base plane from cube4_top equals the
golden model's brick, bit for bit, so the RTL composite is the golden composite, within
the §14 bound of the monolithic render.

Needs the RTL's template starting phase (PH0_X, PH0_Y) and window registers; until the
RTL host side programs them (``cube4_sim.bricks.rtl_supports_bricks``) this test is
skipped with that reason, and the ``rtl`` engine refuses bricks with one clear line."""

from __future__ import annotations

import numpy as np
import pytest
from cube4_testutil import BRICK_TF, brick_volume, make_scene

from cube4.brick_rays import composite_bound
from cube4.bricks import Tile, brick_tasks, composite_tiles, make_grid, render_bricked, run_task
from cube4.config import Cube4Config
from cube4.model import render_frame
from cube4.render import host_tables
from cube4.view import make_traversal
from cube4_sim.bricks import render_brick_rtl, rtl_supports_bricks
from cube4_sim.engine import register

NOT_YET = ("the RTL has no template starting phase (PH0_X, PH0_Y) and window registers yet: "
           "bricks through the RTL are not supported by this tree")


def test_rtl_refuses_bricks_without_the_registers(tmp_path, capsys):
    """Until the registers exist, bricks on the rtl engine are one line, not a wrong picture."""
    if rtl_supports_bricks():
        pytest.skip("the RTL has the brick registers")
    from cube4_sim.cli import main

    rc = main(["render", "sphere:16", "--engine", "rtl", "--bricks", "2,1,1", "--quiet",
               "--out", str(tmp_path / "x.png")])
    err = capsys.readouterr().err
    assert rc == 2 and "PH0_X" in err and err.count("\n") == 1


@pytest.mark.skipif(not rtl_supports_bricks(), reason=NOT_YET)
def test_rtl_bricks_equal_golden_bricks():
    register()
    vol = brick_volume()
    nz, ny, nx = vol.shape
    cfg = Cube4Config(pipelines=4)
    trav = make_traversal((nx, ny, nz), (-1.0, 0.2, -0.7), cfg.weight_bits, 1)
    lut, rmap = host_tables(make_scene(transfer=BRICK_TF), cfg, trav)
    grid = make_grid(trav.dims, (2, 1, 2))
    bricks, tasks = brick_tasks(vol, trav, cfg, lut, rmap, grid, engine="rtl")
    tiles = []
    for br, task in zip(bricks, tasks):
        rtl = render_brick_rtl(task)
        golden = run_task(task.__class__(**{**task.__dict__, "target": "cube4.bricks:render_brick_golden"}))
        assert np.array_equal(rtl.baseplane, golden.baseplane), br.index
        assert rtl.cycles and rtl.cycles > 0
        tiles.append(Tile(br.offset[0], br.offset[1], rtl.baseplane))
    composite = composite_tiles(tiles, trav.baseplane_shape, cfg.acc_bits)
    assert np.array_equal(composite, render_bricked(vol, trav, cfg, lut, rmap, grid).frame.baseplane)
    mono = render_frame(vol, trav, cfg, lut, rmap, keep_streams=True)
    bound = composite_bound(mono, grid, bricks)
    diff = np.abs(composite - mono.baseplane)
    assert np.all(diff[..., 3] <= bound["a"] + 1e-6) and np.all(diff[..., :3] <= bound["rgb"] + 1e-6)

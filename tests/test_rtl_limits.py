"""The RTL engine's limits are checked before any file is written or anything built."""

from __future__ import annotations

import numpy as np
import pytest

from cube4.config import Cube4Config
from cube4.errors import UserError
from cube4.builds import named
from cube4_sim.rtl import SIM_MAX_DIM, build_max_dim, build_params, check_limits, render_frames


@pytest.mark.parametrize("n", [SIM_MAX_DIM, SIM_MAX_DIM + 1])
def test_simulated_memory_limit(n):
    cfg = Cube4Config(pipelines=8)
    dims = (n, n, 8)
    params = build_params(cfg, build_max_dim(dims))
    if n <= SIM_MAX_DIM:
        check_limits(params, dims)
    else:
        with pytest.raises(UserError, match="simulated voxel memory .* --engine golden"):
            check_limits(params, dims)


def test_address_width_limit():
    params = {"P": 1, "DEPTH": 1 << 31, "ADDR_W": 31, "MAX_DIM": 2048}
    with pytest.raises(UserError, match="words per bank, more than the RTL's 2\\^30"):
        check_limits(params, (2048, 2048, 512))


def test_render_frames_stops_before_any_work(tmp_path, monkeypatch):
    """A 1024 x 8 x 8 volume is in the 1024^3 size class: refused before the runner is
    imported or a file is written."""
    import sys

    monkeypatch.delitem(sys.modules, "cube4_sim.runner", raising=False)
    vol = np.zeros((8, 8, 1024), dtype=np.uint16)
    with pytest.raises(UserError, match="simulated voxel memory"):
        render_frames(vol, [], Cube4Config(), workdir=tmp_path / "job")
    assert "cube4_sim.runner" not in sys.modules and not (tmp_path / "job").exists()


def test_voxel_gradient_words_count_their_bytes():
    """A voxel-gradient word (41 bits at V = 8) takes 8 bytes in the simulator: the 512³
    size class no longer fits, 256³ does."""
    cfg = Cube4Config(pipelines=8)
    vg = named("vgrad")
    check_limits(build_params(cfg, 256, build=vg), (256, 256, 256))
    check_limits(build_params(cfg, SIM_MAX_DIM), (SIM_MAX_DIM,) * 3)
    with pytest.raises(UserError, match="with voxel gradients"):
        check_limits(build_params(cfg, SIM_MAX_DIM, build=vg), (SIM_MAX_DIM,) * 3)

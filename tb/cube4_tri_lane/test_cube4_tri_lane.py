"""Unit testbench of rtl/cube4_tri_lane.v: one lane's seven lerps per channel, bit for bit.

Every cycle a new 2 x 2 x 2 cell enters (vals, nvals: rows j and j + 1 of the lower and
upper slice at i and i + 1) with its weights, each at the cycle the unit's header gives:
the cell also one cycle before on pre_vals, pre_nvals (the x-lerps' differences are
formed from those; vals and nvals then carry the cell's a values and, on nvals, noise
where a word is only a b of the x-lerps, so that a lane reading b from nvals fails),
wx one cycle before the cell, wy TRI_LERP_LAT - 1 and wz 2 * TRI_LERP_LAT - 1 cycles
after it. 3 * TRI_LERP_LAT cycles after the cell the sample must equal the golden
``cube4.model.interpolate_pair`` of the cell's two slices (x, y, z lerps in the golden
order; with VGRAD the word's value and its three signed components, each interpolated
alike, ``cube4.model.voxel_gradient_slice``; words ``cube4.vgrad.pack_channels``).
The cells are random, then corner cells (every value 0 or the channel's extreme, every
weight 0 or 2^W - 1), so the rounding of full-scale products is covered. The unit has no
stream interface (it moves on every cycle); the check counts the compared samples.

The test can fail (tried with a deliberately corrupted expectation, not kept): with the
golden sample of cell 40 raised by one, the VOXEL_W = 8 build fails with "cell 40: sample
0x64, golden 0x65".
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly

from cube4.model import interpolate_pair
from cube4.vgrad import grad_bits, pack_channels, unpack_words
from cube4_sim.beats import pack_fields
from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import param_id, run_rtl, start_clock

N = 400
LAT = 4          # TRI_LERP_LAT (rtl/cube4_defs.vh)
WX_LEAD, WY_DELAY, WZ_DELAY, OUT_DELAY = 1, LAT - 1, 2 * LAT - 1, 3 * LAT


class CellWeights:
    """The one thing interpolate_pair asks of a traversal: the weights of slice m."""

    def __init__(self, wx: int, wy: int, wz: int) -> None:
        self.w = (wx, wy, wz)

    def weights(self, m):
        return self.w


def random_cells(rng, vw: int, w: int, vgrad: bool, n: int):
    """n cells (n, 2 slices, 2 rows, 2 columns) of words, weights (n, 3), then the corner
    cells: each value 0 or the extreme, each weight 0 or 2^W - 1 (the same for all
    channels of a word)."""
    shape = (n, 2, 2, 2)
    value = rng.integers(0, 1 << vw, size=shape)
    weights = rng.integers(0, 1 << w, size=(n, 3))
    corners = rng.integers(0, 2, size=shape).astype(bool)
    value[-64:][corners[-64:]] = (1 << vw) - 1
    value[-64:][~corners[-64:]] = 0
    weights[-64:] = rng.integers(0, 2, size=(64, 3)) * ((1 << w) - 1)
    if not vgrad:
        return value, weights
    half = 1 << (grad_bits(vw) - 1)
    comps = rng.integers(-half, half, size=(3, *shape))
    comps[:, -64:] = np.where(rng.integers(0, 2, size=(3, 64, 2, 2, 2)) != 0, half - 1, -half)
    return pack_channels(value, comps, vw), weights


def golden_sample(cell: np.ndarray, wts, vw: int, w: int, vgrad: bool) -> int:
    """interpolate_pair of the cell's lower and upper slice (each 2 x 2: [row, column])."""
    trav = CellWeights(*(int(x) for x in wts))
    if not vgrad:
        return int(interpolate_pair(cell[0], cell[1], trav, 0, w)[0, 0])
    value, comps = unpack_words(cell, vw)
    s = interpolate_pair(value[0], value[1], trav, 0, w)
    g = np.stack([interpolate_pair(c[0], c[1], trav, 0, w) for c in comps])
    return int(pack_channels(s, g, vw)[0, 0])


def lane_words(cell: np.ndarray, col: int, ww: int) -> int:
    """The 4 words of column ``col``: {prev upper, prev lower, cur upper, cur lower}, MSB first
    (row 0 = j, the previous row; row 1 = j + 1, the current one; slice 0 lower, 1 upper)."""
    return pack_fields([cell[1, 0, col], cell[0, 0, col], cell[1, 1, col], cell[0, 1, col]], ww)


@cocotb.test()
async def test_lerps(dut):
    vw, w, vgrad = int(dut.VOXEL_W.value), int(dut.WEIGHT_W.value), bool(int(dut.VGRAD.value))
    ww = vw + (3 * grad_bits(vw) if vgrad else 0)
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    start_clock(dut)
    cells, weights = random_cells(rng, vw, w, vgrad, N)
    want = [golden_sample(cells[n], weights[n], vw, w, vgrad) for n in range(N)]
    checked = 0
    for t in range(-WX_LEAD, N + OUT_DELAY):
        await FallingEdge(dut.clk)
        if 0 <= t < N:
            dut.vals.value = lane_words(cells[t], 0, ww)
            # (nvals: the x-lerps' b; their differences come from pre_nvals, so nvals
            # carries noise; it is read as it is only by the label picks, not built here)
            dut.nvals.value = int.from_bytes(rng.bytes(ww), "little") % (1 << (4 * ww))
        if 0 <= t + 1 < N:
            dut.pre_vals.value = lane_words(cells[t + 1], 0, ww)
            dut.pre_nvals.value = lane_words(cells[t + 1], 1, ww)
        if 0 <= t + WX_LEAD < N:
            dut.wx.value = int(weights[t + WX_LEAD, 0])
        if 0 <= t - WY_DELAY < N:
            dut.wy.value = int(weights[t - WY_DELAY, 1])
        if 0 <= t - WZ_DELAY < N:
            dut.wz.value = int(weights[t - WZ_DELAY, 2])
        k = t - OUT_DELAY
        if k >= 0:
            await ReadOnly()
            got = int(dut.sample.value)
            assert got == want[k], (f"cell {k}: sample {got:#x}, golden {want[k]:#x} (weights "
                                    f"{weights[k].tolist()}, cell {cells[k].ravel().tolist()})")
            checked += 1
    assert checked == N, f"{checked} samples compared, expected {N}"
    dut._log.info("VOXEL_W=%d WEIGHT_W=%d VGRAD=%d: %d cells bit-exact", vw, w, vgrad, checked)


BUILDS = [dict(VOXEL_W=8, WEIGHT_W=8, VGRAD=0), dict(VOXEL_W=12, WEIGHT_W=12, VGRAD=1),
          dict(VOXEL_W=1, WEIGHT_W=4, VGRAD=0), dict(VOXEL_W=16, WEIGHT_W=12, VGRAD=0),
          dict(VOXEL_W=4, WEIGHT_W=4, VGRAD=1)]


@pytest.mark.parametrize("build", sweep(BUILDS, quick=(0, 1), ids=param_id))
def test_cube4_tri_lane(build):
    run_rtl(__file__, build)

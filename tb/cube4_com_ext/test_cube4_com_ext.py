"""Unit testbench of rtl/cube4_com_ext.v: one lane's MIP / MinIP step, bit for bit.

Every cycle a new sample enters: its v at R0 (v0), the ray's kept {v, R, G, B, A} at S5
(acc5, five cycles later), the sample's "counts" flag at S6 (cnt6) and its {R, G, B, A}
at S7 (rgba7); six edges after S5, acc_q and pix must equal the golden step
(``cube4.model.extremum``: take when v >= (MinIP: <=) the kept v and the sample counts)
and ``cube4.model.extremum_pixel`` of the result (colour << (ACC_W - 8), A shifted or
round_shift'ed to ACC_W bits), and termination's flag on the new word (done_q:
``cube4.beats.TerminationRule.dead``, vmin and vmax two of the drawn values). v and the kept v are drawn from a few values so that
ties (v = kept v) are frequent; about one sample in five does not count. The unit has
no stream interface (it moves on every cycle); the check counts the compared outputs.

The test can fail (tried with a deliberately corrupted expectation, not kept).
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from cube4.beats import TerminationRule
from cube4.config import Cube4Config
from cube4.model import extremum, extremum_pixel
from cube4_sim import rtl_sources, run_test

N = 600


def pack(vals, widths) -> int:
    """Fields MSB first."""
    word = 0
    for v, w in zip(vals, widths):
        word = (word << w) | int(v)
    return word


@cocotb.test()
async def test_extremum(dut):
    aw, acc_w, vw = int(dut.ALPHA_W.value), int(dut.ACC_W.value), int(dut.VOXEL_W.value)
    cfg = Cube4Config(alpha_bits=aw, acc_bits=acc_w, voxel_bits=vw)
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    Clock(dut.clk, 10, unit="ns").start(start_high=False)
    widths = [vw, 8, 8, 8, aw]
    checked = dones = 0
    for minimum in (False, True):
        vals = rng.integers(0, 1 << vw, size=4)                  # few values: many ties
        s = rng.choice(vals, size=N)
        value = rng.choice(vals, size=N)
        held = np.stack([rng.integers(0, 256, size=N) for _ in range(3)] + [rng.integers(0, 1 << aw, size=N)])
        rgba = np.stack([rng.integers(0, 256, size=N) for _ in range(3)] + [rng.integers(0, 1 << aw, size=N)])
        rgba[3, rng.random(N) < 0.2] = (1 << aw) - 1
        count = rng.random(N) >= 0.2
        exp_v, exp_h = value.copy(), held.copy()
        extremum(exp_v, exp_h, s, rgba, count, minimum)
        exp_pix = extremum_pixel(exp_h, cfg)
        dut.mode_min.value = int(minimum)
        vmin, vmax = int(vals.min()), int(vals.max())
        dut.vmin.value, dut.vmax.value = vmin, vmax
        rule = TerminationRule("minip" if minimum else "mip", 0, 1 << acc_w, vmin, vmax, value_bits=vw)
        exp_done = rule.dead(None, None, exp_v)
        for t in range(N + 11):
            await FallingEdge(dut.clk)
            if t < N:
                dut.v0.value = int(s[t])
            if 5 <= t < N + 5:
                k = t - 5
                dut.acc5.value = pack([value[k], *held[:, k]], widths)
            if 6 <= t < N + 6:
                dut.cnt6.value = int(count[t - 6])
            if 7 <= t < N + 7:
                dut.rgba7.value = pack(rgba[:, t - 7], widths[1:])
            k = t - 11
            if k >= 0:
                got, want = int(dut.acc_q.value), pack([exp_v[k], *exp_h[:, k]], widths)
                pix, want_pix = int(dut.pix.value), pack(exp_pix[:, k], [acc_w + 1] * 4)
                what = "MinIP" if minimum else "MIP"
                assert got == want, (f"{what} sample {k}: acc_q {got:#x}, golden {want:#x} (v {s[k]}, kept "
                                     f"{value[k]}, counts {count[k]})")
                assert pix == want_pix, f"{what} sample {k}: pix {pix:#x}, golden {want_pix:#x}"
                done = int(dut.done_q.value)
                assert done == int(exp_done[k]), f"{what} sample {k}: done {done}, golden {int(exp_done[k])}"
                dones += done
                checked += 1
    assert checked == 2 * N, f"{checked} outputs compared, expected {2 * N}"
    assert 0 < dones < checked, f"done on {dones} of {checked} steps: the flag would not be seen"
    dut._log.info("VOXEL_W=%d ALPHA_W=%d ACC_W=%d: %d steps bit-exact", vw, aw, acc_w, checked)


BUILDS = [{"ALPHA_W": 12, "ACC_W": 16, "VOXEL_W": 8}, {"ALPHA_W": 16, "ACC_W": 8, "VOXEL_W": 12}]


@pytest.mark.parametrize("params", BUILDS, ids=lambda p: f"a{p['ALPHA_W']}_f{p['ACC_W']}_v{p['VOXEL_W']}")
def test_cube4_com_ext(params):
    run_test(top="cube4_com_ext", sources=rtl_sources(), params=params, test_module=__file__)

"""Unit testbench of rtl/cube4_com_blend.v: one lane's composite / X-ray step, bit for bit.

Every cycle a new sample enters at S5 (acc5 = the ray's {C_R, C_G, C_B, T}, a5 = its A,
t5 = T's factor in T·A as cube4_com_lane forms it: 2^ACC_W in X-ray, else T),
with its colour and its "counts" flag two cycles later (c7, cnt7: S7); six edges later acc_q and pix must equal the golden step (``cube4.model.composite``
or ``cube4.model.xray`` on the same values: w, the rounding, X-ray's saturation) and
the pixel {C_R, C_G, C_B, 2^ACC_W - T}, and termination's flags on the new word
(done: ``cube4.beats.TerminationRule.dead`` of composite with a random τ,
and of X-ray). The partial results are random but legal
(composite: C <= 2^ACC_W - T per channel, as numerics.md section 7 guarantees; X-ray:
anything up to 2^ACC_W, with many values at 0 and 2^ACC_W), A and the colours random
with their extremes, about one sample in five does not count. The unit has no stream
interface (it moves on every cycle); the check counts the compared outputs.

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
from cube4.model import composite, xray
from cube4_sim import rtl_sources, run_test
from cube4_sim.beats import pack_fields

LATENCY = 6       # S5 -> S11
N = 600           # samples per mode


def random_states(rng, n: int, acc_w: int, alpha_w: int, mode: str):
    """(acc (3, n), trans (n,), rgba (4, n), count (n,)): legal partial results and samples."""
    one = 1 << acc_w
    edge = lambda hi: rng.choice([0, hi, rng.integers(0, hi + 1)], size=n)  # noqa: E731
    trans = np.where(rng.random(n) < 0.3, edge(one), rng.integers(0, one + 1, size=n))
    if mode == "composite":
        acc = np.stack([rng.integers(0, one - trans + 1) for _ in range(3)])
    else:
        acc = np.stack([np.where(rng.random(n) < 0.3, edge(one), rng.integers(0, one + 1, size=n))
                        for _ in range(3)])
    rgba = np.stack([rng.integers(0, 256, size=n) for _ in range(3)]
                    + [np.where(rng.random(n) < 0.2, (1 << alpha_w) - 1, rng.integers(0, 1 << alpha_w, size=n))])
    rgba[:3, rng.random(n) < 0.1] = 255
    count = rng.random(n) >= 0.2
    return acc.astype(np.int64), trans.astype(np.int64), rgba.astype(np.int64), count


@cocotb.test()
async def test_blend(dut):
    aw, acc_w = int(dut.ALPHA_W.value), int(dut.ACC_W.value)
    cw = acc_w + 1
    cfg = Cube4Config(alpha_bits=aw, acc_bits=acc_w)
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    Clock(dut.clk, 10, unit="ns").start(start_high=False)
    checked = dones = 0
    for mode in ("composite", "xray"):
        acc, trans, rgba, count = random_states(rng, N, acc_w, aw, mode)
        exp_acc, exp_t = acc.copy(), trans.copy()
        (composite if mode == "composite" else xray)(exp_acc, exp_t, rgba, count, cfg)
        dut.mode_xray.value = int(mode == "xray")
        tau = int(rng.integers(0, 1 << acc_w))
        dut.tau.value = tau
        rule = TerminationRule(mode, tau, 1 << acc_w)
        exp_done = rule.dead(exp_acc, exp_t, None)
        for t in range(N + LATENCY):
            await FallingEdge(dut.clk)
            if t < N:
                dut.acc5.value = pack_fields([*acc[:, t], trans[t]], cw)
                dut.t5.value = (1 << acc_w) if mode == "xray" else int(trans[t])   # T's factor (the lane's)
                dut.a5.value = int(rgba[3, t])
            if 2 <= t <= N + 1:
                dut.c7.value = pack_fields(rgba[:3, t - 2], 8)
                dut.cnt7.value = int(count[t - 2])
            k = t - LATENCY
            if k >= 0:
                got = int(dut.acc_q.value)
                want = pack_fields([*exp_acc[:, k], exp_t[k]], cw)
                pix = int(dut.pix.value)
                want_pix = pack_fields([*exp_acc[:, k], (1 << acc_w) - exp_t[k]], cw)
                assert got == want, (f"{mode} sample {k}: acc_q {got:#x}, golden {want:#x} (C {acc[:, k]}, "
                                     f"T {trans[k]}, RGBA {rgba[:, k]}, counts {count[k]})")
                assert pix == want_pix, f"{mode} sample {k}: pix {pix:#x}, golden {want_pix:#x}"
                done = int(dut.done.value)
                assert done == int(exp_done[k]), f"{mode} sample {k}: done {done}, golden {int(exp_done[k])} (tau {tau})"
                dones += done
                checked += 1
    assert checked == 2 * N, f"{checked} outputs compared, expected {2 * N}"
    assert 0 < dones < checked, f"done on {dones} of {checked} steps: the flags would not be seen"
    dut._log.info("ALPHA_W=%d ACC_W=%d: %d steps bit-exact", aw, acc_w, checked)


BUILDS = [{"ALPHA_W": 12, "ACC_W": 16}, {"ALPHA_W": 16, "ACC_W": 8}]


@pytest.mark.parametrize("params", BUILDS, ids=lambda p: f"a{p['ALPHA_W']}_f{p['ACC_W']}")
def test_cube4_com_blend(params):
    run_test(top="cube4_com_blend", sources=rtl_sources(), params=params, test_module=__file__)

"""Unit testbench of rtl/cube4_com_lane.v: one COM lane around its datapaths, bit for bit.

Every cycle a new sample enters R0 (in_rgba, in_sample); three cycles later its A
leaves as a3 (checked) and a different, random A comes back as a3_w (what the path
weights would put there); at S5 the lane gets the buffer's three candidate words
(back5, back_sh, prevb_sh, random legal partial results of the mode) and, one cycle
earlier, the sample's selects (dxb, t0, fresh: random). Six edges after S5, acc_q and
pix must equal the golden step of the mode on the chosen word (fresh: C = 0, T = 1;
v = 0 for MIP, 2^VOXEL_W - 1 for MinIP; else dxb ? (t0 ? prevb_sh : back_sh) : back5):
``cube4.model.composite`` / ``xray`` / ``extremum`` / ``extremum_pixel``, with the
sample's colour, A = a3_w, v and its "counts" flags (cnt_6, cnt_7). All four modes run
in one simulation (the mode is static within a run). The unit has no stream interface
(it moves on every cycle); the check counts the compared outputs.

The test can fail (tried with a deliberately corrupted expectation, not kept).
"""

from __future__ import annotations

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from cube4.config import Cube4Config
from cube4.model import composite, extremum, extremum_pixel, xray
from cube4_sim import rtl_sources, run_test

N = 300           # samples per mode
S5 = 6            # R0 at cycle k: S5 at k + 6
OUT = S5 + 6      # acc_q, pix


def pack(vals, widths) -> int:
    word = 0
    for v, w in zip(vals, widths):
        word = (word << w) | int(v)
    return word


def unpack(word: int, widths) -> list[int]:
    out = []
    for w in reversed(widths):
        out.append(word & ((1 << w) - 1))
        word >>= w
    return out[::-1]


def legal_words(rng, mode: str, n: int, acc_w: int, aw: int, vw: int):
    """n random partial results of the mode: blending (3, n) C and (n,) T; extremum
    (n,) v and (4, n) RGBA."""
    one = 1 << acc_w
    if mode in ("composite", "xray"):
        t = rng.choice([0, one, *rng.integers(0, one + 1, size=6)], size=n)
        c = np.stack([rng.integers(0, one - t + 1) for _ in range(3)])
        return c.astype(np.int64), t.astype(np.int64)
    v = rng.choice(rng.integers(0, 1 << vw, size=4), size=n)
    rgba = np.stack([rng.integers(0, 256, size=n) for _ in range(3)] + [rng.integers(0, 1 << aw, size=n)])
    return v.astype(np.int64), rgba.astype(np.int64)


@cocotb.test()
async def test_lane(dut):
    aw, acc_w, vw, ac_w = (int(getattr(dut, n).value) for n in ("ALPHA_W", "ACC_W", "VOXEL_W", "AC_W"))
    cw = acc_w + 1
    cfg = Cube4Config(alpha_bits=aw, acc_bits=acc_w, voxel_bits=vw)
    cmp_widths, ext_widths = [cw] * 4, [vw, 8, 8, 8, aw]
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    Clock(dut.clk, 10, unit="ns").start(start_high=False)
    checked = 0
    for mode in ("composite", "xray", "mip", "minip"):
        blend = mode in ("composite", "xray")
        dut.mode_xray.value = int(mode == "xray")
        dut.mode_ext.value = int(not blend)
        dut.mode_min.value = int(mode == "minip")
        # the samples: colour, LUT A, the A that comes back, v, counts
        rgb = rng.integers(0, 256, size=(3, N))
        a_lut = rng.integers(0, 1 << aw, size=N)
        a_w = np.where(rng.random(N) < 0.5, a_lut, rng.integers(0, 1 << aw, size=N))
        s = rng.integers(0, 1 << vw, size=N)
        cnt6, cnt7 = rng.random(N) >= 0.2, rng.random(N) >= 0.2
        dxb, t0, fresh = (rng.random(N) < 0.5 for _ in range(3))
        cands = [legal_words(rng, mode, N, acc_w, aw, vw) for _ in range(3)]   # back5, back_sh, prevb_sh
        pick = np.where(dxb, np.where(t0, 2, 1), 0)
        a, b = (np.stack([cands[pick[k]][x][..., k] for k in range(N)], axis=-1) for x in (0, 1))
        if blend:
            c, t = a.copy(), b.copy()
            c[:, fresh], t[fresh] = 0, 1 << acc_w
            words = [pack([*cand[0][:, k], cand[1][k]], cmp_widths) for cand in cands for k in range(N)]
            rgba = np.concatenate([rgb, a_w[None]])
            (composite if mode == "composite" else xray)(c, t, rgba, cnt7, cfg)
            want_acc = [pack([*c[:, k], t[k]], cmp_widths) for k in range(N)]
            want_pix = [pack([*c[:, k], (1 << acc_w) - t[k]], cmp_widths) for k in range(N)]
        else:
            v, held = a.copy(), b.copy()
            v[fresh], held[:, fresh] = ((1 << vw) - 1 if mode == "minip" else 0), 0
            words = [pack([cand[0][k], *cand[1][:, k]], ext_widths) for cand in cands for k in range(N)]
            rgba = np.concatenate([rgb, a_w[None]])
            extremum(v, held, s, rgba, cnt6, mode == "minip")
            pix = extremum_pixel(held, cfg)
            want_acc = [pack([v[k], *held[:, k]], ext_widths) for k in range(N)]
            want_pix = [pack(pix[:, k], cmp_widths) for k in range(N)]
        words = np.array(words, dtype=object).reshape(3, N)
        for t_ in range(N + OUT + 1):
            await FallingEdge(dut.clk)
            k = t_
            if k < N:
                dut.in_rgba.value = pack([*rgb[:, k], a_lut[k]], [8, 8, 8, aw])
                dut.in_sample.value = int(s[k])
            k = t_ - 4                   # S3: a3 out, a3_w back
            if 0 <= k < N:
                got = int(dut.a3.value)
                assert got == a_lut[k], f"{mode} sample {k}: a3 {got}, expected the LUT's A {a_lut[k]}"
                dut.a3_w.value = int(a_w[k])
            k = t_ - (S5 - 1)            # S4: the selects
            if 0 <= k < N:
                dut.dxb4.value, dut.t0_4.value, dut.fresh_4.value = int(dxb[k]), int(t0[k]), int(fresh[k])
            k = t_ - S5
            if 0 <= k < N:
                dut.back5.value, dut.back_sh.value, dut.prevb_sh.value = (int(words[x, k]) for x in range(3))
            k = t_ - S5 - 1
            if 0 <= k < N:
                dut.cnt_6.value = int(cnt6[k])
            k = t_ - S5 - 2
            if 0 <= k < N:
                dut.cnt_7.value = int(cnt7[k])
            k = t_ - OUT
            if 0 <= k < N:
                got_acc, got_pix = int(dut.acc_q.value), int(dut.pix.value)
                assert got_acc == want_acc[k], (f"{mode} sample {k}: acc_q {got_acc:#x}, golden {want_acc[k]:#x} "
                                                f"(dxb {dxb[k]}, t0 {t0[k]}, fresh {fresh[k]})")
                assert got_pix == want_pix[k], f"{mode} sample {k}: pix {got_pix:#x}, golden {want_pix[k]:#x}"
                checked += 1
    assert checked == 4 * N, f"{checked} outputs compared, expected {4 * N}"
    dut._log.info("ALPHA_W=%d ACC_W=%d VOXEL_W=%d AC_W=%d: %d steps bit-exact", aw, acc_w, vw, ac_w, checked)


# AC_W: the wider of the blending word 4 * (ACC_W + 1) and the extremum's VOXEL_W + 24 + ALPHA_W
BUILDS = [{"ALPHA_W": 12, "ACC_W": 16, "VOXEL_W": 8, "AC_W": 68},
          {"ALPHA_W": 16, "ACC_W": 8, "VOXEL_W": 8, "AC_W": 48}]


@pytest.mark.parametrize("params", BUILDS, ids=lambda p: f"a{p['ALPHA_W']}_f{p['ACC_W']}_w{p['AC_W']}")
def test_cube4_com_lane(params):
    run_test(top="cube4_com_lane", sources=rtl_sources(), params=params, test_module=__file__)

"""Testbench for rtl/cube4_gra_beats_in.v: GRA's beat input, a skid buffer whose head
comes with its place against the row the source steps.

Random beats (a random key {m, j} in the payload with a serial number) through random
valid and ready (seeded from COCOTB_RANDOM_SEED), each beat's data popped from the data
queue (d_pop) at random after it was taken, as the source does (at most one beat taken
and not popped: a beat is taken only while none waits or the one waiting pops), while the row {w, r} stays, moves on
to a random {nx_w, nx_r} (mv) or goes home to {0, 0} (home) at random; r + 1 and
nx_r + 1 come in as the source gives them (r1, nx_r1). Checked every
cycle: the beats come out in order, none lost or extra; the data queue's head (d_data)
is the oldest beat taken and not popped, held until it pops;
with out_valid, the head's flags are its key against the row of that cycle: eq0 =
key == {w, r}, gt0 = key > {w, r}, eq1 and gt1 against {w, r + 1} (r + 1 in DIM_W bits,
so r = 2^DIM_W - 1 compares with {w, 0}); its slice m against w: m_ge = m >= w,
m_gt = m > w, m_eq = m == w, m_eq1 = m + 1 == w in M_W bits (so m = 2^M_W - 1 is w = 0's);
the head's partial beam pb (random, below NBX) as bit words: oh = bit pb, below = bits
0 .. pb - 1; its CW control bits (random in_ctl) as ctl. The flags live in two slots of
registers (head, back) that follow the skid; the test drives both the head leaving with a
beat behind it and with one entering in the same cycle. M_W = 4 and DIM_W = 3 put equal keys and the wrap within reach. With the
entries' flags kept (not compared again) on mv, the check fails ("beat N: flags RTL ...,
model ..."; tried); with below decoded as bits 0 .. pb, "beat N: pb ... bit words"
(tried); with m_eq1 as m == w + 1, "beat N ... flags" (tried).
"""

from __future__ import annotations

from collections import deque

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge

from cube4_sim.sweeps import sweep
from cube4_sim.unit_bench import param_id, run_rtl, start_clock, top_params


def place(key: tuple[int, int], w: int, r: int, m_w: int, dim_w: int) -> tuple[int, ...]:
    r1 = (r + 1) % (1 << dim_w)
    m = key[0]
    return (int(key == (w, r)), int(key > (w, r)), int(key == (w, r1)), int(key > (w, r1)),
            int(m >= w), int(m > w), int(m == w), int((m + 1) % (1 << m_w) == w))


FLAGS = ("eq0", "gt0", "eq1", "gt1", "m_ge", "m_gt", "m_eq", "m_eq1")


@cocotb.test()
async def test_places(dut):
    data_w, m_w, dim_w, nbx, cw = top_params(dut, "DATA_W", "M_W", "DIM_W", "NBX", "CW")
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    start_clock(dut)
    d = dut
    d.in_valid.value, d.out_ready.value, d.mv.value, d.home.value = 0, 0, 0, 0
    d.w.value, d.r.value, d.nx_w.value, d.nx_r.value, d.in_data.value, d.in_m.value, d.in_j.value = 0, 0, 0, 0, 0, 0, 0
    d.wm1.value, d.nx_wm1.value = (1 << m_w) - 1, (1 << m_w) - 1
    d.in_pb.value, d.in_ctl.value = 0, 0
    d.r1.value, d.nx_r1.value = 1, 1
    d.rst.value = 1
    for _ in range(3):
        await RisingEdge(d.clk)
    await FallingEdge(d.clk)
    d.rst.value = 0
    model: deque[tuple[int, tuple[int, int], int, int]] = deque()
    w = r = 0
    sent = got = checked = popped_n = 0
    taken: deque[int] = deque()                                   # beats taken, their data not popped
    for cyc in range(6000):
        key = (int(rng.integers(0, 1 << m_w)), int(rng.integers(0, 1 << dim_w)))
        if rng.random() < 0.5 and w < (1 << m_w) and cyc % 7:      # keys near the row, often
            key = (w, (r + int(rng.integers(-1, 3))) % (1 << dim_w))
            if rng.random() < 0.3:                                # slices beside w (and their wrap)
                key = ((w + int(rng.choice((-1, 1)))) % (1 << m_w), key[1])
        pb = int(rng.integers(0, nbx))
        ctl = int(rng.integers(0, 1 << cw))
        data = (sent << (m_w + dim_w)) | (key[0] << dim_w) | key[1]
        valid, ready = rng.random() < 0.6, rng.random() < 0.55
        dpop = bool(taken) and rng.random() < 0.6
        if cyc >= 5990:                                           # the drain
            valid, ready, dpop = False, True, bool(taken)
        ready = ready and (not taken or dpop)                     # (the source's i0_take)
        home = rng.random() < 0.02
        mv = not home and rng.random() < 0.3
        nx = (int(rng.integers(0, 1 << m_w)), int(rng.integers(0, 1 << dim_w)))
        if rng.random() < 0.7:
            nx = (w, (r + 1) % (1 << dim_w)) if r + 1 < (1 << dim_w) else ((w + 1) % (1 << m_w), 0)
        d.in_valid.value, d.out_ready.value, d.d_pop.value = int(valid), int(ready), int(dpop)
        d.in_data.value, d.in_m.value, d.in_j.value = data & ((1 << data_w) - 1), key[0], key[1]
        d.in_pb.value, d.in_ctl.value = pb, ctl
        d.w.value, d.r.value, d.mv.value, d.home.value = w, r, int(mv), int(home)
        d.r1.value = (r + 1) % (1 << dim_w)                       # (the source's registers)
        d.wm1.value = (w - 1) % (1 << m_w)
        d.nx_w.value, d.nx_r.value = nx
        d.nx_wm1.value = (nx[0] - 1) % (1 << m_w)
        d.nx_r1.value = (nx[1] + 1) % (1 << dim_w)
        await ReadOnly()
        pushed = valid and bool(int(d.in_ready.value))
        ov = bool(int(d.out_valid.value))
        if taken:
            dd = int(d.d_data.value)
            assert dd == taken[0], f"beat {popped_n}: d_data RTL {dd:#x}, model {taken[0]:#x}"
        if ov:
            assert model, f"out_valid with nothing in (beat {got})"
            want_data, want_key, want_pb, want_ctl = model[0]
            flags = tuple(int(getattr(d, n).value) for n in FLAGS)
            want = place(want_key, w, r, m_w, dim_w)
            assert flags == want, (f"beat {got} key {want_key} against row ({w}, {r}): flags RTL {flags}, "
                                   f"model {want}")
            words = (int(d.oh.value), int(d.below.value))
            assert words == (1 << want_pb, (1 << want_pb) - 1), (
                f"beat {got}: pb {want_pb} bit words (oh, below) RTL {words[0]:#x}, {words[1]:#x}")
            assert int(d.ctl.value) == want_ctl, f"beat {got}: ctl RTL {int(d.ctl.value):#x}, model {want_ctl:#x}"
            assert (int(d.m.value), int(d.pb.value)) == (want_key[0], want_pb), (
                f"beat {got}: m, pb RTL {int(d.m.value)}, {int(d.pb.value)}, model {want_key[0]}, {want_pb}")
            checked += 1
        else:
            assert not model, f"{len(model)} beats held and out_valid low (beat {got})"
        if dpop:
            taken.popleft()
            popped_n += 1
        if ov and ready:
            taken.append(model.popleft()[0])
            got += 1
        if pushed:
            model.append((data & ((1 << data_w) - 1), key, pb, ctl))
            sent += 1
        w, r = (0, 0) if home else (nx if mv else (w, r))
        await RisingEdge(d.clk)
        await FallingEdge(d.clk)
    await ReadOnly()
    assert not model and not int(d.out_valid.value), f"{len(model)} beats never came out"
    assert not taken and popped_n == got, f"{len(taken)} beats' data never popped"
    dut._log.info("cube4_gra_beats_in: %d beats, %d places checked", got, checked)


BUILDS = [dict(DATA_W=24, M_W=4, DIM_W=3, PB_W=3, NBX=6, CW=2), dict(DATA_W=90, M_W=9, DIM_W=8, PB_W=5, NBX=17, CW=3)]


@pytest.mark.parametrize("params", sweep(BUILDS, quick=(0,), ids=param_id))
def test_cube4_gra_beats_in(params):
    run_rtl(__file__, params)

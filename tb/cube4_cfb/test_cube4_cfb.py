"""Unit test of the CFB address unit (rtl/cube4_cfb.v) against the memory layout.

The CFB alone, with a cocotb clock and random back-pressure on its request port
(checked every cycle: a stalled beat must hold). Every read beat is checked
against ``cube4.memory`` directly, not against a model of the CFB: for read beat
r (slice k, beam j, partial beam pb in traversal order) lane q must read exactly
the voxel of that partial beam whose bank (x + y + z) mod P is q, at
``address_of(x, y, z)``, and padding lanes must not read. Over a frame every voxel
is read exactly once. All six major directions with both signs of both minor
slopes (24 views, plus 45-degree and on-axis views), non-cubic volumes, P = 1, 5, 16.
"""

from __future__ import annotations

from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from cube4.memory import address_of, bank_of, frontend_regs
from cube4.view import make_traversal
from cube4_sim import rtl_sources, run_test

HERE = Path(__file__).resolve().parent   # the harness sits beside this file


def expected_lanes(trav, p: int, k: int, j: int, pb: int) -> tuple[list[int | None], list[tuple]]:
    """Per lane: the address it must read (None: must not read), and the voxel."""
    dims = trav.dims
    addr: list[int | None] = [None] * p
    vox: list[tuple] = [()] * p
    for t in range(p):
        i = pb * p + t
        if i >= trav.ni:
            continue
        c = [0, 0, 0]
        for coord, ax in ((i, trav.axis_i), (j, trav.axis_j), (k, trav.major)):
            c[ax] = dims[ax] - 1 - coord if trav.flip[ax] else coord
        q = int(bank_of(*c, p))
        assert addr[q] is None, "two positions of a partial beam in one bank: skew broken"
        addr[q] = int(address_of(*c, dims, p))
        vox[q] = tuple(c)
    return addr, vox


@cocotb.test()
async def test_addresses(dut):
    p = int(dut.P.value)
    w = int(dut.WEIGHT_W.value)
    aw = int(dut.ADDR_W.value)
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    Clock(dut.clk, 10, unit="ns").start(start_high=False)
    dut.rst.value = 1
    dut.start.value = 0
    dut.req_ready.value = 0
    for _ in range(3):
        await RisingEdge(dut.clk)
    dut.rst.value = 0
    views = []
    for major in range(3):
        for signs in range(8):
            d = [(-1.0 if (signs >> a) & 1 else 1.0) * (1.0 if a == major else float(rng.uniform(0.1, 0.9)))
                 for a in range(3)]
            views.append((tuple(d), 1))
    views += [((1.0, 1.0, 1.0), 1), ((0.0, 0.0, -1.0), 1), ((-1.0, 0.0, 0.0), 1), ((0.3, 1.0, -0.2), 2)]
    dims_list = [(2 * p + 3, p + 4, 5), (p + 1, 3 * p - 1 if p > 1 else 4, 3)]
    for dims in dims_list:
        for direction, ss in views:
            trav = make_traversal(dims, direction, w, ss)
            for key, val in frontend_regs(trav, p).items():
                getattr(dut, "cfg_" + key.lower()).value = int(val)
            await FallingEdge(dut.clk)
            dut.start.value = 1
            await FallingEdge(dut.clk)
            dut.start.value = 0
            nb = -(-trav.ni // p)
            reads = 0
            seen = np.zeros(dims[::-1], dtype=np.int64)
            held = None
            while True:
                ready = int(rng.random() < 0.7)
                dut.req_ready.value = ready
                await RisingEdge(dut.clk)
                valid = int(dut.req_valid.value)
                if valid:
                    beat = (int(dut.req_addr.value), int(dut.req_rden.value), int(dut.tag_m.value),
                            int(dut.tag_pb.value), int(dut.tag_emit.value))
                    if held is not None:
                        assert beat == held, "request changed while stalled"
                    held = None if ready else beat
                if valid and ready:
                    addr_v, rden, _, _, _ = beat
                    is_read = int(dut.tag_lower_mem.value) or int(dut.tag_upper_mem.value)
                    if is_read:
                        k, j, pb = reads // (trav.nj * nb), (reads // nb) % trav.nj, reads % nb
                        want, vox = expected_lanes(trav, p, k, j, pb)
                        for q in range(p):
                            en = (rden >> q) & 1
                            a = (addr_v >> (q * aw)) & ((1 << aw) - 1)
                            assert en == (want[q] is not None), \
                                f"view {direction} read beat {reads} (k={k}, j={j}, pb={pb}) lane {q}: rden {en}"
                            if en:
                                assert a == want[q], (f"view {direction} (k={k}, j={j}, pb={pb}) lane {q}: "
                                                      f"address {a}, voxel {vox[q]} is at {want[q]}")
                                x, y, z = vox[q]
                                seen[z, y, x] += 1
                        reads += 1
                    else:
                        assert rden == 0, "a beat without a memory read enables a bank"
                if not int(dut.busy.value) and not valid:
                    break
            assert reads == trav.nk * trav.nj * nb, f"{reads} read beats, expected {trav.nk * trav.nj * nb}"
            assert (seen == 1).all(), f"view {direction}: voxels read {seen.min()}..{seen.max()} times"
    dut._log.info("P=%d: %d views x %d volumes, every voxel read once at its address", p, len(views), len(dims_list))


# P = 2, 4 and 8 are covered by the front-end builds (tb/cube4_frontend), which
# check every sample and therefore every address too.
@pytest.mark.parametrize("p", [1, 5, 16])
def test_cube4_cfb(p):
    run_test(
        top="cube4_cfb_harness",
        sources=[*rtl_sources(), HERE / "cube4_cfb_harness.v"],
        params={"P": p, "MAX_DIM": 64, "ADDR_W": 16, "MAX_SS_LOG2": 1},
        test_module=__file__,
    )

"""Testbench of rtl/cube4_stream_check.v: the stream checker fires, naming the stream.

The DUT is ``cube4_stream_check_demo.v``: one checker (NAME "demo.beats")
on a stream that Python drives directly.

* ``test_legal_traffic``: random legal traffic (valid drops only after a transfer
  or while not offered, data changes only then, ready random, a reset in the
  middle releasing a stalled beat) runs to the end: no false alarm.
* ``test_data_change_while_stalled`` and ``test_valid_drop_while_stalled``
  break the rule on purpose: the checker must stop the simulation ($error, then
  $fatal; Verilator already stops at $error and exits with status 1), which
  cocotb reports as SimFailure (``expect_error``); the pytest side then requires
  that exit, the cocotb test's expected SimFailure and the simulator log naming
  the stream and the rule, so a checker that stays silent, or fires without the
  name, fails the test.

The X/Z checks cannot fire in Verilator (two-state); they are exercised only by a
four-state simulator.
"""

from __future__ import annotations

from pathlib import Path

import os

import cocotb
import numpy as np
import pytest
from cocotb.regression import SimFailure
from cocotb.triggers import FallingEdge
from cocotb_tools.check_results import get_results

from cube4_sim import BUILD_ROOT, run_test
from cube4_sim.unit_bench import harness_sources

HERE = Path(__file__).resolve().parent   # the harness sits beside this file

SOURCES = harness_sources(HERE / "cube4_stream_check_demo.v")


async def start(dut) -> None:
    dut.valid.value = 0
    dut.ready.value = 0
    dut.data.value = 0
    dut.rst.value = 1
    for _ in range(3):
        await FallingEdge(dut.clk)
    dut.rst.value = 0


async def stall_then(dut, action) -> None:
    """Offer a beat, hold it stalled for two cycles, then apply ``action`` while still
    stalled, and run on for a few cycles."""
    await start(dut)
    dut.valid.value, dut.data.value, dut.ready.value = 1, 0x5A, 0
    for _ in range(3):
        await FallingEdge(dut.clk)
    action(dut)
    for _ in range(5):
        await FallingEdge(dut.clk)


@cocotb.test(expect_error=SimFailure)
async def test_data_change_while_stalled(dut):
    """Data changes while valid && !ready: the simulation must stop."""
    await stall_then(dut, lambda d: setattr(d.data, "value", 0xA5))


@cocotb.test(expect_error=SimFailure)
async def test_valid_drop_while_stalled(dut):
    """Valid drops while the beat is stalled: the simulation must stop."""
    await stall_then(dut, lambda d: setattr(d.valid, "value", 0))


@cocotb.test()
async def test_legal_traffic(dut):
    """Random legal traffic, with a reset releasing a stalled beat: no violation."""
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    await start(dut)
    offering, transfers = False, 0
    for cycle in range(2000):
        if cycle == 1000 and offering:   # a reset releases the stalled beat
            dut.rst.value = 1
            await FallingEdge(dut.clk)
            dut.rst.value = 0
            offering = False
        if not offering:
            offering = bool(rng.random() < 0.7)
            dut.data.value = int(rng.integers(0, 256))
        dut.valid.value = int(offering)
        ready = bool(rng.random() < 0.5)
        dut.ready.value = int(ready)
        await FallingEdge(dut.clk)
        if offering and ready:
            offering, transfers = False, transfers + 1
    assert transfers > 500, f"only {transfers} transfers"


def _run(testcase: str, data_w: int):
    """Run one cocotb test on its own build (DATA_W differs per test, so parallel
    pytest workers never share a build directory or its sim.log)."""
    return run_test(top="cube4_stream_check_demo", sources=SOURCES, params={"DATA_W": data_w},
                    test_module=__file__, testcase=testcase, timing=True, quiet_logs=True)


def _run_expecting_stop(testcase: str, data_w: int, message: str) -> None:
    """The checker stops the simulator, which exits with status 1 (Verilator's $stop
    on $error); the cocotb test must have seen the stop (SimFailure, expected) and
    the simulator log must name the stream and the rule."""
    with pytest.raises(RuntimeError, match="return code"):
        _run(testcase, data_w)
    name = os.environ["PYTEST_CURRENT_TEST"].rsplit("::", 1)[-1].split(" ", 1)[0]
    runs = BUILD_ROOT.glob(f"cube4_stream_check_demo_*/{name}.results.xml")
    xml = max(runs, key=lambda f: f.stat().st_mtime)
    assert get_results(xml) == (1, 0), f"{xml}: the cocotb test did not see the simulation stop"
    log = (xml.parent / "sim.log").read_text()
    assert message in log, f"no '{message}' in {xml.parent / 'sim.log'}:\n{log[-3000:]}"


def test_stream_check_legal():
    _run("test_legal_traffic", 8)


def test_stream_check_fires_on_data_change():
    _run_expecting_stop("test_data_change_while_stalled", 9, "stream demo.beats: data changed while stalled")


def test_stream_check_fires_on_valid_drop():
    _run_expecting_stop("test_valid_drop_while_stalled", 10,
                        "stream demo.beats: valid dropped while the beat was stalled")

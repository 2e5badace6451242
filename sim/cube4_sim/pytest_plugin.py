"""pytest plugin (loaded by ``-p cube4_sim.pytest_plugin`` in pyproject's addopts).

Sets the C++ optimisation level of the session's simulation builds to ``-O1`` unless
``CUBE4_CXX_OPT`` says otherwise (``cube4_sim.runner.cxx_opt``; command-line renders that
the tests start inherit it): the suite's builds compile in about half the time of -O3.
Lists the FST files written by the session (WAVES=1) at its end. It lives here and not
in a ``tb/conftest.py`` so that no second top-level ``conftest`` module competes with
``tests/conftest.py``. Imports nothing heavy unless a simulation actually ran.
"""

from __future__ import annotations

import os
import sys

#: the C++ level of the test suite's simulation builds (renders and reports use -O3)
TEST_CXX_OPT = "-O1"


def pytest_configure(config):
    os.environ.setdefault("CUBE4_CXX_OPT", TEST_CXX_OPT)


def pytest_terminal_summary(terminalreporter):
    runner = sys.modules.get("cube4_sim.runner")
    if runner is not None and runner.WAVE_FILES:
        terminalreporter.section("FST waveforms (open with gtkwave or surfer)")
        for path in runner.WAVE_FILES:
            terminalreporter.write_line(str(path))

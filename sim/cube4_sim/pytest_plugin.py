"""pytest plugin (loaded by ``-p cube4_sim.pytest_plugin`` in pyproject's addopts).

Lists the FST files written by the session (WAVES=1) at its end. It lives here and not
in a ``tb/conftest.py`` so that no second top-level ``conftest`` module competes with
``tests/conftest.py``. Imports nothing heavy unless a simulation actually ran.
"""

from __future__ import annotations

import sys


def pytest_terminal_summary(terminalreporter):
    runner = sys.modules.get("cube4_sim.runner")
    if runner is not None and runner.WAVE_FILES:
        terminalreporter.section("FST waveforms (open with gtkwave or surfer)")
        for path in runner.WAVE_FILES:
            terminalreporter.write_line(str(path))

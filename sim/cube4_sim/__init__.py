"""Cube-4 RTL simulation harness: a fast cocotb + Verilator runner (see runner.py).

The runner's names below are loaded from ``runner`` on first use, so that importing the
package (e.g. its pytest plugin) does not import cocotb. The source names
(``rtl_sources``, ``RTL_DIR``, ...) come from ``sources`` (rtl/sources.f, the one list
of RTL sources).
"""

from __future__ import annotations

from .sources import REPO_ROOT, RTL_DIR, RTL_INCLUDE_DIR, rtl_sources, synth_sources

__all__ = ["BUILD_ROOT", "REPO_ROOT", "RTL_DIR", "RTL_INCLUDE_DIR", "SIM_HDL_DIR", "WAVE_FILES", "rtl_sources",
           "run_test", "synth_sources"]

_FROM_RUNNER = {"BUILD_ROOT", "SIM_HDL_DIR", "WAVE_FILES", "run_test"}


def __getattr__(name: str):
    if name in _FROM_RUNNER:
        from . import runner

        return getattr(runner, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

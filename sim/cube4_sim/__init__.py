"""Cube-4 RTL simulation harness: a fast cocotb + Verilator runner (see runner.py).

The names below are loaded from ``runner`` on first use, so that importing the package
(e.g. its pytest plugin) does not import cocotb.
"""

from __future__ import annotations

__all__ = ["BUILD_ROOT", "REPO_ROOT", "RTL_DIR", "SIM_HDL_DIR", "WAVE_FILES", "run_test"]


def __getattr__(name: str):
    if name in __all__:
        from . import runner

        return getattr(runner, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

"""Errors of the simulation side (importing this module imports no simulator)."""

from __future__ import annotations


class SimulationError(AssertionError):
    """A Verilator build or a simulation failed; the message is one line naming its log.
    (An AssertionError, so that pytest reports it as a test failure.)"""

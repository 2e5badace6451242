"""Which parameter sets of a testbench's sweep run in `make test` and which only in
`make regress`.

`make test` (the suite every change passes, about ten minutes here) runs each unit at the
parameter sets that cover its options, P = 1 and one P >= 5; the rest of a sweep carries the
pytest marker ``regress`` and runs in `make regress` (before RTL lands). Each Verilator
build costs tens of seconds to a minute or more of compilation, so a sweep's size is its
cost; see docs/simulation.md, "Test time".
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence

import pytest

#: the marker of what only `make regress` runs (registered in pyproject.toml)
regress = pytest.mark.regress


def sweep(sets: Sequence, quick: Iterable[int], ids: Callable | None = None) -> list:
    """``sets`` as pytest parameters: those at the indices in ``quick`` run in `make test`,
    the others are marked ``regress``. ``ids`` names a set (as pytest's ``ids``). A tuple
    is the values of several argument names (``parametrize("p, shading", ...)``)."""
    quick = set(quick)
    bad = quick - set(range(len(sets)))
    if bad:
        raise ValueError(f"sweep: no parameter set at {sorted(bad)}")
    return [pytest.param(*(s if isinstance(s, tuple) else (s,)), id=None if ids is None else ids(s),
                         marks=() if n in quick else (regress,))
            for n, s in enumerate(sets)]

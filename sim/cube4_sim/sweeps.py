"""Which parameter sets of a testbench's sweep run in `make test` and which only in
`make regress`.

`make test` (the suite every change passes, about ten minutes here) runs each unit at the
parameter sets that cover its options at one P >= 5 (the whole top's main builds at P = 1
too: docs/simulation.md lists which); the rest of a sweep carries the
pytest marker ``regress`` and runs in `make regress` (before RTL lands). Each Verilator
build costs tens of seconds to a minute or more of compilation, so a sweep's size is its
cost; see docs/simulation.md, "Test time".
"""

from __future__ import annotations

import json
import os
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


def packed_sets(sets: Sequence[dict], fields: Sequence[str], defaults: dict | None = None) -> dict:
    """The parameters of a harness that instantiates a unit once per parameter set, in one
    build (tb/cube4_sdp_ram/cube4_sdp_ram_sets.v): ``N``, each field's values packed 32 bits
    per instance as a Verilog literal (``<FIELD>S``, instance k's at bits [32 k +: 32]), and
    the ports' strides ``DW_MAX`` (the widest ``DATA_W``) and ``AW_MAX`` (the widest
    address, $clog2(DEPTH), at least 1). A field a set leaves out takes ``defaults``, else 0."""
    defaults = defaults or {}
    n = len(sets)
    params: dict = {"N": n}
    for f in fields:
        packed = sum(int(s.get(f, defaults.get(f, 0))) << (32 * k) for k, s in enumerate(sets))
        params[f + "S"] = f"{32 * n}'h{packed:x}"
    params["DW_MAX"] = max(s["DATA_W"] for s in sets)
    params["AW_MAX"] = max(max(s["DEPTH"] - 1, 1).bit_length() for s in sets)
    return params


def pack_rows(rows: Sequence[Sequence[int]], widths: Sequence[int]) -> list[int]:
    """The port words of such a harness: ``rows[k]`` holds instance k's value of each port,
    and port i's word holds them at a stride of ``widths[i]`` bits (instance k's at bit
    k * widths[i]), as ``packed_sets``' harness lays its ports out."""
    return [sum(int(row[i]) << (k * w) for k, row in enumerate(rows)) for i, w in enumerate(widths)]


def set_lanes(dut, env_name: str, make_lane: Callable) -> tuple[int, int, list]:
    """The cocotb side of such a harness: its strides ``DW_MAX``, ``AW_MAX`` and one lane per
    parameter set, ``make_lane(params, rng)``, the sets read from the JSON list in environment
    variable ``env_name`` (which the pytest half passes) and one generator seeded from
    cocotb's seed shared by all lanes (imported here: only a simulation has one)."""
    import cocotb
    import numpy as np

    sets = json.loads(os.environ[env_name])
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    return int(dut.DW_MAX.value), int(dut.AW_MAX.value), [make_lane(p, rng) for p in sets]

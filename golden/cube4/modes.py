"""The rendering modes: one list, their MODE register codes and their two datapaths
(docs/numerics.md §13)."""

from __future__ import annotations

#: scene `[render] mode` values, in the order of the MODE register's codes 0 .. 3
MODES = ("composite", "xray", "mip", "minip")
MODE_CODES = {m: n for n, m in enumerate(MODES)}


def is_blend(mode: str) -> bool:
    """Composite and X-ray: COM's compositing datapath (multipliers)."""
    return mode in ("composite", "xray")


def is_extremum(mode: str) -> bool:
    """MIP and MinIP: COM's comparators."""
    return mode in ("mip", "minip")

"""User numbers, checked before any arithmetic: one definition of what a number is.

A scene's number is a TOML integer or float, never a boolean or a string; it must be
finite and inside the key's stated range before anything computes with it (an integer
of hundreds of digits is out of range, not an overflow). A number on the command line
is plain decimal text: an optional sign, digits, an optional fraction and exponent; no
underscores (Python's ``1_0``), no spaces, no ``nan`` or ``inf``. Errors are
``UserError`` lines naming the key and the value (long values shortened).
"""

from __future__ import annotations

import math
import numbers
import re

import numpy as np

from .errors import UserError

_INT_TEXT = re.compile(r"[+-]?[0-9]+")
_REAL_TEXT = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
MAX_TEXT = 40      # digits of a command-line number (anything longer is out of every range)


def shown(value, limit: int = 40) -> str:
    """repr(value), shortened for a one-line message."""
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def is_real(value) -> bool:
    """A number (a TOML integer or float, or a NumPy scalar), not a boolean or a string."""
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def real(value, what: str, lo: float | None = None, hi: float | None = None) -> float:
    """A finite number within [lo, hi] (either bound may be None), as a float."""
    if not is_real(value):
        raise UserError(f"{what} must be a number, got {shown(value)}")
    try:
        x = float(value)
    except OverflowError:
        x = math.inf if value > 0 else -math.inf
    if not math.isfinite(x) or (lo is not None and x < lo) or (hi is not None and x > hi):
        rng = f" [{lo:g}, {hi:g}]" if lo is not None and hi is not None else ""
        raise UserError(f"{what} = {shown(value)} is out of range{rng}" + ("" if rng else " (not finite)"))
    return x


def integer(value, what: str, lo: int, hi: int) -> int:
    """An integer (not a boolean, not a float) in lo..hi."""
    if isinstance(value, bool) or not isinstance(value, int) or not lo <= value <= hi:
        raise UserError(f"{what} must be an integer in {lo}..{hi}, got {shown(value)}")
    return value


def vector(value, what: str, n: int = 3, bound: float | None = None) -> list[float]:
    """n finite numbers (each within +-bound if given)."""
    if not isinstance(value, (list, tuple)) or len(value) != n:
        raise UserError(f"{what} must be {n} numbers, got {shown(value)}")
    return [real(v, f"{what}[{i}]", -bound if bound is not None else None, bound) for i, v in enumerate(value)]


def int_text(text: str, what: str) -> int:
    """A command-line integer: decimal digits with an optional sign."""
    t = text.strip()
    if not _INT_TEXT.fullmatch(t) or len(t) > MAX_TEXT:
        raise UserError(f"{what} must be an integer, got {shown(text)}")
    return int(t)


def real_text(text: str, what: str) -> float:
    """A command-line number: decimal, finite, at most MAX_TEXT characters."""
    t = text.strip()
    if not _REAL_TEXT.fullmatch(t) or len(t) > MAX_TEXT:
        raise UserError(f"{what} must be a decimal number, got {shown(text)}")
    x = float(t)
    if not math.isfinite(x):
        raise UserError(f"{what} = {shown(text)} is out of range (not finite)")
    return x

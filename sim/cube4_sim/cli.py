"""The ``cube4`` command: the golden package's command line with the ``rtl`` engine
registered (``pyproject.toml``'s console script points here)."""

from __future__ import annotations

import sys

from cube4.cli import main as cube4_main

from .engine import register


def main(argv: list[str] | None = None) -> int:
    register()
    return cube4_main(argv)


if __name__ == "__main__":
    sys.exit(main())

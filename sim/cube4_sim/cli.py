"""The ``cube4`` command: the golden package's command line with the ``rtl`` engine
registered (``pyproject.toml``'s console script points here)."""

from __future__ import annotations

import sys


def main(argv: list[str] | None = None) -> int:
    try:                     # an interrupt during start-up (the imports) is one line too
        from cube4.app.cli import main as cube4_main

        from .engine import register

        register()
    except KeyboardInterrupt:
        print("cube4: interrupted", file=sys.stderr)
        return 130
    return cube4_main(argv)


if __name__ == "__main__":
    sys.exit(main())

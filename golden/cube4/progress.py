"""Progress of the specification's long loops, for whoever wants to show it.

The bit-exact model (slices), the reference (ray steps) and the local brick executor
(bricks) take an optional ``progress`` callback and call it as
``progress(what, done, total)`` after every step, and once more with ``done == total``
when the loop ends (also when it ends early). They import no progress library: the
application draws the bars (``cube4.app.progress``).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sized
from typing import TypeVar

#: progress(what, done, total): ``done`` of ``total`` steps of the loop ``what`` are done
Progress = Callable[[str, int, int], None]

T = TypeVar("T")


def counted(items: Iterable[T], progress: Progress | None, what: str, total: int | None = None) -> Iterator[T]:
    """The items, one step each: ``progress`` (if given) hears of every step done and of
    the end. ``total``: the number of items when ``items`` has no length."""
    if progress is None:
        yield from items
        return
    n = len(items) if total is None and isinstance(items, Sized) else int(total or 0)
    done = 0
    try:
        for item in items:
            yield item
            done += 1
            progress(what, done, n)
    finally:
        progress(what, n, n)

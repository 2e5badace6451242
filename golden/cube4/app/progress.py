"""Progress bars (tqdm) for the specification's progress callbacks (``cube4.progress``).

``bars(True)`` is a callback that draws one bar per loop (``golden`` slices,
``reference`` ray steps, ``bricks``) on stderr while it runs and removes it when the
loop ends; ``bars(False)`` is None: no callback, no bar.
"""

from __future__ import annotations

from tqdm import tqdm

from ..progress import Progress

UNITS = {"golden": "slice", "reference": "step", "bricks": "brick"}


class Bars:
    """progress(what, done, total) drawn as tqdm bars, one per running loop."""

    def __init__(self):
        self._open: dict[str, tqdm] = {}

    def __call__(self, what: str, done: int, total: int) -> None:
        bar = self._open.get(what)
        if bar is None:
            bar = self._open[what] = tqdm(total=total, desc=what, unit=UNITS.get(what, "step"), leave=False)
        bar.update(done - bar.n)
        if done >= total:
            bar.close()
            del self._open[what]


def bars(enabled: bool) -> Progress | None:
    """A callback that draws progress bars, or None when ``enabled`` is false."""
    return Bars() if enabled else None

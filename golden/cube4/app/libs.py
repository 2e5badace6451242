"""The file libraries' own voices kept off the terminal.

nibabel logs header problems through ``logging`` and pynrrd, nibabel and pydicom warn
about odd files before they fail or carry on; on the command line an error is one line of
ours, so while a library reads a file its warnings are ignored and its loggers are muted
(what matters is turned into that one line, or checked by the loaders themselves).
"""

from __future__ import annotations

import contextlib
import logging
import warnings

_LOGGERS = ("nibabel", "nibabel.global", "pydicom", "nrrd")


@contextlib.contextmanager
def quiet_library():
    loggers = [logging.getLogger(name) for name in _LOGGERS]
    levels = [lg.level for lg in loggers]
    try:
        for lg in loggers:
            lg.setLevel(logging.CRITICAL + 1)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            yield
    finally:
        for lg, level in zip(loggers, levels):
            lg.setLevel(level)

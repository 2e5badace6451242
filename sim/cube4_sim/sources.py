"""The RTL sources of cube4_top: the one list, ``rtl/sources.f``.

One path per line, relative to ``rtl/``, dependencies first; ``#`` starts a comment.
The Makefile (lint), the simulation runner, the testbenches and synthesis read it.
``rtl/`` is also the include directory (Verilog headers such as ``cube4_defs.vh``).
For synthesis a file with a counterpart of the same name in ``rtl/ecp5/`` (the vendor
layer) is replaced by that counterpart; without that folder nothing is replaced.
"""

from __future__ import annotations

from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[2]
RTL_DIR = REPO_ROOT / "rtl"
RTL_INCLUDE_DIR = RTL_DIR
SOURCES_F = RTL_DIR / "sources.f"
VENDOR_DIR = RTL_DIR / "ecp5"
# behavioural models of the primitives the vendor layer instantiates (simulation only)
VENDOR_MODEL_DIR = REPO_ROOT / "sim" / "hdl" / "ecp5"


class SourceListError(Exception):
    """rtl/sources.f is missing, empty, or names a file that does not exist."""


def source_names(path: Path = SOURCES_F) -> list[str]:
    """The entries of a source list, in order, comments and blank lines dropped."""
    try:
        text = path.read_text()
    except OSError as e:
        raise SourceListError(f"cannot read the RTL source list {path}: {e.strerror}") from None
    names = [line.split("#", 1)[0].strip() for line in text.splitlines()]
    names = [n for n in names if n]
    if not names:
        raise SourceListError(f"the RTL source list {path} names no file")
    return names


def _existing(paths: list[Path], listed_in: Path) -> list[Path]:
    for p in paths:
        if not p.is_file():
            raise SourceListError(f"{listed_in} lists {p.name}, which does not exist")
    return paths


def rtl_sources(path: Path = SOURCES_F) -> list[Path]:
    """The design's Verilog files for simulation and lint, dependencies first."""
    base = path.parent
    return _existing([base / n for n in source_names(path)], path)


def synth_sources(path: Path = SOURCES_F, vendor_dir: Path = VENDOR_DIR) -> list[Path]:
    """The same list for synthesis: a file with a same-named counterpart in
    ``vendor_dir`` is replaced by it."""
    return [vendor_dir / s.name if (vendor_dir / s.name).is_file() else s for s in rtl_sources(path)]


def vendor_sim_sources(path: Path = SOURCES_F, vendor_dir: Path = VENDOR_DIR,
                       model_dir: Path = VENDOR_MODEL_DIR) -> list[Path]:
    """The synthesis list plus the behavioural models of the primitives it instantiates
    (e.g. MULT18X18D): the RTL as synthesis reads it, in a form a simulator runs."""
    return [*sorted(model_dir.glob("*.v")), *synth_sources(path, vendor_dir)]


#: The forms the design can be simulated in: the generic RTL (rtl/sources.f) and the RTL
#: as synthesis for the ECP5 reads it (the vendor layer, with the primitives' models).
RTL_FORMS = ("generic", "ecp5")


def form_sources(form: str) -> list[Path]:
    """The Verilog files of one form of the design (``RTL_FORMS``), dependencies first."""
    if form not in RTL_FORMS:
        raise ValueError(f"unknown RTL form {form!r}: one of {', '.join(RTL_FORMS)}")
    return vendor_sim_sources() if form == "ecp5" else rtl_sources()


def form_build_args(form: str) -> list[str]:
    """Verilator arguments of a form (a define, so that its builds have folders of their own)."""
    return ["-DCUBE4_RTL_FORM_ECP5"] if form == "ecp5" else []

"""The package layers: the golden model (golden/cube4, the specification) imports
nothing from the simulation or the reports; engines reach it from above."""

from __future__ import annotations

import ast
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

from cube4.app.render import engine_names, register_engine, render_views
from cube4.errors import UserError

REPO = Path(__file__).resolve().parents[1]
UPPER_PACKAGES = ("cube4_sim", "cube4_reports", "cocotb", "cocotb_tools")


def imported_modules(path: Path) -> set[str]:
    """Every module an ``import`` / ``from ... import`` names, plus string arguments of
    ``importlib.import_module`` and ``__import__`` calls."""
    names: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.add(node.module)
        elif isinstance(node, ast.Call) and node.args and isinstance(node.args[0], ast.Constant):
            func = node.func
            fname = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")
            if fname in ("import_module", "__import__") and isinstance(node.args[0].value, str):
                names.add(node.args[0].value)
    return names


def test_golden_imports_nothing_from_above():
    files = sorted((REPO / "golden").rglob("*.py"))
    assert files, "no Python files under golden/"
    for path in files:
        bad = sorted(m for m in imported_modules(path) if m.split(".")[0] in UPPER_PACKAGES)
        assert not bad, f"{path.relative_to(REPO)} imports {', '.join(bad)}"


def test_import_scan_sees_lazy_imports(tmp_path):
    """The scan above must notice an import inside a function and import_module."""
    f = tmp_path / "m.py"
    f.write_text("def f():\n    from cube4_sim.rtl import x\n    import importlib\n"
                 "    return importlib.import_module('cube4_reports.gates')\n")
    assert {"cube4_sim.rtl", "cube4_reports.gates"} <= imported_modules(f)


def test_golden_cli_does_not_import_the_simulator(tmp_path):
    """`cube4 render --engine golden` through the installed command's entry point
    imports neither cocotb nor the simulation runner."""
    code = ("import sys; from cube4_sim.cli import main; "
            f"rc = main(['render', 'sphere:16', '--engine', 'golden', '--quiet', '--out', {str(tmp_path / 'x.png')!r}]); "
            "bad = [m for m in ('cocotb', 'cocotb_tools', 'cube4_sim.runner') if m in sys.modules]; "
            "sys.exit(rc or (3 if bad else 0))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    assert (tmp_path / "x.png").is_file()


def test_console_script_registers_the_rtl_engine():
    scripts = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["scripts"]
    assert scripts["cube4"] == "cube4_sim.cli:main"
    r = subprocess.run([sys.executable, "-m", "cube4_sim.cli", "render", "--help"], capture_output=True, text=True)
    assert r.returncode == 0 and "rtl" in r.stdout
    r = subprocess.run([sys.executable, "-m", "cube4.app.cli", "render", "--help"], capture_output=True, text=True)
    assert r.returncode == 0 and "rtl" not in r.stdout.split("--engine")[1].split("--out")[0]


def test_registered_engine_is_used(monkeypatch):
    from cube4.app import render as render_mod
    from cube4.app.render import RenderResult
    from cube4.scene import load_scene

    monkeypatch.setattr(render_mod, "_ENGINES", dict(render_mod._ENGINES))
    calls = []

    def fake(vol, scenes, cfg, progress):
        calls.append(len(scenes))
        return [RenderResult("fake", np.zeros((2, 2, 4)), 0.0) for _ in scenes]

    assert "fake" not in engine_names()
    with pytest.raises(UserError, match="unknown engine 'fake'"):
        render_views(np.zeros((4, 4, 4)), [load_scene("default")], None, "fake")
    register_engine("fake", fake)
    out = render_views(np.zeros((4, 4, 4)), [load_scene("default")] * 3, None, "fake")
    assert calls == [3] and len(out) == 3 and engine_names()[:2] == ("reference", "golden")

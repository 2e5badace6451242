"""The package layers: the golden model (golden/cube4) imports nothing from the simulation
or the reports; engines reach it from above. Within it, the specification (every module
outside ``cube4.APPLICATION``) imports only NumPy and the standard library, never the
application (``cube4.app``: files, images, the cluster, progress bars, the command line);
and no project module takes part in an import cycle."""

from __future__ import annotations

import ast
import json
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

import cube4
from cube4.app.render import engine_names, register_engine, render_views
from cube4.errors import UserError

REPO = Path(__file__).resolve().parents[1]
UPPER_PACKAGES = ("cube4_sim", "cube4_reports", "cocotb", "cocotb_tools")
#: where each project package's modules live
PACKAGES = {"cube4": REPO / "golden" / "cube4", "cube4_sim": REPO / "sim" / "cube4_sim",
            "cube4_reports": REPO / "sim" / "cube4_reports"}
#: what the specification may import besides the standard library and itself
SPEC_ALLOWED = ("numpy",)
#: file-format, image, cluster, progress and simulation libraries: blocked while the
#: specification is imported and run (the static check allows nothing outside SPEC_ALLOWED)
APP_LIBRARIES = ("nibabel", "nrrd", "pydicom", "OpenImageIO", "dask", "distributed", "tqdm", "matplotlib",
                 "PIL", "imageio", "SimpleITK", "h5py", "scipy", "pandas", "cocotb", "cocotb_tools")


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
    assert calls == [3] and len(out) == 3 and engine_names()[:3] == ("reference", "reference-point", "golden")


# ------------------------------------------------------------------ specification and application
def module_files(package: str, root: Path) -> dict[str, Path]:
    """{module name: file} of every module of a package."""
    out = {}
    for path in sorted(root.rglob("*.py")):
        parts = [package, *path.relative_to(root).with_suffix("").parts]
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


def is_application(module: str) -> bool:
    return any(module == a or module.startswith(a + ".") for a in cube4.APPLICATION)


def spec_modules() -> dict[str, Path]:
    return {m: p for m, p in module_files("cube4", PACKAGES["cube4"]).items() if not is_application(m)}


def resolved_imports(module: str, path: Path, known: set[str]) -> set[str]:
    """Every module ``module`` imports (at its top or in a function), relative imports
    resolved; ``from P import n`` names the module P.n when that is a known module."""
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    out = set(imported_modules(path))
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if not isinstance(node, ast.ImportFrom):
            continue
        if node.level:
            base = package.split(".")[:len(package.split(".")) - (node.level - 1)]
            mod = ".".join(base + ([node.module] if node.module else []))
        else:
            mod = node.module or ""
        out.add(mod)
        out.update(f"{mod}.{a.name}" for a in node.names if f"{mod}.{a.name}" in known)
    return {m for m in out if m}


def spec_violations(modules: dict[str, Path]) -> list[str]:
    """Static check: each module's imports (also in functions) outside the standard
    library, SPEC_ALLOWED and the specification itself."""
    known = set(module_files("cube4", PACKAGES["cube4"]))
    bad = []
    for mod, path in modules.items():
        for name in sorted(resolved_imports(mod, path, known)):
            top = name.split(".")[0]
            if top == "__future__" or top in sys.stdlib_module_names or top in SPEC_ALLOWED:
                continue
            if top == "cube4" and not is_application(name):
                continue
            bad.append(f"{path.relative_to(REPO) if path.is_relative_to(REPO) else path} imports {name}")
    return bad


def test_specification_imports_only_numpy_statically():
    mods = spec_modules()
    assert {"cube4.model", "cube4.reference", "cube4.tables", "cube4.host", "cube4.view"} <= set(mods)
    assert not any(m.startswith("cube4.app") for m in mods)
    bad = spec_violations(mods)
    assert not bad, "the specification imports an application library or module:\n" + "\n".join(bad)


def test_static_check_sees_an_application_import(tmp_path):
    """The check above fails on a spec module importing tqdm in a function, or cube4.app."""
    f = tmp_path / "m.py"
    f.write_text("import numpy\nfrom .app import cli\ndef f():\n    from tqdm import tqdm\n")
    assert spec_violations({"cube4.m": f}) == [f"{f} imports cube4.app", f"{f} imports cube4.app.cli",
                                               f"{f} imports tqdm"]


#: run in a fresh interpreter: the application libraries blocked, every spec module
#: imported and the model, the reference and a bricked frame run; prints the third-party
#: top-level modules then loaded
SPEC_RUN = """
import importlib, importlib.abc, json, sys
BLOCKED = set(sys.argv[1].split(","))
class Block(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in BLOCKED:
            raise ImportError(f"the specification imported {name}")
sys.meta_path.insert(0, Block())
for m in sys.argv[2].split(","):
    importlib.import_module(m)
if sys.argv[3] == "run":
    from cube4.bricks import make_grid, render_bricked
    from cube4.host import config_for, golden_view, host_tables, setup_view
    from cube4.phantoms import PHANTOMS, quantise
    from cube4.reference import render_reference
    from cube4.scene import load_scene
    from dataclasses import replace
    vol = quantise(PHANTOMS["sphere"][0](12, 12, 12))
    sc = replace(load_scene("default"), width=24, height=24)
    cfg = config_for(sc)
    seen = []
    tick = lambda what, done, total: seen.append(what)
    golden_view(vol, sc, cfg, progress=tick)
    trav, cam = setup_view((12, 12, 12), sc, cfg)
    render_reference(vol, cfg.voxel_bits, sc, cam, progress=tick)
    lut, rmap = host_tables(sc, cfg, trav)
    render_bricked(vol, trav, cfg, lut, rmap, make_grid(trav.dims, (2, 1, 1)), progress=tick)
    assert {"golden", "reference", "bricks"} <= set(seen), set(seen)
top = {n.split(".")[0] for n in sys.modules}
print(json.dumps(sorted(top - set(sys.stdlib_module_names) - {"__main__", "__future__"})))
"""


def run_spec(modules: list[str], run: bool, path: list[Path] = ()) -> subprocess.CompletedProcess:
    """SPEC_RUN without the site module (no .pth hooks, no editable installs): this
    checkout's golden/ and NumPy's folder on the path, nothing else of the environment."""
    env_path = [str(p) for p in path] + [str(REPO / "golden"), str(Path(np.__file__).parents[1])]
    return subprocess.run([sys.executable, "-S", "-c", SPEC_RUN, ",".join(APP_LIBRARIES), ",".join(modules),
                           "run" if run else "import"], capture_output=True, text=True,
                          env={"PYTHONPATH": ":".join(env_path), "PATH": "/usr/bin:/bin"})


def test_specification_runs_without_application_libraries():
    """Every spec module imported, and the model, the reference and a bricked frame run
    with their progress callbacks, while the application's libraries cannot be imported;
    afterwards no third-party package but NumPy is loaded."""
    r = run_spec(sorted(spec_modules()), run=True)
    assert r.returncode == 0, r.stderr[-3000:]
    loaded = set(json.loads(r.stdout.splitlines()[-1]))
    assert loaded - {"cube4", *SPEC_ALLOWED} == set(), loaded


def test_blocked_import_fails_the_run(tmp_path):
    """The run above fails when a spec module imports a blocked library."""
    (tmp_path / "spec_probe.py").write_text("import tqdm\n")
    r = run_spec(["cube4.model", "spec_probe"], run=False, path=[tmp_path])
    assert r.returncode != 0 and "the specification imported tqdm" in r.stderr


# ------------------------------------------------------------------ import cycles
def import_graph() -> dict[str, set[str]]:
    """{module: the project modules it imports}, over cube4, cube4_sim and cube4_reports."""
    files = {m: p for pkg, root in PACKAGES.items() for m, p in module_files(pkg, root).items()}
    known = set(files)
    return {m: resolved_imports(m, p, known) & known - {m} for m, p in files.items()}


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One import cycle (its modules, the first repeated at the end), or None."""
    state: dict[str, int] = {}     # 1 on the current path, 2 done
    stack: list[str] = []

    def visit(m: str) -> list[str] | None:
        state[m] = 1
        stack.append(m)
        for n in sorted(graph.get(m, ())):
            if state.get(n) == 1:
                return stack[stack.index(n):] + [n]
            if n not in state and (found := visit(n)):
                return found
        stack.pop()
        state[m] = 2
        return None

    for m in sorted(graph):
        if m not in state and (found := visit(m)):
            return found
    return None


def test_no_import_cycles():
    graph = import_graph()
    assert {"cube4.model", "cube4.app.cli", "cube4_sim.engine", "cube4_reports.report"} <= set(graph)
    assert "cube4.app.orient" in graph["cube4.app.dicom"]
    cycle = find_cycle(graph)
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


def test_cycle_finder_finds_a_cycle():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": set()}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set(), "c": {"a", "b"}}) is None

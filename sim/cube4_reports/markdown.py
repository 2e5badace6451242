"""What every report writes besides its numbers: Markdown tables and the provenance
stamp (the git commit, whether the RTL differs from it, a digest of the RTL sources).
Only read-only git commands are run."""

from __future__ import annotations

import hashlib
import json
import subprocess
from collections.abc import Iterable
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[2]


def md_table(headers: list[str], rows: list[list[str]], align: str | None = None) -> str:
    """A GitHub Markdown table; align is one of 'l'/'r' per column (default: first l, rest r)."""
    align = align or ("l" + "r" * (len(headers) - 1))
    sep = ["---:" if a == "r" else "---" for a in align]
    lines = ["| " + " | ".join(headers) + " |", "| " + " | ".join(sep) + " |"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(lines)


def fmt_int(x: float) -> str:
    """12345.6 -> '12,346'."""
    return f"{round(x):,}"


def _git(*args: str) -> str:
    """Output of a git command in the repository, '' if git or the repository is missing."""
    try:
        return subprocess.run(["git", *args], cwd=REPO_ROOT, capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return ""


def git_state(paths: Iterable[str] = ("rtl",)) -> dict:
    """{"commit": HEAD's short hash or "unknown", "rtl_dirty": whether any of ``paths``
    differs from HEAD}."""
    return {"commit": _git("rev-parse", "--short", "HEAD") or "unknown",
            "rtl_dirty": bool(_git("status", "--porcelain", "--", *paths))}


def git_describe(paths: Iterable[str] = ("rtl",)) -> str:
    """HEAD's short hash, with '+rtl-modified' when ``paths`` differ from HEAD."""
    state = git_state(paths)
    if state["commit"] == "unknown":
        return "unknown"
    return state["commit"] + ("+rtl-modified" if state["rtl_dirty"] else "")


def last_commit(paths: Iterable[str] = ("rtl",)) -> str:
    """Short hash of the last commit that changed ``paths`` (``git log -1 --format=%h -- rtl``),
    "unknown" without git."""
    return _git("log", "-1", "--format=%h", "--", *paths) or "unknown"


def rtl_commit_note(commit: str, dirty: bool, label: str = "rtl/") -> str:
    """'rtl/ at commit 1a2b3c4', with ' (rtl/ has uncommitted changes)' when ``dirty``."""
    return f"{label} at commit {commit}" + (f" ({label} has uncommitted changes)" if dirty else "")


def rtl_commit(paths: Iterable[str] = ("rtl",)) -> str:
    """Which rtl/ tree a report built: its last commit, and whether the work tree differs from it."""
    paths = tuple(paths)
    return rtl_commit_note(last_commit(paths), git_state(paths)["rtl_dirty"], "/, ".join(paths) + "/")


def rtl_digest(sources: Iterable[Path]) -> str:
    """Short SHA-256 over source files (names and contents, in name order): says which
    RTL was measured."""
    h = hashlib.sha256()
    for src in sorted(sources, key=lambda p: p.name):
        h.update(src.name.encode())
        h.update(src.read_bytes())
    return h.hexdigest()[:12]


def write_report(name: str, data: dict, md: str | None) -> None:
    """A report's outputs: build/reports/<name>.json (its figures) and, unless ``md`` is
    None, reports/<name>.md, which is also printed."""
    out = REPO_ROOT / "build" / "reports"
    out.mkdir(parents=True, exist_ok=True)
    (out / f"{name}.json").write_text(json.dumps(data, indent=1))
    if md is not None:
        (REPO_ROOT / "reports" / f"{name}.md").write_text(md)
        print(md)


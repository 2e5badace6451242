"""All-or-nothing output files for the command line.

A run names its outputs before any work (``check_destinations``): each must be a
file name the file system accepts, in a folder that exists or can be made, not a
folder itself, and no two outputs may be the same file. After the work,
``write_all`` writes every output to a temporary file beside its destination, then
moves them into place one by one. If anything fails, every destination is left as
it was before the run: the outputs already moved are rolled back (an earlier file
at that path is restored, a new one removed), the temporaries are removed, and so
are the folders the run created. Errors name the user's paths, never a temporary.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable, Sequence
from pathlib import Path

from ..errors import UserError

Writer = Callable[[str], None]  # writes the output to the (temporary) path it is given


def _name_max(folder: Path) -> int:
    try:
        return os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError):
        return 255


def _exists(path: Path) -> bool:
    try:
        return path.exists()
    except OSError:          # e.g. a name longer than the file system allows
        return False


def _existing_ancestor(path: Path) -> Path:
    p = path
    while not _exists(p):
        if p.parent == p:
            break
        p = p.parent
    return p


def check_destination(path: Path, what: str) -> None:
    """One output's destination, checked before any work (one clear line on failure)."""
    anc = _existing_ancestor(path.parent)
    if not anc.is_dir():
        raise UserError(f"{what} {str(path)!r}: {str(anc)!r} is not a folder")
    limit = _name_max(anc)
    # the temporary name is the longest written: '.cube4-' + 8 random characters + suffix
    for part in (*path.relative_to(anc).parts, f".cube4-xxxxxxxx{path.suffix}"):
        if len(os.fsencode(part)) > limit:
            raise UserError(f"{what} {str(path)!r}: the name {part[:40]!r}... is longer than the "
                            f"file system allows ({limit} bytes)")
    if path.is_dir():
        raise UserError(f"{what} {str(path)!r} is a folder")
    if not os.access(anc, os.W_OK | os.X_OK):
        raise UserError(f"{what} {str(path)!r}: cannot write in {str(anc)!r} (permission denied)")


def check_destinations(named: Sequence[tuple[Path, str]]) -> None:
    """Every (path, what) checked, and no file named twice."""
    seen: dict[Path, str] = {}
    for path, what in named:
        check_destination(path, what)
        key = Path(os.path.abspath(path))
        if key in seen:
            raise UserError(f"{what} {str(path)!r} is also the {seen[key]}: give them different names")
        seen[key] = what


def _make_parents(path: Path, created: list[Path]) -> None:
    """Make the missing folders above path, remembering them (outermost first)."""
    missing = []
    p = path.parent
    while not _exists(p):
        missing.append(p)
        p = p.parent
    for folder in reversed(missing):
        folder.mkdir()
        created.append(folder)


def write_all(outputs: Sequence[tuple[Path, Writer]]) -> None:
    """Write every output, or none: see the module's docstring."""
    umask = os.umask(0)
    os.umask(umask)
    created: list[Path] = []      # folders made by this run
    temps: list[tuple[str, Path]] = []
    backups: list[tuple[str, Path]] = []   # earlier files moved aside, to restore on failure
    placed: list[Path] = []       # destinations already replaced
    current = outputs[0][0] if outputs else Path(".")
    try:
        for path, write in outputs:
            current = path
            _make_parents(path, created)
            fd, tmp = tempfile.mkstemp(prefix=".cube4-", suffix=path.suffix, dir=path.parent)
            os.close(fd)
            temps.append((tmp, path))
            os.chmod(tmp, 0o666 & ~umask)
            write(tmp)
        for tmp, path in temps:
            current = path
            if path.exists():
                fd, bak = tempfile.mkstemp(prefix=".cube4-old-", dir=path.parent)
                os.close(fd)
                os.replace(path, bak)
                backups.append((bak, path))
            os.replace(tmp, path)
            placed.append(path)
        for bak, _ in backups:
            os.unlink(bak)
        backups.clear()
    except OSError as e:
        _roll_back(temps, placed, backups, created)
        raise UserError(f"cannot write {str(current)!r}: {e.strerror or e}") from None
    except BaseException:
        _roll_back(temps, placed, backups, created)
        raise


def _roll_back(temps: list[tuple[str, Path]], placed: list[Path], backups: list[tuple[str, Path]],
               created: list[Path]) -> None:
    """Undo a failed write_all: temporaries removed, earlier files back, new ones and
    new folders gone."""
    for tmp, _ in temps:
        if os.path.lexists(tmp):
            os.unlink(tmp)
    restored = {path for _, path in backups}
    for path in placed:
        if path not in restored and os.path.lexists(path):
            os.unlink(path)
    for bak, path in backups:
        os.replace(bak, path)
    backups.clear()
    for folder in reversed(created):
        try:
            folder.rmdir()
        except OSError:
            pass

"""All-or-nothing, durable output files for the command line.

A run names its outputs before any work (``check_destinations``): each must be a
file name the file system accepts, in a folder that exists or can be made, not a
folder itself, replaceable (not immutable or append-only, not another user's file in a
sticky folder), and no two outputs may be the same file. After the work,
``write_all`` writes every output to a temporary file beside its destination, flushes
it to the disk (fsync), checks it (not empty, and read back: images decoded, arrays
and JSON parsed), then moves the outputs into place one by one and syncs their
folders. If anything fails (a full disk, a quota, a permission, an interrupt), every
destination is left as it was before the run: the outputs already moved are rolled
back (an earlier file at that path is restored, a new one removed), the temporaries
are removed, and so are the folders the run created. Errors name the user's paths,
never a temporary.
"""

from __future__ import annotations

import contextlib
import errno
import fcntl
import json
import os
import stat
import struct
import sys
import tempfile
from collections.abc import Callable, Sequence
from pathlib import Path

from ..errors import UserError

Writer = Callable[[str], None]  # writes the output to the (temporary) path it is given

_FS_IOC_GETFLAGS = 0x80086601            # Linux: the inode's attribute flags (lsattr)
_IMMUTABLE, _APPEND_ONLY = 0x10, 0x20


def _name_max(folder: Path) -> int:
    try:
        return os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError):
        return 255


def _path_max(folder: Path) -> int:
    try:
        return os.pathconf(folder, "PC_PATH_MAX")
    except (OSError, ValueError):
        return 4096


def _exists(path: Path) -> bool:
    try:
        os.lstat(path)
        return True
    except (OSError, ValueError):  # e.g. a name longer than the file system allows
        return False


def _existing_ancestor(path: Path) -> Path:
    p = path
    while not _exists(p):
        if p.parent == p:
            break
        p = p.parent
    return p


def _attr_flags(path: Path) -> int:
    """The file's immutable/append-only flags (0 where the file system has none)."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOFOLLOW)
    except OSError:
        return 0
    try:
        buf = fcntl.ioctl(fd, _FS_IOC_GETFLAGS, struct.pack("l", 0))
        return struct.unpack("l", buf)[0]
    except OSError:
        return 0
    finally:
        os.close(fd)


def _replaceable(path: Path, folder: Path, what: str) -> None:
    """Refuse, before any work, a destination that cannot be replaced or a folder in
    which the run could not remove its temporaries."""
    flags = _attr_flags(folder)
    if flags & (_IMMUTABLE | _APPEND_ONLY):
        kind = "immutable" if flags & _IMMUTABLE else "append-only"
        raise UserError(f"{what} {str(path)!r}: the folder {str(folder)!r} is {kind}")
    try:
        st = os.lstat(path)
    except OSError:
        return
    if stat.S_ISREG(st.st_mode):
        flags = _attr_flags(path)
        if flags & (_IMMUTABLE | _APPEND_ONLY):
            kind = "immutable" if flags & _IMMUTABLE else "append-only"
            raise UserError(f"{what} {str(path)!r}: the earlier file is {kind} and cannot be replaced")
    dst = os.stat(folder)
    uid = os.geteuid()
    if dst.st_mode & stat.S_ISVTX and uid != 0 and st.st_uid != uid and dst.st_uid != uid:
        raise UserError(f"{what} {str(path)!r}: the earlier file belongs to another user in a "
                        "sticky folder and cannot be replaced")


def check_destination(path: Path, what: str) -> None:
    """One output's destination, checked before any work (one clear line on failure)."""
    anc = _existing_ancestor(path.parent)
    if not anc.is_dir():
        raise UserError(f"{what} {str(path)!r}: {str(anc)!r} is not a folder")
    limit = _name_max(anc)
    # the temporary name is the longest written: '.cube4-old-' + 8 random characters + suffix
    for part in (*path.relative_to(anc).parts, f".cube4-old-xxxxxxxx{path.suffix}"):
        if len(os.fsencode(part)) > limit:
            raise UserError(f"{what} {str(path)!r}: the name {part[:40]!r}... is longer than the "
                            f"file system allows ({limit} bytes)")
    whole = len(os.fsencode(os.path.abspath(path.parent / f".cube4-old-xxxxxxxx{path.suffix}")))
    if whole >= _path_max(anc):
        raise UserError(f"{what} {str(path)[:60]!r}...: the path is longer than the system allows "
                        f"({whole} bytes, at most {_path_max(anc) - 1})")
    if os.path.isdir(path):
        raise UserError(f"{what} {str(path)!r} is a folder")
    _replaceable(path, anc, what)
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


# ------------------------------------------------------------------ checking what was written


@contextlib.contextmanager
def _quiet_stderr():
    """The image libraries' own complaints (libpng prints to the file descriptor) kept
    off the terminal while a file is read back: the error is one line of ours."""
    sys.stderr.flush()
    saved = os.dup(2)
    try:
        with open(os.devnull, "wb") as null:
            os.dup2(null.fileno(), 2)
        yield
    finally:
        os.dup2(saved, 2)
        os.close(saved)


def _read_image(tmp: str) -> None:
    import OpenImageIO as oiio

    with _quiet_stderr():
        inp = oiio.ImageInput.open(tmp)
        if inp is None:
            oiio.geterror()
            raise OSError(errno.EIO, "the written image cannot be read back")
        try:
            spec = inp.spec()
            pixels = inp.read_image(0, 0, 0, spec.nchannels, "float")
            if pixels is None or inp.has_error:
                inp.geterror()
                raise OSError(errno.EIO, "the written image is incomplete")
        finally:
            inp.close()


def _read_npy(tmp: str) -> None:
    import numpy as np

    try:
        a = np.load(tmp, mmap_mode="r", allow_pickle=False)
        _ = a.sum() if a.size else 0
    except (ValueError, EOFError) as e:
        raise OSError(errno.EIO, f"the written array is incomplete ({e})") from None


def _read_json(tmp: str) -> None:
    try:
        json.loads(Path(tmp).read_text(encoding="utf-8"))
    except ValueError as e:
        raise OSError(errno.EIO, f"the written JSON is incomplete ({e})") from None


_READERS = {".png": _read_image, ".tif": _read_image, ".tiff": _read_image, ".exr": _read_image,
            ".npy": _read_npy, ".json": _read_json}


def _sync(path: str, flags: int = os.O_RDONLY) -> None:
    fd = os.open(path, flags)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _sync_folder(folder: Path) -> None:
    """The moves on the disk; a file system that cannot sync a folder is no failure."""
    try:
        _sync(str(folder))
    except OSError as e:
        if e.errno not in (errno.EINVAL, errno.ENOTSUP, errno.EOPNOTSUPP, errno.EBADF, errno.EACCES):
            raise


def _settle(tmp: str, suffix: str) -> None:
    """The temporary on the disk and whole: synced, not empty, read back."""
    _sync(tmp)
    if os.stat(tmp).st_size == 0:
        raise OSError(errno.EIO, "nothing was written")
    reader = _READERS.get(suffix.lower())
    if reader is not None:
        reader(tmp)


def _reason(e: BaseException, tmp: str | None, path: Path) -> str:
    """An error's reason with the temporary's name replaced by the user's, and the disk's
    state where the writer did not say (an image library's 'could not open')."""
    if isinstance(e, OSError):
        text = e.strerror or str(e)
    else:
        text = str(e)
    if tmp:
        text = text.replace(tmp, str(path)).replace(os.path.basename(tmp), path.name)
    text = " ".join(text.split())
    try:
        vfs = os.statvfs(path.parent if _exists(path.parent) else _existing_ancestor(path.parent))
        if vfs.f_bavail * vfs.f_frsize < 64 * 1024 and "space" not in text.lower():
            text += " (no space left on the device)"
    except OSError:
        pass
    return text


def write_all(outputs: Sequence[tuple[Path, Writer]]) -> None:
    """Write every output, or none: see the module's docstring."""
    umask = os.umask(0)
    os.umask(umask)
    created: list[Path] = []      # folders made by this run
    temps: list[tuple[str, Path]] = []
    backups: list[tuple[str, Path]] = []   # earlier files moved aside, to restore on failure
    placed: list[Path] = []       # destinations already replaced
    current = outputs[0][0] if outputs else Path(".")
    tmp: str | None = None
    try:
        for path, write in outputs:
            current, tmp = path, None
            _make_parents(path, created)
            fd, tmp = tempfile.mkstemp(prefix=".cube4-", suffix=path.suffix, dir=path.parent)
            os.close(fd)
            temps.append((tmp, path))
            os.chmod(tmp, 0o666 & ~umask)
            write(tmp)
            _settle(tmp, path.suffix)
        for tmp, path in temps:
            current = path
            if os.path.lexists(path):
                fd, bak = tempfile.mkstemp(prefix=".cube4-old-", dir=path.parent)
                os.close(fd)
                try:
                    os.replace(path, bak)
                except OSError:
                    _remove(bak)
                    raise
                backups.append((bak, path))
            os.replace(tmp, path)
            placed.append(path)
        tmp = None
        for folder in {p.parent for _, p in temps}:
            _sync_folder(folder)
        for bak, _ in backups:
            _remove(bak)
        backups.clear()
    except (OSError, UserError) as e:
        _roll_back(temps, placed, backups, created)
        raise UserError(f"cannot write {str(current)!r}: {_reason(e, tmp, current)}") from None
    except BaseException:
        _roll_back(temps, placed, backups, created)
        raise


def _remove(path: str) -> None:
    try:
        if os.path.lexists(path):
            os.unlink(path)
    except OSError:
        pass


def _roll_back(temps: list[tuple[str, Path]], placed: list[Path], backups: list[tuple[str, Path]],
               created: list[Path]) -> None:
    """Undo a failed write_all as far as the file system allows (each step on its own):
    temporaries removed, earlier files back, new ones and new folders gone."""
    for tmp, _ in temps:
        _remove(tmp)
    restored = {path for _, path in backups}
    for path in placed:
        if path not in restored:
            _remove(str(path))
    for bak, path in backups:
        try:
            os.replace(bak, path)
        except OSError:
            pass
    backups.clear()
    for folder in reversed(created):
        try:
            folder.rmdir()
        except OSError:
            pass

"""Reading what the simulation harnesses dump: frames, strictly, and the binary pixel
records of ``sim/hdl/cube4_top_harness.v``.

A dump is a sequence of records, each a frame start, a beat, or a frame's last beat.
``frame_bounds`` cuts it into frames and refuses anything out of place: beats before a
frame's start (stray beats after the previous frame's done), beats after a frame's last
beat, a frame without its last beat, or a last beat in a frame the caller says is
unfinished (reset in mid-frame, or its beats not dumped). Nothing is dropped silently.

Pixel records (the harness's header says the same): REC_WORDS little-endian 32-bit words,
``record_words(P) = 3 + ceil(P / 32) + 5 P``: header ``{8'hC4, kind, frame}`` (kind 1
start, 2 beat, 3 last beat; frame counts the start records mod 2^16), m, by, the lane
mask, P words bx, 4P words R, G, B, A (lane-major).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from cube4.model import PIXEL_DTYPE

START, BEAT, LAST = 1, 2, 3
MAGIC = 0xC4


class DumpError(AssertionError):
    """A dump that is not what the harness should have written (a test failure)."""


def frame_bounds(kinds: np.ndarray, unfinished: list[bool], what: str = "dump") -> list[tuple[int, int]]:
    """(first beat, end) record indices of each frame in ``kinds`` (START/BEAT/LAST per
    record), one per entry of ``unfinished``. An unfinished frame (reset in mid-frame,
    or its beats not dumped) must not have a last beat; every other frame must end
    with its last beat."""
    kinds = np.asarray(kinds)
    starts = np.flatnonzero(kinds == START)
    if starts.size != len(unfinished):
        raise DumpError(f"{what}: {starts.size} frame start markers, expected {len(unfinished)}")
    if starts.size and starts[0] != 0:
        raise DumpError(f"{what}: {starts[0]} beats before the first frame's start marker")
    bounds = []
    for n, (a, b) in enumerate(zip(starts, [*starts[1:], kinds.size])):
        lasts = np.flatnonzero(kinds[a + 1:b] == LAST)
        if unfinished[n]:
            if lasts.size:
                raise DumpError(f"{what}: frame {n} should be unfinished but has a last beat")
        elif not lasts.size:
            raise DumpError(f"{what}: frame {n} has no last beat ({b - a - 1} beats)")
        elif lasts[0] != b - a - 2:
            raise DumpError(f"{what}: {b - a - 2 - lasts[0]} beats after frame {n}'s last beat (after done)")
        bounds.append((int(a) + 1, int(b)))
    return bounds


def record_words(p: int) -> int:
    """32-bit words per pixel record for P lanes."""
    return 3 + -(-p // 32) + 7 * p


def read_records(path: Path, p: int) -> np.ndarray:
    """The pixel dump as an (n, record_words(p)) uint32 array; its headers checked."""
    data = Path(path).read_bytes()
    size = 4 * record_words(p)
    if len(data) % size:
        raise DumpError(f"{path.name}: {len(data)} bytes is not a whole number of {size}-byte records (P = {p})")
    rec = np.frombuffer(data, dtype="<u4").reshape(-1, record_words(p))
    bad = np.flatnonzero(((rec[:, 0] >> 24) != MAGIC) | ~np.isin((rec[:, 0] >> 16) & 0xFF, (START, BEAT, LAST)))
    if bad.size:
        raise DumpError(f"{path.name}: record {bad[0]} has header {int(rec[bad[0], 0]):#010x}, not a pixel record")
    return rec


def record_kinds(rec: np.ndarray) -> np.ndarray:
    return ((rec[:, 0] >> 16) & 0xFF).astype(np.int64)


def pixels_of(rec: np.ndarray, p: int) -> np.ndarray:
    """PIXEL_DTYPE rows (m, by, bx, r, g, b, a) of the lanes set in each beat record's
    mask, in beat order and lane order within a beat."""
    mw = -(-p // 32)
    lanes = np.arange(p)
    mask = ((rec[:, 3 + lanes // 32] >> (lanes % 32).astype(np.uint32)) & 1).astype(bool)
    bx = rec[:, 3 + mw:3 + mw + p]
    rgba = rec[:, 3 + mw + p:3 + mw + 5 * p].reshape(-1, p, 4)
    z = rec[:, 3 + mw + 5 * p:].reshape(-1, p, 2).astype(np.int64) - 1      # m + 1, 0: none
    beat, lane = np.nonzero(mask)
    out = np.empty(beat.size, dtype=PIXEL_DTYPE)
    out["m"], out["by"], out["bx"] = rec[beat, 1], rec[beat, 2], bx[beat, lane]
    for c, name in enumerate("rgba"):
        out[name] = rgba[beat, lane, c]
    out["zp"], out["zf"] = z[beat, lane, 0], z[beat, lane, 1]
    return out


def read_pixel_frames(path: Path, p: int, unfinished: list[bool]) -> list[np.ndarray]:
    """The finished rays of every finished frame, from a whole pixel dump
    (see ``frame_bounds`` for what is refused). Every beat must carry its frame's number."""
    rec = read_records(path, p)
    frames = []
    bounds = frame_bounds(record_kinds(rec), unfinished, path.name)
    for n, (a, b) in enumerate(bounds):
        want = int(rec[a - 1, 0]) & 0xFFFF
        wrong = np.flatnonzero((rec[a:b, 0] & 0xFFFF) != want)
        if wrong.size:
            raise DumpError(f"{path.name}: beat {wrong[0]} of frame {n} is marked as frame "
                            f"{int(rec[a + wrong[0], 0]) & 0xFFFF}, not {want}")
        if not unfinished[n]:
            frames.append(pixels_of(rec[a:b], p))
    return frames

"""cube4_sim.dump: the binary pixel records of the top harness and the strict framing
that both dump readers use. The records are built here word by word as the harness's
header describes them."""

from __future__ import annotations

import numpy as np
import pytest

from cube4_sim.dump import (BEAT, LAST, START, DumpError, frame_bounds, read_pixel_frames, read_records,
                            record_words)


def header(kind: int, frame: int) -> int:
    return (0xC4 << 24) | (kind << 16) | frame


def start(p: int, frame: int) -> list[int]:
    return [header(START, frame)] + [0] * (record_words(p) - 1)


def beat(p: int, frame: int, m: int, by: int, lanes: dict[int, tuple],
         last: bool = False) -> list[int]:
    """lanes: lane -> (bx, r, g, b, a) or (bx, r, g, b, a, zp + 1, zf + 1): depth out's
    slices as the harness writes them (m + 1; 0: none)."""
    mw = -(-p // 32)
    mask = [0] * mw
    bx = [0] * p
    rgba = [0] * (4 * p)
    z = [0] * (2 * p)
    for q, (x, *c) in lanes.items():
        mask[q // 32] |= 1 << (q % 32)
        bx[q] = x
        rgba[4 * q:4 * q + 4] = c[:4]
        z[2 * q:2 * q + 2] = c[4:] or [0, 0]
    return [header(LAST if last else BEAT, frame), m, by, *mask, *bx, *rgba, *z]


def write(tmp_path, records: list[list[int]]):
    path = tmp_path / "pixels.bin"
    path.write_bytes(np.array([w for r in records for w in r], dtype="<u4").tobytes())
    return path


def test_record_size():
    assert record_words(1) == 3 + 1 + 7 and record_words(32) == 3 + 1 + 224 and record_words(33) == 3 + 2 + 231


@pytest.mark.parametrize("p", [2, 5, 33, 64])
def test_pixels_of_two_frames(tmp_path, p):
    hi = p - 1
    recs = [start(p, 0),
            beat(p, 0, 3, 7, {0: (11, 1, 2, 3, 4, 6, 0), hi: (12, 5, 6, 7, (1 << 25) - 1)}),
            beat(p, 0, 4, 8, {hi: (13, 9, 10, 11, 12)}, last=True),
            start(p, 1),
            beat(p, 1, 0, 0, {0: (1, 0, 0, 0, 1)}, last=True)]
    f0, f1 = read_pixel_frames(write(tmp_path, recs), p, [False, False])
    want0 = [(3, 7, 11, 1, 2, 3, 4, 5, -1), (3, 7, 12, 5, 6, 7, (1 << 25) - 1, -1, -1),
             (4, 8, 13, 9, 10, 11, 12, -1, -1)]
    assert [tuple(int(v) for v in r) for r in f0] == want0
    assert [tuple(int(v) for v in r) for r in f1] == [(0, 0, 1, 0, 0, 0, 1, -1, -1)]


def test_unfinished_frame_is_skipped_only_when_expected(tmp_path):
    p = 4
    recs = [start(p, 0), beat(p, 0, 0, 0, {1: (1, 1, 1, 1, 1)}),
            start(p, 1), beat(p, 1, 0, 0, {2: (2, 2, 2, 2, 2)}, last=True)]
    path = write(tmp_path, recs)
    (f,) = read_pixel_frames(path, p, [True, False])
    assert f["bx"].tolist() == [2]
    with pytest.raises(DumpError, match="frame 0 has no last beat"):
        read_pixel_frames(path, p, [False, False])
    with pytest.raises(DumpError, match="2 frame start markers, expected 1"):
        read_pixel_frames(path, p, [False])


def test_stray_beats_fail(tmp_path):
    p = 2
    one = beat(p, 0, 0, 0, {0: (1, 1, 1, 1, 1)})
    fin = beat(p, 0, 0, 1, {0: (1, 1, 1, 1, 1)}, last=True)
    with pytest.raises(DumpError, match="1 beats after frame 0's last beat"):
        read_pixel_frames(write(tmp_path, [start(p, 0), one, fin, one]), p, [False])
    with pytest.raises(DumpError, match="1 beats before the first frame's start"):
        read_pixel_frames(write(tmp_path, [one, start(p, 0), fin]), p, [False])
    with pytest.raises(DumpError, match="beats after frame 0's last beat"):  # stray beat before the next start
        read_pixel_frames(write(tmp_path, [start(p, 0), fin, one, start(p, 1),
                                           beat(p, 1, 0, 0, {}, last=True)]), p, [False, False])
    with pytest.raises(DumpError, match="marked as frame 0, not 1"):
        read_pixel_frames(write(tmp_path, [start(p, 0), fin, start(p, 1), fin]), p, [False, False])


def test_malformed_files(tmp_path):
    p = 2
    path = write(tmp_path, [start(p, 0)])
    path.write_bytes(path.read_bytes() + b"\0\0\0\0")
    with pytest.raises(DumpError, match="not a whole number"):
        read_records(path, p)
    bad = start(p, 0)
    bad[0] = 0x12345678
    with pytest.raises(DumpError, match="record 0 has header 0x12345678"):
        read_records(write(tmp_path, [bad]), p)


def test_frame_bounds_of_text_dumps():
    """The framing alone, as the front-end testbench uses it (kinds from its text lines)."""
    assert frame_bounds([START, BEAT, BEAT, LAST], [False]) == [(1, 4)]
    assert frame_bounds([START, BEAT, START, LAST], [True, False]) == [(1, 2), (3, 4)]
    assert frame_bounds([START], [True]) == [(1, 1)]
    with pytest.raises(DumpError, match="should be unfinished but has a last beat"):
        frame_bounds([START, LAST, START, LAST], [True, False])
    with pytest.raises(DumpError, match="0 frame start markers, expected 1"):
        frame_bounds([BEAT, LAST], [False])

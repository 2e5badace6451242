"""Bad inputs of the kinds a careless or hostile user gives: each is one clear line on
stderr, exit status 2, no traceback, and no output written (the earlier file at the
output path is untouched)."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest
from cube4_testutil import write_series

from cube4.app.cli import main


def _nrrd(path: Path, header: str, payload: bytes) -> None:
    path.write_bytes(header.encode() + b"\n" + payload)


def _case(tmp_path: Path, kind: str) -> list[str]:
    """The command-line arguments of one bad case (files made in tmp_path)."""
    if kind == "nrrd_corrupt_gzip":
        f = tmp_path / "v.nrrd"
        _nrrd(f, "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: gzip\n", os.urandom(64))
        return [str(f)]
    if kind == "nrrd_unknown_type":
        f = tmp_path / "v.nrrd"
        _nrrd(f, "NRRD0004\ntype: quaternion\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n", bytes(64))
        return [str(f)]
    if kind == "nrrd_truncated":
        f = tmp_path / "v.nrrd"
        _nrrd(f, "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8 8\nencoding: raw\n", bytes(100))
        return [str(f)]
    if kind == "scene_not_utf8":
        s = tmp_path / "s.toml"
        s.write_bytes(b"\xff\xfe[view]\n")
        return ["sphere:16", "--scene", str(s)]
    if kind == "scene_nested_deeply":
        s = tmp_path / "s.toml"
        s.write_text("a = " + "[" * 3000 + "]" * 3000 + "\n")
        return ["sphere:16", "--scene", str(s)]
    if kind == "builtin_too_large_for_memory":
        return ["sphere:2048"]
    if kind == "dicom_folder_of_text":
        d = tmp_path / "series"
        d.mkdir()
        (d / "a.dcm").write_text("not dicom")
        return [str(d)]
    if kind.startswith("dicom_"):
        return [str(_dicom_case(tmp_path / "series", kind))]
    raise AssertionError(kind)


def _dicom_case(folder: Path, kind: str) -> Path:
    ct = np.random.default_rng(3).integers(0, 4096, size=(6, 8, 8)).astype(np.uint16)
    if kind == "dicom_mixed_series":
        write_series(folder, ct)
        write_series(folder, ct[:3], start=100)
    elif kind == "dicom_missing_slice":
        write_series(folder, ct, skip=3)
    elif kind == "dicom_compressed":
        write_series(folder, ct[:3], compressed=True)
    elif kind == "dicom_empty_folder":
        folder.mkdir()
    else:
        raise AssertionError(kind)
    return folder


KINDS = ["nrrd_corrupt_gzip", "nrrd_unknown_type", "nrrd_truncated", "scene_not_utf8",
         "scene_nested_deeply", "builtin_too_large_for_memory", "dicom_folder_of_text",
         "dicom_mixed_series", "dicom_missing_slice", "dicom_compressed", "dicom_empty_folder"]


@pytest.mark.parametrize("kind", KINDS)
def test_bad_input_is_one_line(tmp_path, capsys, kind):
    out = tmp_path / "out.png"
    out.write_bytes(b"earlier image")
    rc = main(["render", *_case(tmp_path, kind), "--quiet", "--out", str(out)])
    err = capsys.readouterr().err
    assert rc == 2, err
    assert err.startswith("cube4: error: ") and err.count("\n") == 1 and "Traceback" not in err, err
    assert out.read_bytes() == b"earlier image"
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".cube4-")]

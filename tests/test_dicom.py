"""DICOM series (cube4.dicom): a folder of slices written here with pydicom loads as the
volume it was made from, renders the same image as that volume given as NIfTI, and
every broken series is one clear error."""

from __future__ import annotations


import nibabel as nib
import numpy as np
import pytest
from cube4_testutil import write_series
from pydicom.uid import generate_uid

from cube4.app.dicom import load_series
from cube4.app.render import render
from cube4.app.volumes import load_volume
from cube4.config import Cube4Config
from cube4.errors import UserError
from cube4.scene import parse_scene


@pytest.fixture
def ct() -> np.ndarray:
    rng = np.random.default_rng(1)
    vol = rng.integers(0, 4096, size=(9, 12, 10)).astype(np.uint16)
    vol[0, 0, 0] = 0                        # the series' minimum: voxel = stored value
    return vol


def test_series_loads_sorted_with_12_bits_kept(tmp_path, ct):
    write_series(tmp_path / "s", ct)
    got = load_series(tmp_path / "s")
    ras = ct[:, ::-1, ::-1]          # LPS rows and columns: x and y flip into RAS
    assert got.shape == ct.shape and np.array_equal(got, ras)
    vol12 = load_volume(str(tmp_path / "s"), voxel_bits=12)
    assert np.array_equal(vol12, ras), "12-bit CT values must be kept for 12-bit voxels"


def test_series_renders_as_the_same_volume_in_nifti(tmp_path, ct):
    write_series(tmp_path / "s", ct)
    nii = tmp_path / "v.nii.gz"
    # the series' own orientation: rows along +x, columns along +y, slices along +z in
    # DICOM's LPS patient axes, i.e. x and y flipped in NIfTI's RAS
    nib.save(nib.Nifti1Image(ct.transpose(2, 1, 0), np.diag([-1.0, -1.0, 1.5, 1.0])), nii)
    a = load_volume(str(tmp_path / "s"), voxel_bits=12)
    b = load_volume(str(nii), voxel_bits=12)
    assert np.array_equal(a, b)
    scene = parse_scene({"view": {"direction": [0.3, 0.5, 0.8]}, "output": {"width": 32, "height": 32}})
    cfg = Cube4Config(voxel_bits=12)
    ia, ib = render(a, scene, cfg, "golden").image, render(b, scene, cfg, "golden").image
    assert ia.max() > 0 and np.array_equal(ia, ib)


@pytest.mark.parametrize("case, needle", [
    ("mixed", "2 DICOM series mixed"),
    ("missing", "a slice is missing"),
    ("compressed", "cannot be decoded here"),
    ("not_dicom", "not a DICOM file"),
    ("empty", "holds no files"),
    ("duplicate", "same position"),
])
def test_broken_series_is_one_clear_error(tmp_path, ct, case, needle):
    folder = tmp_path / "s"
    if case == "mixed":
        write_series(folder, ct)
        write_series(folder, ct[:3], start=100)
    elif case == "missing":
        write_series(folder, ct, skip=4)
    elif case == "compressed":
        write_series(folder, ct[:3], compressed=True)
    elif case == "not_dicom":
        write_series(folder, ct)
        (folder / "notes.txt").write_text("scanner notes")
    elif case == "empty":
        folder.mkdir()
    else:
        uid = generate_uid()
        write_series(folder, ct[:3], series_uid=uid)
        write_series(folder, ct[:1], series_uid=uid, start=100)
    with pytest.raises(UserError, match=needle) as err:
        load_volume(str(folder), voxel_bits=12)
    assert "\n" not in str(err.value)

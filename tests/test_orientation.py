"""Loaders honour the file's orientation: NIfTI affine, NRRD space and space directions
(DICOM: tests/test_dicom.py) all come out RAS (x right, y anterior, z superior)."""

from __future__ import annotations

import nibabel as nib
import nrrd
import numpy as np

from cube4.app.volumes import load_volume


def _ramp_zyx() -> np.ndarray:
    z, y, x = np.meshgrid(np.arange(3), np.arange(4), np.arange(5), indexing="ij")
    return (x + 5 * y + 20 * z).astype(np.uint8)        # distinct values, [z, y, x]


def _nii(tmp_path, vol_zyx, affine, name="v.nii.gz") -> str:
    p = tmp_path / name
    nib.save(nib.Nifti1Image(vol_zyx.transpose(2, 1, 0), affine), str(p))
    return str(p)


def test_nifti_identity_is_stored_order(tmp_path):
    v = _ramp_zyx()
    assert np.array_equal(load_volume(_nii(tmp_path, v, np.eye(4))), v)


def test_nifti_flipped_axis_comes_out_ras(tmp_path):
    v = _ramp_zyx()
    got = load_volume(_nii(tmp_path, v, np.diag([-1.0, 1.0, 1.0, 1.0])))   # file x runs to the left
    assert np.array_equal(got, v[:, :, ::-1])


def test_nifti_permuted_axes_come_out_ras(tmp_path):
    v = _ramp_zyx()
    aff = np.array([[0, 1, 0, 0], [0, 0, 1, 0], [1, 0, 0, 0], [0, 0, 0, 1]], dtype=float)  # file x = superior
    got = load_volume(_nii(tmp_path, v, aff))
    # file axes (x, y, z) point (S, R, A): RAS x = file y, RAS y = file z, RAS z = file x
    assert np.array_equal(got, v.transpose(2, 0, 1))


def test_nrrd_lps_equals_the_same_nifti(tmp_path):
    v = _ramp_zyx()
    p = tmp_path / "v.nrrd"
    nrrd.write(str(p), v, header={"space": "left-posterior-superior", "space directions": np.eye(3)},
               index_order="C")
    got = load_volume(str(p))
    assert np.array_equal(got, v[:, ::-1, ::-1])
    assert np.array_equal(got, load_volume(_nii(tmp_path, v, np.diag([-1.0, -1.0, 1.0, 1.0]))))


def test_nrrd_without_space_keeps_stored_order(tmp_path):
    v = _ramp_zyx()
    p = tmp_path / "v.nrrd"
    nrrd.write(str(p), v, index_order="C")
    assert np.array_equal(load_volume(str(p)), v)

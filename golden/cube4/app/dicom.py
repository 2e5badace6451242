"""A folder of DICOM slices (one series) as a volume vol[z, y, x].

* Every regular, non-hidden file in the folder must be a DICOM image of one series
  (SeriesInstanceUID); another series, a non-DICOM file or an image of another size or
  orientation is an error naming the file.
* Slices are sorted by their position along the slice normal (ImagePositionPatient
  projected on the cross product of ImageOrientationPatient's row and column
  directions), or by InstanceNumber where a slice has no position. Two slices at the
  same position, or a gap of more than 1.5 times the usual spacing (a missing slice),
  is an error; so are positions that are not finite numbers, two slices without positions
  that share an InstanceNumber, and an InstanceNumber that is not an integer.
* RescaleSlope (finite, non-zero, at most 1e100 in size) and RescaleIntercept are applied (e.g. CT values in Hounsfield units).
  Integer results whose range fits 16 bits are shifted so that the series' minimum is 0
  and kept exactly: a 12-bit CT series stays 12 bits, voxel = value - minimum; anything
  else is returned as floats, which the caller rescales min..max.
* Compressed transfer syntaxes that this installation cannot decode are an error that
  names the syntax.

Axes: like every loaded file, RAS (x to the patient's right, y anterior, z superior),
by the nearest axis permutation and flips of the series' orientation (DICOM's patient
axes are LPS); no resampling.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from ..errors import UserError
from ..values import shown
from .libs import quiet_library
from .orient import to_ras

GAP_FACTOR = 1.5      # a spacing this many times the median one means a missing slice
MAX_POSITION_MM = 1e6  # |ImagePositionPatient| components: a kilometre is not a patient
MAX_SLOPE = 1e100     # |RescaleSlope|: pixels (< 2^32) times it stay far inside float64
MAX_INTERCEPT = 1e300


def _read(path: Path):
    import pydicom
    from pydicom.errors import InvalidDicomError

    try:
        with quiet_library():
            return pydicom.dcmread(path)
    except InvalidDicomError:
        raise UserError(f"{path}: not a DICOM file (a DICOM series folder holds only its slices)") from None
    except Exception as e:  # truncated or corrupt files raise many kinds
        raise UserError(f"{path}: cannot read DICOM file: {e}") from None


def _files(folder: Path) -> list[Path]:
    files = sorted(p for p in folder.iterdir() if p.is_file() and not p.name.startswith("."))
    if not files:
        raise UserError(f"{folder}: the folder holds no files (a DICOM series folder holds its slices)")
    return files


def _normal(ds, path: Path | None = None) -> np.ndarray | None:
    """The slice normal from ImageOrientationPatient (six direction cosines, each within
    +-1 up to rounding); None where the slice has none."""
    iop = getattr(ds, "ImageOrientationPatient", None)
    if iop is None:
        return None
    v = _numbers(iop, 6, path or Path(getattr(ds, "filename", None) or "slice"), "ImageOrientationPatient")
    if np.any(np.abs(v) > 1.0 + 1e-3):
        raise UserError(f"{path or 'a slice'}: ImageOrientationPatient must be six direction cosines (each within "
                        f"-1..1), got {shown(str(list(iop)), 60)}")
    n = np.cross(v[:3], v[3:])
    norm = float(np.linalg.norm(n))
    return n / norm if norm > 1e-6 else None


def _numbers(value, count: int, path: Path, key: str) -> np.ndarray | None:
    """A multi-valued DICOM number (ImagePositionPatient, ...) as count finite floats."""
    if value is None:
        return None
    try:
        v = np.array([float(c) for c in value], dtype=np.float64)
    except (TypeError, ValueError, OverflowError):
        raise UserError(f"{path}: {key} must be {count} numbers, got {shown(str(value), 60)}") from None
    if v.shape != (count,) or not np.all(np.isfinite(v)):
        raise UserError(f"{path}: {key} must be {count} finite numbers, got {shown(str(value), 60)}")
    return v


def _instance(ds, path: Path) -> int | None:
    n = getattr(ds, "InstanceNumber", None)
    if n is None or n == "":
        return None
    try:
        return int(str(n).strip())
    except ValueError:
        raise UserError(f"{path}: InstanceNumber must be an integer, got {shown(str(n), 40)}") from None


def _order(slices: list, files: list[Path]) -> list[int]:
    """Slice order along the normal (or by InstanceNumber), with the spacing checked."""
    normal = _normal(slices[0], files[0])
    pos = []
    for ds, f in zip(slices, files):
        ipp = _numbers(getattr(ds, "ImagePositionPatient", None), 3, f, "ImagePositionPatient")
        if ipp is not None and np.any(np.abs(ipp) > MAX_POSITION_MM):
            raise UserError(f"{f}: ImagePositionPatient {list(map(float, ipp))} lies more than "
                            f"{MAX_POSITION_MM:g} mm from the origin")
        if normal is None or ipp is None:
            pos = None
            break
        pos.append(float(np.dot(ipp, normal)))
    if pos is None:
        nums = [_instance(ds, f) for ds, f in zip(slices, files)]
        if any(n is None for n in nums):
            raise UserError(f"{files[0].parent}: slices have neither positions nor instance numbers: "
                            "their order is unknown")
        order = sorted(range(len(slices)), key=lambda i: nums[i])
        for a, b in zip(order, order[1:]):
            if nums[a] == nums[b]:
                raise UserError(f"{files[a].name} and {files[b].name} have the same InstanceNumber {nums[a]} "
                                "and no positions: two series, or a duplicated slice")
        return order
    order = sorted(range(len(slices)), key=lambda i: pos[i])
    p = np.array([pos[i] for i in order])
    if len(p) > 1:
        gaps = np.diff(p)
        if np.any(gaps <= 1e-6 * max(1.0, float(np.max(np.abs(p))))):
            i = int(np.argmin(gaps))
            raise UserError(f"{files[order[i]].name} and {files[order[i + 1]].name} lie at the same position: "
                            "two series, or a duplicated slice")
        usual = float(np.median(gaps))
        if np.any(gaps > GAP_FACTOR * usual):
            i = int(np.argmax(gaps))
            raise UserError(f"{files[0].parent}: a slice is missing between {files[order[i]].name} and "
                            f"{files[order[i + 1]].name} (gap {gaps[i]:g} mm, spacing {usual:g} mm)")
    return order


def _pixels(ds, path: Path) -> np.ndarray:
    try:
        with quiet_library():
            a = ds.pixel_array
    except Exception as e:
        ts = getattr(getattr(ds, "file_meta", None), "TransferSyntaxUID", None)
        if ts is not None and ts.is_compressed:
            raise UserError(f"{path}: transfer syntax {ts.name} ({ts}) cannot be decoded here; "
                            "convert the series to an uncompressed syntax") from None
        raise UserError(f"{path}: cannot decode the pixel data: {e}") from None
    if a.ndim != 2:
        raise UserError(f"{path}: a slice must be one 2-D image, got pixel data of shape {a.shape}")
    return a


def _size(ds, path: Path) -> tuple[int, int]:
    """(Rows, Columns): both present and positive integers."""
    try:
        rows, cols = int(ds.Rows), int(ds.Columns)
    except (AttributeError, TypeError, ValueError):
        raise UserError(f"{path}: a slice needs Rows and Columns (positive integers)") from None
    if rows < 1 or cols < 1:
        raise UserError(f"{path}: Rows and Columns must be positive, got {rows}x{cols}")
    return rows, cols


def _rescale_value(ds, path: Path, key: str, default: float) -> float:
    """RescaleSlope / RescaleIntercept: finite (a slope also non-zero, and at most
    MAX_SLOPE in size so that no voxel overflows)."""
    raw = getattr(ds, key, None)
    if raw is None or raw == "":
        return default
    try:
        v = float(raw)
    except (TypeError, ValueError, OverflowError):
        raise UserError(f"{path}: {key} must be a number, got {shown(str(raw), 40)}") from None
    limit = MAX_SLOPE if key == "RescaleSlope" else MAX_INTERCEPT
    if not math.isfinite(v) or abs(v) > limit or (key == "RescaleSlope" and v == 0.0):
        need = "finite, non-zero and at most" if key == "RescaleSlope" else "finite and at most"
        raise UserError(f"{path}: {key} = {shown(str(raw), 40)}: must be {need} {limit:g} in size")
    return v


def _rescale(stack: np.ndarray, slopes: list[float], intercepts: list[float]) -> np.ndarray:
    s = np.array(slopes, dtype=np.float64)[:, None, None]
    b = np.array(intercepts, dtype=np.float64)[:, None, None]
    values = stack.astype(np.float64) * s + b
    if np.all(values == np.round(values)):
        lo, hi = float(values.min()), float(values.max())
        if hi - lo <= 0xFFFF:
            return (values - lo).astype(np.uint16)      # exact: voxel = value - minimum
    return values


def load_series(folder: str | os.PathLike) -> np.ndarray:
    """Load one DICOM series from a folder: vol[z, y, x] (see the module docstring)."""
    folder = Path(folder)
    files = _files(folder)
    slices = [_read(f) for f in files]
    uids = {str(getattr(ds, "SeriesInstanceUID", "")) for ds in slices}
    if len(uids) > 1:
        raise UserError(f"{folder}: {len(uids)} DICOM series mixed in one folder: put each series in a "
                        "folder of its own")
    for ds, f in zip(slices, files):
        if "PixelData" not in ds:
            raise UserError(f"{f}: a DICOM file without an image")
    shapes = [_size(ds, f) for ds, f in zip(slices, files)]
    for shape, f in zip(shapes, files):
        if shape != shapes[0]:
            raise UserError(f"{f}: a {shape[0]}x{shape[1]} slice in a series of {shapes[0][0]}x{shapes[0][1]}")
    n0 = _normal(slices[0], files[0])
    for ds, f in zip(slices, files):
        n = _normal(ds, f)
        if n0 is not None and n is not None and not np.allclose(n, n0, atol=1e-4):
            raise UserError(f"{f}: its orientation differs from the rest of the series")
    order = _order(slices, files)
    stack = np.stack([_pixels(slices[i], files[i]) for i in order])   # [z, rows (y), columns (x)]
    slopes = [_rescale_value(slices[i], files[i], "RescaleSlope", 1.0) for i in order]
    intercepts = [_rescale_value(slices[i], files[i], "RescaleIntercept", 0.0) for i in order]
    vol = _rescale(stack, slopes, intercepts)
    directions = _ras_directions(slices[order[0]])
    return vol if directions is None else to_ras(vol, directions)


def _ras_directions(ds) -> np.ndarray | None:
    """Columns: the directions of the volume's x (along a row), y (down the columns) and
    z (along the sorted slices) in RAS. DICOM's patient axes are LPS: x and y flip."""
    normal = _normal(ds)
    if normal is None:
        return None
    iop = np.array(ds.ImageOrientationPatient, dtype=float)
    lps = np.stack([iop[:3], iop[3:], normal], axis=1)
    return np.diag([-1.0, -1.0, 1.0]) @ lps

"""Volumes for a run: the built-ins and loaders for raw, NRRD, NIfTI and DICOM files.

A volume is a C-contiguous ``numpy.uint16`` array indexed ``vol[z, y, x]`` (x varies
fastest in memory), holding unsigned voxels in ``0 .. 2**voxel_bits - 1``. Its
dimensions are reported as ``(nx, ny, nz)``.

:func:`load_volume` takes a *spec*:

* a built-in ``NAME:N`` (an N^3 cube) or ``NAME:NX,NY,NZ`` such as ``sphere:64``,
  ``ml:41``, ``head:128`` or ``sphere:64,48,32``; :func:`builtin_names` lists the names:
  the generated phantoms of ``cube4.phantoms`` and two made from real MRI data shipped
  inside nibabel (``mri`` and ``mri_t1``), which may also be given without dimensions
  for their native size;
* a file path: ``.raw``/``.bin``/``.dat`` (headerless little-endian voxels),
  ``.nrrd``/``.nhdr`` (pynrrd) or ``.nii``/``.nii.gz`` (nibabel);
* a folder of DICOM slices of one series (:mod:`cube4.app.dicom`).

File data becomes voxels by :func:`to_voxels`: integer data already inside the voxel
range is kept bit for bit; anything else is rescaled linearly min..max onto the range.
Files that say how their axes lie in the patient are reoriented to RAS
(:func:`cube4.app.orient.to_ras`; no resampling). Files that do not say (raw files, NRRD
without a known space) keep their stored index order (first axis = x).
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Callable
from importlib import resources

import numpy as np

from ..config import MAX_DIM
from ..errors import UserError
from ..phantoms import PHANTOMS, Dims, check_bits, check_dims, check_memory, parse_dims, quantise
from .dicom import load_series
from .libs import quiet_library
from .orient import to_ras

# --------------------------------------------------------------------------------------
# File data to voxels
# --------------------------------------------------------------------------------------


def to_voxels(data: np.ndarray, voxel_bits: int = 8) -> np.ndarray:
    """Convert file data to voxels: in-range integers kept, else min..max rescaled."""
    vmax = check_bits(voxel_bits)
    a = np.asarray(data)
    if a.dtype == np.bool_:
        a = a.astype(np.uint8)
    if a.dtype.kind not in "uif":
        raise UserError(f"cannot use volume data of type {a.dtype}: need integers or real numbers")
    if a.size == 0:
        raise UserError("volume holds no voxels")
    if a.dtype.kind == "f" and not np.all(np.isfinite(a)):
        raise UserError("volume data contain NaN or infinite values")
    lo, hi = a.min(), a.max()
    if a.dtype.kind in "ui" and lo >= 0 and hi <= vmax:
        return np.ascontiguousarray(a.astype(np.uint16))
    lo, hi = float(lo), float(hi)
    if hi == lo:
        return np.zeros(a.shape, dtype=np.uint16)
    with np.errstate(over="raise", invalid="raise"):
        try:
            if np.isfinite(hi - lo):
                scaled = np.floor((a.astype(np.float64) - lo) * (vmax / (hi - lo)) + 0.5)
            else:   # values near the float64 limit: halves, so that no difference overflows
                t = (a.astype(np.float64) / 2.0 - lo / 2.0) / (hi / 2.0 - lo / 2.0)
                scaled = np.floor(t * vmax + 0.5)
        except FloatingPointError:
            raise UserError(f"volume values {lo:g}..{hi:g} cannot be rescaled to {voxel_bits}-bit voxels") from None
    return np.ascontiguousarray(np.clip(scaled, 0, vmax).astype(np.uint16))


# --------------------------------------------------------------------------------------
# Built-ins: the phantoms and real MRI data
# --------------------------------------------------------------------------------------

# Real MRI data shipped inside the nibabel wheel (its test data; no download):
#   example4d.nii.gz  FSL-written 4-D brain series, 128 x 96 x 24 voxels of
#                     2 x 2 x 2.2 mm, 2 volumes, int16 0..1162; the first volume is used.
#   anatomical.nii    SPM-normalised T1 anatomical, 33 x 41 x 25 voxels of 2 mm,
#                     int16 -610..30393, cropped to the middle of the brain.
# Both are reoriented to RAS (x -> right, y -> anterior, z -> superior) and min..max
# normalised; other dims resample them trilinearly (grid corners aligned).
_MRI_FILES = {"mri": ("example4d.nii.gz", 0), "mri_t1": ("anatomical.nii", None)}
_mri_cache: dict[str, np.ndarray] = {}


def _mri_native(name: str) -> np.ndarray:
    """The named nibabel data file as a float32 field in [0, 1], [z, y, x], RAS."""
    if name not in _mri_cache:
        import nibabel as nib

        fname, vol_index = _MRI_FILES[name]
        path = resources.files("nibabel").joinpath("tests", "data", fname)
        if not path.is_file():
            raise UserError(f"built-in {name!r} needs {fname} from nibabel's test data, not found")
        img = nib.as_closest_canonical(nib.load(str(path)))
        data = np.asarray(img.dataobj, dtype=np.float64)
        if vol_index is not None:
            data = data[..., vol_index]
        data = (data - data.min()) / (data.max() - data.min())
        _mri_cache[name] = np.ascontiguousarray(data.transpose(2, 1, 0).astype(np.float32))
    return _mri_cache[name]


def _resample_axis(a: np.ndarray, n: int, axis: int) -> np.ndarray:
    """Linear resampling of one axis to n points, end points aligned."""
    src = a.shape[axis]
    if src == n:
        return a
    pos = np.linspace(0.0, src - 1.0, n)
    i0 = np.minimum(np.floor(pos).astype(np.intp), src - 2)
    w = (pos - i0).astype(np.float32)
    shape = [1] * a.ndim
    shape[axis] = n
    w = w.reshape(shape)
    return np.take(a, i0, axis=axis) * (1 - w) + np.take(a, i0 + 1, axis=axis) * w


def _mri_generator(name: str) -> Callable[[int, int, int], np.ndarray]:
    def gen(nx: int, ny: int, nz: int) -> np.ndarray:
        a = _mri_native(name)
        for axis, n in ((0, nz), (1, ny), (2, nx)):
            a = _resample_axis(a, n, axis)
        return np.ascontiguousarray(a, dtype=np.float32)

    return gen


def gen_mri(nx: int, ny: int, nz: int) -> np.ndarray:
    """Real brain MRI from nibabel's test data (example4d.nii.gz, volume 0), RAS."""
    return _mri_generator("mri")(nx, ny, nz)


def gen_mri_t1(nx: int, ny: int, nz: int) -> np.ndarray:
    """Real T1 MRI crop from nibabel's test data (anatomical.nii), RAS."""
    return _mri_generator("mri_t1")(nx, ny, nz)


# Real MRI from a Debian package (scripts/setup.sh installs it): mricron-data's templates,
#   ch2.nii.gz        the Colin27 T1 (Holmes 1998), 181 x 217 x 181 voxels of 1 mm, uint8,
#                     MNI space; its label maps (cube4.app.labelmaps) lie on the same grid.
MRICRON_TEMPLATES = "/usr/share/mricron/templates"
_PACKAGE_FILES = {"colin": ("ch2.nii.gz", "mricron-data")}


def package_file(fname: str, package: str = "mricron-data") -> str:
    """A template file of a Debian package; one line when the package is missing."""
    path = os.path.join(MRICRON_TEMPLATES, fname)
    if not os.path.isfile(path):
        raise UserError(f"{fname} is missing: install the Debian package {package} "
                        "(scripts/setup.sh does: apt-get install mricron-data)")
    return path


def _colin_native() -> np.ndarray:
    if "colin" not in _mri_cache:
        import nibabel as nib

        img = nib.as_closest_canonical(nib.load(package_file(_PACKAGE_FILES["colin"][0])))
        data = np.asarray(img.dataobj, dtype=np.float64)
        data = (data - data.min()) / (data.max() - data.min())
        _mri_cache["colin"] = np.ascontiguousarray(data.transpose(2, 1, 0).astype(np.float32))
    return _mri_cache["colin"]


def gen_colin(nx: int, ny: int, nz: int) -> np.ndarray:
    """The Colin27 T1 head MRI from the Debian package mricron-data (ch2.nii.gz), RAS."""
    a = _colin_native()
    for axis, n in ((0, nz), (1, ny), (2, nx)):
        a = _resample_axis(a, n, axis)
    return np.ascontiguousarray(a, dtype=np.float32)


def _native_dims(name: str) -> Dims:
    if name == "colin":
        nz, ny, nx = _colin_native().shape
        return (nx, ny, nz)
    nz, ny, nx = _mri_native(name).shape
    return (nx, ny, nz)


BUILTINS: dict[str, tuple[Callable[[int, int, int], np.ndarray], str]] = {
    **PHANTOMS,
    "mri": (gen_mri, "real brain MRI shipped with nibabel, native 128x96x24"),
    "mri_t1": (gen_mri_t1, "real T1 MRI crop shipped with nibabel, native 33x41x25"),
    "colin": (gen_colin, "the Colin27 T1 head MRI of the Debian package mricron-data, native 181x217x181"),
}

# Built-ins with a size of their own, usable without ":dims".
NATIVE_DIMS: dict[str, Callable[[], Dims]] = {
    "mri": lambda: _native_dims("mri"),
    "mri_t1": lambda: _native_dims("mri_t1"),
    "colin": lambda: _native_dims("colin"),
}


def builtin_names() -> list[str]:
    """Names of the built-in volumes, in registration order."""
    return list(BUILTINS)


def _builtin_list() -> str:
    return ", ".join(builtin_names())


def _load_builtin(name: str, dims_text: str | None, spec: str, voxel_bits: int, max_dim: int) -> np.ndarray:
    key = name.lower()
    if key not in BUILTINS:
        raise UserError(
            f"unknown built-in volume {name!r} (and no file {spec!r} exists); "
            f"built-ins: {_builtin_list()}"
        )
    if dims_text is None:
        if key not in NATIVE_DIMS:
            raise UserError(f"built-in {key!r} needs dimensions: {key}:N or {key}:NX,NY,NZ")
        dims = NATIVE_DIMS[key]()
    else:
        dims = parse_dims(dims_text, spec)
    check_dims(dims, max_dim, spec)
    check_bits(voxel_bits)
    check_memory(dims, spec)
    field = BUILTINS[key][0](*dims)
    return quantise(field, voxel_bits)


# --------------------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------------------

RAW_SUFFIXES = (".raw", ".bin", ".dat")
NRRD_SUFFIXES = (".nrrd", ".nhdr")
NIFTI_SUFFIXES = (".nii", ".nii.gz")

RAW_DTYPES = ("uint8", "uint16", "int16", "uint32", "int32", "float32", "float64")
_DTYPE_ALIASES = {
    "u8": "uint8", "uint8": "uint8",
    "u16": "uint16", "uint16": "uint16",
    "i16": "int16", "s16": "int16", "int16": "int16",
    "u32": "uint32", "uint32": "uint32",
    "i32": "int32", "s32": "int32", "int32": "int32",
    "f32": "float32", "float32": "float32", "float": "float32",
    "f64": "float64", "float64": "float64", "double": "float64",
}  # fmt: skip


def _raw_dtype(name: str) -> np.dtype:
    key = _DTYPE_ALIASES.get(name.strip().lower())
    if key is None:
        raise UserError(f"unsupported raw dtype {name!r}: use one of {', '.join(RAW_DTYPES)}")
    return np.dtype(key).newbyteorder("<")


def _dims_from_name(stem: str) -> Dims | None:
    m = re.search(r"(?:^|[^0-9])(\d+)[xX](\d+)[xX](\d+)(?![0-9])", stem)
    return (int(m[1]), int(m[2]), int(m[3])) if m else None


def _dtype_from_name(stem: str) -> str | None:
    for token in reversed(re.split(r"[_.\-]", stem.lower())):
        if token in _DTYPE_ALIASES:
            return token
    return None


def _load_raw(path: str, raw_dims: Dims | None, raw_dtype: str | None, max_dim: int) -> np.ndarray:
    stem = os.path.basename(path).rsplit(".", 1)[0]
    if raw_dims is not None:
        try:
            dims: tuple[int, ...] | None = tuple(int(n) for n in raw_dims)
        except (TypeError, ValueError):
            raise UserError(f"raw file {path}: --dims must be NX,NY,NZ, got {raw_dims!r}") from None
    else:
        dims = _dims_from_name(stem)
    dtype_name = raw_dtype if raw_dtype is not None else _dtype_from_name(stem)
    if dims is None or dtype_name is None:
        missing = " and ".join(
            w for w, v in (("dimensions", dims), ("voxel type", dtype_name)) if v is None
        )
        raise UserError(
            f"raw file {path}: {missing} unknown; pass --dims NX,NY,NZ and "
            f"--dtype TYPE, or name the file like vol_64x48x32_uint8.raw "
            f"(types: {', '.join(RAW_DTYPES)}; also u8, u16, i16, f32)"
        )
    if len(dims) != 3:
        raise UserError(f"raw file {path}: --dims must be NX,NY,NZ, got {raw_dims!r}")
    dtype = _raw_dtype(dtype_name)
    nx, ny, nz = check_dims(dims, max_dim, path)  # type: ignore[misc]
    expected = nx * ny * nz * dtype.itemsize
    actual = os.path.getsize(path)
    if actual != expected:
        kind = "truncated" if actual < expected else "too large"
        raise UserError(
            f"raw file {path} is {kind}: {actual} bytes, but {nx}x{ny}x{nz} {dtype.name} "
            f"needs exactly {expected} bytes"
        )
    _check_room((nx, ny, nz), dtype.itemsize, path)
    data = np.fromfile(path, dtype=dtype, count=nx * ny * nz)
    return data.reshape(nz, ny, nx)  # x varies fastest in the file


# loading a file takes its data, a float64 copy while rescaling, the result and temporaries
LOAD_BYTES_PER_VOXEL = 24


def _check_room(dims, itemsize: int, path: str) -> None:
    """Refuse, before reading, a file whose voxels this process cannot hold."""
    check_memory(tuple(int(n) for n in dims), path, bytes_per_voxel=itemsize + LOAD_BYTES_PER_VOXEL,
                 doing="to load", what="volume file")


def _spatial_3d(data: np.ndarray, path: str, t_axis: int) -> np.ndarray:
    """Accept 3-D data, or 4-D whose extra axis (t_axis) has length 1."""
    if data.ndim == 4 and data.shape[t_axis] == 1:
        data = np.squeeze(data, axis=t_axis)
    if data.ndim != 3:
        raise UserError(f"{path}: need a 3-D volume, file holds {data.ndim}-D data of shape {data.shape}")
    return data


def _load_nrrd(path: str) -> np.ndarray:
    import nrrd

    try:
        # index_order='C' gives the slowest axis first: [z, y, x] for a 3-D file whose
        # first NRRD axis (fastest) is x. (The default 'F' order would give [x, y, z].)
        with quiet_library():
            head = nrrd.read_header(path)
            sizes = [int(n) for n in head.get("sizes", [])]
            _check_room((sizes + [1, 1, 1])[:3], 8 * math.prod(sizes[3:]), path)   # 8: the widest type
            data, header = nrrd.read(path, index_order="C")
    except UserError:
        raise
    except KeyError as e:        # pynrrd's table of types
        raise UserError(f"cannot read NRRD file {path}: unknown NRRD type {e}") from None
    except Exception as e:       # corrupt payloads raise many kinds (zlib, EOF, value errors)
        raise UserError(f"cannot read NRRD file {path}: {type(e).__name__}: {e}") from None
    data = _spatial_3d(np.asarray(data), path, t_axis=0)
    affine = _nrrd_ras_affine(header, path)
    return data if affine is None else to_ras(data, affine)


# NRRD "space" names -> the sign that turns each of its axes into RAS
_NRRD_SPACES = {
    "right-anterior-superior": (1, 1, 1), "ras": (1, 1, 1),
    "left-anterior-superior": (-1, 1, 1), "las": (-1, 1, 1),
    "left-posterior-superior": (-1, -1, 1), "lps": (-1, -1, 1),
}


def _nrrd_ras_affine(header: dict, path: str = "NRRD file") -> np.ndarray | None:
    """The 3 x 3 direction matrix (columns = file axes x, y, z) in RAS, from the NRRD
    'space' and 'space directions'; None when the file does not say (stored order kept)."""
    space = str(header.get("space", "")).lower()
    dirs = header.get("space directions")
    if space not in _NRRD_SPACES or dirs is None:
        return None
    rows = [np.asarray(r, dtype=np.float64) for r in dirs
            if r is not None and np.all(np.isfinite(np.asarray(r, dtype=np.float64)))]
    if len(rows) != 3 or any(r.shape != (3,) for r in rows):
        return None
    m = np.array(rows).T
    big = np.max(np.abs(m), axis=0)
    if np.any(big == 0):
        raise UserError(f"{path}: space directions {[list(map(float, r)) for r in rows]} are zero or not "
                        "independent: the axes do not span a volume")
    m = m / big                      # each axis to at most 1 first: huge spacings neither overflow nor vanish
    m = m / np.linalg.norm(m, axis=0)
    if abs(np.linalg.det(m)) < 1e-6:
        raise UserError(f"{path}: space directions {[list(map(float, r)) for r in rows]} are zero or not "
                        "independent: the axes do not span a volume")
    return m * np.array(_NRRD_SPACES[space], dtype=np.float64)[:, None]


def _nifti_header(img, path: str) -> None:
    """The header's scaling finite (nibabel would ignore an infinite slope; a slope of 0
    or NaN means "unscaled" in the standard), and an uncompressed file as long as its
    header says."""
    from nibabel.openers import ImageOpener

    try:
        with quiet_library(), ImageOpener(path) as f:
            hdr = img.header_class.from_fileobj(f)
        slope, inter = float(hdr["scl_slope"]), float(hdr["scl_inter"])
    except Exception as e:  # nibabel read it once already; a second read failing is corrupt data
        raise UserError(f"cannot read NIfTI file {path}: {type(e).__name__}: {e}") from None
    if np.isinf(slope) or (np.isinf(inter) and slope not in (0.0,) and not np.isnan(slope)):
        raise UserError(f"NIfTI file {path}: scale slope {slope:g} and intercept {inter:g} must be finite")
    if path.lower().endswith(".nii"):
        need = int(hdr.get_data_offset()) + int(np.prod(hdr.get_data_shape(), dtype=np.int64)) * hdr.get_data_dtype().itemsize
        have = os.path.getsize(path)
        if have < need:
            raise UserError(f"NIfTI file {path} is truncated: {have} bytes, its header needs {need}")


def _load_nifti(path: str) -> np.ndarray:
    import nibabel as nib

    try:
        with quiet_library():
            img = nib.load(path)
    except Exception as e:  # nibabel raises many kinds for corrupt files
        raise UserError(f"cannot read NIfTI file {path}: {type(e).__name__}: {e}") from None
    _nifti_header(img, path)
    shape = tuple(int(n) for n in img.shape) or (1,)
    _check_room((shape + (1, 1, 1))[:3], math.prod(shape[3:]) * img.get_data_dtype().itemsize, path)
    try:
        with quiet_library():
            if len(img.shape) >= 3:
                img = nib.as_closest_canonical(img)   # RAS: x right, y anterior, z superior
            data = np.asarray(img.dataobj)  # [x, y, z(, t)]; scl_slope applied if set
    except Exception as e:  # nibabel raises many kinds for corrupt files
        raise UserError(f"cannot read NIfTI file {path}: {type(e).__name__}: {e}".rstrip(": ")) from None
    data = _spatial_3d(data, path, t_axis=3)
    return data.transpose(2, 1, 0)  # -> [z, y, x]


_PATH_MAX = 4096


def _suffix_kind(path: str) -> str | None:
    low = path.lower()
    for kind, suffixes in (("raw", RAW_SUFFIXES), ("nrrd", NRRD_SUFFIXES), ("nifti", NIFTI_SUFFIXES)):
        if low.endswith(suffixes):
            return kind
    return None


def _load_file(path: str, voxel_bits: int, raw_dims, raw_dtype, max_dim: int) -> np.ndarray:
    kind = _suffix_kind(path)
    if kind is None:
        raise UserError(
            f"unknown volume file type {path!r}: use .raw/.bin/.dat, .nrrd/.nhdr or "
            f".nii/.nii.gz, or a built-in NAME:N ({_builtin_list()})"
        )
    if len(os.fsencode(os.path.abspath(path))) >= _PATH_MAX:
        raise UserError(f"volume file {path[:60]!r}...: the path is longer than the system allows")
    if not os.path.isfile(path):
        raise UserError(f"volume file not found: {path}")
    check_bits(voxel_bits)
    if kind == "raw":
        data = _load_raw(path, raw_dims, raw_dtype, max_dim)
    else:
        data = _load_nrrd(path) if kind == "nrrd" else _load_nifti(path)
        nz, ny, nx = data.shape
        check_dims((nx, ny, nz), max_dim, path)
    if data.dtype.kind in "uif" and data.dtype.byteorder not in ("=", "|"):
        data = data.astype(data.dtype.newbyteorder("="))
    return to_voxels(data, voxel_bits)


def _load_dicom(folder: str, voxel_bits: int, max_dim: int) -> np.ndarray:
    """A folder of DICOM slices of one series (cube4.app.dicom)."""
    check_bits(voxel_bits)
    data = load_series(folder)
    nz, ny, nx = data.shape
    check_dims((nx, ny, nz), max_dim, folder)
    return to_voxels(data, voxel_bits)


# --------------------------------------------------------------------------------------
# Entry point
# --------------------------------------------------------------------------------------


def load_volume(
    spec: str,
    *,
    voxel_bits: int = 8,
    raw_dims: tuple[int, int, int] | None = None,
    raw_dtype: str | None = None,
    max_dim: int = MAX_DIM,
) -> np.ndarray:
    """Load a built-in (NAME:N, NAME:NX,NY,NZ), a volume file or a folder of DICOM
    slices (one series) as uint16 vol[z, y, x]."""
    spec = str(spec)
    if os.path.isdir(spec):
        return _load_dicom(spec, voxel_bits, max_dim)
    if os.path.exists(spec) or _suffix_kind(spec) is not None:
        return _load_file(spec, voxel_bits, raw_dims, raw_dtype, max_dim)
    m = re.fullmatch(r"([A-Za-z_][A-Za-z0-9_]*):(.*)", spec)
    if m:
        return _load_builtin(m[1], m[2], spec, voxel_bits, max_dim)
    if spec.lower() in BUILTINS:
        return _load_builtin(spec, None, spec, voxel_bits, max_dim)
    if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", spec):
        raise UserError(
            f"{spec!r} is neither a file nor a built-in volume; built-ins "
            f"(as NAME:N or NAME:NX,NY,NZ): {_builtin_list()}"
        )
    return _load_file(spec, voxel_bits, raw_dims, raw_dtype, max_dim)

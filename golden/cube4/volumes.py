"""Volumes: built-in test volumes and loaders for raw, NRRD and NIfTI files.

A volume is a C-contiguous ``numpy.uint16`` array indexed ``vol[z, y, x]`` (x varies
fastest in memory), holding unsigned voxels in ``0 .. 2**voxel_bits - 1``. Its
dimensions are reported as ``(nx, ny, nz)``.

:func:`load_volume` takes a *spec*:

* a built-in ``NAME:N`` (an N^3 cube) or ``NAME:NX,NY,NZ`` such as ``sphere:64``,
  ``ml:41``, ``head:128`` or ``sphere:64,48,32``; :func:`builtin_names` lists the names.
  The two built-ins made from real MRI data shipped inside nibabel (``mri`` and
  ``mri_t1``) may also be given without dimensions for their native size;
* a file path: ``.raw``/``.bin``/``.dat`` (headerless little-endian voxels),
  ``.nrrd``/``.nhdr`` (pynrrd) or ``.nii``/``.nii.gz`` (nibabel);
* a folder of DICOM slices of one series (:mod:`cube4.dicom`).

File data becomes voxels by :func:`to_voxels`: integer data already inside the voxel
range is kept bit for bit; anything else is rescaled linearly min..max onto the range.
Files that say how their axes lie in the patient (the NIfTI affine, the NRRD ``space``
and ``space directions``, DICOM's orientation and positions) are reoriented to RAS: x
to the right, y anterior (to the front), z superior (up), by the nearest axis
permutation and flips (:func:`to_ras`; no resampling). Files that do not say (raw
files, NRRD without a known space) keep their stored index order (first axis = x).
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable
from importlib import resources

import numpy as np

from .config import MAX_DIM
from .errors import UserError

Dims = tuple[int, int, int]

# --------------------------------------------------------------------------------------
# Quantisation
# --------------------------------------------------------------------------------------


def _check_bits(voxel_bits: int) -> int:
    if not isinstance(voxel_bits, (int, np.integer)) or not 4 <= voxel_bits <= 16:
        raise UserError(f"voxel_bits must be an integer in 4..16, got {voxel_bits!r}")
    return (1 << int(voxel_bits)) - 1


def quantise(field: np.ndarray, voxel_bits: int = 8) -> np.ndarray:
    """Map a float field in [0, 1] to voxels: floor(clip(f, 0, 1) * (2^V - 1) + 0.5)."""
    vmax = _check_bits(voxel_bits)
    f = np.clip(np.asarray(field, dtype=np.float64), 0.0, 1.0)
    return np.ascontiguousarray(np.floor(f * vmax + 0.5).astype(np.uint16))


def to_voxels(data: np.ndarray, voxel_bits: int = 8) -> np.ndarray:
    """Convert file data to voxels: in-range integers kept, else min..max rescaled."""
    vmax = _check_bits(voxel_bits)
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
# Built-in volumes: float fields in [0, 1] indexed [z, y, x]
# --------------------------------------------------------------------------------------


def _unit_axes(nx: int, ny: int, nz: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Grid coordinates on [-1, 1] per axis (x_i = -1 + 2 i / (n - 1)), float64 1-D."""
    return tuple(np.linspace(-1.0, 1.0, n) for n in (nx, ny, nz))  # type: ignore[return-value]


def sphere_radius(dims: Dims) -> float:
    """Radius of the ``sphere`` built-in in voxel units: 0.375 * min(nx, ny, nz)."""
    return 0.375 * min(dims)


def sphere_centre(dims: Dims) -> tuple[float, float, float]:
    """Centre (x, y, z) of the ``sphere`` built-in in voxel coordinates: (n - 1) / 2."""
    return tuple((n - 1) / 2.0 for n in dims)  # type: ignore[return-value]


def _radius_field(nx: int, ny: int, nz: int) -> np.ndarray:
    """Distance in voxels from the volume centre, float32 [z, y, x]."""
    cx, cy, cz = sphere_centre((nx, ny, nz))
    dx = (np.arange(nx, dtype=np.float32) - np.float32(cx)) ** 2
    dy = (np.arange(ny, dtype=np.float32) - np.float32(cy)) ** 2
    dz = (np.arange(nz, dtype=np.float32) - np.float32(cz)) ** 2
    r2 = dz[:, None, None] + (dy[:, None] + dx[None, :])[None, :, :]
    return np.sqrt(r2, out=r2)


def _ball(r: np.ndarray, radius: float) -> np.ndarray:
    """Antialiased solid ball: clip(radius - r + 0.5, 0, 1)."""
    f = np.float32(radius + 0.5) - r
    return np.clip(f, 0.0, 1.0, out=f)


def gen_sphere(nx: int, ny: int, nz: int) -> np.ndarray:
    """Solid sphere of density 1, radius 0.375*min(n), antialiased one-voxel edge."""
    return _ball(_radius_field(nx, ny, nz), sphere_radius((nx, ny, nz)))


ML_FM = 6.0
ML_ALPHA = 0.25


def ml_density(x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
    """Marschner-Lobb density at points of [-1, 1]^3 (f_M = 6, alpha = 0.25), float64."""
    r = np.sqrt(np.asarray(x, np.float64) ** 2 + np.asarray(y, np.float64) ** 2)
    rho_r = np.cos(2.0 * np.pi * ML_FM * np.cos(np.pi * r / 2.0))
    return (1.0 - np.sin(np.pi * np.asarray(z, np.float64) / 2.0) + ML_ALPHA * (1.0 + rho_r)) / (
        2.0 * (1.0 + ML_ALPHA)
    )


def gen_ml(nx: int, ny: int, nz: int) -> np.ndarray:
    """Marschner-Lobb test signal on [-1,1]^3 (f_M = 6, alpha = 0.25)."""
    x, y, z = _unit_axes(nx, ny, nz)
    r = np.sqrt(y[:, None] ** 2 + x[None, :] ** 2)
    a = 2.0 * (1.0 + ML_ALPHA)
    xy = (ML_ALPHA * (1.0 + np.cos(2.0 * np.pi * ML_FM * np.cos(np.pi * r / 2.0)))) / a
    zt = (1.0 - np.sin(np.pi * z / 2.0)) / a
    return zt.astype(np.float32)[:, None, None] + xy.astype(np.float32)[None, :, :]


# 3-D Shepp-Logan head phantom. Geometry: the ten ellipsoids of the 3-D phantom in
# Kak & Slaney, "Principles of Computerized Tomographic Imaging" (IEEE Press, 1988),
# ch. 3. Intensities: the higher-contrast "modified" values of Yu, Ye & Wang,
# "Katsevich-type algorithms for variable radius spiral cone-beam CT" (Proc. SPIE 5535,
# 2004) -- 1, -0.8, -0.2, -0.2, 0.2, 0.2, 0.1, 0.1, 0.2, -0.2 -- in place of Kak &
# Slaney's 2, -0.98, -0.02, -0.02, 0.02, 0.02, 0.01, 0.01, 0.02, -0.02, so the skull is
# 1.0, brain 0.2 and the inner structures 0.0..0.6. Columns: x0, y0, z0, a, b, c (semi-
# axes along x, y, z before rotation), phi (rotation about z, degrees), additive value.
HEAD_ELLIPSOIDS = (
    (0.00, 0.000, 0.000, 0.6900, 0.920, 0.900, 0.0, 1.0),
    (0.00, 0.000, 0.000, 0.6624, 0.874, 0.880, 0.0, -0.8),
    (-0.22, 0.000, -0.250, 0.4100, 0.160, 0.210, 108.0, -0.2),
    (0.22, 0.000, -0.250, 0.3100, 0.110, 0.220, 72.0, -0.2),
    (0.00, 0.350, -0.250, 0.2100, 0.250, 0.500, 0.0, 0.2),
    (0.00, 0.100, -0.250, 0.0460, 0.046, 0.046, 0.0, 0.2),
    (-0.08, -0.650, -0.250, 0.0460, 0.023, 0.020, 0.0, 0.1),
    (0.06, -0.650, -0.250, 0.0460, 0.023, 0.020, 90.0, 0.1),
    (0.06, -0.105, 0.625, 0.0560, 0.040, 0.100, 90.0, 0.2),
    (0.00, 0.100, 0.625, 0.0560, 0.056, 0.100, 0.0, -0.2),
)


def _span(coord: np.ndarray, centre: float, half: float) -> slice:
    """Index range of a sorted 1-D grid that can lie within centre +- half."""
    lo = int(np.searchsorted(coord, centre - half - 1e-9, side="left"))
    hi = int(np.searchsorted(coord, centre + half + 1e-9, side="right"))
    return slice(lo, hi)


def gen_head(nx: int, ny: int, nz: int) -> np.ndarray:
    """3-D Shepp-Logan head phantom (Kak & Slaney geometry, modified contrast)."""
    x, y, z = _unit_axes(nx, ny, nz)
    out = np.zeros((nz, ny, nx), dtype=np.float32)
    for x0, y0, z0, a, b, c, phi, val in HEAD_ELLIPSOIDS:
        ext = max(a, b)  # bounding half-width in x and y for any rotation about z
        sx, sy, sz = _span(x, x0, ext), _span(y, y0, ext), _span(z, z0, c)
        if sx.start >= sx.stop or sy.start >= sy.stop or sz.start >= sz.stop:
            continue
        dx, dy = x[sx][None, :] - x0, y[sy][:, None] - y0
        cp, sp = np.cos(np.radians(phi)), np.sin(np.radians(phi))
        u, v = cp * dx + sp * dy, -sp * dx + cp * dy  # rotate the point by -phi
        qxy = ((u / a) ** 2 + (v / b) ** 2).astype(np.float32)
        qz = (((z[sz] - z0) / c) ** 2).astype(np.float32)
        inside = (qz[:, None, None] + qxy[None, :, :]) <= 1.0
        out[sz, sy, sx] += np.float32(val) * inside
    return np.clip(out, 0.0, 1.0, out=out)


def gen_cube(nx: int, ny: int, nz: int) -> np.ndarray:
    """Hard-edged cube of density 1 over the middle half of each axis (0 -> 1 steps)."""
    out = np.zeros((nz, ny, nx), dtype=np.float32)
    out[nz // 4 : nz - nz // 4, ny // 4 : ny - ny // 4, nx // 4 : nx - nx // 4] = 1.0
    return out


# (inner, outer radius as fractions of 0.45 * min(n), density), outermost first.
SHELLS = ((0.85, 1.00, 0.25), (0.55, 0.70, 0.50), (0.25, 0.40, 0.75), (0.00, 0.12, 1.00))


def gen_shells(nx: int, ny: int, nz: int) -> np.ndarray:
    """Four nested concentric spherical shells, densities 0.25/0.5/0.75/1 outside in."""
    r = _radius_field(nx, ny, nz)
    rmax = 0.45 * min(nx, ny, nz)
    out = np.zeros_like(r)
    for inner, outer, dens in SHELLS:
        shell = _ball(r, outer * rmax)
        if inner > 0:
            shell -= _ball(r, inner * rmax)
        shell *= np.float32(dens)
        out += shell
    return out


def gen_noise(nx: int, ny: int, nz: int) -> np.ndarray:
    """Uniform random voxels, reproducible: the generator is seeded by the dims."""
    rng = np.random.default_rng([nx, ny, nz, 0xC0BE4])
    return rng.random((nz, ny, nx), dtype=np.float32)


def gen_constant(nx: int, ny: int, nz: int) -> np.ndarray:
    """All 0.5: zero gradients everywhere."""
    return np.full((nz, ny, nx), 0.5, dtype=np.float32)


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


def _native_dims(name: str) -> Dims:
    nz, ny, nx = _mri_native(name).shape
    return (nx, ny, nz)


BUILTINS: dict[str, tuple[Callable[[int, int, int], np.ndarray], str]] = {
    "sphere": (gen_sphere, "solid sphere, radius 0.375*min(n), antialiased edge"),
    "ml": (gen_ml, "Marschner-Lobb test signal (f_M = 6, alpha = 0.25)"),
    "head": (gen_head, "3-D Shepp-Logan head phantom, modified contrast"),
    "cube": (gen_cube, "hard-edged cube over the middle half"),
    "shells": (gen_shells, "nested spherical shells of densities 0.25..1"),
    "noise": (gen_noise, "reproducible uniform random voxels"),
    "constant": (gen_constant, "all 0.5 (zero gradients)"),
    "mri": (gen_mri, "real brain MRI shipped with nibabel, native 128x96x24"),
    "mri_t1": (gen_mri_t1, "real T1 MRI crop shipped with nibabel, native 33x41x25"),
}

# Built-ins with a size of their own, usable without ":dims".
NATIVE_DIMS: dict[str, Callable[[], Dims]] = {
    "mri": lambda: _native_dims("mri"),
    "mri_t1": lambda: _native_dims("mri_t1"),
}


def builtin_names() -> list[str]:
    """Names of the built-in volumes, in registration order."""
    return list(BUILTINS)


def _builtin_list() -> str:
    return ", ".join(builtin_names())


# --------------------------------------------------------------------------------------
# Spec parsing and dims
# --------------------------------------------------------------------------------------


def _check_dims(dims: Dims, max_dim: int, what: str) -> Dims:
    for axis, n in zip("xyz", dims):
        if not 2 <= n <= max_dim:
            nx, ny, nz = dims
            raise UserError(
                f"{what}: dimensions {nx}x{ny}x{nz} out of range: n{axis} = {n}, "
                f"each of nx, ny, nz must be in 2..{max_dim}"
            )
    return dims


def _parse_dims(text: str, spec: str) -> Dims:
    parts = [p.strip() for p in text.split(",")]
    if len(parts) not in (1, 3) or not all(re.fullmatch(r"\d+", p) for p in parts):
        raise UserError(
            f"bad built-in volume spec {spec!r}: give NAME:N or NAME:NX,NY,NZ "
            f"with positive integers, e.g. sphere:64 or sphere:64,48,32"
        )
    n = [int(p) for p in parts]
    return (n[0], n[0], n[0]) if len(n) == 1 else (n[0], n[1], n[2])


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
        dims = _parse_dims(dims_text, spec)
    _check_dims(dims, max_dim, spec)
    _check_bits(voxel_bits)
    _check_memory(dims, spec)
    field = BUILTINS[key][0](*dims)
    return quantise(field, voxel_bits)


BUILTIN_BYTES_PER_VOXEL = 32     # peak while generating (float fields and temporaries), measured ~27


def _physical_memory() -> int | None:
    try:
        return os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return None


def _check_memory(dims: Dims, spec: str) -> None:
    """A built-in is generated in memory: refuse a size this machine cannot hold."""
    need = int(np.prod(dims, dtype=np.int64)) * BUILTIN_BYTES_PER_VOXEL
    have = _physical_memory()
    if have is not None and need > 0.75 * have:
        side = int((0.75 * have / BUILTIN_BYTES_PER_VOXEL) ** (1 / 3))
        raise UserError(f"built-in {spec} needs about {need / 2**30:.0f} GiB of memory to generate, this "
                        f"machine has {have / 2**30:.0f} GiB: choose at most about {side}^3 voxels")


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
    nx, ny, nz = _check_dims(dims, max_dim, path)  # type: ignore[misc]
    expected = nx * ny * nz * dtype.itemsize
    actual = os.path.getsize(path)
    if actual != expected:
        kind = "truncated" if actual < expected else "too large"
        raise UserError(
            f"raw file {path} is {kind}: {actual} bytes, but {nx}x{ny}x{nz} {dtype.name} "
            f"needs exactly {expected} bytes"
        )
    data = np.fromfile(path, dtype=dtype, count=nx * ny * nz)
    return data.reshape(nz, ny, nx)  # x varies fastest in the file


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
        data, header = nrrd.read(path, index_order="C")
    except KeyError as e:        # pynrrd's table of types
        raise UserError(f"cannot read NRRD file {path}: unknown NRRD type {e}") from None
    except Exception as e:       # corrupt payloads raise many kinds (zlib, EOF, value errors)
        raise UserError(f"cannot read NRRD file {path}: {type(e).__name__}: {e}") from None
    data = _spatial_3d(np.asarray(data), path, t_axis=0)
    affine = _nrrd_ras_affine(header)
    return data if affine is None else to_ras(data, affine)


# NRRD "space" names -> the sign that turns each of its axes into RAS
_NRRD_SPACES = {
    "right-anterior-superior": (1, 1, 1), "ras": (1, 1, 1),
    "left-anterior-superior": (-1, 1, 1), "las": (-1, 1, 1),
    "left-posterior-superior": (-1, -1, 1), "lps": (-1, -1, 1),
}


def _nrrd_ras_affine(header: dict) -> np.ndarray | None:
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
    return np.array(rows).T * np.array(_NRRD_SPACES[space], dtype=np.float64)[:, None]


def to_ras(vol_zyx: np.ndarray, directions: np.ndarray) -> np.ndarray:
    """Reorient vol[z, y, x] whose file axes x, y, z point along the columns of the 3 x 3
    RAS direction matrix so that x runs to the right, y to the front (anterior) and z up
    (superior): the nearest axis permutation and flips, no resampling."""
    from nibabel.orientations import apply_orientation, io_orientation

    affine = np.eye(4)
    affine[:3, :3] = directions
    xyz = apply_orientation(vol_zyx.transpose(2, 1, 0), io_orientation(affine))
    return np.ascontiguousarray(xyz.transpose(2, 1, 0))


def _load_nifti(path: str) -> np.ndarray:
    import nibabel as nib

    try:
        img = nib.load(path)
        if len(img.shape) >= 3:
            img = nib.as_closest_canonical(img)   # RAS: x right, y anterior, z superior
        data = np.asarray(img.dataobj)  # [x, y, z(, t)]; scl_slope applied if set
    except Exception as e:  # nibabel raises many kinds for corrupt files
        raise UserError(f"cannot read NIfTI file {path}: {e}") from None
    data = _spatial_3d(data, path, t_axis=3)
    return data.transpose(2, 1, 0)  # -> [z, y, x]


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
    if not os.path.isfile(path):
        raise UserError(f"volume file not found: {path}")
    _check_bits(voxel_bits)
    if kind == "raw":
        data = _load_raw(path, raw_dims, raw_dtype, max_dim)
    else:
        data = _load_nrrd(path) if kind == "nrrd" else _load_nifti(path)
        nz, ny, nx = data.shape
        _check_dims((nx, ny, nz), max_dim, path)
    if data.dtype.kind in "uif" and data.dtype.byteorder not in ("=", "|"):
        data = data.astype(data.dtype.newbyteorder("="))
    return to_voxels(data, voxel_bits)


def _load_dicom(folder: str, voxel_bits: int, max_dim: int) -> np.ndarray:
    """A folder of DICOM slices of one series (cube4.dicom)."""
    from .dicom import load_series

    _check_bits(voxel_bits)
    data = load_series(folder)
    nz, ny, nx = data.shape
    _check_dims((nx, ny, nz), max_dim, folder)
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

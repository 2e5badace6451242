"""Built-in test volumes (phantoms), generated as voxels.

A volume is a C-contiguous ``numpy.uint16`` array indexed ``vol[z, y, x]`` (x varies
fastest in memory), holding unsigned voxels in ``0 .. 2**voxel_bits - 1``. Its
dimensions are reported as ``(nx, ny, nz)``.

``PHANTOMS`` names the generators (a solid sphere, the Marschner-Lobb signal, the 3-D
Shepp-Logan head, ...): each makes a float field in [0, 1] of given dimensions, which
``quantise`` turns into voxels. The application adds the built-ins made from real MRI
data and volume files (``cube4.app.volumes.load_volume``).
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Callable

import numpy as np

from .errors import UserError

Dims = tuple[int, int, int]

# --------------------------------------------------------------------------------------
# Quantisation
# --------------------------------------------------------------------------------------


def check_bits(voxel_bits: int) -> int:
    if not isinstance(voxel_bits, (int, np.integer)) or not 4 <= voxel_bits <= 16:
        raise UserError(f"voxel_bits must be an integer in 4..16, got {voxel_bits!r}")
    return (1 << int(voxel_bits)) - 1


def quantise(field: np.ndarray, voxel_bits: int = 8) -> np.ndarray:
    """Map a float field in [0, 1] to voxels: floor(clip(f, 0, 1) * (2^V - 1) + 0.5)."""
    vmax = check_bits(voxel_bits)
    f = np.clip(np.asarray(field, dtype=np.float64), 0.0, 1.0)
    return np.ascontiguousarray(np.floor(f * vmax + 0.5).astype(np.uint16))


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


PHANTOMS: dict[str, tuple[Callable[[int, int, int], np.ndarray], str]] = {
    "sphere": (gen_sphere, "solid sphere, radius 0.375*min(n), antialiased edge"),
    "ml": (gen_ml, "Marschner-Lobb test signal (f_M = 6, alpha = 0.25)"),
    "head": (gen_head, "3-D Shepp-Logan head phantom, modified contrast"),
    "cube": (gen_cube, "hard-edged cube over the middle half"),
    "shells": (gen_shells, "nested spherical shells of densities 0.25..1"),
    "noise": (gen_noise, "reproducible uniform random voxels"),
    "constant": (gen_constant, "all 0.5 (zero gradients)"),
}


# --------------------------------------------------------------------------------------
# Dimensions and memory
# --------------------------------------------------------------------------------------


def check_dims(dims: Dims, max_dim: int, what: str) -> Dims:
    for axis, n in zip("xyz", dims):
        if not 2 <= n <= max_dim:
            nx, ny, nz = dims
            raise UserError(
                f"{what}: dimensions {nx}x{ny}x{nz} out of range: n{axis} = {n}, "
                f"each of nx, ny, nz must be in 2..{max_dim}"
            )
    return dims


def parse_dims(text: str, spec: str) -> Dims:
    parts = [p.strip() for p in text.split(",")]
    if len(parts) not in (1, 3) or not all(re.fullmatch(r"\d+", p) for p in parts):
        raise UserError(
            f"bad built-in volume spec {spec!r}: give NAME:N or NAME:NX,NY,NZ "
            f"with positive integers, e.g. sphere:64 or sphere:64,48,32"
        )
    n = [int(p) for p in parts]
    return (n[0], n[0], n[0]) if len(n) == 1 else (n[0], n[1], n[2])


BUILTIN_BYTES_PER_VOXEL = 32     # peak while generating (float fields and temporaries), measured ~27


def _physical_memory() -> int | None:
    try:
        return os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return None


def _status_bytes(field: str) -> int:
    """A /proc/self/status size (VmSize, VmData) in bytes; 0 where unknown."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith(field + ":"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return 0


def _cgroup_room() -> int | None:
    """Bytes the process's cgroup (v2 memory.max, v1 memory.limit_in_bytes) has left."""
    for limit, usage in (("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current"),
                         ("/sys/fs/cgroup/memory/memory.limit_in_bytes", "/sys/fs/cgroup/memory/memory.usage_in_bytes")):
        try:
            with open(limit) as f:
                text = f.read().strip()
            if text == "max":
                return None
            with open(usage) as f:
                used = int(f.read().strip())
            cap = int(text)
            return max(0, cap - used) if cap < 1 << 60 else None
        except (OSError, ValueError):
            continue
    return None


def memory_room() -> tuple[int | None, str]:
    """The memory this process may still take, and what limits it: three quarters of the
    machine's memory, the address-space and data limits the process runs under
    (ulimit -v, -d) less what it uses, the cgroup's limit less its usage; the smallest."""
    import resource

    rooms: list[tuple[int, str]] = []
    phys = _physical_memory()
    if phys is not None:
        rooms.append((int(0.75 * phys), "this machine has"))
    for lim, field, what in ((resource.RLIMIT_AS, "VmSize", "the address-space limit leaves"),
                             (resource.RLIMIT_DATA, "VmData", "the data-size limit leaves")):
        soft = resource.getrlimit(lim)[0]
        if soft != resource.RLIM_INFINITY:
            rooms.append((max(0, soft - _status_bytes(field)), what))
    cg = _cgroup_room()
    if cg is not None:
        rooms.append((cg, "the cgroup's memory limit leaves"))
    if not rooms:
        return None, ""
    return min(rooms)


def check_memory(dims: Dims, spec: str, bytes_per_voxel: int = BUILTIN_BYTES_PER_VOXEL,
                 doing: str = "to generate", what: str = "built-in") -> None:
    """A volume is generated (or loaded) in memory: refuse a size this process cannot hold
    (under the limits it runs under, not only the machine's memory)."""
    need = math.prod(max(0, int(n)) for n in dims) * bytes_per_voxel
    have, limit = memory_room()
    if have is not None and need > have:
        side = int((have / bytes_per_voxel) ** (1 / 3))
        raise UserError(f"{what} {spec} needs about {need / 2**30:.1f} GiB of memory {doing}, {limit} "
                        f"{have / 2**30:.1f} GiB: choose at most about {side}^3 voxels")

"""View geometry: traversal frame, quantised slopes, base plane and the warp.

Conventions (docs/numerics.md, "Traversal frame"):

* A volume is an array ``vol[z, y, x]``; dims are reported as (nx, ny, nz).
* The view direction ``d`` is the direction rays travel, in volume axes (x, y, z).
* The major axis k is the axis of largest |d| (ties: z before y before x).  The minor
  axes are the other two in x, y, z order: i (the beam axis, the one the pipelines
  span) and j (the beam index).  Each axis whose component of d is negative is
  traversed backwards, so that in the traversal frame rays go towards +i, +j, +k with
  slopes 0 <= sx, sy <= 1 per slice.
* Slopes are quantised to VIEW_X = round(sx * 2^W), VIEW_Y = round(sy * 2^W), in
  [0, 2^W]; the hardware renders the quantised direction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from .errors import UserError
from .values import shown, vector

AXIS_NAMES = "xyz"
ARRAY_AXIS = {0: 2, 1: 1, 2: 0}  # volume axis (x=0, y=1, z=2) -> numpy axis of vol[z, y, x]


def normalize_direction(d, what: str = "direction") -> np.ndarray:
    """Validate a view or light direction: three finite numbers, not all zero."""
    if isinstance(d, (str, bytes)) or not hasattr(d, "__len__"):
        raise UserError(f"{what} must be three numbers, got {shown(d)}")
    if len(d) != 3:
        raise UserError(f"{what} must have three components, got {len(d)}")
    v = np.asarray(vector(list(d), what), dtype=np.float64)
    big = float(np.max(np.abs(v)))
    if big == 0.0:
        raise UserError(f"{what} {list(d)} is zero: a view needs a non-zero vector")
    v = v / big                  # first to at most 1: huge or tiny components neither overflow nor vanish
    return v / float(np.linalg.norm(v))


def direction_from_angles(azimuth_deg: float, elevation_deg: float) -> np.ndarray:
    """Camera at azimuth (about +z, from +x towards +y) and elevation (above the x-y
    plane) looking at the volume centre: the returned vector is the ray direction."""
    az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
    eye = np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
    return -eye


def up_from_angles(azimuth_deg: float, elevation_deg: float) -> np.ndarray:
    """The picture's up for a camera at (azimuth, elevation): the direction in which the
    eye moves when the elevation grows (north on the sphere of views). It is +z projected
    on the image plane wherever that is defined, and it turns continuously through the
    poles (looking straight down at azimuth A, the top of the picture points away from
    azimuth A)."""
    az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
    return np.array([-math.sin(el) * math.cos(az), -math.sin(el) * math.sin(az), math.cos(el)])


POLE_Z = 0.99     # |d_z| from which +z is too close to the view direction to be the up


def default_up(direction) -> np.ndarray:
    """+z, except near the poles (|d_z| >= POLE_Z), where it is up_from_angles of the
    direction's own angles: the same picture direction as +z's projection, so the rule is
    continuous (at the exact pole, azimuth 0 is assumed: the top points to -x)."""
    d = normalize_direction(direction)
    if abs(d[2]) < POLE_Z:
        return np.array([0.0, 0.0, 1.0])
    return up_from_angles(*angles_from_direction(d))


def angles_from_direction(direction) -> tuple[float, float]:
    """Inverse of direction_from_angles: (azimuth, elevation) in degrees."""
    eye = -np.asarray(direction, dtype=np.float64)
    eye = eye / np.linalg.norm(eye)
    el = math.degrees(math.asin(max(-1.0, min(1.0, float(eye[2])))))
    az = math.degrees(math.atan2(float(eye[1]), float(eye[0])))
    return az, el


@dataclass(frozen=True)
class Traversal:
    """How the hardware walks the volume for one view, and the base-plane geometry."""

    dims: tuple[int, int, int]  # (nx, ny, nz)
    direction: tuple[float, float, float]  # unit view direction, volume axes
    weight_bits: int
    supersample: int
    major: int  # volume axis used as k
    axis_i: int  # volume axis used as i (beam axis)
    axis_j: int  # volume axis used as j
    flip: tuple[bool, bool, bool]  # per volume axis (x, y, z): traversed backwards
    view_x: int  # VIEW_X in [0, 2^W]
    view_y: int  # VIEW_Y in [0, 2^W]
    # the template's starting phase at sample slice m = 0, in [0, 2^(W+g)) (PH0_X, PH0_Y):
    # 0 for a whole volume; a brick or a sub-pixel pass starts elsewhere
    phase_x: int = 0
    phase_y: int = 0
    # volume coordinates of the traversed box's voxel (0, 0, 0): a crop box or a brick
    # is traversed as a volume of its own, placed here in the whole volume
    origin: tuple[int, int, int] = (0, 0, 0)
    # which faces of the traversed box are the volume's (cube4.pathlen FACES bits: I0, I1,
    # J0, J1, K0, K1 of the traversal frame from bit 0): all six for a whole volume or a
    # crop box; an empty-space box or a brick has interior faces
    faces: int = 0b111111

    # --- sizes in the traversal frame ---
    @property
    def ni(self) -> int:
        return self.dims[self.axis_i]

    @property
    def nj(self) -> int:
        return self.dims[self.axis_j]

    @property
    def nk(self) -> int:
        return self.dims[self.major]

    @property
    def guard_bits(self) -> int:
        return self.supersample.bit_length() - 1

    @property
    def phase_bits(self) -> int:
        return self.weight_bits + self.guard_bits

    @property
    def num_sample_slices(self) -> int:
        """M = (nk - 1) * S + 1 sample slices, at k = m / S."""
        return (self.nk - 1) * self.supersample + 1

    # --- per-sample-slice template (vectorised over m) ---
    def steps(self, m):
        """Accumulated discrete steps (stepx(m), stepy(m)) = floor((PH0 + m * VIEW) / 2^(W+g))."""
        m = np.asarray(m, dtype=np.int64)
        return ((self.phase_x + m * self.view_x) >> self.phase_bits,
                (self.phase_y + m * self.view_y) >> self.phase_bits)

    def weights(self, m):
        """Resampling weights (wx, wy, wz) of sample slice m, each Q0.W in [0, 2^W-1]."""
        m = np.asarray(m, dtype=np.int64)
        mask = (1 << self.phase_bits) - 1
        g = self.guard_bits
        wx = ((self.phase_x + m * self.view_x) & mask) >> g
        wy = ((self.phase_y + m * self.view_y) & mask) >> g
        wz = (m & (self.supersample - 1)) << (self.weight_bits - g)
        return wx, wy, wz

    @property
    def max_steps(self) -> tuple[int, int]:
        sx, sy = self.steps(self.num_sample_slices - 1)
        return int(sx), int(sy)

    @property
    def baseplane_shape(self) -> tuple[int, int]:
        """(rows, cols) = (nj + stepy_max, ni + stepx_max)."""
        sx, sy = self.max_steps
        return self.nj + sy, self.ni + sx

    # --- distances ---
    @property
    def slope(self) -> tuple[float, float]:
        """Quantised slopes per voxel slice, as the hardware uses them."""
        s = float(1 << self.weight_bits)
        return self.view_x / s, self.view_y / s

    @property
    def sample_distance(self) -> float:
        """Distance between consecutive samples of a ray, in voxels: sqrt(1+sx^2+sy^2)/S."""
        sx, sy = self.slope
        return math.sqrt(1.0 + sx * sx + sy * sy) / self.supersample

    # --- frames ---
    def to_traversal(self, vol: np.ndarray) -> np.ndarray:
        """A view (no copy) of vol[z, y, x] as t[k, j, i] in the traversal frame."""
        t = np.transpose(vol, (ARRAY_AXIS[self.major], ARRAY_AXIS[self.axis_j], ARRAY_AXIS[self.axis_i]))
        flips = []
        for pos, ax in enumerate((self.major, self.axis_j, self.axis_i)):
            if self.flip[ax]:
                flips.append(pos)
        return np.flip(t, axis=flips) if flips else t

    def vector_to_traversal(self, v) -> np.ndarray:
        """A direction (x, y, z) expressed in the traversal frame (i, j, k)."""
        v = np.asarray(v, dtype=np.float64)
        out = []
        for ax in (self.axis_i, self.axis_j, self.major):
            out.append(-v[..., ax] if self.flip[ax] else v[..., ax])
        return np.stack(out, axis=-1)

    def traversal_to_volume_points(self, ti, tj, tk) -> np.ndarray:
        """Traversal-frame coordinates -> volume coordinates (x, y, z) (float arrays),
        in the whole volume (the traversed box placed at ``origin``)."""
        pts = [None, None, None]
        for coord, ax in ((ti, self.axis_i), (tj, self.axis_j), (tk, self.major)):
            coord = np.asarray(coord, dtype=np.float64)
            pts[ax] = ((self.dims[ax] - 1) - coord if self.flip[ax] else coord) + self.origin[ax]
        return np.stack(np.broadcast_arrays(*pts), axis=-1)

    def baseplane_to_volume(self, bx, by) -> np.ndarray:
        """Base-plane pixel -> the point of its (quantised) ray at mid depth."""
        return self.ray_point(bx, by, (self.nk - 1) / 2.0)

    def ray_point(self, bx, by, k) -> np.ndarray:
        """Base-plane pixel -> the point of its (quantised) ray in voxel slice k (a sample
        slice m lies at k = m / S), volume coordinates (..., 3)."""
        sxm, sym = self.max_steps
        sx, sy = self.slope
        ph = float(1 << self.phase_bits)
        u = np.asarray(bx, dtype=np.float64) - sxm + self.phase_x / ph
        v = np.asarray(by, dtype=np.float64) - sym + self.phase_y / ph
        k = np.broadcast_to(np.asarray(k, dtype=np.float64), np.shape(u))
        return self.traversal_to_volume_points(u + sx * k, v + sy * k, k)


def make_traversal(dims, direction, weight_bits: int = 8, supersample: int = 1,
                   phase=(0, 0), origin=(0, 0, 0)) -> Traversal:
    """Choose major axis, signs and quantised slopes for a view direction. ``phase`` is
    the template's starting phase (PH0_X, PH0_Y) in [0, 2^(W+g)); ``origin`` places the
    traversed box (dims) in the whole volume (a crop box or a brick)."""
    d = normalize_direction(direction)
    a = np.abs(d)
    major = 2 if a[2] >= a[0] and a[2] >= a[1] else (1 if a[1] >= a[0] else 0)
    minors = [ax for ax in (0, 1, 2) if ax != major]
    axis_i, axis_j = minors
    flip = tuple(bool(d[ax] < 0) for ax in range(3))
    one = 1 << weight_bits
    vx = min(one, int(math.floor(a[axis_i] / a[major] * one + 0.5)))
    vy = min(one, int(math.floor(a[axis_j] / a[major] * one + 0.5)))
    nx, ny, nz = (int(n) for n in dims)
    return Traversal(
        dims=(nx, ny, nz),
        direction=tuple(float(c) for c in d),
        weight_bits=weight_bits,
        supersample=supersample,
        major=major,
        axis_i=axis_i,
        axis_j=axis_j,
        flip=flip,
        view_x=vx,
        view_y=vy,
        phase_x=_phase(phase[0], weight_bits, supersample),
        phase_y=_phase(phase[1], weight_bits, supersample),
        origin=tuple(int(c) for c in origin),
    )


def sub_faces(faces: int, start, sub_dims, dims) -> int:
    """FACES of a box inside a traversal (the traversal's own FACES, its box start
    (i, j, k) and sizes (ni, nj, nk), and the traversal's sizes): a face of the box is the
    volume's when it lies on a face of the traversal that is."""
    out = 0
    for r in range(3):
        if start[r] == 0:
            out |= faces & (1 << (2 * r))
        if start[r] + sub_dims[r] == dims[r]:
            out |= faces & (1 << (2 * r + 1))
    return out


def sub_traversal(trav: Traversal, s0, s1) -> tuple[Traversal, tuple[int, int], tuple[int, int, int]]:
    """The traversal of the box [s0, s1) (volume axes x, y, z, half-open, within the
    traversed box of ``trav``) whose samples are exactly ``trav``'s samples there: the
    same view registers, and the template's starting phase that ``trav`` has at the
    box's first sample slice. Returns (traversal, (row, col) of its base-plane pixel
    (0, 0) in ``trav``'s base plane, (i, j, k) of its traversal-frame voxel (0, 0, 0) in
    ``trav``'s frame). A brick (numerics.md §14) and the empty-space box (§15) are such
    boxes."""
    start = []
    for ax in (trav.axis_i, trav.axis_j, trav.major):
        start.append(trav.dims[ax] - s1[ax] if trav.flip[ax] else s0[ax])
    i0, j0, k0 = start
    S, pb = trav.supersample, trav.phase_bits
    px, py = trav.phase_x + k0 * S * trav.view_x, trav.phase_y + k0 * S * trav.view_y
    mask = (1 << pb) - 1
    dims = tuple(int(b) - int(a) for a, b in zip(s0, s1))
    origin = tuple(o + int(s) for o, s in zip(trav.origin, s0))
    # the same view registers, exactly (replace, not a re-derivation from the direction)
    sub = replace(trav, dims=dims, origin=origin, phase_x=px & mask, phase_y=py & mask)
    sub = replace(sub, faces=sub_faces(trav.faces, (i0, j0, k0), (sub.ni, sub.nj, sub.nk),
                                       (trav.ni, trav.nj, trav.nk)))
    sxm, sym = trav.max_steps
    bsx, bsy = sub.max_steps
    offset = (j0 - (py >> pb) + sym - bsy, i0 - (px >> pb) + sxm - bsx)
    return sub, offset, (i0, j0, k0)


def _phase(value, weight_bits: int, supersample: int) -> int:
    top = 1 << (weight_bits + supersample.bit_length() - 1)
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not 0 <= int(value) < top:
        raise UserError(f"a template phase must be an integer in 0..{top - 1}, got {value!r}")
    return int(value)


@dataclass(frozen=True)
class Camera:
    """The final image plane: orthographic, centred on the volume centre."""

    dims: tuple[int, int, int]
    direction: np.ndarray  # unit, volume axes
    right: np.ndarray
    up: np.ndarray
    width: int
    height: int
    pixel: float  # voxels per image pixel
    # the point the image centres on, in the volume's coordinates; None: the centre of
    # dims (a preview level's camera puts the whole volume's centre here: level_camera)
    at: tuple[float, float, float] | None = None

    @property
    def centre(self) -> np.ndarray:
        if self.at is not None:
            return np.asarray(self.at, dtype=np.float64)
        return (np.asarray(self.dims, dtype=np.float64) - 1.0) / 2.0

    def project(self, pts: np.ndarray) -> np.ndarray:
        """Volume points (..., 3) -> continuous pixel coordinates (col, row), pixel
        centres at integers."""
        rel = pts - self.centre
        col = rel @ self.right / self.pixel + (self.width - 1) / 2.0
        row = -(rel @ self.up) / self.pixel + (self.height - 1) / 2.0
        return np.stack([col, row], axis=-1)

    def ray_origins(self) -> tuple[np.ndarray, np.ndarray]:
        """For every pixel (row-major), a point on its ray in the plane through the
        volume centre; shape (H*W, 3)."""
        cols = (np.arange(self.width) - (self.width - 1) / 2.0) * self.pixel
        rows = (np.arange(self.height) - (self.height - 1) / 2.0) * self.pixel
        cc, rr = np.meshgrid(cols, rows)
        pts = self.centre + cc[..., None] * self.right - rr[..., None] * self.up
        return pts.reshape(-1, 3), self.direction


def make_camera(dims, direction, width: int, height: int, up=None) -> Camera:
    d = normalize_direction(direction)
    if up is None:
        up = default_up(d)
    u = normalize_direction(up)
    right = np.cross(d, u)
    if np.linalg.norm(right) < 1e-6:
        raise UserError("view 'up' vector is parallel to the view direction")
    right /= np.linalg.norm(right)
    true_up = np.cross(right, d)
    diag = float(np.linalg.norm(np.asarray(dims, dtype=np.float64)))
    return Camera(
        dims=tuple(int(n) for n in dims),
        direction=d,
        right=right,
        up=true_up,
        width=int(width),
        height=int(height),
        pixel=diag / min(width, height),
    )


def level_camera(cam: Camera, level_dims, factor: int) -> Camera:
    """The camera ``cam`` of the whole volume in the coordinates of a preview level whose
    voxel u stands for the whole volume's voxels f·u … f·u + f − 1 (its centre at
    f·u + (f − 1)/2): the same picture of the same place, at 1/f of the voxels per pixel."""
    f = float(factor)
    at = tuple((float(c) - (f - 1.0) / 2.0) / f for c in cam.centre)
    return replace(cam, dims=tuple(int(n) for n in level_dims), pixel=cam.pixel / f, at=at)


def warp_matrix(trav: Traversal, cam: Camera) -> np.ndarray:
    """3x3 affine matrix taking base-plane pixel (bx, by, 1) to image pixel (col, row, 1),
    both with pixel centres at integer coordinates."""
    pts = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    img = cam.project(trav.baseplane_to_volume(pts[:, 0], pts[:, 1]))
    o, ex, ey = img[0], img[1] - img[0], img[2] - img[0]
    return np.array([[ex[0], ey[0], o[0]], [ex[1], ey[1], o[1]], [0.0, 0.0, 1.0]])

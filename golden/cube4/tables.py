"""Host-side tables written into the hardware: classification LUT and reflectance map.

Formats (docs/numerics.md): LUT entry = R, G, B in Q0.8 and alpha in Q0.ALPHA_W, with
alpha already corrected for the view's sample distance; reflectance-map entry = diffuse
factor D and specular term P, each Q2.8 (10 bits, 0 <= v < 4).
"""

from __future__ import annotations

import numpy as np

from .labels import label_lut, label_tf
from .config import COLOR_W, RMAP_FRAC, RMAP_W, Cube4Config
from .scene import Scene
from .view import Traversal


def quantize_unit(x, bits: int) -> np.ndarray:
    """[0, 1] -> Q0.bits, round half up, saturating at 2^bits - 1."""
    q = np.floor(np.asarray(x, dtype=np.float64) * (1 << bits) + 0.5).astype(np.int64)
    return np.clip(q, 0, (1 << bits) - 1)


def correct_opacity(alpha, distance: float) -> np.ndarray:
    """Opacity for a sample spacing of `distance` voxels: 1 - (1 - a)^distance."""
    a = np.clip(np.asarray(alpha, dtype=np.float64), 0.0, 1.0)
    return 1.0 - np.power(1.0 - a, distance)


def classification_lut(scene: Scene, cfg: Cube4Config, distance: float) -> np.ndarray:
    """(2^VOXEL_W, 4) int64: R, G, B (Q0.8), A (Q0.ALPHA_W) per voxel value; a scene with
    labels: (16 · 2^VOXEL_W, 4), label l's block its own transfer function (cube4.labels)."""
    n = 1 << cfg.voxel_bits
    x = np.arange(n) / (n - 1)

    def table(rgba: np.ndarray) -> np.ndarray:
        lut = np.empty((n, 4), dtype=np.int64)
        lut[:, :3] = quantize_unit(rgba[:, :3], COLOR_W)
        lut[:, 3] = quantize_unit(correct_opacity(rgba[:, 3], distance), cfg.alpha_bits)
        return lut

    if scene.labels is not None:
        return label_lut(lambda lb: table(label_tf(scene, lb, x)))
    return table(scene.tf(x))


def extremum_lut(scene: Scene, cfg: Cube4Config) -> np.ndarray:
    """The LUT for MIP and MinIP (numerics.md §13): the classification of a ray's
    extreme value is its pixel, so colour is premultiplied by opacity here,
    R = Q0.8(r * a), and opacity is not corrected for a sample distance."""
    n = 1 << cfg.voxel_bits
    rgba = scene.tf(np.arange(n) / (n - 1))
    a = np.clip(rgba[:, 3], 0.0, 1.0)
    lut = np.empty((n, 4), dtype=np.int64)
    lut[:, :3] = quantize_unit(rgba[:, :3] * a[:, None], COLOR_W)
    lut[:, 3] = quantize_unit(a, cfg.alpha_bits)
    return lut


def phong_terms(scene: Scene, normals, lights_dir, eye) -> tuple[np.ndarray, np.ndarray]:
    """Float Phong terms for unit surface normals (..., 3).

    D = ka + kd * sum_l I_l max(0, N.L_l);  P = ks * sum_l I_l max(0, N.H_l)^n,
    L_l = -light travel direction, H_l = normalise(L_l + V), V = towards the eye.
    lights_dir and eye are in the same frame as the normals.
    """
    normals = np.asarray(normals, dtype=np.float64)
    d = np.full(normals.shape[:-1], scene.ambient)
    p = np.zeros(normals.shape[:-1])
    for light, ldir in zip(scene.lights, lights_dir):
        to_light = -np.asarray(ldir, dtype=np.float64)
        h = to_light + eye
        hn = np.linalg.norm(h)
        h = h / hn if hn > 1e-12 else to_light
        d = d + scene.diffuse * light.intensity * np.maximum(0.0, normals @ to_light)
        if scene.specular > 0:
            p = p + scene.specular * light.intensity * np.power(np.maximum(0.0, normals @ h), scene.shininess)
    return d, p


def unshaded_terms(scene: Scene) -> tuple[float, float]:
    """Terms for a zero gradient (no normal): ambient plus full diffuse, no specular."""
    return scene.ambient + scene.diffuse * sum(lt.intensity for lt in scene.lights), 0.0


def rmap_cell_normals(res: int) -> np.ndarray:
    """Unit *gradient* directions at the centres of the 6 * res^2 cube-map cells, in
    table order (face, v, u); face = 2 * axis + (gradient component negative)."""
    c = -1.0 + (np.arange(res) + 0.5) * 2.0 / res
    vv, uu = np.meshgrid(c, c, indexing="ij")
    dirs = np.empty((6, res, res, 3))
    for face in range(6):
        axis, neg = face >> 1, face & 1
        b, cc = [ax for ax in range(3) if ax != axis]
        dirs[face, :, :, axis] = -1.0 if neg else 1.0
        dirs[face, :, :, b] = uu
        dirs[face, :, :, cc] = vv
    dirs /= np.linalg.norm(dirs, axis=-1, keepdims=True)
    return dirs.reshape(-1, 3)


def reflectance_map(scene: Scene, cfg: Cube4Config, trav: Traversal, volume_axes: bool = False) -> np.ndarray:
    """(6 * R^2 + 1, 2) int64 table of (D, P) in Q2.8, indexed by the quantised
    gradient direction in the traversal frame (GRA's gradient), or in the volume's axes
    x, y, z when ``volume_axes`` (voxel gradients, numerics.md §5b); the last entry is
    for G == 0."""
    grads = rmap_cell_normals(cfg.rmap_res)
    normals = -grads  # surface normal points away from denser material
    frame = (lambda v: np.asarray(v, dtype=np.float64)) if volume_axes else trav.vector_to_traversal
    lights = [frame(lt.direction) for lt in scene.lights]
    eye = -frame(np.asarray(trav.direction))
    d, p = phong_terms(scene, normals, lights, eye)
    d0, p0 = unshaded_terms(scene)
    table = np.empty((cfg.rmap_entries, 2), dtype=np.int64)
    top = (1 << RMAP_W) - 1
    table[:-1, 0] = np.clip(np.floor(d * (1 << RMAP_FRAC) + 0.5), 0, top)
    table[:-1, 1] = np.clip(np.floor(p * (1 << RMAP_FRAC) + 0.5), 0, top)
    table[-1] = [min(top, int(d0 * (1 << RMAP_FRAC) + 0.5)), min(top, int(p0 * (1 << RMAP_FRAC) + 0.5))]
    return table

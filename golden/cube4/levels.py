"""Preview levels: the volume at 1/2 and 1/4 of its resolution, for interaction
(docs/numerics.md §20, scene key ``[render] preview``, ``cube4 render --preview F``).

The host builds level F (F = 2 or 4) from the volume once: voxel u of the level is the
mean of the whole volume's F × F × F voxels F·u … F·u + F − 1 along every axis, rounded
half up (an integer of the same width); a block that reaches past the volume's high face
repeats the face's voxels (the level has ⌈n / F⌉ voxels per axis). A frame of the level
is an ordinary frame of a smaller volume: F³ times fewer voxels and about F³ times fewer
cycles. The picture is the same picture: the camera is the whole volume's, moved into the
level's coordinates (``view.level_camera``: level voxel u sits at F·u + (F − 1)/2), and
the transfer function's opacity is corrected for a sample distance F times as long, so a
ray through the same material reaches the same opacity. The truth a preview is measured
against is the whole volume's (the reference engine renders the volume itself).
"""

from __future__ import annotations

import numpy as np

from .errors import UserError

#: the preview factors a scene may ask for (1: the volume itself)
LEVELS = (1, 2, 4)


def level_volume(vol: np.ndarray, factor: int) -> np.ndarray:
    """vol[z, y, x] at 1/factor of its resolution: the mean of each factor³ block, rounded
    half up, the high faces repeated where a block reaches past them; same dtype."""
    if factor not in LEVELS:
        raise UserError(f"a preview level must be one of {', '.join(map(str, LEVELS))}, got {factor!r}")
    if factor == 1:
        return vol
    f = int(factor)
    pad = [(0, -n % f) for n in vol.shape]
    v = np.pad(vol.astype(np.int64), pad, mode="edge")
    nz, ny, nx = (n // f for n in v.shape)
    total = v.reshape(nz, f, ny, f, nx, f).sum(axis=(1, 3, 5))
    n = f ** 3
    return ((2 * total + n) // (2 * n)).astype(vol.dtype)


def level_dims(dims, factor: int) -> tuple[int, int, int]:
    """(nx, ny, nz) of the level of a volume of ``dims``."""
    return tuple(-(-int(n) // int(factor)) for n in dims)

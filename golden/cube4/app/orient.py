"""Volumes reoriented to RAS: x to the right, y anterior (to the front), z superior (up).

Files that say how their axes lie in the patient (the NIfTI affine, the NRRD ``space``
and ``space directions``, DICOM's orientation and positions) are turned by the nearest
axis permutation and flips (nibabel's orientation tools; no resampling).
"""

from __future__ import annotations

import numpy as np


def to_ras(vol_zyx: np.ndarray, directions: np.ndarray) -> np.ndarray:
    """Reorient vol[z, y, x] whose file axes x, y, z point along the columns of the 3 x 3
    RAS direction matrix so that x runs to the right, y to the front (anterior) and z up
    (superior): the nearest axis permutation and flips, no resampling."""
    from nibabel.orientations import apply_orientation, io_orientation

    affine = np.eye(4)
    affine[:3, :3] = directions
    xyz = apply_orientation(vol_zyx.transpose(2, 1, 0), io_orientation(affine))
    return np.ascontiguousarray(xyz.transpose(2, 1, 0))

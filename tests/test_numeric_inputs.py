"""User numbers at the edge of float64: a volume's extreme but finite values and huge or
tiny direction vectors work, or fail with one line; never a silent zero."""

from __future__ import annotations

import pytest


def test_extreme_finite_volume_values_rescale_without_overflow():
    import warnings

    import numpy as np

    from cube4.app.volumes import to_voxels

    with warnings.catch_warnings():
        warnings.simplefilter("error")      # no RuntimeWarning, no silent zeros
        v = to_voxels(np.array([-1.7e308, 0.0, 1.7e308]), 8)
    assert v.tolist() == [0, 128, 255]


@pytest.mark.parametrize("d, want", [((1e308, 1e308, 0.0), (0.70710678, 0.70710678, 0.0)),
                                     ((1e-320, 0.0, 0.0), (1.0, 0.0, 0.0))])
def test_huge_and_tiny_directions_are_directions(d, want):
    import numpy as np

    from cube4.view import normalize_direction

    assert np.allclose(normalize_direction(d), want)

"""The picture's up is continuous: an elevation sweep through the pole turns the picture
smoothly, at every azimuth (the old rule jumped by 90 degrees at elevation 81.9 at
azimuth 0, by 180 at azimuth 270)."""

from __future__ import annotations

import argparse

import numpy as np
import pytest

from cube4.app.cli import _views
from cube4.scene import load_scene
from cube4.view import make_camera


def _ups(az: float, elevations) -> list[np.ndarray]:
    args = argparse.Namespace(view=[f"{az},{el}" for el in elevations], orbit=None)
    scenes = _views(args, load_scene("default"))
    return [make_camera((32, 32, 32), sc.direction, 64, 64, sc.up).up for sc in scenes]


@pytest.mark.parametrize("az", [0.0, 45.0, 90.0, 270.0, -120.0])
def test_elevation_sweep_turns_the_picture_smoothly(az):
    els = np.round(np.arange(70.0, 90.0001, 0.1), 6)
    ups = _ups(az, els)
    steps = [np.degrees(np.arccos(np.clip(np.dot(a, b), -1.0, 1.0))) for a, b in zip(ups, ups[1:])]
    assert max(steps) < 0.5, f"the picture turns by {max(steps):.1f} degrees in one 0.1-degree step"


def test_far_from_the_pole_up_is_z_projected():
    (up,) = _ups(30.0, [20.0])
    assert up[2] > 0.9 and abs(np.dot(up, [0.0, 0.0, 1.0]) - np.cos(np.radians(20.0))) < 1e-9

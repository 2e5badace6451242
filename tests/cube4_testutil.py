"""Test helpers: small volumes and scenes built in code (no files needed)."""

from __future__ import annotations

import numpy as np

from cube4.scene import parse_scene


def sphere_volume(n: int, bits: int = 8) -> np.ndarray:
    """Antialiased solid sphere, radius 0.375 n, centred: f = clip(R - r + 0.5, 0, 1)."""
    z, y, x = np.ogrid[:n, :n, :n]
    c = (n - 1) / 2.0
    r = np.sqrt((x - c) ** 2 + (y - c) ** 2 + (z - c) ** 2)
    f = np.clip(0.375 * n - r + 0.5, 0.0, 1.0)
    return np.floor(f * ((1 << bits) - 1) + 0.5).astype(np.uint16)


def random_volume(shape, bits: int = 8, seed: int = 1) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return rng.integers(0, 1 << bits, size=shape).astype(np.uint16)


def make_scene(**kw):
    """A scene from keyword sections, e.g. make_scene(view={"direction": [1, 2, 3]})."""
    data = {"output": {"width": 96, "height": 96}}
    data.update(kw)
    return parse_scene(data)

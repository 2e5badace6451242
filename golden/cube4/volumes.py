"""The old import path of the volume loader, kept for its remaining callers (the
testbenches in tb/, cube4_reports.scenes): volume files and ``load_volume`` are
``cube4.app.volumes``, the generated phantoms the specification's ``cube4.phantoms``.
This module is part of the application (``cube4.APPLICATION``); new code imports those
two modules."""

from __future__ import annotations

from .app.volumes import BUILTINS, builtin_names, load_volume, to_voxels  # noqa: F401
from .phantoms import ML_ALPHA, ML_FM, ml_density, quantise, sphere_centre, sphere_radius  # noqa: F401

"""Cube-4 volume rendering: bit-exact golden model, float64 reference, tools.

The integer model in :mod:`cube4.model` is the specification the RTL matches bit for
bit; :mod:`cube4.reference` is the float64 truth that error is measured against. The
specification (the model, the reference, the host's tables and plans, the view, the
scenes, the phantoms) imports NumPy and the standard library only; the application
above it (volume and image files, the warp, the engines, the cluster, progress bars,
the command line) is :mod:`cube4.app`.
"""

__version__ = "0.1.0"

#: the modules of this package above the specification, which may use file-format, image,
#: cluster and progress libraries: the application (``cube4.app``). Every other module is
#: the specification: NumPy and the standard library only (tests/test_layers.py).
APPLICATION = ("cube4.app",)

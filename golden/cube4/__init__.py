"""Cube-4 volume rendering: bit-exact golden model, float64 reference, tools.

The integer model in :mod:`cube4.model` is the specification the RTL matches bit for
bit; :mod:`cube4.reference` is the float64 truth that error is measured against.
"""

__version__ = "0.1.0"

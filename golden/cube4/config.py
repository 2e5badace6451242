"""Hardware configuration: the Verilog parameters the golden model mirrors.

Every field here is a parameter of the RTL (``cube4_top``) with the same meaning and
range; ``docs/numerics.md`` gives the formats they control.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

from .errors import UserError

MAX_PIPELINES = 64
MAX_DIM = 2048

COLOR_W = 8  # colour channels of LUT and shaded samples: Q0.8 (fixed, not a parameter)
RMAP_FRAC = 8  # reflectance-map entries: Q2.8 (10 bits)
RMAP_W = 10


@dataclass(frozen=True)
class Cube4Config:
    """Parameters of one Cube-4 build.

    pipelines   p, number of pipelines = memory banks (1..64)
    voxel_bits  VOXEL_W, unsigned voxel width: 8 or 12 (any 4..16 accepted)
    weight_bits WEIGHT_W, resampling weights Q0.W and view slopes (4..12, paper: 8)
    alpha_bits  ALPHA_W, LUT opacity Q0.A (8..16)
    acc_bits    ACC_W, compositing accumulators Q0.F (8..24)
    rmap_bits   RMAP_BITS, reflectance map has 6 * 4^RMAP_BITS + 1 entries (2..6)
    supersample S, samples per voxel slice along the major axis: 1, 2, 4 or 8
    """

    pipelines: int = 8
    voxel_bits: int = 8
    weight_bits: int = 8
    alpha_bits: int = 12
    acc_bits: int = 16
    rmap_bits: int = 5
    supersample: int = 1

    def __post_init__(self) -> None:
        checks = [
            ("pipelines", self.pipelines, 1, MAX_PIPELINES),
            ("voxel_bits", self.voxel_bits, 4, 16),
            ("weight_bits", self.weight_bits, 4, 12),
            ("alpha_bits", self.alpha_bits, 8, 16),
            ("acc_bits", self.acc_bits, 8, 24),
            ("rmap_bits", self.rmap_bits, 2, 6),
        ]
        for name, val, lo, hi in checks:
            if not isinstance(val, int) or isinstance(val, bool) or not lo <= val <= hi:
                raise UserError(f"{name} must be an integer in {lo}..{hi}, got {val!r}")
        if self.supersample not in (1, 2, 4, 8):
            raise UserError(f"supersample must be 1, 2, 4 or 8, got {self.supersample!r}")

    @property
    def guard_bits(self) -> int:
        """log2(S): extra phase bits below the weight for sub-slice samples."""
        return self.supersample.bit_length() - 1

    @property
    def rmap_res(self) -> int:
        return 1 << self.rmap_bits

    @property
    def rmap_entries(self) -> int:
        return 6 * self.rmap_res * self.rmap_res + 1

    def as_dict(self) -> dict:
        return asdict(self)

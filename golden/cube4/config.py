"""Hardware configuration: the Verilog parameters the golden model mirrors.

Every field here is a parameter of the RTL (``cube4_top``) with the same meaning and
range; ``docs/numerics.md`` gives the formats they control.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

from .errors import UserError
from .modes import is_blend, is_extremum

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
    build       the hardware the build has, as BUILD_PARAMS -> 0 / 1 (SHADING,
                COMPOSITING, EXTREMUM, CLIP, VGRAD, PLW); None: the smallest build the scene needs
    """

    pipelines: int = 8
    voxel_bits: int = 8
    weight_bits: int = 8
    alpha_bits: int = 12
    acc_bits: int = 16
    rmap_bits: int = 5
    supersample: int = 1
    build: tuple[tuple[str, int], ...] | None = None

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
        if self.build is not None:
            check_build_params(dict(self.build))

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
        d = asdict(self)
        d["build"] = None if self.build is None else dict(self.build)
        return d


# ---------------------------------------------------------------- builds
#: cube4_top's parameters that remove hardware a scene does not need (docs/architecture.md)
BUILD_PARAMS = ("SHADING", "COMPOSITING", "EXTREMUM", "CLIP", "VGRAD", "PLW")
#: the full build: every unit of the paper and the path weights (VGRAD = 1 swaps GRA for
#: the voxel-gradient channels)
FULL_BUILD = {"SHADING": 1, "COMPOSITING": 1, "EXTREMUM": 1, "CLIP": 1, "VGRAD": 0, "PLW": 1}
_NEEDS = {"SHADING": "shading (gradients and the reflectance map)",
          "COMPOSITING": "the compositing datapath (composite, xray)",
          "EXTREMUM": "the comparators (mip, minip)",
          "CLIP": "the cut plane or window (cube4_clip)",
          "VGRAD": "voxel gradients (the memory's gradient channels)",
          "PLW": "path-length weights (the LUT's path-weight columns in COM)"}


def complete_build(partial: dict | None) -> dict:
    """A build from the parameters it names: the others as in the full build, but PLW
    (path weights need the compositing datapath) is 0 where COMPOSITING = 0 and PLW is
    not named."""
    build = {**FULL_BUILD, **(partial or {})}
    if "PLW" not in (partial or {}) and not build["COMPOSITING"]:
        build["PLW"] = 0
    return build


def check_build_params(build: dict) -> None:
    """A build's parameters: every one of BUILD_PARAMS, each 0 or 1, and a legal
    combination (the same checks stop cube4_top's elaboration)."""
    if set(build) != set(BUILD_PARAMS) or any(v not in (0, 1) for v in build.values()):
        raise UserError(f"a build sets each of {', '.join(BUILD_PARAMS)} to 0 or 1, got {build}")
    if not build["COMPOSITING"] and not build["EXTREMUM"]:
        raise UserError("a build needs COMPOSITING = 1 or EXTREMUM = 1 (no rendering mode otherwise)")
    if build["SHADING"] and not build["COMPOSITING"]:
        raise UserError("a build with SHADING = 1 needs COMPOSITING = 1 (only compositing is shaded)")
    if build["VGRAD"] and not build["SHADING"]:
        raise UserError("a build with VGRAD = 1 needs SHADING = 1 (voxel gradients only feed shading)")
    if build["PLW"] and not build["COMPOSITING"]:
        raise UserError("a build with PLW = 1 needs COMPOSITING = 1 (only the blending modes are path-weighted)")


def scene_build(scenes) -> dict:
    """The smallest build that renders every one of the scenes. Shaded scenes take their
    gradient from GRA (VGRAD = 0) or from the voxels (VGRAD = 1): one build has one."""
    b = {"SHADING": 0, "COMPOSITING": 0, "EXTREMUM": 0, "CLIP": 0, "VGRAD": 0, "PLW": 0}
    for sc in scenes:
        b["SHADING"] |= int(sc.shaded)
        b["COMPOSITING"] |= int(is_blend(sc.mode))
        b["EXTREMUM"] |= int(is_extremum(sc.mode))
        b["CLIP"] |= int(sc.cut is not None)
        b["VGRAD"] |= int(sc.voxel_gradients)
        b["PLW"] |= int(sc.path_weighted)
    _one_gradient_source(scenes)
    return b


def _one_gradient_source(scenes) -> None:
    kinds = {sc.gradient if sc.voxel_gradients else "gra" for sc in scenes if sc.shaded}
    if "gra" in kinds and len(kinds) > 1:
        raise UserError("one render cannot mix [render] gradient = gra with voxel gradients "
                        "(they need different builds): render them separately")
    if len(kinds) > 1:
        raise UserError(f"one render holds one voxel gradient in memory, got {', '.join(sorted(kinds))}: "
                        "render them separately")


def parse_build(text: str) -> dict | None:
    """--build: "scene" (None: the scene's smallest), "full", or NAME=0/1 pairs
    (e.g. SHADING=0,COMPOSITING=0,EXTREMUM=1,CLIP=0; names not given as in the full build:
    1, and VGRAD 0; PLW 0 without COMPOSITING, complete_build)."""
    t = text.strip()
    if t.lower() == "scene":
        return None
    if t.lower() == "full":
        return dict(FULL_BUILD)
    named = {}
    for part in t.split(","):
        name, _, val = part.partition("=")
        name = name.strip().upper()
        if name not in BUILD_PARAMS or val.strip() not in ("0", "1"):
            raise UserError(f"--build must be scene, full or NAME=0/1 pairs with NAME in "
                            f"{', '.join(BUILD_PARAMS)}, got {text!r}")
        named[name] = int(val)
    build = complete_build(named)
    check_build_params(build)
    return build


def resolve_build(cfg: "Cube4Config", scenes) -> dict:
    """The build a render uses: cfg.build if given (checked against every scene: one line
    naming what is missing), else the scenes' smallest."""
    if cfg.build is None:
        return scene_build(scenes)
    build = dict(cfg.build)
    need = scene_build(scenes)
    if need["SHADING"] and build["VGRAD"] != need["VGRAD"]:
        name = next(sc.name for sc in scenes if sc.shaded)
        src = "voxel gradients (VGRAD = 1)" if need["VGRAD"] else "GRA (VGRAD = 0)"
        raise UserError(f"scene {name} takes its gradient from {src}, the build has VGRAD = {build['VGRAD']}")
    for k in BUILD_PARAMS:
        if need[k] and not build[k]:
            name = next(sc.name for sc in scenes if scene_build([sc])[k])
            raise UserError(f"scene {name} needs {_NEEDS[k]}, which the build leaves out ({k} = 0)")
    return build

"""Hardware configuration: the Verilog parameters the golden model mirrors.

Every field here is a parameter of the RTL (``cube4_top``) with the same meaning and
range; ``docs/numerics.md`` gives the formats they control.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

from .builds import BUILD_PARAMS, BY_NAME, FULL_BUILD, check_build, complete_build, parse_options
from .errors import UserError
from .modes import is_blend, is_extremum
from .values import shown

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
    build       the hardware the build has: every option of builds.OPTIONS -> 0 / 1;
                None: the smallest build the scene needs
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
                raise UserError(f"{name} must be an integer in {lo}..{hi}, got {shown(val)}")
        if self.supersample not in (1, 2, 4, 8):
            raise UserError(f"supersample must be 1, 2, 4 or 8, got {shown(self.supersample)}")
        if self.build is not None:
            check_build(dict(self.build), self.widths())

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

    def widths(self) -> dict[str, int]:
        """The word widths as cube4_top's parameters (VOXEL_W .. MAX_SS_LOG2); a default
        Cube4Config gives cube4_top's defaults (tests/test_build_definition.py checks it)."""
        return {"VOXEL_W": self.voxel_bits, "WEIGHT_W": self.weight_bits, "ALPHA_W": self.alpha_bits,
                "ACC_W": self.acc_bits, "RMAP_BITS": self.rmap_bits, "MAX_SS_LOG2": self.guard_bits}

    def as_dict(self) -> dict:
        d = asdict(self)
        d["build"] = None if self.build is None else dict(self.build)
        return d


# ---------------------------------------------------------------- builds
# The build options, their defaults and legal combinations are defined once, in builds.py;
# here: which build a scene needs.


def scene_build(scenes) -> dict:
    """The smallest build that renders every one of the scenes. Shaded scenes take their
    gradient from GRA (VGRAD = 0) or from the voxels (VGRAD = 1): one build has one."""
    b = dict.fromkeys(BUILD_PARAMS, 0)
    for sc in scenes:
        b["SHADING"] |= int(sc.shaded)
        b["COMPOSITING"] |= int(is_blend(sc.mode))
        b["EXTREMUM"] |= int(is_extremum(sc.mode))
        b["CLIP"] |= int(sc.cut is not None or sc.slab is not None or sc.crop_regions is not None)
        b["SLAB"] |= int(sc.slab is not None)
        b["ZOUT"] |= int(sc.depth_threshold is not None)
        # depth in: COM's stop table; the beat schedule ends each ray at the geometry's stop
        # through the ray table instead (BeatSchedule.limit_stop), with no unit of its own
        b["ZIN"] |= int(sc.geometry is not None and sc.schedule != "beats")
        b["GMOD"] |= int(sc.gmod is not None)
        b["LABELS"] |= int(sc.labels is not None)
        b["VGRAD"] |= int(sc.voxel_gradients)
        b["PLW"] |= int(sc.path_weighted)
        b["RECTS"] |= int(sc.schedule == "rects")
        b["BEATS"] |= int(sc.schedule == "beats")
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
    """--build: "scene" (None: the scene's smallest), "full", or NAME=0/1 pairs (e.g.
    SHADING=0,COMPOSITING=0,EXTREMUM=1,CLIP=0); the options not named as in
    builds.complete_build."""
    t = text.strip()
    if t.lower() == "scene":
        return None
    if t.lower() == "full":
        return dict(FULL_BUILD)
    build = complete_build(parse_options(t, "--build takes scene, full or"))
    check_build(build)
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
            raise UserError(f"scene {name} needs {BY_NAME[k].adds}, which the build leaves out ({k} = 0)")
    return build

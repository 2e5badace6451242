"""The build definition: cube4_top's build options in one place.

A *build* is the set of 0/1 parameters of ``cube4_top`` that leave out hardware a scene
does not need (docs/architecture.md, "Builds"). This module is their single source:

* ``OPTIONS``: every option's Verilog name, its value in the full build (the Verilog
  default everywhere it is declared), the letter it has in build tags, what it adds and
  the RTL units it selects;
* ``RULES``: the legal combinations; ``cube4_top`` stops elaboration on the same ones;
* ``NAMED``: the builds the tests, reports and documents name.

Everything else derives from it: the golden model's checks (``config.py``), the RTL
engine's and the reports' parameter lists (``sim/``), the testbenches' builds.
``tests/test_build_definition.py`` fails when a Verilog file (rtl/, the harnesses)
declares an option with another default, when ``cube4_top`` accepts a combination the
rules refuse, or refuses one they accept.
"""

from __future__ import annotations

from dataclasses import dataclass

from .errors import UserError


@dataclass(frozen=True)
class Option:
    """One build option: a 0/1 parameter of cube4_top."""

    name: str            # the Verilog parameter
    full: int            # its value in the full build = its Verilog default
    letter: str          # in build tags (report folders): 's0', 'g1', ...
    adds: str            # what it adds, as a user reads it in an error
    units: tuple[str, ...]   # the RTL modules (or datapaths of one) it selects
    auto_off: bool = False   # when a build does not name it and a rule forbids it on: off


OPTIONS: tuple[Option, ...] = (
    Option("SHADING", 1, "s", "shading (gradients and the reflectance map)",
           ("cube4_gra", "cube4_sha shading lane")),
    Option("COMPOSITING", 1, "c", "the compositing datapath (composite, xray)",
           ("cube4_com blend lane",)),
    Option("EXTREMUM", 1, "e", "the comparators (mip, minip)",
           ("cube4_com extremum lane",)),
    Option("CLIP", 1, "k", "the cut plane or window (cube4_clip)",
           ("cube4_clip",)),
    Option("VGRAD", 0, "g", "voxel gradients (the memory's gradient channels)",
           ("cube4_tri gradient channels", "no cube4_gra")),
    Option("PLW", 1, "w", "path-length weights (the LUT's path-weight columns in COM)",
           ("cube4_com path-weight columns",), auto_off=True),
    Option("SLAB", 0, "l", "the cut slab (its far face, the falloff weights in SHA and COM)",
           ("cube4_clip far face", "cube4_sha_slab", "cube4_com falloff multipliers")),
    Option("ZOUT", 0, "z", "depth out (two slice numbers per ray in COM's buffer word)",
           ("cube4_com depth fields",)),
    Option("ZIN", 0, "d", "depth in (the stop-slice table in COM)",
           ("cube4_com_stop",)),
    Option("GMOD", 0, "m", "gradient-magnitude modulation (cube4_sha_gm and SHA's modulation multipliers)",
           ("cube4_sha_gm", "cube4_sha modulation stages")),
    Option("LABELS", 0, "t", "label volumes (the label in the memory word, its nearest-corner pick in TRI, "
           "a LUT block per label in SHA)",
           ("cube4_tri_lane label pick", "cube4_gra label carry", "cube4_sha label LUT")),
    Option("RECTS", 0, "r", "slice rectangles (the rectangle table in CFB, GRA's walk, COM)",
           ("cube4_cfb rectangle walk", "cube4_gra position walk", "cube4_com rectangle reader")),
    Option("BEATS", 0, "b", "beat skipping and ray termination (the block and ray tables and the walk "
           "in CFB, COM's reports)",
           ("cube4_cfb_skip", "cube4_cfb_bctl", "cube4_com_beats", "cube4_com_lane termination")),
)

BY_NAME = {o.name: o for o in OPTIONS}
#: the option names, in the order of OPTIONS
BUILD_PARAMS: tuple[str, ...] = tuple(o.name for o in OPTIONS)
#: every option at its full-build value (= the Verilog defaults)
FULL_BUILD: dict[str, int] = {o.name: o.full for o in OPTIONS}
#: options that are off in the full build and stay off unless a build names them
OPT_IN = tuple(o.name for o in OPTIONS if not o.full)


@dataclass(frozen=True)
class Rule:
    """A legal-combination rule: when every parameter of ``when`` has its value, every
    parameter of ``then`` must have one of its values (``then`` may name MAX_SS_LOG2,
    which is not a build option but a width). ``then`` None: the combination is illegal
    outright. ``why`` ends the error line."""

    when: dict[str, int]
    then: dict[str, tuple[int, ...]] | None
    why: str

    def holds(self, build: dict[str, int], widths: dict[str, int] | None = None) -> bool:
        values = {**(widths or {}), **build}
        if any(values.get(k) != v for k, v in self.when.items()):
            return True
        if self.then is None:
            return False
        return all(k not in values or values[k] in ok for k, ok in self.then.items())

    def message(self) -> str:
        cond = " and ".join(f"{k} = {v}" for k, v in self.when.items())
        if self.then is None:
            return f"a build with {cond} {self.why}"
        need = " and ".join(f"{k} = {' or '.join(map(str, ok))}" if len(ok) > 1 else f"{k} = {ok[0]}"
                            for k, ok in self.then.items())
        return f"a build with {cond} needs {need} ({self.why})"


RULES: tuple[Rule, ...] = (
    Rule({"COMPOSITING": 0, "EXTREMUM": 0}, None, "has no rendering mode"),
    Rule({"SHADING": 1}, {"COMPOSITING": (1,)}, "only compositing is shaded"),
    Rule({"VGRAD": 1}, {"SHADING": (1,)}, "voxel gradients only feed shading"),
    Rule({"PLW": 1}, {"COMPOSITING": (1,)}, "only the blending modes are path-weighted"),
    Rule({"SLAB": 1}, {"CLIP": (1,)}, "the slab is the cut plane's"),
    Rule({"RECTS": 1}, {"PLW": (0,), "MAX_SS_LOG2": (0,)}, "rectangles run with S = 1, unweighted"),
    Rule({"ZIN": 1}, {"RECTS": (0,)}, "depth in runs on the fixed and box schedules"),
    Rule({"GMOD": 1}, {"SHADING": (1,), "RECTS": (0,)}, "the gradient comes with shading; not with rectangles"),
    Rule({"LABELS": 1}, {"VGRAD": (0,), "PLW": (0,), "RECTS": (0,)},
         "labels run without voxel gradients, path weights and rectangles"),
    Rule({"BEATS": 1}, {"RECTS": (0,), "ZIN": (0,)},
         "the beat schedule runs without rectangles, and depth in through the ray table's stops"),
)


def complete_build(partial: dict | None) -> dict[str, int]:
    """A build from the options it names: the others at their full-build value, except an
    ``auto_off`` option (PLW) that some rule forbids given the rest (PLW without
    COMPOSITING, PLW with RECTS): that one is off. Unknown names: UserError."""
    partial = {str(k).upper(): int(v) for k, v in (partial or {}).items()}
    unknown = set(partial) - set(BUILD_PARAMS)
    if unknown:
        raise UserError(f"unknown build option {', '.join(sorted(unknown))}; options: {', '.join(BUILD_PARAMS)}")
    build = {**FULL_BUILD, **partial}
    for o in OPTIONS:
        if o.auto_off and o.name not in partial and build[o.name]:
            rules = [r for r in RULES if o.name in r.when or o.name in (r.then or {})]
            if not all(r.holds(build) for r in rules) and all(r.holds({**build, o.name: 0}) for r in rules):
                build[o.name] = 0
    return build


def check_build(build: dict, widths: dict[str, int] | None = None) -> None:
    """A build: every option, each 0 or 1, and a legal combination (the same rules stop
    cube4_top's elaboration). ``widths`` (e.g. MAX_SS_LOG2) takes part in the rules that
    name them. UserError with one line otherwise."""
    if set(build) != set(BUILD_PARAMS) or any(v not in (0, 1) or isinstance(v, bool) for v in build.values()):
        raise UserError(f"a build sets each of {', '.join(BUILD_PARAMS)} to 0 or 1, got {build}")
    for rule in RULES:
        if not rule.holds(build, widths):
            raise UserError(rule.message())


def parse_options(text: str, what: str = "--build") -> dict[str, int]:
    """NAME=0/1 pairs, comma-separated (names in any case); each name once."""
    named: dict[str, int] = {}
    for part in filter(None, (t.strip() for t in text.split(","))):
        name, eq, val = part.partition("=")
        name = name.strip().upper()
        if not eq or name not in BY_NAME or val.strip() not in ("0", "1"):
            raise UserError(f"{what}: NAME=0/1 pairs with NAME in {', '.join(BUILD_PARAMS)}, got {part!r}")
        if name in named:
            raise UserError(f"{what} names {name} twice")
        named[name] = int(val)
    return named


def build_tag(build: dict | None) -> str:
    """A build's folder suffix: '' for the full build, else the letters of the options that
    differ from it and of the opt-in options that are on (e.g. '_s0c1e0k0w0', '_g1')."""
    full = complete_build(build)
    if full == FULL_BUILD:
        return ""
    return "_" + "".join(f"{o.letter}{full[o.name]}" for o in OPTIONS
                         if o.name in (build or {}) and (o.full or full[o.name]))


def build_name(build: dict) -> str:
    """The build's name in NAMED, or its options that differ from the full build."""
    build = complete_build(build)
    for name, b in NAMED.items():
        if b == build:
            return name
    return ", ".join(f"{k}={v}" for k, v in build.items() if v != FULL_BUILD[k])


def named(name: str) -> dict[str, int]:
    """A named build (a copy)."""
    try:
        return dict(NAMED[name])
    except KeyError:
        raise UserError(f"no build named {name!r}; builds: {', '.join(NAMED)}") from None


#: The builds documents, reports and tests name. Each is legal (checked on import).
NAMED: dict[str, dict[str, int]] = {
    "full": dict(FULL_BUILD),
    "vgrad": complete_build({"VGRAD": 1}),                                    # voxel gradients instead of GRA
    "unweighted": complete_build({"PLW": 0}),                                # no path-weight columns
    "noclip": complete_build({"CLIP": 0}),
    "shaded": complete_build({"EXTREMUM": 0, "CLIP": 0}),                    # composite and X-ray, shaded
    "unshaded": complete_build({"SHADING": 0, "EXTREMUM": 0, "CLIP": 0}),    # composite, X-ray unshaded
    "mip": complete_build({"SHADING": 0, "COMPOSITING": 0, "CLIP": 0}),      # MIP, MinIP
    "mip_clip": complete_build({"SHADING": 0, "COMPOSITING": 0}),
    "rects": complete_build({"RECTS": 1, "PLW": 0}),                         # slice rectangles
    "rects_unshaded": complete_build({"RECTS": 1, "SHADING": 0, "EXTREMUM": 0, "CLIP": 0}),
}
for _name, _b in NAMED.items():
    check_build(_b)

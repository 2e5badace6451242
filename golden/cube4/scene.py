"""Scene files (TOML): transfer function, lights, material, view, output, mode.

See docs/scenes.md for the format; every key is optional except where stated.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field, replace
from importlib import resources
from pathlib import Path

import numpy as np

from .clip import CROP_MODES
from .levels import LEVELS
from .errors import UserError
from .values import integer, real, shown, vector
from .modes import MODES, is_blend  # docs/scenes.md, docs/numerics.md §13
from .subpixel import MAX_Q
from .view import direction_from_angles, normalize_direction
from .vgrad import check_gradient
from .warp import DEFAULT_FILTER, check_filter

#: [output] footprint when a scene does not say (docs/scenes.md)
FOOTPRINT_DEFAULT = True
CUT_POINT_BOUND = 1e6   # [cut] point: each coordinate within +-this many voxels
SLAB_MAX = 4096.0       # [slab] thickness and falloff: at most this many voxels
SLAB_FALLOFF_MIN = 0.125  # [slab] falloff: 0 (a hard slab) or at least this many voxels
PRECISION_KEYS = ("voxel_bits", "weight_bits", "alpha_bits", "acc_bits", "rmap_bits")


#: [render] skip left out: the scene runs the schedule ``default_schedule`` chooses
SKIP_DEFAULT = "default"


def default_schedule(scene: "Scene", build: dict | None = None, whole: bool = True,
                     supersample: int | None = None) -> bool | str:
    """The schedule of a scene that leaves [render] skip out: beat skipping and ray
    termination ("beats", exact: tau as the scene says, 0 unless it sets one) wherever
    the beat build runs it, the box (True) elsewhere: the beat schedule renders the volume
    whole, not in bricks, on a build with BEATS = 1. ``build``: the build the render uses
    when one is given (None: the scene's own smallest, which then has BEATS = 1);
    ``supersample``: the render's S where its configuration sets it (None: the scene's;
    every S runs on the beat schedule)."""
    del supersample         # (any S: the beat build runs them all)
    if not whole:
        return True
    if build is not None and not build.get("BEATS"):
        return True
    return "beats"


def with_schedule(scene: "Scene", build: dict | None = None, whole: bool = True,
                  supersample: int | None = None) -> "Scene":
    """The scene with its schedule written out: a scene that leaves [render] skip out gets
    ``default_schedule``'s for this render (the build it runs on, whole or in bricks, its S)."""
    if scene.skip != SKIP_DEFAULT:
        return scene
    return replace(scene, skip=default_schedule(scene, build, whole, supersample))


@dataclass(frozen=True)
class Light:
    direction: np.ndarray  # unit vector: the direction the light travels (volume axes)
    intensity: float
    headlight: bool = False  # travels along the view direction (follows the view)


@dataclass
class Scene:
    direction: np.ndarray
    up: np.ndarray | None = None
    width: int = 256
    height: int = 256
    mode: str = "composite"
    supersample: int = 1
    ambient: float = 0.25
    diffuse: float = 0.65
    specular: float = 0.35
    shininess: float = 24.0
    lights: list[Light] = field(default_factory=list)
    tf_points: np.ndarray = field(default_factory=lambda: np.array([[0, 0, 0, 0, 0], [1, 1, 1, 1, 1]], float))
    precision: dict = field(default_factory=dict)
    name: str = "scene"
    shading: bool = True  # [material] shading: false classifies only (composite mode)
    crop: tuple | None = None  # [crop] box: ((x0, y0, z0), (x1, y1, z1)) voxels, inclusive
    crop_regions: int | None = None  # [crop] mode / regions: VTK's 27 region flags of the box's
    #                                  slabs (cube4.clip); None: the box alone is traversed
    cut: tuple | None = None  # [cut]: (normal, point), volume coordinates
    slab: tuple | None = None  # [slab]: (normal, center, thickness, falloff), volume coordinates, voxels
    skip: bool | str = SKIP_DEFAULT  # [render] skip: true, only the box that can change a ray
    #                          (cube4.skip); "rects": and within it each slice's rectangle (cube4.slices;
    #                          S = 1); "beats": within it only the beats that can change a ray, and rays
    #                          end (cube4.beats); left out (SKIP_DEFAULT): ``schedule`` says which
    tau: float = 0.0  # [render] tau: with skip = "beats", a ray ends at transmittance <= tau (0: exact)
    terminate: bool = True  # [render] terminate: with skip = "beats", rays that can change no more end
    preview: int = 1  # [render] preview: render the volume at 1/preview of its resolution (cube4.levels)
    subpixel: int = 1  # [render] subpixel: q, q×q rays per base-plane pixel (cube4.subpixel)
    gradient: str = "gra"  # [render] gradient: gra (the paper's), central or sobel (cube4.vgrad)
    path_weights: bool = False  # [render] path_weights: weight rays' first and last samples (cube4.pathlen)
    filter: str = DEFAULT_FILTER  # [output] filter: the warp's OpenImageIO filter
    footprint: bool = FOOTPRINT_DEFAULT  # [output] footprint: cut the image to the box's projection
    depth_threshold: float | None = None  # [output] depth_threshold: depth out at this opacity (None: none)
    # [geometry]: ("image", EXR path) or ("mesh", "needle" or a mesh file), which the application
    # turns into a cube4.geometry.Geometry for the view (cube4.app.mesh.resolve_geometry)
    geometry: object = None
    # [gradient_modulation]: (opacity points, shading points), each (n, 2) [|grad f|, factor] or
    # None (1 everywhere); None: no modulation (cube4.gmod)
    gmod: tuple | None = None
    # [labels] and [[label]]: each label's transfer function and visibility (cube4.labels); the
    # volume then comes with a label map, and what render_frame reads are its memory words
    labels: object = None

    @property
    def schedule(self) -> bool | str:
        """The schedule the scene runs: its [render] skip, or where the scene leaves that
        out, ``default_schedule`` for a render of the whole volume on the scene's own build."""
        return default_schedule(self) if self.skip == SKIP_DEFAULT else self.skip

    @property
    def shaded(self) -> bool:
        """Does this scene need gradients and the reflectance map?"""
        return self.shading and self.mode == "composite"

    @property
    def voxel_gradients(self) -> bool:
        """Is this scene shaded with gradients estimated at the voxels (cube4.vgrad)?"""
        return self.shaded and self.gradient != "gra"

    @property
    def path_weighted(self) -> bool:
        """Does this scene weight its rays' first and last samples (cube4.pathlen)? Only
        the blending modes integrate along the ray."""
        return self.path_weights and is_blend(self.mode)

    def tf(self, x) -> np.ndarray:
        """Transfer function at normalised values x in [0, 1]: (..., 4) RGBA, alpha per
        voxel of distance. Piecewise linear between control points, clamped outside."""
        x = np.asarray(x, dtype=np.float64)
        p = self.tf_points
        return np.stack([np.interp(x, p[:, 0], p[:, c]) for c in range(1, 5)], axis=-1)


def _num(tbl: dict, key: str, default, lo=None, hi=None, where=""):
    return real(tbl.get(key, default), f"scene: {where}{key}", lo, hi)


def _int(tbl: dict, key: str, default, lo, hi, where=""):
    return integer(tbl.get(key, default), f"scene: {where}{key}", lo, hi)


def _direction(value, key: str) -> np.ndarray:
    return normalize_direction(value, f"scene: {key}")


def _check_keys(tbl: dict, allowed: tuple, where: str) -> None:
    if not isinstance(tbl, dict):
        raise UserError(f"scene: [{where}] must be a table")
    extra = sorted(set(tbl) - set(allowed))
    if extra:
        raise UserError(f"scene: unknown key(s) in [{where}]: {', '.join(extra)}")


def parse_scene(data: dict, name: str = "scene") -> Scene:
    _check_keys(data, ("view", "output", "render", "material", "light", "transfer", "precision", "crop", "cut", "slab",
                       "geometry", "gradient_modulation", "labels", "label"),
                "top level")
    view = data.get("view", {})
    _check_keys(view, ("direction", "azimuth", "elevation", "up"), "view")
    if "direction" in view:
        if "azimuth" in view or "elevation" in view:
            raise UserError("scene: [view] takes either direction or azimuth/elevation, not both")
        direction = _direction(view["direction"], "view.direction")
    else:
        az = _num(view, "azimuth", 30.0, -360, 360, "view.")
        el = _num(view, "elevation", 20.0, -90, 90, "view.")
        direction = direction_from_angles(az, el)
    up = _direction(view["up"], "view.up") if "up" in view else None

    out = data.get("output", {})
    _check_keys(out, ("width", "height", "filter", "footprint", "depth_threshold"), "output")
    width = _int(out, "width", 256, 8, 8192, "output.")
    height = _int(out, "height", width, 8, 8192, "output.")
    warp_filter = check_filter(out.get("filter", DEFAULT_FILTER), "scene: output.")
    footprint = out.get("footprint", FOOTPRINT_DEFAULT)
    if not isinstance(footprint, bool):
        raise UserError(f"scene: output.footprint must be true or false, got {shown(footprint)}")
    depth = None
    if "depth_threshold" in out:
        depth = real(out["depth_threshold"], "scene: output.depth_threshold", 0, 1)
        if depth <= 0:
            raise UserError("scene: output.depth_threshold must be in (0, 1]")

    rnd = data.get("render", {})
    _check_keys(rnd, ("mode", "supersample", "skip", "subpixel", "gradient", "path_weights", "tau", "terminate",
                      "preview"), "render")
    gradient = check_gradient(rnd.get("gradient", "gra"))
    mode = rnd.get("mode", "composite")
    if mode not in MODES:
        raise UserError(f"scene: render.mode {mode!r} is not supported (supported: {', '.join(MODES)})")
    supersample = rnd.get("supersample", 1)
    if not isinstance(supersample, int) or isinstance(supersample, bool) or supersample not in (1, 2, 4, 8):
        raise UserError(f"scene: render.supersample must be 1, 2, 4 or 8, got {shown(supersample)}")
    subpixel = rnd.get("subpixel", 1)
    if not isinstance(subpixel, int) or isinstance(subpixel, bool) or not 1 <= subpixel <= MAX_Q:
        raise UserError(f"scene: render.subpixel must be an integer in 1..{MAX_Q}, got {shown(subpixel)}")
    skip = rnd.get("skip", SKIP_DEFAULT)
    if "skip" in rnd and not isinstance(skip, bool) and skip not in ("rects", "beats"):
        raise UserError(f"scene: render.skip must be true, false, \"rects\" or \"beats\", got {shown(skip)}")
    tau = _num(rnd, "tau", 0.0, 0.0, 0.5, "render.")
    terminate = rnd.get("terminate", True)
    if not isinstance(terminate, bool):
        raise UserError(f"scene: render.terminate must be true or false, got {shown(terminate)}")
    preview = rnd.get("preview", 1)
    if not isinstance(preview, int) or isinstance(preview, bool) or preview not in LEVELS:
        raise UserError(f"scene: render.preview must be one of {', '.join(map(str, LEVELS))}, got {shown(preview)}")
    path_weights = rnd.get("path_weights", False)
    if not isinstance(path_weights, bool):
        raise UserError(f"scene: render.path_weights must be true or false, got {shown(path_weights)}")

    mat = data.get("material", {})
    _check_keys(mat, ("ambient", "diffuse", "specular", "shininess", "shading"), "material")
    shading = mat.get("shading", True)
    if not isinstance(shading, bool):
        raise UserError(f"scene: material.shading must be true or false, got {shown(shading)}")
    ka = _num(mat, "ambient", 0.25, 0, 4, "material.")
    kd = _num(mat, "diffuse", 0.65, 0, 4, "material.")
    ks = _num(mat, "specular", 0.35, 0, 4, "material.")
    shin = _num(mat, "shininess", 24.0, 0, 1000, "material.")

    lights = []
    raw_lights = data.get("light", [])
    if not isinstance(raw_lights, list):
        raise UserError("scene: lights are given as [[light]] tables")
    for n, lt in enumerate(raw_lights):
        _check_keys(lt, ("direction", "intensity", "headlight"), f"light #{n + 1}")
        inten = _num(lt, "intensity", 1.0, 0, 100, f"light #{n + 1} ")
        headlight = lt.get("headlight", False)
        if not isinstance(headlight, bool):
            raise UserError(f"scene: light #{n + 1} headlight must be true or false, got {shown(headlight)}")
        if headlight:
            if "direction" in lt:
                raise UserError(f"scene: light #{n + 1} is a headlight and also has a direction")
            ldir = direction
        elif "direction" in lt:
            ldir = _direction(lt["direction"], f"light #{n + 1} direction")
        else:
            raise UserError(f"scene: light #{n + 1} needs a direction or headlight = true")
        lights.append(Light(direction=ldir, intensity=float(inten), headlight=headlight))

    tf = data.get("transfer", {})
    _check_keys(tf, ("points",), "transfer")
    pts = tf.get("points", [[0, 0, 0, 0, 0], [1, 1, 1, 1, 1]])
    rows_ok = isinstance(pts, list) and len(pts) >= 1 and all(isinstance(r, list) and len(r) == 5 for r in pts)
    if not rows_ok:
        raise UserError("scene: transfer.points must be a list of [value, r, g, b, a] rows")
    arr = np.array([[real(v, f"scene: transfer.points[{n}][{c}]", 0, 1) for c, v in enumerate(row)]
                    for n, row in enumerate(pts)], dtype=np.float64)
    if np.any(np.diff(arr[:, 0]) < 0):
        raise UserError("scene: transfer.points must be sorted by value")

    prec = data.get("precision", {})
    _check_keys(prec, PRECISION_KEYS, "precision")
    precision = {k: prec[k] for k in PRECISION_KEYS if k in prec}

    crop, crop_regions = _crop(data.get("crop", {}))
    cut = _cut(data.get("cut", {}))
    slab = _slab(data.get("slab", {}))
    geo = data.get("geometry", {})
    _check_keys(geo, ("image", "mesh"), "geometry")
    geometry = None
    if geo:
        if len(geo) != 1 or not isinstance(next(iter(geo.values())), str) or not next(iter(geo.values())):
            raise UserError("scene: [geometry] takes image = \"file.exr\" (a depth image, channel Z) "
                            "or mesh = \"needle\" or a mesh file, one of them")
        geometry = next(iter(geo.items()))
    if cut is not None and slab is not None:
        raise UserError("scene: give [cut] or [slab], not both (they share the plane's registers)")
    gmod = _gradient_modulation(data.get("gradient_modulation", {}))
    if gmod is not None and not (shading and mode == "composite"):
        raise UserError("scene: [gradient_modulation] needs a shaded composite scene (mode = \"composite\", "
                        "shading = true): the gradient comes with shading")

    from .labels import parse_labels
    labels = parse_labels(data.get("labels", {}), data.get("label", []))
    if labels is not None:
        label_scene_checks(mode, skip, path_weights, preview)

    return Scene(
        direction=direction, up=up, width=width, height=height, mode=mode,
        supersample=supersample, ambient=float(ka), diffuse=float(kd), specular=float(ks),
        shininess=float(shin), lights=lights, tf_points=arr, precision=precision, name=name,
        shading=shading, crop=crop, crop_regions=crop_regions, cut=cut, slab=slab, geometry=geometry, skip=skip, tau=tau, terminate=terminate,
        preview=preview,
        subpixel=subpixel, filter=warp_filter,
        footprint=footprint, depth_threshold=depth, gradient=gradient, path_weights=path_weights, gmod=gmod,
        labels=labels,
    )


def label_scene_checks(mode: str, skip, path_weights: bool, preview: int) -> None:
    """What a scene with labels cannot have, one line each (numerics.md §24)."""
    if not is_blend(mode):
        raise UserError(f"scene: labels classify the blending modes (composite, xray), not {mode}: "
                        "MIP and MinIP pick a value, not a material")
    if skip == "rects":
        raise UserError(f"scene: labels run on the fixed, box and beat schedules: render.skip must be true, false "
                        f"or \"beats\", got {shown(skip)}")
    if path_weights:
        raise UserError("scene: labels do not combine with path weights (one table of weighted opacities): "
                        "set [render] path_weights = false")
    if preview != 1:
        raise UserError("scene: labels are not resampled to a preview level: set [render] preview = 1")


def _gradient_modulation(tbl: dict):
    """[gradient_modulation] opacity / shading = [[|grad f|, factor], ...] (cube4.gmod): at
    least one of the two; the other is 1 everywhere."""
    _check_keys(tbl, ("opacity", "shading"), "gradient_modulation")
    if not tbl:
        return None
    from .gmod import parse_points
    return parse_points(tbl, "opacity"), parse_points(tbl, "shading")


def _crop(tbl: dict):
    """[crop] box = [[x0, y0, z0], [x1, y1, z1]]: voxel indices, inclusive (checked
    against the volume's dims when the scene meets a volume: ``crop_box``); mode =
    "subvolume" (the box alone is traversed; the default), "fence", "inverted_fence",
    "cross" or "inverted_cross", or regions = VTK's 27 region flags (an integer): the
    box's three slabs cut the volume into 27 regions and these keep some (cube4.clip).
    Returns (box or None, region flags or None)."""
    _check_keys(tbl, ("box", "mode", "regions"), "crop")
    if "box" not in tbl:
        if "mode" in tbl or "regions" in tbl:
            raise UserError("scene: crop.mode and crop.regions need crop.box (the slabs' faces)")
        return None, None
    box = tbl["box"]
    ok = (isinstance(box, list) and len(box) == 2
          and all(isinstance(c, list) and len(c) == 3 for c in box)
          and all(isinstance(v, int) and not isinstance(v, bool) and abs(v) < 2**31 for c in box for v in c))
    if not ok:
        raise UserError("scene: crop.box must be [[x0, y0, z0], [x1, y1, z1]] (voxel indices)")
    lo, hi = tuple(box[0]), tuple(box[1])
    if any(a < 0 or b < a for a, b in zip(lo, hi)):
        raise UserError(f"scene: crop.box {box} needs 0 <= x0 <= x1 (and likewise y, z)")
    if "mode" in tbl and "regions" in tbl:
        raise UserError("scene: give crop.mode or crop.regions, not both")
    flags = None
    if "mode" in tbl:
        mode = tbl["mode"]
        if mode not in CROP_MODES:
            raise UserError(f"scene: crop.mode must be one of {', '.join(CROP_MODES)}, got {shown(mode)}")
        flags = None if mode == "subvolume" else CROP_MODES[mode]
    if "regions" in tbl:
        flags = tbl["regions"]
        if not isinstance(flags, int) or isinstance(flags, bool) or not 0 <= flags < (1 << 27):
            raise UserError(f"scene: crop.regions must be an integer in 0..{(1 << 27) - 1} (27 region flags), "
                            f"got {shown(flags)}")
    return (lo, hi), flags


def _cut(tbl: dict):
    """[cut] normal = [nx, ny, nz], point = [x, y, z]: the samples on the side the
    normal points to are cut away (transparent)."""
    _check_keys(tbl, ("normal", "point"), "cut")
    if not tbl:
        return None
    if "normal" not in tbl or "point" not in tbl:
        raise UserError("scene: [cut] needs both normal and point")
    normal = _direction(tbl["normal"], "cut.normal")
    point = np.asarray(vector(tbl["point"], "scene: cut.point", bound=CUT_POINT_BOUND), dtype=np.float64)
    return normal, point


def _slab(tbl: dict):
    """[slab] normal = [nx, ny, nz], center = [x, y, z], thickness = t (voxels, > 0),
    falloff = F (voxels, >= 0; default 0): only the samples within t / 2 of the plane
    through center count, and with F > 0 a sample's opacity falls linearly to 0 over the
    F voxels inside each face (cube4.clip)."""
    _check_keys(tbl, ("normal", "center", "thickness", "falloff"), "slab")
    if not tbl:
        return None
    if any(k not in tbl for k in ("normal", "center", "thickness")):
        raise UserError("scene: [slab] needs normal, center and thickness")
    normal = _direction(tbl["normal"], "slab.normal")
    center = np.asarray(vector(tbl["center"], "scene: slab.center", bound=CUT_POINT_BOUND), dtype=np.float64)
    thickness = real(tbl["thickness"], "scene: slab.thickness", 0, SLAB_MAX)
    falloff = real(tbl.get("falloff", 0.0), "scene: slab.falloff", 0, SLAB_MAX)
    if thickness <= 0:
        raise UserError("scene: slab.thickness must be > 0 voxels")
    if 0 < falloff < SLAB_FALLOFF_MIN:
        raise UserError(f"scene: slab.falloff must be 0 or at least {SLAB_FALLOFF_MIN} voxel")
    return normal, center, float(thickness), float(falloff)


def crop_box(scene: Scene, dims) -> tuple[tuple[int, int, int], tuple[int, int, int]]:
    """The scene's crop box in a volume of dims (nx, ny, nz): (origin, box dims); the
    whole volume when the scene has none."""
    dims = tuple(int(n) for n in dims)
    if scene.crop is None:
        return (0, 0, 0), dims
    lo, hi = scene.crop
    if any(b >= n for b, n in zip(hi, dims)):
        raise UserError(f"scene: crop.box {[list(lo), list(hi)]} reaches outside the volume "
                        f"(voxels 0..{dims[0] - 1}, 0..{dims[1] - 1}, 0..{dims[2] - 1})")
    if scene.crop_regions is not None:       # the regions are clipped, the whole volume traversed
        return (0, 0, 0), dims
    size = tuple(b - a + 1 for a, b in zip(lo, hi))
    if min(size) < 2:
        raise UserError(f"scene: crop.box {[list(lo), list(hi)]} is thinner than 2 voxels")
    return tuple(lo), size


def with_view(scene: Scene, direction, up=None) -> Scene:
    """The scene seen along another view direction (and, if given, with that picture up);
    headlights follow the view."""
    d = normalize_direction(direction)
    lights = [replace(lt, direction=d) if lt.headlight else lt for lt in scene.lights]
    new = replace(scene, direction=d, lights=lights)
    return new if up is None else replace(new, up=np.asarray(up, dtype=np.float64))


def builtin_scene_names() -> list[str]:
    return sorted(p.name[:-5] for p in resources.files("cube4.scenes").iterdir() if p.name.endswith(".toml"))


#: Named presets (``cube4 render --preset``): the render keys they set on any scene.
#: quality: voxel central differences (the reference's estimator, numerics.md §5b), S = 4,
#: 2×2 sub-pixel passes and path weights (§17): 40 dB or more on sphere:64, head:64 and ml:41
#: (reports/error_vs_runtime.md).
PRESETS: dict[str, dict] = {
    "default": {},
    "quality": {"gradient": "central", "supersample": 4, "subpixel": 2, "path_weights": True},
}


def apply_preset(scene: Scene, name: str) -> Scene:
    """The scene with a named preset's render keys (``default`` leaves the scene as it is)."""
    if name not in PRESETS:
        raise UserError(f"preset must be one of {', '.join(PRESETS)}, got {shown(name)}")
    return replace(scene, **PRESETS[name])


def _exists(path: Path) -> bool:
    try:
        return path.exists()
    except (OSError, ValueError):      # a name longer than the system allows, a NUL byte
        return False


MAX_SCENE_BYTES = 1 << 20     # a scene file is a few hundred bytes; more is not a scene


def _read_scene_file(path: Path, spec: str) -> str:
    """A scene file's text: a regular file (not a device or a pipe) of at most
    MAX_SCENE_BYTES, UTF-8."""
    try:
        if path.exists() and not path.is_file():
            raise UserError(f"scene {spec} is not a regular file (a scene is a TOML file)")
        with open(path, "rb") as f:
            data = f.read(MAX_SCENE_BYTES + 1)
    except OSError as e:
        name = spec if len(spec) <= 200 else spec[:60] + "..."
        raise UserError(f"cannot read scene {name}: {e.strerror or e}") from None
    if len(data) > MAX_SCENE_BYTES:
        raise UserError(f"scene {spec} is larger than {MAX_SCENE_BYTES >> 20} MiB: not a scene file")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        raise UserError(f"scene {spec} is not UTF-8 text (a scene is a TOML file)") from None


def load_scene(spec: str) -> Scene:
    """A scene from a TOML file path or a built-in name (see builtin_scene_names())."""
    path = Path(spec)
    if path.suffix == ".toml" or _exists(path):
        text = _read_scene_file(path, spec)
        name = path.stem
    else:
        names = builtin_scene_names()
        if spec not in names:
            raise UserError(f"unknown scene {spec!r}: not a file, and built-in scenes are {', '.join(names)}")
        text = resources.files("cube4.scenes").joinpath(spec + ".toml").read_text()
        name = spec
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise UserError(f"scene {spec}: malformed TOML: {e}") from None
    except RecursionError:
        raise UserError(f"scene {spec}: nested too deeply to be a scene") from None
    return parse_scene(data, name=name)

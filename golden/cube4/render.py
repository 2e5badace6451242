"""One render, any engine: volume + scene -> image-plane RGBA (+ base plane, stats).

This package owns two engines: ``reference`` (float64 truth, straight into the image
plane) and ``golden`` (the bit-exact Cube-4 model, base plane warped to the image plane
by OpenImageIO). Other engines are added from outside with ``register_engine``; the
package never imports them (the ``cube4`` command registers the simulated RTL, ``rtl``).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from .config import Cube4Config, resolve_build
from .errors import UserError
from .model import Frame, render_frame
from .reference import render_reference
from .clip import Clip, cut_coefficients
from .modes import is_extremum
from .scene import Scene, crop_box
from .tables import classification_lut, extremum_lut, reflectance_map
from .view import Camera, Traversal, make_camera, make_traversal
from .warp import warp_to_image

@dataclass
class RenderResult:
    engine: str
    image: np.ndarray  # (H, W, 4) premultiplied RGBA float64 in [0, 1]
    wall_s: float
    frame: Frame | None = None
    stats: dict = field(default_factory=dict)


def config_for(scene: Scene, pipelines: int | None = None, **overrides) -> Cube4Config:
    """The hardware configuration a scene asks for (scene [precision], supersampling),
    with command-line overrides."""
    kw = dict(scene.precision)
    kw["supersample"] = scene.supersample
    if pipelines is not None:
        kw["pipelines"] = pipelines
    kw.update({k: v for k, v in overrides.items() if v is not None})
    return Cube4Config(**kw)


def setup_view(dims, scene: Scene, cfg: Cube4Config) -> tuple[Traversal, Camera]:
    """The traversal (of the crop box, if the scene has one) and the camera (framing
    the whole volume, so that a crop stays where it is in the picture)."""
    origin, box = crop_box(scene, dims)
    trav = make_traversal(box, scene.direction, cfg.weight_bits, cfg.supersample, origin=origin)
    cam = make_camera(dims, scene.direction, scene.width, scene.height, scene.up)
    return trav, cam


def crop_volume(vol: np.ndarray, trav: Traversal) -> np.ndarray:
    """The traversed part of vol[z, y, x] (a view, no copy): the crop box or the whole."""
    (x0, y0, z0), (nx, ny, nz) = trav.origin, trav.dims
    return vol[z0:z0 + nz, y0:y0 + ny, x0:x0 + nx]


def frame_clip(scene: Scene, trav: Traversal) -> Clip | None:
    """The scene's cut plane as the clip registers of this view (None: no cut)."""
    if scene.cut is None:
        return None
    return Clip(plane=cut_coefficients(trav, *scene.cut))


def host_tables(scene: Scene, cfg: Cube4Config, trav: Traversal) -> tuple[np.ndarray, np.ndarray | None]:
    """What the host writes into the LUT load ports for this view: the classification
    LUT (opacity corrected for the sample distance; for MIP/MinIP colour premultiplied
    and opacity as given) and the reflectance map (None when the scene is unshaded)."""
    if is_extremum(scene.mode):
        lut = extremum_lut(scene, cfg)
    else:
        lut = classification_lut(scene, cfg, trav.sample_distance)
    return lut, (reflectance_map(scene, cfg, trav) if scene.shaded else None)


def scene_warp(base: np.ndarray, trav: Traversal, cam: Camera, scene: Scene) -> np.ndarray:
    """The base plane warped to the image as the scene's [output] asks (filter, footprint)."""
    return warp_to_image(base, trav, cam, filtername=scene.filter, footprint=scene.footprint)


def image_metrics(img: np.ndarray, ref: np.ndarray) -> dict:
    """RMSE, max |error| and PSNR (peak 1.0) over all four premultiplied RGBA channels."""
    err = img.astype(np.float64) - ref.astype(np.float64)
    rmse = float(np.sqrt(np.mean(err * err)))
    psnr = float("inf") if rmse == 0 else float(20.0 * np.log10(1.0 / rmse))
    return {"rmse": rmse, "max_abs": float(np.max(np.abs(err))), "psnr": psnr}


def view_stats(engine: str, dims, scene: Scene, cfg: Cube4Config) -> dict:
    return {
        "engine": engine,
        "dims": list(dims),
        "pipelines": cfg.pipelines,
        "view": [float(c) for c in scene.direction],
        "config": cfg.as_dict(),
    }


def trav_stats(trav: Traversal) -> dict:
    return {
        "traversed_box": {"origin": list(trav.origin), "dims": list(trav.dims)},
        "major_axis": "xyz"[trav.major],
        "view_x": trav.view_x,
        "view_y": trav.view_y,
        "sample_distance": trav.sample_distance,
        "baseplane_shape": list(trav.baseplane_shape),
    }


#: An engine renders one or more views of one volume:
#: (vol[z, y, x], scenes, cfg, progress) -> one RenderResult per scene, in order.
Engine = Callable[[np.ndarray, list[Scene], Cube4Config, bool], list[RenderResult]]

_ENGINES: dict[str, Engine] = {}


def register_engine(name: str, fn: Engine) -> None:
    """Make an engine available to ``render``, ``render_views`` and the command line."""
    _ENGINES[name] = fn


def engine_names() -> tuple[str, ...]:
    """The registered engines, in registration order."""
    return tuple(_ENGINES)


def _engine(name: str) -> Engine:
    if name not in _ENGINES:
        raise UserError(f"unknown engine {name!r} (engines: {', '.join(_ENGINES)})")
    return _ENGINES[name]


def render_reference_view(vol: np.ndarray, scene: Scene, cfg: Cube4Config, progress: bool = False) -> RenderResult:
    """The float64 reference image of one view."""
    nz, ny, nx = vol.shape
    dims = (nx, ny, nz)
    _, cam = setup_view(dims, scene, cfg)
    stats = view_stats("reference", dims, scene, cfg)
    t0 = time.perf_counter()
    img = render_reference(vol, cfg.voxel_bits, scene, cam, progress=progress, box=crop_box(scene, dims))
    return _timed(RenderResult("reference", img, 0.0, stats=stats), t0)


def render_golden_view(vol: np.ndarray, scene: Scene, cfg: Cube4Config, keep_streams: bool = False,
                       progress: bool = False) -> RenderResult:
    """One view through the bit-exact model, warped to the image plane."""
    nz, ny, nx = vol.shape
    dims = (nx, ny, nz)
    trav, cam = setup_view(dims, scene, cfg)
    stats = view_stats("golden", dims, scene, cfg)
    stats["build"] = resolve_build(cfg, [scene])     # the build this frame models
    t0 = time.perf_counter()
    lut, rmap = host_tables(scene, cfg, trav)
    frame = render_frame(crop_volume(vol, trav), trav, cfg, lut, rmap, keep_streams=keep_streams,
                         progress=progress, mode=scene.mode, shading=scene.shaded, clip=frame_clip(scene, trav))
    img = scene_warp(frame.baseplane_float, trav, cam, scene)
    stats.update(trav_stats(trav))
    stats["pixels"] = int(frame.pixels.size)
    return _timed(RenderResult("golden", img, 0.0, frame=frame, stats=stats), t0)


def _timed(res: RenderResult, t0: float) -> RenderResult:
    res.wall_s = time.perf_counter() - t0
    res.stats["wall_s"] = res.wall_s
    return res


register_engine("reference", lambda vol, scenes, cfg, progress: [
    render_reference_view(vol, sc, cfg, progress) for sc in scenes])
register_engine("golden", lambda vol, scenes, cfg, progress: [
    render_golden_view(vol, sc, cfg, progress=progress) for sc in scenes])


def render(
    vol: np.ndarray,
    scene: Scene,
    cfg: Cube4Config,
    engine: str,
    keep_streams: bool = False,
    progress: bool = False,
) -> RenderResult:
    """Render vol[z, y, x] (VOXEL_W-bit unsigned) with one engine; ``keep_streams``
    (golden only) keeps the model's intermediate streams in the frame."""
    if engine == "golden":
        return render_golden_view(vol, scene, cfg, keep_streams=keep_streams, progress=progress)
    return render_views(vol, [scene], cfg, engine, progress=progress)[0]


def render_views(
    vol: np.ndarray,
    scenes: list[Scene],
    cfg: Cube4Config,
    engine: str,
    progress: bool = False,
) -> list[RenderResult]:
    """Render several views (one scene each, e.g. ``scene.with_view``) of one volume.
    An engine may run them together (the RTL engine loads the volume once and runs the
    frames back to back)."""
    fn = _engine(engine)
    if not scenes:
        raise UserError("no view to render")
    return fn(vol, scenes, cfg, progress)

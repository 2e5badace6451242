"""The host's work for one view, and the bit-exact frame it gets back.

For a scene's view of a volume the host sets up the traversal and the camera, writes the
tables (classification LUT, reflectance map), plans the q×q sub-pixel passes and each
pass's empty-space box, and assembles the passes' base planes into the view's frame
(``plan_view``, ``assemble_view``); ``golden_view`` runs the passes through the bit-exact
model. The warp into the image plane and the engines that make images are the
application's (``cube4.app.render``).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from .beats import LAG, TERM_MIN_ROWS, BeatSchedule, BeatStats, BlockTable, TerminationRule, frame_occupancy, schedule_stats as beat_stats
from .clip import Clip, crop_regions, cut_coefficients, slab_coefficients
from .config import Cube4Config, resolve_build
from .cycles import frame_cycles, has_falloff, has_gmod, rect_frame_cycles
from .geometry import Geometry, check_geometry, stop_slices
from .gmod import gm_table
from .errors import UserError
from .levels import level_dims, level_volume
from .model import PIXEL_DTYPE, Frame, render_frame
from .modes import is_extremum
from .pathlen import weighted_columns
from .progress import Progress
from .scene import Scene, crop_box, with_schedule
from .skip import SkipPlan, find_box, plan_box
from .slices import SliceRects, plan_rects
from .subpixel import Pass, fine_origin, interleave, passes
from .tables import classification_lut, extremum_lut, reflectance_map
from .vgrad import pack_words
from .view import Camera, Traversal, level_camera, make_camera, make_traversal


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
    """The traversal (of the crop box, if the scene has one; of the preview level, if the
    scene asks for one) and the camera (framing the whole volume, so that a crop stays
    where it is in the picture; in a level's coordinates, the same picture). ``dims``
    are the whole volume's."""
    cam = make_camera(dims, scene.direction, scene.width, scene.height, scene.up)
    if scene.preview > 1:
        if scene.crop is not None or scene.cut is not None or scene.slab is not None or scene.geometry is not None:
            raise UserError("a preview level ([render] preview, --preview) renders the whole volume: "
                            "leave out [crop], [cut], [slab] and [geometry]")
        ldims = level_dims(dims, scene.preview)
        trav = make_traversal(ldims, scene.direction, cfg.weight_bits, cfg.supersample)
        return trav, level_camera(cam, ldims, scene.preview)
    origin, box = crop_box(scene, dims)
    trav = make_traversal(box, scene.direction, cfg.weight_bits, cfg.supersample, origin=origin)
    return trav, cam


def level_of(vol: np.ndarray, scene: Scene) -> np.ndarray:
    """What the host loads for a scene: vol[z, y, x] itself, or its preview level
    (cube4.levels)."""
    return level_volume(vol, scene.preview) if scene.preview > 1 else vol


def crop_volume(vol: np.ndarray, trav: Traversal) -> np.ndarray:
    """The traversed part of vol[z, y, x] (a view, no copy): the crop box or the whole."""
    (x0, y0, z0), (nx, ny, nz) = trav.origin, trav.dims
    return vol[z0:z0 + nz, y0:y0 + ny, x0:x0 + nx]


def frame_clip(scene: Scene, trav: Traversal) -> Clip | None:
    """The scene's cut plane and crop regions as the clip registers of this view (None:
    neither)."""
    if scene.cut is None and scene.slab is None and scene.crop_regions is None:
        return None
    plane = None if scene.cut is None else cut_coefficients(trav, *scene.cut)
    slab = None
    if scene.slab is not None:
        plane, slab = slab_coefficients(trav, *scene.slab)
    regions = None if scene.crop_regions is None else crop_regions(trav, *scene.crop, scene.crop_regions)
    return Clip(plane=plane, regions=regions, slab=slab)


def host_tables(scene: Scene, cfg: Cube4Config, trav: Traversal) -> tuple[np.ndarray, np.ndarray | None]:
    """What the host writes into the LUT load ports for this view: the classification
    LUT (opacity corrected for the sample distance; for MIP/MinIP colour premultiplied
    and opacity as given; a path-weighted scene's LUT carries the path-weight columns,
    cube4.pathlen) and the reflectance map (None when the scene is unshaded)."""
    if is_extremum(scene.mode):
        lut = extremum_lut(scene, cfg)
    else:       # a preview level's sample is preview times as far from the next, in the volume's voxels
        lut = classification_lut(scene, cfg, trav.sample_distance * scene.preview)
    if scene.path_weighted:
        lut = np.concatenate([lut, weighted_columns(lut[:, 3], cfg.alpha_bits)], axis=1)
    return lut, (reflectance_map(scene, cfg, trav, volume_axes=scene.voxel_gradients) if scene.shaded else None)


def gm_frame_table(scene: Scene, cfg: Cube4Config) -> np.ndarray | None:
    """The gradient-magnitude modulation table the host writes for this scene (cube4.gmod,
    numerics.md §23; None: the scene has none). One line if the scene cannot have it."""
    if scene.gmod is None:
        return None
    if not scene.shaded:
        raise UserError("[gradient_modulation] needs a shaded composite scene (the gradient comes with shading)")
    if scene.path_weighted:
        raise UserError("[gradient_modulation] does not combine with path weights (the first and last samples "
                        "of a ray take the LUT's weighted opacity): set [render] path_weights = false")
    opacity, shading = scene.gmod
    return gm_table(opacity, shading, cfg.voxel_bits, scene.gradient)


def build_memory(vol: np.ndarray, scenes: list[Scene], cfg: Cube4Config, build: dict) -> np.ndarray:
    """What a build's voxel memory holds for these scenes (checked by resolve_build to share
    one gradient): the volume, or on a VGRAD build the words with the scenes' voxel gradient
    (central when no scene is shaded)."""
    levels = {sc.preview for sc in scenes}
    if len(levels) > 1:
        raise UserError("one render holds one preview level in memory: render the levels separately")
    vol = level_volume(vol, levels.pop()) if scenes else vol
    if not build.get("VGRAD"):
        return vol
    kind = next((sc.gradient for sc in scenes if sc.voxel_gradients), "central")
    return pack_words(vol, kind, cfg.voxel_bits)


def memory_volume(vol: np.ndarray, scene: Scene, cfg: Cube4Config) -> np.ndarray:
    """What the voxel memory holds for this scene: vol[z, y, x] itself, or with voxel
    gradients ([render] gradient = central / sobel) the words of cube4.vgrad, estimated
    over the whole volume (a crop box or a brick reads the same words): the memory of the
    scene's own build."""
    return build_memory(vol, [scene], cfg, {"VGRAD": int(scene.voxel_gradients)})


def schedules(vol_box: np.ndarray, scene: Scene, cfg: Cube4Config, pss: list[Pass], lut: np.ndarray) -> list[SkipPlan]:
    """Each pass's frame: the box that can change a ray (``cube4.skip``; found once per
    view, it does not depend on the phase), or the whole traversed box when the scene asks
    for the fixed schedule ([render] skip = false)."""
    box, table_s = ((0, 0, 0), tuple(pss[0].trav.dims)), 0.0        # the fixed schedule: the whole box
    if scene.schedule:
        box, table_s = find_box(vol_box, pss[0].trav, lut, scene.mode, cfg.pipelines, frame_clip(scene, pss[0].trav),
                                labelled=scene.labels is not None)
    return [plan_box(ps.trav, box, frame_clip(scene, ps.trav), table_s if n == 0 else 0.0)
            for n, ps in enumerate(pss)]


def schedule_stats(plans: list[SkipPlan], cfg: Cube4Config, build: dict) -> dict:
    """What the frames of one view (one per sub-pixel pass) traverse and the cycles they
    predict, against the fixed schedule."""
    shading, vgrad, fall = bool(build["SHADING"]), bool(build.get("VGRAD", 0)), has_falloff(build)
    gm = has_gmod(build)
    full = cycles = 0
    boxes = []
    for plan in plans:
        t = plan.whole
        full += frame_cycles(t.num_sample_slices, t.nj, t.ni, cfg.pipelines, shading, vgrad, fall, gm)
        cycles += plan.cycles(cfg.pipelines, shading, vgrad, fall, gm)
        boxes.append(None if plan.box is None else
                     {"origin": [int(a) + int(o) for a, o in zip(plan.box[0], t.origin)],
                      "dims": [int(b) - int(a) for a, b in zip(*plan.box)]})
    return {"skip": any(p.skips for p in plans), "skip_box": boxes[0],
            "skip_fraction": float(np.mean([p.fraction for p in plans])),
            "predicted_cycles": cycles, "fixed_schedule_cycles": full, "cycles_saved": full - cycles,
            "skip_table_s": sum(p.table_s for p in plans), "frames": len(plans)}


@dataclass
class ViewPlan:
    """Everything the host sends for one view: its tables and one frame per sub-pixel
    pass (each with its empty-space box)."""

    scene: Scene
    trav: Traversal               # the view's traversal (phase 0)
    cam: Camera
    lut: np.ndarray
    rmap: np.ndarray | None
    passes: list[Pass]
    plans: list[SkipPlan]         # one per pass
    gm: np.ndarray | None = None  # gradient-magnitude modulation's table (cube4.gmod; None: none)

    def jobs(self) -> list[tuple[Pass, SkipPlan]]:
        """The passes that run a frame (a pass in which nothing counts runs none)."""
        return [(ps, pl) for ps, pl in zip(self.passes, self.plans) if pl.trav is not None]


def plan_view(vol: np.ndarray, scene: Scene, cfg: Cube4Config) -> ViewPlan:
    """The host's work for one view of vol[z, y, x]: traversal, camera, tables, the q×q
    sub-pixel passes ([render] subpixel) and each pass's schedule."""
    nz, ny, nx = vol.shape
    trav, cam = setup_view((nx, ny, nz), scene, cfg)
    lut, rmap = host_tables(scene, cfg, trav)
    box_vol = crop_volume(level_of(vol, scene), trav)
    pss = passes(trav, scene.subpixel)
    plans = schedules(box_vol, scene, cfg, pss, lut)
    return ViewPlan(scene, trav, cam, lut, rmap, pss, plans, gm_frame_table(scene, cfg))


def scene_geometry(scene: Scene, cam: Camera) -> Geometry | None:
    """The scene's [geometry] as the application resolved it (cube4.app.mesh), checked
    against the camera (None: none)."""
    if scene.geometry is None:
        return None
    if not isinstance(scene.geometry, Geometry):
        raise ValueError("[geometry] must be resolved for the view first (cube4.app.mesh.resolve_geometry)")
    check_geometry(scene.geometry, cam)
    return scene.geometry


def depth_threshold(scene: Scene, cfg: Cube4Config) -> int | None:
    """The depth-out threshold on the transmittance (numerics.md §21): a ray passes the
    scene's opacity threshold theta when T <= floor((1 - theta) 2^ACC_W); None: no depth out."""
    if scene.depth_threshold is None:
        return None
    return int(np.floor((1.0 - scene.depth_threshold) * (1 << cfg.acc_bits)))


def depth_z(trav: Traversal, cam: Camera, depth_m: np.ndarray, scale: float = 1.0) -> np.ndarray:
    """Depth out as distances: the point of each base-plane pixel's ray in its slice m
    (depth_m, (rows, cols, c), -1: none) along the view direction from the camera's
    centre, in voxels of the whole volume (``scale``: a preview level's factor); NaN: none."""
    rows, cols = depth_m.shape[:2]
    by, bx = np.mgrid[0:rows, 0:cols]
    out = np.full(depth_m.shape, np.nan)
    for c in range(depth_m.shape[-1]):
        m = depth_m[..., c]
        pts = trav.ray_point(bx, by, m / float(trav.supersample))
        out[..., c] = np.where(m >= 0, ((pts - cam.centre) @ cam.direction) * scale, np.nan)
    return out


def assemble_view(vp: ViewPlan, cfg: Cube4Config, results: dict[int, tuple[np.ndarray, np.ndarray]],
                  depths: dict[int, np.ndarray] | None = None) -> Frame:
    """The view's frame from its passes' results ({pass index: (box base plane, box
    finished rays)}; a pass that ran no frame is absent): each box placed in its pass's
    base plane, the passes interleaved when q > 1 (the frame's base plane and its rays'
    addresses are then the fine plane's). ``depths`` ({pass index: the box frame's
    depth_m}): the frame's depth_z, each pass's slices turned into distances with its own
    traversal, then interleaved."""
    q = vp.scene.subpixel
    planes, pix, zplanes = [], [], []
    for n, (ps, plan) in enumerate(zip(vp.passes, vp.plans)):
        sub, rays = results.get(n, (None, np.empty(0, PIXEL_DTYPE)))
        planes.append((ps, plan.place(sub)))
        if depths is not None:
            zplanes.append((ps, depth_z(plan.whole, vp.cam, plan.place_depth(depths.get(n)), vp.scene.preview)))
        rays = plan.place_pixels(rays)
        if q > 1 and rays.size:     # place_pixels returned a copy
            r0, c0 = fine_origin(vp.trav, q, ps)
            rays["by"], rays["bx"] = r0 + q * rays["by"], c0 + q * rays["bx"]
        pix.append(rays)
    base = planes[0][1] if q == 1 else interleave(vp.trav, q, planes)
    zs = None
    if depths is not None:
        zs = zplanes[0][1] if q == 1 else interleave(vp.trav, q, zplanes, fill=np.nan)
    return Frame(trav=vp.trav, cfg=cfg, baseplane=base, pixels=np.concatenate(pix), depth_z=zs)


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
        "gradient": scene.gradient if scene.shaded else None,
        "path_weights": scene.path_weighted,
        "preview": scene.preview,
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


def pass_rects(vol: np.ndarray, vp: ViewPlan) -> list[SliceRects | None]:
    """The slice rectangles (cube4.slices, numerics.md §18) of each pass's frame, within
    its empty-space box (None: the pass has no frame)."""
    raw, sc = crop_volume(level_of(vol, vp.scene), vp.trav), vp.scene
    return [None if plan.trav is None else
            plan_rects(plan.box_volume(raw), plan.trav, vp.lut, sc.mode, clip=plan.clip,
                       gra=sc.shaded and not sc.voxel_gradients)
            for plan in vp.plans]


def tau_fixed(tau: float, cfg: Cube4Config) -> int:
    """The termination threshold τ (a transmittance in [0, 1)) in Q0.ACC_W, rounded down."""
    return int(np.floor(float(tau) * (1 << cfg.acc_bits)))


def beat_schedules(vol: np.ndarray, vp: ViewPlan, cfg: Cube4Config, opts: dict) -> list:
    """Each pass's (BeatSchedule, TerminationRule) within its empty-space box
    (None: the pass has no frame); the block table is the whole volume's. MIP and MinIP
    with depth out end no ray: the passed depth is the held sample's slice, the last of
    equal values, which a later sample equal to the volume's extreme still moves (numerics.md §21)."""
    unknown = set(opts) - {"block", "lag", "tau", "terminate"}
    if unknown:
        raise ValueError(f"beat_skip: unknown keys {sorted(unknown)}")
    sc = vp.scene
    t0 = time.perf_counter()
    table = BlockTable.of(level_of(vol, sc), opts.get("block", 4),     # labelled words: by label
                          value_bits=cfg.voxel_bits if sc.labels is not None else None)
    bits = table.bits(vp.lut, sc.mode)
    table_s = time.perf_counter() - t0
    terminate = bool(opts.get("terminate", True)) and not (is_extremum(sc.mode) and sc.depth_threshold is not None)
    out = []
    for plan in vp.plans:
        if plan.trav is None:
            out.append(None)
            continue
        t1 = time.perf_counter()
        occ = frame_occupancy(bits, table.block, plan.trav)
        term = terminate and plan.trav.nj >= TERM_MIN_ROWS
        sched = BeatSchedule(plan.trav, cfg.pipelines, occ, opts.get("lag", LAG), terminate=term,
                             gra=sc.shaded and not sc.voxel_gradients)
        sched.table_s = table_s
        sched.stop_s = time.perf_counter() - t1      # the host's work per view: the rays' stops
        sched.block_bits = bits
        lv = level_of(vol, sc)
        rule = TerminationRule(sc.mode, int(opts.get("tau", 0)), 1 << cfg.acc_bits, int(lv.min()),
                               int(lv.max()), enabled=term, value_bits=cfg.voxel_bits)
        out.append((sched, rule))
    return out


def beat_view_stats(frames: list) -> dict:
    """The beats the view's frames ran and skipped (after they ran), and the front end's walk
    (all zero where no frame ran: nothing in the view can change a ray)."""
    tot: dict = BeatStats(0, 0, 0, 0, 0).as_dict()
    for fr in frames:
        if fr is None:
            continue
        st = beat_stats(fr[0], fr[0].table_s).as_dict()
        for k, v in st.items():
            if isinstance(v, dict):
                tot[k] = {r: tot.get(k, {}).get(r, 0) + c for r, c in v.items()}
            else:
                tot[k] = tot.get(k, 0) + v
        tot["table_s"] = st["table_s"]
    return tot


def golden_view(vol: np.ndarray, scene: Scene, cfg: Cube4Config, keep_streams: bool = False,
                progress: Progress | None = None, rects: bool = False,
                beat_skip: dict | None = None, schedules: list | None = None) -> tuple[ViewPlan, Frame, dict]:
    """One view through the bit-exact model: its plan, its frame (the passes' base planes
    placed and interleaved) and the stats of what it did; ``rects``: each frame computes
    only its slice rectangles (the specified finer schedule; stats ``rect_beats``);
    ``keep_streams``: the frame keeps the model's intermediate streams; ``beat_skip``:
    each frame skips beats and ends rays (cube4.beats; keys block, lag, tau, terminate;
    stats ``beats``); ``schedules``: a list that receives each pass's (BeatSchedule,
    TerminationRule) after the frame (None for a pass without a frame). A scene that leaves
    [render] skip out runs its default schedule on cfg.build (``scene.with_schedule``)."""
    scene = with_schedule(scene, None if cfg.build is None else dict(cfg.build), supersample=cfg.supersample)
    nz, ny, nx = vol.shape
    dims = (nx, ny, nz)
    trav, _ = setup_view(dims, scene, cfg)
    stats = view_stats("golden", dims, scene, cfg)
    stats["build"] = resolve_build(cfg, [scene])     # the build this frame models
    if keep_streams:
        # the streams are a verification aid, indexed by the whole traversal: one pass, the fixed schedule
        if scene.subpixel != 1:
            raise ValueError("keep_streams renders one pass: [render] subpixel must be 1")
        scene = replace(scene, skip=False)
    vp = plan_view(vol, scene, cfg)
    box_vol = crop_volume(memory_volume(vol, scene, cfg), trav)
    results, streams, depths = {}, {}, {}
    rects = rects or scene.schedule == "rects"
    if beat_skip is None and scene.schedule == "beats":
        beat_skip = {"tau": tau_fixed(scene.tau, cfg), "terminate": scene.terminate}
    frame_rects = pass_rects(vol, vp) if rects else [None] * len(vp.plans)
    geo = scene_geometry(scene, vp.cam)
    beat_frames = beat_schedules(vol, vp, cfg, beat_skip) if beat_skip is not None else None
    for n, (ps, plan) in enumerate(zip(vp.passes, vp.plans)):
        if plan.trav is None:       # nothing can change a ray: no frame
            continue
        sched, rule = beat_frames[n] if beat_frames else (None, None)
        sub = render_frame(plan.box_volume(box_vol), plan.trav, cfg, vp.lut, vp.rmap, keep_streams=keep_streams,
                           progress=progress, mode=scene.mode, shading=scene.shaded, clip=plan.clip,
                           vgrad=scene.voxel_gradients, rects=frame_rects[n], beats=sched, done=rule,
                           depth_t=depth_threshold(scene, cfg),
                           stop_m=None if geo is None else plan.box_stop(stop_slices(plan.whole, vp.cam, geo.z)),
                           gm=vp.gm, labels=scene.labels is not None)
        results[n] = (sub.baseplane, sub.pixels)
        if sub.depth_m is not None:
            depths[n] = sub.depth_m
        if keep_streams:
            streams = sub.streams
    if schedules is not None and beat_frames:
        schedules.extend(beat_frames)
    frame = assemble_view(vp, cfg, results, depths if scene.depth_threshold is not None else None)
    frame.streams = streams
    stats.update(trav_stats(trav))
    stats["baseplane_shape"] = list(frame.baseplane.shape[:2])     # the fine plane's with q > 1
    stats.update(schedule_stats(vp.plans, cfg, stats["build"]))
    stats["pixels"] = int(frame.pixels.size)
    if beat_frames:
        stats["beats"] = beat_view_stats(beat_frames)
    if rects:
        stats["rect_beats"] = sum(r.beats(cfg.pipelines) for r in frame_rects if r is not None)
        stats["rect_table_s"] = sum(r.table_s for r in frame_rects if r is not None)
        build = stats["build"]
        if not build.get("VGRAD", 0):   # the cycles a RECTS build of cube4_top takes (GRA's walk with GRA)
            shading = bool(build["SHADING"])
            ran = [replace(r, gra=shading) for r in frame_rects if r is not None]
            stats["predicted_cycles"] = sum(rect_frame_cycles(r, cfg.pipelines, shading, fall=has_falloff(build))
                                            for r in ran)
            stats["cycles_saved"] = stats["fixed_schedule_cycles"] - stats["predicted_cycles"]
            stats["rect_com_waits"] = sum(r.com_waits(cfg.pipelines) for r in ran)
    return vp, frame, stats

"""Empty-space skipping on real content: ``make skipping`` (``python -m
cube4_reports.skipping``) writes reports/skipping.md and reports/skipping.json (the run's
figures, from which ``--md-only`` rewrites the Markdown).

For each volume and a scene a user would pick, at several views, the box schedule of
``cube4.skip``: the box, its share of the voxels, the cycles per frame it takes (the
cycle formula with the box's dims, which tb/cube4_top holds the RTL to) against the
fixed schedule's and against n³/P, the host's time to build its tables, and whether the
image is the fixed schedule's bit for bit (the golden model renders both); and the slice
rectangles within the box: their cycles through cube4_top (predicted) and their image.
The issue's goal case (head:128, scene head, P = 8) also runs through the RTL, with the
box and with the rectangles: measured cycles against the prediction, and the image.

Then beat skipping and ray termination (``cube4.beats``, the golden model's
specification): for the same cases and opaque-surface scenes, the beats that run within
the box without and with termination, the front end's walk, the beats skipped by cause,
the image against the fixed schedule's, the threshold τ as a knob of error against beats,
and the block size against the host's table.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from pathlib import Path

import numpy as np
from tqdm import tqdm

from cube4.app.render import render, render_golden_view
from cube4.beats import DECIDE_RATES, LAG
from cube4.app.volumes import load_volume
from cube4.builds import BUILD_PARAMS
from cube4.config import resolve_build
from cube4.cycles import rect_frame_cycles
from cube4.host import config_for, golden_view, pass_rects, plan_view, schedule_stats
from cube4.scene import load_scene, with_view
from cube4.view import angles_from_direction, direction_from_angles

from . import fmax as fmax_store
from .markdown import REPO_ROOT, fmt_int, git_describe, md_table

P = 8
#: (volume, scene, what a user would look at)
CASES = [
    ("head:128", "head", "Shepp-Logan head phantom, translucent (the goal case)"),
    ("ml:128", "ml", "Marschner-Lobb, one iso-band"),
    ("sphere:128", "default", "antialiased sphere"),
    ("cube:128", "default", "cube of half the volume's side"),
    ("mri", "mri_mip", "nibabel example4d MRI, maximum intensity"),
    ("mri", "head", "nibabel example4d MRI, translucent composite"),
    ("mri_t1", "mri_mip", "nibabel anatomical T1, maximum intensity"),
]
#: the scene's own view and three others: (azimuth, elevation) offsets from it (the elevation's
#: offset turns towards the equator when the view is near a pole)
VIEW_STEPS = [(0.0, 0.0), (45.0, 0.0), (90.0, -10.0), (0.0, 70.0)]
GOAL = ("head:128", "head")
#: opaque surfaces (a skin-like transfer function, nearly opaque above the scalp's intensity)
#: on the real MRI of nibabel, natively and resampled to 128³, and on a phantom
OPAQUE_CASES = [
    ("mri", "mri_skin", "nibabel example4d MRI, skin surface"),
    ("mri:128", "mri_skin", "the same MRI resampled to 128³, skin surface"),
    ("sphere:128", "mri_skin", "antialiased sphere, the same opaque transfer function"),
]
OPAQUE_GOAL = ("mri:128", "mri_skin")
#: the termination threshold's sweep (a transmittance) and the block sizes compared
TAUS = [0.0, 1 / 1024, 1 / 256, 1 / 64, 1 / 16]
BLOCKS = [2, 4, 8]


def views(scene) -> list:
    az0, el0 = angles_from_direction(scene.direction)
    out = []
    for daz, del_ in VIEW_STEPS:
        el = el0 + (del_ if abs(el0 + del_) <= 89.0 else -del_)
        out.append(with_view(scene, direction_from_angles(az0 + daz, el)))
    return out


def measure(vol_spec: str, scene_name: str, check_images: bool) -> list[dict]:
    vol = load_volume(vol_spec)
    nz, ny, nx = vol.shape
    base_scene = dataclasses.replace(load_scene(scene_name), skip=True)     # the box (and its rectangles)
    rows = []
    for sc in views(base_scene):
        cfg = config_for(sc, P)
        build = resolve_build(cfg, [sc])
        vp = plan_view(vol, sc, cfg)
        trav = vp.trav
        st = schedule_stats(vp.plans, cfg, build)
        table_s = st["skip_table_s"]
        az, el = angles_from_direction(sc.direction)
        row = {"volume": vol_spec, "dims": [nx, ny, nz], "scene": scene_name, "mode": sc.mode,
               "azimuth": round(az, 1), "elevation": round(el, 1), "major": "xyz"[trav.major],
               "n3_over_p": nx * ny * nz / P, "table_s": table_s, **st}
        rects = pass_rects(vol, vp)
        row["rect_beats"] = sum(r.beats(P) for r in rects if r is not None)
        # the frames as cube4_top runs them on the scene's build (GRA's walk where it has GRA)
        gra, vgrad = bool(build["SHADING"]), bool(build["VGRAD"])
        ran = [dataclasses.replace(r, gra=gra) for r in rects if r is not None]
        row["rect_cycles"] = None if vgrad else sum(rect_frame_cycles(r, P, gra) for r in ran)
        row["rect_com_waits"] = None if vgrad else sum(r.com_waits(P) for r in ran)
        row["rect_table_s"] = sum(r.table_s for r in rects if r is not None)
        row["rect_fraction"] = float(np.mean([0.0 if r is None else r.fraction() * p.fraction
                                              for r, p in zip(rects, vp.plans)]))
        if check_images:
            on = render(vol, sc, cfg, "golden")
            off = render(vol, dataclasses.replace(sc, skip=False), cfg, "golden")
            part = render_golden_view(vol, sc, cfg, rects=True)
            row["bit_identical"] = bool(np.array_equal(on.frame.baseplane, off.frame.baseplane))
            row["rect_bit_identical"] = bool(np.array_equal(part.frame.baseplane, off.frame.baseplane))
        rows.append(row)
    return rows


def beat_rows(vol_spec: str, scene_name: str) -> list[dict]:
    """Beat skipping on one case's four views: without and with termination (τ = 0)."""
    vol = load_volume(vol_spec)
    nz, ny, nx = vol.shape
    rows = []
    for sc in views(load_scene(scene_name)):
        cfg = config_for(sc, P)
        _, fixed, st = golden_view(vol, dataclasses.replace(sc, skip=False), cfg)
        _, free, st_free = golden_view(vol, sc, cfg, beat_skip={"terminate": False})
        _, ended, st_end = golden_view(vol, sc, cfg, beat_skip={})
        _, boxed, st_box = golden_view(vol, dataclasses.replace(sc, skip=True), cfg)
        az, el = angles_from_direction(sc.direction)
        rows.append({
            "volume": vol_spec, "dims": [nx, ny, nz], "scene": scene_name, "mode": sc.mode,
            "azimuth": round(az, 1), "elevation": round(el, 1), "n3_over_p": nx * ny * nz / P,
            "box_cycles": st_box["predicted_cycles"], "fixed_cycles": st["predicted_cycles"],
            "free": st_free["beats"], "ended": st_end["beats"],
            "identical": bool(np.array_equal(free.baseplane, fixed.baseplane)
                              and np.array_equal(ended.baseplane, fixed.baseplane))})
    return rows


def tau_rows(vol_spec: str, scene_name: str) -> list[dict]:
    """The threshold τ on one case's own view: beats and the change of the base plane."""
    vol = load_volume(vol_spec)
    sc = load_scene(scene_name)
    cfg = config_for(sc, P)
    exact = None
    rows = []
    for tau in TAUS:
        _, fr, st = golden_view(vol, dataclasses.replace(sc, skip="beats", tau=tau), cfg)
        base = fr.baseplane_float
        exact = base if exact is None else exact
        err = base - exact
        rmse = float(np.sqrt(np.mean(err * err)))
        rows.append({"tau": tau, "beats": st["beats"], "n3_over_p": vol.size / P, "rmse": rmse,
                     "max_abs": float(np.abs(err).max()),
                     "psnr": float("inf") if rmse == 0 else float(-20 * np.log10(rmse))})
    return rows


def block_rows(vol_spec: str, scene_name: str) -> list[dict]:
    """The block size on one case's own view: the table and the beats."""
    vol = load_volume(vol_spec)
    sc = load_scene(scene_name)
    cfg = config_for(sc, P)
    rows = []
    for b in BLOCKS:
        _, _, st = golden_view(vol, sc, cfg, beat_skip={"block": b})
        entries = int(np.prod([-(-n // b) for n in vol.shape]))
        rows.append({"block": b, "entries": entries, "beats": st["beats"], "n3_over_p": vol.size / P})
    return rows


def rtl_goal_frame(rects: bool = False) -> dict:
    """The goal case's scene view through the RTL, with the box schedule or (``rects``)
    the slice rectangles within it."""
    from cube4_sim.engine import register

    register()
    vol_spec, scene_name = GOAL
    vol = load_volume(vol_spec)
    sc = load_scene(scene_name)
    cfg = config_for(sc, P)
    res = render(vol, dataclasses.replace(sc, skip="rects" if rects else True), cfg, "rtl",
                 progress=sys.stderr.isatty())
    gold = render(vol, dataclasses.replace(sc, skip=False), cfg, "golden")
    return {"cycles": res.stats["cycles"], "predicted_cycles": res.stats["predicted_cycles"],
            "fixed_schedule_cycles": res.stats["fixed_schedule_cycles"],
            "bit_identical_to_fixed_golden": bool(np.array_equal(res.frame.baseplane, gold.frame.baseplane)),
            "sim_wall_s": res.stats["sim_wall_s"]}


#: the schedules of the beat section's RTL frames: (label, scene changes)
RTL_SCHEDULES = [("box", {"skip": True}), ("beats", {"skip": "beats", "terminate": False}),
                 ("beats + termination", {"skip": "beats"})]


def rtl_beat_frames() -> list[dict]:
    """The goal cases' own views (head:128 translucent, the MRI's opaque surface) through the
    RTL, P = 8, with the box schedule, beat skipping alone and beat skipping with ray
    termination (each on the smallest build the scene needs): cycles, the beats that ran
    as cube4_top counted them, and the base plane against the golden fixed schedule's."""
    from cube4_sim.engine import register

    register()
    out = []
    for vol_spec, scene_name in (GOAL, OPAQUE_GOAL):
        vol = load_volume(vol_spec)
        sc = load_scene(scene_name)
        cfg = config_for(sc, P)
        gold = render(vol, dataclasses.replace(sc, skip=False), cfg, "golden")
        for label, change in RTL_SCHEDULES:
            res = render(vol, dataclasses.replace(sc, **change), cfg, "rtl", progress=sys.stderr.isatty())
            st = res.stats
            out.append({"volume": vol_spec, "scene": scene_name, "schedule": label, "cycles": st["cycles"],
                        "n3_over_p": vol.size / P, "beats": st.get("beats"),
                        "build": {k: v for k, v in st["build"].items() if v}, "widths": cfg.widths(),
                        "identical": bool(np.array_equal(res.frame.baseplane, gold.frame.baseplane))})
    return out


def frame_build(f: dict) -> tuple[dict, dict]:
    """A beat-section frame's build (every option: the frame lists those that are on) and
    word widths (a run from before they were kept: the scene's default configuration's)."""
    build = {k: int(f["build"].get(k, 0)) for k in BUILD_PARAMS}
    widths = f.get("widths") or config_for(load_scene(f["scene"]), P).widths()
    return build, widths


def rtl_beat_lines(frames: list[dict], measured: list[fmax_store.Measured]) -> list[str]:
    """The beat section's RTL table: cycles and frame times side by side, each frame's time
    at the measured Fmax of the build that ran it (cube4_reports.fmax), blank where that
    build was never placed and routed."""
    if not frames:
        return []
    body, sources = [], {}
    for f in frames:
        m = fmax_store.lookup(measured, P, *frame_build(f))
        nofit = m is not None and not m.fits
        m = None if nofit else m
        if m:
            sources.setdefault(m.note(), len(sources) + 1)
        b = f["beats"] or {}
        body.append([f"{f['volume']}", f["scene"], f["schedule"], fmt_int(f["cycles"]),
                     _frac(f["cycles"], f["n3_over_p"]),
                     _frac(b["run_beats"], f["n3_over_p"]) if b else "",
                     f"{m.fmax_mhz:.1f} MHz [{sources[m.note()]}]" if m else ("does not fit" if nofit else "not measured"),
                     f"{f['cycles'] / m.fmax_mhz / 1000:.2f} ms" if m else "",
                     _image(f["identical"])])
    builds = sorted({", ".join(f"{k}={v}" for k, v in f["build"].items()) for f in frames})
    notes = [f"- [{i}] {note}" for note, i in sources.items()]
    return [
        "**Through the RTL** (P = 8, each case's own view; `cube4 render <volume> --scene <scene> --engine rtl "
        "--stats s.json` with `--beats`, and `--beats --no-terminate` for beat skipping alone): cycles "
        "measured; 'beats run' as `cube4_top` counted them (the golden frame's count: `tb/cube4_top` holds "
        "them equal); frame time = cycles / the Fmax of the build that ran it (its options, word widths and "
        "P = 8), placed and routed out of context on the ECP5-85F (`python -m cube4_reports.fpga --p 8 "
        "--build <options> --md reports/fpga_<name>.md`, whose results beside it in reports/ this report "
        "reads: the median of the seeds); 'not measured' where that build was never placed and routed (no "
        "other build's clock is borrowed). Builds: " + "; ".join(builds)
        + ". 'image': the base plane against the golden fixed schedule's, bit for bit.", "",
        md_table(["volume", "scene", "schedule", "cycles", "cycles / (n³/P)", "beats run", "Fmax", "frame time",
                  "image"], body, "lllrrrrrl"), ""] + (["Fmax measured:", ""] + notes + [""] if notes else [])


def rtl_dram_frames() -> list[dict]:
    """The goal case's view through the RTL with its voxel memory in the simulated DRAM
    (the ``rtl-dram`` engine), with the box schedule and the fixed one: cycles beside the
    ideal memory's, bursts read, bandwidth, stalls by cause; the base plane against the
    golden fixed schedule's."""
    from cube4_sim.engine import register

    register()
    vol_spec, scene_name = GOAL
    vol = load_volume(vol_spec)
    sc = load_scene(scene_name)
    cfg = config_for(sc, P)
    gold = render(vol, dataclasses.replace(sc, skip=False), cfg, "golden")
    out = []
    for schedule in ("box", "fixed"):
        res = render(vol, dataclasses.replace(sc, skip=(schedule == "box")), cfg, "rtl-dram",
                     progress=sys.stderr.isatty())
        out.append({"schedule": schedule, **res.stats["dram"],
                    "bit_identical_to_fixed_golden": bool(np.array_equal(res.frame.baseplane, gold.frame.baseplane)),
                    "sim_wall_s": res.stats["sim_wall_s"]})
    return out


#: the front end's units measured by make skipping: (volume, scene) and the decision rates
FRONT_END_CASES = [GOAL, OPAQUE_GOAL]
FRONT_END_RATES = (1, 2)


def rtl_front_end() -> list[dict]:
    """The beat schedule's front end (``cube4_cfb_skip``: decisions, the walk, S = 1) at
    P = 8 on the goal cases' own views, deciding 1 and 2 beats a cycle: its cycles from
    start to the last beat, the golden model's ``decided_cycles`` beside them; each run
    checks every walk beat and position bit against the golden schedule."""
    import tempfile

    from cube4.beats import decided_cycles, walk_beats
    from cube4_sim.beat_frames import view_frame
    from cube4_sim.runner import run_test
    from cube4_sim.sources import rtl_sources

    bench = REPO_ROOT / "tb" / "cube4_cfb_skip" / "test_cube4_cfb_skip.py"
    rows = []
    for vol_spec, scene_name in FRONT_END_CASES:
        bf = view_frame(vol_spec, scene_name, P)
        n3p = load_volume(vol_spec).size / P
        for rate in FRONT_END_RATES:
            with tempfile.TemporaryDirectory() as tmp:
                out = Path(tmp) / "measure.json"
                spec = {"volume": vol_spec, "scene": scene_name, "out": str(out)}
                run_test(top="cube4_cfb_skip", sources=rtl_sources(),
                         params={"P": P, "MAX_DIM": 128, "RATE": rate}, test_module=bench,
                         testcase="test_measure", extra_env={"CUBE4_SKIP_MEASURE": json.dumps(spec)})
                got = json.loads(out.read_text())
            rows.append({"volume": vol_spec, "scene": scene_name, "rate": rate, "n3_over_p": n3p,
                         "cycles": got["cycles"], "decided_cycles": decided_cycles(bf.sched, rate),
                         "walk_beats": walk_beats(bf.sched)})
    return rows


def front_end_lines(rows: list[dict]) -> list[str]:
    if not rows:
        return []
    body = [[f"{r['volume']}, scene {r['scene']}", str(r["rate"]), fmt_int(r["cycles"]),
             f"{r['cycles'] / r['n3_over_p']:.3f}", fmt_int(r["decided_cycles"]),
             f"{r['decided_cycles'] / r['n3_over_p']:.3f}", f"{r['walk_beats'] / r['n3_over_p']:.3f}"]
            for r in rows]
    return ["**The front end's units in RTL** (`cube4_cfb_skip`: `cube4_cfb_decide`, `cube4_ram_fifo`, "
            f"`cube4_cfb_beats`; S = 1, P = 8, MAX_DIM = 128, lag {LAG}; the bench `tb/cube4_cfb_skip` test_measure "
            "plays the host and COM, COM reporting each slice right after its last beat): a frame's cycles from "
            "start to its last walk beat, deciding r beats a cycle, beside the golden model's "
            "`beats.decided_cycles` (which leaves out the two slices decided before the walk starts and the "
            "pipeline's fill) and the walk's beats. Every walk beat and position bit matched the golden "
            "schedule. These are the front end's cycles alone; the frames through the whole design are in "
            "the table above.", "",
            md_table(["case (its own view)", "r", "cycles", "of n³/P", "golden decided_cycles", "of n³/P",
                      "walk beats, of n³/P"], body, "lrrrrrr"), ""]


def dram_lines(frames: list[dict], n3p: float | None) -> list[str]:
    """The goal case with the DRAM: a table, box against fixed."""
    if not frames:
        return []
    rows = [[f["schedule"], fmt_int(f["ideal_memory_cycles"]), fmt_int(f["cycles"]), f"{f['ideal_over_dram']:.3f}",
             "—" if not n3p else f"{f['cycles'] / n3p:.3f}", fmt_int(f["bursts_read"]), f"{f['mb_per_s']:.0f}",
             f"{fmt_int(f['stall_refresh'])} / {fmt_int(f['stall_row_open'])} / {fmt_int(f['stall_bandwidth'])}",
             _image(f["bit_identical_to_fixed_golden"])] for f in frames]
    f0 = frames[0]
    return [f"**With the voxel memory in DRAM** (head:128, scene head, P = {P}, `cube4 render head:128 --scene head "
            f"--engine rtl-dram --pipelines {P} --stats s.json`, add `--no-skip` for the fixed schedule): "
            f"cube4_top with `DRAM = 1`, the ECPIX-5's {f0['part']} behind LiteDRAM's controller at "
            f"{f0['controller_mhz']:.0f} MHz, the pipelines at {f0['pipeline_mhz']} MHz (reports/dram.md). The "
            "ideal memory's cycles are the golden prediction (the on-chip build's, to the cycle); the stalls "
            "(DRAM cycles − ideal) are split by cause, an estimate from the controller's commands (docs/reports.md). "
            "Skipping saves DRAM traffic as well as cycles: what the box leaves out is never read (bursts "
            f"read, below). At P = {P} the DRAM's bandwidth (peak {f0['peak_mb_per_s']:.0f} MB/s) limits both "
            "schedules.", "",
            md_table(["schedule", "ideal-memory cycles", "cycles with the DRAM", "ideal / DRAM", "/ (n³/P)",
                      "bursts read", "MB/s", "stalls: refresh / row open / bandwidth", "image"], rows, "lrrrrrrrl"),
            ""]


def _pct(x: float) -> str:
    return f"{100 * x:.0f}%"


def _image(same: bool | None) -> str:
    return "not checked" if same is None else ("identical" if same else "DIFFERENT")


def _rect_cycles(r: dict) -> str:
    if r["rect_cycles"] is None:
        return "— (voxel gradients)"
    return fmt_int(r["rect_cycles"]) + ("" if r["rect_com_waits"] == 0 else f" (+{r['rect_com_waits']} waits)")


def write_md(rows: list[dict], rtl: dict | None, meta: dict, rtl_rects: dict | None = None,
             rtl_dram: list[dict] | None = None) -> str:
    head = ["volume (dims)", "scene (mode)", "view az, el", "box traversed", "voxels", "cycles",
            "fixed schedule", "cycles / (n³/P)", "saved", "host tables", "image",
            "rectangles: samples", "cycles", "cycles / (n³/P)", "tables", "image"]
    body = []
    for r in rows:
        box = "—" if r["skip_box"] is None else "×".join(str(d) for d in r["skip_box"]["dims"])
        body.append([
            f"{r['volume']} ({'×'.join(map(str, r['dims']))})", f"{r['scene']} ({r['mode']})",
            f"{r['azimuth']:.0f}, {r['elevation']:.0f}", box, _pct(r["skip_fraction"]),
            fmt_int(r["predicted_cycles"]), fmt_int(r["fixed_schedule_cycles"]),
            f"{r['predicted_cycles'] / r['n3_over_p']:.3f}", _pct(r["cycles_saved"] / r["fixed_schedule_cycles"]),
            f"{1000 * r['table_s']:.0f} ms", _image(r.get("bit_identical")),
            _pct(r["rect_fraction"]), _rect_cycles(r),
            "—" if r["rect_cycles"] is None else f"{r['rect_cycles'] / r['n3_over_p']:.3f}",
            f"{1000 * r['rect_table_s']:.0f} ms", _image(r.get("rect_bit_identical"))])
    goal = [r for r in rows if (r["volume"], r["scene"]) == GOAL]
    lines = [
        "# Empty-space skipping on real content",
        "",
        f"Generated by `make skipping` (`python -m cube4_reports.skipping`) on commit {meta['git']}, "
        f"P = {P}. Each frame traverses only the box that can change a ray (`cube4.skip`, "
        "docs/numerics.md §15); its cycles are the cycle formula with the box's dims "
        "(docs/architecture.md), which `tb/cube4_top` holds the RTL to, cycle for cycle. "
        "\"image\": the golden model's base plane with the box schedule against the fixed "
        "schedule's, bit for bit. \"host tables\": the host's time to find the box (cell "
        "ranges, the LUT's prefix sum, the box), in Python on this machine. \"rectangles\": "
        "the slice rectangles within that box (`cube4.slices`, docs/numerics.md §18; `cube4 render "
        "--rects`): the share of the volume's samples they traverse, the cycles `cube4_top` takes "
        "for them on the scene's build (`cube4.cycles.rect_frame_cycles`: each slice's walked rows "
        "and partial beams, with GRA's walk where the build has GRA, flush beams, empty passes, GRA's "
        "own steps, the fill; exact when no beat waits in COM, which `tb/cube4_top` holds the RTL "
        "to; \"+N waits\" where N beats would), the host's time to find them, and the golden "
        "model's base plane with them against the fixed schedule's.",
        "",
        md_table(head, body, "lllrrrrrrrlrrrrl"),
        "",
    ]
    if goal:
        g = goal[0]
        lines += [f"**Goal** (head:128, scene head, P = 8, at most n³/(2P) = {fmt_int(g['n3_over_p'] / 2)} "
                  f"cycles): the scene's view takes {fmt_int(g['predicted_cycles'])} cycles, "
                  f"{g['predicted_cycles'] / g['n3_over_p']:.3f} of n³/P with the box (over the four views "
                  f"{min(r['predicted_cycles'] for r in goal) / g['n3_over_p']:.3f} to "
                  f"{max(r['predicted_cycles'] for r in goal) / g['n3_over_p']:.3f}): a box cannot follow "
                  "the head's rounded shape. With the slice rectangles it takes "
                  f"{fmt_int(g['rect_cycles'])} cycles, {g['rect_cycles'] / g['n3_over_p']:.3f} of n³/P "
                  f"(over the four views {min(r['rect_cycles'] for r in goal) / g['n3_over_p']:.3f} to "
                  f"{max(r['rect_cycles'] for r in goal) / g['n3_over_p']:.3f}).", ""]
    if rtl is not None:
        lines += [f"**Through the RTL** (head:128, scene head, P = 8, `cube4 render head:128 --scene head "
                  f"--engine rtl --pipelines 8 --stats s.json`): {fmt_int(rtl['cycles'])} cycles measured, "
                  f"{fmt_int(rtl['predicted_cycles'])} predicted, {fmt_int(rtl['fixed_schedule_cycles'])} for "
                  f"the fixed schedule; base plane "
                  f"{'identical to' if rtl['bit_identical_to_fixed_golden'] else 'DIFFERENT from'} the golden "
                  f"fixed schedule's.", ""]
    if rtl_rects is not None:
        n3p = goal[0]["n3_over_p"] if goal else None
        lines += [f"**Slice rectangles through the RTL** (head:128, scene head, P = 8, `cube4 render head:128 "
                  f"--scene head --engine rtl --pipelines 8 --rects --stats s.json`): "
                  f"{fmt_int(rtl_rects['cycles'])} cycles measured, {fmt_int(rtl_rects['predicted_cycles'])} "
                  "predicted" + (f", {rtl_rects['cycles'] / n3p:.3f} of n³/P" if n3p else "")
                  + f"; base plane {'identical to' if rtl_rects['bit_identical_to_fixed_golden'] else 'DIFFERENT from'}"
                  " the golden fixed schedule's.", ""]
    lines += dram_lines(rtl_dram or [], goal[0]["n3_over_p"] if goal else None)
    lines += ["No CT volume ships in a PyPI package that I found: pydicom's test files hold one CT slice "
              "(CT_small.dcm) and pydicom-data's enhanced CT two frames (eCT_Supplemental.dcm, 2×512×512), "
              "so the real content here is the two MRI volumes of nibabel.", ""]
    return "\n".join(lines)


def _frac(x: float, n3p: float) -> str:
    return f"{x / n3p:.3f}"


def write_beats_md(rows: list[dict], taus: list[dict], blocks: list[dict], front: list[dict] | None = None,
                   rtl: list[dict] | None = None, measured: list | None = None) -> str:
    rates = [r for r in DECIDE_RATES if r > 1]
    head = ["volume (dims)", "scene (mode)", "view az, el", "box", "beats run", "+ termination",
            "front-end walk", *[f"deciding {r}/cycle" for r in rates], "skipped: empty", "skipped: rays ended",
            "host table", "host stops", "image"]
    body = []
    for r in rows:
        n3p, f, e = r["n3_over_p"], r["free"], r["ended"]
        body.append([f"{r['volume']} ({'×'.join(map(str, r['dims']))})", f"{r['scene']} ({r['mode']})",
                     f"{r['azimuth']:.0f}, {r['elevation']:.0f}", _frac(r["box_cycles"], n3p),
                     _frac(f["run_beats"], n3p), _frac(e["run_beats"], n3p), _frac(e["walk_beats"], n3p),
                     *[_frac(e["decided_cycles"][str(r)], n3p) for r in rates],
                     _pct(e["skipped_empty"] / max(1, e["box_beats"])),
                     _pct(e["skipped_terminated"] / max(1, e["box_beats"])),
                     f"{1000 * e['table_s']:.0f} ms", f"{1000 * e['stop_s']:.0f} ms", _image(r["identical"])])
    lines = [
        "## Beat skipping and ray termination (golden model)",
        "",
        "The specification of `cube4.beats` (docs/numerics.md §19; `cube4 render --beats --engine golden`), "
        f"within each frame's box, P = 8, blocks of 4³ voxels, lag {LAG}, τ = 0. Every figure is a share of "
        "n³/P beats: 'box' the box schedule's cycles (as above); 'beats run' the sample beats that run "
        "without termination; '+ termination' with it; 'front-end walk' the beats the front end walks "
        "with termination (what runs and the voxel beats it reads: rows j + 1, partial beams pb + 1). The "
        "walk is the specification's figure for a front end that passes over a skipped beat in no cycle; "
        "'deciding r/cycle' the cycles of one that decides r beats a cycle (`beats.decided_cycles`: per "
        "slice the larger of its walk and its NJ·NB beats / r); "
        "the RTL's measured cycles follow the table. "
        "'skipped': shares of the box's beats, by cause. 'host table': the block table for the "
        "transfer function (value ranges and bits), once per volume and LUT, not per view. 'host stops': "
        "per view, each ray's stop (the slice after the last in which its sample may count, written into "
        "depth in's stop table; a ray that reaches it is done). 'image': the "
        "base plane with and without termination against the fixed schedule's, bit for bit.",
        "",
        md_table(head, body, "lll" + "r" * (len(head) - 4) + "l"),
        "",
    ]
    if taus:
        lines += [f"**τ as a knob** ({OPAQUE_GOAL[0]}, scene {OPAQUE_GOAL[1]}, its own view; "
                  "`cube4 render … --beats --tau T`): a ray ends once its transmittance is at most τ. "
                  "Error: the base plane (premultiplied RGBA in [0, 1]) against τ = 0's.", "",
                  md_table(["τ", "beats run", "front-end walk", "skipped: rays ended", "RMSE", "max |error|",
                            "PSNR"],
                           [[f"{t['tau']:.5f}" if t["tau"] else "0 (exact)",
                             _frac(t["beats"]["run_beats"], t["n3_over_p"]),
                             _frac(t["beats"]["walk_beats"], t["n3_over_p"]),
                             _pct(t["beats"]["skipped_terminated"] / max(1, t["beats"]["box_beats"])),
                             f"{t['rmse']:.2e}", f"{t['max_abs']:.2e}",
                             "exact" if t["psnr"] == float("inf") else f"{t['psnr']:.1f} dB"] for t in taus],
                           "lrrrrrr"), ""]
    if blocks:
        lines += [f"**Block size** ({GOAL[0]}, scene {GOAL[1]}, its own view): the table's entries (one "
                  "bit each per transfer function; two value ranges each per volume) against the beats.", "",
                  md_table(["block", "entries", "beats run", "front-end walk", "host table"],
                           [[f"{b['block']}³", fmt_int(b["entries"]), _frac(b["beats"]["run_beats"], b["n3_over_p"]),
                             _frac(b["beats"]["walk_beats"], b["n3_over_p"]),
                             f"{1000 * b['beats']['table_s']:.0f} ms"] for b in blocks], "lrrrr"), ""]
    lines += rtl_beat_lines(rtl or [], measured or [])
    lines += front_end_lines(front or [])
    goal = [r for r in rows if (r["volume"], r["scene"]) == GOAL]
    opaque = [r for r in rows if (r["volume"], r["scene"]) == OPAQUE_GOAL]
    if goal and opaque:
        g, o = goal[0], opaque[0]
        lines += [f"**Against the goals** (P = 8): {GOAL[0]}, scene {GOAL[1]}: "
                  f"{g['ended']['walk_beats'] / g['n3_over_p']:.3f} of n³/P walked "
                  f"({g['ended']['run_beats'] / g['n3_over_p']:.3f} run; goal 0.40); {OPAQUE_GOAL[0]}, scene "
                  f"{OPAQUE_GOAL[1]} at τ = 0: {o['ended']['walk_beats'] / o['n3_over_p']:.3f} walked "
                  f"({o['ended']['run_beats'] / o['n3_over_p']:.3f} run; goal 0.15); a front end that decides "
                  + ", ".join(f"{r} beats a cycle takes {g['ended']['decided_cycles'][str(r)] / g['n3_over_p']:.3f} "
                              f"and {o['ended']['decided_cycles'][str(r)] / o['n3_over_p']:.3f}"
                              for r in DECIDE_RATES) + ". What stops finer: a beat "
                  "runs when one of its P lanes holds a running ray, and the rays cross the lanes obliquely "
                  "(the samples of running rays, packed into full beats, would take "
                  f"{g['ended']['ray_samples'] / P / g['n3_over_p']:.3f} and "
                  f"{o['ended']['ray_samples'] / P / o['n3_over_p']:.3f} of n³/P); a ray runs every slice "
                  "from its first sample that may count to its stop, through the empty slices between (one "
                  "interval per ray, as COM needs), and lag slices beyond the slice where COM found it done; "
                  "the block table's margin of two voxels; and the walk's extra row and partial beam per "
                  "running beat (docs/numerics.md §19).", ""]
    return "\n".join(lines)


def parse_args(argv):
    ap = argparse.ArgumentParser(prog="python -m cube4_reports.skipping", description=__doc__.splitlines()[0])
    ap.add_argument("--no-rtl", action="store_true", help="leave out the RTL frames")
    ap.add_argument("--no-dram", action="store_true", help="leave out the RTL frames with the DRAM (about 4 min)")
    ap.add_argument("--no-images", action="store_true", help="do not render both schedules to compare images")
    ap.add_argument("--no-beats", action="store_true", help="leave out beat skipping and ray termination")
    ap.add_argument("--md-only", action="store_true",
                    help="rewrite skipping.md from the last run's skipping.json in --out (e.g. after a "
                         "build's Fmax was measured: reports/fpga*.json)")
    ap.add_argument("--out", default=str(REPO_ROOT / "reports"), help="folder for skipping.md and skipping.json")
    return ap.parse_args(argv)


def write_reports(dest: Path, data: dict) -> None:
    """skipping.md from a run's figures (``data``: what skipping.json holds)."""
    dest.mkdir(parents=True, exist_ok=True)
    md = write_md(data["rows"], data["rtl"], data["meta"], data["rtl_rects"], data["rtl_dram"])
    if data["beats"]:
        md += "\n" + write_beats_md(data["beats"], data["taus"], data["blocks"], data["front_end"],
                                    data.get("rtl_beats"), fmax_store.load())
    (dest / "skipping.md").write_text(md)
    print(f"skipping: {dest / 'skipping.md'}")


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    saved = Path(args.out) / "skipping.json"
    if args.md_only:
        if not saved.exists():
            raise SystemExit(f"skipping: --md-only needs {saved} (run make skipping first)")
        data = json.loads(saved.read_text())
        write_reports(Path(args.out), data)
        return 0
    rows = []
    for vol_spec, scene_name, _ in tqdm(CASES, desc="skipping", unit="volume", disable=not sys.stderr.isatty()):
        rows.extend(measure(vol_spec, scene_name, not args.no_images))
    brows, taus, blocks = [], [], []
    if not args.no_beats:
        for vol_spec, scene_name, _ in tqdm(CASES + OPAQUE_CASES, desc="beats", unit="volume",
                                            disable=not sys.stderr.isatty()):
            brows.extend(beat_rows(vol_spec, scene_name))
        taus, blocks = tau_rows(*OPAQUE_GOAL), block_rows(*GOAL)
    rtl = None if args.no_rtl else rtl_goal_frame()
    rtl_rects = None if args.no_rtl else rtl_goal_frame(rects=True)
    rtl_dram = None if (args.no_rtl or args.no_dram) else rtl_dram_frames()
    front = [] if (args.no_rtl or args.no_beats) else rtl_front_end()
    rtl_beats = [] if (args.no_rtl or args.no_beats) else rtl_beat_frames()
    meta = {"git": git_describe(("rtl", "golden", "sim"))}
    data = {"meta": meta, "rows": rows, "rtl": rtl, "rtl_rects": rtl_rects, "rtl_dram": rtl_dram,
            "front_end": front, "beats": brows, "taus": taus, "blocks": blocks, "rtl_beats": rtl_beats}
    saved.parent.mkdir(parents=True, exist_ok=True)
    saved.write_text(json.dumps(data, indent=1) + "\n")
    write_reports(Path(args.out), data)
    return 0


if __name__ == "__main__":
    sys.exit(main())

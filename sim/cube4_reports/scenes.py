"""`make scenes`: every built-in scene on the smallest build it needs, beside the full build.

For each built-in scene (its mode, shading, crop box and cut plane) the build that
``cube4 render --engine rtl`` chooses by default (``cube4.config.scene_build``): which of
SHADING (GRA, reflectance map, shading multipliers), COMPOSITING (COM's multipliers),
EXTREMUM (COM's comparators) and CLIP (window and cut plane) it keeps, and whether its
gradient comes from GRA or from the voxels (VGRAD), and its word widths (the
supersampling's MAX_SS_LOG2). For every distinct build and the full one:

* NAND2 equivalents per unit, flip-flops and memory bits (the generic-gate synthesis of
  ``make gates``, cube4_top at P = 8, MAX_DIM = 128);
* on the ECP5-85F: LUTs, DSPs, EBRs and Fmax, the median of three nextpnr seeds at P = 8,
  as measured by ``python -m cube4_reports.fpga`` (its results committed under reports/;
  cube4_reports.fmax finds each build's), "not measured" for a build never placed and
  routed, with the command that measures it;

and for every scene: cycles per frame on its build and on the full build, the frame
time at the build's measured Fmax, and the golden engine's image error against the
float64 reference (PSNR over premultiplied RGBA), with what the smaller build saves. A
scene runs its default schedule (``Scene.schedule``): the beat schedule, whose cycles
depend on the content and are measured, through the RTL on the scene's build (its base
plane checked against the golden engine's). The full build (no BEATS) runs the box, whose
cycles are the formula of ``cube4.cycles`` (which tb/cube4_top holds every build to). The
mode matrix runs every scene's box schedule.

    python -m cube4_reports.scenes               # gates, cycles, error; ECP5 from reports/ (~32 min here)
    python -m cube4_reports.scenes --place       # and place and route every build not measured yet
                                                 # (3 seeds each, about 40 min a build), then the report

Results: reports/scenes.json (the run, from which --md-only rewrites the Markdown) and
reports/scenes.md; --place writes each build's
place and route to reports/fpga/<build>.{md,json}.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import time

import numpy as np

from cube4.builds import BUILD_PARAMS, FULL_BUILD, build_name, build_tag, named
from cube4.config import Cube4Config, scene_build
from cube4.app.render import render
from cube4.host import config_for, image_metrics, plan_view, schedule_stats
from cube4.scene import builtin_scene_names, load_scene
from cube4.app.volumes import load_volume

from cube4.app.labelmaps import with_labels

from . import fmax as fmax_store
from . import fpga, gates
from .markdown import fmt_int, git_describe, last_commit, md_table
from .synth import DOC_REPORTS, cli_main, design_digest, progress, write_report

TAG = "scenes"
P = 8
MAX_DIM = 128
DEPTH = 1024
#: the seeds of a build's place and route (--place): the median of three
SEEDS = "1,2,3"
# the volume each built-in scene is made for
SCENE_VOLUME = {"default": "sphere:64", "ml": "ml:41", "mri_mip": "mri", "mri_skin": "mri:64,48,24",
                "mri_t1_tissue": "mri_t1", "mri_needle": "mri",
                "mri_boundaries": "mri", "colin_lobes": "colin"}
UNIT_COLS = ["CFB", "TRI", "GRA", "SHA", "COM", "RING"]


def volume_of(scene: str) -> str:
    return SCENE_VOLUME.get(scene, "head:64")


def scene_volume(name: str, scene) -> np.ndarray:
    """The scene's volume; a scene with labels: the labelled words with its label map."""
    spec = volume_of(name)
    return with_labels(load_volume(spec), spec, scene, config_for(scene).voxel_bits)


DEFAULT_WIDTHS = Cube4Config().widths()


def build_key(build: dict, widths: dict | None = None) -> tuple:
    """A hardware build: its options and its word widths (default: cube4_top's)."""
    w = {**DEFAULT_WIDTHS, **(widths or {})}
    return tuple(build[k] for k in BUILD_PARAMS) + tuple(w[k] for k in DEFAULT_WIDTHS)


full_name = fmax_store.build_label


def image_digest(image: np.ndarray) -> str:
    """The first 12 hex digits of the SHA-256 of an image's array (dtype, shape, bytes):
    a scene's picture changed exactly when this did."""
    a = np.ascontiguousarray(image)
    h = hashlib.sha256(f"{a.dtype.str}{a.shape}".encode())
    h.update(a.tobytes())
    return h.hexdigest()[:12]


def scene_rows(names: list[str]) -> list[dict]:
    """Per scene: its build, cycles on it and on the full build, and the image error."""
    rows = []
    for name in names:
        scene = load_scene(name)
        spec = volume_of(name)
        vol = scene_volume(name, scene)
        cfg = config_for(scene, pipelines=P)
        build = scene_build([scene])
        progress(TAG, f"{name} on {spec}: golden and reference renders (area and point truths) ...")
        gold = render(vol, scene, cfg, "golden")
        ref = render(vol, scene, cfg, "reference")
        m = image_metrics(gold.image, ref.image)
        mp = image_metrics(gold.image, render(vol, scene, cfg, "reference-point").image)
        plans = plan_view(vol, scene, cfg).plans
        own = schedule_stats(plans, cfg, build)
        cycles = own["predicted_cycles"]
        if scene.schedule == "beats":
            cycles = beat_cycles(vol, scene, cfg, gold.frame.baseplane, name)
        # the full build runs the box; a scene with voxel gradients does not run on it (it has GRA instead)
        full = None if build["VGRAD"] else schedule_stats(plans, cfg, FULL_BUILD)
        rows.append({"scene": name, "volume": spec, "mode": scene.mode, "shaded": scene.shaded,
                     "crop": None if scene.crop is None else [list(c) for c in scene.crop],
                     "cut": scene.cut is not None, "build": build, "widths": cfg.widths(), "gradient": scene.gradient,
                     "schedule": "beats" if scene.schedule == "beats" else "box",
                     "cycles": cycles, "cycles_full": None if full is None else full["predicted_cycles"],
                     "cycles_fixed": own["fixed_schedule_cycles"],
                     "psnr_db": m["psnr"] if np.isfinite(m["psnr"]) else None, "rmse": m["rmse"],
                     "psnr_point_db": mp["psnr"] if np.isfinite(mp["psnr"]) else None,
                     "truth_k": ref.stats["truth_k"], "truth_change": ref.stats["truth_change"],
                     "image_sha": image_digest(gold.image)})
    return rows


def beat_cycles(vol: np.ndarray, scene, cfg: Cube4Config, golden_base: np.ndarray, name: str) -> int:
    """A frame of the beat schedule through the RTL (``cube4_sim``'s engine) on the scene's
    build: its cycles, measured (they depend on the samples: termination), its base plane
    the golden engine's bit for bit (else the report stops)."""
    from cube4_sim.engine import register

    register()
    progress(TAG, f"{name}: the beat schedule through the RTL ...")
    res = render(vol, scene, cfg, "rtl")
    if not np.array_equal(res.frame.baseplane, golden_base):
        raise RuntimeError(f"scene {name}: the RTL's base plane differs from the golden engine's")
    return int(res.stats["cycles"])


# every mode (and unshaded compositing) applied to every built-in scene's volume and transfer function
MODE_VARIANTS = [("composite", {"mode": "composite", "shading": True}),
                 ("composite, unshaded", {"mode": "composite", "shading": False}),
                 ("xray", {"mode": "xray"}), ("mip", {"mode": "mip"}), ("minip", {"mode": "minip"})]


def matrix_names(names: list[str]) -> list[str]:
    """The scenes of the mode matrix: every built-in scene but the crop modes other than
    head_crop_inverted_cross (the same volume, view and transfer function with another
    crop mode: one of them stands for all five)."""
    return [n for n in names if not n.startswith("head_crop_") or n == "head_crop_inverted_cross"]


def refuses(scene, kw: dict) -> bool:
    """A mode variant the scene's features cannot take (its table cell says so): labels
    classify the blending modes only (numerics.md §24), the gradient-magnitude modulation
    needs a shaded composite (§23)."""
    if scene.labels is not None and kw["mode"] in ("mip", "minip"):
        return True
    return scene.gmod is not None and not (kw["mode"] == "composite" and kw.get("shading", False))


def mode_matrix(names: list[str]) -> list[dict]:
    """Each built-in scene in every mode: its build, cycles and error against the
    point-sampled reference (the area truth for 5 modes x every scene costs too long)."""
    import dataclasses

    out = []
    for name in names:
        base = load_scene(name)
        spec = volume_of(name)
        vol = scene_volume(name, base)
        for label, kw in MODE_VARIANTS:
            if refuses(base, kw):
                continue
            scene = dataclasses.replace(base, **kw, skip=True)      # the box schedule: its cycles' formula
            cfg = config_for(scene, pipelines=P)
            build = scene_build([scene])
            progress(TAG, f"{name} as {label} ...")
            m = image_metrics(render(vol, scene, cfg, "golden").image, render(vol, scene, cfg, "reference-point").image)
            out.append({"scene": name, "volume": spec, "mode": label, "build": build, "widths": cfg.widths(),
                        "cycles": schedule_stats(plan_view(vol, scene, cfg).plans, cfg, build)["predicted_cycles"],
                        "psnr_db": m["psnr"] if np.isfinite(m["psnr"]) else None})
    return out


def matrix_table(cells: list[dict], recs: list[dict]) -> str:
    by_key = {build_key(r["build"], r["widths"]): r for r in recs}
    full = logic_nand2(by_key[build_key(FULL_BUILD)]["gates"])
    labels = [lab for lab, _ in MODE_VARIANTS]
    rows = []
    for name in dict.fromkeys(c["scene"] for c in cells):
        row = [name, next(c["volume"] for c in cells if c["scene"] == name)]
        for lab in labels:
            c = next((c for c in cells if c["scene"] == name and c["mode"] == lab), None)
            if c is None:       # a mode the scene refuses (refuses)
                row.append("— (refused)")
                continue
            rec = by_key.get(build_key(c["build"], c.get("widths")))
            change = pct_change(logic_nand2(rec["gates"]), full) if rec else "—"
            psnr = "∞" if c["psnr_db"] is None else f"{c['psnr_db']:.1f}"
            row.append(f"{psnr} dB, {fmt_int(c['cycles'])} cyc, {change}")
        rows.append(row)
    return md_table(["scene", "volume", *labels], rows, "ll" + "r" * len(labels))


def logic_nand2(g: dict) -> float:
    """NAND2 equivalents of the logic (memories are counted in bits, not here)."""
    return g["total"]["nand2_total"]


def place_args(build: dict, widths: dict) -> list[str]:
    """The fpga command line that measures one build at P = 8 (three seeds), its report and
    JSON in reports/fpga/ (where cube4_reports.fmax finds them)."""
    opts = ",".join(f"{k}={v}" for k, v in build.items() if v != FULL_BUILD[k])
    wtext = fmax_store.widths_text({**DEFAULT_WIDTHS, **widths}).replace(" ", "")
    wtag = "".join(f"_{t.lower().replace('=', '')}" for t in wtext.split(",") if t)
    diff = {k: v for k, v in build.items() if v != FULL_BUILD[k]}
    name = "full" if not opts and not wtext else (build_tag(diff).lstrip("_") or "full") + wtag
    return (["--p", str(P), "--seeds", SEEDS, "--max-dim", str(MAX_DIM), "--depth", str(DEPTH), "--no-budget",
             "--no-memory"] + (["--build", opts] if opts else []) + (["--widths", wtext] if wtext else [])
            + ["--md", f"reports/fpga/{name}.md"])


def place_command(build: dict, widths: dict, p: int = P) -> str:
    args = place_args(build, widths)
    if p != P:      # a smaller P: its own report beside the P = 8 one
        args[args.index("--p") + 1] = str(p)
        args[-1] = args[-1].replace(".md", f"_p{p}.md")
    return "python -m cube4_reports.fpga " + " ".join(args)


#: the smaller P a build that does not fit at P tries, largest first
SMALLER_P = (4, 2, 1)


def largest_fit(measured: list[fmax_store.Measured], build: dict, widths: dict) -> fmax_store.Measured | None:
    """For a build that does not fit at P = 8: its place and route at the largest smaller P
    that fits, None if no smaller P was measured (or none fits)."""
    for p in SMALLER_P:
        m = fmax_store.lookup(measured, p, build, widths)
        if m is not None and m.fits:
            return m
    return None


def next_p(measured: list[fmax_store.Measured], build: dict, widths: dict) -> int | None:
    """For a build that does not fit at P = 8 and at no smaller P measured: the largest
    smaller P not measured yet (the next run to try), None when every smaller P was measured
    and none fits (the build fits at no P)."""
    return next((p for p in SMALLER_P if fmax_store.lookup(measured, p, build, widths) is None), None)


def ecp5(rec: dict, measured: list[fmax_store.Measured]) -> dict:
    """A build record with its place and route at P (``fpga``; None: never placed and routed)
    and, where it does not fit at P, at the largest smaller P that does (``fit``) or, where
    none measured does, the next smaller P to measure (``next_p``), or ``fits_no_p`` when P = 4,
    2 and 1 were measured and none fits."""
    f = fmax_store.lookup(measured, P, rec["build"], rec["widths"])
    fit = largest_fit(measured, rec["build"], rec["widths"]) if f is not None and not f.fits else None
    todo = next_p(measured, rec["build"], rec["widths"]) if f is not None and not f.fits and fit is None else None
    return {**rec, "fpga": f, "fit": fit, "next_p": todo,
            "fits_no_p": f is not None and not f.fits and fit is None and todo is None}


def run_builds(builds: list[tuple[dict, dict]], measured: list[fmax_store.Measured]) -> list[dict]:
    """Gates for every build (options, widths); its place and route as measured (or None)."""
    out = []
    for b, w in builds:
        progress(TAG, f"build {full_name(b, w)}: generic gates at P = {P} ...")
        g = gates.gates_for_p(P, MAX_DIM, b, w)
        out.append(ecp5({"build": b, "widths": w, "name": full_name(b, w), "gates": g}, measured))
    return out


def buffer_bits(g: dict) -> int:
    """Memory bits of the buffers: everything but the voxel memory (the same in every build)."""
    return g["total"]["memory_bits"] - g["units"]["VMEM"]["memory_bits"]


def pct_change(size: float, full: float) -> str:
    """A build's size against the full build's, signed: "−35 %" smaller, "+12 %" larger."""
    if not full:
        return "—"
    d = 100.0 * (size / full - 1.0)
    return f"{'−' if d < 0 else '+'}{abs(d):.0f} %"


def builds_table(recs: list[dict]) -> str:
    full = next(r for r in recs if r["build"] == FULL_BUILD)
    fg = full["gates"]
    rows = []
    for r in recs:
        g = r["gates"]
        units = [fmt_int(g["units"][u]["nand2_total"]) for u in UNIT_COLS]
        f = r["fpga"]
        rows.append([r["name"], *units, fmt_int(logic_nand2(g)), pct_change(logic_nand2(g), logic_nand2(fg)),
                     fmt_int(g["total"]["ffs"]), fmt_int(buffer_bits(g)), pct_change(buffer_bits(g), buffer_bits(fg)),
                     fmt_int(f.luts) if f and f.luts else "—", str(f.dsps) if f and f.dsps is not None else "—",
                     str(f.ebrs) if f and f.ebrs is not None else "—",
                     fmax_cell(r)])
    head = ["build", *[gates.UNIT_LABEL[u] for u in UNIT_COLS], "NAND2 eq. (logic)", "vs full",
            "FFs", "buffer bits", "vs full", "LUTs", "DSPs", "EBRs", "Fmax MHz"]
    return md_table(head, rows)


def fmax_cell(r: dict) -> str:
    """A build's Fmax at P = 8, or where it does not fit there, at the largest P that fits
    ("fits at no P" when P = 4, 2 and 1 were measured and none fits)."""
    f, fit = r["fpga"], r.get("fit")
    if f is None:
        return "not measured"
    if f.fits:
        return f"{f.fmax_mhz:.1f}"
    if fit:
        return f"does not fit (P = {fit.p}: {fit.fmax_mhz:.1f})"
    return "fits at no P" if r.get("fits_no_p") else "does not fit"


def scenes_table(rows: list[dict], recs: list[dict]) -> str:
    by_key = {build_key(r["build"], r["widths"]): r for r in recs}
    full = by_key[build_key(FULL_BUILD)]
    out = []
    for s in rows:
        rec = by_key[build_key(s["build"], s.get("widths"))]
        fm = rec["fpga"].fmax_mhz if rec["fpga"] else None
        # the full build at the scene's widths (the only full build that runs it)
        full_w = by_key.get(build_key(FULL_BUILD, s.get("widths")))
        fm_full = full_w["fpga"].fmax_mhz if full_w and full_w["fpga"] else None
        t = f"{s['cycles'] / (fm * 1e3):.3f}" if fm else (fmax_cell(rec).split(" (")[0] if rec["fpga"]
                                                         else "not measured")
        t_full = (f"{s['cycles_full'] / (fm_full * 1e3):.3f}" if fm_full else "not measured") if s["cycles_full"] else "—"
        what = s["mode"] + ("" if s["shaded"] or s["mode"] != "composite" else ", unshaded")
        what += ", crop" if s["crop"] else ""
        what += ", cut plane" if s["cut"] else ""
        what += f", gradient {s['gradient']}" if s.get("gradient", "gra") != "gra" else ""
        sched = "beats (RTL)" if s.get("schedule") == "beats" else "box"
        out.append([s["scene"], s["volume"], what, rec["name"], sched, fmt_int(s["cycles"]),
                    "—" if s["cycles_full"] is None else fmt_int(s["cycles_full"]),
                    fmt_int(s["cycles_fixed"]), t, t_full, pct_change(logic_nand2(rec["gates"]), logic_nand2(full["gates"])),
                    _db(s["psnr_db"]), _db(s.get("psnr_point_db")),
                    "—" if s.get("truth_k") is None else f"{s['truth_k']}", f"`{s.get('image_sha', '—')}`"])
    head = ["scene", "volume", "mode", "smallest build", "schedule", "cycles / frame", "on the full build",
            "fixed schedule", "ms / frame at its Fmax", "on the full build", "NAND2 vs full", "PSNR dB vs area truth",
            "PSNR dB vs point truth", "truth k", "image"]
    return md_table(head, out, "lllll" + "r" * 9 + "l")


def beats_against_box(rows: list[dict]) -> list[str]:
    """One paragraph: how the scenes on the beat schedule compare with the box on the full
    build (their cycles against "on the full build"), as measured."""
    pairs = [(s["scene"], s["cycles"] / s["cycles_full"]) for s in rows
             if s.get("schedule") == "beats" and s.get("cycles_full")]
    if not pairs:
        return []
    fewer = [n for n, r in pairs if r < 1]
    more = sorted(((n, r) for n, r in pairs if r > 1), key=lambda x: -x[1])
    best = min(pairs, key=lambda x: x[1])
    text = (f"On the beat schedule {len(fewer)} of {len(pairs)} scenes take fewer cycles than the box on the "
            f"full build (the most: {best[0]}, {best[1]:.2f}×)")
    if more:
        text += (f"; {len(more)} take more ({', '.join(f'{n} {r:.2f}×' for n, r in more)}): frames that skip "
                 "little, where GRA's beat source costs row NJ and two window steps a slice more than the box "
                 "([docs/architecture.md](../docs/architecture.md), \"Small frames\"); the beats a frame "
                 "ran and skipped: `cube4 render VOLUME --scene SCENE --engine rtl --stats s.json` (key beats); "
                 "GRA's steps: the same with `--engine golden` (beats.gra_cycles)")
    return [text + ".", ""]


def _db(x: float | None) -> str:
    return "∞" if x is None else f"{x:.2f}"


def render_markdown(rows: list[dict], recs: list[dict], meta: dict, matrix: list[dict] | None = None) -> str:
    mip_build = named("mip")
    mip = next((r for r in recs if r["build"] == mip_build), None)
    full = next(r for r in recs if r["build"] == FULL_BUILD)
    lines = [
        "# Per-scene builds: what a scene does not need, left out",
        "",
        f"Generated by `make scenes` (`python -m cube4_reports.scenes`) on commit {meta['git']} "
        f"(rtl/ as {meta.get('rtl_commit', 'unknown')}, digest {meta['rtl_digest']}); do not edit. Builds: cube4_top at P = {P}, MAX_DIM = {MAX_DIM}. "
        "Gates: the generic-gate synthesis of `make gates` (NAND2 equivalents of the logic; memories "
        "in bits). ECP5-85F (LUTs, DSPs, EBRs, Fmax): each build placed and routed at P = 8 by "
        f"`python -m cube4_reports.fpga` (DEPTH = {DEPTH}, `--freq {fpga.DEFAULT_FREQ:g}`, seeds {SEEDS}: "
        "the median seed's figures), read from its results committed under reports/ (the section "
        "\"Place and route\" names each run and its RTL commit); \"not measured\" where a build was never placed "
        "and routed, and its frame times are blank: no build borrows another's clock. "
        "Cycles: a scene runs its default schedule: the beat schedule (beat skipping and ray "
        "termination, docs/numerics.md §19; a BEATS = 1 build), its cycles measured through the RTL on the scene's "
        "build (they depend on the samples), its base plane the golden engine's bit for bit; a scene that sets "
        "the box runs it by the formula of docs/architecture.md for the build with the "
        "empty-space box's dims (docs/numerics.md §15; tb/cube4_top checks it for every build). The full build "
        "(no BEATS) runs the box, by the formula; the fixed schedule's cycles are the formula's on the smallest "
        "build. Error: the golden "
        "engine (bit-identical to the RTL) against the float64 reference, 256² image: against the area truth "
        "(each pixel the mean over its square, k × k rays where the picture is not flat, k the column \"truth k\"; "
        "docs/numerics.md §10) and against the point-sampled one (one ray through each pixel's centre).",
        "",
        "## Builds",
        "",
        "Build parameters of cube4_top (docs/architecture.md, \"Builds\"): SHADING (GRA, the reflectance "
        "map, the shading multipliers), COMPOSITING (COM's T·A and w·C' multipliers: composite, X-ray), "
        "EXTREMUM (COM's comparators: MIP, MinIP), CLIP (cube4_clip: window and cut plane), VGRAD "
        "(voxel gradients: the memory word holds the gradient, TRI interpolates four channels, no GRA; "
        "the scene `head_quality`), PLW (path-length weights: COM's per-lane table of the LUT's path-weight "
        "columns and the weight logic; the scenes `ml` and `head_quality`). \"vs full\" is the size against the full build (which has GRA; a "
        "VGRAD build has TRI's four channels instead, so it can be larger). Buffer bits: every memory but the voxel memory (a "
        f"{MAX_DIM}³ volume's worth in every build).",
        "",
        builds_table(recs),
        "",
    ]
    if mip is not None:
        ratio = logic_nand2(mip["gates"]) / logic_nand2(full["gates"])
        lines += [f"The MIP build (no GRA, no reflectance map, no multipliers in COM) has "
                  f"**{fmt_int(logic_nand2(mip['gates']))}** NAND2 equivalents of logic, "
                  f"**{ratio:.2f}×** the full build's {fmt_int(logic_nand2(full['gates']))} "
                  f"(the goal: at most 0.5×), and {fmt_int(buffer_bits(mip['gates']))} bits of buffers "
                  f"against {fmt_int(buffer_bits(full['gates']))}.", ""]
    lines += place_lines(recs, meta)
    lines += ["## Scenes", "", scenes_table(rows, recs), "", *beats_against_box(rows),
              "schedule: \"beats (RTL)\" the beat schedule, cycles measured through the RTL; \"box\" the box "
              "that can change a ray (within a crop box, if the scene has one), whose cycles follow that box's "
              "dims. A build without GRA "
              "has no slice of GRA delay at the end of a frame (NJ·NB + NB + 2 cycles fewer). "
              "image: the first 12 hex digits of the SHA-256 of the golden engine's image (the RGBA array "
              "as rendered, before it is written as a file); a scene's picture changed exactly when its digest did.", ""]
    if matrix:
        lines += ["## Every scene in every mode", "",
                  "Each built-in scene's volume, view, transfer function (and crop box or cut plane) in each "
                  "mode (of the five crop-mode scenes, head_crop_inverted_cross), on the box schedule (`[render] skip "
                  "= true`, whose cycles are the formula's): PSNR against the point-sampled reference, cycles per "
                  "frame on the smallest build for that mode, and "
                  "the NAND2 equivalents that build saves against the full one. A transfer function made for "
                  "compositing is not what one would pick for MIP or MinIP (MinIP of a volume in air is empty: "
                  "∞ dB, both images black), so the error figures say how the hardware follows the reference, "
                  "not which mode suits which scene.", "", matrix_table(matrix, recs), ""]
    return "\n".join(lines)


def place_lines(recs: list[dict], meta: dict) -> list[str]:
    """Which place-and-route run each build's ECP5 figures come from, and the command for
    each build not measured yet."""
    done = [r for r in recs if r["fpga"]]      # measured: an Fmax, or does not fit
    todo = [r for r in recs if not r["fpga"]]
    lines = ["## Place and route", "",
             f"{len(done)} of {len(recs)} builds placed and routed at P = {P} (RTL of this report: "
             f"{meta.get('rtl_commit', 'unknown')}; a run on an older RTL says so)."]
    lines += [""] if done else []
    for r in done:
        lines.append(f"- {r['name']}: {r['fpga'].note()}")
        if not r["fpga"].fits:
            if r.get("fit"):
                lines.append(f"  - the largest P that fits: {r['fit'].note()}")
            elif r.get("fits_no_p"):
                lines.append(f"  - fits at no P: P = {', '.join(map(str, SMALLER_P))} placed and routed too "
                             "(the report's name with _p4, _p2, _p1), none fits")
            else:
                q = r.get("next_p") or SMALLER_P[0]
                lines.append(f"  - the largest P that fits: not measured yet; P = {q}: "
                             f"`{place_command(r['build'], r['widths'], q)}`")
    if todo:
        lines += ["", "Not measured yet (`python -m cube4_reports.scenes --place` runs them all, about "
                  "40 min each here; or one at a time):", ""]
        lines += [f"- {r['name']}: `{place_command(r['build'], r['widths'])}`" for r in todo]
    return lines + [""]


def place_missing(recs: list[dict]) -> None:
    """--place: place and route every build without a measured result, one after the other."""
    for r in [r for r in recs if not r["fpga"]]:
        progress(TAG, f"place and route {r['name']}: {place_command(r['build'], r['widths'])}")
        args = place_args(r["build"], r["widths"])
        args[-1] = str(DOC_REPORTS.parent / args[-1])      # --md: the repository's reports/fpga/, from anywhere
        rc = fpga.main(args)
        if rc != 0:
            raise fpga.UserError(f"place and route of {r['name']} failed (exit {rc}); the builds before it are "
                                 "in reports/fpga/")


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    ap = argparse.ArgumentParser(prog="python -m cube4_reports.scenes", description=__doc__.splitlines()[0])
    ap.add_argument("--md-only", action="store_true",
                    help="render nothing: rewrite scenes.md from the last run (reports/scenes.json) with "
                         "each build's place and route as measured now")
    ap.add_argument("--place", action="store_true",
                    help="place and route each build not measured yet (P = 8, seeds 1, 2, 3; about 40 min a "
                         "build here) into reports/fpga/, then write the report")
    return ap.parse_args(argv)


def rewrite(t0: float) -> None:
    """--md-only: scenes.md from the last run's reports/scenes.json, each build's ECP5
    figures and frame times as measured now (cube4_reports.fmax)."""
    path = DOC_REPORTS / "scenes.json"
    try:
        data = json.loads(path.read_text())
        rows, matrix, builds = data["scenes"], data["modes"], data["builds"]
        meta = {k: data[k] for k in ("git", "rtl_digest", "rtl_commit")}
        if any("gates" not in b for b in builds):
            raise KeyError("gates")
    except FileNotFoundError:
        raise fpga.UserError(f"--md-only needs {path}: run make scenes first") from None
    except (OSError, ValueError, KeyError, TypeError):
        raise fpga.UserError(f"{path} is not a run of this version: rerun make scenes") from None
    measured = fmax_store.load()
    recs = [ecp5({"build": b["build"], "widths": b["widths"], "name": full_name(b["build"], b["widths"]),
                  "gates": b["gates"]}, measured) for b in builds]
    write_report(TAG, {**data, "builds": build_records(recs)}, path, render_markdown(rows, recs, meta, matrix),
                 DOC_REPORTS / "scenes.md", t0)


def build_records(recs: list[dict]) -> list[dict]:
    """The JSON's builds: gates (whole, for --md-only) and the ECP5 figures used."""
    return [{"build": r["build"], "widths": r["widths"], "nand2": logic_nand2(r["gates"]),
             "ffs": r["gates"]["total"]["ffs"], "memory_bits": r["gates"]["total"]["memory_bits"],
             "buffer_bits": buffer_bits(r["gates"]), "gates": r["gates"],
             "units": {u: r["gates"]["units"][u]["nand2_total"] for u in gates.UNITS},
             "fpga": None if r["fpga"] is None else
             {"fmax_mhz": r["fpga"].fmax_mhz, "luts": r["fpga"].luts, "ffs": r["fpga"].ffs,
              "dsps": r["fpga"].dsps, "ebrs": r["fpga"].ebrs, "source": r["fpga"].note()},
             "fit": None if r.get("fit") is None else {"p": r["fit"].p, "fmax_mhz": r["fit"].fmax_mhz,
                                                       "source": r["fit"].note()},
             "fits_no_p": bool(r.get("fits_no_p"))}
            for r in recs]


def run(args: argparse.Namespace) -> None:
    t0 = time.monotonic()
    if args.md_only:
        return rewrite(t0)
    names = builtin_scene_names()
    rows = scene_rows(names)
    matrix = mode_matrix(matrix_names(names))
    builds: dict[tuple, tuple[dict, dict]] = {build_key(FULL_BUILD): (dict(FULL_BUILD), dict(DEFAULT_WIDTHS))}
    for r in rows + matrix:
        builds.setdefault(build_key(r["build"], r["widths"]), (r["build"], r["widths"]))
    recs = run_builds(list(builds.values()), fmax_store.load())
    if args.place:
        place_missing(recs)
        measured = fmax_store.load()
        recs = [ecp5(r, measured) for r in recs]
    meta = {"git": git_describe(), "rtl_digest": design_digest(), "rtl_commit": last_commit()}
    report = {"p": P, "max_dim": MAX_DIM, "scenes": rows, "modes": matrix, "builds": build_records(recs), **meta}
    write_report(TAG, report, DOC_REPORTS / "scenes.json", render_markdown(rows, recs, meta, matrix),
                 DOC_REPORTS / "scenes.md", t0)


def main(argv: list[str] | None = None) -> int:
    return cli_main(TAG, lambda: run(parse_args(argv)))


if __name__ == "__main__":
    raise SystemExit(main())

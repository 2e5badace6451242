"""Bricks: ``make bricks`` (``python -m cube4_reports.bricks``) writes reports/bricks.md
and its pictures:

1. **Overhead against Teramac Table 1**: 128³ split into p x p x 128 bricks (and a few
   other shapes): voxels stored with the overlap beside the paper's memory overhead,
   board memory words at P = 8, cycles per frame (the formula of docs/architecture.md,
   which tb/cube4_top checks against the RTL) summed over the bricks for three views,
   and the measured golden-model time, bricks one after the other against one render.
2. **Bricked against monolithic** (numerics.md §14.3): head:128 in several grids and
   views; the largest difference in LSBs of Q0.16 beside the proven bound.
3. **Wall time** of the ``cube4`` command: monolithic, bricks in one process, bricks on
   a local Dask cluster of 2 workers; and a 512³ volume on boards of 256.
4. **Seed 004's seams**: the same bricks composited through an 8-bit framebuffer
   (their blending), with and without their opacity and sample-rate correction (eq. 4,
   5), and through this design's accumulators (F = 16 and F = 8), against the
   monolithic render: error over the whole base plane, on the rays that cross a brick
   boundary and on those that do not; pictures.

The numbers also go to build/reports/bricks.json. ``--quick`` runs small volumes and no
command timing, into build/reports/bricks_quick/ (a smoke test; reports/ is left alone).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from cube4.app.volumes import load_volume
from cube4.app.warp import warp_to_image
from cube4.brick_rays import (brick_partials, composite_bound, composite_framebuffers, seam_lines,
                              seed004_correction)
from cube4.bricks import (Tile, brick_tasks, composite_tiles, make_grid, plan_bricks, render_bricked, run_task)
from cube4.host import config_for, host_tables, setup_view
from cube4.memory import words_per_bank
from cube4.model import render_frame
from cube4.scene import load_scene, with_view
from cube4.view import direction_from_angles, make_traversal

from cube4.cycles import frame_cycles, slow_slice_factor

from .markdown import REPO_ROOT, git_describe, md_table

DEFAULT_OUT = REPO_ROOT / "reports"
REPORTS_BUILD = REPO_ROOT / "build" / "reports"
STEM = "bricks"
#: Teramac (seed 000) Table 1: memory overhead in percent, 128³ in p x p x 128 sub-volumes
TABLE1 = {8: 61, 16: 34, 32: 18, 64: 10}
P_BOARD = 8


# ----------------------------------------------------------------------------- 1. overhead
def _cycles(trav, grid, p: int) -> tuple[int, int]:
    """(monolithic, bricked) cycles per frame for one view, P = p pipelines."""
    def one(t):
        return frame_cycles(t.num_sample_slices, t.nj, t.ni, p) * slow_slice_factor(t.nj, t.ni, p)
    bricks = plan_bricks(trav, grid)
    return one(trav), sum(one(b.trav) for b in bricks)


def overhead_rows(n: int, shapes, views, time_volume: str | None) -> list[dict]:
    """One row per brick grid of an n³ volume."""
    rows = []
    dims = (n, n, n)
    scene = load_scene("head")
    cfg = config_for(scene)
    vol = load_volume(time_volume, voxel_bits=cfg.voxel_bits) if time_volume else None
    for label, counts, paper_p in shapes:
        grid = make_grid(dims, counts)
        words = sum(words_per_bank(grid.stored_dims(ix), P_BOARD) for ix in grid.indices())
        row = {"shape": label, "bricks": grid.size, "paper": TABLE1.get(paper_p),
               "memory": grid.memory_overhead, "largest": grid.largest_brick(),
               "words": words / words_per_bank(dims, P_BOARD) - 1.0, "cycles": {}}
        for vname, d in views:
            trav = make_traversal(dims, d, cfg.weight_bits, 1)
            mono, br = _cycles(trav, grid, P_BOARD)
            row["cycles"][vname] = br / mono - 1.0
            if paper_p and vname == "oblique":
                mono_p, br_p = _cycles(trav, grid, paper_p)
                row["cycles_p"] = br_p / mono_p - 1.0
        if vol is not None:
            trav = make_traversal(dims, views[-1][1], cfg.weight_bits, 1)
            lut, rmap = host_tables(scene, cfg, trav)
            t0 = time.perf_counter()
            render_frame(vol, trav, cfg, lut, rmap)
            t_mono = time.perf_counter() - t0
            _, tasks = brick_tasks(vol, trav, cfg, lut, rmap, grid)
            t0 = time.perf_counter()
            for task in tasks:
                run_task(task)
            row["time"] = (time.perf_counter() - t0) / t_mono - 1.0
            row["t_mono"] = t_mono
        rows.append(row)
    return rows


def _implied_overlap(p: int, pct: float) -> float:
    """The overlap o (voxels per sub-volume side pair) for which (p + o)^2 / p^2 - 1 = pct/100."""
    return p * (math.sqrt(1.0 + pct / 100.0) - 1.0)


# ----------------------------------------------------------------------------- 2. bound
def bound_rows(volume: str, grids, views) -> list[dict]:
    scene = load_scene("head")
    cfg = config_for(scene)
    vol = load_volume(volume, voxel_bits=cfg.voxel_bits)
    nz, ny, nx = vol.shape
    rows = []
    for vname, (az, el) in views:
        sc = with_view(scene, direction_from_angles(az, el))
        trav, _ = setup_view((nx, ny, nz), sc, cfg)
        lut, rmap = host_tables(sc, cfg, trav)
        mono = render_frame(vol, trav, cfg, lut, rmap, keep_streams=True)
        for counts in grids:
            grid = make_grid(trav.dims, counts)
            bf = render_bricked(vol, trav, cfg, lut, rmap, grid)
            bd = composite_bound(mono, grid, bf.bricks)
            diff = np.abs(bf.frame.baseplane - mono.baseplane).astype(np.float64)
            bounds = np.concatenate([bd["rgb"], bd["a"][..., None]], axis=-1)
            crossed = bd["segments"] >= 2
            ok = bool(np.all(diff <= bounds + 1e-6))
            per = diff.max(axis=-1)[crossed] / (bd["segments"][crossed] - 1)
            rows.append({"view": vname, "grid": "x".join(map(str, counts)), "ok": ok,
                         "max_diff": float(diff.max()), "max_diff_a": float(diff[..., 3].max()),
                         "max_bound": float(bounds[crossed].max()) if crossed.any() else 0.0,
                         "ratio": float(np.max(diff[crossed] / np.maximum(bounds[crossed], 1e-9))) if crossed.any() else 0.0,
                         "crossed": float(crossed.sum() / max(1, (bd["segments"] >= 1).sum())),
                         "max_segments": int(bd["segments"].max()),
                         "per_boundary": float(per.max()) if per.size else 0.0,
                         "mean_diff": float(diff[crossed].mean()) if crossed.any() else 0.0})
    return rows


# ----------------------------------------------------------------------------- 3. wall time
def _timed_command(args: list[str], reps: int) -> dict:
    """Median wall time of the whole command (start-up, volume, render, cluster, output)
    and the render time it reports (--stats wall_s)."""
    walls, renders = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(reps):
            st = Path(tmp) / "s.json"
            cmd = [sys.executable, "-m", "cube4_sim.cli", "render", *args, "--quiet",
                   "--out", str(Path(tmp) / "x.png"), "--stats", str(st)]
            t0 = time.perf_counter()
            subprocess.run(cmd, check=True, cwd=REPO_ROOT)
            walls.append(time.perf_counter() - t0)
            doc = json.loads(st.read_text())
            renders.append(doc["wall_s"])
            bricks = doc.get("bricks")
    return {"wall": float(np.median(walls)), "render": float(np.median(renders)), "reps": reps,
            "bricks": bricks}


def timing_rows(big: bool) -> list[dict]:
    cases = [("head:128", [], 3), ("head:128", ["--bricks", "2,2,2"], 3),
             ("head:128", ["--bricks", "2,2,2", "--workers", "2"], 3)]
    if big:
        cases += [("head:512", [], 1), ("head:512", ["--board-dim", "256", "--workers", "2"], 1)]
    rows = []
    for vol, extra, reps in cases:
        r = _timed_command([vol, *extra], reps)
        r["command"] = " ".join(["cube4 render", vol, *extra, "--out x.png"])
        rows.append(r)
    return rows


# ----------------------------------------------------------------------------- 4. seams
def _rmse(x: np.ndarray, mask: np.ndarray | None = None) -> float:
    if mask is not None:
        x = x[mask]
    return float(np.sqrt(np.mean(x * x))) if x.size else 0.0


def seam_study(volume: str, counts, s_old: int, out_dir: Path, picture: str) -> dict:
    scene = load_scene("head")
    base_cfg = config_for(scene)
    vol = load_volume(volume, voxel_bits=base_cfg.voxel_bits)
    nz, ny, nx = vol.shape
    dims = (nx, ny, nz)

    def whole(s: int):
        cfg = config_for(scene, supersample=s)
        trav, cam = setup_view(dims, scene, cfg)
        lut, rmap = host_tables(scene, cfg, trav)
        mono = render_frame(vol, trav, cfg, lut, rmap, keep_streams=True)
        return cfg, trav, cam, lut, rmap, mono

    cfg, trav, cam, lut, rmap, mono = whole(s_old)
    grid = make_grid(trav.dims, counts)
    one = make_grid(trav.dims, (1, 1, 1))
    bricks, bricks1 = plan_bricks(trav, grid), plan_bricks(trav, one)
    segments = composite_bound(mono, grid, bricks)["segments"]
    hit = mono.baseplane[..., 3] > 0   # rays that gather any opacity in the one render
    crossed = hit & (segments >= 2)    # ... over more than one brick
    lines = hit & seam_lines(mono, grid, bricks)   # ... whose set of bricks changes next to them
    away = hit & ~lines
    ref = mono.baseplane / 65536.0

    # the samples' average opacity and colour (those that draw anything) -> seed 004's rule
    st = mono.streams
    counted = st["inside"] & st["keep"]
    a = st["shaded"][:, 3][counted] / float(1 << cfg.alpha_bits)
    c = np.moveaxis(st["shaded"][:, :3], 1, -1)[counted] / 256.0
    drawn = a > 0
    a_avg, c_avg = float(a[drawn].mean()), float(c[drawn].mean())
    lost = float(np.mean(a[drawn][:, None] * c[drawn] * 255 < 1))
    a_new, sr_new = seed004_correction(a_avg, c_avg, float(s_old))
    s_new = max(s for s in (1, 2, 4, 8) if s <= max(1.0, sr_new))

    planes = {}
    bf = render_bricked(vol, trav, cfg, lut, rmap, grid)
    planes["mono16"] = ref
    planes["bricks16"] = bf.frame.baseplane / 65536.0
    d8 = brick_partials(mono, one, bricks1, "design", acc_bits=8)[0]
    planes["mono8"] = d8 / 256.0
    parts8 = brick_partials(mono, grid, bricks, "design", acc_bits=8)
    tiles8 = [Tile(0, 0, p) for p in parts8]
    planes["bricks8"] = composite_tiles(tiles8, trav.baseplane_shape, 8) / 256.0
    planes["fb_one"] = composite_framebuffers(brick_partials(mono, one, bricks1, "fb8")) / 255.0
    planes["fb_bricks"] = composite_framebuffers(brick_partials(mono, grid, bricks, "fb8")) / 255.0
    del mono, st
    _, trav_n, _, _, _, mono_n = whole(s_new)
    bricks_n = plan_bricks(trav_n, grid)
    planes["fb_one_corr"] = composite_framebuffers(brick_partials(mono_n, one, plan_bricks(trav_n, one), "fb8")) / 255.0
    planes["fb_bricks_corr"] = composite_framebuffers(brick_partials(mono_n, grid, bricks_n, "fb8")) / 255.0
    planes["mono16_snew"] = mono_n.baseplane / 65536.0
    del mono_n

    rows = []
    spec = [("mono16", None, "one render, this design's accumulators, F = 16 (the reference)"),
            ("bricks16", "mono16", f"bricks {'x'.join(map(str, counts))}, F = 16, over at 16 bits"),
            ("mono8", None, "one render, this design's accumulators, F = 8"),
            ("bricks8", "mono8", "bricks, F = 8, over at 8 bits"),
            ("fb_one", None, "one node, 8-bit framebuffer (seed 004 blending)"),
            ("fb_bricks", "fb_one", "bricks, 8-bit framebuffers, 8-bit final blend (seed 004's case)"),
            ("fb_one_corr", None, f"one node, 8-bit framebuffer, eq. 4/5 correction (S = {s_new})"),
            ("fb_bricks_corr", "fb_one_corr", f"bricks, 8-bit framebuffers, eq. 4/5 correction (S = {s_new})"),
            ("mono16_snew", None, f"one render, F = 16, at S = {s_new} (the rate change alone)")]
    for key, one_key, label in spec:
        err = planes[key] - ref
        seam = (planes[key] - planes[one_key]) if one_key else None
        rows.append({"key": key, "label": label, "rmse": _rmse(err, hit), "max": float(np.abs(err[hit]).max()),
                     "rmse_lines": _rmse(err, lines), "rmse_away": _rmse(err, away),
                     "seam_rmse": _rmse(seam, hit) if seam is not None else None,
                     "seam_max": float(np.abs(seam[hit]).max()) if seam is not None else None})
    _seam_picture(planes, lines, trav, cam, out_dir / picture, counts, s_old, s_new)
    return {"rows": rows, "a_avg": a_avg, "c_avg": c_avg, "lost": lost, "a_new": a_new, "sr_new": sr_new,
            "s_old": s_old, "s_new": s_new, "crossed": float(crossed.sum() / hit.sum()), "volume": volume,
            "hit": int(hit.sum()), "single": int((hit & (segments == 1)).sum()), "lines": int(lines.sum()),
            "grid": "x".join(map(str, counts)), "picture": picture}


def _seam_picture(planes, lines, trav, cam, path: Path, counts, s_old, s_new) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    def img(p):
        return np.clip(warp_to_image(p, trav, cam)[..., :3], 0, 1)

    def err(p, q, scale):
        e = np.abs(p - q).max(axis=-1)
        e4 = np.repeat(e[..., None], 4, axis=-1)
        return np.clip(warp_to_image(e4, trav, cam)[..., 0] * scale, 0, 1)

    g = "x".join(map(str, counts))
    panels = [
        (img(planes["mono16"]), f"one render, F = 16, S = {s_old}", None),
        (img(planes["bricks16"]), f"bricks {g}, F = 16", None),
        (err(planes["bricks16"], planes["mono16"], 2000.0), "|bricks F=16 - one| x 2000", "gray"),
        (np.clip(warp_to_image(np.repeat(lines[..., None].astype(float), 4, -1), trav, cam)[..., 0], 0, 1),
         "seam lines: the set of bricks changes", "gray"),
        (img(planes["fb_one"]), "one node, 8-bit framebuffer", None),
        (img(planes["fb_bricks"]), f"bricks {g}, 8-bit framebuffers", None),
        (err(planes["fb_bricks"], planes["fb_one"], 10.0), "seams: |bricks - one node| x 10 (8-bit)", "gray"),
        (err(planes["fb_bricks"], planes["mono16"], 3.0), "|bricks 8-bit - one F=16| x 3", "gray"),
        (img(planes["bricks8"]), f"bricks {g}, F = 8 accumulators", None),
        (img(planes["fb_bricks_corr"]), f"bricks 8-bit, eq. 4/5 correction (S = {s_new})", None),
        (err(planes["fb_bricks_corr"], planes["fb_one_corr"], 10.0), "seams with correction x 10", "gray"),
        (err(planes["fb_bricks_corr"], planes["mono16"], 3.0), "|corrected - one F=16, S=%d| x 3" % s_old, "gray"),
    ]
    fig, axes = plt.subplots(3, 4, figsize=(13, 10.4))
    for ax, (im, title, cmap) in zip(axes.flat, panels):
        ax.imshow(im, cmap=cmap, vmin=0, vmax=1, interpolation="nearest")
        ax.set_title(title, fontsize=9)
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


# ----------------------------------------------------------------------------- report
def _pct(x: float | None) -> str:
    return "—" if x is None else f"{100.0 * x:.1f}%"


def write_report(out: Path, overhead, bound, timing, seams, meta) -> Path:
    lines = ["# Bricks: sub-volume partitioning, several boards, seams",
             "",
             f"Generated by `make bricks` (`python -m cube4_reports.bricks{meta['args']}`) at commit "
             f"{meta['commit']}, {meta['date']}; {meta['cores']} cores, load average {meta['load_start']} at the "
             f"start and {meta['load_end']} at the end (the machine is shared: times are what this run measured). "
             "How the bricks work and the bound are in [numerics.md §14](../docs/numerics.md#14-bricks-sub-volume-partitioning); "
             "the command line in [usage.md](../docs/usage.md#bricks-and-several-boards).",
             "",
             "## Overhead against Teramac Table 1",
             "",
             f"A {meta['n']}³ volume in bricks; a brick stores its own voxels and 1 voxel below and 2 above "
             "along every axis (cut at the volume's faces), the overlap that tri-linear interpolation and the "
             "gradients of its own samples need, so every inner boundary is stored 3 voxels deep twice. "
             "*Voxels*: voxels stored over all bricks against the volume's. *Words, P = 8*: memory words over "
             "all boards (each pads x to a multiple of P) against one board's. *Cycles*: the cycles per frame of "
             "docs/architecture.md (which tb/cube4_top checks cycle for cycle) summed over the bricks against "
             "one frame, at P = 8, for rays along z (the bricks' long axis), along x and oblique (the head "
             "scene's view); *P = p*: oblique, p pipelines per brick as on the Teramac prototype. "
             "*Golden time*: the bit-exact model's measured time for the bricks one after the other against one "
             "render (oblique view).",
             ""]
    hdr = ["bricks", "count", "Table 1", "voxels", "words, P = 8", "cycles z", "cycles x", "cycles oblique",
           "cycles P = p", "golden time"]
    rows = []
    for r in overhead:
        rows.append([r["shape"], str(r["bricks"]), "—" if r["paper"] is None else f"{r['paper']}%",
                     _pct(r["memory"]), _pct(r["words"]), _pct(r["cycles"]["z"]), _pct(r["cycles"]["x"]),
                     _pct(r["cycles"]["oblique"]), _pct(r.get("cycles_p")),
                     _pct(r["time"]) if "time" in r else "—"])
    lines += [md_table(hdr, rows), ""]
    t1 = [r for r in overhead if r["paper"] is not None]
    if t1:
        implied = ", ".join(f"{_implied_overlap(int(r['shape'].split('x')[0]), r['paper']):.1f} at p = "
                            f"{r['shape'].split('x')[0]}" for r in t1)
        lines += [
            "Table 1 does not say how its sub-volumes share boundary voxels. Read as every p×p×128 sub-volume "
            f"padded by o voxels across x and y, ((p + o)/p)² − 1, its figures imply o = {implied}: "
            "between 2 and 3 voxels per sub-volume, growing with p. This design stores 3 per inner boundary "
            "and none at the volume's faces, so it costs more than Table 1 for small bricks (many inner "
            "boundaries, few faces) and less for large ones. Cycles grow faster than memory for narrow "
            "bricks: every brick is a frame of its own with its fill, its flush beam and GRA's last slice, "
            "and at P = 8 an 11-voxel-wide brick takes two partial beams per beam.",
            ""]
    lines += ["## Bricked composite against the monolithic render",
              "",
              f"{meta['bound_volume']} with the head scene from {meta['bound_views']}, S = 1, ACC_W = 16. Δ is the "
              "absolute difference of a channel from the monolithic base plane, in LSBs of Q0.16; *max Δ*: the "
              "largest over the base plane and the channels (in brackets: opacity A); *max bound*: "
              "the largest §14.3 bound on the rays that cross a boundary; *Δ/bound*: the largest ratio over "
              "those rays and channels (the bound held everywhere: "
              f"{'yes' if all(r['ok'] for r in bound) else 'NO'}); *per boundary*: the largest Δ divided by "
              "the boundaries that ray crosses.",
              ""]
    hdr = ["view", "bricks", "rays crossing", "most bricks on a ray", "max Δ (A)", "mean Δ, crossing rays",
           "max bound", "Δ/bound", "per boundary", "within bound"]
    rows = [[r["view"], r["grid"], _pct(r["crossed"]), str(r["max_segments"]), f"{r['max_diff']:.0f} ({r['max_diff_a']:.0f})",
             f"{r['mean_diff']:.2f}", f"{r['max_bound']:.1f}", f"{r['ratio']:.2f}", f"{r['per_boundary']:.1f}",
             "yes" if r["ok"] else "NO"] for r in bound]
    lines += [md_table(hdr, rows), ""]
    if timing:
        lines += ["## Wall time of the command",
                  "",
                  "The whole `cube4 render` command (Python start-up, building the volume, the render, the "
                  "cluster's start for `--workers`, writing the PNG), median of the runs; *render* is the "
                  "render's own time as the command reports it (`--stats` `wall_s`: host tables, bricks, "
                  "composite, warp). The default scene; golden engine.",
                  ""]
        hdr = ["command", "runs", "wall", "render", "bricks", "workers", "cluster start"]
        rows = []
        for r in timing:
            b = r["bricks"] or {}
            rows.append([f"`{r['command']}`", str(r["reps"]), f"{r['wall']:.2f} s", f"{r['render']:.2f} s",
                         f"{b.get('count', 1)}" + (f" ({'x'.join(map(str, b['grid']))})" if b else ""),
                         str(b.get("workers", 1)), f"{b['cluster_start_s']:.2f} s" if "cluster_start_s" in b else "—"])
        lines += [md_table(hdr, rows), ""]
    s = seams
    lines += ["## Seed 004's seams: 8-bit framebuffers against these accumulators",
              "",
              f"{s['volume']} with the head scene (its faint soft tissue) at S = {s['s_old']}, in {s['grid']} "
              f"bricks; of the {s['hit']:,} rays that gather any opacity, {_pct(s['crossed'])} cross a brick "
              f"boundary ({s['single']:,} stay in one brick{': the head fills the middle of the volume, where the bricks meet' if s['single'] == 0 else ''}), "
              f"and {s['lines']:,} lie on a seam line, where the set of bricks a ray meets changes from one "
              "ray to the next (there one brick's partial image ends and another's begins). The samples "
              f"that draw anything have average opacity {s['a_avg']:.4f} and colour {s['c_avg']:.3f}; "
              f"{_pct(s['lost'])} of their premultiplied colours α·C are below 1/255, which an 8-bit "
              "framebuffer drops. Seed 004's rule (their C-like algorithm, Estimated_Error = 1.5/255) raises "
              f"the opacity to {s['a_new']:.4f} and the sample rate falls by eq. 5 to {s['sr_new']:.2f} per "
              f"voxel; this design's rates are S = 1, 2, 4, 8, so the corrected renders run at S = {s['s_new']} "
              "(the largest not above it), with the opacity corrected by eq. 4 in the LUT as always.",
              "",
              "*8-bit framebuffer*: each node blends its brick's samples back to front into 8 bits per channel, "
              "premultiplied, every result truncated (their eq. 1: texture a8 = round(255a), p8 = floor(255aC); "
              "C_d = p8 + floor((255 − a8) C_d / 255)); the root blends the node images back to front the "
              "same way. *This design's accumulators*: the bricks rendered by the golden model (F = 16) or "
              "composited by its rule at F = 8, then `over` at the same precision. Errors are premultiplied "
              "RGBA in [0, 1] on the base plane against the one render at F = 16 and "
              f"S = {s['s_old']}, over the rays that gather any opacity, on the seam lines and away from them; "
              "*bricking adds* is the difference from the same method's one-node result, the part the "
              "bricks add.",
              ""]
    hdr = ["method", "RMSE", "max", "RMSE on seam lines", "RMSE away from them", "bricking adds: RMSE",
           "bricking adds: max"]
    rows = [[r["label"], f"{r['rmse']:.5f}", f"{r['max']:.4f}", f"{r['rmse_lines']:.5f}", f"{r['rmse_away']:.5f}",
             "—" if r["seam_rmse"] is None else f"{r['seam_rmse']:.5f}",
             "—" if r["seam_max"] is None else f"{r['seam_max']:.4f}"] for r in s["rows"]]
    lines += [md_table(hdr, rows), "", f"![seams]({s['picture']})", ""]
    path = out / f"{STEM}.md"
    path.write_text("\n".join(lines))
    return path


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="cube4_reports.bricks", description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", type=Path, default=None,
                    help="folder of bricks.md and its pictures (default reports/; with --quick build/reports/bricks_quick/)")
    ap.add_argument("--quick", action="store_true", help="small volumes, no command timing (a smoke test)")
    args = ap.parse_args(argv)
    out = args.out or (REPORTS_BUILD / "bricks_quick" if args.quick else DEFAULT_OUT)
    out.mkdir(parents=True, exist_ok=True)
    load_start = " / ".join(f"{v:.1f}" for v in os.getloadavg())
    quick = args.quick
    n = 32 if quick else 128
    shapes = ([("8x8x32", (4, 4, 1), None), ("2x2x2", (2, 2, 2), None)] if quick else
              [(f"{p}x{p}x128", (128 // p, 128 // p, 1), p) for p in (8, 16, 32, 64)]
              + [("64x64x64", (2, 2, 2), None), ("32x32x32", (4, 4, 4), None), ("128x128x64", (1, 1, 2), None)])
    views = [("z", (0.0, 0.0, 1.0)), ("x", (1.0, 0.0, 0.0)), ("oblique", tuple(load_scene("head").direction))]
    t0 = time.perf_counter()
    overhead = overhead_rows(n, shapes, views, None if quick else f"head:{n}")
    bound = bound_rows("head:24" if quick else "head:128", [(2, 2, 2)] if quick else [(2, 2, 2), (4, 2, 1), (3, 3, 3)],
                       [("-60, 15", (-60.0, 15.0))] if quick else
                       [("-60, 15", (-60.0, 15.0)), ("30, -40", (30.0, -40.0)), ("200, 70", (200.0, 70.0))])
    timing = [] if quick else timing_rows(big=True)
    seams = seam_study("head:24" if quick else "head:128", (2, 2, 2), 4, out, f"{STEM}_seams.png")
    meta = {"commit": git_describe(), "date": time.strftime("%Y-%m-%d"),
            "cores": os.cpu_count(), "load_start": load_start,
            "load_end": " / ".join(f"{v:.1f}" for v in os.getloadavg()), "n": n,
            "args": " --quick" if quick else "", "bound_volume": "head:24" if quick else "head:128",
            "bound_views": "one view" if quick else "three views (azimuth, elevation)"}
    path = write_report(out, overhead, bound, timing, seams, meta)
    REPORTS_BUILD.mkdir(parents=True, exist_ok=True)
    (REPORTS_BUILD / f"{STEM}{'_quick' if quick else ''}.json").write_text(json.dumps({"overhead": overhead, "bound": bound, "timing": timing,
                                                  "seams": seams, "meta": meta}, indent=1, default=str))
    print(f"bricks: {path} ({time.perf_counter() - t0:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())

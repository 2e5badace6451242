"""Stiff and extreme cases for every option (issue 51; docs/numerics.md section 11b).

Every case of ``option_cases.py`` is rendered as the ``rtl`` engine renders a scene
(``cube4.host.plan_view``: tables, sub-pixel passes, the empty-space box, the cut
plane) through the RTL at P = 1 and P = 5, every frame with random stalls on the
internal streams and the pixel port, bit for bit against the golden model. The golden
model is then held against the float64 reference on each frame's base-plane grid
(``reference.reference_baseplane``) with the case's check:

* saturate   X-ray: on every ray at least four voxels long all four channels are
             exactly 1.0 (the sums saturate, nothing wraps); the reference too.
* extremum   MIP / MinIP at the end of the value range: every channel within one LUT
             step (2^-8 colour, 2^-AW opacity) of the reference on every ray.
* constant   a constant volume: opacity within the rounding of the LUT entry and of
             n compositing steps of the reference's 1 - (1 - a)^L, L the exact path
             length (path weights: no whole sample of slack at the faces).
* opaque     opacity 1 - 2^-AW everywhere: every ray with two samples reaches
             A >= 1 - 2^-AW, nothing above 1, colour never above opacity.
* bricks     each brick through the RTL equals the golden brick; the composite is within
             the §14 bound of the monolithic frame.
* rmse       base-plane RMSE against the reference below the case's regression bound.

The builds are those tb/cube4_top builds too (the full build at P = 1 and 5 with
MAX_DIM = 64, the voxel-gradient builds), and VOXEL_W = 12, S = 8 builds at MAX_DIM = 32
(the q x q and brick cases: P = 5 in `make test`, P = 1 in `make regress`).
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from option_cases import CASES, OptionCase  # noqa: E402
from stiff_cases import path_lengths  # noqa: E402

from cube4.bricks import Tile, brick_tasks, composite_tiles, make_grid, render_brick_golden  # noqa: E402
from cube4.brick_rays import composite_bound  # noqa: E402
from cube4.builds import complete_build, named  # noqa: E402
from cube4.host import build_memory, config_for, crop_volume, frame_clip, image_metrics, plan_view  # noqa: E402
from cube4.model import render_frame  # noqa: E402
from cube4.reference import reference_baseplane  # noqa: E402
from cube4_sim.golden_check import assert_frame_matches_golden  # noqa: E402
from cube4_sim.rtl import FrameJob, baseplane_from_pixels, render_frames  # noqa: E402
from cube4_sim.sweeps import regress  # noqa: E402

#: the pipelines of the runs: P = 1 and one P >= 5 (the reference is checked at the second)
PIPELINES = (1, 5)
#: the case builds of their own (not tb/cube4_top's): `make test` runs them at the second
#: P only, P = 1 in `make regress` (cube4_sim.sweeps)
OWN_BUILDS = ("wide",)
#: stalls of the n-th frame of a run: (internal streams, pixel port), probability / 256
STALLS = [(60, 0), (0, 90), (120, 60), (30, 40)]
#: VGRAD build per P (those of tb/cube4_top's voxel-gradient test)
VGRAD_BUILDS = {1: dict(SHADING=1, COMPOSITING=1, EXTREMUM=0, CLIP=0, VGRAD=1),
                5: dict(SHADING=1, COMPOSITING=1, EXTREMUM=1, CLIP=1, VGRAD=1)}
#: MAX_DIM of the builds: the full and VGRAD builds of tb/cube4_top; the 12-bit S = 8 builds
MAX_DIM = {None: 64, "vgrad": 64, "wide": 32}


def case_build(case: OptionCase, p: int) -> dict:
    """The full build; the voxel-gradient builds; for the 12-bit S = 8 cases (composite
    only) the full build without MIP (with the clip unit: bricks count their samples with
    its window): make test's builds with EXTREMUM = 0."""
    if case.build == "vgrad":
        return VGRAD_BUILDS[p]
    return complete_build({"EXTREMUM": 0}) if case.build == "wide" else named("full")


def case_config(case: OptionCase, p: int):
    return config_for(case.scenes[0], p, **case.cfg)


def golden_frames(case: OptionCase, cfg, build: dict):
    """[(scene, job, lut, rmap)] for every frame of every view (one per sub-pixel pass
    that runs a frame) and the memory image, as the rtl engine plans them."""
    mem = build_memory(case.volume, case.scenes, cfg, build)
    frames = []
    for sc in case.scenes:
        vp = plan_view(case.volume, sc, cfg)
        for _, plan in vp.jobs():
            stall, stall_out = STALLS[len(frames) % len(STALLS)]
            job = FrameJob(plan.trav, vp.lut, vp.rmap, mode=sc.mode, clip=plan.clip, stall=stall, stall_out=stall_out)
            frames.append((sc, job))
    return mem, frames


def check_against_reference(case: OptionCase, cfg, sc, trav, gold, lut, label: str) -> dict:
    """The golden frame against the reference on its base-plane grid (the case's check);
    returns the figures."""
    ref = reference_baseplane(case.volume, cfg.voxel_bits, sc, trav)
    base = gold.baseplane_float
    m = image_metrics(base, ref)
    one = 1 << cfg.acc_bits
    raw = gold.baseplane
    assert raw.max() <= one, f"{label}: a channel above 1.0"
    if case.check == "saturate":
        long_rays = path_lengths(trav, sc) >= 4.0
        assert long_rays.sum() > 0
        assert (raw[long_rays] == one).all(), f"{label}: a long ray not saturated"
        assert (ref[long_rays] == 1.0).all()
    elif case.check == "extremum":
        entered = path_lengths(trav, sc) >= 1.0
        tol = np.array([2.0 ** -8] * 3 + [2.0 ** -cfg.alpha_bits]) + 1e-12
        worst = np.abs(base - ref)[entered].max(axis=0)
        assert (worst <= tol).all(), f"{label}: {worst} beyond one LUT step"
        assert (ref[..., 3][entered] > 0).all()
    elif case.check == "constant":
        m.update(_check_constant(case, cfg, sc, trav, base, ref, label))
    elif case.check == "opaque":
        assert (lut[:, 3] == (1 << cfg.alpha_bits) - 1).all()
        two = path_lengths(trav, sc) >= 2 * trav.sample_distance
        assert two.sum() > 0
        assert (base[..., 3][two] >= 1 - 2.0 ** -cfg.alpha_bits).all(), f"{label}: a ray not opaque"
        assert (raw[..., :3] <= raw[..., 3:4]).all()
    elif case.check == "rmse":
        assert m["rmse"] <= case.bound, f"{label}: RMSE {m['rmse']:.4f} > {case.bound}"
    print(f"{label}: vs reference RMSE {m['rmse']:.4f}, max {m['max_abs']:.4f}")
    return m


def _check_constant(case: OptionCase, cfg, sc, trav, base, ref, label: str) -> dict:
    """Opacity of a constant volume: on rays at least one voxel inside the box, within
    the rounding of the LUT entry and of n compositing steps (and one sample's opacity at
    the faces without path weights); on the outline's rays, shorter than a voxel inside,
    within one sample's opacity (half a sample's with path weights: the weight a ray that
    touches the box at one sample gets) plus the same rounding."""
    a_voxel = float(sc.tf(case.volume.flat[0] / ((1 << cfg.voxel_bits) - 1))[3])
    n = trav.num_sample_slices
    rounding = n * (2.0 ** -(cfg.alpha_bits + 1) + 2.0 ** -(cfg.acc_bits + 1)) + _weight_rounding(sc, cfg)
    sample = 1 - (1 - a_voxel) ** trav.sample_distance
    half = 1 - (1 - a_voxel) ** (trav.sample_distance / 2)
    inner = path_lengths(trav, sc) >= 1.0
    diff = np.abs(base[..., 3] - ref[..., 3])
    bound_in = (0.0 if sc.path_weighted else sample) + rounding
    bound_out = (half if sc.path_weighted else sample) + rounding
    assert inner.any() and diff[inner].max() <= bound_in, (label, diff[inner].max(), bound_in)
    if (~inner).any():
        assert diff[~inner].max() <= bound_out, (label, diff[~inner].max(), bound_out)
    return {"inner_max": float(diff[inner].max()), "outline_max": float(diff[~inner].max(initial=0.0)),
            "outline_rays": int((~inner).sum())}


def _weight_rounding(sc, cfg) -> float:
    """The path weights' own rounding: the weighted LUT columns (Q0.AW) of the first
    and last sample, one LSB each."""
    return 2 * 2.0 ** -cfg.alpha_bits if sc.path_weighted else 0.0



def run_bricks(case: OptionCase, cfg, build: dict, p: int) -> None:
    """Two bricks along the view per scene, each through the RTL (one board each, stalled),
    equal to the golden bricks; the composite within the §14 bound of the whole frame."""
    for nv, sc in enumerate(case.scenes):
        vp = plan_view(case.volume, sc, cfg)
        trav = vp.trav
        grid = make_grid(trav.dims, tuple(2 if a == trav.major else 1 for a in range(3)))
        box = crop_volume(case.volume, trav)
        bricks, tasks = brick_tasks(box, trav, cfg, vp.lut, vp.rmap, grid, engine="golden", mode=sc.mode,
                                    shading=sc.shaded, clip=frame_clip(sc, trav), board_dim=MAX_DIM[case.build])
        assert len(bricks) == 2
        tiles = []
        for nb, (br, task) in enumerate(zip(bricks, tasks)):
            stall, stall_out = STALLS[(2 * nv + nb) % len(STALLS)]
            btrav = dataclasses.replace(task.trav, origin=(0, 0, 0))   # the board holds the brick alone
            job = FrameJob(btrav, task.lut, task.rmap if sc.shaded else None, clip=task.clip,
                           stall=stall, stall_out=stall_out)
            (out,) = render_frames(task.vol, [job], cfg, max_dim=MAX_DIM[case.build], build=build, quiet=True)
            got = baseplane_from_pixels(out["pixels"], btrav.baseplane_shape)
            want = render_brick_golden(task).baseplane
            assert np.array_equal(got, want), f"{case.name} P={p} view {nv} brick {br.index}: differs from golden"
            tiles.append(Tile(br.offset[0], br.offset[1], got))
        composite = composite_tiles(tiles, trav.baseplane_shape, cfg.acc_bits)
        mono = render_frame(box, trav, cfg, vp.lut, vp.rmap, keep_streams=True)
        bound = composite_bound(mono, grid, bricks)
        diff = np.abs(composite - mono.baseplane)
        crossed = bound["segments"] >= 2
        assert crossed.any() and (mono.baseplane[..., 3][crossed] > 0.99 * (1 << cfg.acc_bits)).any()
        assert np.all(diff[..., 3] <= bound["a"] + 1e-6) and np.all(diff[..., :3] <= bound["rgb"] + 1e-6)
        print(f"{case.name} P={p} view {nv}: bricks bit-exact, composite within the §14 bound "
              f"(max |dA| {diff[..., 3].max():.0f} LSB)")


def option_runs() -> list:
    """(case, P) for every case at every P of PIPELINES; P = 1 of the cases on builds of
    their own marked ``regress``."""
    own = {fn: fn().build in OWN_BUILDS for fn in CASES}
    return [pytest.param(fn, p, id=f"{fn.__name__}-{p}", marks=(regress,) if own[fn] and p != PIPELINES[-1] else ())
            for fn in CASES for p in PIPELINES]


@pytest.mark.parametrize(("case_fn", "p"), option_runs())
def test_stiff_option(case_fn, p):
    case = case_fn()
    cfg = case_config(case, p)
    build = case_build(case, p)
    with_reference = p == PIPELINES[-1]
    if case.check == "bricks":
        run_bricks(case, cfg, build, p)
        return
    mem, frames = golden_frames(case, cfg, build)
    results = render_frames(mem, [job for _, job in frames], cfg, max_dim=MAX_DIM[case.build], build=build)
    vgrad = bool(build["VGRAD"])
    for n, ((sc, job), res) in enumerate(zip(frames, results)):
        label = f"{case.name} P={p} frame {n} view {tuple(sc.direction.round(4))}"
        gold = assert_frame_matches_golden(mem, job.trav, cfg, job.lut, job.rmap, res, label, mode=job.mode,
                                           clip=job.clip, vgrad=vgrad)
        if with_reference:
            check_against_reference(case, cfg, sc, job.trav, gold, job.lut, label)

"""Host side of rendering through the RTL (cube4_top in Verilator).

``render_frames`` builds (once per parameter set; the build is cached under
build/sim) the cube4_top harness, packs the volume with ``cube4.memory``, writes
the tables of every frame, and runs all frames in one simulation: the volume is
loaded once, the frames run back to back. It returns each frame's finished rays
(the golden model's PIXEL_DTYPE, read from the harness's binary pixel dump by
``cube4_sim.dump``) and cycle count; ``baseplane_from_pixels`` assembles the
base-plane image from them.
"""

from __future__ import annotations

import copy
import json
import tempfile
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from cube4.clip import Clip
from cube4.builds import check_build, complete_build
from cube4.config import Cube4Config
from cube4.errors import UserError
from cube4.pathlen import path_weighted
from cube4.vgrad import word_bits
from cube4.modes import is_blend, is_extremum
from cube4.memory import load_image, pack_volume, stop_table, top_regs, words_per_bank, write_hex
from cube4.view import Traversal

from cube4.cycles import COM_MIN_SLICE, frame_cycles, has_falloff, has_gmod, rect_frame_cycles, slow_slice_factor
from cube4.gmod import GMF_BITS, identity_table
from cube4.labels import MAX_LABELS
from cube4.slices import SliceRects, whole_box_rects
from .beats import Geometry
from .rect_port import rect_width, rect_words
from .dump import read_pixel_frames
from .dram_core import MAX_COLUMNS_PER_BURST, DramRun, columns_per_burst
from .sources import form_build_args, form_sources

SIM_SOURCES = ["cube4_sim_clock.v", "cube4_top_harness.v"]


@dataclass
class FrameJob:
    """One frame to render: the view, its tables, and test options."""

    trav: Traversal
    lut: np.ndarray  # (2^V, 4): R, G, B Q0.8, A Q0.ALPHA_W; (2^V, 8) with the path-weight columns
    rmap: np.ndarray | None  # (6 R^2 + 1, 2): D, P Q2.8; None: unshaded (identity map)
    mode: str = "composite"
    clip: Clip | None = None
    stall: int = 0  # hold probability /256 on every internal stream
    stall_out: int = 0  # pixel-port not-ready probability /256
    reset_after_cycles: int = 0  # start, reset after this many cycles, then render
    rects: SliceRects | None = None  # slice rectangles (a RECTS build; None there: the whole box)
    depth_t: int | None = None  # depth out's threshold on T (a ZOUT build; None: not tracked)
    stop_m: np.ndarray | None = None  # depth in: (rows, cols) stop slices of the base plane (a ZIN or BEATS build)
    gm: np.ndarray | None = None  # gradient-magnitude modulation's table (cube4.gmod; a GMOD build)
    # the beat schedule (a BEATS build): (cube4.beats.BeatSchedule before the frame, its
    # TerminationRule, the volume's block-table bits (bz, by, bx))
    beats: tuple | None = None
    extra: dict = field(default_factory=dict)


def check_frame_fits(fr: FrameJob, params: dict) -> None:
    """UserError unless the build has what the frame uses: its mode's datapath, the clip
    unit for a window, crop regions or a cut plane (a brick's window too), the slab's for a
    slab, shading for a shaded frame.
    Without this check the RTL would render such a frame without it, silently."""
    if is_blend(fr.mode) and not params["COMPOSITING"]:
        raise UserError(f"a {fr.mode} frame needs a build with COMPOSITING = 1")
    if is_extremum(fr.mode) and not params["EXTREMUM"]:
        raise UserError(f"a {fr.mode} frame needs a build with EXTREMUM = 1")
    if fr.clip is not None and not params["CLIP"]:
        raise UserError("a frame with a window, crop regions or a cut plane needs a build with CLIP = 1")
    if fr.clip is not None and fr.clip.slab is not None and not params["SLAB"]:
        raise UserError("a frame with a slab needs a build with SLAB = 1")
    if fr.depth_t is not None and not params["ZOUT"]:
        raise UserError("a frame with depth out needs a build with ZOUT = 1")
    if fr.gm is not None and not params["GMOD"]:
        raise UserError("a frame with gradient-magnitude modulation needs a build with GMOD = 1")
    if params.get("BEATS") and fr.beats is None:
        raise UserError("a build with BEATS = 1 runs frames of the beat schedule (their block and ray tables)")
    if fr.beats is not None and not params.get("BEATS"):
        raise UserError("a frame of the beat schedule needs a build with BEATS = 1")
    if fr.stop_m is not None and not (params["ZIN"] or params.get("BEATS")):
        raise UserError("a frame with depth in needs a build with ZIN = 1, or BEATS = 1 (the ray table's stops)")
    if fr.rmap is not None and fr.mode == "composite" and not params["SHADING"]:
        raise UserError("a shaded frame needs a build with SHADING = 1")


def build_params(cfg: Cube4Config, max_dim: int, depth: int | None = None,
                 build: dict | None = None) -> dict[str, int]:
    """cube4_top_harness parameters for a configuration and a largest dimension; the
    voxel memory holds a max_dim^3 volume unless ``depth`` (words per bank) is given;
    ``build``: the build options it names (cube4.builds; the others as complete_build
    gives them; default: the full build)."""
    p = cfg.pipelines
    depth = depth or words_per_bank((max_dim, max_dim, max_dim), p)
    build = complete_build(build)
    check_build(build, cfg.widths())
    return {"P": p, **cfg.widths(), "MAX_DIM": max_dim, "DEPTH": depth,
            "ADDR_W": max(1, (depth - 1).bit_length()), **build}


# The simulated voxel memory (the top harness's image, P * DEPTH words) must fit this
# machine's memory comfortably: 2^29 bytes (512 MiB), a 512³ size class of 16-bit voxels.
SIM_MEMORY_BYTES = 1 << 29
SIM_MAX_DIM = 512          # the largest size class whose memory fits, without voxel gradients


def sim_word_bytes(bits: int) -> int:
    """Bytes Verilator stores a word of this many bits in (CData, SData, IData, QData, or
    32-bit chunks above 64 bits)."""
    return 1 if bits <= 8 else 2 if bits <= 16 else 4 if bits <= 32 else 8 if bits <= 64 else 4 * -(-bits // 32)


MAX_ADDR_W = 30            # cube4_top's ADDR_W range


def check_limits(params: dict[str, int], dims) -> None:
    """The build's limits, checked before any file or build: one line saying what to change."""
    nx, ny, nz = dims
    words = params["P"] * params["DEPTH"]
    if params["ADDR_W"] > MAX_ADDR_W:
        raise UserError(f"a {nx}x{ny}x{nz} volume needs {params['DEPTH']:,} words per bank, more than the "
                        f"RTL's 2^{MAX_ADDR_W}: use more pipelines (--pipelines) or a smaller volume")
    nbytes = words * sim_word_bytes(word_bits(params["VOXEL_W"], bool(params.get("VGRAD", 0)),
                                              bool(params.get("LABELS", 0))))
    if nbytes > SIM_MEMORY_BYTES:
        gib = nbytes / 2**30
        raise UserError(f"the RTL engine's simulated voxel memory for a {nx}x{ny}x{nz} volume (size class "
                        f"{params['MAX_DIM']}^3) would take {gib:.1f} GiB: render a volume of at most "
                        f"{SIM_MAX_DIM}^3 through the RTL ({SIM_MAX_DIM // 2}^3 with voxel gradients), or use --engine golden")


def build_max_dim(dims) -> int:
    """Builds are cached per size class: the next power of two, at least 16."""
    n = max(16, max(int(d) for d in dims))
    return 1 << (n - 1).bit_length()


def identity_rmap(cfg: Cube4Config) -> np.ndarray:
    """The reflectance map of an unshaded frame on a build with shading: D = 1.0 (Q2.8),
    P = 0 everywhere, so C' = min(255, round_shift(C * 256, 8)) = C exactly."""
    table = np.zeros((cfg.rmap_entries, 2), dtype=np.int64)
    table[:, 0] = 1 << 8
    return table


def build_lut(lut: np.ndarray, cfg: Cube4Config, params: dict) -> np.ndarray:
    """The LUT a frame loads on this build: a LABELS build's LUT has a block per label
    (cube4.labels); a frame without labels reads label 0's, its table (the other blocks
    repeat it). A label LUT on a build without LABELS: one line."""
    n = 1 << cfg.voxel_bits
    if lut.shape[0] > n and not params["LABELS"]:
        raise UserError("a frame with labels needs a build with LABELS = 1")
    if params["LABELS"] and lut.shape[0] == n:
        return np.concatenate([lut] * MAX_LABELS, axis=0)
    return lut


def write_tables(lut: np.ndarray, rmap: np.ndarray | None, cfg: Cube4Config, lut_path: Path,
                 rmap_path: Path, plw: bool = False) -> None:
    """The harness's table images: one {R, G, B, A} word per LUT entry (on a PLW build
    {the path-weight columns 3 .. 0, R, G, B, A}: a LUT without columns writes zeros
    there, its frames have FACES = 0), one {D, P} word per reflectance-map entry (the
    identity map for an unshaded frame)."""
    aw = cfg.alpha_bits
    rmap = identity_rmap(cfg) if rmap is None else rmap
    words = (lut[:, 0] << (aw + 16)) | (lut[:, 1] << (aw + 8)) | (lut[:, 2] << aw) | lut[:, 3]
    if plw:
        cols = lut[:, 4:8] if lut.shape[1] >= 8 else np.zeros((lut.shape[0], 4), dtype=np.int64)
        words = [int(w) | sum(int(cols[n, c]) << (24 + aw + c * aw) for c in range(4))
                 for n, w in enumerate(words)]
    write_hex(lut_path, words, 24 + aw + (4 * aw if plw else 0))
    write_hex(rmap_path, (rmap[:, 0] << 10) | rmap[:, 1], 20)


def render_frames(vol: np.ndarray, frames: list[FrameJob], cfg: Cube4Config, *, max_dim: int | None = None,
                  fit_memory: bool = False, waves: bool | None = None, workdir: Path | None = None,
                  progress: bool = False, quiet: bool = False, rtl_form: str = "generic",
                  build: dict | None = None, dram: "DramRun | None" = None) -> list[dict]:
    """Render every frame through the RTL; returns per frame
    {"pixels": PIXEL_DTYPE array, "cycles": int, "sim_wall_s": float}.

    The build is chosen by the configuration and max_dim (default: the volume's size
    class). ``fit_memory`` sizes the voxel memory to this volume (the next power of two
    of its words per bank) instead of a max_dim^3 cube: a long, thin volume then needs
    no memory for a cube it never fills (a separate build). On a build with slice
    rectangles (RECTS = 1) each frame runs its FrameJob.rects, or the whole box.
    ``dram``: the voxel memory is the generated DRAM (cube4_sim.dram_core) behind
    cube4_dram_fetch, on its own clock; each frame's result then also has the
    harness's DRAM counters over the frame (cube4_sim.top_job DRAM_COUNTERS: bursts read,
    the controller's activates, precharges, refreshes, reads)."""
    nz, ny, nx = vol.shape
    max_dim = max_dim or build_max_dim((nx, ny, nz))
    depth = None
    if fit_memory:
        depth = 1 << max(1, (words_per_bank((nx, ny, nz), cfg.pipelines) - 1).bit_length())
    if dram is not None:
        # three images (dram_image), each padded to whole bursts; a model of enough rows
        depth = 3 * dram_image_words(words_per_bank((max_dim + 16 * cfg.pipelines, max_dim, max_dim), cfg.pipelines))
        bits = word_bits(cfg.voxel_bits, bool((build or {}).get("VGRAD", 0)), bool((build or {}).get("LABELS", 0)))
        try:
            dram = dram.holding(depth // columns_per_burst(cfg.pipelines, bits))
        except ValueError as e:
            raise UserError(f"the DRAM build cannot hold this volume: {e}") from None
    params = build_params(cfg, max_dim, depth, build)
    if dram is not None:
        params.update(dram.harness_params())
    shading, vgrad, rects = bool(params["SHADING"]), bool(params["VGRAD"]), bool(params["RECTS"])
    if rects and vgrad:
        raise UserError("slice rectangles run on a build without voxel gradients (VGRAD = 0)")
    if rects and any(path_weighted(fr.lut, fr.mode) for fr in frames):
        raise UserError("slice rectangles do not run path-weighted frames (a build with PLW = 0)")
    for fr in frames:
        check_frame_fits(fr, params)
    check_limits(params, (nx, ny, nz))

    from . import runner  # cocotb is imported only when the RTL engine is used
    own_tmp = None
    if workdir is None:
        runner.BUILD_ROOT.mkdir(parents=True, exist_ok=True)
        own_tmp = tempfile.TemporaryDirectory(prefix="rtl_job_", dir=runner.BUILD_ROOT)
        workdir = Path(own_tmp.name)
    workdir.mkdir(parents=True, exist_ok=True)
    try:
        images = {}                     # DRAM builds: per major axis, the image its views read
        if dram is not None:
            banks, images = dram_image(vol, cfg, params)
        else:
            banks = pack_volume(vol, cfg.pipelines)
        load_words = int(banks.shape[1])
        write_hex(workdir / "mem.hex", load_image(banks), word_bits(cfg.voxel_bits, vgrad, bool(params["LABELS"])))
        job_frames = []
        for n, fr in enumerate(frames):
            lut_p, rmap_p = workdir / f"lut{n}.hex", workdir / f"rmap{n}.hex"
            # only composite frames are shaded: any other frame gets the identity map
            weighted = path_weighted(fr.lut, fr.mode)
            if weighted and not params["PLW"]:
                raise UserError("a path-weighted frame needs a build with PLW = 1")
            write_tables(build_lut(fr.lut, cfg, params), fr.rmap if fr.mode == "composite" else None, cfg,
                         lut_p, rmap_p, plw=bool(params["PLW"]))
            M, nj, ni = fr.trav.num_sample_slices, fr.trav.nj, fr.trav.ni
            ideal = ((frame_cycles(M, nj, ni, cfg.pipelines, shading, vgrad, has_falloff(params), has_gmod(params)) + 100)
                     * slow_slice_factor(nj, ni, cfg.pipelines))
            rect_p, stop_p, gm_p = workdir / f"rects{n}.hex", workdir / f"stop{n}.hex", workdir / f"gm{n}.hex"
            blk_p = workdir / f"blk{n}.hex"
            beats = fr.beats
            if beats is not None and fr.stop_m is not None:
                # depth in: no ray runs past the geometry's stop either (BeatSchedule.limit_stop:
                # the stops, and the neighbour term NBR where a stop was cut)
                cut = copy.deepcopy(beats[0])
                cut.limit_stop(fr.stop_m)
                beats = (cut, *beats[1:])
            if params["BEATS"]:     # the ray table's stops and the block table for the view
                m_w = Geometry(cfg.pipelines, max_dim, params["MAX_SS_LOG2"]).m_w
                write_hex(stop_p, stop_table(beats[0].stop, cfg.pipelines, max_dim, m_w), cfg.pipelines * m_w)
                write_hex(blk_p, beat_block_words(fr, max_dim), -(-max_dim // 4))
            if params["GMOD"]:      # every frame loads its table (no modulation: the identity)
                gm = fr.gm if fr.gm is not None else identity_table(cfg.voxel_bits)
                write_hex(gm_p, [(int(a) << GMF_BITS) | int(s) for a, s in gm], 2 * GMF_BITS)
            if params["ZIN"]:       # every frame loads its table (no geometry: no slice stops)
                m_w = Geometry(cfg.pipelines, max_dim, params["MAX_SS_LOG2"]).m_w
                write_hex(stop_p, stop_table(fr.stop_m, cfg.pipelines, max_dim, m_w), cfg.pipelines * m_w)
            if rects:
                fr_rects = frame_rects(fr, shading and not vgrad)
                write_hex(rect_p, rect_words(fr.trav, fr_rects, cfg.pipelines, max_dim, params["ADDR_W"], (nx, ny, nz)),
                          rect_width(cfg.pipelines, max_dim, params["ADDR_W"]))
                ideal = (rect_frame_cycles(fr_rects, cfg.pipelines, shading, vgrad) + 100) * COM_MIN_SLICE
            slow = 1.0 / max(1e-3, 1.0 - max(fr.stall, fr.stall_out) / 256.0) ** 5
            job_frames.append({
                "regs": top_regs(fr.trav, cfg.pipelines, mode=fr.mode, clip=fr.clip, path_weights=weighted,
                                 depth_t=fr.depth_t, **frame_image(fr.trav, (nx, ny, nz), images),
                                 beats=beats[:2] if beats is not None else None),
                "lut": str(lut_p), "rmap": str(rmap_p), "rect": str(rect_p) if rects else None,
                "stop": str(stop_p) if params["ZIN"] or params["BEATS"] else None,
                "blk": str(blk_p) if params["BEATS"] else None,
                "gm": str(gm_p) if params["GMOD"] else None,
                "tables_reload": True, "stall": fr.stall, "stall_out": fr.stall_out,
                "reset_after_cycles": fr.reset_after_cycles,
                # a DRAM feeds P = 8 at half the rate or less (its bandwidth per pipeline cycle)
                "budget": int(ideal * slow * (16 if dram is not None else 2) + fr.reset_after_cycles + 1000),
                "expected_cycles": ideal,
            })
        job = {"words": load_words, "frames": job_frames, "dump": str(workdir / "pixels.bin"),
               "lut": str(workdir / "lut.hex"), "rmap": str(workdir / "rmap.hex"),
               "rect": str(workdir / "rects.hex"), "stop": str(workdir / "stop.hex"),
               "gm": str(workdir / "gm.hex"), "blk": str(workdir / "blk.hex"),
               "result": str(workdir / "result.json")}
        job_path = workdir / "job.json"
        job_path.write_text(json.dumps(job, indent=1))
        runner.run_test(
            top="cube4_top_harness",
            # rtl_form "ecp5": the vendor layer's forms (rtl/ecp5/), as synthesis reads them
            sources=[*form_sources(rtl_form), *(dram.sources() if dram is not None else []),
                     *(runner.SIM_HDL_DIR / s for s in SIM_SOURCES)],
            build_args=form_build_args(rtl_form),
            params=params,
            test_module="cube4_sim.top_job",
            testcase="run_job",
            waves=waves,
            timing=True,
            extra_env={"CUBE4_JOB": str(job_path), "CUBE4_PROGRESS": "1" if progress else "0",
                       **({"COCOTB_LOG_LEVEL": "WARNING"} if quiet else {})},
            plusargs=[f"+CUBE4_MEMFILE={workdir / 'mem.hex'}", f"+CUBE4_LUTFILE={job['lut']}",
                      f"+CUBE4_RMAPFILE={job['rmap']}", f"+CUBE4_RECTFILE={job['rect']}",
                      f"+CUBE4_STOPFILE={job['stop']}", f"+CUBE4_GMFILE={job['gm']}",
                      f"+CUBE4_BLKFILE={job['blk']}",
                      f"+CUBE4_DUMP={job['dump']}"],
            quiet_logs=quiet,
            private_results=True,   # bricks on several workers may run this build at once
        )
        results = json.loads(Path(job["result"]).read_text())
        # a frame reset in mid-frame leaves a start and no last beat before the frame run after it
        unfinished = [flag for fr in frames for flag in ([True, False] if fr.reset_after_cycles else [False])]
        for r, pix in zip(results, read_pixel_frames(Path(job["dump"]), cfg.pipelines, unfinished)):
            r["pixels"] = pix
        return results
    finally:
        if own_tmp is not None:
            own_tmp.cleanup()


def dram_image_words(words: int) -> int:
    """An image's columns padded to whole bursts of any build (cube4_dram_fetch writes a
    burst when its last column arrives; at most MAX_COLUMNS_PER_BURST columns a burst)."""
    return -(-int(words) // MAX_COLUMNS_PER_BURST) * MAX_COLUMNS_PER_BURST


#: the images a DRAM build holds, by the major axis k of the views that read them: the
#: axis order (i, j, k) of those views (memory.py), so that a view reads each of its
#: slices as one run of columns and its slices one after the other
DRAM_ORDERS = {2: (0, 1, 2), 1: (0, 2, 1), 0: (1, 2, 0)}


def dram_image(vol: np.ndarray, cfg: Cube4Config, params: dict) -> tuple[np.ndarray, dict]:
    """The DRAM's memory image: the volume three times, in the axis orders of
    DRAM_ORDERS, one after the other. Each is the image of the volume padded with zeros
    along its fastest axis to whole bursts per row (a row of NBF columns, NBF a
    multiple of the columns per burst): a row never shares a burst with the next.
    Returns the banks and, per major axis, (the image's first column, its order, the
    padded dims the frame's registers address). Checked against the DRAM's address
    space."""
    bits = word_bits(cfg.voxel_bits, bool(params["VGRAD"]), bool(params["LABELS"]))
    try:
        per = columns_per_burst(cfg.pipelines, bits)
    except ValueError as e:
        raise UserError(f"the DRAM build cannot hold this memory image: {e}") from None
    p = cfg.pipelines
    parts, images, base = [], {}, 0
    for major, order in DRAM_ORDERS.items():
        axis = 2 - order[0]                     # vol[z, y, x]: volume axis a is array axis 2 - a
        n = vol.shape[axis]
        padded = -(-(-(-n // p)) // per) * per * p
        pad = [(0, 0)] * 3
        pad[axis] = (0, padded - n)
        b = pack_volume(np.pad(vol, pad), p, order)
        b = np.pad(b, ((0, 0), (0, dram_image_words(b.shape[1]) - b.shape[1])))
        dims = [int(vol.shape[2]), int(vol.shape[1]), int(vol.shape[0])]
        dims[order[0]] = padded
        parts.append(b)
        images[major] = (base, order, tuple(dims))
        base += b.shape[1]
    banks = np.concatenate(parts, axis=1)
    if banks.shape[1] // per > 1 << params["DRAM_AW"]:
        raise UserError(f"the memory images take {banks.shape[1] // per:,} bursts, more than the DRAM's "
                        f"{1 << params['DRAM_AW']:,}")
    return banks, images


def frame_image(trav: Traversal, dims, images: dict) -> dict:
    """top_regs' image arguments for a frame: on a DRAM build (``images``) the image of
    its major axis (ordered i, j, k), its first column and padded dims."""
    if not images:
        return {"vol_dims": dims}
    base, order, pdims = images[trav.major]
    assert order == (trav.axis_i, trav.axis_j, trav.major)
    return {"vol_dims": pdims, "order": order, "base": base}


def frame_rects(fr: FrameJob, gra: bool) -> SliceRects:
    """The rectangles a frame runs on a RECTS build: its own or the whole box, with GRA's
    walk when the build has GRA (every frame passes GRA there, shaded or not)."""
    t = fr.trav
    r = fr.rects if fr.rects is not None else whole_box_rects(t)
    return replace(r, gra=gra)


def depth_from_pixels(pixels: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """Depth out's slices (rows, cols, 2) int64 (passed, first; model.Frame.depth_m) from
    the finished rays; pixels never hit stay -1."""
    z = np.full((*shape, 2), -1, dtype=np.int64)
    z[pixels["by"], pixels["bx"], 0] = pixels["zp"]
    z[pixels["by"], pixels["bx"], 1] = pixels["zf"]
    return z


def baseplane_from_pixels(pixels: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """Base plane (rows, cols, 4) int64 from the finished rays; pixels never hit stay 0."""
    base = np.zeros((*shape, 4), dtype=np.int64)
    base[pixels["by"], pixels["bx"], 0] = pixels["r"]
    base[pixels["by"], pixels["bx"], 1] = pixels["g"]
    base[pixels["by"], pixels["bx"], 2] = pixels["b"]
    base[pixels["by"], pixels["bx"], 3] = pixels["a"]
    return base


def beat_block_words(fr: FrameJob, max_dim: int) -> list[int]:
    """The block table a BEATS build reads for the frame's view (beat_frames.block_words),
    every word of the table's address space (missing ones zero)."""
    from types import SimpleNamespace

    from .beat_frames import block_words, clog2
    nbk = -(-max_dim // 4)
    words = block_words(SimpleNamespace(trav=fr.trav, bits=fr.beats[2]), nbk)
    n = 1 << (2 * max(1, clog2(nbk)))
    return [words.get(a, 0) for a in range(n)]

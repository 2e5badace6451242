"""Host side of rendering through the RTL (cube4_top in Verilator).

``render_frames`` builds (once per parameter set; the build is cached under
build/sim) the cube4_top harness, packs the volume with ``cube4.memory``, writes
the tables of every frame, and runs all frames in one simulation: the volume is
loaded once, the frames run back to back. It returns each frame's finished rays
(the golden model's PIXEL_DTYPE) and cycle count; ``baseplane_from_pixels``
assembles the base-plane image from them.
"""

from __future__ import annotations

import json
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from cube4.config import Cube4Config
from cube4.memory import pack_volume, top_regs, words_per_bank
from cube4.view import Traversal

from .cycles import frame_cycles, slow_slice_factor

RTL_SOURCES = [
    "cube4_round_shift.v", "cube4_lerp.v", "cube4_skid.v", "cube4_credit_fifo.v", "cube4_ring_shift.v", "cube4_beam_ext.v",
    "cube4_voxel_mem.v", "cube4_cfb.v", "cube4_tri.v", "cube4_frontend.v", "cube4_delay_line.v", "cube4_sdp_ram.v",
    "cube4_gra.v", "cube4_sha.v", "cube4_com.v", "cube4_stream_hold.v", "cube4_stream_check.v", "cube4_frame_ctl.v",
    "cube4_top.v",
]
SIM_SOURCES = ["cube4_sim_clock.v", "cube4_top_harness.v"]


@dataclass
class FrameJob:
    """One frame to render: the view, its tables, and test options."""

    trav: Traversal
    lut: np.ndarray  # (2^V, 4): R, G, B Q0.8, A Q0.ALPHA_W
    rmap: np.ndarray  # (6 R^2 + 1, 2): D, P Q2.8
    stall: int = 0  # hold probability /256 on every internal stream
    stall_out: int = 0  # pixel-port not-ready probability /256
    reset_after_cycles: int = 0  # start, reset after this many cycles, then render
    extra: dict = field(default_factory=dict)


def build_params(cfg: Cube4Config, max_dim: int, depth: int | None = None) -> dict[str, int]:
    """cube4_top_harness parameters for a configuration and a largest dimension; the
    voxel memory holds a max_dim^3 volume unless ``depth`` (words per bank) is given."""
    p = cfg.pipelines
    depth = depth or words_per_bank((max_dim, max_dim, max_dim), p)
    return {
        "P": p, "VOXEL_W": cfg.voxel_bits, "WEIGHT_W": cfg.weight_bits, "ALPHA_W": cfg.alpha_bits,
        "ACC_W": cfg.acc_bits, "RMAP_BITS": cfg.rmap_bits, "MAX_DIM": max_dim,
        "MAX_SS_LOG2": cfg.guard_bits, "DEPTH": depth, "ADDR_W": max(1, (depth - 1).bit_length()),
    }


def build_max_dim(dims) -> int:
    """Builds are cached per size class: the next power of two, at least 16."""
    n = max(16, max(int(d) for d in dims))
    return 1 << (n - 1).bit_length()


def _hex_lines(values, digits: int) -> str:
    return "\n".join(f"{int(v):0{digits}x}" for v in values) + "\n"


def write_tables(lut: np.ndarray, rmap: np.ndarray, cfg: Cube4Config, lut_path: Path, rmap_path: Path) -> None:
    aw = cfg.alpha_bits
    words = (lut[:, 0] << (aw + 16)) | (lut[:, 1] << (aw + 8)) | (lut[:, 2] << aw) | lut[:, 3]
    lut_path.write_text(_hex_lines(words, -(-(24 + aw) // 4)))
    rmap_path.write_text(_hex_lines((rmap[:, 0] << 10) | rmap[:, 1], 5))


def render_frames(vol: np.ndarray, frames: list[FrameJob], cfg: Cube4Config, *, max_dim: int | None = None,
                  fit_memory: bool = False, waves: bool | None = None, workdir: Path | None = None,
                  progress: bool = False, quiet: bool = False) -> list[dict]:
    """Render every frame through the RTL; returns per frame
    {"pixels": PIXEL_DTYPE array, "cycles": int, "sim_wall_s": float}.

    The build is chosen by the configuration and max_dim (default: the volume's size
    class). ``fit_memory`` sizes the voxel memory to this volume (the next power of two
    of its words per bank) instead of a max_dim^3 cube: a long, thin volume then needs
    no memory for a cube it never fills (a separate build)."""
    from . import runner  # cocotb is imported only when the RTL engine is used

    nz, ny, nx = vol.shape
    max_dim = max_dim or build_max_dim((nx, ny, nz))
    depth = None
    if fit_memory:
        depth = 1 << max(1, (words_per_bank((nx, ny, nz), cfg.pipelines) - 1).bit_length())
    params = build_params(cfg, max_dim, depth)
    own_tmp = None
    if workdir is None:
        runner.BUILD_ROOT.mkdir(parents=True, exist_ok=True)
        own_tmp = tempfile.TemporaryDirectory(prefix="rtl_job_", dir=runner.BUILD_ROOT)
        workdir = Path(own_tmp.name)
    workdir.mkdir(parents=True, exist_ok=True)
    try:
        banks = pack_volume(vol, cfg.pipelines)
        (workdir / "mem.hex").write_text(_hex_lines(banks.T.reshape(-1), -(-cfg.voxel_bits // 4)))
        job_frames = []
        for n, fr in enumerate(frames):
            lut_p, rmap_p = workdir / f"lut{n}.hex", workdir / f"rmap{n}.hex"
            write_tables(fr.lut, fr.rmap, cfg, lut_p, rmap_p)
            M, nj, ni = fr.trav.num_sample_slices, fr.trav.nj, fr.trav.ni
            ideal = (frame_cycles(M, nj, ni, cfg.pipelines) + 100) * slow_slice_factor(nj, ni, cfg.pipelines)
            slow = 1.0 / max(1e-3, 1.0 - max(fr.stall, fr.stall_out) / 256.0) ** 5
            job_frames.append({
                "regs": top_regs(fr.trav, cfg.pipelines), "lut": str(lut_p), "rmap": str(rmap_p),
                "tables_reload": True, "stall": fr.stall, "stall_out": fr.stall_out,
                "reset_after_cycles": fr.reset_after_cycles, "out": str(workdir / f"pix{n}.npy"),
                "budget": int(ideal * slow * 2 + fr.reset_after_cycles + 1000), "expected_cycles": ideal,
            })
        job = {"words": int(banks.shape[1]), "frames": job_frames, "dump": str(workdir / "pixels.txt"),
               "lut": str(workdir / "lut.hex"), "rmap": str(workdir / "rmap.hex"),
               "result": str(workdir / "result.json")}
        job_path = workdir / "job.json"
        job_path.write_text(json.dumps(job, indent=1))
        runner.run_test(
            top="cube4_top_harness",
            sources=[*(runner.RTL_DIR / s for s in RTL_SOURCES), *(runner.SIM_HDL_DIR / s for s in SIM_SOURCES)],
            params=params,
            test_module="cube4_sim.top_job",
            testcase="run_job",
            waves=waves,
            timing=True,
            extra_env={"CUBE4_JOB": str(job_path), "CUBE4_PROGRESS": "1" if progress else "0",
                       **({"COCOTB_LOG_LEVEL": "WARNING"} if quiet else {})},
            plusargs=[f"+CUBE4_MEMFILE={workdir / 'mem.hex'}", f"+CUBE4_LUTFILE={job['lut']}",
                      f"+CUBE4_RMAPFILE={job['rmap']}", f"+CUBE4_DUMP={job['dump']}"],
            quiet_logs=quiet,
        )
        results = json.loads(Path(job["result"]).read_text())
        for r in results:
            r["pixels"] = np.load(r["pixels"])
        return results
    finally:
        if own_tmp is not None:
            own_tmp.cleanup()


def baseplane_from_pixels(pixels: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """Base plane (rows, cols, 4) int64 from the finished rays; pixels never hit stay 0."""
    base = np.zeros((*shape, 4), dtype=np.int64)
    base[pixels["by"], pixels["bx"], 0] = pixels["r"]
    base[pixels["by"], pixels["bx"], 1] = pixels["g"]
    base[pixels["by"], pixels["bx"], 2] = pixels["b"]
    base[pixels["by"], pixels["bx"], 3] = pixels["a"]
    return base

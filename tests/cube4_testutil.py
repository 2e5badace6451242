"""Test helpers: small volumes and scenes built in code (no files needed)."""

from __future__ import annotations

import numpy as np

from cube4.clip import Clip, cut_coefficients
from cube4.config import Cube4Config
from cube4.scene import parse_scene
from cube4.view import make_traversal


def sphere_volume(n: int, bits: int = 8) -> np.ndarray:
    """Antialiased solid sphere, radius 0.375 n, centred: f = clip(R - r + 0.5, 0, 1)."""
    z, y, x = np.ogrid[:n, :n, :n]
    c = (n - 1) / 2.0
    r = np.sqrt((x - c) ** 2 + (y - c) ** 2 + (z - c) ** 2)
    f = np.clip(0.375 * n - r + 0.5, 0.0, 1.0)
    return np.floor(f * ((1 << bits) - 1) + 0.5).astype(np.uint16)


def brick_volume() -> np.ndarray:
    """A non-cubic volume (18 x 21 x 24) with structure everywhere, for the brick tests:
    a sphere plus noise."""
    rng = np.random.default_rng(0)
    vol = sphere_volume(24).astype(np.int64) // 2 + rng.integers(0, 100, (24, 24, 24))
    return vol[:, :21, :18].astype(np.uint16).copy()


#: a transfer function with faint and dense parts, for the brick tests
BRICK_TF = {"points": [[0, 0, 0, 0, 0], [0.3, 0.9, 0.4, 0.3, 0.05], [1, 1, 1, 1, 0.4]]}


def random_volume(shape, bits: int = 8, seed: int = 1) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return rng.integers(0, 1 << bits, size=shape).astype(np.uint16)


def make_scene(**kw):
    """A scene from keyword sections, e.g. make_scene(view={"direction": [1, 2, 3]})."""
    data = {"output": {"width": 96, "height": 96}}
    data.update(kw)
    return parse_scene(data)


def write_series(folder, vol: np.ndarray, *, spacing: float = 1.5, intercept: float = -1024.0,
                 skip: int | None = None, series_uid: str | None = None, compressed: bool = False,
                 start: int = 0) -> None:
    """vol[z, y, x] of stored values as a DICOM CT series (pydicom), file names in
    shuffled order: rows along +x, columns along +y, slices along +z (LPS)."""
    from pathlib import Path

    from pydicom.dataset import FileDataset, FileMetaDataset
    from pydicom.encaps import encapsulate
    from pydicom.uid import CTImageStorage, ExplicitVRLittleEndian, JPEG2000Lossless, generate_uid

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    uid = series_uid or generate_uid()
    nz = vol.shape[0]
    rng = np.random.default_rng(5)
    names = rng.permutation(nz) + start
    for z in range(nz):
        if z == skip:
            continue
        meta = FileMetaDataset()
        meta.MediaStorageSOPClassUID = CTImageStorage
        meta.MediaStorageSOPInstanceUID = generate_uid()
        meta.TransferSyntaxUID = JPEG2000Lossless if compressed else ExplicitVRLittleEndian
        path = folder / f"IM{names[z]:04d}.dcm"
        ds = FileDataset(str(path), {}, file_meta=meta, preamble=b"\0" * 128)
        ds.SOPClassUID = CTImageStorage
        ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
        ds.SeriesInstanceUID = uid
        ds.Modality = "CT"
        ds.InstanceNumber = z + 1
        ds.ImagePositionPatient = [0.0, 0.0, z * spacing]
        ds.ImageOrientationPatient = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
        ds.Rows, ds.Columns = vol.shape[1], vol.shape[2]
        ds.SamplesPerPixel = 1
        ds.PhotometricInterpretation = "MONOCHROME2"
        ds.BitsAllocated, ds.BitsStored, ds.HighBit, ds.PixelRepresentation = 16, 12, 11, 0
        ds.RescaleSlope, ds.RescaleIntercept = 1.0, intercept
        if compressed:
            ds.PixelData = encapsulate([b"\xff\x4f\xff\x51" + bytes(16)])   # not a decodable codestream
            ds["PixelData"].VR = "OB"
        else:
            ds.PixelData = vol[z].astype("<u2").tobytes()
        ds.save_as(path, enforce_file_format=True)


#: views of the skipping tests: 45° and (1, 1, 1) among them
SKIP_VIEWS = [(0.3, -0.45, 1.0), (-0.6, 0.25, -1.0), (1.0, 1.0, 1.0), (1.0, -1.0, 0.0), (-1.0, -0.8, 0.2),
              (0.5, 1.0, 0.5), (0.0, 0.0, 1.0)]
SKIP_MODES = ["composite", "xray", "mip", "minip"]
SKIP_THRESHOLD = 60     # values below it are empty (above it for MinIP)


def sparse_case(seed: int, supersample: int | None = None):
    """A volume of faint noise (all below the threshold) with one dense blob, the LUT that
    makes the noise empty, and a view, mode, S (``supersample``, or by the seed), shading
    and (every fourth) cut plane."""
    rng = np.random.default_rng(seed)
    S = supersample or (1, 2, 4)[seed % 3]
    cfg = Cube4Config(pipelines=4, supersample=S)
    nx, ny, nz = (int(n) for n in rng.integers(6, 16, size=3))
    vol = rng.integers(0, SKIP_THRESHOLD - 20, size=(nz, ny, nx))
    c = [int(rng.integers(1, n - 1)) for n in (nz, ny, nx)]
    blob = tuple(slice(max(0, a - 2), a + 2) for a in c)
    vol[blob] = rng.integers(0, 256, size=vol[blob].shape)
    mode = SKIP_MODES[seed % 4]
    lut = np.zeros((256, 4), dtype=np.int64)
    lut[:, :3] = rng.integers(0, 256, size=(256, 3))
    if mode == "minip":
        vol = 255 - vol
        lut[SKIP_THRESHOLD:] = 0
        lut[:SKIP_THRESHOLD, 3] = rng.integers(1, 1 << cfg.alpha_bits, size=SKIP_THRESHOLD)
    else:
        lut[:SKIP_THRESHOLD] = 0
        lut[SKIP_THRESHOLD:, 3] = rng.integers(1, 1 << cfg.alpha_bits, size=256 - SKIP_THRESHOLD)
    rmap = rng.integers(0, 1024, size=(cfg.rmap_entries, 2))
    trav = make_traversal((nx, ny, nz), SKIP_VIEWS[seed % len(SKIP_VIEWS)], cfg.weight_bits, S)
    clip = Clip(plane=cut_coefficients(trav, (1.0, 0.3, -0.2), (nx / 2, ny / 2, nz / 2))) if seed % 4 == 1 else None
    return vol, trav, cfg, lut, rmap, mode, seed % 2 == 0, clip


def rays_agree(full, part) -> bool:
    """Each ray leaves the skipping frame ``part`` (slice rectangles, beat skipping) at
    most once, and every ray that leaves either frame with a value other than zero leaves
    both with the same value (``full``: the fixed schedule's frame)."""
    def by_address(pixels):
        addr = pixels["by"].astype(np.int64) * (1 << 20) + pixels["bx"]
        return addr, {a: tuple(p)[3:7] for a, p in zip(addr.tolist(), pixels.tolist())}   # r, g, b, a

    addr, got = by_address(part.pixels)
    if np.unique(addr).size != addr.size:
        return False
    _, want = by_address(full.pixels)
    nonzero = {a for a, v in want.items() if any(v)} | {a for a, v in got.items() if any(v)}
    return all(got.get(a) == want.get(a) for a in nonzero)


def psnr_vs_point(vol, scene, cfg) -> float:
    """The golden model's PSNR (peak 1) against the reference's centre points, one view."""
    from cube4.app.render import render

    err = render(vol, scene, cfg, "golden").image - render(vol, scene, cfg, "reference-point").image
    return float(-20 * np.log10(np.sqrt(np.mean(err * err))))

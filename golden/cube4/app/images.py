"""Image files: a premultiplied RGBA image written with OpenImageIO."""

from __future__ import annotations

import errno

import numpy as np


def write_image(path: str, rgba: np.ndarray, background=(0.0, 0.0, 0.0), depth: np.ndarray | None = None) -> None:
    """Premultiplied RGBA -> file: EXR keeps float RGBA (half), and with ``depth`` (H, W, 2:
    the threshold's and the first sample's depth, numerics.md §21) two more channels Z and
    Zfirst, all as 32-bit float, no depth as +inf; PNG/TIFF get 8-bit RGB over the
    background colour (and no depth)."""
    import OpenImageIO as oiio

    if path.lower().endswith(".exr") and depth is not None:
        z = np.where(np.isfinite(depth), depth, np.inf)
        data = np.concatenate([rgba, z], axis=-1).astype(np.float32)
        spec = oiio.ImageSpec(data.shape[1], data.shape[0], 6, oiio.FLOAT)
        spec.channelnames = ("R", "G", "B", "A", "Z", "Zfirst")
        spec.alpha_channel, spec.z_channel = 3, 4
        buf = oiio.ImageBuf(spec)
        buf.set_pixels(oiio.ROI(), np.ascontiguousarray(data))
        if not buf.write(path):
            raise OSError(errno.EIO, buf.geterror() or "the image library could not write the file")
        return
    if path.lower().endswith(".exr"):
        data, fmt = rgba.astype(np.float32), oiio.HALF
    else:
        bg = np.asarray(background, dtype=np.float64)
        rgb = rgba[..., :3] + (1.0 - rgba[..., 3:4]) * bg
        data, fmt = np.clip(rgb, 0.0, 1.0).astype(np.float32), oiio.UINT8
    buf = oiio.ImageBuf(np.ascontiguousarray(data))
    if not buf.write(path, fmt):
        raise OSError(errno.EIO, buf.geterror() or "the image library could not write the file")

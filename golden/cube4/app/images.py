"""Image files: a premultiplied RGBA image written with OpenImageIO."""

from __future__ import annotations

import errno

import numpy as np


def write_image(path: str, rgba: np.ndarray, background=(0.0, 0.0, 0.0)) -> None:
    """Premultiplied RGBA -> file: EXR keeps float RGBA; PNG/TIFF get 8-bit RGB over the
    background colour."""
    import OpenImageIO as oiio

    if path.lower().endswith(".exr"):
        data, fmt = rgba.astype(np.float32), oiio.HALF
    else:
        bg = np.asarray(background, dtype=np.float64)
        rgb = rgba[..., :3] + (1.0 - rgba[..., 3:4]) * bg
        data, fmt = np.clip(rgb, 0.0, 1.0).astype(np.float32), oiio.UINT8
    buf = oiio.ImageBuf(np.ascontiguousarray(data))
    if not buf.write(path, fmt):
        raise OSError(errno.EIO, buf.geterror() or "the image library could not write the file")

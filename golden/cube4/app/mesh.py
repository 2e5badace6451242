"""Meshes drawn with a scene's camera into a geometry image (cube4.geometry): trimesh's
ray casting, one orthographic ray per pixel centre; ``cube4 mesh`` writes the EXR."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..errors import UserError
from ..geometry import Geometry, check_geometry
from ..scene import Scene
from ..view import Camera


def load_geometry(path: str) -> Geometry:
    """Read a geometry image: an EXR with channel Z (and optionally R, G, B, A)."""
    import OpenImageIO as oiio

    buf = oiio.ImageBuf(str(path))
    if buf.has_error or not buf.spec().width:
        raise UserError(f"geometry image {path!r}: cannot read it ({(buf.geterror() or 'no image').strip()})")
    names = list(buf.spec().channelnames)
    if "Z" not in names:
        raise UserError(f"geometry image {path!r} has no channel Z (it has {', '.join(names) or 'none'})")
    px = buf.get_pixels(oiio.FLOAT).astype(np.float64)
    z = px[..., names.index("Z")]
    rgba = None
    if all(c in names for c in "RGBA"):
        rgba = np.stack([px[..., names.index(c)] for c in "RGBA"], axis=-1)
    return Geometry(z=z, rgba=rgba)


def resolve_geometry(scene: Scene, cam: Camera) -> Scene:
    """The scene with its [geometry] made a ``Geometry`` for this camera (checked): an EXR
    read, the built-in needle or a mesh file drawn; unchanged without one."""
    spec = scene.geometry
    if spec is None or isinstance(spec, Geometry):
        return scene
    kind, name = spec
    if kind == "image":
        geo = load_geometry(name)
    else:
        mesh = needle_mesh(cam.dims) if name == "needle" else load_mesh(name)
        geo = draw_mesh(mesh, cam)
    check_geometry(geo, cam)
    return replace(scene, geometry=geo)


def load_mesh(path: str):
    """A mesh file trimesh reads (.stl, .obj, .ply, ...), in the volume's voxel coordinates."""
    import trimesh

    try:
        mesh = trimesh.load(path, force="mesh")
    except Exception as e:  # noqa: BLE001 - any reader failure is the user's file: one line
        raise UserError(f"mesh {path!r}: cannot read it ({' '.join(str(e).split()) or type(e).__name__})") from None
    if not len(getattr(mesh, "faces", ())):
        raise UserError(f"mesh {path!r} has no triangles")
    return mesh


def needle_mesh(dims, radius: float | None = None):
    """A needle (a thin cylinder with a cone for its tip) entering the volume from near
    its (0, 0, n_z) corner and ending just past its centre, in voxel coordinates."""
    import trimesh

    d = np.asarray(dims, dtype=np.float64)
    tip = (d - 1) / 2 + np.array([0.05, -0.05, 0.0]) * d
    tail = np.array([0.0, 0.1, 1.0]) * (d - 1) + np.array([-0.3, -0.1, 0.3]) * d
    r = float(radius if radius is not None else max(1.5, 0.02 * float(d.max())))
    axis = tip - tail
    length = float(np.linalg.norm(axis))
    body = trimesh.creation.cylinder(radius=r, height=length - 4 * r, sections=24)
    body.apply_translation([0, 0, -2 * r])
    cone = trimesh.creation.cone(radius=r, height=4 * r, sections=24)
    cone.apply_translation([0, 0, length / 2 - 4 * r])
    mesh = trimesh.util.concatenate([body, cone])
    align = trimesh.geometry.align_vectors([0, 0, 1], axis / length)
    mesh.apply_transform(align)
    mesh.apply_translation((tip + tail) / 2)
    return mesh


def draw_mesh(mesh, cam: Camera, color=(0.85, 0.85, 0.9)) -> Geometry:
    """The mesh (voxel coordinates of the volume) drawn with the camera: one orthographic
    ray per pixel centre (trimesh's ray casting), the nearest hit's depth and a Lambert
    shade under a headlight, opaque; +inf and transparent where nothing is hit."""
    origins, d = cam.ray_origins()
    far = 0.5 * float(np.linalg.norm(np.asarray(cam.dims, dtype=np.float64))) + 2.0
    starts = origins - far * d
    locs, ray_idx, tri_idx = mesh.ray.intersects_location(starts, np.tile(d, (starts.shape[0], 1)),
                                                          multiple_hits=False)
    n = cam.width * cam.height
    z = np.full(n, np.inf)
    shade = np.zeros(n)
    if ray_idx.size:
        depth = (locs - cam.centre) @ d
        order = np.argsort(depth)[::-1]          # nearest last: it wins the assignment
        z[ray_idx[order]] = depth[order]
        normals = mesh.face_normals[tri_idx]
        shade[ray_idx[order]] = (0.25 + 0.75 * np.abs(normals @ d))[order]
    hit = np.isfinite(z)
    rgba = np.zeros((n, 4))
    rgba[hit, :3] = np.asarray(color)[None, :] * shade[hit, None]
    rgba[hit, 3] = 1.0
    return Geometry(z=z.reshape(cam.height, cam.width), rgba=rgba.reshape(cam.height, cam.width, 4))


def write_geometry(path: str, geo: Geometry) -> None:
    """An EXR with R, G, B, A and Z (32-bit float), as ``load_geometry`` reads it."""
    import OpenImageIO as oiio

    rgba = geo.rgba if geo.rgba is not None else np.zeros((*geo.z.shape, 4))
    data = np.concatenate([rgba, geo.z[..., None]], axis=-1).astype(np.float32)
    spec = oiio.ImageSpec(data.shape[1], data.shape[0], 5, oiio.FLOAT)
    spec.channelnames = ("R", "G", "B", "A", "Z")
    spec.alpha_channel, spec.z_channel = 3, 4
    buf = oiio.ImageBuf(spec)
    buf.set_pixels(oiio.ROI(), np.ascontiguousarray(data))
    if not buf.write(str(path)):
        raise UserError(f"cannot write {path!r}: {buf.geterror()}")

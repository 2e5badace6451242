"""Label maps for a run: a segmentation beside the volume (cube4.labels, numerics.md §24).

:func:`load_label_map` takes a *spec*:

* a built-in label map of a built-in volume: ``aal_lobes`` for ``colin`` (the AAL atlas
  of the Debian package mricron-data, on the Colin27 grid, its 116 regions folded into
  15 lobes, ``AAL_LOBES``); at other dims of ``colin`` it is resampled by the nearest
  voxel at the positions the volume's trilinear resampling takes;
* a file: ``.nii``/``.nii.gz`` or ``.nrrd``/``.nhdr``, integer labels 0 .. 15 kept as
  they are (no rescaling), reoriented to RAS like the volume.

The map must lie on the volume's grid: the same dimensions and, where both files say
how their axes lie in the patient, the same orientation and voxel positions. Anything
else is one line, before anything is rendered or written.
"""

from __future__ import annotations

import os

import numpy as np

from ..errors import UserError
from ..labels import MAX_LABELS, check_label_map, pack_words
from .libs import quiet_library
from .volumes import NIFTI_SUFFIXES, NRRD_SUFFIXES, _load_nrrd, _nrrd_ras_affine, _suffix_kind, package_file

#: AAL's regions (odd: left, even: right hemisphere) folded into lobes: (first, last, lobe)
AAL_GROUPS = (
    (1, 28, "frontal"),
    (29, 42, "limbic"),          # insula, cingulum, hippocampus, parahippocampal, amygdala
    (43, 56, "occipital"),       # with the fusiform gyrus
    (57, 70, "parietal"),
    (71, 78, "deep grey"),       # caudate, putamen, pallidum, thalamus
    (79, 90, "temporal"),
    (91, 108, "cerebellum"),
)
#: label of each lobe: group g (1-based) left 2g - 1, right 2g; the vermis 15; outside 0
AAL_LOBES = {0: "outside the brain",
             **{2 * g + 1 + side: f"{name} {'left right'.split()[side]}"
                for g, (_, _, name) in enumerate(AAL_GROUPS) for side in (0, 1)},
             15: "vermis"}
#: built-in label maps: name -> (the built-in volume it belongs to, its description)
BUILTIN_MAPS = {"aal_lobes": ("colin", "the AAL atlas (mricron-data) folded into 15 lobes, on colin's grid")}


def fold_aal(aal: np.ndarray) -> np.ndarray:
    """AAL region numbers 0 .. 116 -> lobe labels 0 .. 15 (AAL_LOBES)."""
    table = np.zeros(117, dtype=np.uint8)
    for g, (first, last, _) in enumerate(AAL_GROUPS):
        r = np.arange(first, last + 1)
        table[r] = 2 * g + 1 + (r % 2 == 0)
    table[109:117] = 15
    return table[np.clip(aal, 0, 116)]


def _aal_native() -> np.ndarray:
    import nibabel as nib

    img = nib.as_closest_canonical(nib.load(package_file("aal.nii.gz")))
    data = np.asarray(img.dataobj).astype(np.int64)
    return np.ascontiguousarray(fold_aal(data).transpose(2, 1, 0))     # [z, y, x]


def _nearest_axis(a: np.ndarray, n: int, axis: int) -> np.ndarray:
    """The nearest voxel at the positions of volumes._resample_axis (end points aligned)."""
    src = a.shape[axis]
    if src == n:
        return a
    pos = np.floor(np.linspace(0.0, src - 1.0, n) + 0.5).astype(np.intp)
    return np.take(a, pos, axis=axis)


def _volume_name(volume_spec: str) -> str:
    return str(volume_spec).split(":", 1)[0].lower()


def _builtin_map(name: str, volume_spec: str, shape) -> np.ndarray:
    owner = BUILTIN_MAPS[name][0]
    if _volume_name(volume_spec) != owner or os.path.exists(str(volume_spec)):
        raise UserError(f"built-in label map {name} belongs to the built-in volume {owner} "
                        f"({owner} or {owner}:NX,NY,NZ), not to {volume_spec}")
    a = _aal_native()
    for axis, n in enumerate(shape):
        a = _nearest_axis(a, n, axis)
    return np.ascontiguousarray(a)


def _file_affine(path: str) -> np.ndarray | None:
    """The 4 x 4 voxel-to-RAS affine of a NIfTI file after reorienting to RAS, or an NRRD
    file's 3 x 3 directions (None: the file does not say, or is neither)."""
    kind = _suffix_kind(path)
    try:
        with quiet_library():
            if kind == "nifti":
                import nibabel as nib
                return nib.as_closest_canonical(nib.load(path)).affine
            if kind == "nrrd":
                import nrrd
                return _nrrd_ras_affine(nrrd.read_header(path), path)
    except UserError:
        raise
    except Exception:       # the volume loader reports a file it cannot read
        return None
    return None


def _load_map_file(path: str) -> np.ndarray:
    if not os.path.isfile(path):
        raise UserError(f"label map not found: {path}")
    kind = _suffix_kind(path)
    if kind == "nifti":
        import nibabel as nib
        try:
            with quiet_library():
                img = nib.as_closest_canonical(nib.load(path))
                data = np.asarray(img.dataobj)
        except Exception as e:  # nibabel raises many kinds for corrupt files
            raise UserError(f"cannot read label map {path}: {type(e).__name__}: {e}") from None
        if data.ndim == 4 and data.shape[3] == 1:
            data = data[..., 0]
        if data.ndim != 3:
            raise UserError(f"label map {path} holds {data.ndim}-D data: a label map is 3-D")
        return data.transpose(2, 1, 0)
    if kind == "nrrd":
        return _load_nrrd(path)
    raise UserError(f"label map {path}: use a NIfTI (.nii, .nii.gz) or NRRD (.nrrd, .nhdr) file, "
                    f"or a built-in ({', '.join(BUILTIN_MAPS)})")


def load_label_map(spec: str, volume_spec: str, shape) -> np.ndarray:
    """The label map ``spec`` for the volume ``volume_spec`` of shape (z, y, x): uint8
    labels 0 .. 15 on the volume's grid (module docstring); one line otherwise."""
    spec = str(spec)
    if spec in BUILTIN_MAPS:
        return check_label_map(_builtin_map(spec, volume_spec, shape), shape, f"label map {spec}")
    if not spec.lower().endswith(NIFTI_SUFFIXES + NRRD_SUFFIXES):
        raise UserError(f"label map {spec!r}: not a NIfTI or NRRD file, and built-in label maps are "
                        f"{', '.join(BUILTIN_MAPS)}")
    data = _load_map_file(spec)
    if data.dtype.kind in "uif" and data.dtype.byteorder not in ("=", "|"):
        data = data.astype(data.dtype.newbyteorder("="))
    labels = check_label_map(data, shape, f"label map {spec}")
    vol_aff = _file_affine(str(volume_spec)) if os.path.isfile(str(volume_spec)) else None
    map_aff = _file_affine(spec)
    if vol_aff is not None and map_aff is not None:
        if vol_aff.shape != map_aff.shape or not np.allclose(vol_aff, map_aff, atol=1e-3):
            raise UserError(f"label map {spec} lies differently in the patient from the volume {volume_spec} "
                            "(their orientation or voxel positions differ): resample it onto the volume's grid")
    return labels


def with_labels(vol: np.ndarray, volume_spec: str, scene, voxel_bits: int, map_spec: str | None = None) -> np.ndarray:
    """What a scene renders of vol: vol itself, or with labels (the scene's [[label]]) the
    labelled memory words of its label map (``map_spec``, else the scene's [labels] map)."""
    if scene is None or scene.labels is None:
        return vol
    labels = load_label_map(map_spec or scene.labels.map, volume_spec, vol.shape)
    return pack_words(vol, labels, voxel_bits)


__all__ = ["AAL_LOBES", "BUILTIN_MAPS", "MAX_LABELS", "fold_aal", "load_label_map", "with_labels"]

"""Label volumes (docs/numerics.md §24; build option LABELS).

A clinical volume comes with a segmentation: a second volume of labels on the same grid,
each voxel's material. ULTRAVIS (seed 002) renders such material-tagged volumes with up
to 16 materials, each with its own transfer function. Here a scene gives each label its
own transfer function and a visibility switch ([[label]] tables); a hidden label is
empty space.

* **The memory word** (``pack_words``): the label sits above the value,
  ``word = label · 2^V + value``, LABEL_W = 4 bits (labels 0 .. 15). Outside the volume
  the word is 0: label 0 and value 0.
* **Resampling** (``nearest_pair``): a sample's label is the label of the corner of its
  2×2×2 cell nearest to it, picked along each axis by the weight the value's lerp uses:
  the upper voxel when w ≥ 2^(W−1) (ties go up, as the lerps' rounding does), in the
  lerps' order x, y, z. The value is interpolated from all eight corners as without
  labels (§4), and the gradient from the values (§5).
* **Classification**: the LUT has 16 · 2^V entries; the sample's entry is
  ``label · 2^V + value`` (``label_lut``): label l's rows are the classification of its
  own transfer function (the scene's [transfer] for a label it does not name), all zero
  for a hidden label.
* **Empty space** (``busy_cells``): a cell can change a ray only if one of the labels of
  its corners has a value in [min, max] of the cell whose entry counts; a hidden label's
  entries never count.

The float64 reference resamples the labels by one of three rules (``RESAMPLINGS``, the
scene's [labels] resample; docs/numerics.md §24 compares them on a real segmentation):
``nearest`` (the hardware's: the nearest voxel's label, the value interpolated from all
eight corners), ``masked`` (ULTRAVIS's: the nearest voxel's label, the corners of
other labels count as zero in the value's interpolation) and ``blended`` (each label's
classification weighted by the interpolation weights of its corners).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import UserError
from .values import shown

LABEL_W = 4                      # bits of a label in the memory word
MAX_LABELS = 1 << LABEL_W        # labels 0 .. 15
RESAMPLINGS = ("nearest", "masked", "blended")


@dataclass(frozen=True)
class Label:
    """One label a scene names: its own transfer function (None: the scene's [transfer])
    and whether it is shown."""

    index: int
    name: str = ""
    points: np.ndarray | None = None     # (n, 5) [value, r, g, b, a], as [transfer] points
    visible: bool = True


@dataclass(frozen=True)
class LabelSet:
    """A scene's [labels] and [[label]] tables."""

    labels: tuple[Label, ...] = ()
    map: str | None = None               # the label map's file or built-in name (None: given on the command line)
    resample: str = "nearest"            # the reference's rule (the hardware's is nearest)

    def label(self, index: int) -> Label:
        """The label's entry (a label the scene does not name: shown, the scene's [transfer])."""
        for lb in self.labels:
            if lb.index == index:
                return lb
        return Label(index)


# ---------------------------------------------------------------- scene keys
def _points(raw, where: str) -> np.ndarray:
    from .values import real
    ok = isinstance(raw, list) and len(raw) >= 1 and all(isinstance(r, list) and len(r) == 5 for r in raw)
    if not ok:
        raise UserError(f"scene: {where} must be a list of [value, r, g, b, a] rows")
    arr = np.array([[real(v, f"scene: {where}[{n}][{c}]", 0, 1) for c, v in enumerate(row)]
                    for n, row in enumerate(raw)], dtype=np.float64)
    if np.any(np.diff(arr[:, 0]) < 0):
        raise UserError(f"scene: {where} must be sorted by value")
    return arr


def parse_labels(tbl: dict, entries) -> LabelSet | None:
    """[labels] map / resample and [[label]] index / name / points / visible (None: the
    scene has neither table)."""
    if not tbl and not entries:
        return None
    if not isinstance(tbl, dict):
        raise UserError("scene: [labels] must be a table")
    extra = sorted(set(tbl) - {"map", "resample"})
    if extra:
        raise UserError(f"scene: unknown key(s) in [labels]: {', '.join(extra)}")
    lmap = tbl.get("map")
    if lmap is not None and (not isinstance(lmap, str) or not lmap):
        raise UserError(f"scene: labels.map must be a file name or a built-in label map, got {shown(lmap)}")
    resample = tbl.get("resample", "nearest")
    if resample not in RESAMPLINGS:
        raise UserError(f"scene: labels.resample must be one of {', '.join(RESAMPLINGS)}, got {shown(resample)}")
    if not isinstance(entries, list):
        raise UserError("scene: labels are given as [[label]] tables")
    labels, seen = [], set()
    for n, e in enumerate(entries):
        where = f"label #{n + 1}"
        if not isinstance(e, dict):
            raise UserError(f"scene: {where} must be a table")
        extra = sorted(set(e) - {"index", "name", "points", "visible"})
        if extra:
            raise UserError(f"scene: unknown key(s) in {where}: {', '.join(extra)}")
        idx = e.get("index")
        if not isinstance(idx, int) or isinstance(idx, bool) or not 0 <= idx < MAX_LABELS:
            raise UserError(f"scene: {where} index must be an integer in 0..{MAX_LABELS - 1} "
                            f"(a label volume holds at most {MAX_LABELS} labels), got {shown(idx)}")
        if idx in seen:
            raise UserError(f"scene: label {idx} is given twice")
        seen.add(idx)
        name = e.get("name", "")
        if not isinstance(name, str):
            raise UserError(f"scene: {where} name must be text, got {shown(name)}")
        visible = e.get("visible", True)
        if not isinstance(visible, bool):
            raise UserError(f"scene: {where} visible must be true or false, got {shown(visible)}")
        pts = _points(e["points"], f"label {idx} points") if "points" in e else None
        labels.append(Label(idx, name, pts, visible))
    return LabelSet(tuple(labels), lmap, resample)


# ---------------------------------------------------------------- the memory word
def check_label_map(labels: np.ndarray, shape, what: str = "label map") -> np.ndarray:
    """A label map for a volume of ``shape`` (z, y, x): integers 0 .. 15 on the same grid.
    Returns it as uint8; UserError with one line otherwise."""
    a = np.asarray(labels)
    if a.shape != tuple(shape):
        have = "x".join(map(str, a.shape[::-1]))
        want = "x".join(map(str, tuple(shape)[::-1]))
        raise UserError(f"{what} is {have} voxels, the volume {want}: a label map must lie on the volume's grid")
    if a.dtype.kind == "f":
        if not np.all(np.isfinite(a)) or np.any(a != np.round(a)):
            raise UserError(f"{what} holds values that are not whole numbers: labels are integers 0..{MAX_LABELS - 1}")
    elif a.dtype.kind not in "uib":
        raise UserError(f"{what} holds data of type {a.dtype}: labels are integers 0..{MAX_LABELS - 1}")
    lo, hi = (int(a.min()), int(a.max())) if a.size else (0, 0)
    if lo < 0 or hi >= MAX_LABELS:
        bad = hi if hi >= MAX_LABELS else lo
        raise UserError(f"{what} holds label {bad}: at most {MAX_LABELS} labels, 0..{MAX_LABELS - 1}")
    return a.astype(np.uint8)


def pack_words(vol: np.ndarray, labels: np.ndarray, voxel_bits: int) -> np.ndarray:
    """The memory words label · 2^V + value (uint32), vol[z, y, x] and labels alike."""
    return (labels.astype(np.uint32) << voxel_bits) | vol.astype(np.uint32)


def split_words(words: np.ndarray, voxel_bits: int) -> tuple[np.ndarray, np.ndarray]:
    """(values, labels) of memory words, int64."""
    w = np.asarray(words, dtype=np.int64)
    return w & ((1 << voxel_bits) - 1), w >> voxel_bits


def word_bits(voxel_bits: int) -> int:
    """Bits of a labelled memory word."""
    return voxel_bits + LABEL_W


# ---------------------------------------------------------------- resampling (numerics.md §24)
def nearest_pair(lo: np.ndarray, hi: np.ndarray, weights, weight_bits: int) -> np.ndarray:
    """The labels of one sample slice from the two padded label slices it reads (as
    model.interpolate_pair): per axis the upper corner where the weight is at least one
    half, in the order x, y, z."""
    wx, wy, wz = (int(w) for w in weights)
    half = 1 << (weight_bits - 1)
    src = hi if wz >= half else lo
    sx = src[:, 1:] if wx >= half else src[:, :-1]
    return sx[1:] if wy >= half else sx[:-1]


# ---------------------------------------------------------------- tables
def label_points(scene, index: int) -> np.ndarray:
    """The transfer function's points of one label (the scene's [transfer] unless the
    label has its own)."""
    lb = scene.labels.label(index)
    return scene.tf_points if lb.points is None else lb.points


def label_tf(scene, index: int, x) -> np.ndarray:
    """Label ``index``'s transfer function at normalised values x: (..., 4) RGBA, all zero
    for a hidden label."""
    x = np.asarray(x, dtype=np.float64)
    if not scene.labels.label(index).visible:
        return np.zeros(x.shape + (4,))
    p = label_points(scene, index)
    return np.stack([np.interp(x, p[:, 0], p[:, c]) for c in range(1, 5)], axis=-1)


def label_lut(per_label) -> np.ndarray:
    """The LUT of a label build: (16 · 2^V, 4), label l's block its table ``per_label(l)``
    ((2^V, 4) each)."""
    return np.concatenate([per_label(l) for l in range(MAX_LABELS)], axis=0)


def lut_value_bits(lut: np.ndarray) -> int:
    """V of a label LUT (16 · 2^V rows)."""
    n = lut.shape[0] // MAX_LABELS
    if n * MAX_LABELS != lut.shape[0] or n & (n - 1):
        raise ValueError(f"a label LUT has 16 * 2^V rows, got {lut.shape[0]}")
    return n.bit_length() - 1

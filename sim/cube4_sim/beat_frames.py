"""Golden frames of the beat schedule for the front end's unit testbenches
(tb/cube4_cfb_beats, tb/cube4_cfb_decide): ``render_frame(..., beats=..., done=...)`` run
to the end, so that the schedule holds every slice's decisions and COM's reports.

* ``sparse_frame``: a sparse volume (``cube4_testutil.sparse_case``: a faint background,
  one dense blob, every mode, seven views, cut planes) at S = 1, its LUT made nearly
  opaque on request (COM's reports then end rays), termination on or off.
* ``slab_frame``: a nearly opaque slab in front of a dense block (tests/test_beats.py
  ``opaque_slab``), shaded, with termination: rays end in the slab and many beats run
  only as GRA's neighbours of running ones.

Each returns a ``BeatFrame``: the schedule, the traversal and the volume's block bits.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

import cube4.beats as beats
from cube4.model import render_frame
from cube4.view import Traversal

BLOCK = 4


@dataclass
class BeatFrame:
    sched: beats.BeatSchedule
    trav: Traversal
    bits: np.ndarray            # (bz, by, bx) the block table's bits of the volume


def _run(vol, trav, cfg, lut, rmap, mode, shading, clip, terminate: bool) -> BeatFrame:
    bits = beats.BlockTable.of(vol, BLOCK).bits(lut, mode)
    occ = beats.frame_occupancy(bits, BLOCK, trav)
    sched = beats.BeatSchedule(trav, cfg.pipelines, occ, terminate=terminate, gra=shading and mode == "composite")
    rule = beats.TerminationRule(mode, 0, 1 << cfg.acc_bits, int(vol.min()), int(vol.max()),
                                 enabled=terminate, value_bits=cfg.voxel_bits)
    render_frame(vol, trav, cfg, lut, rmap, mode=mode, shading=shading, clip=clip, beats=sched, done=rule)
    return BeatFrame(sched, trav, bits)


def sparse_frame(seed: int, p: int, opaque: bool, terminate: bool) -> BeatFrame:
    from cube4_testutil import sparse_case
    vol, trav, cfg, lut, rmap, mode, shading, clip = sparse_case(seed)
    trav = dataclasses.replace(trav, supersample=1)
    cfg = dataclasses.replace(cfg, pipelines=p, supersample=1)
    if opaque and mode in ("composite", "xray"):
        lut = lut.copy()
        lut[lut[:, 3] > 0, 3] = (1 << cfg.alpha_bits) - 1
    return _run(vol, trav, cfg, lut, rmap, mode, shading, clip, terminate)


def slab_frame(p: int, direction) -> BeatFrame:
    from test_beats import opaque_slab
    vol, trav, cfg, lut, rmap = opaque_slab(p, direction)
    return _run(vol, trav, cfg, lut, rmap, "composite", True, None, True)


def bits_of(row) -> int:
    """A row of bools as an integer, bit n = row[n]."""
    return sum(1 << int(i) for i in np.flatnonzero(row))

"""What the testbenches of TRI's cell path share (tb/cube4_tri_src, tb/cube4_tri_beam): the
harness sim/hdl/cube4_tri_cell_harness.v (cube4_cfb reading cube4_voxel_mem, with seeded
Verilog stalls on the memory request and response, in front of cube4_tri_src and
cube4_tri_beam) driven from Python, the views, and the golden voxels of each beat.

A beat of the golden sample stream (``cube4_sim.beats.BeatSchedule``: slice m, row j,
partial beam pb; lane q holds i = pos[q]) is made of the voxels of the 2 x 2 x 2 cell of
each lane's sample: the lower voxel slice k0 = m // S and the upper one k0 + 1, rows j and
j + 1, positions i and i + 1 of the traversal-frame volume zero-padded at the high end of
each axis (``cube4.model.padded_traversal``, what ``interpolate_slice`` reads). A voxel
weighted by 0 is not read by the sample (lerp(a, b, 0) = a): ``needed`` says which are.
"""

from __future__ import annotations

import cocotb
import numpy as np
from cocotb.triggers import FallingEdge, ReadOnly

from cube4.memory import pack_volume
from cube4.model import inside_mask, padded_traversal
from cube4.vgrad import pack_words, word_bits
from cube4.view import Traversal, make_traversal

from .beats import BeatSchedule, Geometry, pack_lanes, unpack_lanes
from .sweeps import sweep
from .unit_bench import UnitBench, param_id, run_unit

DEPTH, ADDR_W = 4096, 12
# (direction, supersampled (S = 2^MAX_SS_LOG2, else 1), memory-request stall /256,
#  memory-response stall /256, starting phase)
VIEWS = [((0.3, -0.45, 1.0), False, 0, 0, (0, 0)),
         ((-0.6, 0.25, -1.0), True, 60, 120, (0, 0)),
         ((1.0, 0.4, -0.7), True, 0, 200, (101, 250)),
         ((-0.2, -1.0, -0.9), True, 30, 30, (200, 9))]


# the builds (MAX_DIM = 32): P = 1, S <= 2; P = 5, S <= 4 (later passes read the upper slice
# from its buffer), voxel gradients; `make regress` also P = 8, VOXEL_W = 12
CELL_BUILDS = sweep([dict(P=1, VOXEL_W=8, MAX_SS_LOG2=1, VGRAD=0), dict(P=5, VOXEL_W=8, MAX_SS_LOG2=2, VGRAD=1),
                     dict(P=8, VOXEL_W=12, MAX_SS_LOG2=2, VGRAD=0)], quick=(1,), ids=param_id)


def run_cells(test_file: str, build: dict) -> None:
    """Run a cell-path testbench (its ``__file__``) on the shared harness built with ``build``."""
    run_unit(test_file, {**build, "MAX_DIM": 32, "DEPTH": DEPTH, "ADDR_W": ADDR_W}, harness="cube4_tri_cell_harness",
             blocks=("cube4_sim_stall.v",))


class CellView:
    """One view's golden beats: the schedule (its headers with KEEP = LVALID, what s0 forms),
    the weights and the voxels of every beat."""

    def __init__(self, trav: Traversal, words: np.ndarray, p: int) -> None:
        self.trav = trav
        inside = np.stack([inside_mask(trav, m) for m in range(trav.num_sample_slices)])
        self.sched = BeatSchedule(trav, p, inside)     # KEEP = LVALID: what s0 forms
        self.tp = padded_traversal(words, trav)
        self.wx, self.wy, self.wz = trav.weights(self.sched.m)
        self.k0 = self.sched.m // trav.supersample

    def voxels(self, dk: int, dj: int, di: int) -> np.ndarray:
        """(beats, P) words at (k0 + dk, j + dj, i + di); 0 in lanes with no position."""
        s = self.sched
        i = np.minimum(s.pos, self.trav.ni - 1) + di
        return np.where(s.lval, self.tp[(self.k0 + dk)[:, None], (s.j + dj)[:, None], i], 0)

    def needed(self, dk: int, dj: int, di: int) -> np.ndarray:
        """(beats, P): the lanes whose sample reads that voxel (its weights are not 0)."""
        need = self.sched.lval.copy()
        for d, w in ((dk, self.wz), (dj, self.wy), (di, self.wx)):
            if d:
                need &= (w != 0)[:, None]
        return need


class CellBench(UnitBench):
    """UnitBench around the cell harness: the build, the volume, one view's run."""

    def __init__(self, dut) -> None:
        super().__init__(dut)
        self.p, self.vw, self.w = (int(self.sig(n).value) for n in ("P", "VOXEL_W", "WEIGHT_W"))
        self.vgrad = bool(int(dut.VGRAD.value))
        self.ww = word_bits(self.vw, self.vgrad)
        self.geo = Geometry(self.p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
        p = self.p
        self.dims = (max(11, 2 * p + 3), max(9, p + 4), max(8, p + 2))
        vol = self.rng.integers(0, 1 << self.vw, size=self.dims[::-1], dtype=np.int64)
        self.words = pack_words(vol, "central", self.vw) if self.vgrad else vol

    async def start(self) -> None:
        """Reset, then write the packed volume (cube4.memory) through the load port."""
        self.dut.seed.value = cocotb.RANDOM_SEED & 0xFFFFFFFF
        await self.reset({"start": 0, "ld_valid": 0, "stall_req": 0, "stall_in": 0})
        banks = pack_volume(self.words, self.p)
        assert banks.shape[1] <= DEPTH, f"volume needs {banks.shape[1]} words per bank, DEPTH = {DEPTH}"
        d = self.dut
        for a in range(banks.shape[1]):
            await FallingEdge(d.clk)
            d.ld_valid.value, d.ld_addr.value, d.ld_data.value = 1, a, pack_lanes(banks[:, a], self.ww)
        await FallingEdge(d.clk)
        d.ld_valid.value = 0

    def view(self, direction, supersampled: bool, phase) -> CellView:
        ss = (1 << self.geo.max_ss_log2) if supersampled else 1
        phase = tuple(ph % (1 << (self.w + self.geo.max_ss_log2)) for ph in phase)
        trav = make_traversal(self.dims, direction, self.w, ss, phase=phase)
        return CellView(trav, self.words, self.p)

    async def run_view(self, cv: CellView, stall_req: int, stall_in: int, record: str, signals,
                       tail: int = 60, limit: int = 200000) -> tuple[list[dict[str, int]], dict[str, int]]:
        """Start a frame of view ``cv`` and record ``signals`` in every cycle with ``record``
        (s1_v: the beats s1_ctl emits; s4_v) until as many beats as the view has came and
        ``tail`` cycles more. Also counts s1 beats, emitted s1 beats, s4 beats and gives."""
        d, n = self.dut, len(cv.sched)
        self.set_view(cv.trav, self.p, vol_dims=self.dims)
        d.stall_req.value, d.stall_in.value = stall_req, stall_in
        await FallingEdge(d.clk)
        d.start.value = 1
        await FallingEdge(d.clk)
        d.start.value = 0
        emit_bit = self.geo.hdr_w + 2 * self.p + 3 * self.w   # TRI_C_EMIT (cube4_defs.vh)
        counts = dict(s1=0, emit=0, s4=0, give=0)
        got, quiet, cycle = [], 0, 0
        while quiet < tail:
            await ReadOnly()
            s1 = int(d.s1_v.value)
            emit = s1 and (int(d.s1_ctl.value) >> emit_bit) & 1
            s4 = int(d.s4_v.value)
            counts["s1"] += s1
            counts["emit"] += emit
            counts["s4"] += s4
            counts["give"] += int(d.give.value)
            if (emit if record == "s1_v" else s4):
                got.append({name: int(self.sig(name).value) for name in signals})
            quiet += int(len(got) >= n)
            cycle += 1
            assert cycle < limit, f"{len(got)} of {n} beats after {cycle} cycles"
            await FallingEdge(d.clk)
        assert len(got) == n, f"{len(got)} beats, expected {n}: {len(got) - n} extra within {tail} cycles"
        return got, counts

    def lanes(self, words: list[int], slot: int, per_lane: int) -> np.ndarray:
        """(beats, P): word ``slot`` of the ``per_lane`` words of each lane of each beat."""
        stride = per_lane * self.ww
        return np.stack([unpack_lanes(v >> (slot * self.ww), self.p, self.ww, stride=stride) for v in words])

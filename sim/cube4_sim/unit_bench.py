"""What the unit testbenches of tb/ share: how each is built and run (``run_unit`` for a
unit harness, ``run_rtl`` for a unit tested directly, ``param_id`` naming its parameter
sets) and the cocotb side of the harnessed ones (tb/cube4_tri, _gra*, _sha, _com*).

A unit harness (tb/cube4_<unit>/cube4_<unit>_harness.v) has a Verilog clock, the unit's
view registers as individual ``cfg_*`` ports, and the unit's input and output
streams as top-level ports with a cube4_stream_check on each. ``UnitBench``
drives them from Python, one clock at a time (the volumes are small):

* the input stream: the golden beats in order, with random gaps in valid (a
  beat once offered is held, unchanged, until taken);
* the output stream: random ready; every transfer is recorded;
* after the last expected output beat the bench keeps ready high for ``tail``
  cycles and then requires that exactly the expected number of beats came out
  (nothing extra, nothing missing).

Randomness comes from ``cocotb.RANDOM_SEED`` (COCOTB_RANDOM_SEED reproduces a run).
Handshake timing: inputs change just after the falling edge; in the read-only
phase of that time step the bench samples in_ready / out_valid / data, so a
transfer it records is exactly one that the next rising edge performs.
``SourceBench`` drives GRA's source instead, which steps on its output FIFO's credit.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Sequence
from pathlib import Path

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge, Timer

from cube4.memory import top_regs
from cube4.view import Traversal

from .beats import Geometry
from .runner import SIM_HDL_DIR, run_test
from .sources import form_build_args, form_sources, rtl_sources


def param_id(params: dict) -> str:
    """A test id naming a parameter set: {"P": 5, "VOXEL_W": 8} -> "P=5,VOXEL_W=8"."""
    return ",".join(f"{k}={v}" for k, v in params.items())


def harness_sources(*files, form: str = "generic") -> list:
    """rtl/sources.f (the one list of RTL sources, dependency order; ``form`` "ecp5": with
    the vendor layer's forms and the primitives' models), the Verilog clock, then the
    simulation files named: a Path as it is (a harness beside its testbench), a bare name
    from sim/hdl/ (the shared simulation blocks, e.g. cube4_sim_stall.v)."""
    extra = [f if isinstance(f, Path) else SIM_HDL_DIR / f for f in files]
    return [*form_sources(form), SIM_HDL_DIR / "cube4_sim_clock.v", *extra]


def run_unit(test_file: str, params: dict, testcase: str | None = None, harness: str | None = None,
             blocks: tuple[str, ...] = (), form: str = "generic") -> None:
    """Build the harness of the unit testbench ``test_file`` (tb/<unit>/test_<unit>.py, its
    ``__file__``) with ``params`` and run the testbench's cocotb tests (or ``testcase``) on it.
    The harness is <unit>_harness.v beside the testbench, or ``harness``, the name of a
    shared one in sim/hdl/; ``blocks``: the sim/hdl/ blocks it instantiates besides the
    Verilog clock (which needs Verilator's --timing); ``form``: the RTL form
    (cube4_sim.sources.RTL_FORMS; "ecp5" simulates the vendor layer)."""
    here = Path(test_file).resolve().parent
    top = harness or f"{here.name}_harness"
    src = SIM_HDL_DIR / f"{top}.v" if harness else here / f"{top}.v"
    run_test(top=top, sources=harness_sources(*blocks, src, form=form), params=params, test_module=test_file,
             testcase=testcase, timing=True, build_args=form_build_args(form))


def run_rtl(test_file: str, params: dict) -> None:
    """Run the testbench ``test_file`` (tb/<unit>/test_<unit>.py, its ``__file__``) on the
    RTL unit <unit> itself (rtl/sources.f), built with ``params``; the testbench drives the
    clock from cocotb."""
    top = Path(test_file).resolve().parent.name
    run_test(top=top, sources=rtl_sources(), params=params, test_module=test_file)


def top_params(dut, *names: str) -> list[int]:
    """The values of the top's parameters ``names`` (the runner makes them VPI-visible)."""
    return [int(getattr(dut, name).value) for name in names]


def start_clock(dut) -> None:
    """Start the cocotb clock of a top without a Verilog clock: 10 ns, low first (the
    first rising edge at 5 ns)."""
    Clock(dut.clk, 10, unit="ns").start(start_high=False)


class QueueCheck:
    """A queue's stream (in_valid/in_ready/in_data, out_valid/out_ready/out_data) against a
    Python deque, one cycle at a time: call ``observe`` in ReadOnly after driving the
    cycle's inputs. The head must be the oldest item not yet taken and stay put while not
    taken; with ``empty_only_when_low`` out_valid may be low only with nothing held (a
    queue of latency one)."""

    def __init__(self, dut, empty_only_when_low: bool = False) -> None:
        self.dut = dut
        self.model: deque[int] = deque()
        self.sent = self.got = 0
        self.held: int | None = None          # out_data seen while not taken
        self.empty_only_when_low = empty_only_when_low

    def observe(self, valid: bool, ready: bool, data: int) -> tuple[bool, bool]:
        """The transfers of the coming edge, checked and recorded: (pushed, popped)."""
        d = self.dut
        pushed = valid and bool(int(d.in_ready.value))
        ov = int(d.out_valid.value)
        popped = ready and bool(ov)
        if ov:
            od = int(d.out_data.value)
            assert self.model, f"out_valid with nothing in the model (item {self.got})"
            assert od == self.model[0], f"item {self.got}: RTL {od:#x}, model {self.model[0]:#x}"
            if self.held is not None:
                assert self.held == od, "out_data changed while out_ready was low"
            self.held = None if popped else od
        elif self.empty_only_when_low:
            assert not self.model, f"{len(self.model)} items held and out_valid low (item {self.got})"
        if popped:
            self.model.popleft()
            self.got += 1
        if pushed:
            self.model.append(data)
            self.sent += 1
        return pushed, popped


class QueueTB:
    """The bench of a queue with one stream in and one out (cube4_skid, cube4_skid_oreg,
    cube4_ram_fifo, cube4_skid_fifo): a seeded generator, a QueueCheck, the clock; reset, random words
    and one cycle of driven valid and ready with its transfers checked; a queue with the
    port in_ready_nx (in_ready's next value) has it checked against in_ready after each edge."""

    def __init__(self, dut, empty_only_when_low: bool = False, ready_is_register: bool = False) -> None:
        self.dut = dut
        self.ready_is_register = ready_is_register
        self.has_ready_nx = hasattr(dut, "in_ready_nx")
        (self.data_w,) = top_params(dut, "DATA_W")
        self.rng = np.random.default_rng(cocotb.RANDOM_SEED)
        self.q = QueueCheck(dut, empty_only_when_low=empty_only_when_low)
        start_clock(dut)

    async def reset(self) -> None:
        d = self.dut
        d.in_valid.value, d.in_data.value, d.out_ready.value = 0, 0, 0
        d.rst.value = 1
        for _ in range(3):
            await RisingEdge(d.clk)
        await FallingEdge(d.clk)
        d.rst.value = 0

    def word(self) -> int:
        """Random bits in every 64-bit group, the sent count in the top bits."""
        w = 0
        for lo in range(0, self.data_w, 62):
            w |= int(self.rng.integers(0, 1 << 62)) << lo
        w ^= self.q.sent << max(0, self.data_w - 16)
        return w & ((1 << self.data_w) - 1)

    async def drive(self, valid: bool, ready: bool, data: int) -> None:
        """The cycle's inputs; with ``ready_is_register`` the other out_ready first, and
        in_ready must not follow out_ready within the cycle."""
        d = self.dut
        if not self.ready_is_register:
            d.in_valid.value, d.in_data.value, d.out_ready.value = int(valid), data, int(ready)
            return
        d.in_valid.value, d.in_data.value, d.out_ready.value = int(valid), data, int(not ready)
        await Timer(1, "ns")
        ready_other = int(d.in_ready.value)
        d.out_ready.value = int(ready)
        await Timer(1, "ns")
        assert int(d.in_ready.value) == ready_other, "in_ready follows out_ready within a cycle"

    async def cycle(self, valid: bool, ready: bool) -> tuple[bool, bool]:
        """One cycle: drive, record the transfers of the coming edge; (pushed, popped)."""
        data = self.word()
        await self.drive(valid, ready, data)
        await ReadOnly()
        flow = self.q.observe(valid, ready, data)
        nx = int(self.dut.in_ready_nx.value) if self.has_ready_nx else None
        await RisingEdge(self.dut.clk)
        await FallingEdge(self.dut.clk)
        if nx is not None:
            assert int(self.dut.in_ready.value) == nx, \
                f"in_ready = {int(self.dut.in_ready.value)} after an edge with in_ready_nx = {nx}"
        return flow

    async def edges_to_out(self) -> int:
        """Into an empty queue: one item in, then the edges after the one that took it
        until it is on out_valid (out_ready low); the item stays held."""
        await self.cycle(True, False)
        edges = 0
        while not int(self.dut.out_valid.value):
            await self.cycle(False, False)
            edges += 1
        return edges

    async def fill(self, cycles: int) -> int:
        """Offer an item every cycle with out_ready low; the items held after."""
        for _ in range(cycles):
            await self.cycle(True, False)
        return len(self.q.model)

    async def drain(self, cycles: int | None = None) -> None:
        """out_ready high, nothing offered: until the model is empty, or ``cycles`` cycles."""
        n = 0
        while (self.q.model if cycles is None else n < cycles):
            await self.cycle(False, True)
            n += 1

    async def skid_checks(self) -> None:
        """A two-entry skid buffer's stream (cube4_skid_peek, cube4_skid_oreg), from reset:
        latency one edge, capacity two (then in_ready low), one item in and one out a cycle
        at full rate from full, a drain, then random traffic with nothing left over."""
        d = self.dut
        await self.cycle(True, False)
        assert int(d.out_valid.value), "an item is not on out_valid one edge after the edge that took it"
        await self.cycle(False, True)
        held = await self.fill(6)
        assert held == 2, f"the buffer took {held} items, not 2"
        assert not int(d.in_ready.value), "in_ready high with two items held"
        flow = [await self.cycle(True, True) for _ in range(64)]
        assert all(q for _, q in flow), "not one item out a cycle at full rate"
        assert all(p for p, _ in flow[1:]), "not one item in a cycle at full rate"
        await self.drain()
        await self.random_traffic(3000, 8)

    async def random_traffic(self, cycles: int, tail: int) -> None:
        """Random valid (0.6) and ready (0.55) for ``cycles``, then ``tail`` cycles of
        draining; nothing may be left in the model or on out_valid."""
        for _ in range(cycles):
            await self.cycle(bool(self.rng.random() < 0.6), bool(self.rng.random() < 0.55))
        await self.drain(tail)
        assert not self.q.model and not int(self.dut.out_valid.value), f"{len(self.q.model)} items never came out"


class UnitBench:
    """Python source and sink around one unit harness."""

    def __init__(self, dut) -> None:
        self.dut = dut
        self.log = dut._log
        self.rng = np.random.default_rng(cocotb.RANDOM_SEED)

    def sig(self, name: str):
        return getattr(self.dut, name)

    async def cycles(self, n: int) -> None:
        for _ in range(n):
            await RisingEdge(self.dut.clk)

    async def reset(self, idle: dict[str, int]) -> None:
        """Reset with the given inputs idle (e.g. in_valid = 0, out_ready = 0)."""
        for name, val in idle.items():
            self.sig(name).value = val
        self.dut.rst.value = 1
        await self.cycles(4)
        self.dut.rst.value = 0
        await self.cycles(2)

    def set_view(self, trav: Traversal, p: int, mode: str = "composite", clip=None, vol_dims=None,
                 path_weights: bool = False) -> None:
        """Write the host's registers (cube4.memory.top_regs) to the harness's cfg_*
        ports; a harness without the address unit has no ports for its registers.
        vol_dims: the volume in memory when trav is a box inside it (a crop);
        path_weights: FACES = trav.faces (else 0)."""
        for key, val in top_regs(trav, p, vol_dims, mode=mode, clip=clip, path_weights=path_weights).items():
            name = "cfg_" + key.lower()
            if hasattr(self.dut, name):
                self.sig(name).value = int(val)

    async def run_stream(self, inputs: list[dict[str, int]] | None, expected: int, outputs: list[str],
                         gap: float, stall: float, tail: int = 300, limit: int = 200000) -> list[dict[str, int]]:
        """Offer ``inputs`` (signal -> value per beat; None: the harness makes its own
        input) on in_valid / in_ready with gap probability ``gap`` per cycle, take
        output beats with ready probability 1 - ``stall``, until ``expected`` beats
        came out and every input was taken; then ``tail`` cycles with ready high.
        Returns the output beats (signal -> value), in order."""
        d = self.dut
        got: list[dict[str, int]] = []
        k, offering, cycle, quiet = 0, False, 0, 0
        n_in = 0 if inputs is None else len(inputs)
        while quiet < tail:
            await FallingEdge(d.clk)
            if inputs is not None:
                if not offering and k < n_in and self.rng.random() >= gap:
                    for name, val in inputs[k].items():
                        self.sig(name).value = val
                    offering = True
                d.in_valid.value = int(offering)
            done = len(got) >= expected and k == n_in
            ready = 1 if done else int(self.rng.random() >= stall)
            d.out_ready.value = ready
            await ReadOnly()
            if offering and int(d.in_ready.value):
                offering, k = False, k + 1
            if ready and int(d.out_valid.value):
                got.append({name: int(self.sig(name).value) for name in outputs})
            if done:
                quiet += 1
            cycle += 1
            assert cycle < limit, (f"{len(got)} of {expected} output beats and {k} of {n_in} input beats "
                                   f"after {cycle} cycles")
        await FallingEdge(d.clk)
        if inputs is not None:
            d.in_valid.value = 0
        d.out_ready.value = 0
        assert len(got) == expected, (f"{len(got)} output beats, expected {expected}: "
                                      f"{len(got) - expected} extra beat(s) within {tail} cycles of the last one")
        return got


class SourceBench(UnitBench):
    """UnitBench around GRA's source (sim/hdl/cube4_gra_source_harness.v; tb/cube4_gra_lines,
    tb/cube4_gra_walk): the build's parameters and geometry, and a random test volume whose
    rows span several beams (2P + 1 voxels, at least 7)."""

    def __init__(self, dut) -> None:
        super().__init__(dut)
        self.p, self.vw, self.w = (int(self.sig(n).value) for n in ("P", "VOXEL_W", "WEIGHT_W"))
        self.geo = Geometry(self.p, int(dut.MAX_DIM.value), int(dut.MAX_SS_LOG2.value))
        self.dims = (max(7, 2 * self.p + 1), 6, 5)
        self.vol = self.rng.integers(0, 1 << self.vw, size=self.dims[::-1], dtype=np.int64)

    async def run_steps(self, inputs: list[dict[str, int]], n_steps: int, record: Sequence[str], gap: float,
                        stall: float, tail: int = 30) -> list[dict[str, int]]:
        """Offer ``inputs`` with gap probability ``gap``, give the output FIFO's credit with
        probability 1 - ``stall``, and record the signals ``record`` in every cycle with
        step = 1, until ``n_steps`` steps happened and every input was taken; then ``tail``
        cycles with the credit high and no input (a step there is an extra one). Returns the
        steps, in order."""
        d = self.dut
        got, k, offering, quiet, cycle = [], 0, False, 0, 0
        while quiet < tail:
            await FallingEdge(d.clk)
            if not offering and k < len(inputs) and self.rng.random() >= gap:
                for name, val in inputs[k].items():
                    self.sig(name).value = val
                offering = True
            d.in_valid.value = int(offering)
            done = len(got) >= n_steps and k == len(inputs)
            d.credit.value = 1 if done else int(self.rng.random() >= stall)
            await ReadOnly()
            if offering and int(d.in_ready.value):
                offering, k = False, k + 1
            if int(d.step.value):
                got.append({n: int(self.sig(n).value) for n in record})
            quiet += int(done)
            cycle += 1
            assert cycle < 200000, f"{len(got)} of {n_steps} steps and {k} of {len(inputs)} beats after {cycle} cycles"
        await FallingEdge(d.clk)
        d.in_valid.value = 0
        d.credit.value = 0
        assert len(got) == n_steps, f"{len(got)} steps, expected {n_steps}: {len(got) - n_steps} extra"
        return got


MAX_MISMATCH_LOGS = 8


def check_headers(got: list[int], want: list[int], geo, sched, log, stream: str) -> None:
    """Every output beat's header equals the golden one, field by field."""
    bad = [n for n, (g, w) in enumerate(zip(got, want)) if g != w]
    for n in bad[:MAX_MISMATCH_LOGS]:
        g, w = geo.unpack_header(got[n]), geo.unpack_header(want[n])
        diff = {k: (g[k], w[k]) for k in g if g[k] != w[k]}
        log.error("%s %s: header fields (RTL, golden) %s", stream, sched.describe(n), diff)
    assert not bad, f"{stream}: {len(bad)} beat headers differ from the golden model, first at {sched.describe(bad[0])}"


def check_lanes(got: np.ndarray, want: np.ndarray, valid: np.ndarray, sched, log, what: str,
                beat: np.ndarray | None = None) -> None:
    """Per-lane values (beats, P) equal the golden ones in every lane where ``valid``
    (by default the lanes that hold a position: lanes beyond NI carry no sample).
    ``beat``: the schedule's beat of each compared beat (default: the same index)."""
    where = np.arange(len(got)) if beat is None else beat
    bad = np.argwhere(valid & (got != want))
    for n, q in bad[:MAX_MISMATCH_LOGS]:
        log.error("%s %s: RTL %d, golden %d", what, sched.describe(where[n], q), got[n, q], want[n, q])
    assert bad.size == 0, (f"{len(bad)} {what} lanes differ from the golden model, first at "
                           f"{sched.describe(where[bad[0][0]], bad[0][1])}")


def random_clip(trav, kind: str | None, rng):
    """A window, a cut plane and/or crop regions for testbenches (``kind``: None or
    names joined by "+": "window", "cut", "regions"): the window keeps a random
    sub-box of the samples, the plane passes near the volume's centre in a random
    direction, so both sides hold samples, and the regions are a random box's 27
    regions (a low face may lie outside the traversed box) with random flags."""
    from cube4.clip import Clip, crop_regions, cut_coefficients

    if kind is None:
        return None
    window = plane = regions = None
    if "regions" in kind:
        o, n = np.asarray(trav.origin), np.asarray(trav.dims)
        lo = o + rng.integers(-1, np.maximum(n // 2, 1))
        hi = lo + rng.integers(0, np.maximum(n // 2, 1) + 1)
        regions = crop_regions(trav, lo, hi, int(rng.integers(1, 1 << 27)))
    if "window" in kind:
        M = trav.num_sample_slices
        i0, j0, m0 = (int(rng.integers(0, max(1, n // 3))) for n in (trav.ni, trav.nj, M))
        i1, j1, m1 = (int(rng.integers(max(lo + 1, 2 * n // 3), n + 1)) for lo, n in
                      ((i0, trav.ni), (j0, trav.nj), (m0, M)))
        window = (i0, i1, j0, j1, m0, m1)
    if "cut" in kind:
        normal = rng.normal(size=3)
        centre = np.asarray(trav.origin, dtype=np.float64) + (np.asarray(trav.dims) - 1) / 2.0
        point = centre + rng.uniform(-0.2, 0.2, size=3) * np.asarray(trav.dims)
        plane = cut_coefficients(trav, normal, point)
    return Clip(window=window, plane=plane, regions=regions)

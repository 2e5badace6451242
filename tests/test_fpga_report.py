"""`make fpga` (sim/cube4_reports/fpga.py) over several nextpnr seeds: the median seed, the
flatness figure, the per-seed cache, the order of the runs, the options, and the rtl/ commit
stamp (cube4_reports.markdown). Fast: no Yosys or nextpnr run."""

from __future__ import annotations

import json
import subprocess
import threading
import time
from pathlib import Path

import pytest

from cube4 import cycles
from cube4_reports import fpga, fpga_memory, markdown
from cube4_reports.synth import UserError


def run_of(seed: int, fmax: float | None, tmp_path: Path, luts: int = 1000, rc: int = 0) -> fpga.SeedRun:
    """A finished seed run with a timing report (and a critical path naming the seed)."""
    d = tmp_path / f"seed{seed}"
    d.mkdir(parents=True, exist_ok=True)
    (d / "nextpnr.log").write_text("ERROR: Unable to place cell\n" if rc else "")
    report = {} if fmax is None else {
        "fmax": {"clk": {"achieved": fmax}},
        "critical_paths": [{"path": [
            {"type": "clk-to-q", "from": {"cell": f"u_com.s{seed}", "port": "CLK"},
             "to": {"cell": "u_com.b", "port": "A"}, "delay": 0.5, "net": "n1"},
            {"type": "routing", "from": {"cell": "u_com.b", "port": "A"}, "to": {"cell": "u_com.c", "port": "D"},
             "delay": 1.5, "net": "n2"}]}]}
    return fpga.SeedRun(seed, d, rc, 100.0 + seed, report, {"TRELLIS_COMB": (luts, 83640)})


def cfg_of(p: int = 8, seeds: tuple[int, ...] = (1, 2, 3)) -> fpga.BuildConfig:
    return fpga.BuildConfig(p=p, max_dim=16, depth=64, freq=125.0, seeds=seeds)


# ------------------------------------------------------------------ median, min, max
def test_median_seed_odd_even_and_failed(tmp_path):
    runs = [run_of(1, 80.0, tmp_path), run_of(2, 90.0, tmp_path), run_of(3, 70.0, tmp_path)]
    assert fpga.median_run(runs).seed == 1
    assert fpga.median_run(runs[:2]).seed == 1            # even count: the lower of the two middle ones
    assert fpga.median_run([runs[1], runs[0]]).seed == 1  # not the order given
    failed = run_of(4, None, tmp_path, rc=1)
    assert fpga.median_run([failed, runs[1], runs[2]]).seed == 3   # a failed run ranks lowest
    assert fpga.median_run([failed, runs[1]]).seed == 4 and fpga.median_run([failed, runs[1]]).fmax is None
    tie = [run_of(5, 80.0, tmp_path), run_of(1, 80.0, tmp_path), run_of(2, 90.0, tmp_path)]
    assert fpga.median_run(tie).seed == 5                  # equal Fmax: seed order


def test_seed_fields(tmp_path):
    runs = [run_of(3, 70.0, tmp_path), run_of(1, 80.0, tmp_path), run_of(2, 90.0, tmp_path),
            run_of(4, None, tmp_path, rc=1)]
    f = fpga.seed_fields(runs)
    assert [s["seed"] for s in f["fmax_seeds"]] == [1, 2, 3, 4]
    assert [s["fmax_mhz"] for s in f["fmax_seeds"]] == [80.0, 90.0, 70.0, None]
    assert f["fmax_seeds"][0]["wall_s"] == 101.0 and "u_com.s1" in f["fmax_seeds"][0]["critical_path"]
    assert f["fmax_seeds"][3]["critical_path"].startswith("failed: nextpnr exit 1: ERROR")
    assert (f["fmax_median"], f["fmax_min"], f["fmax_max"]) == (70.0, 70.0, 90.0)  # 4 runs: lower middle
    none = fpga.seed_fields([run_of(1, None, tmp_path, rc=1)])
    assert (none["fmax_median"], none["fmax_min"], none["fmax_max"]) == (None, None, None)


def test_combine_takes_the_median_seeds_run(tmp_path, monkeypatch):
    monkeypatch.setattr(fpga, "SYNTH_DIR", tmp_path)
    runs = [run_of(2, 90.0, tmp_path, luts=222), run_of(3, 70.0, tmp_path, luts=333),
            run_of(1, 80.0, tmp_path, luts=111)]
    res = fpga.combine(cfg_of(), {"LUT4": 5, "DP16KD": 3}, 12.5, runs)
    assert res["seed"] == 1 and res["fmax_mhz"] == res["fmax_median"] == 80.0
    assert (res["fmax_min"], res["fmax_max"]) == (70.0, 90.0)
    assert res["luts"] == 111 and res["ebrs"] == 3         # nextpnr's count of the median seed; else Yosys's
    assert "u_com.s1" in res["critical_path"] and res["log"].endswith("seed1/nextpnr.log")
    assert res["wall_s"] == 12.5 + 101.0 and res["pnr_s"] == 101.0 and res["fits"]


# ------------------------------------------------------------------ the report's lines
def result(p: int, med: float | None, lo: float | None = None, hi: float | None = None) -> dict:
    return {"p": p, "fmax_mhz": med, "fmax_median": med, "fmax_min": lo or med, "fmax_max": hi or med,
            "fmax_seeds": [{"seed": 1, "fmax_mhz": lo or med}, {"seed": 2, "fmax_mhz": med},
                           {"seed": 3, "fmax_mhz": hi or med}],
            "seed": 2, "luts": 100, "ffs": 100, "dsps": 1, "ebrs": 1, "dpr16x4": 0, "fits": med is not None,
            "wall_s": 10.0, "critical_path": "COM: a -> b" if med else "does not fit: 258 DSPs > 156"}


def test_flatness_over_p_1_2_4_8():
    rs = [result(1, 100.0), result(2, 95.0), result(4, 92.0), result(8, 90.0), result(16, None)]
    f = fpga.flatness(rs)
    assert f == {"ps": [1, 2, 4, 8], "min_mhz": 90.0, "max_mhz": 100.0, "spread_pct": 10.0}
    assert ": met, 10.0 % over P = 1, 2, 4, 8 (90.0 – 100.0 MHz)" in fpga.flatness_line(rs)
    rs[3] = result(8, 80.0)
    assert fpga.flatness(rs)["spread_pct"] == 20.0 and "**not met**, 20.0 %" in fpga.flatness_line(rs)
    assert fpga.flatness([result(4, 60.0), result(16, 200.0), result(8, 66.0)])["spread_pct"] == pytest.approx(9.1)
    one = [result(1, 100.0), result(8, None)]
    assert fpga.flatness(one) == {"ps": [1], "spread_pct": None}
    assert "needs two of those P with an Fmax; this run has P = 1." in fpga.flatness_line(one)


def test_goal_line_judges_the_median():
    assert "met (130.0 MHz; seeds 120.0 – 140.0)" in fpga.goal_line([result(8, 130.0, 120.0, 140.0)])
    line = fpga.goal_line([result(8, 100.0, 90.0, 130.0)])   # one seed above the goal is not enough
    assert "**not met** (100.0 MHz; seeds 90.0 – 130.0)" in line
    assert "**not met** (does not fit" in fpga.goal_line([result(8, None)])
    assert fpga.goal_line([result(1, 100.0)]) == "P = 8 was not built in this run."


def test_markdown_tables_and_header():
    rs = [result(1, 86.27, 80.0, 95.84), result(8, 77.8, 76.2, 80.1)]
    table = fpga.resource_table(rs).splitlines()
    assert "| P | Fmax median (MHz) | seeds (min – max) |" in table[0]
    assert table[2].startswith("| 1 | 86.3 | 1: 80.0, 2: 86.3, 3: 95.8 (80.0 – 95.8) | 100 |")
    assert all(line.count("|") == table[0].count("|") for line in table)
    meta = {"yosys": "Yosys", "nextpnr": "nextpnr", "git": "abc1234", "rtl_commit": "rtl/ at commit 1234567",
            "rtl_digest": "d", "freq": 125.0, "seeds": [1, 2, 3], "jobs": 2, "router": "router2",
            "max_dim": 128, "depth": 1024, "build": ""}
    md = fpga.render_markdown(rs, [], meta)
    assert "RTL: git abc1234, rtl/ at commit 1234567, sources sha256 d." in md
    assert "nextpnr seeds 1, 2 and 3 (one run per `--seed`" in md and "2 at a time" in md
    assert "--seed 1" not in md and "Flatness (aim" in md and "- P = 8 (seed 2, the median):" in md
    assert fpga.seeds_text([7]) == "seed 7"


def mem(who: str, n: int, p: int, clock: float, cycles: int, ideal: int) -> dict:
    return {"who": who, "n": n, "p": p, "clock_mhz": clock, "formula_cycles": ideal, "ideal_cycles": ideal,
            "cycles": cycles, "ratio": ideal / cycles, "mb_per_s": 550.0, "needed_mb_per_s": 1100.0, "wall_s": 1.0}


def test_board_record_takes_the_median_seeds_pipeline_clock(tmp_path):
    def run(seed, pipe):
        util = {k: {"used": seed * 10, "available": 1} for k in ("TRELLIS_COMB", "TRELLIS_FF", "MULT18X18D", "DP16KD")}
        return {"seed": seed, "rc": 0, "synth_s": 60.0, "pnr_s": 600.0, "utilization": util,
                "fmax": {"$glbnet$crg_ecp5pll1_clkout": {"achieved": pipe}, "$glbnet$sys_clk": {"achieved": 80.0}}}
    path = tmp_path / "board.json"
    assert fpga_memory.board_record(path) is None
    path.write_text(json.dumps({"board": "B", "p": 4, "params": {"MAX_DIM": 128}, "commit": "abc",
                                "runs": [run(1, 90.0), run(2, 70.0), run(3, 80.0)]}))
    b = fpga_memory.board_record(path)
    assert (b["seed"], b["fmax_mhz"], b["luts"], b["sys_mhz"]) == (3, 80.0, 30, 80.0)
    row = fpga_memory.board_resource_row(b)
    assert row[0].startswith("4, on the B with LiteDRAM") and row[1] == "80.0" and row[2] == "1: 90.0, 2: 70.0, 3: 80.0"


def test_rate_table_with_the_dram():
    rs = [result(4, 150.0), result(8, 137.7)]
    n4, n8 = cycles.frame_cycles(128, 128, 128, 4), cycles.frame_cycles(128, 128, 128, 8)
    memory = [mem("P = 4", 128, 4, 150.0, int(n4 / 0.9), n4), mem("P = 8", 128, 8, 137.7, 2 * n8, n8)]
    lines = fpga.rate_table(rs, memory).splitlines()
    assert all(line.count("|") == lines[0].count("|") for line in lines)
    p8 = next(line for line in lines if line.startswith("| ours, P = 8 |"))
    assert f"**{137.7e6 / (2 * n8):,.2f}** ({137.7e6 / n8:,.2f}; 0.500)" in p8
    assert "ideal memory, not measured" in p8                # 256³ and 512³ were not measured here
    assert "**4**" in fpga_memory.saturation_line(memory) and fpga_memory.ideal_matches(memory)
    memory[0]["ratio"] = 0.8
    assert "none measured" in fpga_memory.saturation_line(memory)
    meta = {"yosys": "Yosys", "nextpnr": "nextpnr", "git": "abc1234", "rtl_commit": "r", "rtl_digest": "d",
            "freq": 125.0, "seeds": [1], "jobs": 1, "router": "router1", "max_dim": 128, "depth": 1024, "build": ""}
    md = fpga.render_markdown(rs, [], meta, memory, None)
    assert "Frames/s with the voxel memory in DRAM" in md and "No board row" in md
    assert "Every frame with the DRAM:" in md and "Frames/s with the voxel memory" not in fpga.render_markdown(rs, [], meta)


# ------------------------------------------------------------------ cache and work order
def test_keys_and_folders_per_seed():
    cfg = cfg_of()
    assert cfg.seed_dir(2) == cfg.workdir() / "seed2" and cfg.workdir().name == "p8_d16_w64"
    assert cfg.key("d", 1) != cfg.key("d", 2) and cfg.key("d", 1) == cfg_of(seeds=(1,)).key("d", 1)
    other = fpga.BuildConfig(p=8, max_dim=16, depth=64, freq=100.0, router="router1")
    assert other.key("d", 1) != cfg.key("d", 1)
    assert other.synth_key("d") == cfg.synth_key("d") != cfg.synth_key("e")   # synthesis: RTL and parameters
    assert cfg_of(p=4).synth_key("d") != cfg.synth_key("d")


def test_reuse_is_per_seed(tmp_path, monkeypatch):
    monkeypatch.setattr(fpga, "SYNTH_DIR", tmp_path)
    cfg = cfg_of(seeds=(1, 2))
    ran = []

    def fake_pnr(c, seed, timeout_s):
        ran.append(seed)
        sd = c.seed_dir(seed)
        sd.mkdir(parents=True, exist_ok=True)
        (sd / "report.json").write_text(json.dumps({"fmax": {"clk": {"achieved": 50.0 + seed}}}))
        return 0, 3.0

    monkeypatch.setattr(fpga, "run_pnr", fake_pnr)
    first = [fpga.place_and_route(cfg, s, "digest", 10.0, reuse=True) for s in (1, 2)]
    assert ran == [1, 2] and [r.fmax for r in first] == [51.0, 52.0]
    assert json.loads((cfg.seed_dir(2) / "result.json").read_text())["key"] == cfg.key("digest", 2)
    again = [fpga.place_and_route(cfg, s, "digest", 10.0, reuse=True) for s in (1, 2, 3)]
    assert ran == [1, 2, 3] and [r.fmax for r in again] == [51.0, 52.0, 53.0] and again[0].wall_s == 3.0
    fpga.place_and_route(cfg, 1, "new rtl", 10.0, reuse=True)
    fpga.place_and_route(cfg, 2, "digest", 10.0, reuse=False)
    assert ran == [1, 2, 3, 1, 2]
    # a run stopped at its time limit (exit status -1) is run again, not reused
    stopped = json.loads((cfg.seed_dir(3) / "result.json").read_text())
    (cfg.seed_dir(3) / "result.json").write_text(json.dumps({**stopped, "rc": -1}))
    fpga.place_and_route(cfg, 3, "digest", 10.0, reuse=True)
    assert ran == [1, 2, 3, 1, 2, 3]


def test_build_all_largest_p_first_synth_before_its_seeds(tmp_path, monkeypatch):
    monkeypatch.setattr(fpga, "SYNTH_DIR", tmp_path)
    events, lock = [], threading.Lock()

    def fake_synth(cfg, digest, reuse):
        with lock:
            events.append(("synth", cfg.p))
        return {"LUT4": cfg.p}, 1.0

    def fake_pnr(cfg, seed, digest, timeout_s, reuse):
        with lock:
            events.append(("pnr", cfg.p, seed))
        return run_of(seed, 10.0 * cfg.p + seed, tmp_path / f"p{cfg.p}")

    monkeypatch.setattr(fpga, "synthesize", fake_synth)
    monkeypatch.setattr(fpga, "place_and_route", fake_pnr)
    cfgs = [cfg_of(p=p, seeds=(3, 1, 2)) for p in (1, 8, 2)]
    res = fpga.build_all(cfgs, 10.0, "d", False, jobs=1)
    assert [r["p"] for r in res] == [1, 8, 2]                       # in the order asked for
    assert [r["fmax_median"] for r in res] == [12.0, 82.0, 22.0] and all(r["seed"] == 2 for r in res)
    assert [e for e in events if e[0] == "pnr"][:3] == [("pnr", 8, 3), ("pnr", 8, 1), ("pnr", 8, 2)]
    assert [e[1] for e in events if e[0] == "synth"] == [8, 2, 1]
    for p in (1, 2, 8):
        assert events.index(("synth", p)) < min(events.index(("pnr", p, s)) for s in (1, 2, 3))
    events.clear()
    assert [r["fmax_median"] for r in fpga.build_all(cfgs, 10.0, "d", False, jobs=3)] == [12.0, 82.0, 22.0]
    assert len(events) == 12


# ------------------------------------------------------------------ options
def args_of(*argv: str):
    return fpga.parse_args(list(argv))


def test_seed_options():
    assert fpga.seeds_of(args_of()) == (1, 2, 3)
    assert fpga.seeds_of(args_of("--seed", "7")) == (7,)
    assert fpga.seeds_of(args_of("--seeds", "4,5")) == (4, 5)
    for argv, msg in ((("--seed", "1", "--seeds", "1,2"), "--seed and --seeds both given"),
                      (("--seeds", "1,x"), "expected comma-separated integers"),
                      (("--seeds", "2,2"), "duplicate"), (("--seeds", ""), "empty list"),
                      (("--seed", "-1"), "out of range")):
        with pytest.raises(UserError, match=msg):
            fpga.seeds_of(args_of(*argv))


def test_jobs_option_and_one_line_errors(capsys, monkeypatch):
    def no_tools(name):
        raise UserError(f"{name}: no tool runs in this test")

    monkeypatch.setattr(fpga, "tool", no_tools)   # should the checks let it through, no build starts
    assert args_of().jobs == 2
    with pytest.raises(UserError, match="--jobs: 0 is out of range"):
        fpga.check_args(args_of("--jobs", "0"))
    assert fpga.main(["--seed", "1", "--seeds", "2"]) == 2
    err = capsys.readouterr().err
    assert err == "fpga: error: --seed and --seeds both given: use one (--seed N is short for --seeds N)\n"


# ------------------------------------------------------------------ which rtl/ was built
def test_rtl_commit_note():
    assert markdown.rtl_commit_note("1a2b3c4", False) == "rtl/ at commit 1a2b3c4"
    assert markdown.rtl_commit_note("1a2b3c4", True) == "rtl/ at commit 1a2b3c4 (rtl/ has uncommitted changes)"


def test_rtl_commit_asks_git_about_rtl_only(monkeypatch):
    calls = []

    def fake_git(*args):
        calls.append(args)
        return {"log": "deadbee", "status": " M rtl/cube4_gra.v", "rev-parse": "1234567"}[args[0]]

    monkeypatch.setattr(markdown, "_git", fake_git)
    assert markdown.rtl_commit() == "rtl/ at commit deadbee (rtl/ has uncommitted changes)"
    assert ("log", "-1", "--format=%h", "--", "rtl") in calls and ("status", "--porcelain", "--", "rtl") in calls
    monkeypatch.setattr(markdown, "_git", lambda *a: "deadbee" if a[0] == "log" else "")
    assert markdown.rtl_commit() == "rtl/ at commit deadbee"
    monkeypatch.setattr(markdown, "_git", lambda *a: "")            # no git
    assert markdown.rtl_commit() == "rtl/ at commit unknown"


def test_last_commit_matches_git():
    try:
        want = subprocess.run(["git", "log", "-1", "--format=%h", "--", "rtl"], cwd=markdown.REPO_ROOT,
                              capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        pytest.skip("no git")
    assert markdown.last_commit() == (want or "unknown")


@pytest.mark.parametrize("name, unit", [
    ("u_com.g_lane[3].s9_wc_TRELLIS_FF_Q", "COM"),
    ("u_frontend.u_tri.g_lerp[0].u_x_l0", "TRI"),
    ("u_frontend.u_req_skid.u_ready.u_copies.g_copy[2].q_q", "front end"),
    ("genblk13.g_gra.u_gra.u_x_p1.g_one_bank.u_ram", "GRA"),   # a unit inside a generate block
    ("g_gra.u_gra.win_q", "GRA"),
    ("sha_skew_LUT4_Z", None),                                  # a top-level net's name
])
def test_unit_of_name(name, unit):
    assert fpga.unit_of_name(name) == unit


def router2_log(tmp_path: Path, overuse: list[int]) -> Path:
    """A nextpnr log with router2's iteration lines (iteration 1 .. len(overuse))."""
    log = tmp_path / "nextpnr.out"
    log.write_text("Info: Running router2...\n" + "".join(
        f"Info:     iter={i} wires=410171 overused={o} overuse={o} archfail=NA\n"
        for i, o in enumerate(overuse, start=1)))
    return log


def test_router2_divergence_rule(tmp_path):
    """A run whose overuse grows DIVERGE_FACTOR-fold over its least is stopped, but only from
    iteration DIVERGE_ITER on; a slow convergence (overuse falling, or a small bump) is not."""
    n = fpga.DIVERGE_ITER
    falling = [50000 // (i + 1) + 1 for i in range(n + 10)]
    assert fpga.router2_diverged(router2_log(tmp_path, falling)) is None
    early = [1000] * (n - 3) + [100, 100 * fpga.DIVERGE_FACTOR + 1]      # last: iteration n - 1
    assert fpga.router2_diverged(router2_log(tmp_path, early)) is None
    bump = [1000] * (n - 1) + [100, 100 * fpga.DIVERGE_FACTOR]                 # exactly the factor: goes on
    assert fpga.router2_diverged(router2_log(tmp_path, bump)) is None
    grown = [1000] * (n - 1) + [863, 863 * fpga.DIVERGE_FACTOR + 1]
    why = fpga.router2_diverged(router2_log(tmp_path, grown))
    assert why and f"iteration {n + 1}" in why and "863 at iteration" in why
    # a nearly routed run swinging between a few wires is not diverging (the floor) ...
    nearly = [1000] * (n - 1) + [2, fpga.DIVERGE_FLOOR]
    assert fpga.router2_diverged(router2_log(tmp_path, nearly)) is None
    # ... but the same growth past the floor is
    past = [1000] * (n - 1) + [2, fpga.DIVERGE_FLOOR + 1]
    assert fpga.router2_diverged(router2_log(tmp_path, past))
    assert fpga.router2_diverged(tmp_path / "missing.out") is None
    assert fpga.router2_diverged(router2_log(tmp_path, [])) is None


def test_run_tool_watch_stops_and_records_why(tmp_path):
    """run_tool's watch kills a running tool once it returns a reason: exit -2, the reason in the
    log, which a failed seed's path line then names; a tool that ends by itself is left alone."""
    import sys
    from cube4_reports.synth import run_tool, stop_reason

    loop = [sys.executable, "-c", "import time\nfor i in range(600):\n print(f'iter={i}', flush=True); time.sleep(0.05)"]
    seen = []

    def watch(log: Path) -> str | None:
        seen.append(log.read_text().count("iter="))
        return "enough" if seen[-1] >= 3 else None

    run = run_tool(loop, tmp_path / "seed1" / "nextpnr.out", tmp_path, check=False, watch=watch, poll_s=0.2)
    assert run.rc == -2 and run.wall_s < 20
    assert stop_reason(run.log) == "stopped: enough"
    sr = fpga.SeedRun(1, tmp_path / "seed1", run.rc, run.wall_s)
    assert sr.fmax is None and sr.path_line() == "failed: stopped: enough"
    done = run_tool([sys.executable, "-c", "print('ok')"], tmp_path / "ok.out", tmp_path, watch=lambda _: None)
    assert done.rc == 0 and stop_reason(done.log) is None
    slow = run_tool(loop, tmp_path / "slow.out", tmp_path, check=False, timeout_s=0.5, poll_s=0.2)
    assert slow.rc == -1 and stop_reason(slow.log) == "timeout after 0 s"

    def broken(log: Path) -> str | None:
        raise RuntimeError("watch failed")

    t0 = time.monotonic()
    with pytest.raises(RuntimeError, match="watch failed"):      # the tool is killed, not waited for
        run_tool(loop, tmp_path / "broken.out", tmp_path, check=False, watch=broken, poll_s=0.2)
    assert time.monotonic() - t0 < 20


def test_detailed_timing_option_is_part_of_the_seed_key(monkeypatch, tmp_path):
    cfg = cfg_of()
    detailed = fpga.BuildConfig(p=8, max_dim=16, depth=64, freq=cfg.freq, seeds=cfg.seeds, detailed=True)
    assert detailed.key("d", 1) != cfg.key("d", 1) and detailed.synth_key("d") == cfg.synth_key("d")
    assert args_of("--detailed-timing").detailed_timing and not args_of().detailed_timing
    seen = []

    def fake_run_tool(cmd, *a, **k):
        seen.append(cmd)
        return type("Run", (), {"rc": 0, "wall_s": 1.0})()

    monkeypatch.setattr(fpga, "SYNTH_DIR", tmp_path)
    monkeypatch.setattr(fpga, "tool", lambda name: name)
    monkeypatch.setattr(fpga, "run_tool", fake_run_tool)
    fpga.run_pnr(detailed, 1, 10.0)
    fpga.run_pnr(cfg, 1, 10.0)
    assert "--detailed-timing-report" in seen[0] and "--detailed-timing-report" not in seen[1]


# ------------------------------------------------------------------ builds named whole
def test_widths_option_names_the_build_and_its_folder():
    """--widths: cube4_top's word widths beside the build options; checked by the build's rules
    (the rectangle build has no S > 1), part of the synthesis key and of the folder."""
    from cube4.builds import complete_build
    assert fpga.parse_widths_arg("", complete_build({})) == ()
    assert fpga.parse_widths_arg("max_ss_log2=2, WEIGHT_W=6", complete_build({})) == (("MAX_SS_LOG2", 2), ("WEIGHT_W", 6))
    for text, msg in (("FOO=1", "NAME=V pairs"), ("WEIGHT_W=x", "NAME=V pairs"), ("ACC_W=8,ACC_W=9", "twice")):
        with pytest.raises(UserError, match=msg):
            fpga.parse_widths_arg(text, complete_build({}))
    with pytest.raises(UserError, match="rectangles run with S = 1"):
        fpga.parse_widths_arg("MAX_SS_LOG2=2", complete_build({"RECTS": 1, "EXTREMUM": 0, "CLIP": 0, "PLW": 0}))
    assert fpga.parse_widths_arg("MAX_SS_LOG2=2", complete_build({"BEATS": 1, "PLW": 0})) == (("MAX_SS_LOG2", 2),)
    base, ss = cfg_of(), fpga.BuildConfig(p=8, max_dim=16, depth=64, freq=100.0, widths=(("MAX_SS_LOG2", 2),))
    assert ss.params()["MAX_SS_LOG2"] == 2 and base.params()["MAX_SS_LOG2"] == fpga.TOP_DEFAULTS["MAX_SS_LOG2"]
    assert ss.synth_key("d") != base.synth_key("d") and ss.workdir().name == "p8_d16_w64_max_ss_log22"
    assert ss.word_widths() == {**fpga.TOP_DEFAULTS, "MAX_SS_LOG2": 2}


def test_json_beside_a_report_in_reports():
    """A report written into reports/ keeps its JSON beside it (cube4_reports.fmax reads it)."""
    assert fpga.json_beside(fpga.DOC_REPORTS / "fpga_beats.md") == fpga.DOC_REPORTS / "fpga_beats.json"
    assert fpga.json_beside(fpga.BUILD_REPORTS / "fpga_quick.md") is None


def test_results_as_written_are_what_the_frame_times_read(tmp_path, monkeypatch):
    """The JSON fpga writes (combine's records, named whole) is what cube4_reports.fmax reads:
    the same build, widths, P, median and every seed's Fmax."""
    import json

    from cube4.builds import complete_build
    from cube4_reports import fmax
    monkeypatch.setattr(fpga, "SYNTH_DIR", tmp_path)
    build = (("BEATS", 1), ("EXTREMUM", 0), ("CLIP", 0), ("PLW", 0))
    cfg = fpga.BuildConfig(p=8, max_dim=16, depth=64, freq=125.0, seeds=(1, 2, 3), build=build)
    runs = [run_of(2, 90.0, tmp_path), run_of(3, 70.0, tmp_path), run_of(1, 80.0, tmp_path)]
    cfg.workdir().mkdir(parents=True, exist_ok=True)
    (cfg.workdir() / "yosys.log").write_text("Top module:  \\cube4_top\nUsed module:     \\cube4_skid\n")
    recs = fpga.result_records([fpga.combine(cfg, {"LUT4": 5}, 1.0, runs)], [cfg])
    f = tmp_path / "fpga_t.json"
    f.write_text(json.dumps({"seeds": [1, 2, 3], "speed": 8, "max_dim": 16, "rtl_commit": "abc1234", "results": recs}))
    m = fmax.lookup(fmax.load([f]), 8, complete_build(dict(build)), fpga.TOP_DEFAULTS)
    assert m.fmax_mhz == 80.0 and sorted(m.fmax_seeds) == [70.0, 80.0, 90.0] and m.luts == recs[0]["luts"]
    # the files its synthesis read (make fpga-status: current while rtl/ changes elsewhere)
    assert {"rtl/cube4_top.v", "rtl/cube4_skid.v", "rtl/cube4_defs.vh"} <= set(m.files)
    assert "rtl/cube4_cfb_beats.v" not in m.files

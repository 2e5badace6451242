"""`make report` helpers (sim/cube4_reports/report.py): configurations, the cycle formula,
Fmax look-up and the table. Fast: no reference render and no RTL build."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from cube4.builds import build_name, complete_build
from cube4.config import Cube4Config
from cube4.cycles import frame_cycles
from cube4.errors import UserError
from cube4.host import config_for, setup_view
from cube4.scene import PRESETS, load_scene
from cube4_reports import fmax, report


def test_variants_one_parameter_at_a_time() -> None:
    scene = load_scene("default")
    plan = report.case_variants(scene, report.variants(quick=False))
    hw = [(v, cfg) for v, cfg in plan if v.varied not in (*report.SCENE_SWEEPS, "combo")]
    cfgs = [cfg for _, cfg in hw]
    assert plan[0][0].varied == "default" and cfgs[0] == Cube4Config()
    assert len(cfgs) == len(set(cfgs)) == 13  # 1 + S 2 + W 4 + F 3 + p 3
    default = Cube4Config().as_dict()
    for v, cfg in hw[1:]:
        changed = {k for k, x in cfg.as_dict().items() if x != default[k]}
        assert changed == {v.varied}, v.label
    subpixel = [(v, cfg) for v, cfg in plan if v.varied == "subpixel"]     # the scene's key, the default hardware
    assert [v.value for v, _ in subpixel] == [2, 3, 4] and all(cfg == Cube4Config() for _, cfg in subpixel)
    assert all(v.scene(scene).subpixel == v.value for v, _ in subpixel)
    combos = [v for v, _ in plan if v.varied == "combo"]      # several scene keys at once
    assert len(combos) == len(report.COMBOS) and all(len(v.value) >= 2 for v in combos)
    quality = next(v for v in combos if v.label.startswith("quality"))
    assert {k: getattr(quality.scene(scene), k) for k, _ in quality.value} == PRESETS["quality"]
    quick = [v.label for v, _ in report.case_variants(scene, report.variants(quick=True))]
    assert quick == ["default", "S=2", "W=4", "F=8", "p=1", "q=2", "warp=mitchell", "grad=sobel", "pw=True",
                     "preview=2", "beats τ=0.03125", "quality: grad=central S=4 q=2 pw=True"]
    # the preview levels and the beat schedule's thresholds: scene keys on the default hardware
    tau = [v for v, _ in plan if v.varied == "tau"]
    assert [v.value for v in tau] == [0.0, 1 / 256, 1 / 32, 1 / 8]
    assert all(v.scene(scene).skip == "beats" and v.scene(scene).tau == v.value for v in tau)
    assert [v.scene(scene).preview for v, _ in plan if v.varied == "preview"] == [2, 4]
    # the default schedule at every S: the beat schedule
    ss = {v.value: v for v, _ in plan if v.varied == "supersample"}
    assert plan[0][0].scene(scene).schedule == "beats" and ss[2].scene(scene).schedule == "beats"
    assert ss[2].config(scene).supersample == 2


def test_cycle_formula_matches_docs() -> None:
    """(M·NJ + 1)·NB + 1 + NJ·NB + NB + 2 + fill for the default view of a 64³ volume, with the
    fill that docs/architecture.md states (tb/cube4_top checks the same formula against the RTL)."""
    import re
    doc = (Path(__file__).resolve().parents[1] / "docs" / "architecture.md").read_text()
    found = re.search(r"NJ·NB \+ NB \+ 2 \+ fill \((\d+) cycles\)", doc)
    assert found, "docs/architecture.md no longer states the fill of the cycles formula"
    fill = int(found.group(1))
    scene = load_scene("default")
    for p, s in ((8, 1), (1, 1), (8, 4), (5, 2)):
        cfg = config_for(scene, pipelines=p, supersample=s)
        trav, _ = setup_view((64, 64, 64), scene, cfg)
        m, nj, nb = 63 * s + 1, 64, -(-64 // p)
        assert frame_cycles(trav.num_sample_slices, trav.nj, trav.ni, p) == (m * nj + 1) * nb + 1 + nj * nb + nb + 2 + fill


def _fpga_json(path: Path, results: list[dict], **top) -> Path:
    """A result file of python -m cube4_reports.fpga (the fields cube4_reports.fmax reads)."""
    path.write_text(json.dumps({"part": "LFE5U-85F", "max_dim": 128, "seeds": [1, 2, 3], "rtl_commit": "abc1234",
                                "finished": "2026-11-30 12:00", **top, "results": results}))
    return path


def _result(p: int, fmax: float | None, build: dict | None = None, fits: bool = True, **widths) -> dict:
    return {"p": p, "fmax_median": fmax, "fits": fits,
            "fmax_seeds": [{"seed": s, "fmax_mhz": fmax, "critical_path": "x"} for s in (1, 2, 3)],
            "build": complete_build(build), "widths": {**Cube4Config().widths(), **widths}}


def test_fmax_lookup(tmp_path: Path) -> None:
    """A frame time comes only from the build that runs it: its options, widths and P."""
    beats = {"BEATS": 1, "EXTREMUM": 0, "CLIP": 0, "PLW": 0}
    f = _fpga_json(tmp_path / "fpga_a.json", [_result(8, 113.1, beats), _result(4, 120.0, beats, fits=False)])
    g = _fpga_json(tmp_path / "fpga_b.json", [_result(8, 130.0), _result(8, 90.0, beats, MAX_SS_LOG2=2),
                                               {"p": 1, "fmax_median": 99.0, "fits": True}],   # names no build
                   finished="2026-11-29 12:00")
    m = fmax.load([f, g])
    assert len(m) == 4                                                        # the one naming no build left out
    w = Cube4Config().widths()
    hit = fmax.lookup(m, 8, beats, w)
    assert hit.fmax_mhz == 113.1 and "P = 8" in hit.note() and "abc1234" in hit.note() and "fpga_a.json" in hit.note()
    assert fmax.lookup(m, 8, {}, w).fmax_mhz == 130.0                          # the full build
    assert fmax.lookup(m, 8, {"PLW": 0}, w) is None                           # another build: never borrowed
    nofit = fmax.lookup(m, 4, beats, w)                                       # placed and routed, does not fit
    assert not nofit.fits and nofit.fmax_mhz is None and "does not fit" in nofit.note()
    ss = fmax.lookup(m, 8, beats, {**w, "MAX_SS_LOG2": 2})                      # widths are part of the build
    assert ss.fmax_mhz == 90.0 and "(MAX_SS_LOG2=2) at P = 8" in ss.note()
    assert fmax.lookup(m, 8, beats, {**w, "ACC_W": 24}) is None
    assert fmax.lookup(m, 1, {}, w) is None
    # the latest finished of two results of the same build counts
    h = _fpga_json(tmp_path / "fpga_c.json", [_result(8, 115.0, beats)], finished="2026-12-01 08:00")
    assert fmax.lookup(fmax.load([f, g, h]), 8, beats, w).fmax_mhz == 115.0
    # another speed grade is another chip: not the reports' clock
    s6 = _fpga_json(tmp_path / "fpga_s6.json", [_result(8, 150.0, beats)], speed=6, finished="2026-12-02 08:00")
    assert fmax.lookup(fmax.load([f, s6]), 8, beats, w).fmax_mhz == 113.1
    # a result that cannot be read as a build is left out, not a traceback
    odd = _fpga_json(tmp_path / "fpga_odd.json", [{**_result(8, 1.0, beats), "build": {"NOPE": 1}},
                                                   {**_result(8, 1.0, beats), "p": None}])
    assert fmax.load([odd]) == []
    assert fmax.build_from_name(build_name(complete_build(beats))) == complete_build(beats)
    assert fmax.build_from_name("full") == complete_build({})
    (tmp_path / "bad.json").write_text("{not json")
    with pytest.raises(UserError, match="bad.json is not a result of python -m cube4_reports.fpga"):
        fmax.load([tmp_path / "bad.json"])


def _row(varied: str, label: str, psnr: float, cycles: int, build: str = "EXTREMUM=0, CLIP=0, PLW=0",
         **cfg) -> report.Row:
    c = Cube4Config(**cfg).as_dict()
    return report.Row(volume="sphere:64", scene="default", varied=varied, label=label,
                      pipelines=c["pipelines"], weight_bits=c["weight_bits"], acc_bits=c["acc_bits"],
                      supersample=c["supersample"], voxel_bits=c["voxel_bits"], alpha_bits=c["alpha_bits"],
                      rmap_bits=c["rmap_bits"], rmse=10 ** (-psnr / 20), max_abs=0.5, psnr=psnr, rmse_rgb=0.0,
                      rmse_alpha=0.0, golden_wall_s=0.1, formula_cycles=cycles, cycles=cycles, build=build,
                      cycles_source="rtl")


def test_table_frame_time_and_failures(tmp_path: Path) -> None:
    rows = [_row("default", "default", 34.0, 1000), _row("pipelines", "p=1", 34.0, 8000, pipelines=1),
            _row("weight_bits", "W=4", 30.0, 1000, weight_bits=4), _row("acc_bits", "F=8", 33.0, 1000, acc_bits=8)]
    rows[1].rtl_error, rows[1].cycles_source = "build failed", "formula (RTL failed)"
    measured = fmax.read_results(_fpga_json(tmp_path / "fpga_t.json", [
        _result(8, 100.0, {"EXTREMUM": 0, "CLIP": 0, "PLW": 0}), _result(1, 50.0, {}),  # p = 1: another build
        _result(8, 90.0, {"EXTREMUM": 0, "CLIP": 0, "PLW": 0}, WEIGHT_W=6),           # another width
        _result(1, 60.0, {"EXTREMUM": 0, "CLIP": 0, "PLW": 0})]))                     # p = 1's own: RTL failed
    report.finish_rows(rows, measured)
    assert rows[0].frame_time_ms == pytest.approx(0.01) and "100.0 MHz" in rows[0].fmax_source
    assert rows[1].frame_time_ms is None and rows[1].cycles_ratio == 8.0
    assert rows[2].frame_time_ms is None and "not placed and routed" in rows[2].fmax_source
    assert "(WEIGHT_W=4) at P = 8" in rows[2].fmax_source
    table = report.markdown_table(rows)
    lines = table.splitlines()
    assert all(line.count("|") - line.count("\\|") == lines[0].count("|") - lines[0].count("\\|") for line in lines)
    assert "0.0100 @ 100.0 MHz" in lines[2] and "none (formula (RTL failed) cycles)" in lines[3]
    assert report.NA_FMAX in lines[4] and report.NA_FMAX in lines[5]
    assert "RTL failed: build failed" in lines[3] and "**1**" in lines[3]
    assert "| EXTREMUM=0, CLIP=0, PLW=0 |" in lines[2]
    note = report.fmax_note(rows, measured)
    assert "2 of 4 rows run on a build that was never placed and routed" in note and "100.0 MHz" in note


def test_tables_only_roundtrip(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A finished run's JSON gets frame times once fpga.json (make fpga's schema) exists."""
    monkeypatch.setattr(report, "REPORTS_BUILD", tmp_path)
    monkeypatch.setattr(fmax, "REPORTS", tmp_path)
    with pytest.raises(UserError, match="run make report first"):
        report.rewrite_tables(tmp_path / "out")
    rows = [_row("default", "default", 34.0, 1000), _row("pipelines", "p=1", 34.0, 8000, pipelines=1)]
    meta = {"command": "make report", "finished": "then", "wall_s": 60.0, "git": {"commit": "x", "rtl_dirty": False},
            "rtl": True, "cycles_note": "measured", "loadavg_start": "0", "loadavg_end": "0",
            "truth": {"v, scene `s`": {"truth_k": 3, "truth_change": 0.001, "truth_converged": True,
                                       "truth_steps": "k=1: 100.0% of pixels; k=3: 20.0% of pixels, RMS change 1.00e-03",
                                       "wall_s": 12.0}},
            "axis": [{"volume": "head:24", "scene": "head", "axis": "+x", "axis_area": 30.0, "tilted_area": 31.5,
                      "axis_point": 28.0, "tilted_point": 31.0, "axis_quality": 40.0, "tilted_quality": 40.5},
                     {"volume": "head:24", "scene": "head", "axis": "-x", "axis_area": 30.0, "tilted_area": 31.0,
                      "axis_point": 28.0, "tilted_point": 31.0}]}
    report.write_json(report.json_path(tmp_path / "out"), rows, meta)
    build = {"EXTREMUM": 0, "CLIP": 0, "PLW": 0}
    _fpga_json(tmp_path / "fpga_x.json", [_result(1, 50.0, build), _result(8, 99.0, build, fits=False)])
    new_rows, new_meta = report.rewrite_tables(tmp_path / "out")
    assert new_rows[1].frame_time_ms == pytest.approx(8000 / 50e6 * 1e3)
    assert new_rows[0].frame_time_ms is None  # p = 8 does not fit: no Fmax
    assert "50.0 MHz: EXTREMUM=0, CLIP=0, PLW=0 at P = 1" in new_meta["fmax_note"] and new_meta["tables_rewritten"]
    paths = report.write_outputs(new_rows, new_meta, tmp_path / "out")
    assert all(p.exists() for p in paths)
    text = (tmp_path / "out" / f"{report.STEM}.md").read_text()
    assert "0.1600 @ 50.0 MHz" in text
    # the budget lines (the front: p=1 is slower and no better) and the truth's convergence
    assert "≥ 1,000 cycles: default (34.00 dB)" in text and "p=1 (" not in text.split("## The truth")[0].split("budget")[1]
    assert "| head:24, `head` | +x | 30.00 | 31.50 | -1.50 | 28.00 | 31.00 | -3.00 | 40.00 | 40.50 | -0.50 |" in text
    assert "| -x | 30.00 | 31.00 | -1.00 | 28.00 | 31.00 | -3.00 | not run | not run | — |" in text
    assert "-1.50 dB in the default configuration and -0.50 dB with the quality preset" in text
    assert "- v, scene `s`: k=1: 100.0% of pixels; k=3: 20.0% of pixels, RMS change 1.00e-03; 12 s." in text
    # the gradient angles are the research prototype's stored results, not measured here
    assert "| `vgrad_sobel` | 1.40 | 1.34 | 1.31 | 1.31 | 1.48 at (0, 0, 1), S = 1 | 3.5 |" in text
    monkeypatch.setattr(report, "ANGLES_JSON", tmp_path / "missing.json")
    with pytest.raises(UserError, match="missing.json.*scripts/research/gradients.py"):
        report.write_outputs(new_rows, new_meta, tmp_path / "out")


def test_pareto_front() -> None:
    """The non-dominated rows: fewest cycles for their PSNR, PSNR rising along the front."""
    def row(label, cycles, psnr):
        return report.Row(volume="v", scene="s", varied="default", label=label, pipelines=8, weight_bits=8,
                          acc_bits=16, supersample=1, voxel_bits=8, alpha_bits=12, rmap_bits=5, rmse=0.0,
                          max_abs=0.0, psnr=psnr, rmse_rgb=0.0, rmse_alpha=0.0, golden_wall_s=0.1,
                          formula_cycles=cycles, cycles=cycles)
    rs = [row("a", 100, 30.0), row("b", 100, 31.0), row("c", 200, 30.5), row("d", 400, 33.0), row("e", 300, 33.0)]
    assert [r.label for r in report.pareto(rs)] == ["b", "e"]

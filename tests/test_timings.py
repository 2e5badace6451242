"""The test-time breakdown (python -m cube4_sim.timings): builds against simulations."""

from __future__ import annotations

import json

import pytest

from cube4_sim import timings


def test_summary_adds_builds_and_simulations_per_top(tmp_path):
    path = tmp_path / "t.jsonl"
    rows = [{"test": "a", "top": "cube4_top_harness", "build": "cube4_top_harness_1", "build_s": 80.0, "sim_s": 20.0},
            {"test": "b", "top": "cube4_top_harness", "build": "cube4_top_harness_1", "build_s": 0.5, "sim_s": 30.0},
            {"test": "c", "top": "cube4_sha_harness", "build": "cube4_sha_harness_2", "build_s": 10.0, "sim_s": 2.0}]
    path.write_text("".join(json.dumps(r) + "\n" for r in rows))
    text = timings.summary(timings.load(path))
    assert text.splitlines()[0] == "3 simulations, 2 builds: build 90 s, simulation 52 s (worker seconds)"
    top_row = next(line for line in text.splitlines() if line.startswith("cube4_top_harness "))
    assert top_row.split() == ["cube4_top_harness", "1", "2", "80", "50"]
    assert text.index("cube4_top_harness_1") < text.index("cube4_sha_harness_2")


def test_missing_records_are_one_line(tmp_path):
    with pytest.raises(SystemExit, match="does not exist"):
        timings.load(tmp_path / "none.jsonl")


def test_compare_uses_the_builds_both_runs_made(tmp_path):
    new = [{"test": "a", "top": "t", "build": "t_1", "build_s": 30.0, "sim_s": 10.0},
           {"test": "b", "top": "t", "build": "t_1", "build_s": 0.5, "sim_s": 6.0},
           {"test": "c", "top": "u", "build": "u_9", "build_s": 99.0, "sim_s": 99.0}]
    old = [{"test": "a", "top": "t", "build": "t_1", "build_s": 20.0, "sim_s": 8.0},
           {"test": "d", "top": "v", "build": "v_3", "build_s": 5.0, "sim_s": 1.0}]
    text = timings.compare(new, old)
    assert text.startswith("1 builds in both runs (1 only in this one, 1 only in the other)")
    assert "build 30 s against 20 s (x1.52)" in text and "simulation 16 s against 8 s (x2.00)" in text
    assert timings.compare(new, [old[1]]).startswith("no build in common")


def test_main_prints_the_comparison(tmp_path, capsys):
    path = tmp_path / "t.jsonl"
    path.write_text(json.dumps({"test": "a", "top": "t", "build": "t_1", "build_s": 4.0, "sim_s": 2.0}) + "\n")
    assert timings.main([str(path), "--against", str(path)]) == 0
    assert "build 4 s against 4 s (x1.00)" in capsys.readouterr().out

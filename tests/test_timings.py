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

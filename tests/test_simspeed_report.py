"""make simspeed's report: one row per build, its speed against the full build's."""

from __future__ import annotations

from cube4_reports import simspeed


def test_table_rows_and_ratio():
    args = simspeed.parse_args(["--runs", "2", "--build", "full", "--build", "noclip"])
    assert args.build == ["full", "noclip"]
    run = {"cycles": 1000, "sim_wall_s": 0.004, "cycles_per_s": 250_000.0, "command_wall_s": 3.0}
    fast = {**run, "sim_wall_s": 0.002, "cycles_per_s": 500_000.0}
    results = [{"build": "full", "runs": [run, run], "median_cycles_per_s": 250_000.0},
               {"build": "noclip", "runs": [fast, fast], "median_cycles_per_s": 500_000.0}]
    text = simspeed.markdown(args, results, (0.5, 1.0))
    assert "| `full` | 1,000 | 0.00 | 0.250 | 1.00 |" in text
    assert "| `noclip` | 1,000 | 0.00 | 0.500 | 2.00 |" in text
    assert "median of 2 runs" in text


def test_default_builds_start_with_full():
    assert simspeed.parse_args([]).build[0] == "full"


def test_named_builds_become_option_pairs():
    assert simspeed.build_flag("full") == "full"
    assert simspeed.build_flag("shaded") == "EXTREMUM=0,CLIP=0"
    assert simspeed.build_flag("SHADING=0") == "SHADING=0"

"""`make bricks` (sim/cube4_reports/bricks.py): a quick run writes the report, and its
figures are those of the brick plan and of seed 004's rule."""

from __future__ import annotations

import json

import pytest

from cube4.bricks import make_grid
from cube4_reports import bricks as report


def test_quick_report(tmp_path, monkeypatch):
    monkeypatch.setattr(report, "REPORTS_BUILD", tmp_path / "build")
    assert report.main(["--quick", "--out", str(tmp_path / "out")]) == 0
    md = (tmp_path / "out" / "bricks.md").read_text()
    doc = json.loads((tmp_path / "build" / "bricks_quick.json").read_text())
    assert (tmp_path / "out" / "bricks_seams.png").stat().st_size > 10000
    for section in ("## Overhead against Teramac Table 1", "## Bricked composite against the monolithic render",
                    "## Seed 004's seams"):
        assert section in md
    row = next(r for r in doc["overhead"] if r["shape"] == "2x2x2")
    assert row["memory"] == pytest.approx(make_grid((32, 32, 32), (2, 2, 2)).memory_overhead)
    assert f"{100 * row['memory']:.1f}%" in md
    assert all(r["ok"] for r in doc["bound"])
    seams = {r["key"]: r for r in doc["seams"]["rows"]}
    # the bricks in this design's 16-bit accumulators are far closer to the one render than 8-bit framebuffers
    assert seams["bricks16"]["rmse"] < 1e-3 < seams["fb_bricks"]["rmse"]
    assert seams["fb_bricks_corr"]["rmse"] < seams["fb_bricks"]["rmse"]
    assert doc["seams"]["s_new"] < doc["seams"]["s_old"]


def test_table1_layout_and_implied_overlap():
    """Teramac's Table 1 read as (p + o)^2 / p^2 - 1: o between 2 and 3.2 voxels."""
    for p, pct in report.TABLE1.items():
        o = report._implied_overlap(p, pct)
        assert 2.0 < o < 3.2
        assert (p + o) ** 2 / p ** 2 - 1 == pytest.approx(pct / 100)

"""rtl/sources.f, the one list of RTL sources (cube4_sim.sources), and its readers."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from cube4_sim.sources import RTL_DIR, SourceListError, rtl_sources, source_names, synth_sources

REPO = Path(__file__).resolve().parents[1]


def test_every_rtl_module_is_listed_once():
    names = source_names()
    assert len(names) == len(set(names)), "rtl/sources.f lists a file twice"
    assert sorted(names) == sorted(p.name for p in RTL_DIR.glob("*.v"))
    assert names[-1] == "cube4_top.v", "dependencies first: the top comes last"


def test_comments_blank_lines_and_missing_files(tmp_path):
    (tmp_path / "a.v").write_text("")
    (tmp_path / "b.v").write_text("")
    lst = tmp_path / "sources.f"
    lst.write_text("# header\n\na.v   # the first\n  b.v\n")
    assert rtl_sources(lst) == [tmp_path / "a.v", tmp_path / "b.v"]
    lst.write_text("a.v\nc.v\n")
    with pytest.raises(SourceListError, match="lists c.v, which does not exist"):
        rtl_sources(lst)
    lst.write_text("# nothing\n")
    with pytest.raises(SourceListError, match="names no file"):
        rtl_sources(lst)
    with pytest.raises(SourceListError, match="cannot read"):
        rtl_sources(tmp_path / "missing.f")


def test_synthesis_takes_the_vendor_counterparts(tmp_path):
    for n in ("a.v", "b.v", "c.v"):
        (tmp_path / n).write_text("")
    lst = tmp_path / "sources.f"
    lst.write_text("a.v\nb.v\nc.v\n")
    vendor = tmp_path / "ecp5"
    assert synth_sources(lst, vendor) == rtl_sources(lst)  # no vendor folder: nothing replaced
    vendor.mkdir()
    (vendor / "b.v").write_text("")
    (vendor / "other.v").write_text("")
    assert synth_sources(lst, vendor) == [tmp_path / "a.v", vendor / "b.v", tmp_path / "c.v"]


@pytest.mark.skipif(shutil.which("make") is None, reason="no make")
def test_makefile_reads_the_same_list():
    r = subprocess.run(["make", "-s", "--no-print-directory", "--eval",
                        "_print_rtl_srcs: ; @echo $(RTL_SRCS)", "_print_rtl_srcs"],
                       cwd=REPO, capture_output=True, text=True, check=True)
    assert r.stdout.split() == [str(p.relative_to(REPO)) for p in rtl_sources()]

"""The reports' shared pieces: Markdown tables, the provenance stamp, and what Yosys reads."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from cube4_reports import markdown, synth
from cube4_sim.sources import RTL_DIR, rtl_sources, synth_sources


def test_md_table_alignment_and_shape():
    t = markdown.md_table(["a", "b", "c"], [["1", "2", "3"], ["x", "y", "z"]])
    assert t.splitlines() == ["| a | b | c |", "| --- | ---: | ---: |", "| 1 | 2 | 3 |", "| x | y | z |"]
    assert markdown.md_table(["a", "b"], [], "ll").splitlines()[1] == "| --- | --- |"
    assert markdown.fmt_int(12345.6) == "12,346"


def test_rtl_digest_covers_names_and_contents(tmp_path):
    a, b = tmp_path / "a.v", tmp_path / "b.v"
    a.write_text("module a; endmodule\n")
    b.write_text("module b; endmodule\n")
    d = markdown.rtl_digest([a, b])
    assert re.fullmatch(r"[0-9a-f]{12}", d) and d == markdown.rtl_digest([b, a])
    b.write_text("module b; wire w; endmodule\n")
    assert markdown.rtl_digest([a, b]) != d


def test_git_stamp():
    state = markdown.git_state(("rtl", "sim/hdl"))
    assert set(state) == {"commit", "rtl_dirty"} and isinstance(state["rtl_dirty"], bool)
    desc = markdown.git_describe()
    assert desc == "unknown" or desc.startswith(state["commit"])


@pytest.mark.parametrize("vendor", [True, False])
def test_yosys_reads_the_source_list_with_the_include_dir(tmp_path, vendor):
    """The ECP5 flow reads the vendor forms and the primitives' black boxes (MULT18X18D in
    cells_bb.v, DP16KD in cells_sim.v); the generic
    gate count reads the generic forms (rtl/sources.f as it is)."""
    lines = synth.read_verilog_cmd(tmp_path, vendor=vendor).splitlines()
    lib = ["read_verilog -lib +/ecp5/cells_bb.v", "read_verilog -lib -specify +/ecp5/cells_sim.v"]
    assert (lines[:2] == lib) == vendor and len(lines) == 1 + 2 * vendor
    words = lines[-1].split()
    assert words[:2] == ["read_verilog", "-sv"]
    inc = words[2]
    assert inc.startswith("-I") and (tmp_path / inc[2:]).resolve() == RTL_DIR.resolve()
    want = synth_sources() if vendor else rtl_sources()
    assert [(tmp_path / w).resolve() for w in words[3:]] == [p.resolve() for p in want]
    assert all(not Path(w).is_absolute() for w in words[2:])  # YoWASP mounts its own /tmp
    assert any("rtl/ecp5/" in str(p) for p in synth_sources()) and not any("ecp5" in str(p) for p in rtl_sources())


def test_design_sources_error_is_one_line(monkeypatch):
    monkeypatch.setattr(synth, "synth_sources", lambda: [RTL_DIR / "cube4_lerp.v"])
    with pytest.raises(synth.UserError, match="does not list cube4_top.v"):
        synth.design_sources()


@pytest.mark.parametrize("name", ["fpga", "gates", "scenes", "bricks", "report", "skipping",
                                  "synth", "markdown"])
def test_report_modules_import(name):
    """Every report module imports (a report is not part of make test; a broken import
    would show only when someone runs it)."""
    import importlib

    importlib.import_module(f"cube4_reports.{name}")

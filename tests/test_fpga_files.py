"""cube4_reports.fpga_files: the rtl/ files a build's synthesis read, from Yosys's log."""

from __future__ import annotations

from pathlib import Path

import pytest

from cube4.errors import UserError
from cube4_reports import fpga_files as ff

LOG = """
=== design hierarchy ===
Top module:  \\cube4_top
Used module:     \\cube4_frontend
Used module:         $paramod$4f2a9c\\cube4_skid
Used module:         $paramod\\cube4_sdp_ram\\DATA_W=s32'00000000000000000000000000100000
Used module:     \\cube4_skid
"""


def test_module_names_strip_parameterised_copies():
    assert ff.module_names(LOG) == {"cube4_top", "cube4_frontend", "cube4_skid", "cube4_sdp_ram"}


# the hierarchy pass lists the tree as it derives modules: the first listing names every
# module the top's text mentions (both branches of a generate), the last what is built;
# after flattening, a later pass lists the top alone
LOG_DERIVED = """
82.1. Analyzing design hierarchy..
Top module:  \\cube4_top
Used module:     \\cube4_com
Used module:         \\cube4_com_walk
Used module:         \\cube4_com_beats

82.7. Analyzing design hierarchy..
Top module:  \\cube4_top
Used module:     $paramod$77aa\\cube4_com
Used module:         $paramod$12bc\\cube4_com_beats
Removing unused module `\\cube4_com_walk'.

83.50.1. Analyzing design hierarchy..
Top module:  \\cube4_top
"""


def test_module_names_are_the_last_listing_of_the_tree():
    assert ff.module_names(LOG_DERIVED) == {"cube4_top", "cube4_com", "cube4_com_beats"}
    # a build without submodules: its top
    assert ff.module_names("Top module:  \\cube4_skid\n") == {"cube4_skid"}


def test_files_map_modules_to_their_files_with_every_header(tmp_path: Path):
    rtl = tmp_path / "rtl"
    (rtl / "ecp5").mkdir(parents=True)
    for f in ("cube4_top.v", "cube4_frontend.v", "cube4_skid.v", "cube4_unused.v", "cube4_defs.vh",
              "ecp5/cube4_sdp_ram.v", "ecp5/cube4_ebr_plan.vh"):
        (rtl / f).write_text("")
    sources = [rtl / "cube4_skid.v", rtl / "ecp5/cube4_sdp_ram.v", rtl / "cube4_unused.v",
               rtl / "cube4_frontend.v", rtl / "cube4_top.v"]
    got = ff.files_of(ff.module_names(LOG), sources, rtl)
    assert got == ["rtl/cube4_defs.vh", "rtl/cube4_frontend.v", "rtl/cube4_skid.v", "rtl/cube4_top.v",
                   "rtl/ecp5/cube4_ebr_plan.vh", "rtl/ecp5/cube4_sdp_ram.v"]
    with pytest.raises(UserError, match="cube4_frontend"):
        ff.files_of({"cube4_frontend"}, [rtl / "cube4_top.v"], rtl)


def test_a_missing_log_is_one_clear_error(tmp_path: Path):
    with pytest.raises(UserError, match="no synthesis ran there"):
        ff.synth_files(tmp_path)

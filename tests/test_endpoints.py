"""cube4_reports.endpoints: the late register inputs of a nextpnr run with detailed net
timings, grouped by register. A synthetic report: which sinks count as register inputs,
the period as the limit, lane indices merged, the latest group first, one-line errors."""

from __future__ import annotations

import json

import pytest

from cube4_reports import endpoints
from cube4_reports.synth import UserError


def sink(cell: str, port: str, late: float) -> dict:
    return {"cell": cell, "port": port, "delay": [0.5, late], "event": "posedge clk"}


REPORT = {"detailed_net_timings": [
    {"net": "a", "driver": "x", "port": "Q", "endpoints": [
        sink("u_com.g_lane[3].rgba_l_TRELLIS_FF_Q_120", "DI", 9.9),     # late flip-flop D
        sink("u_com.g_lane[5].rgba_l_TRELLIS_FF_Q_7", "DI", 8.5),       # same register, other lane
        sink("u_com.g_lane[5].rgba_l_TRELLIS_FF_Q_8", "DI", 7.9),       # in time
        sink("u_com.g_lane[5].rgba_l_TRELLIS_FF_Q_8_DI_LUT4_Z", "A", 9.5)]},  # a LUT input: no register
    {"net": "b", "driver": "y", "port": "F", "endpoints": [
        sink("genblk13.g_gra.u_gra.p2b1_TRELLIS_FF_Q_9", "CE", 11.3),   # clock enable
        sink("genblk13.g_gra.u_gra.h1_b_TRELLIS_FF_Q_57", "M", 8.3),    # flip-flop through M
        sink("u_com.g_lane[1].pix_LUT4_Z", "M", 9.0),                   # M of a LUT cell: a select
        sink("u_com.u_fifo.g_grp[1].mem.0.3$DPRAM_COMB1", "WAD2", 8.1),  # distributed RAM write address
        sink("u_com.g_lane[0].g_cmp.u_ta.g_dsp.u_mult", "A7", 8.2),     # multiplier operand
        {"cell": "u_sha.a_s_TRELLIS_FF_Q", "port": "DI", "delay": 8.05, "event": "posedge clk"}]},  # old format
]}


def test_register_inputs_only():
    assert endpoints.is_register_input("u_x.q_TRELLIS_FF_Q_3", "M")
    assert not endpoints.is_register_input("u_x.q_LUT4_Z", "M")
    assert endpoints.is_register_input("u_x.mem.0.0$DPRAM_COMB0", "WD")
    assert endpoints.is_register_input("u_x.u_mult", "B17") and not endpoints.is_register_input("u_x.q_LUT4_Z", "B")


def test_groups_beyond_the_period_latest_first():
    groups = endpoints.late_groups(REPORT, 8.0)
    names = [g["group"] for g in groups]
    assert names == ["genblk13.g_gra.u_gra.p2b1", "u_com.g_lane[*].rgba_l", "genblk13.g_gra.u_gra.h1_b",
                     "u_com.g_lane[*].g_cmp.u_ta.g_dsp.u_mult", "u_com.u_fifo.g_grp[*].mem", "u_sha.a_s"]
    rgba = groups[1]
    assert rgba["count"] == 2 and rgba["worst_ns"] == 9.9 and rgba["unit"] == "COM"
    assert groups[0]["unit"] == "GRA" and groups[-1]["unit"] == "SHA"
    assert [g["group"] for g in endpoints.late_groups(REPORT, 10.0)] == ["genblk13.g_gra.u_gra.p2b1"]
    assert endpoints.late_groups(REPORT, 12.0) == []


def test_cli_and_errors(tmp_path, capsys):
    rep = tmp_path / "report.json"
    rep.write_text(json.dumps(REPORT))
    assert endpoints.main([str(rep), "--freq", "125", "--top", "2"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0] == "6 registers (7 inputs) arrive after 8.000 ns" and "p2b1" in out[1] and out[-1] == "... 4 more (--top)"
    (tmp_path / "plain.json").write_text(json.dumps({"fmax": {}}))
    assert endpoints.main([str(tmp_path / "plain.json")]) == 2
    assert "run nextpnr with --detailed-timing-report" in capsys.readouterr().err
    assert endpoints.main([str(rep), "--top", "-1"]) == 2
    assert capsys.readouterr().err == "endpoints: error: --top: -1 is negative\n"
    assert endpoints.main([str(tmp_path / "missing.json")]) == 2
    assert capsys.readouterr().err.startswith("endpoints: error: cannot read")
    with pytest.raises(UserError, match="no detailed net timings"):
        endpoints.late_groups({}, 8.0)


def test_ports_per_group_and_inputs_with_drivers(tmp_path, capsys):
    groups = {g["group"]: g for g in endpoints.late_groups(REPORT, 8.0)}
    assert groups["genblk13.g_gra.u_gra.p2b1"]["ports"] == {"CE": 1}
    assert groups["u_com.g_lane[*].g_cmp.u_ta.g_dsp.u_mult"]["ports"] == {"A": 1}
    assert groups["u_com.u_fifo.g_grp[*].mem"]["ports"] == {"WAD": 1}
    assert endpoints.port_kind("A17") == "A" and endpoints.port_kind("WD") == "WD"
    inputs = endpoints.late_inputs(REPORT, 8.0)
    assert [x["ns"] for x in inputs] == sorted((x["ns"] for x in inputs), reverse=True) and len(inputs) == 7
    assert inputs[0] == {"group": "genblk13.g_gra.u_gra.p2b1", "cell": "genblk13.g_gra.u_gra.p2b1_TRELLIS_FF_Q_9",
                         "port": "CE", "driver": "y", "ns": 11.3}
    rep = tmp_path / "report.json"
    rep.write_text(json.dumps(REPORT))
    assert endpoints.main([str(rep), "--freq", "125"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[1].endswith("genblk13.g_gra.u_gra.p2b1  (CE 1)") and out[2].endswith("rgba_l  (DI 2)")
    assert endpoints.main([str(rep), "--inputs", r"rgba_l$", "--top", "1"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out == ["2 inputs of groups matching 'rgba_l$' arrive after 8.000 ns",
                   "  9.90 ns  u_com.g_lane[3].rgba_l_TRELLIS_FF_Q_120.DI  <- x", "... 1 more (--top)"]
    assert endpoints.main([str(rep), "--inputs", "("]) == 2
    assert capsys.readouterr().err.startswith("endpoints: error: --inputs: '(' is not a regular expression")

"""`make scenes` (sim/cube4_reports/scenes.py) without synthesis: each build named with its
word widths, its ECP5 figures only from its own place and route, and the command that
measures a build not measured yet."""

from __future__ import annotations

import json
import shlex
from pathlib import Path

from cube4.builds import FULL_BUILD, complete_build
from cube4_reports import fmax, fpga, gates, scenes

VGRAD = complete_build({"EXTREMUM": 0, "CLIP": 0, "VGRAD": 1})
SS4 = {**scenes.DEFAULT_WIDTHS, "MAX_SS_LOG2": 2}


def _gates(nand2: int) -> dict:
    units = {u: {"nand2_total": nand2 // 8, "memory_bits": 100} for u in gates.UNITS}
    return {"units": units, "total": {"nand2_total": nand2, "ffs": nand2 // 10, "memory_bits": 1000}}


def test_builds_are_options_and_widths():
    assert scenes.build_key(VGRAD) != scenes.build_key(VGRAD, SS4)
    assert scenes.build_key(FULL_BUILD) == scenes.build_key(FULL_BUILD, dict(scenes.DEFAULT_WIDTHS))
    assert scenes.full_name(VGRAD, SS4) == "EXTREMUM=0, CLIP=0, VGRAD=1 (MAX_SS_LOG2=2)"
    assert scenes.full_name(FULL_BUILD) == "full"


def test_place_command_measures_that_build_where_the_report_reads_it():
    """The command a build's row gives runs the fpga tool on exactly that build, and its JSON
    lands where cube4_reports.fmax looks (reports/fpga/)."""
    args = fpga.parse_args(scenes.place_args(VGRAD, SS4))
    assert (args.p, args.seeds, args.max_dim, args.no_budget, args.no_memory) == ("8", "1,2,3", 128, True, True)
    assert fpga.parse_build_arg(args.build) == (("EXTREMUM", 0), ("CLIP", 0), ("VGRAD", 1))
    assert fpga.parse_widths_arg(args.widths, VGRAD) == (("MAX_SS_LOG2", 2),)
    md = Path(args.md)
    assert md.parent == Path("reports/fpga") and fpga.json_beside(fpga.DOC_REPORTS / "fpga" / md.name) is not None
    full = fpga.parse_args(scenes.place_args(dict(FULL_BUILD), dict(scenes.DEFAULT_WIDTHS)))
    assert full.build == "" and full.widths == "" and full.md == Path("reports/fpga/full.md")
    assert shlex.split(scenes.place_command(VGRAD, SS4))[3:] == scenes.place_args(VGRAD, SS4)


def test_ecp5_columns_only_from_the_builds_own_run(tmp_path):
    f = tmp_path / "fpga_x.json"
    f.write_text(json.dumps({"seeds": [1, 2, 3], "rtl_commit": "abc1234", "max_dim": 128, "results": [
        {"p": 8, "fmax_median": 137.7, "fits": True, "luts": 50000, "ffs": 40000, "dsps": 130, "ebrs": 190,
         "build": dict(FULL_BUILD), "widths": dict(scenes.DEFAULT_WIDTHS)}]}))
    measured = fmax.load([f])
    recs = [{"build": dict(FULL_BUILD), "widths": dict(scenes.DEFAULT_WIDTHS), "name": "full", "gates": _gates(800000),
             "fpga": fmax.lookup(measured, 8, FULL_BUILD, scenes.DEFAULT_WIDTHS)},
            {"build": VGRAD, "widths": SS4, "name": scenes.full_name(VGRAD, SS4), "gates": _gates(900000),
             "fpga": fmax.lookup(measured, 8, VGRAD, SS4)}]
    table = scenes.builds_table(recs).splitlines()
    assert "| 50,000 | 130 | 190 | 137.7 |" in table[2] and table[3].endswith("| — | — | — | not measured |")
    rows = [{"scene": "head_quality", "volume": "head:64", "mode": "composite", "shaded": True, "crop": None,
             "cut": False, "build": VGRAD, "widths": SS4, "gradient": "central", "cycles": 137700,
             "cycles_full": None, "cycles_fixed": 200000, "psnr_db": 40.0, "psnr_point_db": 39.0, "truth_k": 3},
            {"scene": "head", "volume": "head:64", "mode": "composite", "shaded": True, "crop": None, "cut": False,
             "build": dict(FULL_BUILD), "widths": dict(scenes.DEFAULT_WIDTHS), "gradient": "gra", "schedule": "beats",
             "cycles": 137700,
             "cycles_full": 137700, "cycles_fixed": 200000, "psnr_db": 40.0, "psnr_point_db": 39.0, "truth_k": 3}]
    text = scenes.scenes_table(rows, recs).splitlines()
    assert "| not measured | — |" in text[2] and "| 1.000 | 1.000 |" in text[3]
    assert "| box | 137,700 |" in text[2] and "| beats (RTL) | 137,700 |" in text[3]
    assert scenes.beats_against_box(rows)[0].startswith(
        "On the beat schedule 0 of 1 scenes take fewer cycles than the box on the full build")
    rows[1]["cycles"] = 137600
    assert "1 of 1 scenes take fewer" in scenes.beats_against_box(rows)[0]
    assert scenes.beats_against_box(rows[:1]) == []
    lines = "\n".join(scenes.place_lines(recs, {"rtl_commit": "abc1234"}))
    assert "1 of 2 builds placed and routed" in lines and "- full: 137.7 MHz: full at P = 8" in lines
    assert "--widths MAX_SS_LOG2=2 --md reports/fpga/" in lines


def test_a_build_that_does_not_fit_says_so_and_is_not_placed_again(tmp_path):
    f = tmp_path / "fpga_y.json"
    f.write_text(json.dumps({"seeds": [1, 2, 3], "rtl_commit": "abc1234", "max_dim": 128, "results": [
        {"p": 8, "fmax_median": None, "fits": False, "build": VGRAD, "widths": SS4}]}))
    m = fmax.lookup(fmax.load([f]), 8, VGRAD, SS4)
    recs = [{"build": dict(FULL_BUILD), "widths": dict(scenes.DEFAULT_WIDTHS), "name": "full", "gates": _gates(800000),
             "fpga": None},
            {"build": VGRAD, "widths": SS4, "name": scenes.full_name(VGRAD, SS4), "gates": _gates(900000), "fpga": m}]
    assert scenes.builds_table(recs).splitlines()[3].endswith("| does not fit |")
    lines = "\n".join(scenes.place_lines(recs, {"rtl_commit": "abc1234"}))
    assert "does not fit the ECP5-85F: EXTREMUM=0, CLIP=0, VGRAD=1 (MAX_SS_LOG2=2) at P = 8" in lines
    # the largest P that fits: not measured yet, its command; the full build left to measure
    assert "  - the largest P that fits: not measured yet; P = 4: `python -m cube4_reports.fpga --p 4 " in lines
    assert "--md reports/fpga/e0k0g1_max_ss_log22_p4.md`" in lines
    assert lines.count("python -m cube4_reports.fpga") == 2
    # measured at P = 4 (it fits) and at P = 2: the table and the lines give P = 4's
    f4 = tmp_path / "fpga_y4.json"
    f4.write_text(json.dumps({"seeds": [1, 2, 3], "rtl_commit": "abc1234", "max_dim": 128, "results": [
        {"p": p, "fmax_median": mhz, "fits": True, "build": VGRAD, "widths": SS4} for p, mhz in ((4, 141.3), (2, 150.0))]}))
    recs = [scenes.ecp5({k: v for k, v in r.items() if k != "fpga"}, fmax.load([f, f4])) for r in recs]
    assert recs[1]["fit"].p == 4 and recs[0]["fit"] is None
    assert scenes.builds_table(recs).splitlines()[3].endswith("| does not fit (P = 4: 141.3) |")
    lines = "\n".join(scenes.place_lines(recs, {"rtl_commit": "abc1234"}))
    assert "  - the largest P that fits: 141.3 MHz: EXTREMUM=0, CLIP=0, VGRAD=1 (MAX_SS_LOG2=2) at P = 4" in lines
    assert scenes.build_records(recs)[1]["fit"]["p"] == 4
    # measured at P = 4 (no fit): the next P to try is 2; at 4, 2 and 1 (none fits): it fits at no P
    def smaller(ps):
        g = tmp_path / f"fpga_n{len(ps)}.json"
        g.write_text(json.dumps({"seeds": [1, 2, 3], "rtl_commit": "abc1234", "max_dim": 128, "results": [
            {"p": p, "fmax_median": None, "fits": False, "build": VGRAD, "widths": SS4} for p in ps]}))
        return [scenes.ecp5({k: v for k, v in r.items() if k not in ("fpga", "fit")}, fmax.load([f, g]))
                for r in recs]
    recs4 = smaller((4,))
    assert recs4[1]["next_p"] == 2 and not recs4[1]["fits_no_p"]
    lines = "\n".join(scenes.place_lines(recs4, {"rtl_commit": "abc1234"}))
    assert "  - the largest P that fits: not measured yet; P = 2: `python -m cube4_reports.fpga --p 2 " in lines
    assert "--md reports/fpga/e0k0g1_max_ss_log22_p2.md`" in lines
    assert scenes.builds_table(recs4).splitlines()[3].endswith("| does not fit |")
    recs_all = smaller((4, 2, 1))
    assert recs_all[1]["fits_no_p"] and not recs_all[0]["fits_no_p"]
    assert scenes.builds_table(recs_all).splitlines()[3].endswith("| fits at no P |")
    lines = "\n".join(scenes.place_lines(recs_all, {"rtl_commit": "abc1234"}))
    assert "  - fits at no P: P = 4, 2, 1 placed and routed too" in lines and "--p 2 " not in lines
    assert scenes.build_records(recs_all)[1]["fits_no_p"] is True
    row = {"scene": "head_quality", "volume": "head:64", "mode": "composite", "shaded": True, "crop": None,
           "cut": False, "build": VGRAD, "widths": SS4, "gradient": "central", "cycles": 1000, "cycles_full": None,
           "cycles_fixed": 2000, "psnr_db": 40.0, "psnr_point_db": 39.0, "truth_k": 3}
    assert "| fits at no P | — |" in scenes.scenes_table([row], recs_all).splitlines()[2]


def test_another_build_needs_its_own_report(capsys):
    assert fpga.main(["--p", "8", "--build", "BEATS=1,EXTREMUM=0,CLIP=0,PLW=0"]) == 2
    assert "name its report with --md" in capsys.readouterr().err


def test_md_only_rewrites_from_the_last_run_with_the_fpga_results_of_now(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(scenes, "DOC_REPORTS", tmp_path / "docs")
    monkeypatch.setattr(fmax, "REPORTS", tmp_path / "store")
    assert scenes.main(["--md-only"]) == 2 and "run make scenes first" in capsys.readouterr().err
    full = dict(FULL_BUILD)
    recs = [{"build": full, "widths": dict(scenes.DEFAULT_WIDTHS), "name": "full", "gates": _gates(800000),
             "fpga": None}]
    row = {"scene": "head", "volume": "head:64", "mode": "composite", "shaded": True, "crop": None, "cut": False,
           "build": full, "widths": dict(scenes.DEFAULT_WIDTHS), "gradient": "gra", "cycles": 137700,
           "cycles_full": 137700, "cycles_fixed": 200000, "psnr_db": 40.0, "psnr_point_db": 39.0, "truth_k": 3}
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "scenes.json").write_text(json.dumps({"p": 8, "max_dim": 128, "scenes": [row], "modes": [],
                                                      "builds": scenes.build_records(recs), "git": "abc",
                                                      "rtl_digest": "d", "rtl_commit": "abc1234"}))
    assert scenes.main(["--md-only"]) == 0
    assert "| not measured | not measured |" in (tmp_path / "docs" / "scenes.md").read_text()
    (tmp_path / "store").mkdir()
    (tmp_path / "store" / "fpga.json").write_text(json.dumps({"seeds": [1, 2, 3], "rtl_commit": "abc1234", "results": [
        {"p": 8, "fmax_median": 137.7, "fits": True, "luts": 1, "dsps": 2, "ebrs": 3, "build": full,
         "widths": dict(scenes.DEFAULT_WIDTHS)}]}))
    assert scenes.main(["--md-only"]) == 0
    text = (tmp_path / "docs" / "scenes.md").read_text()
    assert "| 1.000 | 1.000 |" in text and "- full: 137.7 MHz" in text

"""cube4_reports.fpga_status: the builds the reports need, classified against the measured
place-and-route results (synthetic reports and results; git of this repository)."""

from cube4.builds import FULL_BUILD
from cube4.config import Cube4Config
from cube4_reports import fmax as fmax_store
from cube4_reports import fpga_status as fs
from cube4_reports.markdown import last_commit

W = Cube4Config(pipelines=8).widths()
BEATS = {**FULL_BUILD, "EXTREMUM": 0, "CLIP": 0, "PLW": 0, "BEATS": 1}
BIG = {**FULL_BUILD, "EXTREMUM": 0, "CLIP": 0, "BEATS": 1}


def measured(p, build, fmax, rtl, fits=True, widths=W):
    return fmax_store.Measured(fmax_mhz=fmax if fits else None, p=p, build=fmax_store.complete_build(build),
                               widths=dict(widths), seeds=(1, 2, 3), fmax_seeds=(fmax, fmax, fmax) if fits else (),
                               max_dim=128, rtl=rtl, source="reports/fpga/x.json", finished="2026-12-05 10:00",
                               fits=fits)


def needs_of(scenes=(), rows=(), frames=()):
    needs = {}
    fs.scene_needs({"builds": [{"build": b, "widths": W} for b in scenes]}, needs)
    fs.report_needs({"rows": list(rows)}, needs)
    fs.skipping_needs({"rtl_beats": list(frames)}, needs)
    return needs


def row(build_name, p=8, weight_bits=8, source="rtl"):
    return {"build": build_name, "pipelines": p, "voxel_bits": 8, "weight_bits": weight_bits, "alpha_bits": 12,
            "acc_bits": 16, "rmap_bits": 5, "supersample": 1, "cycles_source": source}


def test_needs_merge_builds_and_count_their_users():
    name = "EXTREMUM=0, CLIP=0, PLW=0, BEATS=1"
    needs = needs_of(scenes=[BEATS], rows=[row(name), row(name), row(name, weight_bits=6),
                                            row(name, source=fs.NO_BUILD_SOURCE), row(name, p=4)],
                     frames=[{"build": {"SHADING": 1, "COMPOSITING": 1, "BEATS": 1}, "widths": W}])
    by = {(n.p, n.widths["WEIGHT_W"]): n for n in needs.values()}
    assert set(by) == {(8, 8), (8, 6), (4, 8)}                 # the row no build runs is left out
    assert by[(8, 8)].users == {"scenes": 1, "report": 2, "skipping": 1}
    assert by[(8, 8)].build == fmax_store.complete_build(BEATS)


def test_states_goal_and_todo():
    head = last_commit()
    needs = needs_of(scenes=[FULL_BUILD, BEATS, BIG], rows=[row("EXTREMUM=0, CLIP=0, PLW=0, BEATS=1", weight_bits=6)])
    results = [measured(8, FULL_BUILD, 141.0, head), measured(8, BEATS, 129.6, "0000000"),
               measured(8, BIG, None, head, fits=False)]
    fs.smaller_p_needs(needs, results)
    rows = fs.statuses(needs, results)
    st = {(s.need.p, fmax_store.build_label(s.need.build, s.need.widths)): s for s in rows}
    full = st[(8, "full")]
    assert full.state == "measured" and full.current and not full.below_goal
    beats = st[(8, "EXTREMUM=0, CLIP=0, PLW=0, BEATS=1")]
    assert beats.below_goal and not beats.current          # 129.6 < 130; a commit git does not know
    assert beats.age == "unknown"
    assert st[(8, "EXTREMUM=0, CLIP=0, PLW=0, BEATS=1 (WEIGHT_W=6)")].state == "not measured"
    big = st[(8, "EXTREMUM=0, CLIP=0, BEATS=1")]
    assert big.state == "does not fit" and big.current
    assert (4, "EXTREMUM=0, CLIP=0, BEATS=1") in st            # the next smaller P to try
    assert (2, "EXTREMUM=0, CLIP=0, BEATS=1") not in st        # not before P = 4 was measured
    text = fs.markdown(rows)
    assert "129.6 (below 130)" in text and "Below 130 MHz at P = 8: EXTREMUM=0, CLIP=0, PLW=0, BEATS=1 129.6" in text
    todo = [fs.place_command(s.need) for s in rows if not s.current]
    assert len(todo) == len(rows) - 2 and all(c.startswith("python -m cube4_reports.fpga --p ") for c in todo)
    assert any("--p 4 " in c and c.endswith("_p4.md") for c in todo)


def test_smaller_p_stops_at_the_first_that_fits():
    needs = needs_of(scenes=[BIG])
    results = [measured(8, BIG, None, "x", fits=False), measured(4, BIG, None, "x", fits=False),
               measured(2, BIG, 120.0, "x")]
    fs.smaller_p_needs(needs, results)
    assert sorted(n.p for n in needs.values()) == [2, 4, 8]


def test_committed_reports_are_read(capsys):
    assert fs.main([]) == 0
    out = capsys.readouterr().out
    assert out.startswith("# Place and route") and "| full | 8 |" in out


def test_comment_only_changes_keep_a_result_current(monkeypatch):
    diffs = {"comment": "--- a/rtl/x.v\n+++ b/rtl/x.v\n@@ -3 +3 @@\n-// old words\n+// new words\n+\n",
             "logic": "--- a/rtl/x.v\n+++ b/rtl/x.v\n@@ -3 +3 @@\n-    assign a = b;  // why\n+    assign a = c;  // why\n"}

    def fake_git(*args):
        if args[0] == "rev-parse":
            return "tree-" + args[-1].split("^")[0]
        if args[0] == "diff":
            return diffs[args[2]]
        return "4"                                            # rev-list --count
    monkeypatch.setattr(fs, "_git", fake_git)
    assert fs.rtl_age("comment", "tree-HEAD") == "as now but comments"
    assert fs.rtl_age("logic", "tree-HEAD") == "4 commits to rtl/ since"
    assert fs.rtl_age("HEAD", "tree-HEAD") == "as now"


def test_a_change_in_files_a_build_does_not_read_keeps_it_current(monkeypatch):
    """rtl/ changed only in another build's module: current for a build whose list of files
    lacks it; a build that reads it (or one with no list) is not."""
    diffs = {("logic", "--unified=0"): "--- a/rtl/b.v\n+++ b/rtl/b.v\n@@ -3 +3 @@\n-    assign a = b;\n+    assign a = c;\n",
             ("logic", "--no-renames"): "rtl/b.v\n"}

    def fake_git(*args):
        if args[0] == "rev-parse":
            return "tree-" + args[-1].split("^")[0]
        if args[0] == "diff":
            return diffs[args[2] if args[1] == "--unified=0" else args[3], args[1]]
        return "1"                                            # rev-list --count
    monkeypatch.setattr(fs, "_git", fake_git)
    assert fs.rtl_age("logic", "tree-HEAD", ("rtl/a.v", "rtl/x.vh")) == "as now in the files it reads"
    assert fs.rtl_age("logic", "tree-HEAD", ("rtl/a.v", "rtl/b.v")) == "1 commit to rtl/ since"
    assert fs.rtl_age("logic", "tree-HEAD") == "1 commit to rtl/ since"

"""cube4_reports.fpga_todo: the list of runs and the lanes that run them (fake processes; no
synthesis, no place and route)."""

import pytest

from cube4.builds import FULL_BUILD
from cube4.config import Cube4Config
from cube4_reports import fmax as fmax_store
from cube4_reports import fpga_todo as ft
from cube4_reports.markdown import last_commit

CMD = ("python -m cube4_reports.fpga --p 8 --seeds 1,2,3 --max-dim 128 --depth 1024 --no-budget --no-memory "
       "--build EXTREMUM=0,CLIP=0,PLW=0,BEATS=1 --md reports/fpga/e0k0w0b1.md")


def test_a_status_command_becomes_a_job():
    j = ft.job_from_command(CMD)
    assert j.name == "e0k0w0b1"
    assert j.command[1:3] == ["-m", "cube4_reports.fpga"] and j.args[-2:] == ("--md", "reports/fpga/e0k0w0b1.md")
    flow = ft.with_flow(j, 2400)
    assert flow[-5:] == ["--jobs", "1", "--reuse", "--timeout", "2400"]
    with pytest.raises(ValueError):
        ft.job_from_command("python -m cube4_reports.scenes --md x.md")


def test_full_jobs_skip_the_p_measured_on_todays_rtl():
    def run(p, rtl):
        return fmax_store.Measured(fmax_mhz=150.0, p=p, build=fmax_store.complete_build(FULL_BUILD),
                                   widths=Cube4Config(pipelines=p).widths(), seeds=(1, 2, 3),
                                   fmax_seeds=(150.0,) * 3, max_dim=128, rtl=rtl, source="reports/fpga/x.json",
                                   finished="2026-12-07 10:00", fits=True)
    jobs = ft.full_jobs([run(4, last_commit()), run(2, "0000000")])     # P = 4 current, P = 2 on an unknown RTL
    assert [j.name for j in jobs] == ["full_p1", "full_p2", "full_p8"]
    for j in jobs:
        p = j.name[len("full_p"):]
        assert j.args[j.args.index("--p") + 1] == p and j.args[-2:] == ("--md", f"reports/fpga/full_p{p}.md")
        assert "--build" not in j.args and "--widths" not in j.args


def test_the_full_build_at_p8_runs_once_under_either_name(monkeypatch):
    full8 = ft.Job("full_p8", ("--p", "8", "--seeds", "1,2,3", "--md", "reports/fpga/full_p8.md"))
    full4 = ft.Job("full_p4", ("--p", "4", "--seeds", "1,2,3", "--md", "reports/fpga/full_p4.md"))
    monkeypatch.setattr(ft, "full_jobs", lambda measured: [full8, full4])

    class Row:                    # fpga_status rows: the full build at P = 8 (as "full"), a beat build, one current
        def __init__(self, cmd, current=False):
            self.need, self.current = cmd, current
    rows = [Row("python -m cube4_reports.fpga --p 8 --seeds 1,2,3 --md reports/fpga/full.md"), Row(CMD),
            Row(CMD.replace("e0k0w0b1", "mip"), current=True)]
    monkeypatch.setattr(ft.fpga_status, "collect", lambda measured=None: rows)
    monkeypatch.setattr(ft.fpga_status, "place_command", lambda need: need)
    assert [j.name for j in ft.todo(full=True)] == ["full_p8", "full_p4", "e0k0w0b1"]
    assert [j.name for j in ft.todo(full=False)] == ["full", "e0k0w0b1"]


class FakeProc:
    """A run that ends after ``ticks`` polls with exit code ``rc``."""
    live = 0
    most = 0

    def __init__(self, cmd, ticks, rc):
        self.cmd, self.ticks, self.returncode, self.pid = cmd, ticks, None, None
        self.rc = rc
        FakeProc.live += 1
        FakeProc.most = max(FakeProc.most, FakeProc.live)

    def poll(self):
        self.ticks -= 1
        if self.ticks <= 0 and self.returncode is None:
            self.returncode = self.rc
            FakeProc.live -= 1
        return self.returncode


def test_lanes_run_each_job_once_and_pick_up_new_needs(monkeypatch, tmp_path):
    monkeypatch.setattr(ft, "LOG_DIR", tmp_path)
    FakeProc.live = FakeProc.most = 0
    a, b, c, d = (ft.Job(n, ("--md", f"reports/fpga/{n}.md")) for n in "abcd")
    todo = [a, b, c]
    ticks = {"a": 1, "b": 3, "c": 1, "d": 1}
    started = []

    def start(cmd, **kw):
        name = cmd[cmd.index("--md") + 1].split("/")[-1][:-3]
        started.append(name)
        return FakeProc(cmd, ticks[name], 1 if name == "c" else 0)

    def next_jobs():
        # a ran: it is gone from the list; after a, d is needed (a build that did not fit, say);
        # c failed and stays listed, but is not started again in this run
        done = {n for n in started if n in ("a", "b", "d")}
        out = [j for j in todo if j.name not in done]
        return out + ([d] if "a" in started and "d" not in done else [])

    ended = ft.run(next_jobs, lanes=2, timeout=10, start=start, poll_s=0)
    assert sorted(started) == ["a", "b", "c", "d"] and len(started) == 4
    assert FakeProc.most == 2
    assert {j.name: rc for j, rc in ended} == {"a": 0, "b": 0, "c": 1, "d": 0}
    assert (tmp_path / "d.log").exists()


def test_one_lane_runs_one_at_a_time(monkeypatch, tmp_path):
    monkeypatch.setattr(ft, "LOG_DIR", tmp_path)
    FakeProc.live = FakeProc.most = 0
    jobs = [ft.Job(n, ("--md", f"{n}.md")) for n in "xyz"]
    ended = ft.run(lambda: jobs, lanes=1, timeout=10, start=lambda cmd, **kw: FakeProc(cmd, 2, 0), poll_s=0)
    assert [j.name for j, _ in ended] == ["x", "y", "z"] and FakeProc.most == 1


def test_only_runs_the_named_builds_in_the_named_order(monkeypatch, capsys):
    jobs = [ft.Job(n, ("--p", "8", "--md", f"reports/fpga/{n}.md")) for n in ("e0k0w0", "e0k0w0b1", "e0w0b1")]
    assert [j.name for j in ft.only(jobs, ["e0w0b1", "e0k0w0b1"])] == ["e0w0b1", "e0k0w0b1"]
    with pytest.raises(ft.UserError, match="full_p8"):
        ft.only(jobs, ["e0w0b1", "full_p8"])       # measured already, or no such build
    monkeypatch.setattr(ft, "todo", lambda full: jobs)
    assert ft.main(["--only", "e0w0b1,e0k0w0", "--list"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert [line.split()[-1] for line in out] == ["reports/fpga/e0w0b1.md", "reports/fpga/e0k0w0.md"]
    assert ft.main(["--only", "nosuch", "--list"]) == 1
    assert "not among the runs still to do: nosuch" in capsys.readouterr().err

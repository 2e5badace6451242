"""Bricks on several boards: a real Dask LocalCluster of worker processes, one of them
killed in mid-frame; the command line's brick options; the layers (the golden model
never imports dask)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from cube4.app.cli import main
from cube4.bricks import make_grid, render_bricked
from cube4.config import Cube4Config
from cube4.host import host_tables
from cube4.view import make_traversal
from cube4_testutil import BRICK_TF, brick_volume, make_scene

WAIT_S = 90.0   # every wait below ends by itself: a broken cluster fails the test, it does not hang it


def _wait_for(pred, what: str, timeout: float = WAIT_S):
    t_end = time.monotonic() + timeout
    while time.monotonic() < t_end:
        got = pred()
        if got:
            return got
        time.sleep(0.02)
    raise AssertionError(f"timed out waiting for {what}")


def test_worker_killed_in_mid_frame_costs_a_retry_not_the_frame(tmp_path):
    """Two worker processes; every brick waits at the start of its run (the executor's
    fault-injection hook) until the test has SIGKILLed the worker running one of them.
    The frame still completes, bit for bit the same as rendered in this process, and
    the journal shows the interrupted brick run again in another process."""
    from cube4.app.cluster import DaskExecutor

    vol = brick_volume()
    nz, ny, nx = vol.shape
    cfg = Cube4Config()
    trav = make_traversal((nx, ny, nz), (0.6, 1.0, -0.45), cfg.weight_bits, 1)
    lut, rmap = host_tables(make_scene(transfer=BRICK_TF), cfg, trav)
    grid = make_grid(trav.dims, (2, 2, 2))
    local = render_bricked(vol, trav, cfg, lut, rmap, grid)

    journal, hold = tmp_path / "journal", tmp_path / "hold"
    journal.mkdir()
    hold.touch()
    out: dict = {}
    with DaskExecutor(workers=2, journal=str(journal), hold=str(hold), timeout=WAIT_S) as ex:
        def frame():
            try:
                out["frame"] = render_bricked(vol, trav, cfg, lut, rmap, grid, executor=ex)
            except BaseException as exc:  # reported by the assertions below
                out["error"] = exc

        th = threading.Thread(target=frame, daemon=True)
        th.start()
        started = _wait_for(lambda: sorted(journal.glob("*.start")), "a brick to start")
        victim = started[0]
        label, pid = victim.name.split(".")[0], int(victim.name.split(".")[1])
        assert pid != os.getpid()
        os.kill(pid, signal.SIGKILL)
        time.sleep(0.2)
        hold.unlink()
        th.join(WAIT_S)
        assert not th.is_alive(), "the frame did not finish"
        stats = ex.stats()
    assert "error" not in out, out.get("error")
    assert np.array_equal(out["frame"].frame.baseplane, local.frame.baseplane)
    runs = sorted(p.name for p in journal.glob(f"{label}.*"))
    assert f"{label}.{pid}.start" in runs and f"{label}.{pid}.done" not in runs     # killed in its run
    done = [r for r in runs if r.endswith(".done")]
    assert len(done) == 1 and int(done[0].split(".")[1]) != pid                   # finished elsewhere
    assert len(list(journal.glob("*.done"))) == grid.size
    assert stats["retries"] >= 1 and stats["executor"] == "dask"


@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")   # a socket distributed leaves open
def test_cli_bricks_on_a_local_cluster(tmp_path, capsys):
    """`cube4 render ... --bricks 2,2,2 --workers 2`, and `--scheduler` to a cluster
    started apart: the same base plane as the bricks rendered in this process, the brick
    statistics, one summary line each."""
    from distributed import LocalCluster

    base = {}
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster:
        runs = (("local", []), ("cluster", ["--workers", "2"]), ("remote", ["--scheduler", cluster.scheduler_address]))
        for name, extra in runs:
            rc = main(["render", "sphere:20", "--bricks", "2,2,2", *extra, "--out", str(tmp_path / f"{name}.png"),
                       "--baseplane", str(tmp_path / f"{name}.npy"), "--stats", str(tmp_path / f"{name}.json")])
            assert rc == 0
            base[name] = np.load(tmp_path / f"{name}.npy")
    assert np.array_equal(base["local"], base["cluster"]) and np.array_equal(base["local"], base["remote"])
    st = json.loads((tmp_path / "cluster.json").read_text())
    b = st["bricks"]
    assert b["grid"] == [2, 2, 2] and b["count"] == 8 and b["workers"] == 2 and b["executor"] == "dask"
    assert b["memory_overhead"] > 0 and b["largest"] == [12, 12, 12]
    remote = json.loads((tmp_path / "remote.json").read_text())["bricks"]
    assert remote["scheduler"].startswith("tcp://") and remote["workers"] == 1
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 3 and "8 bricks 2x2x2" in lines[1] and "on 2 workers" in lines[1] and "on 1 worker)" in lines[2]
    # a monolithic render of the same volume is within a few LSBs (the §14 bound is tested in test_bricks)
    assert main(["render", "sphere:20", "--quiet", "--out", str(tmp_path / "m.png"),
                 "--baseplane", str(tmp_path / "m.npy")]) == 0
    diff = np.abs(np.load(tmp_path / "m.npy") - base["local"])
    assert 0 < diff.max() <= 16


@pytest.mark.parametrize("args, message", [
    (["--bricks", "2,2"], "--bricks must be BX,BY,BZ"),
    (["--bricks", "2,0,2"], "--bricks must be BX,BY,BZ"),
    (["--bricks", "17,1,1"], "17 bricks along x need at least 17 voxels"),
    (["--workers", "2"], "give --bricks BX,BY,BZ or --board-dim N"),
    (["--bricks", "2,2,2", "--workers", "2", "--scheduler", "tcp://127.0.0.1:8786"], "exclude each other"),
    (["--bricks", "2,2,2", "--workers", "0"], "--workers must be in 1..256"),
    (["--bricks", "2,2,2", "--scheduler", "localhost"], "--scheduler must be a Dask scheduler address"),
    (["--board-dim", "3"], "--board-dim must be in 4..2048"),
    (["--bricks", "2,2,2", "--board-dim", "8"], "more than --board-dim 8"),
    (["--bricks", "2,2,2", "--engine", "reference"], "needs an engine that renders bricks"),
    (["--bricks", "2,2,2", "--build", "CLIP=0"], "the build needs CLIP = 1"),
])
def test_bad_brick_options_are_one_line(tmp_path, capsys, args, message):
    out = tmp_path / "out.png"
    out.write_bytes(b"earlier image")
    rc = main(["render", "sphere:16", *args, "--quiet", "--out", str(out)])
    err = capsys.readouterr().err
    assert rc == 2 and err.startswith("cube4: error: ") and err.count("\n") == 1 and message in err, err
    assert out.read_bytes() == b"earlier image"


def test_bricks_refuse_mip(tmp_path, capsys):
    scene = tmp_path / "mip.toml"
    scene.write_text('[render]\nmode = "mip"\n')
    rc = main(["render", "sphere:16", "--scene", str(scene), "--bricks", "2,1,1", "--quiet",
               "--out", str(tmp_path / "x.png")])
    err = capsys.readouterr().err
    assert rc == 2 and "--bricks composes the modes composite, xray" in err and err.count("\n") == 1


def test_board_dim_chooses_the_bricks(tmp_path):
    """A volume larger than one board (40 voxels on boards of 24) renders in the fewest
    bricks that fit: 2 per axis (21 + 2 and 20 + 1 voxels with the overlap)."""
    st = tmp_path / "s.json"
    assert main(["render", "sphere:40", "--board-dim", "24", "--quiet", "--out", str(tmp_path / "x.png"),
                 "--stats", str(st)]) == 0
    b = json.loads(st.read_text())["bricks"]
    assert b["grid"] == [2, 2, 2] and max(b["largest"]) <= 24


def test_golden_bricks_never_import_dask(tmp_path):
    """The golden package renders bricks in-process without dask; only --workers or
    --scheduler import it (cube4.cluster)."""
    code = ("import sys; from cube4.app.cli import main; "
            f"rc = main(['render', 'sphere:16', '--bricks', '2,1,2', '--quiet', '--out', {str(tmp_path / 'x.png')!r}]); "
            "import cube4.bricks, cube4.brick_rays, cube4.model; "
            "bad = [m for m in ('dask', 'distributed') if m in sys.modules]; "
            "sys.exit(rc or (3 if bad else 0))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=dict(os.environ))
    assert r.returncode == 0, r.stderr[-2000:]
    src = Path(__file__).resolve().parents[1] / "golden" / "cube4"
    for name in ("model.py", "bricks.py", "brick_rays.py", "host.py", "view.py", "clip.py"):
        text = (src / name).read_text()
        assert "import dask" not in text and "from distributed" not in text and "from dask" not in text, name

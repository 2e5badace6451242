"""The cube4 command line: a good render, and every kind of bad input giving one clear
line on stderr, exit status 2, no traceback and no output file."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from cube4.app.cli import main

SMALL_SCENE = """
[view]
direction = [0.4, 0.3, 0.86]
[output]
width = 48
"""


@pytest.fixture
def scene_file(tmp_path: Path) -> Path:
    p = tmp_path / "s.toml"
    p.write_text(SMALL_SCENE)
    return p


def run_cli(args: list[str], capsys) -> tuple[int, str, str]:
    rc = main(args)
    out, err = capsys.readouterr()
    return rc, out, err


def test_render_golden_with_stats_and_compare(tmp_path, scene_file, capsys):
    out = tmp_path / "x.png"
    stats = tmp_path / "s.json"
    bp = tmp_path / "bp.npy"
    rc, so, se = run_cli(["render", "sphere:24", "--scene", str(scene_file), "--engine", "golden",
                          "--compare-to", "reference", "--stats", str(stats), "--out", str(out),
                          "--baseplane", str(bp), "--pipelines", "5"], capsys)
    assert rc == 0, se
    assert out.stat().st_size > 0
    d = json.loads(stats.read_text())
    for key in ("engine", "dims", "pipelines", "view", "wall_s", "rmse", "max_abs", "psnr"):
        assert key in d
    assert d["engine"] == "golden" and d["dims"] == [24, 24, 24] and d["pipelines"] == 5
    assert d["psnr"] > 25
    # the error is against the area truth, and the stats say how it converged
    assert d["reference"] == "reference" and d["truth"] == "area" and d["truth_k"] in (3, 9)
    assert d["truth_change"] <= 2.0 ** -9 or not d["truth_converged"]
    base = np.load(bp)
    assert base.ndim == 3 and base.shape[2] == 4 and base.max() > 0
    assert "PSNR" in so
    assert not list(tmp_path.glob(".cube4-*")), "temporary files left behind"


def test_console_script_runs(tmp_path, scene_file):
    exe = Path(sys.executable).with_name("cube4")
    out = tmp_path / "y.exr"
    r = subprocess.run([str(exe), "render", "sphere:16", "--scene", str(scene_file), "--out", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert out.exists()


def _raw(tmp_path: Path, name: str, nbytes: int) -> Path:
    p = tmp_path / name
    p.write_bytes(bytes(np.arange(nbytes, dtype=np.uint8)))
    return p


BAD = {
    "truncated raw": (lambda t: [str(_raw(t, "v.raw", 8 * 8 * 8 - 1)), "--dims", "8,8,8", "--dtype", "uint8"], "bytes"),
    "oversized raw": (lambda t: [str(_raw(t, "v.raw", 8 * 8 * 8 + 5)), "--dims", "8,8,8", "--dtype", "uint8"], "bytes"),
    "wrong dims": (lambda t: [str(_raw(t, "v.raw", 512)), "--dims", "8,8", "--dtype", "uint8"], "dims"),
    "zero dim": (lambda t: [str(_raw(t, "v.raw", 512)), "--dims", "0,8,64", "--dtype", "uint8"], ""),
    "unknown dtype": (lambda t: [str(_raw(t, "v.raw", 512)), "--dims", "8,8,8", "--dtype", "complex64"], "complex64"),
    "missing file": (lambda t: [str(t / "nope.nrrd")], ""),
    "unknown built-in": (lambda t: ["teapot:32"], "teapot"),
    "bad built-in size": (lambda t: ["sphere:1"], ""),
    "p out of range": (lambda t: ["sphere:16", "--pipelines", "0"], "pipelines"),
    "p too large": (lambda t: ["sphere:16", "--pipelines", "1000"], "pipelines"),
    "bad output suffix": (lambda t: ["sphere:16", "--out", str(t / "x.jpg2")], "--out"),
}

BAD_SCENES = {
    "NaN view": '[view]\ndirection = [nan, 0.0, 1.0]\n',
    "zero view": '[view]\ndirection = [0.0, 0.0, 0.0]\n',
    "two-component view": '[view]\ndirection = [1.0, 0.0]\n',
    "malformed TOML": '[view\ndirection = 1\n',
    "unknown key": '[view]\ndirektion = [1, 0, 0]\n',
    "bad mode": '[render]\nmode = "hologram"\n',
    "bad supersample": '[render]\nsupersample = 3\n',
    "unsorted transfer": '[transfer]\npoints = [[0.5, 1, 1, 1, 1], [0.2, 0, 0, 0, 0]]\n',
    "light without direction": '[[light]]\nintensity = 1.0\n',
    "bad precision": '[precision]\nacc_bits = 99\n',
    "float supersample": '[render]\nsupersample = 2.0\n',
    "string headlight": '[[light]]\nheadlight = "no"\n',
    "string direction": '[view]\ndirection = "123"\n',
}


EARLIER = b"an earlier image"


def _earlier_output(tmp_path: Path) -> Path:
    """An earlier run's output at the path this run writes: it must survive untouched."""
    p = tmp_path / "out.png"
    p.write_bytes(EARLIER)
    return p


def _assert_clean_failure(rc: int, err: str, tmp_path: Path, needle: str = "") -> None:
    assert rc == 2
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1, err
    assert lines[0].startswith("cube4: error: ")
    assert "Traceback" not in err
    assert needle.lower() in lines[0].lower()
    earlier = tmp_path / "out.png"
    assert not earlier.exists() or earlier.read_bytes() == EARLIER, "an earlier output was replaced"
    left = [p for p in tmp_path.glob("out*") if p != earlier] + list(tmp_path.glob(".cube4-*"))
    assert not left, f"an output file was left behind: {left}"


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_input(case, tmp_path, scene_file, capsys):
    make_args, needle = BAD[case]
    _earlier_output(tmp_path)
    args = make_args(tmp_path)
    out = ["--out", str(tmp_path / "out.png")] if "--out" not in args else []
    rc, _, err = run_cli(["render", *args, "--scene", str(scene_file), *out,
                          "--stats", str(tmp_path / "out.json")], capsys)
    _assert_clean_failure(rc, err, tmp_path, needle)


@pytest.mark.parametrize("case", sorted(BAD_SCENES))
def test_bad_scene(case, tmp_path, capsys):
    sc = tmp_path / "bad.toml"
    sc.write_text(BAD_SCENES[case])
    _earlier_output(tmp_path)
    rc, _, err = run_cli(["render", "sphere:16", "--scene", str(sc), "--out", str(tmp_path / "out.png")], capsys)
    _assert_clean_failure(rc, err, tmp_path)


def test_rtl_engine_bad_input_fails_before_simulating(tmp_path, scene_file, capsys):
    """Bad input is reported in one line before the RTL engine builds anything.
    (Rendering through the RTL itself is tested in tb/cube4_top.)"""
    from cube4_sim.cli import main as sim_main

    _earlier_output(tmp_path)
    rc = sim_main(["render", "sphere:16", "--scene", str(scene_file), "--engine", "rtl",
                   "--pipelines", "0", "--out", str(tmp_path / "out.png")])
    _, err = capsys.readouterr()
    _assert_clean_failure(rc, err, tmp_path, "pipelines")


def test_bad_input_as_a_subprocess_has_no_traceback(tmp_path):
    r = subprocess.run([sys.executable, "-m", "cube4.app.cli", "render", "sphere:16", "--pipelines", "99",
                        "--out", str(tmp_path / "out.png")], capture_output=True, text=True)
    assert r.returncode == 2
    assert r.stderr.strip().count("\n") == 0 and "Traceback" not in r.stderr


def test_unwritable_output_leaves_nothing(tmp_path, scene_file, capsys):
    blocker = tmp_path / "afile"
    blocker.write_text("x")
    out = _earlier_output(tmp_path)
    rc, _, err = run_cli(["render", "sphere:16", "--scene", str(scene_file), "--out", str(out),
                          "--stats", str(blocker / "s.json")], capsys)
    _assert_clean_failure(rc, err, tmp_path)


def test_stats_are_strict_json_and_files_world_readable(tmp_path, scene_file, capsys):
    stats = tmp_path / "s.json"
    out = tmp_path / "r.png"
    rc, _, err = run_cli(["render", "sphere:16", "--scene", str(scene_file), "--engine", "reference-point",
                          "--compare-to", "reference-point", "--stats", str(stats), "--out", str(out)], capsys)
    assert rc == 0, err
    d = json.loads(stats.read_text(), parse_constant=lambda c: pytest.fail(f"non-JSON constant {c}"))
    assert d["psnr"] is None and d["rmse"] == 0.0
    assert out.stat().st_mode & 0o044 == 0o044


def test_several_views_numbered_outputs_and_stats(tmp_path, capsys):
    """--view repeated and --orbit: one numbered image and base plane per view, the
    stats list every frame, and each view equals a single render from that view."""
    out, bp, st = tmp_path / "v.png", tmp_path / "v.npy", tmp_path / "v.json"
    rc, text, err = run_cli(["render", "sphere:16", "--view", "10,20", "--view=-100,-45", "--out", str(out),
                             "--baseplane", str(bp), "--stats", str(st)], capsys)
    assert rc == 0, err
    assert text.count("cube4: golden render") == 2
    d = json.loads(st.read_text())
    assert d["views"] == 2 and [round(f["azimuth"]) for f in d["frames"]] == [10, -100]
    for n, view in enumerate(["10,20", "-100,-45"]):
        assert (tmp_path / f"v_{n:03d}.png").is_file()
        single = tmp_path / f"single{n}.npy"
        assert run_cli(["render", "sphere:16", f"--view={view}", "--out", str(tmp_path / f"s{n}.png"),
                        "--baseplane", str(single), "--quiet"], capsys)[0] == 0
        assert np.array_equal(np.load(tmp_path / f"v_{n:03d}.npy"), np.load(single))
    rc, text, err = run_cli(["render", "sphere:16", "--orbit", "4", "--out", str(tmp_path / "o{n}.png"),
                             "--stats", str(tmp_path / "o.json"), "--quiet"], capsys)
    assert rc == 0, err
    assert sorted(p.name for p in tmp_path.glob("o0*.png")) == [f"o{n:03d}.png" for n in range(4)]
    az = [f["azimuth"] for f in json.loads((tmp_path / "o.json").read_text())["frames"]]
    steps = [(b - a) % 360 for a, b in zip(az, az[1:])]
    assert all(abs(s - 90) < 1e-6 for s in steps), az


@pytest.mark.parametrize("args, needle", [
    (["--view", "10,20", "--orbit", "3"], "exclude"),
    (["--view", "10"], "--view"),
    (["--view", "0,95"], "elevation"),
    (["--orbit", "0"], "--orbit"),
])
def test_bad_views_fail_cleanly(tmp_path, capsys, args, needle):
    _earlier_output(tmp_path)
    rc, _, err = run_cli(["render", "sphere:16", *args, "--out", str(tmp_path / "out.png")], capsys)
    _assert_clean_failure(rc, err, tmp_path, needle)

"""All-or-nothing outputs (cube4.outputs): destinations checked before any work; a
failure at any point leaves every earlier file as it was, removes what the run made
(files, temporaries, folders) and names the user's path in one line."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from cube4.app import cli
from cube4.app.outputs import check_destinations, write_all
from cube4.errors import UserError

SCENE = "[view]\ndirection = [0.4, 0.3, 0.86]\n[output]\nwidth = 32\n"


def _text(s: str):
    return lambda tmp: Path(tmp).write_text(s)


def _fail(tmp: str) -> None:
    raise OSError(28, "No space left on device", tmp)


def _leftovers(folder: Path) -> list[Path]:
    return [p for p in folder.rglob("*") if p.name.startswith(".cube4-")]


def test_write_all_replaces_every_file(tmp_path):
    a, b = tmp_path / "a.txt", tmp_path / "new" / "b.txt"
    a.write_text("old a")
    write_all([(a, _text("new a")), (b, _text("new b"))])
    assert a.read_text() == "new a" and b.read_text() == "new b" and not _leftovers(tmp_path)


def test_failed_write_leaves_earlier_files_and_no_folders(tmp_path):
    a, b = tmp_path / "a.txt", tmp_path / "x" / "y" / "b.txt"
    a.write_text("old a")
    with pytest.raises(UserError, match=r"cannot write '.*b\.txt'"):
        write_all([(a, _text("new a")), (b, _fail)])
    assert a.read_text() == "old a"
    assert not (tmp_path / "x").exists() and not _leftovers(tmp_path)


def test_failed_move_rolls_back_files_already_moved(tmp_path, monkeypatch):
    """The second rename fails after the first output is in place: the first is put back."""
    a, b, c = tmp_path / "a.txt", tmp_path / "b.txt", tmp_path / "c.txt"
    a.write_text("old a")
    real_replace = os.replace
    calls = {"n": 0}

    def replace(src, dst):
        if str(dst) == str(b):
            calls["n"] += 1
            raise OSError(13, "Permission denied", str(dst))
        return real_replace(src, dst)

    monkeypatch.setattr(os, "replace", replace)
    with pytest.raises(UserError, match=r"cannot write '.*b\.txt': Permission denied"):
        write_all([(a, _text("new a")), (b, _text("new b")), (c, _text("new c"))])
    assert calls["n"] == 1
    assert a.read_text() == "old a" and not b.exists() and not c.exists() and not _leftovers(tmp_path)


def test_interrupt_rolls_back_too(tmp_path):
    a = tmp_path / "a.txt"
    a.write_text("old a")

    def interrupted(tmp: str) -> None:
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        write_all([(a, _text("new a")), (tmp_path / "b.txt", interrupted)])
    assert a.read_text() == "old a" and not _leftovers(tmp_path)


@pytest.mark.parametrize("kind", ["folder", "under_a_file", "too_long", "twice"])
def test_destinations_checked(tmp_path, kind):
    if kind == "folder":
        (tmp_path / "o.png").mkdir()
        named = [(tmp_path / "o.png", "--out")]
        needle = "is a folder"
    elif kind == "under_a_file":
        (tmp_path / "f").write_text("x")
        named = [(tmp_path / "f" / "o.png", "--out")]
        needle = "is not a folder"
    elif kind == "too_long":
        named = [(tmp_path / ("n" * 300 + ".png"), "--out")]
        needle = "longer than the file system allows"
    else:
        named = [(tmp_path / "o.json", "--stats"), (tmp_path / "." / "o.json", "--out")]
        needle = "is also the --stats"
    with pytest.raises(UserError, match=needle):
        check_destinations(named)


def _render(tmp_path: Path, capsys, *args: str) -> tuple[int, str]:
    scene = tmp_path / "s.toml"
    scene.write_text(SCENE)
    rc = cli.main(["render", "sphere:16", "--scene", str(scene), "--quiet", *args])
    return rc, capsys.readouterr().err


def test_cli_checks_every_numbered_output_before_work(tmp_path, capsys, monkeypatch):
    """Two views into out.png where out_001.png is a folder: nothing rendered, nothing
    touched, the message names the user's path."""
    first = tmp_path / "out_000.png"
    first.write_bytes(b"earlier image")
    (tmp_path / "out_001.png").mkdir()
    monkeypatch.setattr(cli, "render_views", lambda *a, **k: pytest.fail("rendered before checking"))
    rc, err = _render(tmp_path, capsys, "--view", "10,10", "--view", "20,20", "--out", str(tmp_path / "out.png"))
    assert rc == 2 and err.count("\n") == 1 and "out_001.png" in err and ".cube4-" not in err
    assert first.read_bytes() == b"earlier image"


def test_cli_failure_after_work_keeps_earlier_outputs(tmp_path, capsys, monkeypatch):
    """The stats file cannot be written after the image was: the earlier image stays."""
    out, stats = tmp_path / "out.png", tmp_path / "s.json"
    out.write_bytes(b"earlier image")
    stats.write_text("earlier stats")
    real = cli.write_image

    def image_then_fail(path, *a, **k):
        real(path, *a, **k)
        raise OSError(28, "No space left on device", path)

    monkeypatch.setattr(cli, "write_image", image_then_fail)
    rc, err = _render(tmp_path, capsys, "--out", str(out), "--stats", str(stats))
    assert rc == 2 and err.count("\n") == 1 and "out.png" in err and ".cube4-" not in err
    assert out.read_bytes() == b"earlier image" and stats.read_text() == "earlier stats"
    assert not _leftovers(tmp_path)


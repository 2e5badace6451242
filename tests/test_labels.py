"""Label volumes (cube4.labels, docs/numerics.md §24): the memory word, the nearest-corner
pick against its definition, the LUT's blocks, empty space by label, the golden model
against the reference, the three resampling rules of the reference, scene keys, label
maps and their errors (one line, no output written), and the build a scene gets."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from cube4.app.cli import main
from cube4.app.labelmaps import AAL_LOBES, fold_aal, load_label_map
from cube4.app.render import render, render_bricked_views
from cube4.config import scene_build
from cube4.errors import UserError
from cube4.host import config_for, golden_view, image_metrics
from cube4.labels import MAX_LABELS, check_label_map, nearest_pair, pack_words, split_words
from cube4.model import render_frame, sample_stream
from cube4.phantoms import PHANTOMS, quantise
from cube4.scene import parse_scene
from cube4.skip import busy_cells, cell_ranges
from cube4.view import make_traversal

TF = [[0.0, 0.0, 0.0, 0.0, 0.0], [0.3, 0.8, 0.8, 0.8, 0.0], [0.6, 0.9, 0.8, 0.7, 0.4], [1.0, 1.0, 1.0, 1.0, 0.6]]


def label_scene(**over) -> dict:
    """A head phantom's scene with four labels: 0 hidden, 1 red and nearly opaque, 2 the
    scene's [transfer], 3 blue and faint."""
    data = {"view": {"azimuth": -50.0, "elevation": 25.0}, "output": {"width": 64},
            "light": [{"headlight": True}], "transfer": {"points": TF},
            "label": [{"index": 0, "visible": False},
                      {"index": 1, "name": "red", "points": [[0, 1, 0.2, 0.2, 0], [0.2, 1, 0.2, 0.2, 0.9],
                                                             [1, 1, 0.2, 0.2, 0.9]]},
                      {"index": 3, "points": [[0, 0.2, 0.3, 1, 0.05], [1, 0.2, 0.3, 1, 0.05]]}]}
    data.update(over)
    return data


@pytest.fixture(scope="module")
def head_words():
    """head:32 with labels: 0 outside a ball, 1 / 2 / 3 in thirds of it along x."""
    vol = quantise(PHANTOMS["head"][0](32, 32, 32), 8)
    zz, yy, xx = np.mgrid[0:32, 0:32, 0:32]
    inside = (xx - 15.5) ** 2 + (yy - 15.5) ** 2 + (zz - 15.5) ** 2 < 14.0 ** 2
    labels = np.where(inside, 1 + np.minimum(xx // 11, 2), 0)
    return pack_words(vol, labels, 8)


def test_words_round_trip_and_map_checks():
    rng = np.random.default_rng(1)
    vol = rng.integers(0, 256, size=(4, 5, 6))
    lab = rng.integers(0, MAX_LABELS, size=(4, 5, 6))
    v, lb = split_words(pack_words(vol, lab, 8), 8)
    assert (v == vol).all() and (lb == lab).all()
    assert check_label_map(lab.astype(np.float32), (4, 5, 6)).dtype == np.uint8
    for bad, shape, msg in ((lab, (4, 5, 7), "6x5x4 voxels, the volume 7x5x4"), (lab + 16, (4, 5, 6), "holds label 31: at most 16 labels"),
                            (lab - 1, (4, 5, 6), "holds label -1"), (lab + 0.5, (4, 5, 6), "not whole numbers")):
        with pytest.raises(UserError, match=msg):
            check_label_map(bad, shape)


def test_nearest_corner_by_definition():
    """Each sample's label is that of its cell's corner nearest to it: per axis the upper
    voxel where the weight is at least one half (a tie goes up), for every phase."""
    rng = np.random.default_rng(2)
    lo, hi = rng.integers(0, 16, size=(2, 6, 7))
    wb = 8
    for wx in (0, 1, 127, 128, 129, 255):
        for wy in (0, 128, 200):
            for wz in (0, 127, 128):
                got = nearest_pair(lo, hi, (wx, wy, wz), wb)
                src = hi if wz >= 128 else lo
                want = np.array([[src[j + (wy >= 128), i + (wx >= 128)] for i in range(6)] for j in range(5)])
                assert (got == want).all(), (wx, wy, wz)


def test_sample_words_carry_value_and_label():
    """sample_stream of labelled words: the value is the unlabelled stream's, the label one
    of the cell's corners."""
    rng = np.random.default_rng(3)
    vol = rng.integers(0, 256, size=(6, 7, 8))
    lab = rng.integers(0, 16, size=vol.shape)
    trav = make_traversal((8, 7, 6), (0.7, -0.4, 1.0), 8, 2)
    words, _ = sample_stream(pack_words(vol, lab, 8), trav, label_bits=8)
    plain, _ = sample_stream(vol, trav)
    assert ((words & 255) == plain).all()
    assert (words >> 8).max() < 16


def test_lut_blocks_and_build(head_words):
    sc = parse_scene(label_scene())
    cfg = config_for(sc, 4)
    vp, frame, stats = golden_view(head_words, sc, cfg)
    lut = vp.lut
    assert lut.shape == (16 * 256, 4)
    assert not lut[0:256].any()                      # label 0 hidden
    assert (lut[2 * 256:3 * 256] == lut[5 * 256:6 * 256]).all()   # unnamed labels: the scene's [transfer]
    assert (lut[256:512, 0] == 255).all() and lut[256 + 100, 3] > lut[3 * 256 + 100, 3]
    b = scene_build([sc])
    assert b["LABELS"] == 1 and b["PLW"] == 0 and stats["build"]["LABELS"] == 1


def test_hidden_label_is_empty_space(head_words):
    """The box schedule with labels is the fixed schedule's image bit for bit, and a hidden
    label's voxels are empty space (the ball's outside: a smaller box)."""
    sc = parse_scene(label_scene())
    cfg = config_for(sc, 4)
    _, skipped, st = golden_view(head_words, sc, cfg)
    _, fixed, _ = golden_view(head_words, dataclasses.replace(sc, skip=False), cfg)
    assert (skipped.baseplane == fixed.baseplane).all()
    assert st["skip_fraction"] < 0.95
    entries = label_scene()["label"]
    shown = parse_scene(label_scene(label=[{"index": 0, "points": [[0, 1, 1, 1, 0.02], [1, 1, 1, 1, 0.02]]},
                                           *entries[1:]]))
    _, _, st_all = golden_view(head_words, shown, cfg)
    assert st["skip_fraction"] < st_all["skip_fraction"]
    lut = golden_view(head_words, sc, cfg)[0].lut
    busy = busy_cells(head_words, lut, "composite", labelled=True)
    labs = split_words(head_words, 8)[1]
    assert busy.any() and not (busy & (cell_ranges(labs)[1] == 0)).any()   # no busy cell all hidden


def test_beat_schedule_with_labels(head_words):
    """Beat skipping and ray termination with labels: the block table keeps, per label,
    the blocks that hold it, so a hidden label's blocks are empty; the image is the fixed
    schedule's bit for bit, with fewer beats than with the hidden label shown, and than a
    table of the words' ranges would need (a label's blocks test its own LUT block)."""
    from cube4.beats import BlockTable
    sc = parse_scene(label_scene(render={"skip": "beats"}))
    cfg = config_for(sc, 4)
    assert scene_build([sc])["LABELS"] and scene_build([sc])["BEATS"]
    _, beats, st = golden_view(head_words, sc, cfg)
    _, fixed, _ = golden_view(head_words, dataclasses.replace(sc, skip=False), cfg)
    assert (beats.baseplane == fixed.baseplane).all()
    entries = label_scene()["label"]
    shown = parse_scene(label_scene(render={"skip": "beats"},
                                    label=[{"index": 0, "points": [[0, 1, 1, 1, 0.02], [1, 1, 1, 1, 0.02]]},
                                           *entries[1:]]))
    _, _, st_all = golden_view(head_words, shown, cfg)
    assert st["beats"]["run_beats"] < st_all["beats"]["run_beats"], (st["beats"], st_all["beats"])
    lut = golden_view(head_words, sc, cfg)[0].lut
    by_label = BlockTable.of(head_words, 4, value_bits=8).bits(lut, "composite")
    held = BlockTable.of(head_words, 4, value_bits=8).labels
    assert set(held) == {0, 1, 2, 3} and by_label.any() and not by_label[~(held[1] | held[2] | held[3])].any()
    # a block of label 1 at 200 beside label 2 at 10: a label-1 sample between them (100)
    # counts; the words' range (1·256 + 200 .. 2·256 + 10) does not hold its word
    words = pack_words(np.full((4, 4, 4), 200), np.ones((4, 4, 4), dtype=np.int64), 8)
    words[2:] = pack_words(np.full((2, 4, 4), 10), np.full((2, 4, 4), 2), 8)
    lut1 = np.zeros((16 * 256, 4), dtype=np.int64)
    lut1[256 + 100, 3] = 1
    assert BlockTable.of(words, 4, value_bits=8).bits(lut1, "composite").all()
    assert not BlockTable.of(words, 4).bits(lut1, "composite").any()


def test_golden_near_the_reference(head_words):
    """The golden model against the point-sampled reference (the hardware's rule, nearest)
    is within 3 dB of its distance on the unlabelled scene; the labels change the picture."""
    sc = parse_scene(label_scene())
    plain = dataclasses.replace(parse_scene(label_scene()), labels=None)
    cfg = config_for(sc, 4)
    vals = split_words(head_words, 8)[0]
    g, r = render(head_words, sc, cfg, "golden").image, render(head_words, sc, cfg, "reference-point").image
    pg, pr = render(vals, plain, cfg, "golden").image, render(vals, plain, cfg, "reference-point").image
    with_l, without = image_metrics(g, r)["psnr"], image_metrics(pg, pr)["psnr"]
    print(f"golden vs reference-point: {with_l:.2f} dB with labels, {without:.2f} dB without")
    assert with_l >= without - 3.0
    assert image_metrics(r, pr)["psnr"] < 30.0


def test_reference_resampling_rules(head_words):
    """The three rules agree away from label boundaries and differ at them: masked and
    blended are the reference's alternatives, nearest the hardware's."""
    imgs = {}
    for rule in ("nearest", "masked", "blended"):
        sc = parse_scene(label_scene(labels={"resample": rule}))
        imgs[rule] = render(head_words, sc, config_for(sc, 4), "reference-point").image
    for a, b in (("nearest", "masked"), ("nearest", "blended")):
        psnr = image_metrics(imgs[a], imgs[b])["psnr"]
        assert 15.0 < psnr < 60.0, (a, b, psnr)


def test_scene_keys_and_errors(head_words):
    for bad, msg in (({"label": [{"index": 16}]}, r"integer in 0..15"),
                     ({"label": [{"index": 1}, {"index": 1}]}, "given twice"),
                     ({"label": [{"index": 1, "points": [[0, 1, 1]]}]}, r"\[value, r, g, b, a\]"),
                     ({"label": [{"index": 1, "colour": 1}]}, "unknown key"),
                     ({"labels": {"resample": "cubic"}}, "resample must be one of"),
                     ({"label": [{"index": 1}], "render": {"mode": "mip"}}, "blending modes"),
                     ({"label": [{"index": 1}], "render": {"skip": "rects"}}, "fixed, box and beat schedules"),
                     ({"label": [{"index": 1}], "render": {"path_weights": True}}, "path weights"),
                     ({"label": [{"index": 1}], "render": {"preview": 2}}, "preview level")):
        with pytest.raises(UserError, match=msg):
            parse_scene(bad)
    sc = parse_scene(label_scene())
    with pytest.raises(UserError, match="not rendered in bricks"):
        render_bricked_views(head_words, [sc], config_for(sc, 4), "golden", (2, 1, 1))


def test_aal_folding():
    aal = np.arange(117)
    lobes = fold_aal(aal)
    assert lobes[0] == 0 and lobes[1] == 1 and lobes[2] == 2 and lobes[28] == 2 and lobes[29] == 3
    assert lobes[108] == 14 and (lobes[109:] == 15).all()
    assert set(np.unique(lobes)) == set(AAL_LOBES) == set(range(16))


def _nifti(path: Path, data: np.ndarray, affine=None) -> Path:
    import nibabel as nib
    nib.save(nib.Nifti1Image(data, np.eye(4) if affine is None else affine), str(path))
    return path


def test_label_map_files_and_cli_errors(tmp_path, capsys):
    """A label map file on the volume's grid renders; a map of other dims, another
    orientation, labels beyond 15 or a built-in of another volume is one line and
    writes nothing."""
    rng = np.random.default_rng(4)
    vol = rng.integers(0, 200, size=(12, 10, 8)).astype(np.uint8)      # [x, y, z] in the file
    lab = rng.integers(0, 4, size=vol.shape).astype(np.uint8)
    vpath = _nifti(tmp_path / "v.nii.gz", vol)
    good = _nifti(tmp_path / "l.nii.gz", lab)
    assert (load_label_map(str(good), str(vpath), (8, 10, 12)) == lab.transpose(2, 1, 0)).all()
    scene = tmp_path / "s.toml"
    scene.write_text('[output]\nwidth = 32\n[[label]]\nindex = 0\nvisible = false\n'
                     '[[label]]\nindex = 2\npoints = [[0, 1, 0, 0, 0.5], [1, 1, 0, 0, 0.5]]\n')
    out = tmp_path / "o.png"
    base = ["render", str(vpath), "--scene", str(scene), "--quiet"]
    assert main(base + ["--labels", str(good), "--out", str(out)]) == 0 and out.stat().st_size > 0
    cases = ((_nifti(tmp_path / "d.nii.gz", lab[:, :, :6]), "a label map must lie on the volume's grid"),
             (_nifti(tmp_path / "o.nii.gz", lab, np.diag([2.0, 1.0, 1.0, 1.0])), "lies differently in the patient"),
             (_nifti(tmp_path / "b.nii.gz", (lab * 6).astype(np.uint8)), "holds label 18: at most 16 labels"),
             ("aal_lobes", "belongs to the built-in volume colin"))
    for n, (bad, msg) in enumerate(cases):
        dest = tmp_path / f"bad{n}.png"
        rc = main(base + ["--labels", str(bad), "--out", str(dest)])
        err = capsys.readouterr().err
        assert rc != 0 and msg in err and len(err.strip().splitlines()) == 1, err
        assert not dest.exists()
    rc = main(["render", str(vpath), "--labels", str(good), "--out", str(tmp_path / "x.png"), "--quiet"])
    assert rc != 0 and "needs a scene with [[label]] tables" in capsys.readouterr().err
    rc = main(["render", str(vpath), "--scene", str(scene), "--out", str(tmp_path / "y.png"), "--quiet"])
    assert rc != 0 and "give their map with --labels" in capsys.readouterr().err


def test_frames_of_label_blocks_match_a_single_table():
    """A label build with every block the same table is the unlabelled frame bit for bit."""
    rng = np.random.default_rng(5)
    vol = rng.integers(0, 256, size=(9, 8, 7))
    lab = rng.integers(0, 16, size=vol.shape)
    lut = rng.integers(0, 256, size=(256, 4))
    lut[:, 3] = rng.integers(0, 1 << 10, size=256)
    rmap = rng.integers(0, 1024, size=(6 * 32 * 32 + 1, 2))
    trav = make_traversal((7, 8, 9), (1.0, 1.0, 1.0), 8, 1)
    from cube4.config import Cube4Config
    cfg = Cube4Config(pipelines=4)
    a = render_frame(pack_words(vol, lab, 8), trav, cfg, np.concatenate([lut] * 16), rmap, labels=True)
    b = render_frame(vol, trav, cfg, lut, rmap)
    assert (a.baseplane == b.baseplane).all()

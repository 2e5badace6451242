"""Hostile but fair inputs, second round: each case is one clear line on stderr (exit
status 2, no traceback), the earlier output at --out untouched byte for byte, and nothing
left behind (no temporary, no backup, no folder). Among them: real full disks (a small
tmpfs mounted by the test, filled up), destinations that cannot be replaced (chattr +i,
+a), numbers beyond floating point, memory limits, cluster addresses, paths, scanner
files and numbers written the wrong way."""

from __future__ import annotations

import os
import struct
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from cube4_testutil import write_series

from cube4.app.cli import main

EARLIER = b"earlier image"
BIG = "9" * 400                    # an integer far beyond float64
LONG = "/".join(["d" * 250] * 20)  # a path longer than PATH_MAX, of names the file system accepts


def _leftovers(folder: Path) -> list[Path]:
    return [p for p in folder.rglob("*") if p.name.startswith(".cube4-")]


def _check(rc: int, err: str, out: Path, folder: Path, name_in_err: str | None = None) -> None:
    assert rc == 2, err
    assert err.startswith("cube4: error: ") and err.count("\n") == 1 and "Traceback" not in err, err
    assert ".cube4-" not in err, err
    if name_in_err is not None:
        assert name_in_err in err, err
    assert out.read_bytes() == EARLIER
    assert not _leftovers(folder)


def _render(capfd, *args: str) -> tuple[int, str]:
    """main() in this process; stderr as the terminal would see it (file descriptor 2,
    so a C library's message would count too)."""
    rc = main(["render", *args, "--quiet"])
    return rc, capfd.readouterr().err


# ------------------------------------------------------------------ cases that need only files


def _scene(tmp_path: Path, text: str) -> list[str]:
    s = tmp_path / "s.toml"
    s.write_text(text + "\n")
    return ["sphere:16", "--scene", str(s)]


SCENE_CASES = {
    # numbers beyond floating point, in every numeric key
    "huge_int_view_azimuth": f"[view]\nazimuth = {BIG}",
    "huge_int_view_elevation": f"[view]\nelevation = -{BIG}",
    "huge_int_view_direction": f"[view]\ndirection = [{BIG}, 0, 1]",
    "huge_int_view_up": f"[view]\nup = [0, 0, {BIG}]",
    "huge_int_light_intensity": f"[[light]]\ndirection = [1, 0, 0]\nintensity = {BIG}",
    "huge_int_light_direction": f"[[light]]\ndirection = [1, -{BIG}, 0]",
    "huge_int_transfer_point": f"[transfer]\npoints = [[0, 0, 0, 0, 0], [1, 1, 1, 1, {BIG}]]",
    "huge_int_cut_normal": f"[cut]\nnormal = [{BIG}, 0, 0]\npoint = [8, 8, 8]",
    "huge_int_cut_point": f"[cut]\nnormal = [1, 0, 0]\npoint = [{BIG}, 8, 8]",
    "huge_int_material_shininess": f"[material]\nshininess = {BIG}",
    "huge_int_output_width": f"[output]\nwidth = {BIG}",
    "huge_int_precision": f"[precision]\nvoxel_bits = {BIG}",
    "huge_int_crop_box": f"[crop]\nbox = [[0, 0, 0], [{BIG}, 5, 5]]",
    "cut_point_1e308": "[cut]\nnormal = [1, 0, 0]\npoint = [1e308, 8, 8]",
    # types accepted silently before
    "bool_in_direction": "[view]\ndirection = [true, 0, 1]",
    "string_in_direction": '[view]\ndirection = ["1", 0, 1]',
    "bool_in_transfer_points": "[transfer]\npoints = [[0, 0, 0, 0, 0], [1, 1, 1, 1, true]]",
    "string_in_transfer_points": '[transfer]\npoints = [[0, 0, 0, 0, 0], [1, 1, 1, "1", 1]]',
    "string_in_cut_point": '[cut]\nnormal = [1, 0, 0]\npoint = ["8", 8, 8]',
    "bool_in_light_direction": "[[light]]\ndirection = [false, true, 0]",
    "bool_as_material_number": "[material]\nambient = true",
    "duplicate_scene_key": "[view]\nazimuth = 10\nazimuth = 20",
}


@pytest.mark.parametrize("name", sorted(SCENE_CASES))
def test_scene_case(tmp_path, capfd, name):
    out = tmp_path / "out.png"
    out.write_bytes(EARLIER)
    rc, err = _render(capfd, *_scene(tmp_path, SCENE_CASES[name]), "--out", str(out))
    _check(rc, err, out, tmp_path)
    assert "scene" in err or "voxel_bits" in err


def _args_case(tmp_path: Path, name: str) -> list[str]:
    out = str(tmp_path / "out.png")
    if name == "view_angle_with_underscore":
        return ["sphere:16", "--view", "1_0,20", "--out", out]
    if name == "view_angle_beyond_float":
        return ["sphere:16", "--view", "1e400,20", "--out", out]
    if name == "pipelines_with_underscore":
        return ["sphere:16", "--pipelines", "1_0", "--out", out]
    if name == "background_with_underscore":
        return ["sphere:16", "--background", "0,0,0_5", "--out", out]
    if name == "bricks_with_underscore":
        return ["sphere:16", "--bricks", "1_0,1,1", "--out", out]
    if name == "dims_with_underscore":
        raw = tmp_path / "v.raw"
        raw.write_bytes(bytes(64))
        return [str(raw), "--dims", "4,4,4_0", "--dtype", "uint8", "--out", out]
    if name == "build_given_twice":
        return ["sphere:16", "--build", "SHADING=1", "--build", "SHADING=0", "--out", out]
    if name == "out_given_twice":
        return ["sphere:16", "--out", str(tmp_path / "other.png"), "--out", out]
    if name == "path_weights_on_and_off":
        return ["sphere:16", "--path-weights", "--no-path-weights", "--out", out]
    if name == "out_ending_in_slash":
        return ["sphere:16", "--out", out + "/"]
    if name == "out_path_too_long":
        return ["sphere:16", "--out", str(tmp_path / LONG / "o.png")]
    if name == "volume_path_too_long":
        return [str(tmp_path / LONG / "v.nrrd"), "--out", out]
    if name == "scene_path_too_long":
        return ["sphere:16", "--scene", str(tmp_path / LONG / "s.toml"), "--out", out]
    if name == "scene_endless_device":
        return ["sphere:16", "--scene", "/dev/zero", "--out", out]
    if name == "scene_larger_than_a_scene":
        s = tmp_path / "big.toml"
        s.write_text("# " + "x" * (2 << 20) + "\n")
        return ["sphere:16", "--scene", str(s), "--out", out]
    if name.startswith("scheduler_"):
        addr = {"scheduler_port_out_of_range": "tcp://127.0.0.1:70000",
                "scheduler_port_zero": "tcp://127.0.0.1:0",
                "scheduler_unsupported_protocol": "tls://127.0.0.1:8786",
                "scheduler_bad_ipv6": "tcp://[zz::1]:8786",
                "scheduler_bad_host": "tcp://a..b:8786",
                "scheduler_with_path": "tcp://host:8786/x"}[name]
        return ["sphere:16", "--bricks", "2,1,1", "--scheduler", addr, "--out", out]
    raise AssertionError(name)


ARGS_CASES = ["view_angle_with_underscore", "view_angle_beyond_float", "pipelines_with_underscore",
              "background_with_underscore", "bricks_with_underscore", "dims_with_underscore",
              "build_given_twice", "out_given_twice", "path_weights_on_and_off", "out_ending_in_slash",
              "out_path_too_long", "volume_path_too_long", "scene_path_too_long", "scene_endless_device",
              "scene_larger_than_a_scene", "scheduler_port_out_of_range", "scheduler_port_zero",
              "scheduler_unsupported_protocol", "scheduler_bad_ipv6", "scheduler_bad_host",
              "scheduler_with_path"]


@pytest.mark.parametrize("name", ARGS_CASES)
def test_command_line_case(tmp_path, capfd, name):
    out = tmp_path / "out.png"
    out.write_bytes(EARLIER)
    t0 = time.monotonic()
    rc, err = _render(capfd, *_args_case(tmp_path, name))
    _check(rc, err, out, tmp_path)
    assert time.monotonic() - t0 < 10.0      # refused, not waited for (a scheduler's timeout is 20 s)
    if name == "out_ending_in_slash":
        assert not (tmp_path / "out.png" / "").is_dir()


# ------------------------------------------------------------------ scanner files


def _dicom(folder: Path, name: str) -> Path:
    import warnings

    import pydicom

    warnings.filterwarnings("ignore", category=UserWarning, module="pydicom")   # NaN/inf written on purpose
    ct = np.random.default_rng(3).integers(0, 4096, size=(5, 8, 8)).astype(np.uint16)
    write_series(folder, ct)
    files = sorted(folder.iterdir())
    for n, f in enumerate(files):
        ds = pydicom.dcmread(f)
        if name == "dicom_nan_position" and n == 1:
            ds.ImagePositionPatient = ["0", "0", "NaN"]
        elif name == "dicom_duplicate_slice_without_position":
            del ds.ImagePositionPatient
            if n == 1:
                ds.InstanceNumber = pydicom.dcmread(files[0]).InstanceNumber
        elif name == "dicom_instance_number_not_numeric":
            del ds.ImagePositionPatient
            if n == 2:
                ds["InstanceNumber"].VR = "LO"
                ds.InstanceNumber = "third"
        elif name == "dicom_rescale_slope_huge" and n == 0:
            ds.RescaleSlope = "1e300"
        elif name == "dicom_rescale_slope_zero" and n == 0:
            ds.RescaleSlope = "0"
        elif name == "dicom_rescale_slope_infinite" and n == 0:
            ds.RescaleSlope = "inf"
        ds.save_as(f)
    return folder


def _nifti(path: Path, name: str) -> Path:
    import nibabel as nib

    nib.save(nib.Nifti1Image(np.arange(512, dtype=np.int16).reshape(8, 8, 8), np.eye(4)), str(path))
    b = bytearray(path.read_bytes())
    if name == "nifti_infinite_scale_slope":
        b[112:116] = struct.pack("<f", np.inf)      # scl_slope
    elif name == "nifti_header_claims_more_data":
        b = b[:600]
    path.write_bytes(bytes(b))
    return path


def _nrrd(path: Path, directions: str) -> Path:
    head = ("NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nspace: RAS\n"
            f"space directions: {directions}\nencoding: raw\n\n")
    path.write_bytes(head.encode() + bytes(range(64)))
    return path


SCANNER_CASES = ["dicom_nan_position", "dicom_duplicate_slice_without_position",
                 "dicom_instance_number_not_numeric", "dicom_rescale_slope_huge", "dicom_rescale_slope_zero",
                 "dicom_rescale_slope_infinite", "nifti_infinite_scale_slope", "nifti_header_claims_more_data",
                 "nrrd_zero_space_direction", "nrrd_colinear_space_directions"]


@pytest.mark.parametrize("name", SCANNER_CASES)
def test_scanner_case(tmp_path, capfd, name):
    import warnings

    if name.startswith("dicom_"):
        vol = _dicom(tmp_path / "series", name)
    elif name.startswith("nifti_"):
        vol = _nifti(tmp_path / "v.nii", name)
    else:
        dirs = "(0,0,0) (0,1,0) (0,0,1)" if "zero" in name else "(1,0,0) (2,0,0) (0,0,1)"
        vol = _nrrd(tmp_path / "v.nrrd", dirs)
    out = tmp_path / "out.png"
    out.write_bytes(EARLIER)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)    # no warning before the error
        rc, err = _render(capfd, str(vol), "--out", str(out))
    _check(rc, err, out, tmp_path)
    word = {"dicom_nan_position": "ImagePositionPatient", "dicom_duplicate_slice_without_position": "InstanceNumber",
            "dicom_instance_number_not_numeric": "InstanceNumber", "nifti_infinite_scale_slope": "slope",
            "nifti_header_claims_more_data": "truncated", "nrrd_zero_space_direction": "space directions",
            "nrrd_colinear_space_directions": "space directions"}.get(name, "RescaleSlope")
    assert word in err, err


# ------------------------------------------------------------------ memory limits


def _render_under_an_address_space_limit(tmp_path, volume: str) -> None:
    """`cube4 render volume` in a process whose address space is capped 1 GiB above what it
    uses: one line naming the limit, exit 2, the earlier image untouched."""
    out = tmp_path / "out.png"
    out.write_bytes(EARLIER)
    code = ("import resource, sys\n"
            "from cube4.phantoms import _status_bytes\n"
            "cap = _status_bytes('VmSize') + (1 << 30)\n"
            "resource.setrlimit(resource.RLIMIT_AS, (cap, cap))\n"
            "from cube4.app.cli import main\n"
            f"sys.exit(main(['render', {volume!r}, '--quiet', '--out', {str(out)!r}]))\n")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                       env={**os.environ, "OPENBLAS_NUM_THREADS": "1"})
    _check(p.returncode, p.stderr, out, tmp_path, "address-space limit")


def test_builtin_under_an_address_space_limit(tmp_path):
    """Under ulimit -v the size check compares with what the limit leaves, not with the
    machine's memory: one line, before the volume is generated."""
    _render_under_an_address_space_limit(tmp_path, "sphere:512")


def test_volume_file_under_an_address_space_limit(tmp_path):
    """A 512^3 raw file (sparse: no disk used) under ulimit -v: refused before it is read."""
    raw = tmp_path / "ct_512x512x512_u16.raw"
    with open(raw, "wb") as f:
        f.truncate(2 * 512**3)
    _render_under_an_address_space_limit(tmp_path, str(raw))


# ------------------------------------------------------------------ full disks and stuck files


@pytest.fixture
def small_disk(tmp_path):
    """A 512 KiB tmpfs mounted in tmp_path (root only), unmounted afterwards."""
    mnt = tmp_path / "disk"
    mnt.mkdir()
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=512k", "tmpfs", str(mnt)], capture_output=True, text=True)
    if r.returncode != 0:
        pytest.skip(f"cannot mount a small tmpfs here ({r.stderr.strip() or 'mount refused'})")
    try:
        yield mnt
    finally:
        subprocess.run(["umount", "-l", str(mnt)], check=False)


def _fill(disk: Path, leave: int) -> None:
    """Fill the disk until `leave` bytes are free."""
    v = os.statvfs(disk)
    free = v.f_bavail * v.f_frsize
    (disk / "filler").write_bytes(bytes(max(0, free - leave)))


@pytest.mark.parametrize("suffix", [".png", ".tif", ".exr"])
def test_full_disk_keeps_the_earlier_image(small_disk, capfd, suffix):
    """A disk with one page free: the image cannot be written whole. Exit 2, one line
    naming the user's path, the earlier image byte for byte, no temporary."""
    out = small_disk / f"out{suffix}"
    out.write_bytes(EARLIER)
    _fill(small_disk, 4096)
    rc, err = _render(capfd, "sphere:32", "--out", str(out))
    _check(rc, err, out, small_disk, str(out))


def test_full_disk_with_several_outputs(small_disk, capfd):
    """The image fits, the base plane does not: neither replaces its earlier file."""
    out, bp = small_disk / "out.png", small_disk / "bp.npy"
    out.write_bytes(EARLIER)
    bp.write_bytes(b"earlier base plane")
    _fill(small_disk, 48 * 1024)
    rc, err = _render(capfd, "sphere:32", "--out", str(out), "--baseplane", str(bp))
    _check(rc, err, out, small_disk)
    assert bp.read_bytes() == b"earlier base plane"


def test_render_that_fits_is_whole(small_disk, capfd):
    """With room the same render succeeds and the image reads back."""
    import OpenImageIO as oiio

    out = small_disk / "out.png"
    out.write_bytes(EARLIER)
    rc, err = _render(capfd, "sphere:32", "--out", str(out))
    assert rc == 0, err
    assert oiio.ImageBuf(str(out)).spec().width == 256 and not _leftovers(small_disk)


@pytest.fixture
def chattr(tmp_path):
    """chattr on tmp_path's file system (root, ext4 or tmpfs); attributes cleared afterwards."""
    probe = tmp_path / "probe"
    probe.write_bytes(b"")
    if subprocess.run(["chattr", "+i", str(probe)], capture_output=True).returncode != 0:
        pytest.skip("chattr +i is not available here (not root, or the file system has no attributes)")
    subprocess.run(["chattr", "-i", str(probe)], check=True)
    probe.unlink()
    marked: list[Path] = []

    def mark(path: Path, flag: str) -> None:
        subprocess.run(["chattr", f"+{flag}", str(path)], check=True)
        marked.append(path)

    yield mark
    for p in marked:
        subprocess.run(["chattr", "-i", "-a", str(p)], check=False)


@pytest.mark.parametrize("name", ["immutable_earlier_output", "append_only_earlier_output",
                                  "immutable_folder", "append_only_folder"])
def test_stuck_destination(tmp_path, capfd, chattr, name):
    folder = tmp_path / "o"
    folder.mkdir()
    out = folder / "out.png"
    out.write_bytes(EARLIER)
    kind = "i" if "immutable" in name else "a"
    chattr(out if "output" in name else folder, kind)
    rc, err = _render(capfd, "sphere:16", "--out", str(out))
    _check(rc, err, out, tmp_path, "immutable" if kind == "i" else "append-only")


def test_write_all_leaves_no_backup_when_the_earlier_file_is_stuck(tmp_path, chattr):
    """Past the checks (a file made immutable during the render): the move fails, the
    error names the user's path, and neither the temporary nor an empty backup stays."""
    from cube4.app.outputs import write_all
    from cube4.errors import UserError

    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_text("old a")
    b.write_text("old b")
    chattr(b, "i")
    with pytest.raises(UserError, match=r"cannot write '.*b\.txt'"):
        write_all([(a, lambda t: Path(t).write_text("new a")), (b, lambda t: Path(t).write_text("new b"))])
    assert a.read_text() == "old a" and b.read_text() == "old b" and not _leftovers(tmp_path)


def test_sticky_folder_of_another_user(tmp_path, capfd, monkeypatch):
    """Another user's earlier file in a sticky folder cannot be replaced: refused before
    any work (as root the kernel would allow it, so the test runs as user 4242)."""
    folder = tmp_path / "shared"
    folder.mkdir()
    os.chmod(folder, 0o1777)
    out = folder / "out.png"
    out.write_bytes(EARLIER)
    monkeypatch.setattr(os, "geteuid", lambda: 4242)
    rc, err = _render(capfd, "sphere:16", "--out", str(out))
    _check(rc, err, out, tmp_path, "sticky")


def test_full_disk_for_the_stats_after_the_image(small_disk, capfd):
    """One page free: the small image takes it, the stats file finds the disk full. The
    image written first is not kept either."""
    out, stats = small_disk / "out.png", small_disk / "st.json"
    out.write_bytes(EARLIER)
    stats.write_text("earlier stats")
    scene = small_disk.parent / "s.toml"
    scene.write_text("[output]\nwidth = 8\n")
    _fill(small_disk, 4096)
    rc, err = _render(capfd, "sphere:4", "--scene", str(scene), "--out", str(out), "--stats", str(stats))
    _check(rc, err, out, small_disk, "st.json")
    assert stats.read_text() == "earlier stats"


def test_interrupt_while_writing(tmp_path, capfd, monkeypatch):
    """Ctrl-C while the outputs are written: exit 130, one line, the earlier image back,
    nothing left behind."""
    from cube4.app import cli

    out = tmp_path / "out.png"
    out.write_bytes(EARLIER)

    def interrupted(path, *a, **k):
        Path(path).write_bytes(b"half an image")
        raise KeyboardInterrupt

    monkeypatch.setattr(cli, "write_image", interrupted)
    rc = main(["render", "sphere:8", "--quiet", "--out", str(out)])
    err = capfd.readouterr().err
    assert rc == 130 and err == "cube4: interrupted\n", err
    assert out.read_bytes() == EARLIER and not _leftovers(tmp_path)

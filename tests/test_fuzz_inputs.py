"""Fuzzing the command line: Hypothesis generates hostile scene files (every key of the
scene schema, values of every type and size, duplicated keys, broken TOML), command lines
(every option of ``cube4 render``, repeated, with numbers written every way) and volume
files (NRRD headers, NIfTI headers with any field overwritten, raw files of any size).

Every generated case must end in one of two ways:

* exit status 0, nothing on stderr, and every output complete (the image reads back);
* exit status 2, exactly one ``cube4: error:`` line on stderr and nothing on stdout, the
  earlier output untouched byte for byte;

never a traceback or a warning, and never a temporary (``.cube4-*``) or a new folder left behind.

Six kinds: scenes alone (on a small built-in), scenes with command lines, NRRD, NIfTI,
raw files and DICOM series (slice attributes changed or deleted). ``make test`` runs
FUZZ_EXAMPLES (60) cases per kind, derandomized (about 15 s); ``make regress`` runs the
long fuzz (FUZZ_LONG_EXAMPLES per kind, 2000 by default: 12,000 in all, seeded).
CUBE4_FUZZ_EXAMPLES overrides both counts.

Clusters are not started: a case that would start a Dask cluster or reach a scheduler
gets one line from a stand-in (the addresses themselves are checked before that).
"""

from __future__ import annotations

import json
import math
import os
import struct
import tempfile
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, seed, settings
from hypothesis import strategies as st

from cube4.app import cli, cluster
from cube4.errors import UserError

FUZZ_EXAMPLES = int(os.environ.get("CUBE4_FUZZ_EXAMPLES", "60"))
FUZZ_LONG_EXAMPLES = int(os.environ.get("CUBE4_FUZZ_EXAMPLES", "2000"))
EARLIER = b"earlier output"
COUNT = {"cases": 0, "ok": 0, "refused": 0}

# ------------------------------------------------------------------ values

HUGE = [10**400, -(10**400), 2**63, -(2**63) - 1, 2**64, 10**20]
hostile_scalar = st.one_of(
    st.integers(), st.sampled_from(HUGE), st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([1e308, -1e308, 5e-324, 0.0, -0.0]), st.booleans(), st.text(max_size=6),
    st.sampled_from(["1", "1_0", "nan", "", "0x10"]), st.just([]), st.just({}),
)


def number(lo: float, hi: float):
    """Mostly a valid number of the key's range, sometimes anything."""
    valid = st.one_of(st.floats(lo, hi), st.integers(int(math.ceil(lo)), int(math.floor(hi))))
    return st.one_of(valid, valid, valid, hostile_scalar)


def whole(lo: int, hi: int):
    return st.one_of(st.integers(lo, hi), st.integers(lo, hi), hostile_scalar)


def vec(lo: float = -1.0, hi: float = 1.0):
    return st.one_of(st.lists(number(lo, hi), min_size=3, max_size=3), st.lists(number(lo, hi), max_size=5),
                     hostile_scalar)


def optional_keys(d: dict):
    """A table holding any subset of the keys."""
    return st.fixed_dictionaries({}, optional=d)


def choice(valid, extra=()):
    return st.one_of(st.sampled_from(list(valid) + list(extra)), hostile_scalar)


SCENE_SCHEMA = {
    "view": optional_keys({"direction": vec(), "azimuth": number(-360, 360), "elevation": number(-90, 90),
                           "up": vec()}),
    "output": optional_keys({"width": whole(8, 24), "height": whole(8, 24),
                             "filter": choice(["triangle", "box", "lanczos3"], ["nope"]),
                             "footprint": choice([True, False])}),
    "render": optional_keys({"mode": choice(["composite", "xray", "mip", "minip"], ["max"]),
                             "supersample": choice([1, 2, 4, 8], [3]), "skip": choice([True, False, "rects"]),
                             "subpixel": whole(1, 4), "gradient": choice(["gra", "central", "sobel"]),
                             "path_weights": choice([True, False])}),
    "material": optional_keys({"ambient": number(0, 4), "diffuse": number(0, 4), "specular": number(0, 4),
                               "shininess": number(0, 1000), "shading": choice([True, False])}),
    "light": st.lists(optional_keys({"direction": vec(), "intensity": number(0, 100),
                                     "headlight": choice([True, False])}), max_size=3),
    "transfer": optional_keys({"points": st.one_of(
        st.lists(st.lists(number(0, 1), min_size=5, max_size=5), min_size=1, max_size=4), hostile_scalar)}),
    "precision": optional_keys({k: whole(lo, hi) for k, lo, hi in (
        ("voxel_bits", 4, 16), ("weight_bits", 4, 12), ("alpha_bits", 8, 16), ("acc_bits", 8, 24),
        ("rmap_bits", 2, 6))}),
    "crop": optional_keys({"box": st.one_of(st.lists(st.lists(whole(0, 9), min_size=3, max_size=3),
                                                     min_size=2, max_size=2), hostile_scalar)}),
    "cut": optional_keys({"normal": vec(), "point": vec(-20, 20)}),
    "extra": st.one_of(hostile_scalar, st.just(1)),
}
scene_tables = st.fixed_dictionaries({}, optional=SCENE_SCHEMA)


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k} = {_toml_value(x)}" for k, x in v.items()) + "}"
    raise AssertionError(v)


def toml_text(tables: dict) -> str:
    """A scene dict as TOML: [section] tables, [[light]] arrays, other values at the top."""
    top, body = [], []
    for name, val in tables.items():
        if isinstance(val, dict):
            body.append(f"[{name}]")
            body += [f"{k} = {_toml_value(x)}" for k, x in val.items()]
        elif name == "light" and isinstance(val, list) and all(isinstance(x, dict) for x in val):
            for lt in val:
                body.append("[[light]]")
                body += [f"{k} = {_toml_value(x)}" for k, x in lt.items()]
        else:
            top.append(f"{name} = {_toml_value(val)}")
    return "\n".join(top + body) + "\n"


@st.composite
def scene_files(draw) -> str:
    """TOML text over the scene schema, sometimes with a line repeated or broken."""
    text = toml_text(draw(scene_tables))
    lines = text.splitlines()
    how = draw(st.sampled_from(["as is"] * 6 + ["repeat a line", "cut short", "garbage"]))
    if how == "repeat a line" and lines:
        i = draw(st.integers(0, len(lines) - 1))
        lines.insert(i + 1, lines[i])
    elif how == "cut short" and text:
        return text[: draw(st.integers(0, len(text)))]
    elif how == "garbage":
        lines.append(draw(st.text(max_size=20)))
    return "\n".join(lines) + "\n"


# ------------------------------------------------------------------ command lines


def num_text(valid):
    """A number as command-line text: valid, or written the wrong way."""
    return st.one_of(valid.map(str), valid.map(str), st.sampled_from(["1_0", " 1", "1.5", "-1", "0", "nan", "inf", "1e400",
                                                      "9" * 60, "", "0x8", "+3", "１"]), st.text(max_size=6))


def triple_text(lo: int, hi: int):
    return st.one_of(st.tuples(st.integers(lo, hi), st.integers(lo, hi), st.integers(lo, hi))
                     .map(lambda t: ",".join(map(str, t))), num_text(st.integers(lo, hi)))


OPTIONS = {
    "--pipelines": num_text(st.integers(1, 8)),
    "--voxel-bits": num_text(st.integers(4, 16)),
    "--view": st.one_of(st.tuples(st.floats(-360, 360), st.floats(-90, 90)).map(lambda t: f"{t[0]},{t[1]}"),
                        num_text(st.integers(-90, 90)), st.just("1_0,5"), st.just("1e400,0")),
    "--orbit": num_text(st.integers(1, 3)),
    "--background": st.one_of(st.tuples(st.floats(0, 1), st.floats(0, 1), st.floats(0, 1))
                              .map(lambda t: ",".join(map(str, t))), num_text(st.floats(0, 1))),
    "--bricks": triple_text(1, 2),
    "--board-dim": num_text(st.integers(4, 12)),
    "--workers": num_text(st.integers(1, 2)),
    "--scheduler": st.one_of(st.sampled_from(["tcp://127.0.0.1:70000", "tcp://[zz]:1", "tls://h:1", "tcp://h:0",
                                              "tcp://a..b:1", "inproc://x", "tcp://h:1/x", "tcp://" + "a" * 300]),
                             st.text(max_size=20), st.text(max_size=12).map(lambda s: "tcp://" + s)),
    "--build": st.one_of(st.sampled_from(["scene", "full", "SHADING=0", "CLIP=1,CLIP=0", "shading=1", "VGRAD=2"]),
                         st.text(max_size=12)),
    "--gradient": st.sampled_from(["gra", "central", "sobel", "x"]),
    "--preset": st.sampled_from(["default", "quality", "fast"]),
    "--engine": st.sampled_from(["golden", "reference", "nope"]),
    "--compare-to": st.sampled_from(["reference", "golden"]),
    "--dims": triple_text(2, 6),
    "--dtype": st.sampled_from(["uint8", "u16", "f32", "float64", "f16", "int64"]),
}
FLAGS = ["--no-skip", "--rects", "--path-weights", "--no-path-weights", "--quiet"]


@st.composite
def option_lists(draw) -> list[str]:
    """A few options, any of them possibly repeated."""
    args: list[str] = []
    for _ in range(draw(st.sampled_from([0, 0, 1, 1, 2, 4]))):
        if draw(st.integers(0, 4)) == 0:
            args.append(draw(st.sampled_from(FLAGS)))
        else:
            name = draw(st.sampled_from(sorted(OPTIONS)))
            value = draw(OPTIONS[name])
            args += [f"{name}={value}"] if value.startswith("-") else [name, value]
    return args


OUT_NAMES = ["out.png", "out.tif", "out.exr", "sub/dir/out.png", "out.png/", "out.jpg", "f{n}.png", "OUT.PNG",
             "n" * 300 + ".png", "out", ".png"]
VOLUMES = st.one_of(st.integers(2, 10).map(lambda n: f"sphere:{n}"),
                    st.sampled_from(["cube:6", "ml:6", "noise:5,6,7", "sphere:0", "sphere:1_0", "sphere:5000",
                                     "sphere:" + "9" * 30, "nope", "", "sphere", "mri_t1:6"]),
                    st.text(max_size=10))


# ------------------------------------------------------------------ volume files


NRRD_TYPES = {"uint8": 1, "int16": 2, "uint16": 2, "float": 4, "double": 8, "int32": 4}


@st.composite
def nrrd_files(draw) -> bytes:
    """An NRRD file: a consistent header and payload, then up to three fields (or the
    payload's length) made wrong."""
    kind = draw(st.sampled_from(sorted(NRRD_TYPES)))
    sizes = draw(st.lists(st.integers(2, 6), min_size=3, max_size=3))
    fields = {"type": kind, "dimension": "3", "sizes": " ".join(map(str, sizes)), "encoding": "raw",
              "endian": "little"}
    if draw(st.booleans()):
        fields["space"] = draw(st.sampled_from(["RAS", "LPS", "left-anterior-superior", "scanner-xyz"]))
        fields["space directions"] = "(1,0,0) (0,1,0) (0,0,1)"
    n = int(np.prod(sizes)) * NRRD_TYPES[kind]
    payload = bytes(range(256)) * (n // 256) + bytes(range(n % 256))
    for _ in range(draw(st.integers(0, 3))):
        key = draw(st.sampled_from(["type", "dimension", "sizes", "encoding", "endian", "space",
                                    "space directions", "byte skip", "line skip", "spacings", "kinds", "data file",
                                    "payload"]))
        if key == "payload":
            payload = payload[: draw(st.integers(0, len(payload)))] + draw(st.binary(max_size=40))
        elif key == "space directions":
            fields["space"] = fields.get("space", "RAS")
            vecs = draw(st.lists(st.one_of(
                st.tuples(number(-2, 2), number(-2, 2), number(-2, 2)).map(
                    lambda t: "(" + ",".join(v if isinstance(v, str) else _toml_value(v) for v in t) + ")"),
                st.sampled_from(["none", "(0,0,0)", "(nan,0,1)", "(1e308,1e308,0)", "()", "(1,0,0)"])),
                min_size=0, max_size=4))
            fields[key] = " ".join(vecs)
        else:
            fields[key] = draw(st.one_of(
                st.sampled_from(["-1", "0", "1", "3", "1e30", "x", "LIST", "1 1 1", "4 4", "gzip", "ascii", "hex",
                                 "bzip2", "big", "block", "quaternion", "uint8", "9" * 40, ""]),
                st.text(max_size=8).filter(lambda t: "\n" not in t and "\r" not in t)))
    head = "NRRD0004\n" + "".join(f"{k}: {v}\n" for k, v in fields.items()) + "\n"
    return head.encode("utf-8", "surrogatepass") + payload


# NIfTI-1 header fields a corrupt file may get wrong: (offset, struct format)
NIFTI_FIELDS = [(40, "<8h"), (70, "<h"), (72, "<h"), (76, "<8f"), (108, "<f"), (112, "<f"), (116, "<f"),
                (252, "<h"), (254, "<h"), (256, "<6f"), (280, "<12f"), (0, "<i"), (344, "4s")]


@st.composite
def nifti_files(draw) -> bytes:
    import io

    import nibabel as nib

    shape = draw(st.tuples(st.integers(2, 5), st.integers(2, 5), st.integers(2, 5)))
    dtype = draw(st.sampled_from([np.uint8, np.int16, np.float32, np.float64]))
    img = nib.Nifti1Image(np.arange(np.prod(shape)).reshape(shape).astype(dtype), np.eye(4))
    bio = io.BytesIO()
    img.to_file_map({"image": nib.FileHolder(fileobj=bio), "header": nib.FileHolder(fileobj=bio)})
    b = bytearray(bio.getvalue())
    for _ in range(draw(st.integers(0, 3))):
        off, fmt = draw(st.sampled_from(NIFTI_FIELDS))
        n = struct.calcsize(fmt)
        if fmt.endswith("h"):
            vals = draw(st.lists(st.integers(-(2**15), 2**15 - 1), min_size=n // 2, max_size=n // 2))
            b[off:off + n] = struct.pack(fmt, *vals)
        elif fmt.endswith("f"):
            vals = draw(st.lists(st.floats(width=32, allow_nan=True, allow_infinity=True), min_size=n // 4,
                                 max_size=n // 4))
            b[off:off + n] = struct.pack(fmt, *vals)
        elif fmt == "<i":
            b[off:off + n] = struct.pack(fmt, draw(st.sampled_from([348, 540, 0, -1])))
        else:
            b[off:off + n] = draw(st.sampled_from([b"n+1\0", b"ni1\0", b"xxxx", b"n+2\0"]))
    if draw(st.booleans()):
        b = b[: draw(st.integers(0, len(b)))]
    return bytes(b)


@st.composite
def raw_files(draw) -> tuple[bytes, list[str]]:
    dims = draw(triple_text(2, 6))
    dtype = draw(st.sampled_from(["uint8", "u16", "f32", "float64", "int16", "f16"]))
    size = draw(st.one_of(st.integers(0, 2000), st.just(-1)))
    if size < 0:       # the right size for dims and type, where they parse
        try:
            n = np.prod([int(p) for p in dims.split(",")]) * np.dtype(
                {"u16": "uint16", "f32": "float32"}.get(dtype, dtype)).itemsize
            size = int(min(max(n, 0), 5000))
        except (ValueError, TypeError):
            size = 64
    data = draw(st.binary(min_size=size, max_size=size)) if size <= 64 else os.urandom(size)
    return data, ["--dims", dims, "--dtype", dtype]


DICOM_ATTRS = ["ImagePositionPatient", "ImageOrientationPatient", "InstanceNumber", "RescaleSlope",
               "RescaleIntercept", "Rows", "Columns", "BitsAllocated", "PixelRepresentation", "SeriesInstanceUID",
               "PixelData", "SamplesPerPixel"]


def _dicom_value(draw, attr: str):
    if attr in ("ImagePositionPatient", "ImageOrientationPatient"):
        n = 3 if attr == "ImagePositionPatient" else 6
        return [draw(st.sampled_from(["0", "1", "-1", "NaN", "inf", "1e308", "x", "0.5"])) for _ in range(n)] \
            if draw(st.booleans()) else draw(st.sampled_from([None, ["1", "0"], []]))
    if attr in ("InstanceNumber", "RescaleSlope", "RescaleIntercept"):
        return draw(st.sampled_from([None, "0", "1", "-3", "1e300", "inf", "NaN", "third", "", "2.5"]))
    if attr in ("Rows", "Columns", "BitsAllocated", "PixelRepresentation", "SamplesPerPixel"):
        return draw(st.sampled_from([None, 0, 1, 3, 4, 8, 16, 32, 65535]))
    if attr == "SeriesInstanceUID":
        return draw(st.sampled_from([None, "1.2.3", "1.2.4"]))
    return draw(st.sampled_from([None, b"", b"\0" * 7, b"\1" * 32, b"\2" * 64]))


@st.composite
def dicom_series(draw) -> list[tuple[int, str, object]]:
    """Changes to a 3-slice series: (slice, attribute, new value or None to delete)."""
    return [(draw(st.integers(0, 2)), attr, _dicom_value(draw, attr))
            for attr in draw(st.lists(st.sampled_from(DICOM_ATTRS), max_size=3))]


def _write_dicom(folder: Path, changes) -> None:
    import warnings

    import pydicom
    from cube4_testutil import write_series

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        write_series(folder, np.arange(3 * 4 * 4, dtype=np.uint16).reshape(3, 4, 4) * 50)
        files = sorted(folder.iterdir())
        for n, attr, value in changes:
            ds = pydicom.dcmread(files[n])
            try:
                if value is None:
                    if attr in ds:
                        delattr(ds, attr)
                else:
                    if attr == "InstanceNumber":
                        ds["InstanceNumber"].VR = "LO"
                    setattr(ds, attr, value)
                ds.save_as(files[n])
            except Exception:      # a value pydicom will not write: the change is skipped
                pass


# ------------------------------------------------------------------ the property


class _NoCluster:
    """Stand-in for the Dask executor: fuzzing starts no cluster."""

    def __init__(self, *a, **k):
        pass

    def __enter__(self):
        raise UserError("cluster not started in the fuzz run")

    def __exit__(self, *exc):
        return False


@pytest.fixture(autouse=True)
def _no_cluster(monkeypatch):
    monkeypatch.setattr(cluster, "DaskExecutor", _NoCluster)


def _run_case(capfd, volume: str | None, files: dict[str, bytes], args: list[str], out_name: str,
              scene: str | None, dicom=None) -> None:
    """Run one generated case in a fresh folder and check the outcome (module docstring)."""
    import OpenImageIO as oiio

    capfd.readouterr()
    with tempfile.TemporaryDirectory(prefix="fuzz") as d:
        root = Path(d)
        for name, data in files.items():
            (root / name).write_bytes(data)
        if dicom is not None:
            _write_dicom(root / "series", dicom)
            volume = str(root / "series")
        earlier = root / "out.png"
        earlier.write_bytes(EARLIER)
        argv = ["render", volume if volume is not None else str(root / next(iter(files)))]
        if scene is not None:
            (root / "s.toml").write_text(scene, encoding="utf-8", errors="surrogatepass")
            argv += ["--scene", str(root / "s.toml")]
        argv += ["--out", str(root / out_name), *args]
        before = {p for p in root.rglob("*")}
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")        # a warning would be a second line on the terminal
            rc = cli.main(argv)
        out, err = capfd.readouterr()
        COUNT["cases"] += 1
        assert "Traceback" not in err, (argv, err)
        assert not caught, (argv, [str(w.message) for w in caught])
        left = [p for p in root.rglob("*") if p.name.startswith(".cube4-")]
        assert not left, (argv, left)
        if rc == 0:
            COUNT["ok"] += 1
            assert err == "", (argv, err)
            for p in set(root.rglob("*")) - before:
                if p.suffix.lower() in (".png", ".tif", ".tiff", ".exr"):
                    buf = oiio.ImageBuf(str(p))
                    assert buf.spec().width >= 8 and not buf.has_error, (argv, p)
        else:
            COUNT["refused"] += 1
            assert rc == 2, (argv, rc, err)
            assert err.startswith("cube4: error: ") and err.count("\n") == 1, (argv, err)
            assert out == "", (argv, out)
            assert earlier.read_bytes() == EARLIER, argv
            assert {p for p in root.rglob("*")} == before, argv   # no new file or folder


def _settings(n: int):
    return settings(max_examples=n, deadline=None, derandomize=n <= FUZZ_EXAMPLES,
                    suppress_health_check=list(HealthCheck), database=None)


def _fuzz(n: int):
    """The three fuzz properties with n examples each."""

    @_settings(n)
    @given(scene=scene_files(), args=option_lists(), volume=VOLUMES, out_name=st.sampled_from(OUT_NAMES))
    def scenes_and_options(capfd, scene, args, volume, out_name):
        _run_case(capfd, volume, {}, args, out_name, scene)

    @_settings(n)
    @given(scene=scene_files(), n_vox=st.integers(3, 10), out_name=st.sampled_from(OUT_NAMES[:3]),
           engine=st.sampled_from(["golden", "reference"]))
    def scenes(capfd, scene, n_vox, out_name, engine):
        """The scene alone hostile: a small built-in, a good output name, no other option."""
        _run_case(capfd, f"sphere:{n_vox}", {}, ["--engine", engine], out_name, scene)

    @_settings(n)
    @given(data=nrrd_files(), args=option_lists())
    def nrrd(capfd, data, args):
        _run_case(capfd, None, {"v.nrrd": data}, args, "out.png", None)

    @_settings(n)
    @given(data=nifti_files(), args=option_lists(), gz=st.booleans())
    def nifti(capfd, data, args, gz):
        import gzip

        name = "v.nii.gz" if gz else "v.nii"
        _run_case(capfd, None, {name: gzip.compress(data) if gz else data}, args, "out.png", None)

    @_settings(n)
    @given(raw=raw_files(), args=option_lists())
    def raw(capfd, raw, args):
        data, extra = raw
        _run_case(capfd, None, {"v.raw": data}, [*extra, *args], "out.png", None)

    @_settings(n)
    @given(changes=dicom_series(), args=option_lists())
    def dicom(capfd, changes, args):
        _run_case(capfd, None, {}, args, "out.png", None, dicom=changes)

    return {"scenes": scenes, "scenes_and_options": scenes_and_options, "nrrd": nrrd, "nifti": nifti, "raw": raw, "dicom": dicom}


KINDS = ["scenes", "scenes_and_options", "nrrd", "nifti", "raw", "dicom"]


@pytest.mark.parametrize("kind", KINDS)
def test_fuzz(capfd, kind):
    """make test: FUZZ_EXAMPLES derandomized cases of each kind."""
    COUNT.update(cases=0, ok=0, refused=0)
    _fuzz(FUZZ_EXAMPLES)[kind](capfd)
    assert COUNT["cases"] >= FUZZ_EXAMPLES
    with capfd.disabled():
        print(f"\nfuzz {kind}: {COUNT['cases']} cases ({COUNT['ok']} rendered, {COUNT['refused']} refused)")


@pytest.mark.regress
@pytest.mark.parametrize("kind", KINDS)
def test_fuzz_long(capfd, kind):
    """make regress: FUZZ_LONG_EXAMPLES seeded cases of each kind (more than 10,000 in all)."""
    import time

    COUNT.update(cases=0, ok=0, refused=0)
    t0 = time.monotonic()
    seed(52)(_fuzz(FUZZ_LONG_EXAMPLES)[kind])(capfd)
    with capfd.disabled():
        print(f"\nfuzz {kind}: {COUNT['cases']} cases ({COUNT['ok']} rendered, {COUNT['refused']} refused) "
              f"in {time.monotonic() - t0:.0f} s")

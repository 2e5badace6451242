"""Property-based tests (Hypothesis) of the one-line contract: whatever a user gives as
a scene file, a raw volume's name and header options, or a command line, the command
either succeeds or fails with exactly one `cube4: error:` line and exit status 2 (no
traceback, no other exception), and a failed run leaves the earlier output untouched.
(Their first run found one: `--dims -1,0,0`, which argparse printed as its usage text.)"""

from __future__ import annotations


from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cube4.app.cli import main
from cube4.errors import UserError
from cube4.scene import parse_scene

SETTINGS = settings(max_examples=60, deadline=None,
                    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])

# ---------------------------------------------------------------- scene files
NUMBERS = st.one_of(st.integers(-10**6, 10**6), st.floats(allow_nan=True, allow_infinity=True),
                    st.sampled_from([0, 1, -1, 0.5, 1e308, -1e308, 5e-324]))
VALUES = st.recursive(
    st.one_of(NUMBERS, st.booleans(), st.text(max_size=8), st.sampled_from(["composite", "mip", "phong", "x"])),
    lambda inner: st.one_of(st.lists(inner, max_size=4), st.dictionaries(st.text(max_size=6), inner, max_size=3)),
    max_leaves=8)
SECTIONS = st.sampled_from(["view", "output", "render", "material", "light", "transfer", "precision", "bogus"])
KEYS = st.sampled_from(["direction", "azimuth", "elevation", "up", "width", "height", "mode", "supersample",
                        "ambient", "diffuse", "specular", "shininess", "lights", "points", "opacity",
                        "weight_bits", "acc_bits", "voxel_bits", "pipelines", "colormap", "x"])
SCENES = st.dictionaries(SECTIONS, st.dictionaries(KEYS, VALUES, max_size=4), max_size=4)


@SETTINGS
@given(SCENES)
def test_any_scene_table_parses_or_is_a_user_error(data):
    try:
        parse_scene(data)
    except UserError as e:
        assert "\n" not in str(e)


@SETTINGS
@given(st.binary(max_size=200))
def test_any_scene_file_bytes_are_one_line(tmp_path, capsys, raw):
    scene = tmp_path / "s.toml"
    scene.write_bytes(raw)
    out = tmp_path / "o.png"
    rc = main(["render", "sphere:8", "--scene", str(scene), "--quiet", "--out", str(out)])
    err = capsys.readouterr().err
    if rc != 0:
        assert rc == 2 and err.startswith("cube4: error: ") and err.count("\n") == 1, err


# ---------------------------------------------------------------- raw volumes
DTYPES = st.sampled_from(["uint8", "uint16", "int16", "uint32", "int32", "float32", "float64", "u8", "f4", "x", ""])
DIMS = st.tuples(st.integers(-2, 9), st.integers(-2, 9), st.integers(-2, 9))


@SETTINGS
@given(DIMS, DTYPES, DIMS, st.booleans(), st.integers(0, 5000))
def test_raw_names_and_headers_are_one_line(tmp_path, capsys, name_dims, dtype, opt_dims, use_opts, size):
    nx, ny, nz = name_dims
    f = tmp_path / f"vol_{nx}x{ny}x{nz}_{dtype}.raw"
    f.write_bytes(bytes(size))
    args = ["render", str(f), "--quiet", "--out", str(tmp_path / "o.png")]
    if use_opts:
        args += ["--dims", ",".join(str(d) for d in opt_dims), "--dtype", dtype or "uint8"]
    rc = main(args)
    err = capsys.readouterr().err
    assert rc in (0, 2)
    if rc:
        assert err.startswith("cube4: error: ") and err.count("\n") == 1, err


# ---------------------------------------------------------------- command lines
def _option(name: str, values):
    return st.tuples(st.just(name), values).map(list)


OPTIONS = st.lists(st.one_of(
    _option("--pipelines", st.sampled_from(["1", "5", "0", "65", "-3", "x", "99999999999999999999"])),
    _option("--voxel-bits", st.sampled_from(["8", "12", "3", "17", "nan"])),
    _option("--view", st.sampled_from(["10,20", "0,90", "1e308,0", "nan,0", "10", "a,b", "30,-91", ""])),
    _option("--orbit", st.sampled_from(["2", "0", "-1", "1000000"])),
    _option("--background", st.sampled_from(["0,0,0", "1,1", "2,0,0", "nan,0,0", "0.5,0.5,0.5"])),
    _option("--scene", st.sampled_from(["default", "head", "nope", "/nonexistent/s.toml"])),
    _option("--stats", st.sampled_from(["s.json", "s.txt", "sub/s.json"])),
    _option("--baseplane", st.sampled_from(["b.npy", "b.png"])),
), max_size=4)
VOLUMES = st.sampled_from(["sphere:8", "ml:9", "cube:8,6,5", "sphere:1", "sphere:x", "nope", "head:3000",
                           "sphere:8,8", "mri_t1"])


@SETTINGS
@given(VOLUMES, OPTIONS, st.sampled_from(["o.png", "o.exr", "o.jpg", "o"]))
def test_command_lines_are_one_line(tmp_path, capsys, monkeypatch, volume, options, out_name):
    monkeypatch.chdir(tmp_path)
    earlier = tmp_path / "o.png"
    earlier.write_bytes(b"earlier")
    args = ["render", volume, "--quiet", "--out", out_name]
    for opt in options:
        args += opt
    rc = main(args)
    err = capsys.readouterr().err
    assert rc in (0, 2)
    if rc:
        assert err.startswith("cube4: error: ") and err.count("\n") == 1 and "Traceback" not in err, err
        assert earlier.read_bytes() == b"earlier"
        assert not [p for p in tmp_path.rglob(".cube4-*")]

"""The command line (throwmap.cli.app): happy paths and one-line errors with exit status 2."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from typer.testing import CliRunner

import throwmap as tm
from throwmap.cli.app import app, main

runner = CliRunner()

TRIANGLE = ["--part", "triangle", "--h", "-0.01"]
START = ["--x", "0.2", "--side", "0", "--omega", "4"]

QUAD = "[[0.0, 0.0], [0.1, 0.0], [0.13, 0.02], [0.03, 0.02]]"
"""A slanted parallelogram: sides 0 and 2 stable, 1 and 3 unstable."""


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def part_file(tmp_path, vertices=QUAD, mass="0.05", extra="", arm="h = -0.01", name="part.toml"):
    text = f"[part]\nvertices = {vertices}\nmass = {mass}\n{extra}"
    if arm is not None:
        text += f"\n[arm]\n{arm}\n"
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def assert_one_error(result, field):
    """Exit 2, exactly one stderr line ``error: <field>: …``, nothing on stdout, no traceback."""
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"error: {field}"), lines[0]
    assert result.stdout == ""
    assert "Traceback" not in result.output
    assert result.exception is None or isinstance(result.exception, SystemExit)


def strict_json(text):
    def refuse(token):
        raise ValueError(f"non-standard JSON token {token}")

    return json.loads(text, parse_constant=refuse)


# ---------------------------------------------------------------- happy paths
def test_version():
    result = invoke("--version")
    assert result.exit_code == 0
    assert result.stdout.strip() == f"throwmap {tm.__version__}"


def test_python_dash_m_version():
    proc = subprocess.run([sys.executable, "-m", "throwmap", "--version"], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0
    assert proc.stdout.strip() == f"throwmap {tm.__version__}"


def test_main_entry_point():
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code in (0, None)


def test_throw_json():
    result = invoke("throw", *TRIANGLE, *START, "--json")
    assert result.exit_code == 0, result.output
    doc = strict_json(result.stdout)
    assert doc["status"] == "ok"
    assert doc["kind"] in ("jog", "flip")
    assert doc["part"] == tm.triangle_30_60_90(0.17).name
    assert doc["arm"] == {"h": -0.01, "g": 9.81, "length": None, "mu": None, "back": 0.0}
    assert doc["version"] == tm.__version__
    direct = tm.throw(tm.triangle_30_60_90(0.17), tm.Arm(-0.01), 0.2, 0, 4.0)
    assert doc["x"] == direct.x and doc["side"] == direct.side
    assert result.stderr == ""


def test_throw_json_escape_has_no_nan():
    """An escape leaves some record entries non-finite: they must come out as null."""
    result = invoke("throw", *TRIANGLE, "--length", "0.3", "--x", "0.2", "--side", "0", "--omega", "20", "--json")
    assert result.exit_code == 0, result.output
    doc = strict_json(result.stdout)
    assert doc["status"] != "ok"
    assert None in doc.values()


def test_throw_table():
    result = invoke("throw", *TRIANGLE, *START)
    assert result.exit_code == 0, result.output
    for label in ("new x (m)", "status", "kind", "flight time (s)", "contact vertex", "impacts", "flips",
                  "friction ratio needed", "lift-off"):
        assert label in result.stdout


def test_an_escape_is_not_shown_as_a_landing():
    """ω = 40 rad/s throws the triangle behind the joint: the table says where the part was when it left, and that
    it does not rest there."""
    result = invoke("throw", *TRIANGLE, "--x", "0.2", "--side", "0", "--omega", "40")
    assert result.exit_code == 0, result.output
    assert "behind_joint" in result.stdout and "x when it ended (m)" in result.stdout
    assert "new x (m)" not in result.stdout and "behind the joint" in result.stdout.splitlines()[-1]


def test_throw_arm_from_file_and_override(tmp_path):
    path = part_file(tmp_path, arm="h = -0.01\nlength = 0.5")
    a = strict_json(invoke("throw", "--part", path, "--x", "0.07", "--side", "0", "--omega", "3", "--json").stdout)
    assert a["arm"] == {"h": -0.01, "g": 9.81, "length": 0.5, "mu": None, "back": 0.0}
    b = strict_json(invoke("throw", "--part", path, "--h", "-0.005", "--x", "0.07", "--side", "0", "--omega", "3",
                           "--json").stdout)
    assert b["arm"] == {"h": -0.005, "g": 9.81, "length": 0.5, "mu": None, "back": 0.0}


def test_regime_warning_is_one_line():
    result = invoke("throw", "--part", "triangle", "--h", "0.01", *START)
    assert result.exit_code == 0, result.output
    lines = result.stderr.splitlines()
    assert lines and all(line.startswith("warning: ") for line in lines)
    assert "Traceback" not in result.output


def test_iterate_plot_png(tmp_path):
    out = tmp_path / "orbit.png"
    result = invoke("iterate", *TRIANGLE, "--x", "0.12", "--side", "0", "--omega", "4", "-n", "20", "--plot", out)
    assert result.exit_code == 0, result.output
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "throws done" in result.stdout and "20 of 20" in result.stdout
    assert [p.name for p in tmp_path.iterdir()] == ["orbit.png"]  # atomic write left no temp file


def test_iterate_json_with_omega_sequence():
    result = invoke("iterate", *TRIANGLE, "--x", "0.12", "--side", "0", "--omega", "3,4", "--omega", "5", "--json")
    assert result.exit_code == 0, result.output
    doc = strict_json(result.stdout)
    assert doc["omegas"] == [3.0, 4.0, 5.0]
    assert doc["summary"]["throws_done"] == 3
    assert len(doc["x"]) == 4


def test_iterate_progress_path_matches_library():
    """Above the progress threshold the CLI shows a progress bar; the orbit must not change."""
    result = invoke("iterate", *TRIANGLE, "--x", "0.12", "--side", "0", "--omega", "4", "-n", "230", "--json")
    assert result.exit_code == 0, result.output
    doc = strict_json(result.stdout)
    orbit = tm.iterate(tm.triangle_30_60_90(0.17), tm.Arm(-0.01), (0.12, 0), 4.0, n=230)
    assert doc["x"] == [float(v) for v in orbit.x]
    assert doc["side"] == [int(v) for v in orbit.side]
    assert doc["status"] == orbit.status.label


def test_compare(tmp_path):
    out = tmp_path / "cmp.json"
    result = invoke("compare", *TRIANGLE, "--omegas", "1,2", "--n-x", "10", "--out", out)
    assert result.exit_code == 0, result.output
    assert "small_angle" in result.stdout
    doc = strict_json(out.read_text())
    assert doc["version"] == tm.__version__


def test_demo(tmp_path):
    result = invoke("demo", "--out", tmp_path / "demo")
    assert result.exit_code == 0, result.output
    written = [line.removeprefix("wrote ") for line in result.stdout.splitlines() if line.startswith("wrote ")]
    assert written
    assert all((tmp_path / "demo").joinpath(p.rsplit("/", 1)[-1]).exists() for p in written)


# ---------------------------------------------------------------- one-line errors
@pytest.mark.parametrize(
    "vertices, field",
    [
        pytest.param("[[0, 0], [0.1, 0], [0.02, 0.02], [0, 0.1]]", "part.vertices", id="non-convex"),
        pytest.param("[[0, 0.05], [0.0294, -0.0405], [-0.0476, 0.0155], [0.0476, 0.0155], [-0.0294, -0.0405]]",
                     "part.vertices", id="self-intersecting-pentagram"),
        pytest.param("[[0, 0], [0.05, 0], [0.1, 0]]", "part.vertices", id="degenerate-collinear"),
        pytest.param("[[0, 0], [0.1, 0], [0.1, 0], [0, 0.1]]", "part.vertices", id="degenerate-repeated"),
        pytest.param("[[0, 0], [0.1, 0]]", "part.vertices", id="degenerate-two-vertices"),
        pytest.param("[[0, 0], [nan, 0], [0, 0.1]]", "part.vertices[1][0]", id="nan-in-file"),
        pytest.param("[[0, 0], [0.1, 0], [0, inf]]", "part.vertices[2][1]", id="inf-in-file"),
    ],
)
def test_bad_polygon(tmp_path, vertices, field):
    path = part_file(tmp_path, vertices=vertices)
    assert_one_error(invoke("throw", "--part", path, *START), field)


def test_cm_outside_part(tmp_path):
    path = part_file(tmp_path, extra="com = [0.5, 0.5]\n")
    assert_one_error(invoke("throw", "--part", path, *START), "part.com")


def test_point_mass_outside_part(tmp_path):
    path = part_file(tmp_path, extra="[[part.point_masses]]\nmass = 0.01\nat = [0.5, 0.01]\n")
    assert_one_error(invoke("throw", "--part", path, *START), "part.point_masses[0].at")


@pytest.mark.parametrize("mass", ["0", "-0.05"], ids=["zero", "negative"])
def test_non_positive_mass(tmp_path, mass):
    path = part_file(tmp_path, mass=mass)
    assert_one_error(invoke("throw", "--part", path, *START), "part.mass")


def test_non_positive_point_mass(tmp_path):
    path = part_file(tmp_path, extra="[[part.point_masses]]\nmass = -0.01\nat = [0.05, 0.01]\n")
    assert_one_error(invoke("throw", "--part", path, *START), "part.point_masses[0].mass")


@pytest.mark.parametrize("text, field", [("mass = nan", "part.mass"), ("h = inf", "arm.h")], ids=["nan-mass", "inf-h"])
def test_non_finite_in_file(tmp_path, text, field):
    if text.startswith("mass"):
        path = part_file(tmp_path, mass="nan")
    else:
        path = part_file(tmp_path, arm=text)
    assert_one_error(invoke("throw", "--part", path, *START), field)


@pytest.mark.parametrize(
    "option, value, field",
    [
        ("--x", "nan", "x"),
        ("--x", "inf", "x"),
        ("--omega", "nan", "omega"),
        ("--omega", "-inf", "omega"),
        ("--h", "nan", "arm.h"),
        ("--h", "inf", "arm.h"),
        ("--g", "nan", "arm.g"),
        ("--length", "nan", "arm.length"),
        ("--length", "-inf", "arm.length"),
    ],
)
def test_non_finite_on_command_line(option, value, field):
    args = {"--x": "0.2", "--side": "0", "--omega": "4", "--h": "-0.01"}
    args[option] = value
    flat = [a for kv in args.items() for a in kv]
    assert_one_error(invoke("throw", "--part", "triangle", *flat), field)


def test_non_finite_omega_in_iterate_list():
    assert_one_error(invoke("iterate", *TRIANGLE, "--x", "0.2", "--side", "0", "--omega", "4,nan"), "omega")


def test_side_does_not_exist():
    result = invoke("throw", *TRIANGLE, "--x", "0.2", "--side", "7", "--omega", "4")
    assert_one_error(result, "side")
    assert "does not exist" in result.stderr


def test_unstable_side(tmp_path):
    path = part_file(tmp_path)
    part = tm.Part.from_vertices(json.loads(QUAD), 0.05)
    assert not part.stable[1] and part.stable[0]  # the premise of the test
    result = invoke("throw", "--part", path, "--x", "0.07", "--side", "1", "--omega", "4")
    assert_one_error(result, "side")
    assert "unstable" in result.stderr


def test_start_behind_joint():
    result = invoke("throw", *TRIANGLE, "--x", "0.01", "--side", "0", "--omega", "4")
    assert_one_error(result, "x")
    assert "behind the joint" in result.stderr


def test_negative_omega():
    assert_one_error(invoke("throw", *TRIANGLE, "--x", "0.2", "--side", "0", "--omega", "-1"), "omega")


def test_malformed_toml(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("[part]\nvertices = [[0, 0],\nmass = = 1\n")
    result = invoke("throw", "--part", path, *START)
    assert_one_error(result, "file")
    assert "line" in result.stderr and "bad.toml" in result.stderr


def test_unknown_key(tmp_path):
    path = part_file(tmp_path, extra="colour = 'red'\n")
    result = invoke("throw", "--part", path, *START)
    assert_one_error(result, "part.colour")
    assert "unknown key" in result.stderr


def test_missing_file(tmp_path):
    result = invoke("throw", "--part", tmp_path / "nowhere.toml", *START)
    assert_one_error(result, "file")
    assert "nowhere.toml" in result.stderr


def test_unknown_builtin_part():
    result = invoke("throw", "--part", "dodecahedron", "--h", "-0.01", *START)
    assert_one_error(result, "part")
    assert "dodecahedron" in result.stderr


def test_unknown_model():
    assert_one_error(invoke("throw", *TRIANGLE, *START, "--model", "exact"), "model")


def test_unknown_model_in_compare():
    assert_one_error(invoke("compare", *TRIANGLE, "--models", "small_angle,bogus"), "model")


def test_file_arm_fields_survive_command_line_overrides(tmp_path):
    """An option overrides its own field only: the file's μ and back are kept (were dropped before)."""
    path = part_file(tmp_path, arm="h = -0.01\nlength = 0.5\nmu = 0.7\nback = 0.02")
    doc = strict_json(invoke("throw", "--part", path, "--h", "-0.005", "--x", "0.07", "--side", "0", "--omega", "3",
                             "--model", "paper", "--json").stdout)
    assert doc["arm"] == {"h": -0.005, "g": 9.81, "length": 0.5, "mu": 0.7, "back": 0.02}
    doc = strict_json(invoke("throw", "--part", path, "--mu", "0.3", "--back", "0", "--x", "0.07", "--side", "0",
                             "--omega", "3", "--model", "paper", "--json").stdout)
    assert doc["arm"] == {"h": -0.01, "g": 9.81, "length": 0.5, "mu": 0.3, "back": 0.0}


def test_compare_x_range(tmp_path):
    """--x-min/--x-max reach the library and the printed table states the range."""
    result = invoke("compare", *TRIANGLE, "--omegas", "2", "--n-x", "5", "--x-min", "0.12", "--x-max", "0.3", "--json")
    assert result.exit_code == 0, result.output
    settings = strict_json(result.stdout)["settings"]
    assert settings["x_min"] == 0.12 and settings["x_max"] == 0.3
    table = invoke("compare", *TRIANGLE, "--omegas", "2", "--n-x", "5", "--x-max", "0.3").stdout
    assert "0.3 m]" in table
    assert_one_error(invoke("compare", *TRIANGLE, "--x-max", "inf"), "x_max")


def test_animate_reports_the_frames_in_the_file(tmp_path):
    """The frame count printed is the one in the GIF (a held end is merged there), not the frames drawn."""
    from PIL import Image

    out = tmp_path / "t.gif"
    result = invoke("animate", *TRIANGLE, *START, "--model", "paper", "--out", out)
    assert result.exit_code == 0, result.output
    with Image.open(out) as im:
        n = im.n_frames
    assert f"({n} frames," in result.stdout


def test_h_required_without_arm_section(tmp_path):
    path = part_file(tmp_path, arm=None)
    assert_one_error(invoke("throw", "--part", path, *START), "arm.h")


def test_iterate_needs_n_with_single_omega():
    assert_one_error(invoke("iterate", *TRIANGLE, "--x", "0.2", "--side", "0", "--omega", "4"), "n")


def test_iterate_n_must_match_omegas():
    assert_one_error(invoke("iterate", *TRIANGLE, "--x", "0.2", "--side", "0", "--omega", "4,5", "-n", "3"), "n")


def test_plot_unsupported_extension(tmp_path):
    result = invoke("iterate", *TRIANGLE, "--x", "0.2", "--side", "0", "--omega", "4", "-n", "2",
                    "--plot", tmp_path / "orbit.xyz")
    assert_one_error(result, "plot")


def test_plot_missing_directory_is_refused(tmp_path):
    """One rule for every output: a missing folder is never made; the figure is refused before any work."""
    target = tmp_path / "no" / "deeper" / "orbit.png"
    result = invoke("iterate", *TRIANGLE, "--x", "0.2", "--side", "0", "--omega", "4", "-n", "2", "--plot", target)
    assert result.exit_code == 2, result.output
    assert result.stderr.splitlines() == [f"error: plot: folder {str(target.parent)!r} does not exist"]
    assert list(tmp_path.iterdir()) == []


def test_plot_directory_that_is_a_file(tmp_path):
    (tmp_path / "no").write_text("a file, not a folder")
    result = invoke("iterate", *TRIANGLE, "--x", "0.2", "--side", "0", "--omega", "4", "-n", "2",
                    "--plot", tmp_path / "no" / "orbit.png")
    assert_one_error(result, "plot")


def test_usage_error_keeps_exit_code_2():
    result = invoke("throw", *TRIANGLE, "--x", "0.2", "--side", "one", "--omega", "4")
    assert result.exit_code == 2
    assert "Traceback" not in result.output


def test_subprocess_error_is_one_line(tmp_path):
    """The installed entry point, not just the in-process runner, prints one line and exits 2."""
    proc = subprocess.run([sys.executable, "-m", "throwmap", "throw", "--part", "triangle", "--h", "-0.01",
                           "--x", "nan", "--side", "0", "--omega", "4"], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2
    assert proc.stderr.splitlines() == ["error: x: must be finite, got nan"]
    assert proc.stdout == ""

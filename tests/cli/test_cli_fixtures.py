"""--alpha, --wall, --wall-mu and --cavity on the command line, and ``throwmap validate-fixtures`` (issue 11, item 2).

Refusals and bad values: one ``error: <field>: …`` line, exit 2, from every command that takes the options.
Happy paths use a registered synthetic model with tilt and fixtures (a jog stopped by the wall), so they
check the plumbing and the JSON records without depending on any kernel's physics.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

import throwmap as tm
from throwmap.cli.app import app
from throwmap.cli.options import parse_alpha
from throwmap.errors import InvalidStateError
from throwmap.kernels import codes as C
from throwmap.models.base import BatchArrays, Features, NoOptions
from throwmap.models.registry import register, unregister
from throwmap.system.starts import start_interval

runner = CliRunner()
ARM = ["--part", "triangle", "--h", "-0.01", "--length", "0.3", "--mu", "1"]
START = ["--x", "0.15", "--side", "0"]


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def assert_one_error(result, field):
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}"), result.stderr
    assert result.stdout == "" and "Traceback" not in result.output


class WalledJog:
    """T(x, k) = (min(x + 0.02 ω (1 − α), length − u_R), k) with a wall; off_end past it without."""

    name = "cli_walled_jog"
    summary = "test model: a jog that stops at the wall"
    options_type = NoOptions
    features = Features(fixtures=True, tilt=True, parallel=False)

    def throw_batch(self, part, system, x, side, omega, valid, options, progress=None):
        hi = np.array([start_interval(part, system.arm, int(k))[1] for k in side])
        xn = x + 0.02 * omega * (1.0 - system.alpha)
        status = np.zeros(x.size, dtype=np.int64)
        if any(isinstance(f, tm.Wall) for f in system.fixtures):
            xn = np.minimum(xn, hi)
        else:
            status[xn > hi] = C.OFF_END
        status[~valid] = C.INVALID_START
        return BatchArrays(np.where(valid, xn, x), side.copy(), status, np.full((x.size, C.NREC), np.nan))

    def throw_one(self, part, system, x, side, omega, options):
        b = self.throw_batch(part, system, np.array([x]), np.array([side]), np.array([omega]), np.array([True]),
                             options)
        return float(b.x[0]), int(b.side[0]), int(b.status[0]), b.records[0]

    def trajectory(self, part, system, x, side, omega, options, dt):  # features.trajectory is False
        raise NotImplementedError


@pytest.fixture
def walled():
    m = WalledJog()
    register(m, replace=True)
    yield m.name
    unregister(m.name)


@pytest.mark.parametrize("text, rad", [("0.05", 0.05), ("-0.1", -0.1), ("5deg", math.radians(5)),
                                       ("-10 deg", math.radians(-10)), ("2.5°", math.radians(2.5)),
                                       ("0.01rad", 0.01), ("3degrees", math.radians(3))])
def test_alpha_is_rad_or_degrees_with_a_suffix(text, rad):
    assert parse_alpha(text) == pytest.approx(rad, abs=0, rel=1e-15)


@pytest.mark.parametrize("text", ["", "abc", "5 grad", "nan", "infdeg", "5degdeg"])
def test_a_bad_alpha_is_refused_naming_alpha(text):
    with pytest.raises(InvalidStateError) as err:
        parse_alpha(text)
    assert err.value.field == "alpha"


COMMANDS = {
    "throw": ["throw", *ARM, *START, "--omega", "1"],
    "iterate": ["iterate", *ARM, *START, "--omega", "1", "-n", "2"],
    "limitset": ["limitset", *ARM, "--omega", "1"],
    "basins": ["basins", *ARM, "--omega", "1"],
    "funnels": ["funnels", *ARM, "--omega", "1"],
    "animate": ["animate", *ARM, *START, "--omega", "1"],
}


@pytest.mark.parametrize("cmd", list(COMMANDS))
@pytest.mark.parametrize("extra, field", [(["--alpha", "5deg"], "alpha"), (["--wall", "0.05"], "fixtures")])
def test_a_model_without_the_feature_refuses_it_from_every_command(cmd, extra, field, tmp_path):
    out = ["--out", tmp_path / "x.gif"] if cmd == "animate" else []
    model = "paper" if cmd == "animate" and field == "fixtures" else "small_angle"
    if cmd == "animate" and field == "alpha":
        model = "paper" if not tm.get_model("paper").features.tilt else None
        if model is None:
            pytest.skip("every model that records a trajectory takes alpha")
    r = invoke(*COMMANDS[cmd], "--model", model, *extra, *out)
    assert_one_error(r, field)
    assert f"(model is '{model}')" in r.stderr
    assert not (tmp_path / "x.gif").exists()


@pytest.mark.parametrize("cmd", list(COMMANDS))
@pytest.mark.parametrize("extra, field", [
    (["--alpha", "abc"], "alpha"), (["--wall", "0"], "wall"), (["--wall", "nan"], "wall"),
    (["--wall", "0.05", "--wall-mu", "-1"], "wall_mu"), (["--wall-mu", "0.5"], "wall_mu"),
    (["--cavity", "/no/such/cavity.json"], "cavity"),
])
def test_bad_values_are_refused_naming_the_field(cmd, extra, field, tmp_path):
    out = ["--out", tmp_path / "x.gif"] if cmd == "animate" else []
    assert_one_error(invoke(*COMMANDS[cmd], "--model", "engine" if cmd == "animate" else "rigid_body", *extra, *out),
                     field)


@pytest.mark.parametrize("content, field", [("{not json", "cavity"), ('{"depth": 1}', "cavity"),
                                            ('{"profile": [[0.06, 0.0], [0.06, 0.02], [0.0, 0.02]]}', "cavity.profile")])
def test_a_bad_cavity_file_is_refused(content, field, tmp_path):
    f = tmp_path / "cav.json"
    f.write_text(content, encoding="utf-8")
    assert_one_error(invoke(*COMMANDS["throw"], "--model", "engine", "--cavity", f), field)


def test_a_wall_needs_an_arm_length(walled):
    r = invoke("throw", "--part", "triangle", "--h", "-0.01", *START, "--omega", "1", "--model", walled,
               "--wall", "0.05")
    assert_one_error(r, "arm.length")


def test_throw_records_alpha_and_the_wall_in_json(walled):
    r = invoke(*COMMANDS["throw"], "--model", walled, "--wall", "0.05", "--wall-mu", "0", "--alpha", "5deg", "--json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["alpha_rad"] == pytest.approx(math.radians(5))
    assert doc["fixtures"] == [{"kind": "wall", "height_m": 0.05, "thickness_m": 0.01, "mu": 0.0}]
    assert doc["x"] == pytest.approx(0.15 + 0.02 * (1 - math.radians(5)))
    plain = json.loads(invoke(*COMMANDS["throw"], "--model", walled, "--json").stdout)
    assert plain["alpha_rad"] == 0.0 and plain["fixtures"] == []
    table = invoke(*COMMANDS["throw"], "--model", walled, "--wall", "0.05", "--alpha", "5deg")
    assert "α = 5°, wall 5 cm (arm μ)" in table.stdout


def test_iterate_stops_at_the_wall_and_says_so_in_json(walled):
    r = invoke(*COMMANDS["iterate"][:-2], "-n", "20", "--model", walled, "--wall", "0.05", "--json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    x_star = start_interval(tm.triangle_30_60_90(), tm.Arm(h=-0.01, length=0.3), 0)[1]
    assert doc["summary"]["final"] == {"x": x_star, "side": 0} and doc["status"] == "ok"
    assert doc["fixtures"][0]["kind"] == "wall" and doc["alpha_rad"] == 0.0


def test_limitset_reports_the_fixed_points_at_the_wall(walled, tmp_path):
    r = invoke(*COMMANDS["limitset"], "--model", walled, "--wall", "0.05", "--wall-mu", "0", "--starts", "4",
               "--out", tmp_path)
    assert r.exit_code == 0, r.output
    assert "against the wall" in r.stdout and "multiplier +0" in r.stdout
    doc = json.loads((tmp_path / "limit_set.json").read_text())
    ls = doc["limit_set"]
    assert len(ls["at_wall"]) == 3 and {a["multiplier"] for a in ls["attractors"]} == {0.0}
    assert ls["map"]["fixtures"] == doc["fixtures"] and doc["alpha_rad"] == 0.0


@pytest.mark.parametrize("cmd", ["basins", "funnels"])
def test_basins_and_funnels_record_the_system(walled, cmd):
    extra = ["--grid", "20", "--starts", "2"] if cmd == "funnels" else ["--grid", "20", "--starts", "2", "--check", "0"]
    r = invoke(*COMMANDS[cmd], "--model", walled, "--wall", "0.05", "--alpha", "0.01", *extra, "--json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["alpha_rad"] == 0.01 and doc["fixtures"][0] == {"kind": "wall", "height_m": 0.05, "thickness_m": 0.01,
                                                               "mu": "arm"}


def test_a_cavity_file_reaches_the_engine(tmp_path):
    f = tmp_path / "cav.toml"
    f.write_text("[cavity]\nprofile = [[0.06, 0.0], [0.06, -0.02], [0.0, -0.02]]\n", encoding="utf-8")
    r = invoke(*COMMANDS["throw"], "--model", "engine", "--cavity", f, "--json")
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["fixtures"] == [{"kind": "cavity", "profile_m": [[0.06, 0.0], [0.06, -0.02],
                                                                                 [0.0, -0.02]]}]


def test_validate_fixtures_writes_its_table_and_refuses_bad_input(tmp_path):
    r = invoke("validate-fixtures", "--n", "2", "--conditions", "wall-0", "--no-fixed-point", "--part", "square",
               "--out", tmp_path)
    assert r.exit_code == 0, r.output
    assert "wall, μ_w = 0: rigid_body vs engine" in r.stdout
    doc = json.loads((tmp_path / "tilt_wall.json").read_text())
    assert doc["settings"]["n_per_condition"] == 2 and doc["settings"]["seed"] == 0
    assert list(doc["settings"]["conditions"]) == ["wall, μ_w = 0"] and (tmp_path / "tilt_wall.md").exists()
    assert_one_error(invoke("validate-fixtures", "--conditions", "nope", "--out", tmp_path), "conditions")
    assert_one_error(invoke("validate-fixtures", "--n", "0", "--out", tmp_path), "n")
    assert_one_error(invoke("validate-fixtures", "-O", "impact_law=nope", "--out", tmp_path), "impact_law")

"""``-O/--model-option KEY=VALUE``: a model's numerical options reach the library from the CLI
(throw, iterate, limitset, basins), are recorded in the JSON, and bad ones are refused in one line."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

import throwmap as tm
from throwmap.cli.app import app
from throwmap.models.rigid_body import RigidBodyOptions
from throwmap.system.catalogue import triangle_30_60_90

runner = CliRunner()
TRI = ["--part", "triangle", "--h", "-0.01", "--mu", "0.3"]
START = ["--x", "0.1625", "--side", "2", "--omega", "5"]


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def test_throw_option_reaches_the_model_and_the_record():
    arm = tm.Arm(h=-0.01, mu=0.3)
    want = tm.throw(triangle_30_60_90(), arm, 0.1625, 2, 5.0, options=RigidBodyOptions(impact_law="velocity"))
    plain = tm.throw(triangle_30_60_90(), arm, 0.1625, 2, 5.0)
    assert abs(want.x - plain.x) > 1e-3  # the two impact laws differ here, so the test can see the option
    res = invoke("throw", *TRI, *START, "-O", "impact_law=velocity", "--json")
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["x"] == want.x and doc["side"] == want.side
    assert doc["model_options"]["impact_law"] == "velocity"
    assert json.loads(invoke("throw", *TRI, *START, "--json").stdout)["model_options"] is None


def test_iterate_and_numbers_are_parsed():
    res = invoke("iterate", *TRI, *START, "-n", "3", "-O", "max_impacts=2", "-O", "tol=1e-12", "--json")
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["model_options"]["max_impacts"] == 2 and doc["model_options"]["tol"] == 1e-12
    assert doc["summary"]["status"] == "unresolved"  # two events are not enough to come to rest: refused


def test_limitset_takes_model_options():
    args = ["limitset", *TRI, "--omega", "4", "--starts", "4", "--record", "64", "--transient", "20", "--json"]
    a = json.loads(invoke(*args).stdout)
    b = invoke(*args, "-O", "impact_law=velocity")
    assert b.exit_code == 0, b.output
    assert json.loads(b.stdout)["model_options"]["impact_law"] == "velocity" and a["model_options"] is None


@pytest.mark.parametrize("opt, field", [("impact_law=moreau", "impact_law"), ("colour=3", "colour"),
                                        ("tol", "model_option"), ("max_iter=abc", "max_iter"), ("tol=-1", "tol")])
def test_bad_model_options_one_line(opt, field):
    res = invoke("throw", *TRI, *START, "-O", opt)
    assert res.exit_code == 2
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}:"), res.stderr


def test_paper_model_refuses_rigid_body_options():
    res = invoke("throw", *TRI, *START, "--model", "paper", "-O", "impact_law=velocity")
    assert res.exit_code == 2 and "error: impact_law:" in res.stderr


def test_animate_takes_model_options(tmp_path):
    ok = invoke("animate", *TRI, *START, "--model", "rigid_body", "-O", "impact_law=velocity", "--fps", "5",
                "--out", tmp_path / "a.gif")
    assert ok.exit_code == 0, ok.output
    bad = invoke("animate", *TRI, *START, "-O", "impact_law=x", "--out", tmp_path / "b.gif")
    assert bad.exit_code == 2 and bad.stderr.startswith("error: impact_law:") and not (tmp_path / "b.gif").exists()


def test_a_refused_throw_prints_its_reason():
    """A throw that used all its max_iter steps is `unresolved`, and the table says why."""
    res = invoke("throw", *TRI, *START, "--model", "paper", "-O", "max_iter=1")
    assert res.exit_code == 0, res.output
    assert "unresolved" in res.stdout and "reason" in res.stdout and "max_iter" in res.stdout

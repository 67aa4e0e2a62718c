"""``throwmap plan …``: the inverse throw and the planner on the command line."""

import json

from typer.testing import CliRunner

import throwmap as tm
from throwmap.cli.app import app

runner = CliRunner()
ARM = ["--h", "-0.01", "--mu", "1"]


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def test_jog_json_rate_lands_on_the_target_when_thrown_again():
    r = invoke("plan", "jog", *ARM, "--x", 0.25, "--side", 0, "--target", 0.27, "--model", "paper", "--json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    out = tm.throw(tm.triangle_30_60_90(), tm.Arm(h=-0.01, mu=1.0), 0.25, 0, doc["omega"], "paper")
    assert abs(out.x - 0.27) <= 1e-6 and doc["monotone"] is True and doc["side"] == 0


def test_unreachable_jog_is_one_line_exit_2():
    r = invoke("plan", "jog", *ARM, "--x", 0.25, "--side", 0, "--target", 0.6, "--model", "paper")
    assert r.exit_code == 2 and r.stdout == ""
    lines = r.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: x_target: no jog from x0 = 0.25 m on side 0")


def test_route_unreachable_exits_1_with_the_reason():
    r = invoke("plan", "route", *ARM, "--omegas", "5.6", "--model", "paper", "--x", 0.2, "--side", 0)
    assert r.exit_code == 1 and "NOT REACHED" in r.stdout and "ω = 5.6 rad/s" in r.stdout


def test_check_inverse_table_has_a_row_per_model():
    r = invoke("plan", "check-inverse", *ARM, "--n", 2, "--models", "paper,small_angle", "--json")
    assert r.exit_code == 0, r.output
    rows = json.loads(r.stdout)["rows"]
    assert [x["model"] for x in rows] == ["paper", "small_angle"]
    assert all(x["hit"] + x["refused"] + x["no_branch"] == 2 for x in rows)

"""``throwmap experiment position`` follows the shared experiment contract (JSON keys, seeds, resume,
config errors) and ``throwmap control`` draws and summarises it. Short runs on the analytic model
(the drops are engine runs, ≈ 50 ms each); the engine runs' figures are in the evidence, not asserted."""

import json
import math

import pytest
from typer.testing import CliRunner

from throwmap.cli.app import app
from throwmap.cli.control import control_app
from throwmap.experiments import get_experiment
from throwmap.experiments.base import config_of, trial_generator
from throwmap.experiments.runner import run_experiment

runner = CliRunner()
QUICK = {"model": "paper", "max_throws": 60}  # the impulse map: fast (rigid_body rides the recoil arm in Python)
KINDS = {"not_stopped", "stopped_off_goal", "stopped_wrong_side", "off_end", "behind_joint"}
CONTRACT = ("n", "successes", "success_rate", "ci95", "failures", "seed", "parameters", "config", "values",
            "version", "elapsed_s", "workers", "resumed")


def invoke(*args):
    if args[0] == "control":  # the group itself: these tests do not depend on its registration in cli/app.py
        return runner.invoke(control_app, [str(a) for a in args[1:]])
    return runner.invoke(app, [str(a) for a in args])


def one_error(result, field):
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}:"), result.stderr
    return lines[0]


@pytest.fixture()
def quick_toml(tmp_path):
    p = tmp_path / "quick.toml"
    p.write_text('model = "paper"\nmax_throws = 60\n')
    return p


def test_json_has_the_contract_keys_and_matches_the_library(quick_toml):
    r = invoke("experiment", "position", quick_toml, "--n", 3, "--seed", 2, "--workers", 1, "--json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    for key in CONTRACT:
        assert key in doc, key
    lib = run_experiment("position", QUICK, n=3, seed=2, workers=1)
    assert (doc["successes"], doc["failures"], doc["ci95"]) == (lib.successes, lib.failures, list(lib.ci95))
    p = doc["parameters"]
    assert p["goal"] == {"x_m": 0.48, "side": 1, "eps_m": 0.01} and p["controller"]["kind"] == "paper"
    assert p["noise"]["realisation"].startswith("impulse")  # "paper" throws the impulse (rigid_body: the recoil)
    for t in lib.trials:
        assert t.success or t.failure in KINDS or t.failure.startswith("refused:")
        v = t.values
        assert 0 <= v["throws"] <= 60
        if t.success:
            assert v["side"] == 1 and abs(v["x"] - 0.48) <= 0.01 and v["error_m"] <= 0.01 and v["stopped"]


def test_trials_repeat_and_resume(tmp_path):
    out = tmp_path / "run"
    a = run_experiment("position", QUICK, n=2, seed=5, workers=1, out=out)
    b = run_experiment("position", QUICK, n=4, seed=5, workers=1, out=out)
    fresh = run_experiment("position", QUICK, n=4, seed=5, workers=1)
    assert b.resumed == 2 and a.n == 2
    assert [t.to_json() for t in b.trials] == [t.to_json() for t in fresh.trials]
    r = invoke("control", "summary", out, "--json")
    assert r.exit_code == 0, r.output
    s = json.loads(r.stdout)
    assert s["n"] == 4 and s["successes"] == fresh.successes
    if fresh.successes:
        thr = sorted(t.values["throws"] for t in fresh.trials if t.success)
        assert s["throws"]["max"] == thr[-1] and thr[0] <= s["throws"]["median"] <= thr[-1]


@pytest.mark.parametrize("text, field", [
    ("lenght = 0.6\n", "config.lenght"),
    ("x_f = 0.55\n", "config.x_f"),
    ("side = 7\n", "config.side"),
    ('model = "nope"\n', "config.model"),
    ("eps = -0.01\n", "config.eps"),
    ('controller = "pid"\n', "config.controller"),
    ("[sensors]\nfalse_positive = 1.5\n", "config.sensors.false_positive"),
    ("x_range = [0.3, 0.2]\n", "config.x_range"),
])
def test_config_errors_are_one_line(tmp_path, text, field):
    p = tmp_path / "bad.toml"
    p.write_text(text)
    one_error(invoke("experiment", "position", p, "--n", 1, "--workers", 1, "--json"), field)


def test_parameters_and_the_inverse_controller():
    pytest.importorskip("throwmap.control.inverse")
    exp = get_experiment("position")
    cfg = config_of(exp, dict(QUICK, controller="inverse"))
    p = exp.parameters(cfg)
    assert p["controller"]["kind"] == "inverse" and p["model"] == "paper"
    t = exp.trial(cfg, 0, trial_generator(1, 0))
    assert t.success or t.failure in KINDS or t.failure.startswith("refused:")


def test_low_rate_jogs_less_than_eps():
    from throwmap.experiments.position import low_rate

    cfg = config_of(get_experiment("position"), QUICK)
    w1, w2 = low_rate(cfg, 0.01), low_rate(cfg, 0.002)
    assert 0.5 <= w2 < w1 <= 3.0


def test_control_episode_fan_tradeoff(quick_toml, tmp_path):
    r = invoke("control", "episode", quick_toml, "--index", 1, "--seed", 2, "--json", "--plot", tmp_path / "e.png")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["goal"]["side"] == 1 and doc["steps"][0]["throw"] == 0 and (tmp_path / "e.png").stat().st_size > 0
    lib = run_experiment("position", QUICK, n=2, seed=2, workers=1).trials[1]
    assert doc["summary"]["success"] == lib.success and doc["summary"]["throws"] == lib.values["throws"]
    r = invoke("control", "fan", quick_toml, "--n", 3, "--seed", 2, "--plot", tmp_path / "f.png")
    assert r.exit_code == 0 and "episodes succeeded" in r.stdout
    r = invoke("control", "tradeoff", quick_toml, "--eps", "0.005,0.02", "--omega-low", "1.2,2.5", "--n", 2,
               "--workers", 1, "--json", "--plot", tmp_path / "t.png")
    assert r.exit_code == 0, r.output
    rows = json.loads(r.stdout)["rows"]
    assert [x["eps_m"] for x in rows] == [0.005, 0.02] and [x["omega_low"] for x in rows] == [1.2, 2.5]
    assert all(set(x) >= {"median", "p90", "success_rate", "ci95"} for x in rows)
    assert (tmp_path / "t.png").stat().st_size > 0


def test_control_errors(quick_toml, tmp_path):
    one_error(invoke("control", "tradeoff", quick_toml, "--eps", "0.01", "--omega-low", "1,2"), "omega_low")
    one_error(invoke("control", "tradeoff", quick_toml, "--eps", "-0.01"), "eps")
    one_error(invoke("control", "summary", tmp_path / "none"), "directory")
    one_error(invoke("control", "episode", quick_toml, "--index", -1), "index")


@pytest.mark.slow
def test_one_engine_trial():
    exp = get_experiment("position")
    cfg = config_of(exp, {"max_throws": 80})
    t = exp.trial(cfg, 0, trial_generator(1, 0))
    assert t.success or t.failure in KINDS or t.failure.startswith("refused:")
    assert math.isfinite(t.values["drop_x"]) and t.values["throws"] <= 80


@pytest.mark.slow
def test_the_experiments_benchmark_runs_position(tmp_path):
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "benchmarks" / "experiments.py"
    spec = importlib.util.spec_from_file_location("experiments_bench_position", path)
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    data = bench.main(["--quick", "--experiments", "position", "--workers", "1"])
    run = data["experiments"][0]["runs"][0]
    assert data["experiments"][0]["experiment"] == "position" and run["cpu_s_per_trial"] > 0


def test_rigid_body_rides_the_recoil_arm_in_the_experiment():
    # rigid_body takes the arm's motion: its rows are made on the recoil arm, as the engine's are
    cfg = config_of(get_experiment("position"), {"model": "rigid_body", "max_throws": 2})
    p = get_experiment("position").parameters(cfg)
    assert p["noise"]["realisation"] == "recoil"

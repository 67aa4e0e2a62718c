"""The feeder search's verdict: a feeder is called found only when its verification and an independent rerun
reach the goal and agree; otherwise the result says why. The engine runs are replaced by stated results here
(the verdict's logic), and one real command line run checks the JSON and the exit status."""

from __future__ import annotations

import json
from types import SimpleNamespace

import pytest
from typer.testing import CliRunner

import throwmap as tm
from throwmap.cli.app import app
from throwmap.errors import InvalidStateError
from throwmap.experiments.stats import wilson_interval
from throwmap.feeder import VerifyPlan, design_feeder, screen

GRID = dict(omegas=(4.0, 4.75), hs=(0.0, -0.01), depths=(0.01,))
SMALL = dict(grid=GRID)


def _fake(monkeypatch, rates):
    """Replace the engine runs: run i of a candidate feeds ``rates[(k, name)]`` (default 0) of its trials."""
    import throwmap.experiments.runner as runner

    calls = []

    def run_experiment(name, cfg, *, n, seed, workers, out, progress=None):
        k = int(out.parent.name)
        r = rates.get((k, out.name), rates.get(out.name, 0.0))
        s = int(round(r * n))
        calls.append((k, out.name, n, seed))
        return SimpleNamespace(n=n, successes=s, success_rate=s / n, ci95=wilson_interval(s, n), seed=seed,
                               failures={} if s == n else {"not_captured": n - s})

    monkeypatch.setattr(runner, "run_experiment", run_experiment)
    return calls


@pytest.fixture(scope="module")
def tri():
    return tm.triangle_30_60_90(0.17)


def test_the_first_candidate_that_verifies_and_reruns_is_the_feeder(tri, tmp_path, monkeypatch):
    calls = _fake(monkeypatch, {"first": 1.0, "verify": 0.97, "rerun": 0.96})
    res = design_feeder(tri, tmp_path, plan=VerifyPlan(n_pre=20, n_verify=200, seed=5), **SMALL)
    assert res.success and res.config == str(tmp_path / "feeder.toml") and (tmp_path / "part.toml").is_file()
    assert [c[1:] for c in calls] == [("first", 20, 5), ("verify", 200, 5), ("rerun", 200, 6)]
    assert res.verified["successes"] == 194 and res.rerun["successes"] == 192
    assert res.side == res.tried[0].candidate.side and res.tried[0].verdict == "fed"
    assert "reason" not in res.to_dict() and (tmp_path / "candidates.jsonl").read_text().count("\n") == 1


def test_a_rerun_outside_the_interval_is_not_a_feeder(tri, tmp_path, monkeypatch):
    _fake(monkeypatch, {"first": 1.0, "verify": 1.0, "rerun": 0.96})  # 200/200 has Wilson [98.1, 100] %
    res = design_feeder(tri, tmp_path, plan=VerifyPlan(n_pre=20, n_verify=200), **SMALL)
    assert not res.success and all(t.verdict == "rerun disagrees" for t in res.tried)
    assert "rerun disagrees" in res.reason and res.config is None


def test_weak_candidates_are_dropped_and_the_reason_names_the_best(tri, tmp_path, monkeypatch):
    ranked = [k for k, c in enumerate(screen(tri, **GRID).candidates) if c.window]
    rates = {(k, "first"): 0.5 for k in ranked}
    rates[(ranked[-1], "first")] = 0.95
    rates[(ranked[-1], "verify")] = 0.9
    _fake(monkeypatch, rates)
    res = design_feeder(tri, tmp_path, plan=VerifyPlan(n_pre=20, n_verify=200), **SMALL)
    assert not res.success and len(res.tried) == len(ranked)
    assert [t.verdict for t in res.tried].count("dropped after the first trials") == len(ranked) - 1
    assert "reached 95.0 %" in res.reason and "below the goal" in res.reason


def test_a_part_no_pocket_separates_is_refused_before_any_engine_run(tmp_path, monkeypatch):
    calls = _fake(monkeypatch, {})
    res = design_feeder(tm.rectangle(0.06, 0.06), tmp_path, grid=dict(omegas=(3.0, 4.0), hs=(-0.01,), depths=(0.01,)))
    assert not res.success and calls == [] and "no end-wall pocket holds one side alone" in res.reason


@pytest.mark.parametrize("kw, field", [({"n_verify": 0}, "n_verify"), ({"goal": 1.5}, "goal"),
                                       ({"seed": -1}, "seed"), ({"budget_s": -1.0}, "budget_s")])
def test_bad_search_settings_name_their_field(tri, tmp_path, kw, field):
    with pytest.raises(InvalidStateError) as err:
        design_feeder(tri, tmp_path, plan=VerifyPlan(**kw), **SMALL)
    assert err.value.field == field


def test_the_command_prints_one_json_object_and_exits_1_without_a_feeder(tmp_path):
    res = CliRunner().invoke(app, ["feeder", "design", "triangle", "--out", str(tmp_path / "f"), "--budget", "0",
                                   "--json"])
    assert res.exit_code == 1, res.output
    doc = json.loads(res.stdout)
    assert doc["success"] is False and doc["config"] is None and doc["verified"] is None
    assert "budget" in doc["reason"] and doc["time_s"] > 0 and doc["assumptions"]["goal"] == 0.95


@pytest.mark.parametrize("args, field", [(["--side", "7"], "side"), (["--budget", "-1"], "budget"),
                                         (["--budget", "nan"], "budget"), (["--n", "0"], "n:"),
                                         (["--n-pre", "0"], "n-pre"), (["--seed", "-1"], "seed")])
def test_bad_command_input_is_one_line_exit_2(tmp_path, args, field):
    res = CliRunner().invoke(app, ["feeder", "design", "triangle", "--out", str(tmp_path / "f"), *args])
    assert res.exit_code == 2, res.output
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}"), lines
    assert res.stdout == ""  # nothing but the error line

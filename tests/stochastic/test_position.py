"""The position experiment's closed loop as a chain, against its Monte Carlo on rigid_body (the impulse)."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from throwmap.cli.app import app
from throwmap.errors import InvalidStateError
from throwmap.experiments import run_experiment
from throwmap.experiments.position import PositionConfig, _setup
from throwmap.stochastic import PolicyStep, compare_curve
from throwmap.stochastic.experiments import position_chain, position_hits, position_initial, read_trials

CFG = {"model": "rigid_body", "noise": {"omega_rel": 0.03, "mu_rel": 0.1, "realisation": "impulse"}}


def test_a_controller_with_memory_is_refused():
    part, arm, ctl = _setup(PositionConfig(model="rigid_body", sensors={"confirm": 3}))
    with pytest.raises(InvalidStateError, match="confirm"):
        PolicyStep(part, arm, ctl)
    part, arm, ctl = _setup(PositionConfig(model="rigid_body", sensors={"hysteresis": 0.002}))
    with pytest.raises(InvalidStateError, match="hysteresis"):
        PolicyStep(part, arm, ctl)


def test_the_stop_is_taken_in_the_goal_cells_only():
    cfg = PositionConfig(**CFG)
    part, arm, ctl = _setup(cfg)
    step = PolicyStep(part, arm, ctl, "rigid_body")
    w = step.decide(np.array([0.475, 0.485, 0.30, 0.48]), np.array([1, 1, 1, 0]), np.random.default_rng(0))
    assert np.isnan(w[0]) and np.isnan(w[1])
    assert w[2] == pytest.approx(3.0) and w[3] == pytest.approx(cfg.omega_high)


@pytest.fixture(scope="module")
def mc(tmp_path_factory):
    out = tmp_path_factory.mktemp("pos")
    run_experiment("position", CFG, n=80, seed=5, workers=1, out=out)
    return out


def test_position_chain_lies_in_the_monte_carlo_band(mc):
    """80 trials (≈ 3 s) against a chain of 1 cm cells, 16 throws per cell, 3 μ nodes."""
    trials = read_trials(mc)
    mix, builds = position_chain(PositionConfig(**CFG), cell=0.01, samples=16, n_mu=3, rng=0)
    init = position_initial(mix.cells, trials)
    hits = position_hits(trials)
    cmp = compare_curve(mix.p_goal_by(int(hits.max()), "stop:goal", init), hits)
    assert cmp.fraction_inside >= 0.8, cmp.summary()


def test_cli_chain_position_writes_the_comparison(mc, tmp_path):
    out = tmp_path / "c.json"
    r = CliRunner().invoke(app, ["chain", "position", str(mc), "--cell", "0.01", "--samples", "8", "--mu-nodes", "1",
                                 "--out", str(out)])
    assert r.exit_code == 0, r.output
    assert "inside the Wilson 95 % band" in r.output
    d = json.loads(out.read_text())
    assert 0 <= d["fraction_inside"] <= 1 and d["trials"] == 80
    # the Monte Carlo's P(success) with the library's Wilson interval (experiments.stats), not one of the CLI's own
    from throwmap.experiments.stats import wilson_interval

    hits = position_hits(read_trials(mc))
    k = int((hits >= 0).sum())
    p = d["p_success"]
    assert p["mc"] == k / 80 and p["mc_ci95"] == pytest.approx(list(wilson_interval(k, 80)), abs=1e-15)
    lo, hi = wilson_interval(k, 80)
    assert f"Monte Carlo {100 * k / 80:.1f} % [{100 * lo:.1f}, {100 * hi:.1f}] (Wilson 95 %)" in r.output


def test_cli_chain_errors_are_one_line(tmp_path):
    r = CliRunner().invoke(app, ["chain", "throw", "--goal", "nowhere", "--trials", "0"])
    assert r.exit_code == 2
    assert "error: goal:" in r.output
    r = CliRunner().invoke(app, ["chain", "throw", "--cell", "-1"])
    assert r.exit_code == 2 and "error: cell:" in r.output


def test_cli_chain_position_without_a_run_is_one_line(tmp_path):
    r = CliRunner().invoke(app, ["chain", "position", str(tmp_path)])
    assert r.exit_code == 2 and "error: trials: no run.json" in r.output


@pytest.mark.parametrize("args, field", [(["--cell", "1e-6"], "cell"), (["--samples", "100000000"], "samples"),
                                         (["--mu-nodes", "0"], "mu_nodes"), (["--max-time", "1e-6"], "")])
def test_cli_chain_position_sizes_are_guarded(mc, args, field):
    """Oversized chains are refused before any work, one line naming the field (as ``chain throw``)."""
    r = CliRunner().invoke(app, ["chain", "position", str(mc)] + args)
    assert r.exit_code == 2, r.output
    lines = r.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}") and "Traceback" not in r.output, r.output

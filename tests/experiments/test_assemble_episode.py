"""One ``assemble`` trial recorded throw by throw: the same trial as the Monte Carlo run's, its numbering and
roles, the Fig. 15/16 analogues and the animation's motion; ``throwmap assemble episode|animate``."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from throwmap.cli import app
from throwmap.control.pair_sensors import is_assembled
from throwmap.errors import InvalidStateError
from throwmap.experiments.assemble_episode import MOTIONS, PHASES, assembly_episode, first_success
from throwmap.experiments.runner import run_experiment

QUICK = {"max_high": 3}  # a drop and at most three randomising throws: seconds


def test_the_episode_is_the_monte_carlo_trial():
    run = run_experiment("assemble", QUICK, n=2, seed=5, workers=1)
    for i in range(2):
        ep = assembly_episode(QUICK, i, 5)
        t = run.trials[i]
        assert (ep.trial.success, ep.trial.failure, ep.trial.seed) == (t.success, t.failure, t.seed)
        assert ep.trial.values.keys() == t.values.keys()
        for k, v in t.values.items():
            assert ep.trial.values[k] == v or (v != v and ep.trial.values[k] != ep.trial.values[k])


def test_numbering_phases_and_states():
    ep = assembly_episode(QUICK, 0, 5)
    assert ep.phases[0] == "drop" and set(ep.phases) <= set(PHASES)
    assert ep.throw_no[0] == 0 and np.all(np.diff(ep.throw_no) >= 0)
    throws = sum(p not in MOTIONS for p in ep.phases)
    v = ep.trial.values
    assert ep.throw_no[-1] == throws == v["throws_high"] + v["throws_low"] + ep.phases.count("hold")
    assert ep.poses.shape == (ep.n_runs, 2, 3) and ep.states.shape == (ep.n_runs, 2, 3)
    assert np.allclose(ep.states[:, :, 0], ep.poses[:, :, 0])  # x of the state is the CM abscissa
    json.dumps(ep.rows()) and json.dumps(ep.summary(), default=str)
    with pytest.raises(InvalidStateError, match="^motion: this episode was recorded without its motion"):
        ep.motion()


def test_bad_index_and_seed():
    with pytest.raises(InvalidStateError, match="^index: must be a non-negative integer"):
        assembly_episode(QUICK, -1, 0)
    with pytest.raises(InvalidStateError, match="^seed: must be a non-negative integer"):
        assembly_episode(QUICK, 0, True)
    with pytest.raises(InvalidStateError, match=r"^index: no successful trial among indices 0…1 of seed 0"):
        first_success({"max_high": 0}, 0, max_tries=2)


@pytest.mark.slow
def test_a_successful_episode_its_figures_and_motion(tmp_path):
    ep = first_success(None, 1, motion=True, max_tries=6)
    assert ep.success and ep.switch_run is not None and ep.phases[ep.switch_run] == "tilt"
    k = ep.assembled_run
    assert ep.phases[k] == "low" and ep.alphas[k] < 0
    assert is_assembled(ep.part, ep.poses[k], length=ep.length, h=ep.h)
    assert not any(is_assembled(ep.part, ep.poses[i], length=ep.length, h=ep.h)
                   for i in range(ep.switch_run) if ep.phases[i] == "high")
    names = sorted(n for n, _ in ep.roles())
    assert names == ["a", "b"]
    labels = [lbl for lbl, _ in ep.snapshot_runs()]
    assert labels[0] == "ready (switch)" and labels[-1] == "assembled"
    traj = ep.motion()
    assert traj.poses.shape[1] == 2 and np.all(np.diff(traj.t) >= 0)
    x0, x1, y0, y1 = traj.meta["view"]
    assert x0 < 0 < ep.length < x1 and y0 < ep.h < y1 < ep.wall_height
    ep.plot().savefig(tmp_path / "f16.png")
    ep.plot_snapshots().savefig(tmp_path / "f15.png")
    assert (tmp_path / "f16.png").stat().st_size > 10_000 and (tmp_path / "f15.png").stat().st_size > 10_000


def test_cli_episode_json_and_errors(tmp_path):
    runner = CliRunner()
    cfg = tmp_path / "quick.toml"
    cfg.write_text("max_high = 2\n")
    r = runner.invoke(app, ["assemble", "episode", str(cfg), "--seed", "5", "--json", "--plot", str(tmp_path / "e.png")])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["summary"]["seed"] == 5 and d["runs"][0]["phase"] == "drop" and (tmp_path / "e.png").is_file()
    r = runner.invoke(app, ["assemble", "episode", "--index", "-2"])
    assert r.exit_code == 2 and "error: index: must be ≥ 0" in r.output
    r = runner.invoke(app, ["assemble", "animate", str(cfg), "--out", str(tmp_path / "a.txt")])
    assert r.exit_code == 2 and r.output.startswith("error: ")
    r = runner.invoke(app, ["assemble", "animate", str(cfg), "--start", "middle", "--out", str(tmp_path / "a.gif")])
    assert r.exit_code == 2 and "error: start: must be 'switch' or 'drop'" in r.output

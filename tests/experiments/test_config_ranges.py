"""Experiment configs refuse ranges and rates that cannot run, with one line naming the field (CLI exit 2)."""

import re

import pytest
from typer.testing import CliRunner

from throwmap.cli.app import app
from throwmap.errors import ConfigError, InvalidStateError
from throwmap.experiments.runner import run_experiment


@pytest.mark.parametrize("experiment,cfg,field", [
    ("assemble", {"height": [0.1, 0.02]}, "config.height"),
    ("assemble", {"height": [-0.05, -0.01]}, "config.height[0]"),
    ("assemble", {"omega_high": [6.0, 3.0]}, "config.omega_high"),
    ("assemble", {"x_range": [0.4, 0.1]}, "config.x_range"),
    ("position", {"omega_high": 1e9}, "config.omega_high"),
    ("position", {"height": [0.05, 0.01]}, "config.height"),
    ("feed", {"height": [0.05, 0.01]}, "config.height"),
    ("feed", {"omega": 500.0}, "config.omega"),
])
def test_a_range_that_cannot_run_is_refused_before_any_trial(experiment, cfg, field):
    with pytest.raises(ConfigError, match="^" + re.escape(field) + ": "):
        run_experiment(experiment, cfg, n=1, seed=0, workers=1)


def test_zero_trials_on_the_command_line_is_a_usage_error():
    r = CliRunner().invoke(app, ["experiment", "settle", "--n", "0"])
    assert r.exit_code == 2, r.output
    assert "n: must be an integer ≥ 1, got 0" in r.output


def test_the_default_configs_still_load():
    for name in ("assemble", "position", "feed", "assemble-sequential", "assemble-serial", "settle"):
        with pytest.raises(InvalidStateError, match=r"^n: "):
            run_experiment(name, None, n=0, seed=0, workers=1)

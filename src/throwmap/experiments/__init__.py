"""Monte Carlo experiments (issue 11, item 3): the contract, the registry, the runner, the
statistics, the noise models and random initial conditions by dropping.

Every experiment is run by :func:`run_experiment` and on the command line by
``throwmap experiment NAME [CONFIG] --n N --seed S [--json] [--out DIR]``.
"""

from __future__ import annotations

from .base import Experiment, Trial, trial_generator, trial_seed
from .registry import experiment_names, get_experiment, register_experiment, unregister_experiment

__all__ = ["Experiment", "Trial", "trial_generator", "trial_seed", "register_experiment", "get_experiment",
           "experiment_names", "unregister_experiment"]

"""Monte Carlo experiments (issue 11, item 3): the contract, the registry, the runner, the
statistics, the noise models and random initial conditions by dropping.

Every experiment is run by :func:`run_experiment` and on the command line by
``throwmap experiment NAME [CONFIG] --n N --seed S [--json] [--out DIR]``.
Importing this package loads neither pymunk nor matplotlib nor pyarrow.
"""

from __future__ import annotations

from .base import Experiment, Trial, config_of, read_config, seed_of, trial_generator, trial_seed
from .drop import DropResult, drop_part
from .noise import Noise, NoiseConfig
from .registry import experiment_names, get_experiment, register_experiment, unregister_experiment
from .runner import ExperimentResult, run_experiment
from .stats import wilson_interval

__all__ = ["Experiment", "Trial", "trial_generator", "trial_seed", "seed_of", "config_of", "read_config",
           "register_experiment", "get_experiment", "experiment_names", "unregister_experiment", "run_experiment",
           "ExperimentResult", "wilson_interval", "Noise", "NoiseConfig", "drop_part", "DropResult"]

"""Monte Carlo experiments: the contract, the registry, the runner, the statistics and random
initial conditions by dropping (the noise models are :mod:`throwmap.system.noise`, re-exported here).

Every experiment is run by :func:`run_experiment` and on the command line by
``throwmap experiment NAME [CONFIG] --n N --seed S [--json] [--out DIR]``.
Importing this package loads neither pymunk nor matplotlib nor pyarrow.
"""

from __future__ import annotations

from .base import Experiment, Trial, config_of, read_config, seed_of, trial_generator, trial_seed
from .drop import DropResult, drop_part
from ..system.noise import Noise
from ..io.spec import NoiseSpec
from .registry import experiment_names, get_experiment, register_experiment, unregister_experiment
from .runner import ExperimentResult, run_experiment
from .stats import wilson_interval

__all__ = ["Experiment", "Trial", "trial_generator", "trial_seed", "seed_of", "config_of", "read_config",
           "register_experiment", "get_experiment", "experiment_names", "unregister_experiment", "run_experiment",
           "ExperimentResult", "wilson_interval", "Noise", "NoiseSpec", "drop_part", "DropResult"]

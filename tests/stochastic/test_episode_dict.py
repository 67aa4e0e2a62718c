"""A recorded assembly episode is its own JSON row (``to_dict``, the line ``chain assemble --record`` writes)
and prints as a table; ``read_episodes`` reads the row back."""

from __future__ import annotations

import json
import math

import numpy as np

import throwmap as tm
from throwmap.experiments.assemble_episode import AssemblyEpisode
from throwmap.experiments.base import Trial, trial_seed
from throwmap.stochastic.assembly import read_episodes


def _episode() -> AssemblyEpisode:
    trial = Trial(2, trial_seed(1, 2), False, "not_assembled", {"throws": 3, "t": math.nan})
    poses = np.zeros((2, 2, 3))
    poses[:, :, 0] = [[0.1, 0.3], [0.12, 0.28]]
    states = np.zeros((2, 2, 3))
    states[:, :, 0] = poses[:, :, 0]
    return AssemblyEpisode(trial, 1, 2, tm.triangle_30_60_90(), 0.5, -0.01, 0.1, ("drop", "high"),
                           np.array([0.0, 4.0]), np.array([0, 1]), poses, states, np.zeros(2), ("ok", "ok"))


def test_an_episode_is_its_row(tmp_path):
    ep = _episode()
    row = ep.to_dict()
    assert row["index"] == 2 and row["seed"] == 1 and row["success"] is False and row["values"]["t"] is None
    assert row["phases"] == ["drop", "high"] and row["throw_no"] == [0, 1] and len(row["poses"]) == 2
    f = tmp_path / "ep.jsonl"
    f.write_text(json.dumps(row, allow_nan=False) + "\n")
    assert read_episodes(f) == [row]
    t = ep.table()
    assert t.splitlines()[0].startswith("AssemblyEpisode(seed 1, trial 2: failed (not_assembled)")
    assert "| 1 | 1 | high | 4 | 12.00, 0; 28.00, 0 | ok |" in t

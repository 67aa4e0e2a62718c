"""A goal may be a single rest x (lo = hi); start weights that are all zero name no start and are refused."""

import numpy as np
import pytest

import throwmap as tm
from throwmap.errors import InvalidStateError
from throwmap.stochastic import Cells, GoalSet, ThrowStep, open_loop_trials

PART = tm.triangle_30_60_90()
ARM = tm.Arm(h=-0.01, length=0.60, mu=1.0)


def test_a_one_point_goal_is_a_goal():
    g = GoalSet(side=0, lo=0.25, hi=0.25)
    assert (g.lo, g.hi) == (0.25, 0.25)


def test_all_zero_start_weights_are_refused():
    cells = Cells.on_arm(PART, ARM, 0.05)
    step = ThrowStep(PART, ARM, 3.0, "paper")
    with pytest.raises(InvalidStateError, match=r"^initial: "):
        open_loop_trials(step, cells, np.zeros(cells.n), GoalSet(label="off_end"), n=4, k_max=2, rng=0)

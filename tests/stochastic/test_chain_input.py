"""Chains refuse questions they cannot answer with one line naming the field: an unknown goal state, a goal no
throw can reach, a rate that does not throw, a horizon beyond the work limits."""

import math

import numpy as np
import pytest
from typer.testing import CliRunner

import throwmap as tm
from throwmap.cli.app import app
from throwmap.errors import InvalidStateError
from throwmap.stochastic import Cells, GoalSet, MarkovChain, ThrowStep, open_loop_trials

PART = tm.triangle_30_60_90()
ARM = tm.Arm(h=-0.01, length=0.60, mu=1.0)


def ruin(p=0.5):
    q = 1 - p
    P = np.zeros((5, 5))
    P[0, 1], P[0, 3] = p, q
    P[1, 2], P[1, 0] = p, q
    P[2, 4], P[2, 1] = p, q
    P[3, 3] = P[4, 4] = 1.0
    return MarkovChain(P, ("c1", "c2", "c3", "lost", "won"), 3)


@pytest.mark.parametrize("goal", [[5], [-1], [99], ["wonn"]])
def test_p_goal_by_refuses_a_goal_outside_the_chain(goal):
    with pytest.raises(InvalidStateError, match=r"^goal: "):
        ruin().p_goal_by(5, goal)


def test_p_goal_by_refuses_a_horizon_beyond_the_limits():
    with pytest.raises(InvalidStateError, match=r"^k_max: p_goal_by on 1,000,000,001 steps needs"):
        ruin().p_goal_by(10**9, ["won"])


def test_p_goal_by_is_the_first_hitting_curve_still():
    c = ruin(0.5)
    curve = c.p_goal_by(40, ["won"])
    d = c.with_goal(c.states(["won"])).evolve(40)
    assert np.array_equal(curve, d[:, 4])  # no stop states: P(won by k) is the absorbed mass at k
    p_won, _ = c.reach(["won"])
    assert curve[-1] == pytest.approx(p_won, abs=1e-6)


@pytest.mark.parametrize("omega", [math.nan, -3.0, 0.0, "3"])
def test_a_throw_step_needs_a_rate_that_throws(omega):
    with pytest.raises(InvalidStateError, match=r"^omega: "):
        ThrowStep(PART, ARM, omega, "paper")


@pytest.mark.parametrize("kw,field", [(dict(side=-1), "goal.side"), (dict(side=0, lo=0.3, hi=0.2), "goal.lo"),
                                      (dict(side=0, lo=math.nan), "goal.lo")])
def test_a_goal_set_that_cannot_hold_is_refused(kw, field):
    with pytest.raises(InvalidStateError, match=rf"^{field}: "):
        GoalSet(**kw)


@pytest.mark.parametrize("goal,field", [(GoalSet(label="offend"), "goal.label"), (GoalSet(side=7), "goal.side"),
                                        (GoalSet(side=0, lo=5.0, hi=6.0), "goal.lo")])
def test_open_loop_trials_refuse_a_goal_never_reached(goal, field):
    cells = Cells.on_arm(PART, ARM, 0.05)
    step = ThrowStep(PART, ARM, 3.0, "paper")
    with pytest.raises(InvalidStateError, match=rf"^{field}: "):
        open_loop_trials(step, cells, np.ones(cells.n), goal, n=4, k_max=2, rng=0)


@pytest.mark.parametrize("kw,field", [(dict(initial=None), "initial"), (dict(n=-1), "n"),
                                      (dict(initial="uniform"), "initial")])
def test_open_loop_trials_refuse_bad_arguments(kw, field):
    cells = Cells.on_arm(PART, ARM, 0.05)
    step = ThrowStep(PART, ARM, 3.0, "paper")
    args = dict(initial=np.ones(cells.n), n=4) | kw
    initial = args.pop("initial")
    with pytest.raises(InvalidStateError, match=rf"^{field}: "):
        open_loop_trials(step, cells, initial, GoalSet(label="off_end"), k_max=2, rng=0, **args)


def test_chain_throw_refuses_a_pose_keeping_model():
    r = CliRunner().invoke(app, ["chain", "throw", "--model", "engine"])
    assert r.exit_code == 2 and "model: 'engine' keeps the part's pose" in r.output

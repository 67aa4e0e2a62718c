"""Trajectories through the registry: every model that records one, the same outcome as throw()."""

import numpy as np
import pytest

import throwmap as tm
from throwmap.errors import InvalidStateError
from throwmap.throws.orbit_trajectory import orbit_trajectory, throw_trajectory, trajectory_models
from throwmap.system.pose import state_from_pose

TRI = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01, mu=1.5)


def test_trajectory_models_come_from_the_features():
    assert trajectory_models() == ("paper", "rigid_body", "engine", "mujoco")


@pytest.mark.parametrize("model", ["paper", "rigid_body", "engine"])
def test_trajectory_outcome_equals_throw_and_ends_at_rest(model):
    out, traj = throw_trajectory(TRI, ARM, 0.34, 1, 4.0, model)
    ref = tm.throw(TRI, ARM, 0.34, 1, 4.0, model=model)
    assert (out.side, out.status) == (ref.side, ref.status)
    # the analytic kernels are the same computation; the engine records on its sampling grid (≤ 1 mm apart)
    assert out.x == (ref.x if model != "engine" else pytest.approx(ref.x, abs=1e-3))
    assert traj.n_samples > 10 and np.all(np.diff(traj.t) >= 0)
    x, k, _ = state_from_pose(TRI, traj.poses[-1, 0], traj.arm_angle[-1])
    assert k == out.side and x == pytest.approx(out.x, abs=2e-4)  # the engine reads its pose at the settle time


def test_default_model_trajectory_is_rigid_body():
    out, traj = throw_trajectory(TRI, ARM, 0.34, 1, 4.0)
    assert out.model == "rigid_body" and traj.source == "rigid_body"


def test_models_without_trajectories_and_bad_keywords_are_refused():
    with pytest.raises(InvalidStateError, match="^model: model 'small_angle' records no trajectory"):
        throw_trajectory(TRI, ARM, 0.34, 1, 4.0, "small_angle")
    with pytest.raises(InvalidStateError, match="^fixtures:"):
        throw_trajectory(TRI, ARM, 0.34, 1, 4.0, "rigid_body",
                         fixtures=(tm.system.fixtures.Cavity(((0.05, 0.0), (0.05, -0.01), (0.0, -0.01))),))
    with pytest.raises(InvalidStateError, match="^dt:"):
        throw_trajectory(TRI, ARM, 0.34, 1, 4.0, "paper", dt=-1.0)
    with pytest.raises(InvalidStateError, match="^x:"):
        throw_trajectory(TRI, ARM, 0.0, 1, 4.0, "paper")


def test_orbit_trajectory_of_the_default_model_matches_iterate():
    traj = orbit_trajectory(TRI, ARM, 0.3, 1, 4.0, 3)
    orbit = tm.iterate(TRI, ARM, (0.3, 1), 4.0, n=3)
    assert [(o.x, o.side) for o in traj.meta["outcomes"]] == [(o.x, o.side) for o in orbit.outcomes]
    assert traj.source == "rigid_body orbit"

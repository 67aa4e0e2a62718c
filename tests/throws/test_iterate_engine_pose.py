"""iterate(model="engine") keeps each part's settled pose between throws (issue 11, item 2/3).

A part that a cavity (with a wall at the arm's end) holds tilted is thrown again from
that tilted pose, not restarted flat at the reported (x, side); on a bare arm, where every
rest is flat, the chain agrees with the old restart-flat orbit.
"""

import math

import numpy as np
import pytest

import throwmap as tm
from throwmap.engine import ImpulseThrow, Placement, Scene, simulate
from throwmap.system.fixtures import Cavity, Wall

ARM = tm.Arm(h=-0.01, length=0.4, mu=0.8)
FIXTURES = (Cavity(((0.12, 0.0), (0.12, -0.015), (0.0, -0.015))), Wall(height=0.04))
"""A 12 cm pocket 1.5 cm deep ending at a 4 cm wall: the triangle lands in it leaning on the pocket's edge."""


def _tilt(part, pose, side):
    return float((pose[2] - part.beta[side] + math.pi) % (2 * math.pi) - math.pi)


@pytest.fixture(scope="module")
def cavity_orbit(triangle):
    return tm.iterate(triangle, ARM, (0.28, 0), [2.5, 2.5, 2.5], model="engine", fixtures=FIXTURES)


def test_tilted_rest_in_the_cavity_is_the_next_start(triangle, cavity_orbit):
    o = cavity_orbit
    assert o.status == tm.Status.OK and len(o.poses) == 4
    # after the first throw the part lies tilted in the pocket (not flat on its side)
    tilt1 = _tilt(triangle, o.poses[1], int(o.side[1]))
    assert abs(tilt1) > 0.05
    # the second throw is exactly an engine run from that tilted pose ...
    scene = Scene(ARM, (Placement(triangle, pose=o.poses[1]),), FIXTURES, 0.0)
    again = simulate(scene, ImpulseThrow(2.5))
    assert again.states[0][0] == o.outcomes[1].x and again.states[0][1] == o.outcomes[1].side
    assert tuple(again.poses[0]) == pytest.approx(o.poses[2], abs=0.0)
    # ... and not the old restart flat at the reported (x, side), which lands elsewhere
    flat = tm.throw(triangle, ARM, float(o.x[1]), int(o.side[1]), 2.5, model="engine", fixtures=FIXTURES)
    assert abs(flat.x - o.outcomes[1].x) > 1e-3 or flat.side != o.outcomes[1].side


def test_first_throw_is_the_flat_start(triangle, cavity_orbit):
    first = tm.throw(triangle, ARM, 0.28, 0, 2.5, model="engine", fixtures=FIXTURES)
    assert cavity_orbit.outcomes[0].x == first.x and cavity_orbit.outcomes[0].side == first.side
    assert cavity_orbit.poses[0] == pytest.approx(
        Placement(triangle, x=0.28, side=0).arm_pose(ARM.h), abs=0.0)


def test_bare_arm_chain_matches_restart_flat(triangle):
    """On a bare arm every rest is flat, so keeping the pose changes nothing beyond the engine's settling slack."""
    arm = tm.Arm(h=-0.01, length=0.6, mu=0.8)
    chain = tm.iterate(triangle, arm, (0.1, 1), [3.0] * 4, model="engine")
    xs, ss = [0.1], [1]
    for w in [3.0] * 4:
        o = tm.throw(triangle, arm, xs[-1], ss[-1], w, model="engine")
        xs.append(o.x)
        ss.append(o.side)
    assert list(chain.side) == ss
    np.testing.assert_allclose(chain.x, xs, atol=5e-4)
    for pose, k in zip(chain.poses, chain.side):
        assert abs(_tilt(triangle, pose, int(k))) < 0.02


def test_realisation_factory_per_throw(triangle):
    """A callable realisation builds each throw's arm motion from its ω (here the impulse: same orbit)."""
    arm = tm.Arm(h=-0.01, length=0.6, mu=0.8)
    a = tm.iterate(triangle, arm, (0.1, 1), [2.0, 3.0], model="engine")
    b = tm.iterate(triangle, arm, (0.1, 1), [2.0, 3.0], model="engine", realisation=lambda w: ImpulseThrow(w))
    assert list(a.x) == list(b.x) and a.poses == b.poses


def test_other_models_unchanged(triangle, arm):
    o = tm.iterate(triangle, arm, (0.1, 1), 4.0, n=5, model="paper")
    assert o.poses is None
    xs, ss = [0.1], [1]
    for _ in range(5):
        t = tm.throw(triangle, arm, xs[-1], ss[-1], 4.0, model="paper")
        xs.append(t.x)
        ss.append(t.side)
    assert list(o.x) == xs and list(o.side) == ss
    assert tm.Orbit.from_dict(o.to_dict()).poses is None


def test_engine_orbit_round_trips_poses(cavity_orbit):
    back = tm.Orbit.from_dict(cavity_orbit.to_dict())
    assert back.poses == cavity_orbit.poses


def test_a_dropped_part_is_thrown_from_where_it_fell(triangle):
    """iterate(state=DropResult) starts from the engine scene the drop left (its fixtures, its pose)."""
    from throwmap.experiments.drop import drop_part

    d = drop_part(triangle, ARM, 3, fixtures=FIXTURES, x_range=(0.05, 0.3))
    assert d.ok
    o = tm.iterate(triangle, ARM, d, [2.5, 2.5], model="engine")
    assert o.poses[0] == pytest.approx(d.pose, abs=0.0) and o.x[0] == d.x and o.side[0] == d.side
    first = simulate(d.scene, ImpulseThrow(2.5))
    assert o.outcomes[0].x == first.states[0][0] and tuple(first.poses[0]) == o.poses[1]
    assert tm.iterate(triangle, ARM, d.scene, [2.5, 2.5], model="engine").poses == o.poses
    with pytest.raises(tm.InvalidStateError, match="^state: an engine Scene is a start for model 'engine' only"):
        tm.iterate(triangle, ARM, d, [2.5], model="paper")
    with pytest.raises(tm.InvalidStateError, match="^fixtures: a start Scene brings its own"):
        tm.iterate(triangle, ARM, d, [2.5], model="engine", fixtures=FIXTURES)
    with pytest.raises(tm.InvalidStateError, match="^state: the engine Scene must hold this one part"):
        tm.iterate(tm.rectangle(0.08, 0.04), ARM, d, [2.5], model="engine")

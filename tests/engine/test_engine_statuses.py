"""Engine statuses agree with the analytic models' (issue 10, item 1: engine statuses, behind the joint).

ok means what :func:`throwmap.throw` accepts as a start: flat on a stable side with
both support vertices on the arm (−back < x + u_L, x + u_R ≤ L); a part over an
edge of the arm is behind_joint / off_end at once.
"""

import itertools
import math

import numpy as np
import pytest

from throwmap import Arm, throw
from throwmap.errors import InvalidStateError
from throwmap.engine import Placement, Scene, engine_run, simulate
from throwmap.system.catalogue import triangle_30_60_90
from throwmap.records.outcome import Status
from throwmap.system.starts import check_start, start_interval
from throwmap.system.pose import world_vertices

TRI = triangle_30_60_90()
ARM = Arm(h=-0.01, mu=1.5)


def _leaning_on_the_joint_corner(part, h):
    """A pose with one vertex on the surface at x > 0, a side on the corner (0, h), a vertex ≥ 20 mm below the surface behind it."""
    for a, b, c in itertools.permutations(range(len(part.w))):
        for phi in np.linspace(0.0, 2.0 * math.pi, 72, endpoint=False):
            rot = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
            wa, wb, wc = rot @ part.w[a], rot @ part.w[b], rot @ part.w[c]
            d = wb - wa
            if abs(d[1]) < 1e-9:
                continue
            s = (wc[1] - wa[1]) / d[1]
            if not 0.1 < s < 0.9:
                continue
            pose = (-(wa[0] + s * d[0]), h - wc[1], float(phi))
            v = world_vertices(part, pose)
            low = int(np.argmin(v[:, 1]))
            if v[c, 0] > 0.01 and 0.0 < pose[0] < v[c, 0] - 0.005 and v[low, 1] < h - 0.02 and v[low, 0] < 0.0:
                return pose
    raise AssertionError("no such pose")


def test_part_tilted_on_the_joint_corner_is_not_ok():
    """(a) Before: ok at x = 0.0356 m, tilt 0.195 rad, a vertex 22 mm below the surface — an x throw() refuses."""
    pose = _leaning_on_the_joint_corner(TRI, ARM.h)
    run = simulate(Scene(ARM, (Placement(TRI, pose=pose),)))
    assert run.status == Status.BEHIND_JOINT


def test_part_falling_behind_the_joint_is_behind_joint_at_once():
    """(b) Before: timeout after 10 s of exact-flight leaps; the escape is now checked after every leap."""
    assert throw(TRI, ARM, 0.1101, 2, 7.0, model="rigid_body").status == Status.BEHIND_JOINT
    run = engine_run(TRI, ARM, 0.1101, 2, 7.0)
    assert run.status == Status.BEHIND_JOINT
    assert run.t_end < 1.0


@pytest.mark.parametrize("x, side, omega", [(0.2, 1, 3.0), (0.2018, 1, 4.0), (0.2291, 0, 2.0), (0.2291, 0, 4.0),
                                            (0.2716, 2, 3.0), (0.2714, 2, 2.0)])
def test_part_over_the_arms_end_is_off_end_as_in_rigid_body(x, side, omega):
    """(c) Before: ok (resting over the end) or penetration (a vertex swung under the arm); rigid_body says off_end.
    Starts close to the arm's end that throw() still accepts (x + u_R ≤ length)."""
    arm = Arm(h=-0.01, mu=1.5, length=0.3)
    assert throw(TRI, arm, x, side, omega, model="rigid_body").status == Status.OFF_END
    assert engine_run(TRI, arm, x, side, omega).status == Status.OFF_END


@pytest.mark.parametrize("x, side", [(0.2714, 1), (0.3, 0), (0.2857, 0), (0.2857, 1)])
@pytest.mark.parametrize("model", ["rigid_body", "engine"])
def test_a_start_hanging_over_the_arms_end_is_refused_by_every_model(x, side, model):
    """One rule for starts and rests: the right support vertex must be on the arm (x + u_R ≤ length)."""
    arm = Arm(h=-0.01, mu=1.5, length=0.3)
    with pytest.raises(InvalidStateError, match="^x:"):
        throw(TRI, arm, x, side, 3.0, model=model)


@pytest.mark.slow
def test_every_ok_engine_result_is_a_start_throw_accepts():
    arm = Arm(h=-0.01, mu=1.5, length=0.3)
    n_ok = 0
    for side, x, omega in itertools.product((0, 1, 2), np.linspace(0.1, 0.3, 5), (2.0, 4.0, 6.0)):
        lo, hi = start_interval(TRI, arm, side)
        x = min(max(float(x), lo + 1e-3), hi)
        o = throw(TRI, arm, x, side, omega, model="engine")
        if o.status == Status.OK:
            n_ok += 1
            check_start(TRI, arm, o.x, o.side, 1.0)  # raises if refused
            assert o.x + TRI.uR[o.side] <= arm.length
    assert n_ok >= 10


# ------------------------------------------------------------------ the arm behind the joint (Arm.back)
def test_part_resting_across_the_joint_is_ok_when_the_arm_continues_behind_it():
    x = TRI.x_min(0) - 0.01  # left support vertex 1 cm behind the joint
    on = simulate(Scene(Arm(h=-0.01, mu=1.5, back=0.05), (Placement(TRI, x=x, side=0),)))
    assert on.status == Status.OK and on.states[0][0] == pytest.approx(x, abs=1e-5)
    off = simulate(Scene(Arm(h=-0.01, mu=1.5), (Placement(TRI, x=x, side=0),)))
    assert off.status == Status.BEHIND_JOINT


@pytest.mark.parametrize("x, omega", [(0.1492, 7.0), (0.1695, 5.0), (0.1797, 6.0)])
def test_landing_across_the_joint_agrees_with_rigid_body_for_back(x, omega):
    """Throws that land across the joint: behind_joint with back = 0, ok with back = 5 cm, engine as rigid_body."""
    for back in (0.0, 0.05):
        arm = Arm(h=-0.01, mu=1.5, back=back)
        r = throw(TRI, arm, x, 2, omega, model="rigid_body")
        e = throw(TRI, arm, x, 2, omega, model="engine")
        assert e.status == r.status == (Status.OK if back else Status.BEHIND_JOINT)
        if back:
            assert e.side == r.side and e.x == pytest.approx(r.x, abs=1e-3)

"""Arm.back: the arm's surface behind the joint (issue 10, item 1 "Behind the joint").

A contact at x ≤ −back is ``behind_joint``; back = 0 (the default) keeps the
paper's rule (any contact at x ≤ 0). The analytic models and the start check use it.
"""

import math

import numpy as np
import pytest

import throwmap as tm
from throwmap.errors import InvalidArmError, InvalidStateError
from throwmap.kernels import codes as C

ANALYTIC = ("paper", "rigid_body", "small_angle", "small_angle2")


def test_default_is_zero_and_values_are_floats():
    assert tm.Arm(h=-0.01).back == 0.0
    a = tm.Arm(h=-0.01, back=1)
    assert a.back == 1.0 and type(a.back) is float


@pytest.mark.parametrize("bad", [-0.01, math.inf, math.nan, "0.1", True, None])
def test_back_is_validated(bad):
    with pytest.raises(InvalidArmError) as e:
        tm.Arm(h=-0.01, back=bad)
    assert e.value.field == "arm.back"
    assert "\n" not in str(e.value)


def _across_joint(part):
    """A start on the first stable side with the left support vertex 4 mm behind the joint."""
    k = int(np.flatnonzero(part.stable)[0])
    return k, -float(part.uL[k]) - 0.004


@pytest.mark.parametrize("model", ANALYTIC)
@pytest.mark.parametrize("omega", [0.0, 0.5, 1.0])
def test_part_resting_across_the_joint(triangle, model, omega):
    """back > 0: a part resting across the joint is on the arm (ok); back = 0: it is behind the joint."""
    k, x0 = _across_joint(triangle)
    o = tm.throw(triangle, tm.Arm(h=-0.01, back=0.02), x0, k, omega, model=model)
    assert int(o.status) == C.OK, (model, omega, o.status)
    assert o.x + triangle.uL[o.side] > -0.02
    # back = 0: throw() refuses the start, and the model itself says behind_joint
    with pytest.raises(InvalidStateError) as e:
        tm.throw(triangle, tm.Arm(h=-0.01), x0, k, omega, model=model)
    assert e.value.field == "x"
    m = tm.get_model(model)
    xn, kn, st, _rec = m.throw_one(triangle, tm.System(tm.Arm(h=-0.01)), x0, k, omega, m.options_type())
    assert int(st) == C.BEHIND_JOINT, (model, omega)


@pytest.mark.parametrize("model", ANALYTIC)
def test_back_moves_the_start_bound_in_batches(triangle, model):
    k, x0 = _across_joint(triangle)
    b = tm.throw_batch(triangle, tm.Arm(h=-0.01, back=0.003), [x0, x0 + 0.002], k, 1.0, model=model,
                       on_invalid="status")
    assert b.status[0] == C.INVALID_START  # 4 mm behind the joint, the surface reaches 3 mm
    assert b.status[1] != C.INVALID_START  # 2 mm behind: on the arm


@pytest.mark.parametrize("model", ANALYTIC)
def test_back_zero_is_todays_rule(triangle, model):
    """With back = 0 the results are those of an Arm without the field set (same numbers)."""
    k = int(np.flatnonzero(triangle.stable)[0])
    x = np.linspace(-triangle.uL[k] + 1e-3, 0.5, 60)
    a = tm.throw_batch(triangle, tm.Arm(h=-0.01), x, k, 6.0, model=model)
    b = tm.throw_batch(triangle, tm.Arm(h=-0.01, back=0.0), x, k, 6.0, model=model)
    np.testing.assert_array_equal(a.x, b.x)
    np.testing.assert_array_equal(a.status, b.status)


@pytest.mark.parametrize("model", ["paper", "rigid_body"])
def test_more_surface_behind_the_joint_only_saves_throws(triangle, model):
    """A throw that ends behind the joint with back = 0 may end on the arm with back > 0, never the reverse
    for throws that never touch x < 0 (those are unchanged)."""
    k = int(np.flatnonzero(triangle.stable)[0])
    x = np.linspace(-triangle.uL[k] + 1e-3, 0.5, 80)
    a = tm.throw_batch(triangle, tm.Arm(h=-0.01), x, k, 7.0, model=model)
    b = tm.throw_batch(triangle, tm.Arm(h=-0.01, back=0.05), x, k, 7.0, model=model)
    same = a.status != C.BEHIND_JOINT
    np.testing.assert_array_equal(a.x[same], b.x[same])
    np.testing.assert_array_equal(a.status[same], b.status[same])

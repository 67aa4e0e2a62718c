"""Records that hold arrays compare by value: a record read back from its dict equals the one written."""

from dataclasses import replace

import numpy as np

import throwmap as tm
from throwmap.serial import same_value


def test_a_batch_read_back_equals_the_batch_written_and_a_changed_one_does_not():
    part, arm = tm.triangle_30_60_90(), tm.Arm(h=-0.01)
    b = tm.throw_batch(part, arm, np.array([0.2, 0.25, 0.9]), np.array([0, 0, 0]), np.array([4.0, 4.5, 4.0]),
                       "paper")
    back = type(b).from_dict(b.to_dict())
    assert back == b and not (back != b)
    x = b.x.copy()
    x[0] += 1e-9
    assert replace(b, x=x) != b
    assert replace(b, model="rigid_body") != b
    assert b != "not a batch"


def test_critical_points_read_back_equal_and_nan_equals_nan():
    part, arm = tm.triangle_30_60_90(), tm.Arm(h=-0.01)
    cp = tm.critical_points(part, arm, 4.5, "paper")
    assert type(cp).from_dict(cp.to_dict()) == cp
    k = next(iter(cp.r))
    assert replace(cp, r={**cp.r, k: cp.r[k] + 1e-6}) != cp


def test_same_value_rules():
    assert same_value(np.array([1.0, np.nan]), np.array([1.0, np.nan]))
    assert not same_value(np.array([1.0]), np.array([1.0, 1.0]))
    assert not same_value(np.array([1.0]), [1.0])
    assert same_value({"a": float("nan")}, {"a": float("nan")})
    assert not same_value((1, 2), [1, 2])

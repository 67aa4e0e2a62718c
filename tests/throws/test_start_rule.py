"""The start rule (both support vertices on the arm) and one side rule for single throws and batches."""

import math

import numpy as np
import pytest

import throwmap as tm
from throwmap.errors import InvalidStateError
from throwmap.records.outcome import Status
from throwmap.system.starts import check_start, start_interval

PART = tm.triangle_30_60_90(0.17)


@pytest.mark.parametrize("arm", [tm.Arm(h=-0.01, length=0.5), tm.Arm(h=-0.01, length=0.37, back=0.02),
                                 tm.Arm(h=-0.01, back=0.05)])
def test_start_interval_is_exactly_the_rest_rule(arm):
    """lo < x <= hi  <=>  -back < x + u_L and x + u_R <= length, at the interval's ends to the last double."""
    L = arm.length_or_inf
    for k in PART.stable_sides:
        lo, hi = start_interval(PART, arm, k)
        uL, uR = float(PART.uL[k]), float(PART.uR[k])
        assert not lo + uL > -arm.back and math.nextafter(lo, math.inf) + uL > -arm.back
        if arm.length is None:
            assert hi == math.inf
            continue
        assert hi + uR <= L and not math.nextafter(hi, math.inf) + uR <= L
        check_start(PART, arm, hi, k, 1.0)
        check_start(PART, arm, math.nextafter(lo, math.inf), k, 1.0)
        for bad in (math.nextafter(hi, math.inf), lo):
            with pytest.raises(InvalidStateError):
                check_start(PART, arm, bad, k, 1.0)


def test_overhanging_start_refused_single_and_batch():
    """The outsider's case: x = 0.49 on side 0 of a 0.5 m arm overhangs the end (x + u_R > 0.5)."""
    arm = tm.Arm(h=-0.01, length=0.5)
    k = 0
    assert 0.49 + float(PART.uR[k]) > 0.5
    with pytest.raises(InvalidStateError, match="right support vertex"):
        tm.throw(PART, arm, 0.49, k, 1e-6)
    with pytest.raises(InvalidStateError, match=r"x\[1\]"):
        tm.throw_batch(PART, arm, np.array([0.3, 0.49]), k, 1e-6)
    b = tm.throw_batch(PART, arm, np.array([0.3, 0.49]), k, 1e-6, on_invalid="status")
    assert [Status(s) for s in b.status] == [Status.OK, Status.INVALID_START]


def test_admissible_start_near_end_stays_put_at_tiny_omega():
    """A start 1 µm inside the interval's end, thrown at ω ≈ 0, rests where it was: ok, not off_end."""
    arm = tm.Arm(h=-0.01, length=0.5)
    for k in PART.stable_sides:
        _, hi = start_interval(PART, arm, k)
        for model in ("rigid_body", "paper", "small_angle"):
            o = tm.throw(PART, arm, hi - 1e-6, k, 1e-6, model=model)
            assert o.status == Status.OK and abs(o.x - (hi - 1e-6)) < 1e-9


@pytest.mark.parametrize("side", [np.array([1.0]), [True, False], True, 1.0, np.array([0.0, 1.0])])
def test_batch_side_rule_is_throws(side):
    """throw() refuses side 1.0 and True; so does throw_batch, for every element type."""
    with pytest.raises(InvalidStateError, match="side"):
        tm.throw(PART, tm.Arm(h=-0.01), 0.2, np.asarray(side).ravel()[0].item(), 4.0)
    with pytest.raises(InvalidStateError, match="side"):
        tm.throw_batch(PART, tm.Arm(h=-0.01), 0.2, side, 4.0)


def test_batch_integer_sides_accepted():
    b = tm.throw_batch(PART, tm.Arm(h=-0.01), 0.2, np.array([0, 1], dtype=np.int32), 4.0)
    for i, k in enumerate((0, 1)):
        o = tm.throw(PART, tm.Arm(h=-0.01), 0.2, k, 4.0)
        assert b.status[i] == o.status and b.side[i] == o.side

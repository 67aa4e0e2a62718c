"""Arms: validation and the paper's regime (Sec. III-D)."""

import math

import pytest

import throwmap as tm
from throwmap.errors import InvalidArmError


@pytest.mark.parametrize(
    "kwargs, field",
    [
        (dict(h=math.nan), "arm.h"),
        (dict(h=math.inf), "arm.h"),
        (dict(h=-0.01, g=0.0), "arm.g"),
        (dict(h=-0.01, g=-9.81), "arm.g"),
        (dict(h=-0.01, length=0.0), "arm.length"),
        (dict(h=-0.01, length=math.nan), "arm.length"),
        (dict(h="low"), "arm.h"),
    ],
)
def test_bad_arms(kwargs, field):
    with pytest.raises(InvalidArmError) as err:
        tm.Arm(**kwargs)
    assert err.value.field == field


def test_regime_warnings_name_the_lost_guarantee(triangle):
    assert tm.regime_problems(triangle, tm.Arm(h=-0.01)) == []
    with pytest.warns(tm.RegimeWarning, match="jogs are no longer guaranteed to move outward"):
        tm.throw(triangle, tm.Arm(h=0.01), 0.15, 0, 2.0, model="paper")
    with pytest.warns(tm.RegimeWarning, match="flips are no longer guaranteed to move inward"):
        tm.throw(triangle, tm.Arm(h=-0.03), 0.15, 0, 2.0, model="paper")

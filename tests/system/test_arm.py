"""Arms: validation and the paper's regime (Sec. III-D)."""

import math
import warnings

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


def _regime_warnings(call) -> list[str]:
    """The RegimeWarning messages ``call()`` issues, every one recorded (the filter ``always``: nothing merged)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        call()
    return [str(w.message) for w in caught if issubclass(w.category, tm.RegimeWarning)]


def test_a_limit_set_warns_a_lost_guarantee_once_however_many_throws(triangle):
    """limit_set throws the map hundreds of times on an arm with h ≥ 0: one warning for the call (it was one per
    throw batch: 1,213), and a second call warns again (the registry is the call's, not global)."""
    arm = tm.Arm(h=0.01)
    got = _regime_warnings(lambda: tm.limit_set(triangle, arm, 4.0, "paper", n_starts=4))
    assert got == ["h = 0.01 m ≥ 0: jogs are no longer guaranteed to move outward"]
    twice = _regime_warnings(lambda: [tm.limit_set(triangle, arm, 4.0, "paper", n_starts=4) for _ in range(2)])
    assert len(twice) == 2


def test_a_loop_of_throws_in_one_block_warns_each_cause_once(triangle):
    from throwmap.system.arm import regime_warnings_once

    def loop():
        with regime_warnings_once():
            for x in (0.12, 0.15, 0.18):
                for h in (0.01, -0.03):  # two causes: h ≥ 0, and h ≤ -min d
                    tm.throw(triangle, tm.Arm(h=h), x, 0, 2.0, model="paper")

    got = _regime_warnings(loop)
    assert len(got) == 2 and any("outward" in m for m in got) and any("inward" in m for m in got)
    assert len(_regime_warnings(lambda: tm.throw(triangle, tm.Arm(h=0.01), 0.15, 0, 2.0, model="paper"))) == 1

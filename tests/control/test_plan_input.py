"""plan_throws and reachability refuse bad input with one line naming the field, before any throw."""

import math

import pytest

import throwmap as tm
from throwmap.control.planner import plan_throws, reachability
from throwmap.errors import InvalidStateError

TRI = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01)


class _Counting:
    def __init__(self):
        self.n = 0


@pytest.fixture
def no_throws(monkeypatch):
    """Fails the test if any throw is made (the checks must come first)."""
    import throwmap.throws.throw as thr

    count = _Counting()
    real = thr.throw

    def counted(*a, **kw):
        count.n += 1
        return real(*a, **kw)

    monkeypatch.setattr(thr, "throw", counted)
    return count


@pytest.mark.parametrize("kw,field", [(dict(tol=0.0), "tol"), (dict(tol=-1e-6), "tol"),
                                      (dict(jog_omega_max=0.0), "jog_omega_max"),
                                      (dict(jog_omega_max=-2.0), "jog_omega_max"),
                                      (dict(omegas="4"), "omegas"), (dict(omegas=(4.0, 0.0)), "omegas"),
                                      (dict(x_max=1e5, arm=tm.Arm(h=-0.01, length=0.5)), "x_max"),
                                      (dict(x_max=math.nan), "x_max")])
def test_plan_throws_refuses_before_throwing(kw, field, no_throws):
    arm = kw.pop("arm", ARM)
    with pytest.raises(InvalidStateError, match=rf"^{field}: "):
        plan_throws(TRI, arm, 0.2, 0, 0.25, 1, model="paper", **kw)
    assert no_throws.n == 0


@pytest.mark.parametrize("omegas", [0.0, (0.0,), (), "4", math.nan])
def test_reachability_refuses_rates_that_do_not_throw(omegas):
    with pytest.raises(InvalidStateError, match=r"^omegas: "):
        reachability(TRI, ARM, 0.25, 1, omegas, "paper")


def test_reachability_refuses_a_nan_goal():
    with pytest.raises(InvalidStateError, match=r"^x_f: "):
        reachability(TRI, ARM, math.nan, 1, (5.0,), "paper")


def test_reachability_still_answers_a_good_question():
    r = reachability(TRI, ARM, 0.25, 0, (5.0,), "paper")
    assert set(r.per_omega) == {5.0}


def test_the_throw_counter_sees_a_plans_throws(no_throws):
    plan_throws(TRI, ARM, 0.2, 0, 0.25, 0, model="paper")
    assert no_throws.n > 0  # the fixture above would see a throw made before a refusal

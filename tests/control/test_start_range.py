"""The far end x_max of the starts a limit set is sought over: any x in (0, the arm's end], the end included; an
x_max of 0 is refused by the planner before any throw (also when the part is already on the goal side, where jogs
are tried before the limit set is sought)."""

import pytest

import throwmap as tm
import throwmap.throws.throw as thr
from throwmap.control.planner import plan_throws, reachability
from throwmap.errors import InvalidStateError

TRI = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01, length=0.5)


def test_x_max_at_the_arms_end_is_taken():
    r = reachability(TRI, ARM, 0.25, 0, (5.0,), "paper", x_max=0.5, n_starts=8)
    assert set(r.per_omega) == {5.0}


def test_x_max_zero_is_refused_before_any_throw(monkeypatch):
    thrown = []
    real = thr.throw
    monkeypatch.setattr(thr, "throw", lambda *a, **kw: thrown.append(1) or real(*a, **kw))
    with pytest.raises(InvalidStateError, match=r"^x_max: must be > 0 m"):
        plan_throws(TRI, ARM, 0.2, 0, 0.25, 0, model="paper", x_max=0.0)
    assert thrown == []

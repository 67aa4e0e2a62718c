"""The partial jog goes a share of the way to the end of the jog branch that lies towards x_f."""

import pytest

import throwmap as tm
from throwmap.control.inverse import inverse_jog
from throwmap.control.planner import JOG_SHARE, _partial_jog

TRI = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01)


def test_a_goal_beyond_the_jogs_reach_is_approached_along_the_branch_towards_it():
    x, k, x_f = 0.2, 0, 0.9
    lo, hi = inverse_jog(TRI, ARM, x, k, x, "paper", omega_max=10.0, tol=1e-9).reach
    assert hi < x_f and hi - lo > 1e-3  # the goal is out of the jogs' reach; the branch has two distinct ends
    w = _partial_jog(TRI, ARM, x, k, x_f, "paper", 10.0, 1e-6, {})
    assert w is not None
    out = tm.throw(TRI, ARM, x, k, w, "paper")
    assert out.side == k
    assert out.x == pytest.approx(x + JOG_SHARE * (hi - x), abs=1e-5)  # towards hi, the end on x_f's side

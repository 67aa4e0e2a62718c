"""Open-loop plans (paper Prop. 4.3): replayed forward, they reach the goal; unreachable goals say why."""

import pytest

import throwmap as tm
from throwmap.control.planner import plan_throws, reachability
from throwmap.errors import InvalidStateError

PART = tm.triangle_30_60_90()
ARM = tm.Arm(h=-0.01, mu=1.0)


@pytest.mark.parametrize("model", ["paper", "rigid_body"])
def test_plan_replayed_forward_reaches_the_goal(model):
    p = plan_throws(PART, ARM, 0.2, 0, 0.45, 1, omegas=(4.0,), model=model)
    assert p.reachable and p.error <= 1e-6
    x, k = 0.2, 0
    for s in p.steps:  # an independent replay with throw(): the plan's rates alone take the part there
        out = tm.throw(PART, ARM, x, k, s.omega, model)
        assert str(out.status) == "ok"
        x, k = out.x, out.side
    assert k == 1 and abs(x - 0.45) <= 1e-6
    phases = [s.phase for s in p.steps]
    assert "round" in phases and phases[-1] == "jog"  # Lemma 4.1 first, Lemma 4.2 last


def test_every_orbit_escapes_at_the_drafts_rate():
    # the canonical triangle at the draft's 5.6 rad/s: no orbit from x <= 0.6 m stays on the arm
    p = plan_throws(PART, ARM, 0.2, 0, 0.45, 1, omegas=(5.6,), model="rigid_body")
    assert not p.reachable and not p.steps
    assert "every orbit escapes" in p.explanation and "behind_joint" in p.explanation
    assert "x ≤ 0.6 m" in p.explanation  # the claim states its range


def test_goal_below_the_limit_set_is_unreachable_with_the_bound_named():
    r = reachability(PART, ARM, 0.2, 1, (4.0,), "rigid_body")
    ls = tm.limit_set(PART, ARM, 4.0, "rigid_body", n_starts=32)
    low = min(lo for a in ls.attractors for (k, lo, hi) in a.bands if k == 1)
    assert not r.reachable and r.per_omega[4.0][2] == pytest.approx(low)
    assert "is not below x_f" in r.explanation()


def test_goal_past_the_arms_end_is_refused_before_any_throw():
    arm = tm.Arm(h=-0.01, mu=1.0, length=0.5)
    p = plan_throws(PART, arm, 0.2, 0, 0.49, 1, omegas=(4.0,), model="rigid_body")
    assert not p.reachable and "overhang the arm's end" in p.explanation and not p.steps


def test_already_on_the_side_short_of_the_goal_needs_only_jogs():
    p = plan_throws(PART, ARM, 0.25, 0, 0.30, 0, omegas=(4.0,), model="rigid_body")
    assert p.reachable and {s.phase for s in p.steps} == {"jog"}
    assert "jogs only" in p.explanation


def test_bad_arguments_are_refused():
    with pytest.raises(InvalidStateError, match="omegas"):
        plan_throws(PART, ARM, 0.2, 0, 0.45, 1, omegas=(-1.0,), model="paper")
    with pytest.raises(InvalidStateError, match="max_throws"):
        plan_throws(PART, ARM, 0.2, 0, 0.45, 1, max_throws=0, model="paper")
    with pytest.raises(InvalidStateError, match="side_f"):
        plan_throws(PART, ARM, 0.2, 0, 0.45, 7, model="paper")


def test_jogs_alone_reach_a_goal_on_the_start_side_whatever_the_high_rate():
    # Prop. 4.3's screen is sufficient, not necessary: at 5.6 rad/s every orbit escapes, yet the goal is one jog away
    p = plan_throws(PART, ARM, 0.25, 0, 0.27, 0, omegas=(5.6,), model="rigid_body")
    assert p.reachable and [s.phase for s in p.steps] == ["jog"] and p.error <= 1e-6


def test_non_finite_goal_is_refused():
    with pytest.raises(InvalidStateError, match="x_f"):
        plan_throws(PART, ARM, 0.2, 0, float("nan"), 1, model="paper")

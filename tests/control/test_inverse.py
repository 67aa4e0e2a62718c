"""Inverse throws (paper Lemma 4.2): every answer is checked by a forward throw, and against a closed form."""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import throwmap as tm
from throwmap.control.inverse import inverse_jog, jog_rate, jog_size
from throwmap.errors import InvalidStateError

PART = tm.triangle_30_60_90()
ARM = tm.Arm(h=-0.01, mu=1.0)


@pytest.mark.parametrize("model", ["paper", "rigid_body", "small_angle2"])
def test_forward_throw_at_the_rate_lands_on_the_target(model):
    # the contract: ω from jog_rate, thrown forward, lands within 1 µm on the same side
    w = jog_rate(PART, ARM, 0.25, 0, 0.27, model)
    out = tm.throw(PART, ARM, 0.25, 0, w, model)
    assert out.status == tm.Status.OK and out.side == 0
    assert abs(out.x - 0.27) <= 1e-6


def test_small_angle_inverse_matches_its_closed_form():
    # the small-angle map is x0 + c ω² exactly (c from one forward throw): ω* = sqrt((x_f − x0)/c)
    c = tm.throw(PART, ARM, 0.3, 1, 1.0, "small_angle").x - 0.3
    target = 0.3 + 0.8 * (tm.throw(PART, ARM, 0.3, 1, 2.0, "small_angle").x - 0.3)
    r = inverse_jog(PART, ARM, 0.3, 1, target, "small_angle", omega_max=2.5, tol=1e-9)
    assert r.omega == pytest.approx(math.sqrt((target - 0.3) / c), rel=1e-6)
    assert r.monotone


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(x0=st.floats(0.16, 0.45), share=st.floats(0.02, 0.95), side=st.sampled_from([0, 1, 2]))
def test_random_targets_within_reach_are_hit(x0, share, side):
    # any target inside the branch's reach (measured by the search itself) is hit to 1 µm
    probe = inverse_jog(PART, ARM, x0, side, x0, "paper")
    lo, hi = probe.reach
    end = hi if hi - x0 >= x0 - lo else lo
    target = x0 + share * (end - x0)
    r = inverse_jog(PART, ARM, x0, side, target, "paper")
    out = tm.throw(PART, ARM, x0, side, r.omega, "paper")
    assert out.side == side and abs(out.x - target) <= 1e-6
    assert r.omega < probe.omega_flip or math.isinf(probe.omega_flip)


def test_monotone_flag_agrees_with_a_dense_scan():
    r = inverse_jog(PART, ARM, 0.3, 0, 0.32, "rigid_body")
    ws = np.linspace(0.05, 0.999 * r.omega_flip, 120)
    xs = tm.throw_batch(PART, ARM, 0.3, 0, ws, "rigid_body").x
    assert r.monotone == bool(np.all(np.diff(xs) > -1e-9))
    assert r.beyond.startswith("lands on side")  # beyond the branch the triangle flips


def test_unreachable_target_names_the_field_and_what_faster_throws_do():
    with pytest.raises(InvalidStateError) as e:
        jog_rate(PART, ARM, 0.3, 0, 0.5, "rigid_body")
    assert e.value.field == "x_target"
    assert "beyond the jogs' reach" in e.value.reason and "lands on side 1" in e.value.reason
    with pytest.raises(InvalidStateError, match="x_target"):
        jog_rate(PART, ARM, 0.3, 0, 0.29, "paper")  # behind the start: the paper's jogs only go outward


def test_bad_arguments_are_refused():
    for kw, field in ((dict(tol=0.0), "tol"), (dict(omega_max=-1.0), "omega_max"), (dict(n_grid=1), "n_grid"),
                      (dict(realisation="sinusoid"), "realisation")):
        with pytest.raises(InvalidStateError) as e:
            inverse_jog(PART, ARM, 0.3, 0, 0.31, "paper", **kw)
        assert e.value.field == field
    with pytest.raises(InvalidStateError, match="x_target"):
        jog_rate(PART, ARM, 0.3, 0, math.nan, "paper")


def test_jog_vanishes_near_the_joint():
    # erratum of Lemma 4.1's proof: no positive lower bound δ on the jog — on "paper" it shrinks to 0
    # as the support reaches the joint (x → x + u_L = 0), far below its size further out
    lo = float(-PART.uL[0])
    d = jog_size(PART, ARM, np.array([lo + 1e-4, lo + 1e-3, 0.2, 0.3]), 0, 3.0, "paper")
    assert 0 <= d[0] < d[1] < d[2] < d[3]
    assert d[0] < 0.01 * d[3]
    # rigid_body's slow jogs near the joint even go inward (the draft's ΔV_x > 0 assumes no slip/lift-off)
    assert jog_size(PART, ARM, np.array([lo + 1e-3]), 0, 3.0, "rigid_body")[0] < 0


@pytest.mark.slow
def test_engine_inverse_jog_checked_forward():
    # the engine's map: the rate found lands within 1 µm when thrown again (deterministic engine)
    r = inverse_jog(PART, ARM, 0.3, 0, 0.31, "engine", omega_max=6.0, n_grid=12)
    out = tm.throw(PART, ARM, 0.3, 0, r.omega, "engine")
    assert out.side == 0 and abs(out.x - 0.31) <= 1e-6


def test_first_rate_already_leaving_the_branch_ends_instead_of_halving_for_ever():
    # frictionless arm: any throw makes the part slide off; the branch is empty and the answer is a refusal
    with pytest.raises(InvalidStateError, match="x_target"):
        inverse_jog(PART, tm.Arm(h=-0.01, mu=0.0), 0.25, 0, 0.26, "rigid_body")


def test_a_large_omega_max_does_not_step_over_the_branch():
    # the first rate of a 48-point grid up to 500 rad/s lands back on side 0 on a later branch; the grid's
    # spacing cap keeps the first branch, whose answer is the default search's
    a = inverse_jog(PART, ARM, 0.25, 0, 0.26, "rigid_body")
    b = inverse_jog(PART, ARM, 0.25, 0, 0.26, "rigid_body", omega_max=500.0)
    assert b.omega == pytest.approx(a.omega, rel=1e-6) and b.omega_flip == pytest.approx(a.omega_flip, rel=1e-6)

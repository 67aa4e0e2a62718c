"""Models "small_angle" and "small_angle2" (Sec. IV–V, corrected) against closed forms and "paper"."""

import numpy as np
import pytest

import throwmap as tm
from throwmap.studies.compare import compare_models


def test_first_order_jog_is_the_corrected_lemma_4_1(triangle, arm):
    """Jog: x' = R − h ω t* = R − (2hω²/g)(R + u_L); the draft's Lemma 4.1 took the CM at impact instead."""
    g, h = arm.g, arm.h
    for s in triangle.stable_sides:
        uL, d = triangle.uL[s], triangle.d[s]
        for omega in (0.5, 1.0, 2.0):
            R = triangle.x_min(s) + 0.02
            o = tm.throw(triangle, arm, R, s, omega, model="small_angle")
            assert o.side == s
            t = 2 * omega * (R + uL) / g
            assert o.t_flight == pytest.approx(t, rel=1e-12)
            assert o.x == pytest.approx(R - 2 * h * omega**2 * (R + uL) / g, rel=1e-12)
            x_star = R - (h + d) * omega * t  # the draft's "new rest position": the CM at impact
            assert o.x - x_star == pytest.approx(d * omega * t, rel=1e-9)  # the pivot moved the CM by d φ*
            assert o.x - x_star > 0


def test_first_order_jog_map_stretches(triangle, arm):
    """Slope of the jog branch is 1 − 2hω²/g > 1 for h < 0."""
    omega = 1.5
    xs = np.linspace(triangle.x_min(0) + 0.01, triangle.x_min(0) + 0.05, 9)
    res = tm.throw_batch(triangle, arm, xs, 0, omega, model="small_angle")
    slope = np.polyfit(xs, res.x, 1)[0]
    assert slope == pytest.approx(1 - 2 * arm.h * omega**2 / arm.g, rel=1e-10)
    assert slope > 1


def test_flip_test_respects_the_sense_of_rotation(triangle, arm):
    """A post-impact spin toward side i (φ̇⁺ ≤ 0) is a jog whatever the energy."""
    xs = np.linspace(triangle.x_min(0), 0.6, 2000)[1:]
    res = tm.throw_batch(triangle, arm, xs, 0, 5.0, model="small_angle")
    back = res.record("W_POST") <= 0
    assert back.any()
    assert np.all(res.side[back & (res.status == 0)] == 0)


def test_energies_have_consistent_units(triangle, arm):
    """K = ½ m (ρ² + |r|²) φ̇⁺² and U = m g (y_cm − h): both in J, scale with m and g correctly."""
    heavy = tm.triangle_30_60_90(0.17, mass=0.5)
    a = tm.throw(triangle, arm, 0.15, 0, 2.0, model="small_angle")
    b = tm.throw(heavy, arm, 0.15, 0, 2.0, model="small_angle")
    assert b.kinetic_post == pytest.approx(10 * a.kinetic_post)
    assert b.potential_impact == pytest.approx(10 * a.potential_impact)
    rho2 = triangle.radius_of_gyration**2
    vx, vy, wp = a.v_post
    assert a.kinetic_post == pytest.approx(0.5 * triangle.mass * (vx**2 + vy**2 + rho2 * wp**2))


@pytest.mark.parametrize("model, phi_max, tol", [("small_angle", 0.004, 0.05), ("small_angle2", 0.1, 0.01)])
def test_small_angle_within_a_few_percent_of_paper_for_gentle_throws(canonical_part, arm, model, phi_max, tol):
    checked = 0
    for s in canonical_part.stable_sides:
        for omega in (0.3, 0.6, 1.0, 1.5):
            xs = np.linspace(canonical_part.x_min(s), canonical_part.x_min(s) + 0.3, 200)[1:]
            ref = tm.throw_batch(canonical_part, arm, xs, s, omega, model="paper")
            sa = tm.throw_batch(canonical_part, arm, xs, s, omega, model=model)
            gentle = (omega * ref.record("T_FLIGHT") < phi_max) & (ref.status == 0) & (ref.side == s)
            assert np.all(sa.side[gentle] == s)
            jog_ref = ref.x[gentle] - xs[gentle]
            jog_sa = sa.x[gentle] - xs[gentle]
            assert np.all(np.abs(jog_sa - jog_ref) <= tol * np.abs(jog_ref))
            checked += gentle.sum()
    assert checked > 50


def test_second_order_converges_faster_than_first(triangle, arm):
    comp = compare_models(triangle, arm, omegas=(0.5, 1.0, 2.0), n_x=60)
    by = {(r["model"], r["omega"]): r for r in comp.rows}
    for om in (0.5, 1.0, 2.0):
        assert by[("small_angle2", om)]["jog_rel_err_median"] < 0.2 * by[("small_angle", om)]["jog_rel_err_median"]
    # error grows with ω for the first-order model
    errs = [by[("small_angle", om)]["jog_rel_err_median"] for om in (0.5, 1.0, 2.0)]
    assert errs == sorted(errs)
    assert "small_angle2" in comp.table()

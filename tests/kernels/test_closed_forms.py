"""Checks added by the mutation pass (tools/mutants.py) where the kernel tests let a slip through.

Each test names the mutant(s) it kills. They compare a kernel with a closed form or an
independent computation (dense sampling with exact trigonometry, scipy's Carlson
integral, energy conservation along a swing), never with copied outputs.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.special import elliprf

import throwmap as tm
from throwmap.kernels import codes as C
from throwmap.kernels.rigid_body.landing import flat_slide
from throwmap.kernels.rigid_body.swing import carlson_rf
from throwmap.kernels.roll import _check_arc, pivot_swing, reach_end, rocking_rest, turn_back

G = 9.81


def _record():
    rec = np.zeros(C.NREC)
    rec[C.N_MIN] = math.inf
    return rec


def _normal_and_friction(th, E, ell, I, g):
    """Pivot forces in units of m g at angle θ (exact trig): N = 1 − k + 3k s² − 2k e s, F = k cos θ (3s − 2e)."""
    k = ell * ell / I
    e = E / (g * ell)
    s = np.sin(th)
    return 1.0 - k + 3.0 * k * s * s - 2.0 * k * e * s, k * np.cos(th) * (3.0 * s - 2.0 * e)


ARC = dict(th1=0.2, th2=1.3, ell=0.08, rho2=0.08 ** 2)  # k = ℓ²/(ρ² + ℓ²) = 1/2


@pytest.mark.parametrize("e", [0.9, 1.5, 2.1])
def test_arc_normal_force_minimum_is_the_exact_minimum_over_the_arc(e):
    """K19: N's minimum over the arc (at s = e/3 when inside) equals a dense exact-trig search."""
    a = ARC
    I = a["rho2"] + a["ell"] ** 2
    E = e * G * a["ell"]
    rec = _record()
    _check_arc(a["th1"], a["th2"], E, a["ell"], I, G, 64, rec)
    N, _ = _normal_and_friction(np.linspace(a["th1"], a["th2"], 200_001), E, a["ell"], I, G)
    assert rec[C.N_MIN] == pytest.approx(N.min(), abs=1e-9)


@pytest.mark.parametrize("preset", [0.0, 0.9])
def test_arc_friction_ratio_is_the_largest_sampled_ratio(preset):
    """K20, K21: MU_MAX is max |F|/N over the n equally spaced arc samples, also when a lower record
    was already set (the skip bound must be an upper bound of every sample)."""
    a = ARC
    I = a["rho2"] + a["ell"] ** 2
    E = 1.5 * G * a["ell"]
    n = 64
    th = np.linspace(a["th1"], a["th2"], n)
    N, F = _normal_and_friction(th, E, a["ell"], I, G)
    assert np.all(N > 0)
    want = np.max(np.abs(F) / N)
    rec = _record()
    rec[C.MU_MAX] = preset * want
    _check_arc(a["th1"], a["th2"], E, a["ell"], I, G, n, rec)
    assert rec[C.MU_MAX] == pytest.approx(want, rel=1e-9)


@pytest.mark.parametrize("dirn", [1, -1])
def test_turning_angle_is_where_the_energy_is_all_potential_on_the_side_the_swing_came_from(dirn):
    """K23: a swing below its barrier turns at g ℓ sin θ = E, before the peak θ = π/2 in its direction."""
    ell, E = 0.07, 0.6 * G * 0.07
    th = turn_back(E, G, ell, dirn)
    assert G * ell * math.sin(th) == pytest.approx(E, rel=1e-12)
    assert (th < 0.5 * math.pi) if dirn > 0 else (th > 0.5 * math.pi)


def test_reach_end_needs_the_energy_of_a_higher_end():
    """K22: with no peak ahead, an end higher than the start is reached only with E above its height."""
    ell, th, tb, ta = 0.07, 0.3, 1.2, 0.1
    top = G * ell * math.sin(tb)
    assert not reach_end(th, 1, ta, tb, top * (1 - 1e-6), G, ell)
    assert reach_end(th, 1, ta, tb, top * (1 + 1e-6), G, ell)
    # downhill to the end: reached from rest (E = potential at the start)
    assert reach_end(2.0, 1, 1.7, 2.8, G * ell * math.sin(2.0), G, ell)


@pytest.mark.parametrize("theta, thdot", [(0.4, 3.0), (0.4, 8.0), (2.5, -3.0), (1.0, -0.5), (2.0, 0.2)])
def test_pivot_swing_conserves_energy_up_to_its_landing(theta, thdot):
    """K24: the rate on arrival satisfies ½ I θ̇² + g ℓ sin θ_end = E (the compound pendulum's energy)."""
    ell, rho2 = 0.07, 0.05 ** 2
    I = rho2 + ell * ell
    ta, tb = 0.35, 2.6
    rec = _record()
    E, end, land_dir, _, w_end = pivot_swing(theta, thdot, ta, tb, ell, I, G, 16, rec)
    assert E == pytest.approx(0.5 * I * thdot ** 2 + G * ell * math.sin(theta), rel=1e-12)
    assert 0.5 * I * w_end ** 2 + G * ell * math.sin(end) == pytest.approx(E, rel=1e-9)
    assert np.sign(w_end) in (0.0, float(land_dir))


def test_rocking_rest_needs_energy_below_both_topple_barriers():
    """K27: rest only when K < g (min(ℓ_A, ℓ_B) − d); between the two barriers the part can still topple."""
    lA, lB, d = 0.06, 0.09, 0.03
    low, high = G * (lA - d), G * (lB - d)
    assert rocking_rest(0.5 * low, lA, lB, d, G)
    assert not rocking_rest(0.5 * (low + high), lA, lB, d, G)
    assert not rocking_rest(0.5 * (low + high), lB, lA, d, G)


def test_flat_slide_stops_where_coulomb_says():
    """K46: a flat slide from speed v decelerates at μ g: distance v²/(2μg), time |v|/(μg), either sense."""
    mu = 0.4
    for v in (0.3, -0.7):
        rec = np.zeros(C.NREC)
        x, t = flat_slide(0.25, v, 1.0, mu, G, 0.0, 0.0, np.empty((0, 4)), np.zeros(8), rec)
        assert x == pytest.approx(0.25 + math.copysign(v * v / (2 * mu * G), v), rel=1e-12)
        assert t == pytest.approx(1.0 + abs(v) / (mu * G), rel=1e-12)
        assert rec[C.SLIP_DISTANCE] == pytest.approx(v * v / (2 * mu * G), rel=1e-12)


@pytest.mark.parametrize("xyz", [(0.0, 1.0, 2.0), (1.0, 1.0, 1.0), (0.2, 3.0, 7.5), (1e-3, 0.5, 0.5), (2.0, 9.0, 0.1)])
def test_carlson_rf_matches_scipy(xyz):
    """K53: R_F by duplication and its series is accurate to ~1e-15 (scipy.special.elliprf as reference)."""
    assert carlson_rf(*xyz) == pytest.approx(float(elliprf(*xyz)), rel=1e-14)


@pytest.fixture(scope="module")
def part():
    return tm.triangle_30_60_90(0.17)


@pytest.mark.parametrize("model", ["paper", "rigid_body"])
def test_impact_friction_ratios_are_non_negative_and_bound_the_first_impulse(part, model):
    """K16, K45: friction ratios are |J_t|/J_n ≥ 0; the largest over the throw is at least the first impact's."""
    arm = tm.Arm(h=-0.01, mu=1.0 if model == "rigid_body" else math.inf)
    seen_neg = seen_pos = False
    for s in part.stable_sides:
        for x in np.linspace(part.x_min(s) + 0.01, 0.4, 9):
            for w in (2.0, 4.0, 6.0):
                o = tm.throw(part, arm, float(x), s, w, model=model)
                jt, jn = o.impulse
                if not jn > 0:
                    continue
                seen_neg |= jt < 0
                seen_pos |= jt > 0
                assert o.friction_ratio_max >= abs(jt) / jn * (1 - 1e-12)
                if model == "paper":
                    assert o.friction_ratio_impact == pytest.approx(abs(jt) / jn, rel=1e-12)
                assert o.friction_ratio_impact >= 0 and o.friction_ratio_max >= 0
    assert seen_neg and seen_pos  # both senses of the tangential impulse were exercised


def test_impact_cap_allows_exactly_max_impacts(part):
    """K30: a throw needing N impacts rests with max_impacts = N and is refused (no_rest) with N − 1."""
    arm = tm.Arm(h=-0.01)
    o = tm.throw(part, arm, 0.3, part.stable_sides[0], 5.0, model="paper")
    assert o.ok and o.n_impacts >= 2
    capped = tm.throw(part, arm, 0.3, part.stable_sides[0], 5.0, model="paper", max_impacts=o.n_impacts)
    assert capped.ok and capped.x == o.x and capped.n_impacts == o.n_impacts
    short = tm.throw(part, arm, 0.3, part.stable_sides[0], 5.0, model="paper", max_impacts=o.n_impacts - 1)
    assert short.status.label == "no_rest"


@pytest.mark.parametrize("model", ["small_angle", "small_angle2"])
def test_small_angle_rest_puts_the_contact_vertex_where_it_touched(part, model):
    """K35: Sec. V-A step 8: a jog rests with its left vertex at the contact x (x' = P_x − u_L); a flip over
    the contact vertex onto the next side (all of the triangle's sides are stable) rests with that vertex,
    now the side's right vertex, at P_x (x' = P_x − u_R)."""
    assert all(part.stable)
    arm = tm.Arm(h=-0.01)
    flips = jogs = 0
    for s in part.stable_sides:
        for x in np.linspace(part.x_min(s) + 0.005, 0.3, 12):
            for w in (1.0, 2.0, 3.0, 4.0, 5.0):
                o = tm.throw(part, arm, float(x), s, w, model=model)
                if not o.ok:
                    continue
                if o.n_flips:
                    flips += 1
                    assert o.side == (s + 1) % part.n_sides
                    assert o.x + part.uR[o.side] == pytest.approx(o.contact_x, abs=1e-12)
                else:
                    jogs += 1
                    assert o.x + part.uL[o.side] == pytest.approx(o.contact_x, abs=1e-12)
    assert flips and jogs


@pytest.mark.parametrize("theta, mu", [(2.0, 0.05), (2.0, 1.0), (0.3, 0.05), (0.3, 1.0), (2.6, 0.3)])
def test_contact_mode_sticks_exactly_inside_the_friction_cone(theta, mu):
    """K51: from rest on a pivot (θ̇ = 0, v_A = 0) the contact sticks iff N > 0 and |F| ≤ μ N, with the
    compound pendulum's forces N = 1 − k + k s², F = k s cos θ (units m g; k = ℓ²/I, e = s at rest)."""
    from throwmap.kernels.rigid_body.modes import MODE_STICK
    from throwmap.kernels.rigid_body.slide import select_contact_mode

    ell, rho2 = 0.07, 0.07 ** 2  # k = 1/2
    k, s = 0.5, math.sin(theta)
    N, F = 1.0 - k + k * s * s, k * s * math.cos(theta)
    mode, _ = select_contact_mode(theta, 0.0, 0.0, ell, rho2, G, mu, mu, False)
    assert (mode == MODE_STICK) == (N > 0 and abs(F) <= mu * N)


@pytest.mark.parametrize("theta", [0.3, 2.0, 2.6])
def test_sticking_phase_outside_the_friction_cone_slips_at_once(theta):
    """K52: a sticking phase entered with |F| > μ N (either sign of F) ends at once with the slip event."""
    from throwmap.kernels.rigid_body.modes import EV_SLIP
    from throwmap.kernels.rigid_body.stick import pivot_stick

    ell = 0.07
    I = 2 * ell * ell  # k = 1/2
    k, s, mu = 0.5, math.sin(theta), 0.05
    N, F = 1.0 - k + k * s * s, k * s * math.cos(theta)
    assert N > 0 and abs(F) > mu * N  # the case this test is about
    ev, th, _, t = pivot_stick(theta, 0.0, 0.25, 2.9, ell, I, G, mu, 0.0, 1000, 0.2, 0.0, 0.0, np.empty((0, 4)),
                               np.zeros(8), _record())
    assert ev == EV_SLIP and th == theta and t == 0.0

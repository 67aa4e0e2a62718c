"""Model "rigid_body" (kernels/rigid_body/): agreement with "paper", physics invariants, guards."""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp
from scipy.spatial import ConvexHull

import throwmap as tm
from throwmap.kernels import codes as C
from throwmap.kernels import rigid_body as RB
from throwmap.kernels.impact import plastic_impact
from throwmap.kernels.paper import throw_one

TOL = 1e-14
MAX_ITER = 100_000
MAX_EVENTS = 10_000
VALID = {C.OK, C.BEHIND_JOINT, C.OFF_END, C.NO_REST, C.NO_CONTACT, C.INCONSISTENT}


def records(part, arm, mu):
    """The kernels' records of ``part`` on ``arm`` at α = 0 with Coulomb ``mu``, the Routh law, no wall."""
    return (RB.part_arrays(part), RB.arm_arrays(arm.h, arm.g, 0.0, arm.length_or_inf, arm.back, mu, RB.LAW_ROUTH),
            RB.run_limits(TOL, MAX_ITER, MAX_EVENTS))


def rb(part, arm, x, k, om, mu, m=0, dt=0.005):
    rec = np.empty(C.NREC)
    traj = np.empty((m, 4))
    x1, k1, st_ = RB.throw_one_rigid_body(x, k, om, *records(part, arm, mu), rec, traj, dt)
    return x1, k1, st_, rec, traj


def paper(part, arm, x, k, om):
    rec = np.empty(C.NREC)
    x1, k1, st_ = throw_one(x, k, om, arm.h, arm.g, 0.0, arm.length_or_inf, arm.back, part.radius_of_gyration**2, part.w,
                            part.beta, part.d, part.uL, part.uR, part.ell, part.stable, TOL, MAX_ITER, MAX_EVENTS,
                            16, rec)
    return x1, k1, st_, rec


def starts(part, n, seed, om_lo=3.0, om_hi=7.0, x_hi=0.4):
    rng = np.random.default_rng(seed)
    ss = np.asarray(part.stable_sides)
    k = ss[rng.integers(0, len(ss), n)]
    x = -part.uL[k] + 1e-3 + rng.random(n) * (x_hi + part.uL[k] - 1e-3)
    om = rng.uniform(om_lo, om_hi, n)
    return x, k.astype(np.int64), om


def batch(part, arm, x, k, om, mu):
    n = len(x)
    xo = np.empty(n)
    so = np.empty(n, np.int64)
    sto = np.empty(n, np.int64)
    rec = np.empty((n, C.NREC))
    RB.throw_many_rigid_body(x, k, om, np.ones(n, bool), *records(part, arm, mu), xo, so, sto, rec)
    return xo, so, sto, rec


# ----------------------------------------------------------------------------- agreement with "paper"
def test_agrees_with_paper_where_its_assumptions_hold(canonical_part, arm):
    """μ = ∞, no lift-off and no pulling impulse in the paper record: same (x, side, status) to 1e-9 m."""
    part = canonical_part
    x, k, om = starts(part, 300, 1)
    compared = 0
    for xi, ki, oi in zip(x, k, om):
        xp, kp, sp, rp = paper(part, arm, float(xi), int(ki), float(oi))
        if not (rp[C.N_MIN] > 0.0 and rp[C.N_PULL] == 0.0):
            continue
        xr, kr, sr, rr, _ = rb(part, arm, float(xi), int(ki), float(oi), math.inf)
        compared += 1
        assert (kr, sr) == (kp, sp)
        assert xr == pytest.approx(xp, abs=1e-9)
        assert rr[C.N_IMPACTS] == rp[C.N_IMPACTS]
        assert rr[C.N_FLIPS] == rp[C.N_FLIPS]
        assert rr[C.N_LIFTOFFS] == 0 and rr[C.N_SLIPS] == 0
        for q in (C.T_FLIGHT, C.CONTACT_X, C.VX_POST, C.VY_POST, C.W_POST, C.K_POST):
            assert rr[q] == pytest.approx(rp[q], rel=1e-9, abs=1e-12)
    assert compared > 30


def test_batch_equals_single(triangle, arm):
    x, k, om = starts(triangle, 200, 2)
    xo, so, sto, rec = batch(triangle, arm, x, k, om, 0.8)
    for i in range(0, 200, 7):
        x1, k1, s1, r1, _ = rb(triangle, arm, float(x[i]), int(k[i]), float(om[i]), 0.8)
        assert (x1, k1, s1) == (xo[i], so[i], sto[i])
        np.testing.assert_array_equal(r1, rec[i])


# ----------------------------------------------------------------------------- energy and friction invariants
@pytest.mark.parametrize("mu", [math.inf, 1.5, 0.5, 0.2])
def test_energy_and_friction_cone(triangle, arm, mu):
    """Flight conserves energy; impacts never add kinetic energy; every impulse and force is in the cone."""
    x, k, om = starts(triangle, 2000, 3)
    _, _, sto, rec = batch(triangle, arm, x, k, om, mu)
    assert set(np.unique(sto)) <= VALID
    e = rec[:, C.E_RELEASE]
    np.testing.assert_allclose(rec[:, C.K_PRE] + rec[:, C.U_IMPACT], e, rtol=1e-9)
    assert np.all(rec[:, C.K_MAX_IMPACT_GAIN] <= 1e-9 * e)
    assert np.all(rec[:, C.K_POST] <= rec[:, C.K_PRE] * (1 + 1e-12))
    if math.isfinite(mu):
        assert np.all(rec[:, C.MU_MAX] <= mu * (1 + 1e-9))
    assert np.all(rec[:, C.PENETRATION_MAX] == 0.0)
    ok = sto == C.OK
    assert ok.any() and np.all(np.isfinite(rec[ok, C.T_REST]) & (rec[ok, C.T_REST] > rec[ok, C.T_FLIGHT]))
    assert np.all(rec[:, C.SLIP_DISTANCE] >= 0.0)


@pytest.mark.parametrize("phase", ["pivot_stick", "pivot_stick_exact"])
def test_pivot_stick_conserves_energy_and_matches_solve_ivp(triangle, phase):
    """A sticking swing (RK4 + bisection, or closed form) vs DOP853 for the landing time; energy exact at the event."""
    part = triangle
    rho2 = part.radius_of_gyration**2
    j = 0
    lj = part.ell[j]
    I = rho2 + lj * lj
    n = len(part.d)
    ta = math.atan2(part.d[(j - 1) % n], -part.uL[(j - 1) % n])
    tb = math.atan2(part.d[j], -part.uR[j])
    th0 = 0.5 * (ta + tb)
    for w0 in (-4.0, -1.0, 1.0, 3.0):
        rec = np.zeros(C.NREC)
        rec[C.N_MIN] = math.inf
        ev, th, w, t = getattr(RB, phase)(th0, w0, ta, tb, lj, I, 9.81, math.inf, 0.0, MAX_ITER, 0.0, 0.0, 0.0,
                                          np.empty((0, 4)), np.zeros(3), rec)
        assert ev in (RB.EV_LAND_A, RB.EV_LAND_B, RB.EV_LIFT_OFF)
        E0 = 0.5 * I * w0 * w0 + 9.81 * lj * math.sin(th0)
        assert 0.5 * I * w * w + 9.81 * lj * math.sin(th) == pytest.approx(E0, rel=1e-12)

        def land(tt, y):
            return (y[0] - ta) * (y[0] - tb)

        land.terminal = True
        sol = solve_ivp(lambda tt, y: [y[1], -9.81 * lj * math.cos(y[0]) / I], (0, 20), [th0, w0], method="DOP853",
                        rtol=1e-12, atol=1e-13, events=land)
        if ev != RB.EV_LIFT_OFF:
            assert t == pytest.approx(sol.t_events[0][0], rel=1e-7)


def test_slide_phase_matches_solve_ivp(triangle):
    """PIVOT_SLIDE (RK4 + bisection) against scipy solve_ivp of the same ODE, to the first guard."""
    part = triangle
    rho2 = part.radius_of_gyration**2
    g = 9.81
    j = 0
    lj = part.ell[j]
    n = len(part.d)
    ta = math.atan2(part.d[(j - 1) % n], -part.uL[(j - 1) % n])
    tb = math.atan2(part.d[j], -part.uR[j])
    for mu, va0, w0 in ((0.3, 0.4, 2.0), (0.2, -0.3, -1.5), (0.5, 0.2, 0.5)):
        sig = 1.0 if va0 > 0 else -1.0
        th0 = 0.5 * (ta + tb)
        rec = np.zeros(C.NREC)
        rec[C.N_MIN] = math.inf
        ev, xa, th, va, w, t = RB.pivot_slide(0.1, th0, va0, w0, sig, ta, tb, lj, rho2, g, mu, math.inf, 0.0, 0.0,
                                              MAX_ITER, 0.0, 0.0, np.empty((0, 4)), np.zeros(3), rec)
        assert ev in (RB.EV_STICK, RB.EV_LAND_A, RB.EV_LAND_B, RB.EV_LIFT_OFF)

        def rhs(tt, y):  # independent writing of the same equations (Newton–Euler, ÿ_A = 0)
            x_a, thv, v, wv = y
            c, s = math.cos(thv), math.sin(thv)
            # unknowns N, thdd, xdd: ρ² θ̈ = −ℓ c N + ℓ s F, F = −μσN; ℓ(cθ̈ − sθ̇²) = N − g
            F_over_N = -mu * sig
            A = np.array([[rho2, lj * c - lj * s * F_over_N, 0.0], [lj * c, -1.0, 0.0], [0.0, -F_over_N, 1.0]])
            A[2] = [-lj * s, -F_over_N, 1.0]  # ẍ_A − ℓ s θ̈ − F = ℓ c θ̇²
            b = np.array([0.0, -g + lj * s * wv * wv, lj * c * wv * wv])
            thdd, N, xdd = np.linalg.solve(A, b)
            return [v, wv, xdd, thdd]

        def stick(tt, y):
            return sig * y[2]

        def land_a(tt, y):
            return y[1] - ta

        def land_b(tt, y):
            return tb - y[1]

        def lift(tt, y):
            return g - lj * math.sin(y[1]) * y[3] ** 2

        for f in (stick, land_a, land_b, lift):
            f.terminal = True
            f.direction = -1
        sol = solve_ivp(rhs, (0, 20), [0.1, th0, va0, w0], method="DOP853", rtol=1e-12, atol=1e-13,
                        events=[stick, land_a, land_b, lift])
        assert sol.status == 1
        assert t == pytest.approx(sol.t[-1], rel=1e-6)
        np.testing.assert_allclose([xa, th, w], sol.y[[0, 1, 3], -1], rtol=1e-6, atol=1e-8)


# ----------------------------------------------------------------------------- impact reset
@given(vx=st.floats(-2, 2), vy=st.floats(-3, -0.05), w=st.floats(-8, 8), a=st.floats(0.0, 2 * math.pi),
       ell=st.floats(0.01, 0.1), mu=st.sampled_from([0.1, 0.5, 1.0, 3.0, math.inf]))
@settings(max_examples=300, deadline=None)
def test_coulomb_impact_in_cone_and_dissipative(vx, vy, w, a, ell, mu):
    rho2 = 0.03**2
    rx, ry = ell * math.cos(a), -abs(ell * math.sin(a)) - 1e-3
    un = vy + w * rx
    vxp, vyp, wp, pt, pn, kind, jt0, jn0 = RB.coulomb_impact(vx, vy, w, rx, ry, rho2, mu)
    k0 = 0.5 * (vx * vx + vy * vy + rho2 * w * w)
    k1 = 0.5 * (vxp * vxp + vyp * vyp + rho2 * wp * wp)
    if un >= 0.0:
        assert kind == RB.IMP_SEPARATE and pn == 0.0
        return
    if kind == RB.IMP_INCONSISTENT:
        return
    assert k1 <= k0 * (1 + 1e-12) + 1e-15
    assert pn >= -1e-15
    assert abs(pt) <= mu * pn * (1 + 1e-9) + 1e-15 or (math.isinf(mu))
    un1 = vyp + wp * rx
    assert un1 >= -1e-9 * (abs(un) + 1)
    if jn0 >= 0 and abs(jt0) <= mu * jn0:
        ex = plastic_impact(vx, vy, w, rx, ry, rho2)
        assert (vxp, vyp, wp) == ex
        assert kind == RB.IMP_STICK


# ----------------------------------------------------------------------------- lift-off
@pytest.mark.parametrize("phase", ["pivot_stick", "pivot_stick_exact"])
def test_lift_off_exactly_where_normal_force_vanishes(triangle, arm, phase):
    """Canonical triangle, h = −0.01 m, ω 3–7 rad/s: paper's N_MIN < 0 flag vs the rigid-body guards.

    * With μ = ∞, the first pivot phase of every flip run with ``phase`` (RK4 or closed form) fires
      ``lift_off`` at an angle where N = 0 exactly, iff paper's first arc has N < 0.
    * With μ = 1.5, no throw whose paper record has N_MIN < 0 keeps sticking: it slips
      or lifts off (the sticking normal force would have to pull).
    """
    part = triangle
    rho2 = part.radius_of_gyration**2
    x, k, om = starts(part, 400, 4)
    n = len(part.d)
    flips = lift_paper = lift_stick = 0
    for xi, ki, oi in zip(x, k, om):
        xp, kp, sp, rp = paper(part, arm, float(xi), int(ki), float(oi))
        if rp[C.N_FLIPS] == 0 or rp[C.N_PULL] > 0:
            continue
        flips += 1
        j = int(rp[C.CONTACT_VERTEX])
        lj = part.ell[j]
        I = rho2 + lj * lj
        ta = math.atan2(part.d[(j - 1) % n], -part.uL[(j - 1) % n])
        tb = math.atan2(part.d[j], -part.uR[j])
        # pivot state after the first impact, from the record
        w1 = rp[C.W_POST]
        rx, ry = rp[C.VY_POST] / -w1, rp[C.VX_POST] / w1
        th = min(max(math.atan2(-ry, -rx), ta), tb)
        rec = np.zeros(C.NREC)
        rec[C.N_MIN] = math.inf
        ev, th1, wv, t = getattr(RB, phase)(th, w1, ta, tb, lj, I, arm.g, math.inf, 0.0, MAX_ITER, 0.0, 0.0, 0.0,
                                            np.empty((0, 4)), np.zeros(3), rec)
        if ev == RB.EV_LIFT_OFF:
            lift_stick += 1
            N, F = RB.stick_forces(th1, wv, lj, I, arm.g)
            if t > 0.0:
                assert abs(N) < 1e-9  # crossed zero during the swing: located exactly
            else:
                assert N <= 0.0  # the impact left it with N < 0: it hops at once
            assert rp[C.N_MIN] < 0.0
        if rp[C.N_MIN] < 0.0:
            lift_paper += 1
            _, _, sr, rr, _ = rb(part, arm, float(xi), int(ki), float(oi), 1.5)
            assert rr[C.N_SLIPS] + rr[C.N_LIFTOFFS] > 0
            assert rr[C.N_MIN] > -1e-9  # the rigid-body contact never pulls
    assert flips > 50
    assert lift_stick <= lift_paper
    assert lift_paper > 0.3 * flips  # "about two thirds of flips" lift off under the paper's assumptions


# ----------------------------------------------------------------------------- trajectories
@pytest.mark.parametrize("mu", [math.inf, 1.5, 0.3])
def test_trajectory_above_line_and_ends_at_rest(triangle, arm, mu):
    part = triangle
    x, k, om = starts(part, 20, 5)
    for xi, ki, oi in zip(x, k, om):
        x1, k1, s1, rec, traj = rb(part, arm, float(xi), int(ki), float(oi), mu, m=4000, dt=0.002)
        ns = RB.count_samples(traj)
        assert ns >= 3
        tr = traj[:ns]
        assert np.all(np.diff(tr[:, 0]) >= -1e-12)
        c, s = np.cos(tr[:, 3]), np.sin(tr[:, 3])
        vy = tr[:, 2, None] + s[:, None] * part.w[None, :, 0] + c[:, None] * part.w[None, :, 1]
        assert vy.min() >= arm.h - 1e-9
        if s1 == C.OK:
            assert tr[-1, 0] == pytest.approx(rec[C.T_REST])
            assert tr[-1, 1] == pytest.approx(x1, abs=1e-12)
            assert tr[-1, 2] == pytest.approx(arm.h + part.d[k1], abs=1e-12)
            assert math.remainder(tr[-1, 3] - part.beta[k1], 2 * math.pi) == pytest.approx(0.0, abs=1e-12)


# ----------------------------------------------------------------------------- random parts
@st.composite
def convex_parts(draw):
    n = draw(st.integers(3, 8))
    ang = sorted(draw(st.lists(st.floats(0, 2 * math.pi), min_size=n, max_size=n, unique=True)))
    rad = draw(st.lists(st.floats(0.02, 0.08), min_size=n, max_size=n))
    pts = np.array([(r * math.cos(a), r * math.sin(a)) for r, a in zip(rad, ang)])
    try:
        hull = ConvexHull(pts)
    except Exception:
        return None
    verts = pts[hull.vertices]
    try:
        return tm.Part.from_vertices([tuple(v) for v in verts], mass=0.05)
    except Exception:
        return None


@pytest.mark.slow
@given(part=convex_parts(), mu=st.sampled_from([0.2, 0.7, 2.0, math.inf]), seed=st.integers(0, 10**6))
@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
def test_random_convex_parts_finite_and_valid(part, mu, seed):
    if part is None:
        return
    arm = tm.Arm(h=-0.3 * part.min_d)
    x, k, om = starts(part, 20, seed, 1.0, 8.0, 0.3)
    xo, so, sto, rec = batch(part, arm, x, k, om, mu)
    assert set(np.unique(sto)) <= VALID
    assert np.all(np.isfinite(xo))
    assert np.all((so >= 0) & (so < part.n_sides))
    ok = sto == C.OK
    assert np.all(part.stable[so[ok]])
    assert np.all(rec[:, C.K_MAX_IMPACT_GAIN] <= 1e-9 * rec[:, C.E_RELEASE])
    if math.isfinite(mu):
        assert np.all(rec[:, C.MU_MAX] <= mu * (1 + 1e-9))

"""Model "rigid_body": the closed-form sticking phase (rigid_body/stick_exact.py, swing.py) against the RK4 one."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad, solve_ivp
from scipy.special import elliprf

from throwmap.kernels import codes as C
from throwmap.kernels import rigid_body as RB
from throwmap.kernels.rigid_body.swing import carlson_rf, first_quartic_root, swing_time

G = 9.81
MAX_ITER = 100_000
MAX_EVENTS = 10_000


def pivot(part, j=0):
    """Pivot data of vertex j: ℓ, I, θa, θb."""
    rho2 = part.radius_of_gyration**2
    lj = part.ell[j]
    n = len(part.d)
    ta = math.atan2(part.d[(j - 1) % n], -part.uL[(j - 1) % n])
    tb = math.atan2(part.d[j], -part.uR[j])
    return lj, rho2 + lj * lj, ta, tb


def fresh_rec():
    rec = np.zeros(C.NREC)
    rec[C.N_MIN] = math.inf
    return rec


def run_phase(phase, th0, w0, ta, tb, lj, I, mu):
    rec = fresh_rec()
    ev, th, w, t = phase(th0, w0, ta, tb, lj, I, G, mu, 0.0, MAX_ITER, 0.0, 0.0, 0.0, np.empty((0, 4)), np.zeros(3),
                         rec)
    return ev, th, w, t, rec


# ----------------------------------------------------------------------------- building blocks
@given(x=st.floats(0.0, 10.0), y=st.floats(1e-6, 10.0), z=st.floats(1e-6, 10.0))
@settings(max_examples=200, deadline=None)
def test_carlson_rf_matches_scipy(x, y, z):
    assert carlson_rf(x, y, z) == pytest.approx(elliprf(x, y, z), rel=2e-15)


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")  # quad at the turning point
@pytest.mark.parametrize("th1, th2, e", [(0.5, 1.0, 0.95), (0.5, math.asin(0.95), 0.95), (2.0, math.pi - math.asin(0.92), 0.92),
                                         (0.3, 2.5, 1.2), (0.3, 2.5, 1.0001), (1.0, 1.4, 1.0 + 1e-7), (1.2, 0.9, 0.99),
                                         (2.9, 2.2, 1.5)])
def test_swing_time_is_the_quadrature_of_dtheta_over_thetadot(th1, th2, e):
    c = 9.81 * 0.07 / (0.03**2 + 0.07**2)
    lo, hi = sorted((th1, th2))
    ref = quad(lambda th: 1.0 / math.sqrt(max(2 * c * (e - math.sin(th)), 1e-300)), lo, hi, limit=400,
               epsabs=1e-14, epsrel=1e-12)[0]
    assert swing_time(th1, th2, e, c) == pytest.approx(ref, rel=1e-9)


@given(roots=st.lists(st.floats(-0.5, 1.5), min_size=4, max_size=4), lead=st.floats(0.1, 10.0),
       a=st.floats(0.0, 1.0), b=st.floats(0.0, 1.0))
@settings(max_examples=300, deadline=None)
def test_first_quartic_root_is_the_first_sign_change(roots, lead, a, b):
    """P(s) = lead ∏(s − r_i) + δ: the returned s has P ≤ 0 and a dense grid finds no P ≤ 0 before it."""
    p = np.poly(roots)[::-1] * lead  # p0 … p4
    p[0] += 1e-3 * lead
    poly = np.polynomial.Polynomial(p)
    if poly(a) <= 0.0:
        return
    s = first_quartic_root(a, b, *p)
    grid = np.linspace(a, b, 20001)
    neg = np.nonzero(poly(grid) <= 0.0)[0]
    if math.isnan(s):
        assert neg.size == 0 or np.min(np.abs(poly(grid))) < 1e-12 * lead
        return
    assert poly(s) <= 1e-12 * lead
    if neg.size:
        first = grid[neg[0]]
        assert abs(s - a) <= abs(first - a) + 1e-4 * abs(b - a) + 1e-12
    if s != a:
        assert poly(a + 0.999999 * (s - a)) > -1e-12 * lead


# ----------------------------------------------------------------------------- the phase: guards located exactly
@pytest.mark.parametrize("mu", [math.inf, 1.5, 0.5, 0.2])
def test_exact_phase_matches_solve_ivp_and_conserves_energy(triangle, mu):
    """Event angle, rate and time against DOP853 with the same guards as event functions."""
    lj, I, ta, tb = pivot(triangle)
    k = lj * lj / I
    compared = 0
    for th0 in np.linspace(ta + 0.05, tb - 0.05, 5):
        for w0 in (-6.0, -3.0, -1.0, 0.0, 1.0, 3.0, 6.0):
            E0 = 0.5 * I * w0 * w0 + G * lj * math.sin(th0)
            e = E0 / (G * lj)

            def forces(y):
                s = math.sin(y[0])
                return 1 - k + 3 * k * s * s - 2 * k * e * s, k * math.cos(y[0]) * (3 * s - 2 * e)

            if forces([th0])[0] <= 0 or abs(forces([th0])[1]) > mu * forces([th0])[0]:
                continue
            ev, th, w, t, rec = run_phase(RB.pivot_stick_exact, th0, w0, ta, tb, lj, I, mu)
            assert 0.5 * I * w * w + G * lj * math.sin(th) == pytest.approx(E0, rel=1e-12)
            def guards(y):
                n_, f_ = forces(y)
                return [y[0] - ta, tb - y[0], n_, mu * n_ - abs(f_) if math.isfinite(mu) else math.inf]

            def first_guard(tt, y):
                return min(guards(y))

            first_guard.terminal = True
            first_guard.direction = -1
            sol = solve_ivp(lambda tt, y: [y[1], -G * lj * math.cos(y[0]) / I], (0, 5), [th0, w0], method="DOP853",
                            rtol=1e-12, atol=1e-13, events=first_guard)
            assert sol.status == 1
            which = int(np.argmin(guards(sol.y[:, -1])))
            expect = {0: RB.EV_LAND_A, 1: RB.EV_LAND_B, 2: RB.EV_LIFT_OFF, 3: RB.EV_SLIP}[which]
            assert ev == expect
            assert t == pytest.approx(sol.t[-1], rel=1e-7, abs=1e-12)
            assert th == pytest.approx(sol.y[0, -1], abs=1e-7)
            assert w == pytest.approx(sol.y[1, -1], abs=1e-5 * (1 + abs(w0)))
            N, F = RB.stick_forces(th, w, lj, I, G)
            if ev == RB.EV_LIFT_OFF:
                assert abs(N) < 1e-12
            if ev == RB.EV_SLIP:
                assert abs(F) == pytest.approx(mu * N, rel=1e-9)
            if math.isfinite(mu):
                assert rec[C.MU_MAX] <= mu * (1 + 1e-9)
            compared += 1
    assert compared > (5 if mu < 0.3 else 15)


def test_first_guard_along_the_swing_matches_a_dense_search(triangle):
    """Dense brute force along the swept path (80,000 angles): the first N < 0 or |F| > μN is where the phase stops."""
    lj, I, ta, tb = pivot(triangle)
    k = lj * lj / I
    rng = np.random.default_rng(7)
    checked = 0
    for _ in range(300):
        th0 = rng.uniform(ta, tb)
        w0 = rng.uniform(-8, 8)
        mu = rng.choice([0.3, 0.7, 1.5])
        E = 0.5 * I * w0 * w0 + G * lj * math.sin(th0)
        e = E / (G * lj)
        ev, th, w, t, rec = run_phase(RB.pivot_stick_exact, th0, w0, ta, tb, lj, I, mu)
        if t == 0.0:
            continue
        # the path swept, densely: from th0 in the sense of motion, turning where sin θ = e
        sense = 1 if w0 > 0 else -1
        path = []
        a = th0
        end = tb if sense > 0 else ta
        turn = math.asin(min(e, 1)) if sense > 0 else math.pi - math.asin(min(e, 1))
        if (sense > 0 and th0 < turn < end and e < 1) or (sense < 0 and end < turn < th0 and e < 1):
            path += list(np.linspace(a, turn, 40001))
            a = turn
            sense = -sense
            end = tb if sense > 0 else ta
        stop = th
        seg = np.linspace(a, end, 40001)
        path = np.array(path + list(seg))
        s = np.sin(path)
        N = 1 - k + 3 * k * s * s - 2 * k * e * s
        F = k * np.cos(path) * (3 * s - 2 * e)
        bad = np.nonzero((np.abs(F) > mu * N * (1 + 1e-9)) | (N < -1e-12))[0]
        if bad.size:
            assert ev in (RB.EV_SLIP, RB.EV_LIFT_OFF)
            assert abs(path[bad[0]] - stop) < 1e-3
        else:
            assert ev in (RB.EV_LAND_A, RB.EV_LAND_B)
        checked += 1
    assert checked > 200


# ----------------------------------------------------------------------------- whole throws: exact vs RK4 phase
def _starts(part, n, seed):
    rng = np.random.default_rng(seed)
    ss = np.asarray(part.stable_sides)
    k = ss[rng.integers(0, len(ss), n)].astype(np.int64)
    x = -part.uL[k] + 1e-3 + rng.random(n) * (0.4 + part.uL[k] - 1e-3)
    return x, k, rng.uniform(3.0, 7.0, n)


def _records(part, arm, mu):
    return (RB.part_arrays(part), RB.arm_arrays(arm.h, arm.g, 0.0, arm.length_or_inf, arm.back, mu, RB.LAW_ROUTH),
            RB.run_limits(1e-14, MAX_ITER, MAX_EVENTS))


def _batch(fn, part, arm, x, k, om, mu):
    n = len(x)
    xo, so, sto, rec = np.empty(n), np.empty(n, np.int64), np.empty(n, np.int64), np.empty((n, C.NREC))
    fn(x, k, om, np.ones(n, bool), *_records(part, arm, mu), xo, so, sto, rec)
    return xo, so, sto, rec


@pytest.mark.parametrize("mu", [math.inf, 1.5, 0.5])
@pytest.mark.parametrize("which", ["triangle", "offset_triangle"])
def test_whole_throws_agree_with_the_rk4_sticking_phase(which, mu, request, arm):
    """20,000 throws (ω 3–7 rad/s): same status and side in ≥ 99.9 %, median |Δx| ≤ 1 µm; T_REST to 1e-6 s."""
    part = request.getfixturevalue(which)
    x, k, om = _starts(part, 20_000, 11)
    xa, sa, sta, ra = _batch(RB.throw_many_rigid_body, part, arm, x, k, om, mu)
    xb, sb, stb, rb = _batch(RB.throw_many_rigid_body_rk4, part, arm, x, k, om, mu)
    same = (sa == sb) & (sta == stb)
    assert same.mean() >= 0.999
    assert np.median(np.abs(xa - xb)[same]) <= 1e-6
    ok = same & (sta == C.OK)
    assert np.median(np.abs(ra[ok, C.T_REST] - rb[ok, C.T_REST])) <= 1e-6
    if math.isfinite(mu):
        assert np.all(ra[:, C.MU_MAX] <= mu * (1 + 1e-9))


def test_batch_equals_single_with_trajectory(triangle, arm):
    """Same outcome with and without trajectory rows; rows lie on the pivot circle of the exact swing."""
    x, k, om = _starts(triangle, 40, 3)
    xb, sb, stb, rb = _batch(RB.throw_many_rigid_body, triangle, arm, x, k, om, 1.5)
    for i in range(40):
        rec = np.empty(C.NREC)
        traj = np.empty((3000, 4))
        out = RB.throw_one_rigid_body(x[i], k[i], om[i], *_records(triangle, arm, 1.5), rec, traj, 0.002)
        assert out == (xb[i], sb[i], stb[i])
        np.testing.assert_array_equal(rec, rb[i])
        ns = RB.count_samples(traj)
        assert np.all(np.diff(traj[:ns, 0]) >= -1e-12)

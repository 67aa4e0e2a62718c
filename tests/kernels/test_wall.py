"""The wall's guards, resets and statics of model "rigid_body" (kernels/rigid_body/wall.py, wall_statics.py, the
flat slide into it in flat.py), by closed forms and independent checks (dense sampling of the gaps, scipy's
linprog for the cone tests)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import linprog

from throwmap.kernels.flight import departure_window
from throwmap.kernels.rigid_body import LAW_ROUTH, LAW_VELOCITY
from throwmap.kernels.rigid_body.flat import corner_pivot_rate, slide_hit, wall_reach_at_rest
from throwmap.kernels.rigid_body.impact import contact_impact, coulomb_impact
from throwmap.kernels.rigid_body.modes import IMP_INCONSISTENT, IMP_SEPARATE, IMP_STICK, WHY_NONE, WHY_WALL_SLIDE
from throwmap.kernels.rigid_body.wall import (corner_inside, corner_touch_time, wall_contact_angle, wall_hit_in_flight,
                                              wall_theta, wall_touch_time)
from throwmap.kernels.rigid_body.wall_statics import cone_contains, contacts_can_supply, rest_flat_at_wall
from throwmap.system.catalogue import rectangle, triangle_30_60_90

G = 9.81
finite = dict(allow_nan=False, allow_infinity=False, allow_subnormal=False)  # offsets of 1e-308 m are not a part


def wall_impact(vx, vy, w, rx, ry, rho2, mu_w, law):
    """The impact of a vertex at (r_x, r_y) on the face x = L: the arm's law in the frame (x', y') = (y, −x), a
    proper rotation by −90° in which the face's inward normal −x̂ is ŷ' (what :func:`contact_impact` computes
    for the normal −x̂)."""
    vxp, vyp, wp, pt, pn, kind, jt0, jn0 = coulomb_impact(vy, -vx, w, ry, -rx, rho2, mu_w, law)
    return -vyp, vxp, wp, pt, pn, kind, jt0, jn0


def _state():
    return st.tuples(st.floats(-2, 2, **finite), st.floats(-2, 2, **finite), st.floats(-30, 30, **finite),
                     st.floats(0.0, 0.05, **finite), st.floats(-0.05, 0.05, **finite), st.floats(1e-4, 2e-3, **finite))


# ---------------------------------------------------------------------------------------- wall_impact
@settings(max_examples=300, deadline=None)
@given(_state(), st.sampled_from([0.0, 0.3, 1.0, math.inf]), st.sampled_from([LAW_ROUTH, LAW_VELOCITY]))
def test_wall_impact_stops_the_normal_motion_and_never_gains_energy(s, mu_w, law):
    vx, vy, w, rx, ry, rho2 = s
    un0 = vx - w * ry  # vertex velocity into the wall (+x)
    vxp, vyp, wp, pt, pn, kind, _, _ = wall_impact(vx, vy, w, rx, ry, rho2, mu_w, law)
    if kind == IMP_INCONSISTENT:
        return
    if un0 <= 0.0:
        assert kind == IMP_SEPARATE and (vxp, vyp, wp) == (vx, vy, w)
        return
    assert pn >= -1e-12 * (abs(vx) + abs(vy) + abs(w) * 0.1)  # ≥ 0 up to rounding
    assert abs(vxp - wp * ry) <= 1e-9 * (abs(vx) + abs(w * ry) + 1e-12)  # plastic: zero normal velocity after
    k0 = 0.5 * (vx * vx + vy * vy + rho2 * w * w)
    k1 = 0.5 * (vxp * vxp + vyp * vyp + rho2 * wp * wp)
    assert k1 <= k0 * (1 + 1e-12) + 1e-15
    # the impulse is (−P_n, P_t) at the vertex: momentum and angular momentum about the CM
    assert vxp - vx == pytest.approx(-pn, abs=1e-12)
    assert vyp - vy == pytest.approx(pt, abs=1e-12)
    assert rho2 * (wp - w) == pytest.approx(rx * pt - ry * (-pn), abs=1e-12)
    if not math.isinf(mu_w):
        assert abs(pt) <= mu_w * pn * (1 + 1e-9) + 1e-15


@settings(max_examples=200, deadline=None)
@given(_state())
def test_frictionless_wall_conserves_tangential_momentum_and_matches_the_closed_form(s):
    vx, vy, w, rx, ry, rho2 = s
    un0 = vx - w * ry
    vxp, vyp, wp, pt, pn, kind, _, _ = wall_impact(vx, vy, w, rx, ry, rho2, 0.0, LAW_ROUTH)
    assert vyp == vy and pt == 0.0
    if un0 > 0:
        p = un0 / (1.0 + ry * ry / rho2)  # P_n = u_n / K_nn with K_nn = 1 + r_y²/ρ² along x̂
        assert pn == pytest.approx(p, rel=1e-12)


@settings(max_examples=200, deadline=None)
@given(_state())
def test_infinitely_rough_wall_sticks_the_vertex_when_no_pull_is_needed(s):
    vx, vy, w, rx, ry, rho2 = s
    ux, uy = vx - w * ry, vy + w * rx
    K = np.array([[1 + ry * ry / rho2, -rx * ry / rho2], [-rx * ry / rho2, 1 + rx * rx / rho2]])
    P = -np.linalg.solve(K, [ux, uy])  # the no-slip impulse (world frame)
    vxp, vyp, wp, pt, pn, kind, _, _ = wall_impact(vx, vy, w, rx, ry, rho2, math.inf, LAW_ROUTH)
    if ux > 0 and -P[0] >= 0:
        assert kind == IMP_STICK
        assert abs(vxp - wp * ry) < 1e-9 and abs(vyp + wp * rx) < 1e-9
        assert (-pn, pt) == pytest.approx(tuple(P), abs=1e-9)


# ---------------------------------------------------------------------------------------- wall_touch
@settings(max_examples=60, deadline=None)
@given(st.floats(0.0, 2 * math.pi), st.floats(-1.5, 1.5, **finite), st.floats(-15, 15, **finite),
       st.floats(0.0, 0.08), st.floats(-3, 3, **finite))
def test_wall_touch_is_the_first_crossing_found_by_dense_sampling(phi0, vx, om, gap, gx):
    tri = triangle_30_60_90()
    w = np.asarray(tri.w)
    ell = np.hypot(w[:, 0], w[:, 1])
    c, s = math.cos(phi0), math.sin(phi0)
    ru = c * w[:, 0] - s * w[:, 1]
    rv = s * w[:, 0] + c * w[:, 1]
    L = float(ru.max() + gap)  # CM at x = 0, the nearest vertex `gap` from the wall
    cw = L - ru
    t_max = 0.6
    t, j = wall_touch_time(cw, ru, rv, vx, om, gx, ell, -1, 0.0, t_max, 1e-14, 100_000, np.zeros(3))
    ts = np.linspace(0, t_max, 60001)
    xs = (vx * ts + 0.5 * gx * ts * ts)[:, None] + np.cos(om * ts)[:, None] * ru - np.sin(om * ts)[:, None] * rv
    over = np.nonzero((xs > L + 1e-9).any(axis=1))[0]
    if j < 0:
        assert j == -1 and over.size == 0
    else:
        assert t <= t_max
        x_j = vx * t + 0.5 * gx * t * t + math.cos(om * t) * ru[j] - math.sin(om * t) * rv[j]
        assert x_j == pytest.approx(L, abs=1e-10)
        assert over.size == 0 or ts[over[0]] >= t - 1e-12
        before = ts < t - 1e-9
        assert (xs[before] <= L + 1e-9).all()


def test_wall_touch_respects_the_horizon_and_the_departure_window():
    ru = np.array([0.02, -0.02])
    rv = np.array([0.0, 0.0])
    ell = np.abs(ru)
    cw = np.array([0.0, 0.04])
    # vertex 0 on the wall, moving away: no contact at t = 0
    t, j = wall_touch_time(cw, ru, rv, -0.1, 0.0, 0.0, ell, -1, 0.0, 1.0, 1e-14, 1000, np.zeros(2))
    assert j == -1
    # moving in from 1 cm: reaches the wall after 0.01/0.5 s, unless the horizon comes first
    cw = np.array([0.01, 0.05])
    t, j = wall_touch_time(cw, ru, rv, 0.5, 0.0, 0.0, ell, -1, 0.0, 1.0, 1e-14, 1000, np.zeros(2))
    assert j == 0 and t == pytest.approx(0.02, rel=1e-12)
    t, j = wall_touch_time(cw, ru, rv, 0.5, 0.0, 0.0, ell, -1, 0.0, 0.019, 1e-14, 1000, np.zeros(2))
    assert j == -1


def test_wall_departure_window():
    # the face's frame: tangent ŷ, normal −x̂, so a vertex at (r_x, r_y) from the CM is at (r_y, −r_x)
    # a spinning vertex right of the CM curves back from the wall: it leaves (positive window)
    assert departure_window(0.0, -0.03, 10.0, 0.0, 0.03, G) > 0
    # gravity pushing it into the wall with no spin: it stays pressed (no window)
    assert departure_window(0.0, -0.03, 0.0, 1.0, 0.03, 1.0 + G) == 0.0


def test_wall_hit_in_flight_refuses_a_pressed_vertex():
    # no spin after a frictionless hit through the CM line, gravity towards the wall: it stays pressed
    r = wall_hit_in_flight(1.0, 0.0, 0.0, 0.02, 0.0, -1.0, 0.0, False, 4e-4, 0.0, LAW_ROUTH, 1.0, G, 0.02)
    assert r[-1] == WHY_WALL_SLIDE
    r = wall_hit_in_flight(1.0, 0.0, 0.0, 0.02, 0.01, -1.0, 0.0, False, 4e-4, 0.0, LAW_ROUTH, 0.0, G, 0.0224)
    assert r[-1] == WHY_NONE and r[-2] > 0


@settings(max_examples=200, deadline=None)
@given(_state(), st.floats(0, 2 * math.pi), st.sampled_from([0.0, 0.5, math.inf]))
def test_contact_impact_on_the_face_is_the_arms_law_turned_by_minus_90_degrees(s, ang, mu):
    vx, vy, w, rx, ry, rho2 = s
    a = wall_impact(vx, vy, w, rx, ry, rho2, mu, LAW_ROUTH)
    b = contact_impact(vx, vy, w, rx, ry, -1.0, 0.0, rho2, mu, LAW_ROUTH)
    assert a[:5] == pytest.approx(b[:5], abs=1e-12) and a[5] == b[5]
    # any normal: the contact's normal velocity is 0 after a plastic impact that was closing
    nx, ny = math.cos(ang), math.sin(ang)
    un = (vx - w * ry) * nx + (vy + w * rx) * ny
    vxp, vyp, wp, pt, pn, kind, _, _ = contact_impact(vx, vy, w, rx, ry, nx, ny, rho2, mu, LAW_ROUTH)
    if un < 0 and kind != IMP_INCONSISTENT:
        assert abs((vxp - wp * ry) * nx + (vyp + wp * rx) * ny) <= 1e-9 * (abs(vx) + abs(vy) + abs(w) * 0.1 + 1e-9)
        assert pn >= 0


# ---------------------------------------------------------------------------------------- wall_reach (pivots)
@pytest.mark.parametrize("part", [triangle_30_60_90(), rectangle(0.08, 0.04)])
def test_wall_theta_puts_the_vertex_on_the_wall_and_the_rest_inside(part):
    w = np.asarray(part.w)
    rng = np.random.default_rng(3)
    for _ in range(50):
        jp = int(rng.integers(len(w)))
        phi = float(rng.uniform(0, 2 * math.pi))
        px = 0.3
        c, s = math.cos(phi), math.sin(phi)
        R = np.array([[c, -s], [s, c]])
        V = (R @ w.T).T
        A = V[jp]
        if ((V - A)[:, 1] < -1e-12).any():
            continue  # jp must be the lowest vertex of a pose pivoting on it
        cm = -A
        theta = math.atan2(cm[1], cm[0])
        L = px + float(rng.uniform(0.0, 1.2)) * float(np.max(np.hypot(*(V - A).T)))
        th_w, jw, yw = wall_theta(px, L, 0.1, theta, phi, w, jp)
        if jw < 0:
            assert (px + (V - A)[:, 0] <= L + 1e-12).all()
            continue

        def pose(th):
            rot = np.array([[math.cos(th - theta), -math.sin(th - theta)], [math.sin(th - theta), math.cos(th - theta)]])
            return np.array([px, 0.0]) + (rot @ (V - A).T).T

        P = pose(th_w)
        assert P[jw, 0] == pytest.approx(L, abs=1e-12)
        assert P[jw, 1] == pytest.approx(yw, abs=1e-12)
        assert (P[:, 0] <= L + 1e-12).all()
        assert (pose(th_w - 1e-6)[:, 0] > L).any()


# ---------------------------------------------------------------------------------------- FLAT_SLIDE into the wall
def test_slide_hit_closed_form():
    hit, t, vh = slide_hit(1.0, -0.3 * G, 0.05)
    assert hit and vh == pytest.approx(math.sqrt(1 - 2 * 0.3 * G * 0.05)) and t == pytest.approx((1 - vh) / (0.3 * G))
    hit, t, vh = slide_hit(0.2, -0.3 * G, 0.05)
    assert not hit and vh == 0 and t == pytest.approx(0.2 / (0.3 * G))
    hit, t, vh = slide_hit(0.2, 1.0, 0.05)  # accelerating towards the wall (tilted arm, little friction)
    assert hit and vh == pytest.approx(math.sqrt(0.04 + 0.1)) and 0.2 * t + 0.5 * t * t == pytest.approx(0.05)


def _flat(part, k):
    """Vertex offsets (u, v) from the CM of a part flat on side k, and its support vertices."""
    c, s = math.cos(part.beta[k]), math.sin(part.beta[k])
    w = np.asarray(part.w)
    return c * w[:, 0] - s * w[:, 1], s * w[:, 0] + c * w[:, 1], (k + 1) % len(w), k


def test_a_flat_slide_stops_at_the_wall_with_its_cm_at_length_minus_u_r():
    part = rectangle(0.08, 0.04)
    L, mu = 0.4, 0.3
    for k in range(4):
        u, v, jl, jr = _flat(part, k)
        u_w, j_w, above = wall_reach_at_rest(u, v + part.d[k], 0.05)
        assert j_w in (jr, (jr - 1) % 4) and not above and u_w == pytest.approx(part.uR[k])
        x0 = L - u_w - 0.02
        hit, t, vh = slide_hit(0.6, -mu * G, L - (x0 + u_w))
        assert hit and vh > 0
        # the flush side touches the wall at two vertices: one plastic impulse stops the part
        pts = np.array([[u[jl], v[jl]], [u[jr], v[jr]], [u_w, v[jr]], [u_w, v[(jr - 1) % 4]]])
        nrm = np.array([[0, 1.0], [0, 1.0], [-1.0, 0], [-1.0, 0]])
        for mu_w in (0.0, mu):
            mus = np.array([mu, mu, mu_w, mu_w])
            assert contacts_can_supply(pts, nrm, mus, 4, -vh, 0.0, 0.0, 0.05)
            # and it rests there: x = L − u_R, held at α = 0 and on an arm tilted towards the wall
            assert rest_flat_at_wall(u, v, jl, jr, u_w, 0.05 - part.d[k], mu, mu_w, 0.0, -G, 0.05)
            a = math.radians(-15)
            assert rest_flat_at_wall(u, v, jl, jr, u_w, 0.05 - part.d[k], mu, mu_w, -G * math.sin(a), -G * math.cos(a),
                                     0.05)
            # away from the wall the same tilt is not held by μ = 0.2 < tan 15°
            assert not rest_flat_at_wall(u, v, jl, jr, u_w + 0.01, 0.05 - part.d[k], 0.2, mu_w, -G * math.sin(a),
                                         -G * math.cos(a), 0.05)


def test_a_part_hitting_the_wall_with_an_acute_foot_turns_about_the_corner():
    tri = triangle_30_60_90()
    for k in tri.stable_sides:
        u, v, jl, jr = _flat(tri, k)
        if u.max() > tri.uR[k] + 1e-12:
            continue  # the foot is not the leading vertex
        vel = 0.5
        pts = np.array([[u[jl], v[jl]], [u[jr], v[jr]], [u[jr], v[jr]]])
        nrm = np.array([[0, 1.0], [0, 1.0], [-1.0, 0]])
        mus = np.array([1.0, 1.0, 1.0])
        assert not contacts_can_supply(pts, nrm, mus, 3, -vel, 0.0, 0.0, 0.05)  # it cannot stop dead
        wp = corner_pivot_rate(vel, tri.uR[k], tri.d[k], tri.radius_of_gyration ** 2)
        assert wp < 0
        # angular momentum about the corner: before −d v, after (ρ² + ℓ²) ω
        ell2 = tri.uR[k] ** 2 + tri.d[k] ** 2
        assert (tri.radius_of_gyration ** 2 + ell2) * wp == pytest.approx(-tri.d[k] * vel)
        # the impulse that does it lies in the sum of the arm's and the wall's cones at the corner
        vxp, vyp = -wp * tri.d[k], -wp * tri.uR[k]
        assert contacts_can_supply(pts[1:], nrm[1:], mus[1:], 2, vxp - vel, vyp,
                                   tri.radius_of_gyration ** 2 * wp, 0.05)


# ---------------------------------------------------------------------------------------- cone test vs linprog
@settings(max_examples=150, deadline=None)
@given(st.integers(1, 9), st.integers(0, 2 ** 31 - 1))
def test_cone_contains_agrees_with_linprog(m, seed):
    rng = np.random.default_rng(seed)
    Gm = rng.normal(size=(3, m))
    if rng.random() < 0.5:
        b = Gm @ rng.uniform(0, 1, m)  # inside by construction
    else:
        b = rng.normal(size=3)
    res = linprog(np.zeros(m), A_eq=Gm, b_eq=b, bounds=[(0, None)] * m, method="highs")
    ours = cone_contains(Gm, m, b)
    if res.status == 0:
        # feasible for linprog: ours must agree unless it is a boundary case at linprog's tolerance
        assert ours or np.min(np.abs(np.linalg.svd(Gm, compute_uv=False))) < 1e-6
    else:
        assert not ours


# ---------------------------------------------------------------------------------------- the wall's top corner
def _inside(P, q):
    """Whether point q is inside the convex polygon P (rows, either orientation)."""
    e = np.roll(P, -1, axis=0) - P
    cr = e[:, 0] * (q[1] - P[:, 1]) - e[:, 1] * (q[0] - P[:, 0])
    return (cr > 0).all() or (cr < 0).all()


@settings(max_examples=40, deadline=None)
@given(st.floats(0.0, 2 * math.pi), st.floats(-1.0, 1.5, **finite), st.floats(-1.0, 1.0, **finite),
       st.floats(-12, 12, **finite), st.floats(0.0, 0.06), st.floats(-0.04, 0.06))
def test_corner_touch_is_the_first_entry_found_by_dense_sampling(phi0, vx, vy, om, dx, dy):
    tri = triangle_30_60_90()
    w = np.asarray(tri.w)
    c, s = math.cos(phi0), math.sin(phi0)
    ru = c * w[:, 0] - s * w[:, 1]
    rv = s * w[:, 0] + c * w[:, 1]
    q = np.array([ru.max() + dx, dy])  # corner relative to the CM at t = 0
    P0 = np.stack([ru, rv], 1)
    if _inside(P0, q):
        return
    gx, gn, t_max = 0.5, G, 0.4
    t, e = corner_touch_time(q[0], q[1], vx, vy, om, gx, gn, ru, rv, -1, 0.0, t_max, 1e-14, 200_000)

    def poly(tt):
        X = np.array([vx * tt + 0.5 * gx * tt * tt, vy * tt - 0.5 * gn * tt * tt])
        R = np.array([[math.cos(om * tt), -math.sin(om * tt)], [math.sin(om * tt), math.cos(om * tt)]])
        return X + P0 @ R.T

    ts = np.linspace(0, t_max, 8001)
    first = next((tt for tt in ts if _inside(poly(tt), q)), None)
    if e < 0:
        assert e == -1 and first is None
    else:
        assert first is None or first >= t - 1e-12
        P = poly(t)
        a, b = P[e], P[(e + 1) % 3]
        # the corner is on edge e at that time
        cross = (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0])
        assert abs(cross) / np.hypot(*(b - a)) < 1e-9
        u = np.dot(q - a, b - a) / np.dot(b - a, b - a)
        assert -1e-9 <= u <= 1 + 1e-9


def test_wall_contact_angle_finds_the_corner_on_an_edge_above_a_low_wall():
    tri = triangle_30_60_90()
    w = np.asarray(tri.w)
    rng = np.random.default_rng(5)
    found = 0
    for _ in range(300):
        jp = int(rng.integers(3))
        phi = float(rng.uniform(0, 2 * math.pi))
        R = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
        V = (R @ w.T).T
        A = V[jp]
        if ((V - A)[:, 1] < -1e-12).any():
            continue
        theta = math.atan2(-A[1], -A[0])
        px, top = 0.3, 0.02
        L = px + float(rng.uniform(0.0, 0.15))
        if corner_inside(px, 0.0, theta, phi, w, jp, L, top) or (px + (V - A)[:, 0] > L).any():
            continue
        th, corner, j, cx, cy, nx, ny = wall_contact_angle(px, L, top, theta, phi, w, jp)
        if not np.isfinite(th):
            continue
        rot = np.array([[math.cos(th - theta), -math.sin(th - theta)], [math.sin(th - theta), math.cos(th - theta)]])
        P = np.array([px, 0.0]) + ((V - A) @ rot.T)
        # at the bound the part touches the wall and does not cross it: no vertex beyond below the top,
        # the corner not inside
        below = P[:, 1] < top - 1e-12
        assert (P[below, 0] <= L + 1e-9).all()
        assert not _inside(P, np.array([L, top])) or corner
        if corner:
            found += 1
            a, b = P[j], P[(j + 1) % 3]
            cross = (b[0] - a[0]) * (top - a[1]) - (b[1] - a[1]) * (L - a[0])
            assert abs(cross) / np.hypot(*(b - a)) < 1e-9
            # the normal points into the part (towards its CM)
            cm = np.array([px, 0.0]) + rot @ (-A)
            assert np.dot(cm - np.array([L, top]), [nx, ny]) > 0
        else:
            assert P[j, 0] == pytest.approx(L, abs=1e-12) and P[j, 1] < top
    assert found > 5

"""rigid_body's wall contact modes (issue 11): a vertex sliding on the face, the two-contact impact, the ladder.

Independent checks: energy balance (a frictionless wall and arm conserve it, friction only removes it),
a second integration of the same motion in other coordinates (scipy's solve_ivp on the free body
with the contact force from the gap's second derivative), the impact's conditions checked on its
result (normal velocities, cones, energy), the frictionless impact against a quadratic program, and
the engine on throws that go through the new modes.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp
from scipy.optimize import minimize

import throwmap as tm
from throwmap.kernels.rigid_body.modes import EV_LIFT_OFF
from throwmap.kernels.rigid_body.impact import C_OPEN, multi_contact_impact
from throwmap.kernels.rigid_body.wall import fill_wall_vertices
from throwmap.kernels.rigid_body.wall_lean import ladder_phase, ladder_pose, ladder_rhs
from throwmap.kernels.rigid_body.wall_slide import W_SLIDE, W_STICK, wall_phase, wall_rhs, wall_select
from throwmap.kernels.rigid_body.wall_statics import contacts_can_supply
from throwmap.system.catalogue import rectangle, regular_polygon

G = 9.81
NO_TRAJ = np.zeros((0, 4))


def _rec():
    return np.zeros(64)


def _square_on_face(theta, thd, vp, alpha, top=0.5):
    """A 6 cm square with vertex 0 on the face x = L = 0.3 (P at y_P = 0.05), CM at P + ℓ(cos θ, sin θ)."""
    part = rectangle(0.06, 0.06)
    w = np.asarray(part.w, dtype=float)
    rho2 = part.radius_of_gyration ** 2
    lj = math.hypot(*w[0])
    # φ such that vertex 0 sits at P: R(φ) w_0 = −ℓ (cos θ, sin θ)
    phi = theta + math.pi - math.atan2(w[0, 1], w[0, 0])
    wv = np.zeros((4, 2))
    fill_wall_vertices(theta, phi, w, 0, wv)
    gx, gn = -G * math.sin(alpha), G * math.cos(alpha)
    return dict(w=w, rho2=rho2, lj=lj, phi_off=phi - theta, wv=wv, gx=gx, gn=gn, th=theta, thd=thd, vp=vp,
                yp=0.05, L=0.3, h=-0.2, top=top)


def _energy(s, yp, th, vp, thd):
    c, sn = math.cos(th), math.sin(th)
    x, y = s["L"] + s["lj"] * c, yp + s["lj"] * sn
    vx, vy = -s["lj"] * sn * thd, vp + s["lj"] * c * thd
    return 0.5 * (vx * vx + vy * vy + s["rho2"] * thd * thd) - s["gx"] * x + s["gn"] * y


def _run(s, mu_w, stick=False, sig=0.0):
    return wall_phase(s["yp"], s["th"], s["vp"], s["thd"], stick, sig, 0.0, s["lj"], s["rho2"], s["gx"], s["gn"],
                      mu_w, s["h"], s["top"], s["wv"], -1, 0.0, 0.0, s["L"], s["phi_off"], 100000, NO_TRAJ, np.zeros(3),
                      _rec())


# ------------------------------------------------------------------------------------------ WALL_CONTACT
@pytest.mark.parametrize("theta,thd,vp,alpha", [(math.pi - 0.3, -2.0, -0.5, -0.2), (math.pi + 0.4, 1.0, 0.3, -0.25),
                                                (math.pi - 0.1, 3.0, 0.0, -0.1)])
def test_frictionless_face_conserves_energy_and_falls_freely(theta, thd, vp, alpha):
    s = _square_on_face(theta, thd, vp, alpha)
    mode, _sig = wall_select(s["th"], s["thd"], s["vp"], s["lj"], s["rho2"], s["gx"], s["gn"], 0.0, False)
    assert mode == W_SLIDE
    ev, k, yp, th, vp1, thd1, t = _run(s, 0.0)
    assert t > 0.01  # a motion, not an event at the start
    e0 = _energy(s, s["yp"], s["th"], s["vp"], s["thd"])
    assert _energy(s, yp, th, vp1, thd1) == pytest.approx(e0, abs=1e-9 * (abs(e0) + 1.0))
    # no vertical force on a frictionless face: the CM falls freely
    vy0 = s["vp"] + s["lj"] * math.cos(s["th"]) * s["thd"]
    vy1 = vp1 + s["lj"] * math.cos(th) * thd1
    assert vy1 == pytest.approx(vy0 - s["gn"] * t, abs=1e-9)


def _free_body_reference(s, mu_w, sig, t_end):
    """The same motion as a free body (x, y, φ, v_x, v_y, ω) with the contact force from W'' = 0 (W = L − x_P)."""
    w0 = s["w"][0]
    rho2 = s["rho2"]

    def rhs(_t, q):
        x, y, phi, vx, vy, om = q
        rx = math.cos(phi) * w0[0] - math.sin(phi) * w0[1]
        ry = math.sin(phi) * w0[0] + math.cos(phi) * w0[1]
        # force (−N, −μσN) at r: ẍ = g_x − N, ω̇ = (r_y N − μσ r_x N)/ρ²; W'' = −ẍ + r_x ω² + r_y ω̇ = 0
        a_n = (1.0 + (ry * ry - mu_w * sig * rx * ry) / rho2)
        N = (s["gx"] - rx * om * om) / a_n
        F = -mu_w * sig * N
        return [vx, vy, om, s["gx"] - N, -s["gn"] + F, (ry * N + rx * F) / rho2]

    c, sn = math.cos(s["th"]), math.sin(s["th"])
    q0 = [s["L"] + s["lj"] * c, s["yp"] + s["lj"] * sn, s["th"] + s["phi_off"], -s["lj"] * sn * s["thd"],
          s["vp"] + s["lj"] * c * s["thd"], s["thd"]]
    return solve_ivp(rhs, (0.0, t_end), q0, rtol=1e-11, atol=1e-13).y[:, -1]


@pytest.mark.parametrize("mu_w,vp", [(0.0, -0.5), (0.4, -0.6), (0.4, 0.8)])
def test_face_slide_matches_a_free_body_integration(mu_w, vp):
    s = _square_on_face(math.pi - 0.25, -1.5, vp, -0.2)
    sig = 0.0 if mu_w == 0.0 else math.copysign(1.0, vp)
    ev, k, yp, th, vp1, thd1, t = _run(s, mu_w, sig=sig)
    assert t > 0.005
    ref = _free_body_reference(s, mu_w, sig, t)
    c, sn = math.cos(th), math.sin(th)
    assert s["L"] + s["lj"] * c == pytest.approx(ref[0], abs=1e-8)
    assert yp + s["lj"] * sn == pytest.approx(ref[1], abs=1e-8)
    assert th + s["phi_off"] == pytest.approx(ref[2], abs=1e-7)
    assert thd1 == pytest.approx(ref[5], abs=1e-6)
    if mu_w > 0.0:  # sliding friction only removes energy
        assert _energy(s, yp, th, vp1, thd1) < _energy(s, s["yp"], s["th"], s["vp"], s["thd"])


def test_stuck_on_a_rough_face_the_vertex_stays_put_and_energy_is_kept():
    s = _square_on_face(math.pi - 0.2, -1.0, 0.0, -0.25)
    mode, _sig = wall_select(s["th"], s["thd"], 0.0, s["lj"], s["rho2"], s["gx"], s["gn"], math.inf, False)
    assert mode == W_STICK
    ev, k, yp, th, vp1, thd1, t = _run(s, math.inf, stick=True)
    assert t > 0.0 and yp == s["yp"] and vp1 == 0.0
    e0 = _energy(s, s["yp"], s["th"], 0.0, s["thd"])
    assert _energy(s, yp, th, 0.0, thd1) == pytest.approx(e0, abs=1e-9 * (abs(e0) + 1.0))


def test_a_vertex_thrown_off_the_face_lifts():
    # gravity pulls away from the wall (α > 0) and no spin: not pressed at all
    s = _square_on_face(math.pi - 0.2, 0.0, 0.0, 0.2)
    mode, _ = wall_select(s["th"], s["thd"], s["vp"], s["lj"], s["rho2"], s["gx"], s["gn"], 0.0, False)
    assert mode == -1
    # pressed at first, the spin's centripetal pull takes over: N reaches 0
    s = _square_on_face(math.pi + 0.3, 6.0, 0.0, -0.05)
    _N = wall_rhs(s["th"], s["thd"], s["lj"], s["rho2"], s["gx"], s["gn"], 0.0, False)[2]
    ev = _run(s, 0.0)[0]
    assert ev == EV_LIFT_OFF or _N <= 0.0


# ------------------------------------------------------------------------------------------ impacts
def _contacts(rng):
    """An arm contact and a face contact of a random part (CM → contact offsets, m)."""
    return (np.array([[rng.uniform(-0.04, 0.02), rng.uniform(-0.04, -0.005)],
                      [rng.uniform(0.005, 0.04), rng.uniform(-0.03, 0.03)]]),
            np.array([[0.0, 1.0], [-1.0, 0.0]]))


@settings(max_examples=300, deadline=None)
@given(st.integers(0, 2**32 - 1), st.sampled_from([0.0, 0.3, 1.0, math.inf]), st.sampled_from([0.0, 0.5, math.inf]))
def test_the_two_contact_impact_meets_every_condition(seed, mu, mu_w):
    rng = np.random.default_rng(seed)
    pts, nrm = _contacts(rng)
    mus = np.array([mu, mu_w])
    rho2 = rng.uniform(2e-4, 1e-3)
    vx, vy, om = rng.uniform(-1, 1), rng.uniform(-1, 0.2), rng.uniform(-20, 20)
    stt = np.zeros(2, dtype=np.int64)
    ok, vxp, vyp, wp = multi_contact_impact(vx, vy, om, pts, nrm, mus, 2, rho2, stt)
    if not ok:  # only infinite friction can make a frictional impact inconsistent (a pulling normal impulse)
        assert math.isinf(mu) or math.isinf(mu_w)
        return
    scale = abs(vx) + abs(vy) + abs(om) * 0.1
    for i in range(2):
        rx, ry = pts[i]
        un = nrm[i, 0] * (vxp - wp * ry) + nrm[i, 1] * (vyp + wp * rx)
        assert un >= -1e-8 * scale
    assert 0.5 * (vxp**2 + vyp**2 + rho2 * wp**2) <= 0.5 * (vx**2 + vy**2 + rho2 * om**2) * (1 + 1e-9) + 1e-15
    # the impulse is a sum of impulses inside the cones (independent: the exact cone test)
    assert contacts_can_supply(pts, nrm, mus, 2, vxp - vx, vyp - vy, rho2 * (wp - om), 0.1) or \
        abs(vxp - vx) + abs(vyp - vy) + abs(wp - om) * 0.1 <= 1e-9 * scale


@settings(max_examples=100, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_the_frictionless_two_contact_impact_is_the_least_energy_projection(seed):
    rng = np.random.default_rng(seed)
    pts, nrm = _contacts(rng)
    rho2 = rng.uniform(2e-4, 1e-3)
    v = np.array([rng.uniform(-1, 1), rng.uniform(-1, 0.2), rng.uniform(-20, 20)])
    stt = np.zeros(2, dtype=np.int64)
    ok, vxp, vyp, wp = multi_contact_impact(*v, pts, nrm, np.zeros(2), 2, rho2, stt)
    assert ok
    # frictionless plastic impact: the least kinetic energy velocity with every normal velocity ≥ 0
    M = np.diag([1.0, 1.0, rho2])
    J = np.array([[n[0], n[1], r[0] * n[1] - r[1] * n[0]] for r, n in zip(pts, nrm)])
    res = minimize(lambda u: 0.5 * (u - v) @ M @ (u - v), v, jac=lambda u: M @ (u - v),
                   constraints=[{"type": "ineq", "fun": lambda u: J @ u, "jac": lambda u: J}], method="SLSQP",
                   options={"ftol": 1e-14, "maxiter": 500})
    assert np.allclose([vxp, vyp, wp], res.x, atol=1e-6 * (1 + np.abs(v).max()))


# ------------------------------------------------------------------------------------------ LADDER
def _ladder_start():
    part = rectangle(0.10, 0.02)
    w = np.asarray(part.w, dtype=float)
    return part, w, part.radius_of_gyration ** 2


@pytest.mark.parametrize("mu,mu_w", [(0.0, 0.0), (0.3, 0.0), (0.3, 0.3)])
def test_a_ladder_falls_conserving_energy_only_without_friction(mu, mu_w):
    part, w, rho2 = _ladder_start()
    # the bar's long axis at 40° (it slides at μ = 0.3: tan 40° < 1/(2μ)): A its lowest vertex on the arm,
    # P its rightmost on the face
    phi = math.radians(40.0)
    ry = np.sin(phi) * w[:, 0] + np.cos(phi) * w[:, 1]
    rx = np.cos(phi) * w[:, 0] - np.sin(phi) * w[:, 1]
    ja, jp, L, h = int(np.argmin(ry)), int(np.argmax(rx)), 0.2, 0.0
    assert ja != jp
    gx, gn = 0.0, G
    rax = math.cos(phi) * w[ja, 0] - math.sin(phi) * w[ja, 1]
    rpy = math.sin(phi) * w[jp, 0] + math.cos(phi) * w[jp, 1]
    wd, na, npw, D = ladder_rhs(phi, 0.0, w[ja], w[jp], rho2, mu, mu_w, -1.0, gx, gn)
    assert D > 0 and na > 0 and npw > 0 and wd < 0  # it starts to fall (P slides down, A away from the wall)

    def energy(ph, om):
        x, y = ladder_pose(ph, w, ja, jp, h, L)
        ra = math.cos(ph) * w[ja, 0] - math.sin(ph) * w[ja, 1]
        rp = math.sin(ph) * w[jp, 0] + math.cos(ph) * w[jp, 1]
        return 0.5 * ((rp * om) ** 2 + (ra * om) ** 2 + rho2 * om * om) + gn * y - gx * x

    ev, k, ph1, om1, t = ladder_phase(phi, 0.0, -1.0, 0.0, w, ja, jp, rho2, mu, mu_w, gx, gn, h, L, 1.0, 1.0,
                                      100000, NO_TRAJ, np.zeros(3))
    assert t > 0.0 and om1 < 0.0
    e0, e1 = energy(phi, 0.0), energy(ph1, om1)
    if mu == 0.0 and mu_w == 0.0:
        assert e1 == pytest.approx(e0, abs=1e-9 * (abs(e0) + 1.0))  # RK4 at DTH per step
    else:
        assert e1 < e0


# ------------------------------------------------------------------------------------------ whole throws
CASES = [  # throws of `throwmap validate-fixtures` (seed 0) that go through the new modes; the engine's answers
    ("rectangle+lead", 0.25711748484354724, 0, 5.908167703922793, -0.08323508322250456, 2.127503043208594, -0.005,
     0.29297229897960875, 0.0),
    ("pentagon", 0.25510662518841554, 2, 6.131239563617951, -0.1843462541428077, 2.804603629432211, -0.005,
     0.3236004434048211, 0.0),
    ("square", 0.2554037864980324, 3, 4.170120034233814, -0.10197374104022494, 1.0447287825484441, -0.01,
     0.30924359188652734, 0.0),
    ("triangle+lead", 0.30253116533566654, 2, 3.1012186793165215, -0.233856252413293, 0.9529752883548481, -0.005,
     0.34947706414083574, 0.9529752883548481),
]


def _parts():
    from throwmap.studies.validation import default_parts

    return default_parts()


@pytest.mark.parametrize("case", CASES, ids=[c[0] + f"-{i}" for i, c in enumerate(CASES)])
def test_throws_through_the_wall_modes_resolve(case):
    name, x, side, om, alpha, mu, h, length, wall_mu = case
    o = tm.throw(_parts()[name], tm.Arm(h=h, mu=mu, length=length), x, side, om, "rigid_body",
                 fixtures=(tm.Wall(0.05, mu=wall_mu),), alpha=alpha)
    assert o.status.label == "ok"
    assert o.x <= length


@pytest.mark.slow
@pytest.mark.parametrize("case", CASES, ids=[c[0] + f"-{i}" for i, c in enumerate(CASES)])
def test_throws_through_the_wall_modes_match_the_engine(case):
    """Against the engine at half and a quarter of its default step: rigid_body within 0.5 mm of either. On
    rectangle+lead-0 (μ = 2.13) the engine's steps split between two rests 0.94 mm apart — against the wall, at
    rigid_body's x = L − u_R, and just short of it (dt, dt/2: short; dt/4: at the wall; with exact flight off the
    other way round at dt/4 and dt/8): the engine has not converged there, and rigid_body is one of its answers."""
    from throwmap.engine.settings import EngineSettings

    name, x, side, om, alpha, mu, h, length, wall_mu = case
    args = (_parts()[name], tm.Arm(h=h, mu=mu, length=length), x, side, om)
    kw = dict(fixtures=(tm.Wall(0.05, mu=wall_mu),), alpha=alpha)
    o = tm.throw(*args, "rigid_body", **kw)
    runs = [tm.throw(*args, "engine", settings=EngineSettings(dt=1.25e-4 / f, coarse_dt=5e-4 / f), **kw) for f in (2, 4)]
    for e in runs:
        assert (o.status.label, o.side) == (e.status.label, e.side)
    assert min(abs(o.x - e.x) for e in runs) <= 0.5e-3


# ------------------------------------------------------------------------------------------ CORNER
def _pentagon_on_corner(vx, vy, om, gx=0.5):
    """A 5 cm pentagon whose edge 0 touches the corner (0.3, 0.05) at its middle, normal velocity 0."""
    from throwmap.kernels.rigid_body.wall_corner import edge_body

    part = regular_polygon(5, 0.05)
    w = np.asarray(part.w, dtype=float)
    nx, ny, tx, ty, le = edge_body(w, 0)
    phi = math.atan2(-0.5, 1.0) - math.atan2(ny, nx)  # the edge's outward normal along (1, −0.5)
    c, s = math.cos(phi), math.sin(phi)
    rot = np.array([[c, -s], [s, c]])
    a, b = rot @ w[0], rot @ w[1]
    Q = np.array([0.3, 0.05])
    X = Q - 0.5 * (a + b)
    n = rot @ np.array([nx, ny])
    r = Q - X
    V = np.array([vx, vy])
    V = V + (om * (-n[1] * r[0] + n[0] * r[1]) - n @ V) * n  # g' = 0
    return part, w, np.array([X[0], X[1], phi, V[0], V[1], om]), (nx, ny, tx, ty), gx


@pytest.mark.parametrize("mu_w", [0.0, 0.4])
def test_corner_slide_matches_a_free_body_integration(mu_w):
    from throwmap.kernels.rigid_body.wall_corner import corner_phase, corner_select

    part, w, s0, (nx, ny, tx, ty), gx = _pentagon_on_corner(0.3, -0.2, -2.0)
    rho2 = part.radius_of_gyration ** 2
    L, h, top = 0.3, 0.0, 0.05
    mode, sig = corner_select(s0, 0, w, rho2, gx, G, mu_w, L, h, top, False)
    assert mode == 0
    ev, k, s1, t = corner_phase(s0, 0, False, sig, 0.0, w, rho2, gx, G, mu_w, h, L, top, -1, 0.0, 0.0, 100000, NO_TRAJ,
                                np.zeros(3))
    assert t > 0.01
    Q = np.array([L, h + top])

    def rhs(_t, q):  # the free body with the corner's force from g'' = 0 (linear in λ: two evaluations)
        x, y, ph, vx, vy, om = q
        c, s = math.cos(ph), math.sin(ph)
        n = np.array([c * nx - s * ny, s * nx + c * ny])
        tt = np.array([c * tx - s * ty, s * tx + c * ty])
        r = Q - np.array([x, y])
        V = np.array([vx, vy])
        sg = np.sign(tt @ (V + om * np.array([-r[1], r[0]]))) if mu_w > 0 else 0.0

        def gdd(lam):
            F = -lam * n - mu_w * sg * lam * tt
            A = np.array([gx, -G]) + F
            wd = (r[0] * F[1] - r[1] * F[0]) / rho2
            jn = np.array([-n[1], n[0]])
            return wd * (jn @ r) - om ** 2 * (n @ r) - 2 * om * (jn @ V) - n @ A, A, wd

        g0, g1 = gdd(0.0)[0], gdd(1.0)[0]
        _, A, wd = gdd(-g0 / (g1 - g0))
        return [vx, vy, om, A[0], A[1], wd]

    ref = solve_ivp(rhs, (0.0, t), s0, rtol=1e-11, atol=1e-13).y[:, -1]
    assert np.allclose(s1[:3], ref[:3], atol=1e-8)
    assert np.allclose(s1[3:], ref[3:], atol=1e-6)

    def energy(q):
        return 0.5 * (q[3] ** 2 + q[4] ** 2 + rho2 * q[5] ** 2) - gx * q[0] + G * q[1]

    if mu_w == 0.0:
        assert energy(s1) == pytest.approx(energy(s0), abs=1e-8)
    else:
        assert energy(s1) < energy(s0)


@settings(max_examples=300, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_corner_departure_window_is_a_true_lower_bound(seed):
    """Inside the window the corner stays outside the edge's line, on the exact free flight (rotation included)."""
    from throwmap.kernels.rigid_body.wall import corner_departure

    rng = np.random.default_rng(seed)
    q = rng.uniform(-0.05, 0.05, 2)  # Q − CM at t = 0
    ang = rng.uniform(0, 2 * math.pi)
    n0 = np.array([math.cos(ang), math.sin(ang)])
    V = rng.uniform(-1, 1, 2)
    om = rng.uniform(-15, 15)
    V = V + (om * (-n0[1] * q[0] + n0[0] * q[1]) - n0 @ V) * n0  # gap rate 0
    gx, gn = rng.uniform(-2, 2), G
    win = corner_departure(q[0], q[1], V[0], V[1], om, gx, gn, n0[0], n0[1], 1.0)
    d = n0 @ q  # the edge's support: gap 0 at t = 0
    for s in np.linspace(0.0, win, 50)[1:]:
        X = V * s + 0.5 * np.array([gx, -gn]) * s * s  # CM displacement
        n = np.array([math.cos(ang + om * s), math.sin(ang + om * s)])
        assert n @ (q - X) - d >= -1e-12


def test_a_start_inside_the_wall_is_refused():
    from throwmap.studies.validation import default_parts

    pent = default_parts()["pentagon"]
    arm = tm.Arm(h=-0.01, mu=0.89, length=0.289)
    wall = (tm.Wall(0.05),)
    o = tm.throw(pent, arm, 0.2515, 3, 4.86, "rigid_body", fixtures=wall)
    assert o.status.label == "invalid_start" and "into the wall" in o.message
    b = tm.throw_batch(pent, arm, [0.2, 0.2515], 3, 4.86, fixtures=wall, on_invalid="status")
    assert [tm.Status(int(v)).label for v in b.status] == ["ok", "invalid_start"]
    with pytest.raises(tm.ThrowmapError, match=r"x\[1\].*into the wall"):
        tm.throw_batch(pent, arm, [0.2, 0.2515], 3, 4.86, fixtures=wall)
    # a square flush with the wall is a valid start (its outline touches the face, does not enter it)
    from throwmap.system.starts import start_interval

    sq = rectangle(0.06, 0.06)
    arm = tm.Arm(h=-0.01, mu=1.0, length=0.3)
    flush = start_interval(sq, arm, 0)[1]
    o = tm.throw(sq, arm, flush, 0, 3.0, fixtures=(tm.Wall(0.05, mu=0.0),))
    assert o.status.label == "ok" and o.side == 0 and abs(o.x - flush) < 1e-5
    # a wall lower than the part's overhang: the part may reach beyond the face above the wall's top
    from throwmap.system.starts import wall_reach

    assert wall_reach(pent, 3, 0.001) < wall_reach(pent, 3, 0.05)


def test_an_orbit_ends_cleanly_where_a_rest_is_not_a_start():
    """A part at rest leaning on the wall reports its CM's x, which may lie past the last flat start: the orbit
    ends there with status invalid_start and says why (it used to raise on the next throw)."""
    part = tm.triangle_30_60_90()
    arm = tm.Arm(h=-0.0116, mu=2.75, length=0.404)
    w = (tm.Wall(0.0405, mu=math.inf),)
    al = math.radians(-13.22)
    first = tm.throw(part, arm, 0.2986, 1, 3.32, fixtures=w, alpha=al)
    orbit = tm.iterate(part, arm, (0.2986, 1), 3.32, n=5, fixtures=w, alpha=al)
    assert first.status.label == "ok"
    if first.x + float(part.uR[first.side]) > arm.length:  # the rest leans past the last start
        assert orbit.status.label == "invalid_start" and len(orbit.outcomes) == 2
        assert "not a start of the map" in orbit.outcomes[-1].message


@pytest.mark.parametrize("x", [0.2699, 0.2695, 0.269, 0.268, 0.266])
def test_the_square_near_a_rough_wall_resolves(x):
    """Near a wall as rough as the arm (μ = 1) the square jams or rests; no Zeno loop (no_rest) and no false
    inconsistency where the face contact simply lets go."""
    part = tm.rectangle(0.06, 0.06)
    arm = tm.Arm(h=-0.01, mu=1.0, length=0.30)
    o = tm.throw(part, arm, x, 0, 3.0, "rigid_body", fixtures=(tm.Wall(0.05),))
    assert o.status.label == "ok"
    assert 0.25 < o.x <= 0.27 + 1e-12


def test_a_start_past_the_arm_is_refused_for_that_reason_with_or_without_a_wall():
    sq = rectangle(0.06, 0.06)
    arm = tm.Arm(h=-0.01, mu=1.0, length=0.30)
    wall = (tm.Wall(0.05),)
    with pytest.raises(tm.ThrowmapError, match="beyond the arm's end"):
        tm.throw(sq, arm, 0.29, 0, 3.0, fixtures=wall)
    with pytest.raises(tm.ThrowmapError, match=r"x\[0\].*beyond the arm's end"):
        tm.throw_batch(sq, arm, [0.29], 0, 3.0, fixtures=wall)


def test_a_sliding_pivot_watches_the_face_below_the_top_and_the_top_corner():
    """slide.py's wall guard: a vertex above the wall's top passes over it; the top corner is found on an edge."""
    from throwmap.kernels.rigid_body.slide import _wall_gap

    sq = rectangle(0.06, 0.06)
    w = np.asarray(sq.w, dtype=float)
    jp = int(np.argmin(w[:, 1] + 1e-9 * w[:, 0]))  # a bottom vertex as the pivot A
    wv = np.zeros((4, 3))
    fill_wall_vertices(math.pi / 4, 0.0, w, jp, wv)  # unrotated square, A → CM at 45°
    L = 0.2
    wv[:, 2] = math.inf  # no top: the plain face guard, L − x_j
    xs = [wv[j, 0] * math.cos(math.pi / 4 + wv[j, 1]) for j in range(4)]
    assert _wall_gap(0.1, math.pi / 4, L, wv) == pytest.approx(L - 0.1 - max(xs))
    wv[:, 2] = 0.03  # a wall half the square's height: its right side reaches the face below the top
    assert _wall_gap(0.1, math.pi / 4, L, wv) == pytest.approx(L - 0.1 - max(xs))
    wv[:, 2] = 0.01  # the right side's lower end is below the top, the upper end above: the corner meets the side
    g = _wall_gap(L - max(xs), math.pi / 4, L, wv)
    assert g == pytest.approx(0.0, abs=1e-12)
    # past the face above the top: only the corner's distance counts, and it is negative (inside the part)
    assert _wall_gap(L - max(xs) + 0.005, math.pi / 4, L, wv) < 0.0

"""Model "paper": physics invariants of single throws (Sec. III, Eqs. 1–4)."""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from scipy.spatial import ConvexHull

import throwmap as tm
from throwmap.errors import InvalidStateError
from throwmap.kernels import codes as C

OMEGAS = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]


def _impact_geometry(part, arm, o):
    """CM position and contact vector r at the first impact, from Eq. (1)."""
    k, x0, w, t = o.side0, o.x0, o.omega, o.t_flight
    d = part.d[k]
    xc = x0 - (arm.h + d) * w * t
    yc = arm.h + d + x0 * w * t - 0.5 * arm.g * t * t
    return xc, yc, np.array([o.contact_x - xc, arm.h - yc])


def _grid(part, n=25, x_hi=0.45):
    for s in part.stable_sides:
        for x in np.linspace(part.x_min(s), x_hi, n + 1)[1:]:
            yield float(x), s


def _check_invariants(part, arm, o):
    rho2 = part.radius_of_gyration**2
    m = part.mass
    # energy conserved in flight: release = kinetic + potential at impact
    assert o.kinetic_pre + o.potential_impact == pytest.approx(o.energy_release, rel=1e-9, abs=1e-15)
    # the contact vertex is on the arm line at impact, r is the vertex at the impact orientation
    xc, yc, r = _impact_geometry(part, arm, o)
    j = [part.user_vertex(q) for q in range(part.n_sides)].index(o.contact_vertex)
    phi = part.beta[o.side0] + o.omega * o.t_flight
    R = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
    assert np.allclose(R @ part.w[j], r, atol=1e-9)
    # angular momentum about the contact point conserved by the impact (Eq. 4)
    vx, vy, w = o.v_pre
    vxp, vyp, wp = o.v_post
    H_pre = rho2 * w + r[1] * vx - r[0] * vy
    H_post = rho2 * wp + r[1] * vxp - r[0] * vyp
    assert H_post == pytest.approx(H_pre, rel=1e-9, abs=1e-12)
    # no slip, no rebound: the contact point is at rest after impact
    vscale = 1e-9 * (abs(vx) + abs(vy) + 1e-3)
    assert vxp - wp * r[1] == pytest.approx(0.0, abs=vscale)
    assert vyp + wp * r[0] == pytest.approx(0.0, abs=vscale)
    # impulse is m Δv
    assert o.impulse[0] == pytest.approx(m * (vxp - vx), abs=1e-15)
    # impacts never add energy; the part ends with no more than it started with
    assert o.kinetic_post <= o.kinetic_pre * (1 + 1e-12) + 1e-15
    assert o.max_impact_energy_gain <= 1e-12 * max(o.energy_release, 1e-12)
    assert o.energy_final <= o.energy_release * (1 + 1e-12)
    if o.ok:
        assert part.stable[o.side]
        assert o.x + part.uL[o.side] > 0


@pytest.mark.parametrize("omega", OMEGAS)
def test_invariants_on_grid(canonical_part, arm, omega):
    for x, s in _grid(canonical_part):
        o = tm.throw(canonical_part, arm, x, s, omega, model="paper")
        _check_invariants(canonical_part, arm, o)


@pytest.mark.parametrize("omega", [1.0, 3.0, 5.0, 6.0])
def test_no_vertex_below_the_arm_before_contact(canonical_part, arm, omega):
    """Dense check of the first-contact guarantee (Eq. 3 for every vertex)."""
    part = canonical_part
    for x, s in _grid(part, n=12):
        o = tm.throw(part, arm, x, s, omega, model="paper")
        d = part.d[s]
        t = np.linspace(0.0, o.t_flight, 4001)
        phi = part.beta[s] + omega * t
        c, sn = np.cos(phi), np.sin(phi)
        vy = arm.h + d + x * omega * t - 0.5 * arm.g * t * t
        heights = vy[:, None] + sn[:, None] * part.w[None, :, 0] + c[:, None] * part.w[None, :, 1]
        assert heights.min() >= arm.h - 1e-11
        assert heights[-1].min() == pytest.approx(arm.h, abs=1e-10)


@pytest.mark.parametrize("omega", OMEGAS)
def test_jogs_are_outward_for_negative_h(canonical_part, arm, omega):
    part = canonical_part
    n_jogs = 0
    for s in part.stable_sides:
        xs = np.linspace(part.x_min(s), 0.5, 301)[1:]
        res = tm.throw_batch(part, arm, xs, s, omega, model="paper")
        jog = (res.status == tm.Status.OK) & (res.side == s)
        assert np.all(res.x[jog] > xs[jog])
        n_jogs += int(jog.sum())
    assert n_jogs > 0  # the check above ran on something


def test_jog_and_flip_both_occur_and_flip_moves_inward(triangle, arm):
    """Fig. 5 behaviour for the canonical triangle at ω = 4: jogs out, flips in."""
    xs = np.linspace(triangle.x_min(0), 0.6, 400)[1:]
    res = tm.throw_batch(triangle, arm, xs, 0, 4.0, model="paper")
    flip = (res.status == 0) & (res.side != 0)
    jog = (res.status == 0) & (res.side == 0)
    assert jog.any() and flip.any()
    assert np.all(res.x[flip] < xs[flip])
    assert xs[flip].min() > xs[jog].min()


def test_batch_matches_single_throws_and_broadcasts(triangle, arm):
    xs = np.linspace(0.11, 0.4, 7)
    om = np.array([[2.0], [4.5]])
    res = tm.throw_batch(triangle, arm, xs, 0, om, model="paper")
    assert res.x.shape == (2, 7) and res.records.shape == (2, 7, C.NREC)
    for i in range(2):
        for j in range(7):
            o = tm.throw(triangle, arm, xs[j], 0, om[i, 0], model="paper")
            assert res.x[i, j] == o.x and res.side[i, j] == o.side and res.status[i, j] == o.status
            assert res.record("t_flight")[i, j] == o.t_flight


def test_batch_invalid_starts(triangle, arm):
    xs = np.array([0.05, 0.2, np.nan])
    with pytest.raises(InvalidStateError) as err:
        tm.throw_batch(triangle, arm, xs, 0, 3.0, model="paper")
    assert err.value.field == "x[0]"
    res = tm.throw_batch(triangle, arm, xs, 0, 3.0, on_invalid="status", model="paper")
    assert list(res.status) == [tm.Status.INVALID_START, tm.Status.OK, tm.Status.INVALID_START]


def test_zero_omega_is_identity(triangle, arm):
    o = tm.throw(triangle, arm, 0.2, 1, 0.0, model="paper")
    assert (o.x, o.side, o.status) == (0.2, 1, tm.Status.OK)


@pytest.mark.parametrize(
    "x, side, omega, field",
    [(0.05, 0, 3.0, "x"), (0.2, 0, -1.0, "omega"), (math.nan, 0, 3.0, "x"), (0.2, 0, math.inf, "omega"),
     (0.2, 3, 3.0, "side"), (0.2, 1.5, 3.0, "side")],
)
def test_bad_starts(triangle, arm, x, side, omega, field):
    with pytest.raises(InvalidStateError) as err:
        tm.throw(triangle, arm, x, side, omega, model="paper")
    assert err.value.field == field


def test_arm_length_gives_off_end(triangle):
    """Starts up to the last admissible x; a rest is ok only with the whole support side on the arm."""
    from throwmap.system.starts import start_interval

    arm = tm.Arm(h=-0.01, length=0.3)
    xs = np.linspace(0.11, start_interval(triangle, arm, 0)[1], 200)
    res = tm.throw_batch(triangle, arm, xs, 0, 4.0, model="paper")
    assert np.any(res.status == tm.Status.OFF_END)
    ok = res.status == tm.Status.OK
    assert ok.any()
    assert np.all(res.x[ok] + triangle.uR[res.side[ok]] <= 0.3)


def test_hard_throw_leaves_behind_joint(triangle, arm):
    """Known fact: at ω = 5.6 rad/s, h = −1 cm the canonical triangle's orbit leaves the arm."""
    orbit = tm.iterate(triangle, arm, (0.12, 0), 5.6, n=500, model="paper")
    assert orbit.status == tm.Status.BEHIND_JOINT
    assert orbit.n_throws < 500


def test_relabelled_part_gives_the_same_throws(triangle, arm):
    v = list(triangle.vertices)
    q = tm.Part.from_vertices(v[1:] + v[:1], 0.05)
    offset = [o for o in range(3) if np.allclose(np.roll(triangle.d, -o), q.d)][0]
    for s in range(3):
        xs = np.linspace(triangle.x_min(s), 0.4, 50)[1:]
        a = tm.throw_batch(triangle, arm, xs, s, 4.0, model="paper")
        b = tm.throw_batch(q, arm, xs, (s - offset) % 3, 4.0, model="paper")
        assert np.allclose(a.x, b.x, atol=1e-12)
        assert np.array_equal((a.side - offset) % 3, b.side)


# ---------------------------------------------------------------- Hypothesis
@st.composite
def convex_parts(draw):
    n = draw(st.integers(3, 8))
    angles = np.sort(np.array(draw(st.lists(st.floats(0, 2 * np.pi), min_size=n, max_size=n, unique=True))))
    radii = np.array(draw(st.lists(st.floats(0.02, 0.08), min_size=n, max_size=n)))
    pts = np.c_[radii * np.cos(angles), radii * np.sin(angles)]
    try:
        hull = ConvexHull(pts)
    except Exception:
        assume(False)
    v = pts[hull.vertices]
    # refuse nearly collinear or tiny edges up front (the part constructor would refuse them)
    e = np.roll(v, -1, 0) - v
    L = np.hypot(e[:, 0], e[:, 1])
    assume(len(v) >= 3 and L.min() > 0.004)
    nxt = np.roll(e, -1, 0)
    assume(np.min(np.abs(e[:, 0] * nxt[:, 1] - e[:, 1] * nxt[:, 0]) / (L * np.roll(L, -1))) > 0.02)
    # a lead weight somewhere inside: convex combination of vertices
    wts = np.array(draw(st.lists(st.floats(0.01, 1.0), min_size=len(v), max_size=len(v))))
    at = (wts / wts.sum()) @ v
    m_pm = draw(st.floats(0.0, 0.2))
    pms = [(m_pm, tuple(at))] if m_pm > 1e-3 else []
    try:
        return tm.Part.from_vertices(v, 0.05, point_masses=pms)
    except tm.InvalidPartError:
        assume(False)


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(part=convex_parts(), data=st.data())
def test_random_convex_parts_satisfy_invariants(part, data):
    s = data.draw(st.sampled_from(part.stable_sides))
    x = part.x_min(s) + data.draw(st.floats(1e-3, 0.4))
    omega = data.draw(st.floats(0.3, 8.0))
    h = -data.draw(st.floats(0.01, 0.99)) * part.min_d
    arm = tm.Arm(h=h)
    o = tm.throw(part, arm, x, s, omega, model="paper")
    assert o.status in (tm.Status.OK, tm.Status.BEHIND_JOINT, tm.Status.OFF_END)
    assert math.isfinite(o.x) and math.isfinite(o.t_flight) and o.t_flight > 0
    _check_invariants(part, arm, o)


def _side_map(p, q):
    """σ with q's side σ(k) ≡ p's side k (same edge), from the edge geometry."""
    n = p.n_sides
    for o in range(n):
        if (np.allclose(np.roll(p.d, -o), q.d, atol=1e-12) and np.allclose(np.roll(p.uL, -o), q.uL, atol=1e-12)
                and np.allclose(np.roll(p.length, -o), q.length, atol=1e-12)):
            return lambda k, o=o: (k - o) % n
    raise AssertionError("no cyclic side map")


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(part=convex_parts(), data=st.data())
def test_rigid_motions_and_relabelling_change_nothing_but_labels(part, data):
    """Rotating/translating the body frame, shifting the vertex list or reversing it: same throws."""
    v = np.array(part.vertices)
    pms = [(m, np.array(at)) for m, at in part.point_masses]
    plate = part.mass - sum(m for m, _ in pms)
    ang = data.draw(st.floats(-np.pi, np.pi))
    shift = data.draw(st.integers(0, len(v) - 1))
    reverse = data.draw(st.booleans())
    off = np.array(data.draw(st.tuples(st.floats(-1, 1), st.floats(-1, 1))))
    R = np.array([[np.cos(ang), -np.sin(ang)], [np.sin(ang), np.cos(ang)]])
    w = v @ R.T + off
    w = np.roll(w, -shift, axis=0)
    if reverse:
        w = w[::-1]
    q = tm.Part.from_vertices(w, plate, point_masses=[(m, tuple(R @ at + off)) for m, at in pms])
    assert q.radius_of_gyration == pytest.approx(part.radius_of_gyration, rel=1e-9)
    sigma = _side_map(part, q)
    arm = tm.Arm(h=-0.5 * part.min_d)
    s = data.draw(st.sampled_from(part.stable_sides))
    x = part.x_min(s) + data.draw(st.floats(1e-3, 0.4))
    omega = data.draw(st.floats(0.3, 8.0))
    a = tm.throw(part, arm, x, s, omega, model="paper")
    b = tm.throw(q, arm, x, sigma(s), omega, model="paper")
    assert a.status == b.status
    assert b.x == pytest.approx(a.x, abs=1e-9)
    assert b.side == sigma(a.side)
    assert b.t_flight == pytest.approx(a.t_flight, rel=1e-9, abs=1e-12)

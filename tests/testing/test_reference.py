"""Model "paper": the compiled kernels against the independent SciPy reference.

:mod:`throwmap.testing.reference` recomputes each throw with different numerics (grid scan
+ brentq for first contact, a 5×5 linear system per impact, ``solve_ivp`` for the
pivot swings). Agreement required (per throw): same side, status, contact vertex,
impact and flip counts; |Δx| < 1e-6 m; |Δt_flight| < 1e-8 s. Throws whose outcome
sits within 1e-6 (relative) of a decision threshold (flip or fall back, lift or
stay down, which vertex lands first, a contact at the joint) are detected by the
reference, skipped explicitly and counted; few may be.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import throwmap as tm
from throwmap.kernels import codes as C
from throwmap.kernels.impact import plastic_impact
from throwmap.kernels.roll import roll_to_rest
from throwmap.records.outcome import Status
from throwmap.system.starts import start_interval
from throwmap.testing.reference import impact_linear_system, reference_roll, reference_throw, rest_geometry

X_TOL = 1e-6  # m
T_TOL = 1e-8  # s
V_RTOL = 1e-6  # relative, post-impact velocities and impulses
V_ATOL = 1e-6  # m/s: ≳ (g + ω²ℓ) T_TOL, what a flight-time difference within T_TOL moves a velocity
X_MIN_OFFSET = 1e-4  # m: "just above x_min" (see test_near_x_min_flight_time for closer starts)
X_MAX = 0.4  # m
OMEGAS = (2.0, 3.0, 4.0, 5.0, 6.0)  # rad/s
MAX_SKIPPED_FRACTION = 0.01

TRIANGLE = tm.triangle_30_60_90(0.17)
PENTAGON = tm.regular_polygon(5, 0.04)
RECTANGLE = tm.rectangle(0.08, 0.04)
TRIANGLE_OFFSET_CM = tm.triangle_30_60_90(0.17, point_masses=[(0.03, (0.10, 0.01))])
# an obtuse triangle with one unstable side: exercises tipping over an unstable side
OBTUSE = tm.Part.from_vertices([(0.0, 0.0), (0.1, 0.0), (0.3, 0.05)], mass=0.05, name="obtuse")

PARTS = {
    "triangle": TRIANGLE,
    "pentagon": PENTAGON,
    "rectangle": RECTANGLE,
    "triangle_offset_cm": TRIANGLE_OFFSET_CM,
}


# ------------------------------------------------------------------------------ helpers
def _outside_regime(part, arm) -> bool:
    return not (arm.h < 0 < arm.h + part.min_d)


def _x_grid(part, side, n_x, x_max=X_MAX):
    return np.linspace(part.x_min(side) + X_MIN_OFFSET, x_max, n_x)


def compare_throw(part, arm, x, side, omega):
    """Kernel vs reference for one throw: ``(skipped, problems)``."""
    k = tm.throw(part, arm, x, side, omega, model="paper")
    r = reference_throw(part, arm, x, side, omega)
    if r["ill_conditioned"]:
        return True, []
    where = f"{part.name} h={arm.h:g} L={arm.length} side={side} omega={omega:g} x={x!r}"
    problems = []

    def check(ok, what, kv, rv):
        if not ok:
            problems.append(f"{where}: {what}: kernel {kv!r} vs reference {rv!r}")

    check(k.status.label == r["status"], "status", k.status.label, r["status"])
    check(k.side == r["side"], "side", k.side, r["side"])
    check(k.contact_vertex == part.user_vertex(r["contact_vertex"]), "contact vertex (user index)",
          k.contact_vertex, part.user_vertex(r["contact_vertex"]))
    check(abs(k.x - r["x"]) < X_TOL, "x", k.x, r["x"])
    check(abs(k.t_flight - r["t_flight"]) < T_TOL, "t_flight", k.t_flight, r["t_flight"])
    check(k.n_impacts == r["n_impacts"], "n_impacts", k.n_impacts, r["n_impacts"])
    check(k.n_flips == r["n_flips"], "n_flips", k.n_flips, r["n_flips"])
    check(np.allclose(k.v_post, r["v_post"], rtol=V_RTOL, atol=V_ATOL), "v_post", k.v_post, r["v_post"])
    check(np.allclose(k.impulse, r["impulse"], rtol=V_RTOL, atol=V_ATOL * part.mass), "impulse (N s)", k.impulse,
          r["impulse"])
    # physics: no impact may create kinetic energy (both methods)
    check(r["max_impact_energy_gain"] <= 1e-12, "reference impact energy gain", None, r["max_impact_energy_gain"])
    check(k.max_impact_energy_gain <= 1e-12 * part.mass, "kernel impact energy gain", k.max_impact_energy_gain, None)
    return False, problems


def compare_grid(part, arm, omegas, n_x, x_max=X_MAX):
    """Compare every (stable side, ω, x) of a grid; assert agreement and few skips."""
    n = 0
    skipped = []
    problems = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tm.RegimeWarning)
        for side in part.stable_sides:
            for omega in omegas:
                for x in _x_grid(part, side, n_x, x_max):
                    n += 1
                    skip, probs = compare_throw(part, arm, float(x), side, omega)
                    if skip:
                        skipped.append((side, omega, float(x)))
                    problems += probs
    assert not problems, f"{len(problems)} disagreements of {n} throws, e.g.\n" + "\n".join(problems[:10])
    assert len(skipped) <= max(2, MAX_SKIPPED_FRACTION * n), f"{len(skipped)} of {n} ill-conditioned: {skipped[:10]}"
    return n, skipped


def _arm_checked(part, h, length=None):
    """The arm; outside the paper's regime a throw must warn (and the warning is an error otherwise)."""
    arm = tm.Arm(h=h, length=length)
    if _outside_regime(part, arm):
        side = part.stable_sides[0]
        with pytest.warns(tm.RegimeWarning):
            tm.throw(part, arm, part.x_min(side) + 0.05, side, 3.0, model="paper")
    return arm


# --------------------------------------------------------------------- throw map grids
def test_canonical_triangle_matches_reference():
    """The paper's 17 cm triangle on h = −1 cm, ω ∈ {2..6} rad/s, every stable side, x up to 0.4 m."""
    n, skipped = compare_grid(TRIANGLE, tm.Arm(h=-0.01), OMEGAS, n_x=40)
    assert n == 3 * len(OMEGAS) * 40


CASES = [(name, h) for name in PARTS for h in (-0.01, 0.01, -0.05) if not (name == "triangle" and h == -0.01)]


@pytest.mark.parametrize("name, h", CASES)
def test_parts_and_arms_match_reference(name, h):
    """Pentagon, rectangle, offset-CM triangle; h inside and outside the paper's regime (coarse grid)."""
    part = PARTS[name]
    compare_grid(part, _arm_checked(part, h), (2.0, 4.0, 6.0), n_x=8)


@pytest.mark.slow
@pytest.mark.parametrize("name, h", CASES)
def test_parts_and_arms_match_reference_dense(name, h):
    part = PARTS[name]
    compare_grid(part, _arm_checked(part, h), OMEGAS, n_x=24)


def test_unstable_side_part_matches_reference():
    """A part with an unstable side (it tips over it from rest) on an unbounded arm."""
    compare_grid(OBTUSE, tm.Arm(h=-0.003), (2.0, 3.0, 4.0, 6.0, 8.0), n_x=15, x_max=0.3)


def test_unstable_side_is_exercised():
    """Guard for the test above: some throw of the obtuse part lands on its unstable side and tips on."""
    assert not OBTUSE.stable[0] and OBTUSE.stable[1] and OBTUSE.stable[2]
    arm = tm.Arm(h=-0.003)
    n_flips = [reference_throw(OBTUSE, arm, x, 2, om)["n_flips"] for om in (4.0, 6.0, 8.0)
               for x in np.linspace(0.05, 0.3, 10)]
    assert max(n_flips) >= 2  # side 2 → 0 (unstable) → 1


# ---------------------------------------------------------------- edges of the arm
def test_near_x_min_flight_time():
    """Starts 1e-6 m above x_min: flights of ~1 µs, resolved to the reference's accuracy.

    The kernel evaluates the gap in a cancellation-free form (d + v_j = 0 exactly for
    the support vertices) and polishes the contact time with one Newton step.
    """
    arm = tm.Arm(h=-0.01)
    for side in TRIANGLE.stable_sides:
        for omega in OMEGAS:
            x = TRIANGLE.x_min(side) + 1e-6
            k = tm.throw(TRIANGLE, arm, x, side, omega, model="paper")
            r = reference_throw(TRIANGLE, arm, x, side, omega)
            assert (k.status.label, k.side) == (r["status"], r["side"])
            assert k.contact_vertex == TRIANGLE.user_vertex(r["contact_vertex"])
            assert abs(k.x - r["x"]) < X_TOL
            assert k.t_flight == pytest.approx(r["t_flight"], rel=1e-6)


FINITE_ARM = tm.Arm(h=-0.01, length=0.25)


@pytest.mark.parametrize("part", [TRIANGLE, RECTANGLE, OBTUSE], ids=["triangle", "rectangle", "obtuse"])
def test_finite_arm_agrees_including_landing_vertex_beyond_end(part):
    """On a finite arm every contact — first impact, side landings, rest — must be on the arm."""
    bad = []
    n = 0
    warnings.simplefilter("ignore", tm.RegimeWarning)  # inside pytest's per-test warnings context
    for side in part.stable_sides:
        for omega in (2.0, 3.0, 4.0, 5.0):
            lo, hi = start_interval(part, FINITE_ARM, side)
            for x in _x_grid(part, side, 16, x_max=min(0.25, hi)):
                if not lo < x <= hi:  # a side too long for this arm has no admissible start
                    continue
                k = tm.throw(part, FINITE_ARM, float(x), side, omega, model="paper")
                r = reference_throw(part, FINITE_ARM, float(x), side, omega)
                if r["ill_conditioned"]:
                    continue
                n += 1
                if not ((k.status.label, k.side) == (r["status"], r["side"]) and abs(k.x - r["x"]) < X_TOL):
                    bad.append((side, omega, float(x), k.status.label, r["status"]))
    assert n > 40 and not bad, bad[:5]  # the obtuse triangle has admissible starts on one side only


def test_finite_arm_landing_vertex_beyond_end_is_off_end():
    """Found by the reference: a rectangle falling back onto a landing vertex past the end."""
    x = start_interval(RECTANGLE, FINITE_ARM, 0)[1] - 1e-4  # the last starts throw() accepts on side 0
    k = tm.throw(RECTANGLE, FINITE_ARM, x, 0, 2.0, model="paper")
    r = reference_throw(RECTANGLE, FINITE_ARM, x, 0, 2.0)
    assert r["status"] == "off_end" and r["escape"] == "landing_vertex"
    assert k.status == Status.OFF_END
    geo = rest_geometry(RECTANGLE, r["side"])
    assert k.x <= FINITE_ARM.length < k.x + geo["uR"]  # CM on the arm, the landing vertex past its end


# ------------------------------------------------------------------- ill-conditioning
def _flip_threshold(part, arm, side, omega, lo, hi, iters=60):
    """x at which the kernel's throw turns from a jog (at lo) into a flip (at hi), by bisection."""
    def kind(x):
        return tm.throw(part, arm, x, side, omega, model="paper").kind

    assert kind(lo) == "jog" and kind(hi) == "flip"
    for _ in range(iters):
        mid = 0.5 * (lo + hi)
        if kind(mid) == "jog":
            lo = mid
        else:
            hi = mid
    return lo, hi


@pytest.mark.parametrize("side, omega", [(0, 5.0), (1, 4.0), (2, 4.0)])
def test_ill_conditioned_throws_are_flagged(side, omega):
    """At the jog/flip threshold the reference flags the throw, and agrees just off it."""
    arm = tm.Arm(h=-0.01)
    xs = _x_grid(TRIANGLE, side, 40)
    kinds = [tm.throw(TRIANGLE, arm, float(x), side, omega, model="paper").kind for x in xs]
    i = next(i for i in range(len(xs) - 1) if kinds[i] == "jog" and kinds[i + 1] == "flip")
    lo, hi = _flip_threshold(TRIANGLE, arm, side, omega, float(xs[i]), float(xs[i + 1]))
    assert hi - lo < 1e-12
    for x in (lo, hi):
        r = reference_throw(TRIANGLE, arm, x, side, omega)
        assert r["ill_conditioned"] and r["margins"]["energy"] < 1e-6
    for x in (lo - 1e-4, hi + 1e-4):
        skipped, problems = compare_throw(TRIANGLE, arm, x, side, omega)
        assert not skipped and not problems


# ---------------------------------------------------------------------- impact (Eq. 4)
finite = dict(allow_nan=False, allow_infinity=False)


@settings(max_examples=300, deadline=None)
@given(
    vx=st.floats(-5.0, 5.0, **finite),
    vy=st.floats(-5.0, 5.0, **finite),
    w=st.floats(-30.0, 30.0, **finite),
    rx=st.floats(-0.2, 0.2, **finite),
    ry=st.floats(-0.2, 0.2, **finite),
    rho=st.floats(1e-3, 0.2, **finite),
)
def test_plastic_impact_eq4_matches_linear_system(vx, vy, w, rx, ry, rho):
    """Eq. (4)'s closed form (kernel) = momentum/angular-momentum/contact-velocity equations solved directly."""
    rho2 = rho * rho
    kern = plastic_impact(vx, vy, w, rx, ry, rho2)
    vxp, vyp, wp, jx, jy = impact_linear_system(vx, vy, w, rx, ry, rho2)
    scale = abs(vx) + abs(vy) + abs(w) * (abs(rx) + abs(ry) + rho) + 1e-12  # m/s
    arm_len = max(rho, math.hypot(rx, ry))  # m
    assert np.allclose(kern[:2], (vxp, vyp), rtol=1e-8, atol=1e-12 * scale)
    assert math.isclose(kern[2], wp, rel_tol=1e-8, abs_tol=1e-12 * scale / arm_len)
    # the contact point stops, angular momentum about it is conserved, kinetic energy does not grow
    assert abs(vxp - wp * ry) <= 1e-10 * scale and abs(vyp + wp * rx) <= 1e-10 * scale
    h_pre = rho2 * w + ry * vx - rx * vy
    h_post = rho2 * wp + ry * vxp - rx * vyp
    assert abs(h_post - h_pre) <= 1e-10 * scale * (rho + abs(rx) + abs(ry))
    k_pre = vx * vx + vy * vy + rho2 * w * w
    k_post = vxp * vxp + vyp * vyp + rho2 * wp * wp
    assert k_post <= k_pre * (1 + 1e-12) + 1e-300
    assert np.allclose((jx, jy), (vxp - vx, vyp - vy), rtol=1e-12, atol=1e-12 * scale)


# ----------------------------------------------------------- pivot decision vs solve_ivp
ROLL_PARTS = [TRIANGLE, PENTAGON, RECTANGLE, TRIANGLE_OFFSET_CM, OBTUSE]


def _kernel_roll(part, arm, j, theta, thdot, px):
    rec = np.zeros(C.NREC)
    rec[C.N_MIN] = math.inf
    rec[C.K_MAX_IMPACT_GAIN] = -math.inf
    length = arm.length_or_inf
    x, k, status = roll_to_rest(j, theta, thdot, px, -1, part.radius_of_gyration**2, part.d, part.uL, part.uR,
                                part.ell, part.stable, arm.g, length, 10_000, 16, rec)
    if status == C.OK:  # the resting checks throw_one applies after roll_to_rest
        if x + part.uL[k] <= 0.0:
            status = C.BEHIND_JOINT
        elif x > length:
            status = C.OFF_END
    return x, k, Status(int(status)).label, int(rec[C.N_IMPACTS]), int(rec[C.N_FLIPS])


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    ipart=st.integers(0, len(ROLL_PARTS) - 1),
    j=st.integers(0, 7),
    frac=st.floats(0.02, 0.98, **finite),
    thdot=st.floats(-15.0, 15.0, **finite),
    px=st.floats(0.001, 0.5, **finite),
)
def test_pivot_decision_matches_integration(ipart, j, frac, thdot, px):
    """The kernels' energy/sense-of-rotation decision vs integrating I_P θ̈ = torque with solve_ivp.

    Start pivoting on vertex w_j anywhere between its two adjacent sides, at any
    rate and sense, with the pivot at world x ``px`` (near the joint some end
    behind it); both must land on the same sides, as often, and rest at the same x.
    """
    part = ROLL_PARTS[ipart]
    n = part.n_sides
    j %= n
    arm = tm.Arm(h=-0.01)
    qa = -rest_geometry(part, (j - 1) % n)["p"][j]  # pivot → CM resting on side j−1
    qb = -rest_geometry(part, j)["p"][j]  # ... resting on side j
    ta, tb = math.atan2(qa[1], qa[0]), math.atan2(qb[1], qb[0])
    theta = ta + frac * (tb - ta)
    psi = theta + math.pi - math.atan2(part.w[j][1], part.w[j][0])  # body angle with pivot → CM at theta
    r = reference_roll(part, arm, j, psi, thdot, px)
    assume(min(r["margins"]["energy"], r["margins"]["lift"]) >= 1e-6 and r["margins"]["position"] >= 1e-9)
    x, k, status, n_impacts, n_flips = _kernel_roll(part, arm, j, theta, thdot, px)
    assert (status, k) == (r["status"], r["side"])
    assert abs(x - r["x"]) < 1e-9
    assert (n_impacts, n_flips) == (r["n_impacts"], r["n_flips"])

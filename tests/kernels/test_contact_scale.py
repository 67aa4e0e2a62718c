"""First contact resolved at every scale of the flight (issue 10, items 1.1 and 3.2).

* Long flights: the contact search's tolerance is relative to the size of the gap's
  terms, so starts metres out at high ω never end in ``no_contact`` (with an absolute
  1e-14 m tolerance, 12 % of a 0.6–10 m scan at ω = 8 did).
* Tiny flights: a start δ above x_min flies for t* → 2ωδ/(g − dω²) as δ → 0 (the
  left support vertex's gap is ωδ t − ½(g − dω²) t² + O(t³)), so t_flight/δ must
  match that closed form for δ from 1e-12 to 1e-6 m (an absolute tolerance stopped
  the search at its first step: t_flight 19–26 % short).
* Flights beyond what double precision resolves are refused (UNRESOLVED), the same
  way by every analytic model.
"""

import numpy as np
import pytest

import throwmap as tm
from throwmap.kernels import codes as C
from throwmap.kernels.flight import MAX_SPIN_ANGLE

ANALYTIC = ("paper", "rigid_body", "small_angle", "small_angle2")
PARTS = {
    "triangle": lambda: tm.triangle_30_60_90(0.17),
    "rectangle": lambda: tm.rectangle(0.08, 0.04),
    "pentagon": lambda: tm.regular_polygon(5, 0.05),
}


@pytest.mark.filterwarnings("ignore::throwmap.RegimeWarning")
@pytest.mark.parametrize("model", ANALYTIC)
@pytest.mark.parametrize("part_name", sorted(PARTS))
@pytest.mark.parametrize("h", [-0.01, -0.002])
def test_long_flights_never_miss_the_contact(model, part_name, h):
    part = PARTS[part_name]()
    arm = tm.Arm(h=h)
    x = np.linspace(0.6, 10.0, 120)
    omega = np.array([4.0, 8.0, 30.0, 1e3])
    for k in np.flatnonzero(part.stable):
        xs = x[x + part.uL[k] > 0]
        b = tm.throw_batch(part, arm, xs[:, None], int(k), omega[None, :], model=model)
        assert not np.any(b.status == C.NO_CONTACT), (model, part_name, h, int(k))
        if model in ("paper", "rigid_body"):
            # a resolved contact: some vertex on the arm line at the reported time (relative to the flight's size)
            t = b.records[..., C.T_FLIGHT]
            assert np.all(np.isfinite(t[b.status != C.UNRESOLVED]))


@pytest.mark.parametrize("model", ["paper", "rigid_body"])
def test_contact_at_high_omega_is_on_the_line(triangle, model):
    """At ω = 1e3 and x = 10 m the CM at the reported first contact puts a vertex on y = h (to rounding of the flight)."""
    arm = tm.Arm(h=-0.01)
    k = int(np.flatnonzero(triangle.stable)[0])
    for om in (8.0, 1e3):
        b = tm.throw_batch(triangle, arm, np.array([0.6, 3.0, 10.0]), k, om, model=model)
        r = b.records
        t = r[:, C.T_FLIGHT]
        x0 = np.array([0.6, 3.0, 10.0])
        d = triangle.d[k]
        # CM height at contact (Eq. 1) and the contact vertex's height from the release pose
        yc = arm.h + d + x0 * om * t - 0.5 * arm.g * t * t
        j = r[:, C.CONTACT_VERTEX].astype(int)
        phi = triangle.beta[k] + om * t
        wv = triangle.w[j]
        vy = np.sin(phi) * wv[:, 0] + np.cos(phi) * wv[:, 1]
        scale = x0 * om * t + 0.5 * arm.g * t * t  # the size of the terms the height is summed from
        assert np.all(np.abs(yc + vy - arm.h) <= 1e-9 * scale + 1e-12)


@pytest.mark.parametrize("model", ["paper", "rigid_body"])
@pytest.mark.parametrize("omega", [2.0, 5.0])
def test_flight_time_just_above_x_min_matches_closed_form(model, omega):
    """t_flight/δ → 2ω/(g − dω²) for starts x_min + δ, δ from 1e-12 to 1e-6 m (no drift)."""
    part = tm.triangle_30_60_90(0.17)
    arm = tm.Arm(h=-0.01)
    for k in np.flatnonzero(part.stable):
        x_min = -float(part.uL[k])
        d = float(part.d[k])
        limit = 2.0 * omega / (arm.g - d * omega * omega)
        for delta in 10.0 ** np.arange(-12, -5.5, 1.0):
            x0 = x_min + delta
            eff = x0 + float(part.uL[k])  # δ as the floats have it (x0 + u_L is exact here)
            o = tm.throw(part, arm, x0, int(k), omega, model=model)
            ratio = o.t_flight / eff / limit
            assert abs(ratio - 1.0) < 1e-4, (model, int(k), delta, ratio)


@pytest.mark.filterwarnings("ignore::throwmap.RegimeWarning")
def test_unresolvable_flight_is_refused_by_every_analytic_model(triangle):
    """ω = 1e6 rad/s at x = 2e8 m: the spin angle at contact (~4e19 rad) is beyond double precision.

    Before, "small_angle" said ok and "paper" no_contact; now all refuse it the same way.
    """
    arm = tm.Arm(h=-0.01)
    k = int(np.flatnonzero(triangle.stable)[0])
    for model in ANALYTIC:
        b = tm.throw_batch(triangle, arm, np.array([2e8]), k, 1e6, model=model)
        assert int(b.status[0]) == C.UNRESOLVED, model


def test_spin_limit_is_where_double_precision_stops_resolving_the_angle():
    assert np.spacing(MAX_SPIN_ANGLE) <= 1e-6  # orientation still known to a micro-radian there
    assert np.spacing(1e3 * 2 * 1e3 * 10.0 / 9.81) < np.spacing(MAX_SPIN_ANGLE)  # the scan above stays inside


@pytest.mark.filterwarnings("ignore::throwmap.RegimeWarning")
def test_unresolved_through_throw_has_its_label(triangle):
    k = int(np.flatnonzero(triangle.stable)[0])
    for model in ANALYTIC:
        o = tm.throw(triangle, tm.Arm(h=-0.01), 2e8, k, 1e6, model=model)
        assert o.status.label == "unresolved" and not o.ok, model
    # small_angle2 has no contact when g ≤ d ω² (before: the "bug if ever seen" no_contact)
    o = tm.throw(triangle, tm.Arm(h=-0.01), 0.3, k, 100.0, model="small_angle2")
    assert o.status.label == "unresolved"

"""A frictionless arm (μ = 0) in model "rigid_body" (issue 10, item 2.1).

μ = 0 used to raise ZeroDivisionError (a flat slide decelerating at μ g) or, inside
a parallel batch, an opaque SystemError. Physics check: with μ = 0 every contact
force on the horizontal arm is vertical, so the CM's horizontal velocity never
changes: it stays −(h + d) ω from the release (Eq. 1), through every impact, slide
and landing, and the CM's x is linear in time for the whole throw.
"""

import math

import numpy as np
import pytest

import throwmap as tm
from throwmap.kernels import codes as C
from throwmap.records.outcome import Status

ARM0 = tm.Arm(h=-0.01, mu=0.0)


def _stable(part):
    return [int(k) for k in np.flatnonzero(part.stable)]


def test_throw_with_mu_zero(triangle):
    for k in _stable(triangle):
        o = tm.throw(triangle, ARM0, 0.3, k, 5.0, model="rigid_body")
        # inward horizontal velocity −(h + d) ω < 0 is never braked: the part slides off behind the joint
        assert o.status == Status.BEHIND_JOINT
        assert o.x == pytest.approx(-float(triangle.uL[o.side]) - ARM0.back)


def test_throw_batch_with_mu_zero_matches_throw(triangle):
    k = _stable(triangle)[0]
    x = np.linspace(0.1, 0.6, 40)
    b = tm.throw_batch(triangle, ARM0, x, k, 6.0, model="rigid_body")
    assert not np.any(b.status == C.NO_CONTACT)
    for i in (0, 17, 39):
        o = tm.throw(triangle, ARM0, x[i], k, 6.0, model="rigid_body")
        assert (o.x, o.side, int(o.status)) == (b.x[i], b.side[i], b.status[i])


@pytest.mark.parametrize("part_name", ["triangle", "rectangle", "pentagon"])
def test_horizontal_momentum_is_conserved_by_frictionless_contacts(part_name):
    part = {"triangle": tm.triangle_30_60_90(0.17), "rectangle": tm.rectangle(0.08, 0.04),
            "pentagon": tm.regular_polygon(5, 0.05)}[part_name]
    for k in _stable(part):
        x0 = -float(part.uL[k]) + 0.2
        for om in (3.0, 6.0, 9.0):
            vx = -(ARM0.h + part.d[k]) * om
            o = tm.throw(part, ARM0, x0, k, om, model="rigid_body")
            out, traj = tm.get_model("rigid_body").trajectory(part, tm.System(ARM0), x0, k, om,
                                                                tm.get_model("rigid_body").options_type(), 1e-3)
            assert int(out.status) == int(o.status)
            t = traj.t
            xcm = traj.poses[:, 0, 0]
            # x_cm(t) = x0 − (h + d) ω t for every sample: no horizontal impulse or force, ever
            # (1e-7 m: the RK4 accuracy of the sliding pivot phase)
            assert np.allclose(xcm, x0 + vx * t, rtol=0, atol=1e-7), (part_name, k, om)
            assert o.v_pre[0] == pytest.approx(vx, rel=1e-12)
            assert o.v_post[0] == pytest.approx(vx, rel=1e-12)  # the first impact has no horizontal impulse


def test_outward_slide_on_a_frictionless_arm():
    """h < −d: the release velocity −(h + d) ω points outward; a finite arm is left off its end, an unbounded
    one never lets the part come to rest (NO_REST), and the CM velocity is still unchanged."""
    part = tm.rectangle(0.08, 0.04)
    k = _stable(part)[0]
    h = -part.d[k] - 0.01
    for om in (2.0, 3.0, 5.0):
        with pytest.warns(tm.RegimeWarning):
            o = tm.throw(part, tm.Arm(h=h, mu=0.0, length=1.0), 0.3, k, om, model="rigid_body")
        assert o.status == Status.OFF_END
        assert 0.3 < o.x <= 1.0
        with pytest.warns(tm.RegimeWarning):
            o = tm.throw(part, tm.Arm(h=h, mu=0.0), 0.3, k, om, model="rigid_body")
        assert o.status == Status.NO_REST  # slides outward for ever ...
        assert o.n_impacts < 100  # ... decided at once, not by the impact cap


def test_critical_points_and_limit_set_with_mu_zero(triangle):
    cp = tm.critical_points(triangle, ARM0, 5.0, "rigid_body", n_grid=32)
    assert cp is not None
    ls = tm.limit_set(triangle, ARM0, 5.0, "rigid_body", n_starts=8)
    assert ls is not None


def test_mu_zero_is_a_valid_arm_and_tiny_mu_is_continuous(triangle):
    """μ → 0⁺ approaches μ = 0: the first impact's horizontal impulse vanishes with μ."""
    k = _stable(triangle)[0]
    o0 = tm.throw(triangle, ARM0, 0.3, k, 5.0, model="rigid_body")
    o1 = tm.throw(triangle, tm.Arm(h=-0.01, mu=1e-9), 0.3, k, 5.0, model="rigid_body")
    assert o0.t_flight == o1.t_flight
    assert math.isfinite(o1.x)

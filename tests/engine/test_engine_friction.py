"""Friction in the pymunk engine: high and infinite μ must not lose contacts (issue 10, item 3).

Chipmunk's solver diverges on a sliding contact when μ |K_nt| > K_nn; the engine
caps each arbiter's friction below that (:mod:`throwmap.engine.pymunk.friction`).
"""

import math

import numpy as np
import pytest

from throwmap import Arm, throw
from throwmap.engine import engine_throw
from throwmap.engine.pymunk.friction import CAP, cap_bound
from throwmap.system.catalogue import rectangle, triangle_30_60_90
from throwmap.records.outcome import Status

TRI = triangle_30_60_90()
XS = np.linspace(0.3, 0.6, 8)


@pytest.mark.parametrize("mu", [math.inf, 10.0])
def test_long_throws_at_high_friction_are_not_refused(mu):
    """Before the cap, 37/40 side-0 throws at 0.28–0.6 m, ω = 4 were refused as penetration at μ = ∞."""
    arm = Arm(h=-0.01, mu=mu)
    for x in XS:
        o = engine_throw(TRI, arm, float(x), 0, 4.0)
        assert o.status == Status.OK, (x, o.status)
        assert o.penetration_max < 0.5e-3


def test_high_friction_agrees_with_rigid_body_to_two_mm():
    """An independent model (rigid_body, exact Coulomb) at μ = 3: same side, |Δx| < 2 mm."""
    arm = Arm(h=-0.01, mu=3.0)
    for x in XS:
        e = engine_throw(TRI, arm, float(x), 0, 4.0)
        r = throw(TRI, arm, float(x), 0, 4.0, model="rigid_body")
        if r.status == Status.OK:
            assert e.status == Status.OK and e.side == r.side
            assert abs(e.x - r.x) < 2e-3, (x, e.x, r.x)


@pytest.mark.parametrize("part", [TRI, rectangle(0.06, 0.03)], ids=["triangle", "rectangle"])
def test_cap_bound_is_the_minimum_of_the_contact_ratio(part):
    """cap_bound = CAP · min over vertices and contact angles of K_nn/|K_nt| (brute force over angles)."""
    rho2 = part.radius_of_gyration**2
    th = np.linspace(1e-4, math.pi / 2 - 1e-4, 20001)
    best = math.inf
    for wx, wy in part.w:
        ell = math.hypot(wx, wy)
        rn, rt = ell * np.sin(th), ell * np.cos(th)
        best = min(best, float(np.min((1.0 + rn**2 / rho2) / (rn * rt / rho2))))
    assert cap_bound(part) == pytest.approx(CAP * best, rel=1e-6)


@pytest.mark.parametrize("fixtures", [(), "wall"], ids=["bare", "wall"])
def test_the_generic_friction_hook_caps_as_the_fast_ones(monkeypatch, fixtures):
    """The generic hook (:class:`FrictionCap`, two bodies, K from 1/m and 1/I) is the fallback where no fast hook
    exists; with the fast hooks switched off it caps the same solves (K_nn = 1/m + r_n²/I, K_nt = r_n r_t/I) and
    lands where they do. A slip in its K_nn (r_t² for r_n²) caps other solves and moves the landings."""
    from throwmap.engine import engine_run
    from throwmap.engine.pymunk import friction as F
    from throwmap.system.fixtures import Wall

    fix = (Wall(0.05, mu=2.0),) if fixtures == "wall" else ()
    lead = triangle_30_60_90(point_masses=[(0.03, (0.1, 0.01))])
    arm = Arm(h=-0.01, mu=10.0, length=0.40 if fix else None)
    starts = [(0.28, 0, 4.0), (0.25, 2, 5.0), (0.3, 1, 4.5)] if fix else [(0.3, 0, 4.0), (0.45, 0, 4.0), (0.25, 2, 6.0)]
    ref = [engine_run(lead, arm, x, k, om, fixtures=fix) for x, k, om in starts]
    assert sum(r.n_capped for r in ref) > 0  # the cap binds in these throws
    for name in ("_native_hook", "_single_part_hook", "_single_part_fixture_hook", "_multi_part_hook"):
        monkeypatch.setattr(F, name, lambda *a, **k: None)
    generic = [engine_run(lead, arm, x, k, om, fixtures=fix) for x, k, om in starts]
    for r, g in zip(ref, generic):
        assert g.n_capped == r.n_capped
        assert g.status == r.status and g.states[0][1] == r.states[0][1]
        assert abs(g.states[0][0] - r.states[0][0]) < 1e-6

"""The engine's friction-cap sensitivity used by validate-fixtures (studies/engine_cap.py)."""

import math

import numpy as np
import pytest

import throwmap as tm
from throwmap.studies.engine_cap import CAP_ALT, MOVED, cap_sensitive, friction_cap


def test_friction_cap_is_set_inside_the_block_and_restored_after_it():
    from throwmap.engine.pymunk import friction

    before = friction.CAP
    with friction_cap(CAP_ALT):
        assert friction.CAP == CAP_ALT
    assert friction.CAP == before
    with pytest.raises(RuntimeError):
        with friction_cap(0.8):
            raise RuntimeError
    assert friction.CAP == before


def test_cap_sensitive_marks_moves_side_and_status_changes():
    ref = {"x": np.array([0.1, 0.1, 0.1, 0.1]), "side": np.array([0, 0, 0, 0]), "status": np.array([0, 0, 0, 0])}
    alt = {"x": np.array([0.1 + 0.5 * MOVED, 0.1 + 2 * MOVED, 0.1, 0.1]), "side": np.array([0, 0, 1, 0]),
           "status": np.array([0, 0, 0, 10])}
    assert cap_sensitive(ref, alt).tolist() == [False, True, True, True]


@pytest.mark.slow
def test_a_slip_before_the_landing_at_high_mu_is_cap_bound_only_without_the_exact_solve(monkeypatch):
    """Throw 83 of validate-fixtures (wall-0, seed 0): with the capped solver (``friction.EXACT = False``) the engine
    moves when its cap is relaxed (rigid_body landed 0.86 mm from it); with the exact solve where the cap would bind
    (the default) relaxing the cap changes nothing; a throw at μ = 0.8 does not move either way."""
    from throwmap.engine.pymunk import friction

    tri = tm.triangle_30_60_90()
    bound = (tri, tm.Arm(h=-0.005, mu=2.024555560819926, length=0.37842149651658363), 0.28149619657876224, 2,
             3.8756595706315426)
    kw = dict(alpha=0.20131954884405256)
    calm = (tri, tm.Arm(h=-0.01, mu=0.8, length=0.6), 0.15, 1, 4.0)
    for exact in (False, True):
        monkeypatch.setattr(friction, "EXACT", exact)
        a = tm.throw(*bound, "engine", **kw)
        with friction_cap(CAP_ALT):
            b = tm.throw(*bound, "engine", **kw)
        assert a.status.label == b.status.label == "ok"
        assert (abs(a.x - b.x) > MOVED) is (not exact)
        c = tm.throw(*calm, "engine")
        with friction_cap(CAP_ALT):
            d = tm.throw(*calm, "engine")
        assert (c.status, c.side) == (d.status, d.side) and abs(c.x - d.x) <= MOVED
        assert math.isfinite(c.x)

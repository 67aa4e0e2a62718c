"""Statics answers at the edges of the range its docstrings give: a frictionless arm (μ = 0) for the lean-free
angle, and a least μ as small as about 1e-50 (the bisection's step cap)."""

import math

import pytest

import throwmap as tm
from throwmap.statics import edge_frame_cm, lean_free_beta, lean_possible
from throwmap.statics.rest import MAX_BISECTIONS, least_mu

TRI = tm.triangle_30_60_90()


@pytest.mark.parametrize("alpha", [0.0, math.radians(-10)])
def test_lean_free_beta_takes_a_frictionless_arm(alpha):
    a, b, _ = edge_frame_cm(TRI)
    beta = lean_free_beta(a, b, alpha, 0.0)
    assert 0.0 < beta <= math.pi / 2
    if beta < math.pi / 2:
        assert lean_possible(a, b, beta + 1e-9, alpha, 0.0) and not lean_possible(a, b, beta - 1e-9, alpha, 0.0)


def test_least_mu_finds_the_smallest_threshold_its_cap_allows():
    steps = []

    def ok(mu):
        steps.append(mu)
        return mu >= 1e-50

    assert least_mu(ok) == pytest.approx(1e-50, rel=1e-9)
    # ok(0), ok(inf), ok(1), then one call per bisection: exactly the cap, all of it needed
    assert len(steps) - 3 == MAX_BISECTIONS

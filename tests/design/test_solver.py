"""The Levenberg–Marquardt machinery (throwmap.design.solver) on smooth synthetic maps with known answers.

Independent of the throw map: the residuals are closed forms, so the root, the Jacobian, its
rank and condition number are known exactly.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from throwmap.design.solver import damped_lm, fd_jacobian, jacobian_summary


def box(lo, hi):
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)

    def project(p):
        q = np.clip(p, lo, hi)
        hits = tuple(f"p{j} bound" for j in range(len(p)) if q[j] != p[j])
        return q, hits

    return project


def smooth(target):
    """A nonlinear map R³ → R³ with a known preimage p* = (0.3, −0.2, 1.5) of f(p*) = target."""
    def f(p):
        x, y, w = p
        return np.array([x + 0.5 * y * y + 0.1 * w, math.sin(y) + x * w, w * w + 0.2 * x]) - target

    return f


P_STAR = np.array([0.3, -0.2, 1.5])


def test_reaches_a_known_root_from_afar():
    target = smooth(np.zeros(3))(P_STAR)
    f = smooth(target)
    rep = damped_lm(lambda p: (f(p), None), [1.0, 0.5, 0.7], project=box([-5] * 3, [5] * 3), scale=np.ones(3),
                    step=np.full(3, 1e-5), tol=1e-10, noise=1e-14)
    assert rep.success, rep.message
    assert np.allclose(rep.p, P_STAR, atol=1e-7)
    assert rep.jacobian_end.rank == 3
    # history: starts at p0, norms fall monotonically (every accepted step reduces |f|)
    norms = [it.norm for it in rep.iterates]
    assert np.allclose(rep.iterates[0].p, [1.0, 0.5, 0.7])
    assert all(b < a for a, b in zip(norms, norms[1:]))


def test_fd_jacobian_matches_the_analytic_one():
    f = smooth(np.zeros(3))
    p = np.array([0.4, 0.1, 1.2])
    J, n = fd_jacobian(lambda q: (f(q), None), p, f(p), np.full(3, 1e-6), box([-5] * 3, [5] * 3))
    x, y, w = p
    exact = np.array([[1.0, y, 0.1], [w, math.cos(y), x], [0.2, 0.0, 2 * w]])
    assert n == 6  # central differences: two evaluations per column
    assert np.allclose(J, exact, atol=1e-8)


def test_one_sided_difference_at_a_bound():
    f = smooth(np.zeros(3))
    p = np.array([0.0, 0.1, 1.2])  # x on its lower bound
    J, n = fd_jacobian(lambda q: (f(q), None), p, f(p), np.full(3, 1e-6), box([0.0, -5, -5], [5, 5, 5]))
    assert n == 5
    assert abs(J[0, 0] - 1.0) < 1e-5


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(0.01, 100.0), min_size=3, max_size=3), st.integers(0, 2**31 - 1))
def test_rank_and_condition_of_known_matrices(svals, seed):
    rng = np.random.default_rng(seed)
    U, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    V, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    s = np.array(sorted(svals, reverse=True))
    J = U @ np.diag(s) @ V.T
    js = jacobian_summary(J, np.ones(3), np.ones(3), noise=1e-14)
    assert js.rank == 3
    assert js.condition == pytest.approx(s[0] / s[-1], rel=1e-8)
    s[-1] = 0.0
    js = jacobian_summary(U @ np.diag(s) @ V.T, np.ones(3), np.ones(3), noise=1e-14)
    assert js.rank == 2
    assert js.condition > 1e12


def test_rank_deficient_two_parameters_moving_the_features_identically():
    """r_0 and r_1 depend on a + b only: rank 1 < 2 targets, an inconsistent target is unreachable."""
    def f(p):
        a, b = p
        s = a + b
        return np.array([s + 0.1 * s * s - 1.0, 2.0 * s - 3.0]), None

    rep = damped_lm(f, [0.1, 0.2], project=box([-5, -5], [5, 5]), scale=np.ones(2), step=np.full(2, 1e-6),
                    tol=1e-9, noise=1e-12)
    assert rep.jacobian_start.rank == 1 and rep.jacobian_end.rank == 1
    assert not rep.success
    assert "rank deficient" in rep.message and "rank 1" in rep.message


def test_unreachable_target_at_a_bound_says_so():
    """f = p² − (−1) has no root; within [0.5, 2] the best is the bound 0.5."""
    rep = damped_lm(lambda p: (np.array([p[0] ** 2 + 1.0]), None), [1.5], project=box([0.5], [2.0]),
                    scale=np.ones(1), step=np.full(1, 1e-6), tol=1e-9, noise=1e-12)
    assert not rep.success
    assert "bound" in rep.message
    assert rep.p[0] == pytest.approx(0.5)


def test_undefined_features_at_the_start():
    rep = damped_lm(lambda p: (np.array([math.nan]), None), [1.0], project=box([0.0], [2.0]), scale=np.ones(1),
                    step=np.full(1, 1e-6), tol=1e-9, noise=1e-12, labels=["r_0"])
    assert not rep.success and "undefined" in rep.message and "r_0" in rep.message

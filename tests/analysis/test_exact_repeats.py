"""Orbits of a deterministic map stop being thrown once they repeat exactly, and nothing changes.

The recurrence test's :func:`run_orbits` copies the rest of an orbit that came back to a
state it had p ≤ 16 throws before (bit for bit): the recorded tails, fates and escape steps
must equal those of throwing every orbit to the end, on maps with fixed points, cycles of
several periods, chaos, escapes and side changes.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import throwmap as tm
from throwmap.analysis.maps import FunctionMap
from throwmap.analysis.tails import run_orbits
from throwmap.models import model_names


def _map(kind: int, a: float, deterministic: bool, calls: list):
    """A two-sided map: kind 0 a contraction to a fixed point (rounded so it lands exactly),
    1 a period-p rotation of a few values, 2 the logistic map (chaos), 3 a doubling that escapes."""

    def f(x, s):
        calls.append(x.size)
        st_ = np.zeros(x.size, dtype=np.int64)
        if kind == 0:
            xn = np.round(0.5 + (x - 0.5) * a, 12)
        elif kind == 1:
            grid = np.linspace(0.1, 0.9, 7)
            k = np.argmin(np.abs(x[:, None] - grid[None, :]), axis=1)
            xn = grid[(k + 1 + int(a * 10) % 3) % 7]
        elif kind == 2:
            xn = 3.9 * x * (1 - x)
        else:
            xn = 0.5 + (x - 0.5) * (2 + a)
            st_[(xn <= 0) | (xn >= 1)] = 2
        sn = np.where(xn > 0.5, 1 - s, s)
        return xn, sn, st_

    return FunctionMap(f, {0: (0.0, 1.0), 1: (0.0, 1.0)}, deterministic=deterministic)


@settings(max_examples=40, deadline=None)
@given(kind=st.integers(0, 3), a=st.floats(0.05, 0.95), n=st.integers(1, 40),
       skip=st.integers(0, 60), rec=st.integers(1, 60), seed=st.integers(0, 2**31 - 1))
def test_exact_repeats_change_nothing(kind, a, n, skip, rec, seed):
    rng = np.random.default_rng(seed)
    x0 = rng.uniform(0.01, 0.99, n)
    s0 = rng.integers(0, 2, n)
    slow, fast = [], []
    ref = run_orbits(_map(kind, a, False, slow), x0, s0, skip, rec)
    got = run_orbits(_map(kind, a, True, fast), x0, s0, skip, rec)
    for r, g in zip(ref, got):
        np.testing.assert_array_equal(r, g)
    assert sum(fast) <= sum(slow)


def test_a_fixed_point_reached_exactly_is_not_thrown_on():
    slow, fast = [], []
    x0 = np.linspace(0.1, 0.9, 9)
    run_orbits(_map(0, 0.1, False, slow), x0, np.zeros(9, dtype=int), 200, 400)
    run_orbits(_map(0, 0.1, True, fast), x0, np.zeros(9, dtype=int), 200, 400)
    assert sum(slow) == 9 * 600
    assert sum(fast) <= 9 * 20


def test_a_throw_map_is_deterministic_and_its_limit_set_is_found_from_few_throws():
    """The walled square's fixed points (one per side against the wall) are reached to the
    last bit within a few throws; the limit set is the same as throwing the whole transient."""
    sq, arm = tm.rectangle(0.06, 0.06), tm.Arm(h=-0.01, mu=1.0, length=0.30)
    wall = tm.Wall(0.05, mu=0.0)
    cmap = tm.analysis.maps.ThrowMap(sq, arm, 3.0, "rigid_body", throw_options={"fixtures": (wall,)})
    assert cmap.deterministic
    calls = []

    def f(x, s):
        calls.append(x.size)
        return cmap(x, s)

    fast = FunctionMap(f, cmap.domain(), deterministic=True)
    x0 = np.linspace(0.2, 0.26, 8)
    s0 = np.arange(8) % 4
    X, S, fate, _ = run_orbits(fast, x0, s0, 200, 400)
    assert np.all(fate == 0) and sum(calls) < 8 * 50
    np.testing.assert_allclose(X[:, -1], 0.27 - 2.3e-6, atol=1e-6)


@pytest.mark.parametrize("model", model_names())
def test_every_model_throws_each_start_as_if_alone(model):
    """What ``ThrowMap.deterministic`` claims: a start's landing does not depend on the rest of the batch or its
    order (bit for bit), so an orbit that repeats exactly repeats for ever."""
    part, arm = tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01, length=0.6)
    xs = np.array([0.2, 0.25, 0.3, 0.22])
    a = tm.throw_batch(part, arm, xs, 0, 4.0, model)
    b = tm.throw_batch(part, arm, xs[::-1].copy(), 0, 4.0, model)
    alone = tm.throw(part, arm, float(xs[1]), 0, 4.0, model)
    np.testing.assert_array_equal(np.asarray(a.x).view(np.int64), np.asarray(b.x)[::-1].view(np.int64))
    np.testing.assert_array_equal(np.asarray(a.side), np.asarray(b.side)[::-1])
    assert np.float64(a.x[1]).tobytes() == np.float64(alone.x).tobytes()

"""Checks added by the mutation pass (tools/mutants.py) where the analysis tests let a slip through.

Each test names the mutant(s) it kills. All use synthetic maps or small objects whose
answer is known in closed form (a contraction's multiplier and Lyapunov exponent, a
rotation's period, a repeller's instability), never copied outputs.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from throwmap.analysis import Attractor, ConfigSet, FunctionMap, limit_set
from throwmap.records.outcome import Status

OK, BEHIND, OFF_END = int(Status.OK), int(Status.BEHIND_JOINT), int(Status.OFF_END)


def _ok(x):
    return np.zeros(x.size, dtype=np.int64)


def rotation(p, x=0.5):
    """Side s → side s + 1 (mod p), x kept: every orbit is a p-cycle with multiplier 1 (neutral)."""
    return FunctionMap(lambda x, s: (x.copy(), (s + 1) % p, _ok(x)), {s: (0.0, 1.0) for s in range(p)},
                       name=f"rotation {p}")


def contraction(a, k):
    return FunctionMap(lambda x, s: (a + k * (x - a), s, _ok(x)), {0: (0.0, 1.0)}, name=f"contraction {a} {k}")


def test_a_cycle_of_exactly_the_longest_period_sought_is_found():
    """A01: period p = max_period must be tested (range(1, max_period + 1))."""
    p = 6
    cyc = FunctionMap(lambda x, s: (0.2 + 0.5 * (x - 0.2), (s + 1) % p, _ok(x)),
                      {s: (0.0, 1.0) for s in range(p)}, name="contracting rotation")
    ls = limit_set(cyc, n_starts=2, max_period=p, n_record=4 * p, transient=200)
    assert ls.kind == "cycle", ls.summary()
    (cy,) = ls.attractors
    assert cy.period == p
    # closed form: every point at x = 0.2, one per side; T^p contracts by 0.5^p
    assert sorted(s for s, _ in cy.points) == list(range(p))
    assert cy.multiplier == pytest.approx(0.5 ** p, rel=1e-5)


def test_lyapunov_exponent_of_an_alternating_contraction_is_log_of_the_slope_size():
    """A07: the mean of log|dT/dx| over a cycle uses |slope|; a negative slope must not give NaN."""
    k = -0.5
    ls = limit_set(contraction(0.4, k), n_starts=8)
    (fp,) = ls.attractors
    assert fp.multiplier == pytest.approx(k, rel=1e-5)
    assert fp.lyapunov == pytest.approx(math.log(abs(k)), rel=1e-5)


def test_a_flipping_repeller_is_unstable():
    """A09: stability is |multiplier| < 1, so a multiplier of −2 is unstable."""
    a = 0.5

    def f(x, s):
        xn = a - 2.0 * (x - a)
        return xn, s, np.where(xn > 1.0, OFF_END, np.where(xn <= 0.0, BEHIND, OK))

    ls = limit_set(FunctionMap(f, {0: (0.0, 1.0)}, name="flipping repeller"), starts=(np.array([a, 0.3]), 0))
    (fp,) = ls.attractors
    assert fp.points == ((0, a),)
    assert fp.multiplier == pytest.approx(-2.0, rel=1e-6)
    assert fp.stable is False


def test_attractor_contains_is_a_closed_interval_widened_by_tol():
    """A10: contains(x, side, tol) is lo − tol ≤ x ≤ hi + tol at both ends."""
    a = Attractor(id=1, kind="band", period=0, points=(), bands=((0, 0.2, 0.3),), multiplier=math.nan,
                  lyapunov=0.1, fraction=1.0, side_visits=((0, 1.0),))
    tol = 1e-3
    x = np.array([0.2 - 0.5 * tol, 0.2, 0.25, 0.3, 0.3 + 0.5 * tol, 0.2 - 2 * tol, 0.3 + 2 * tol])
    assert a.contains(x, 0, tol).tolist() == [True] * 5 + [False] * 2
    assert not np.any(a.contains(x, 1, tol))


def test_config_set_contains_its_end_points_and_one_point_sets():
    """A12, A13: intervals are closed; a one-point interval (lo = hi) is a valid set containing its point."""
    cs = ConfigSet(((0, 0.2, 0.3), (1, 0.4, 0.4)))
    assert cs.contains(np.array([0.2, 0.3, 0.25]), 0).all()
    assert bool(cs.contains(0.4, 1)) and not bool(cs.contains(0.4 + 1e-9, 1))
    assert ConfigSet.parse("1:0.4").intervals == ((1, 0.4, 0.4),)


def test_stationarity_needs_both_ends_of_the_span_to_stay():
    """A02: tails whose lower end drifts while the upper end stays are not stationary (nor the converse)."""
    from throwmap.analysis.recurrence import _stationary

    S = np.zeros((1, 8), dtype=np.int64)
    steady = np.array([[0.1, 0.5, 0.1, 0.5, 0.1, 0.5, 0.1, 0.5]])
    low_drifts = np.array([[0.1, 0.5, 0.1, 0.5, 0.3, 0.5, 0.3, 0.5]])
    high_drifts = np.array([[0.1, 0.5, 0.1, 0.5, 0.1, 0.3, 0.1, 0.3]])
    assert _stationary(steady, S, 1e-3)
    assert not _stationary(low_drifts, S, 1e-3)
    assert not _stationary(high_drifts, S, 1e-3)


def test_converging_means_a_tail_still_shrinking_above_tol():
    """A03: a tail already within tol, or one that does not shrink, is not "still converging"."""
    from throwmap.analysis.recurrence import _converging

    settled = np.array([[0.3 + 1e-12, 0.3 - 1e-12, 0.3, 0.3, 0.3, 0.3]])
    wide = np.array([[0.1, 0.9, 0.1, 0.9, 0.1, 0.9]])
    shrinking = 0.3 + 0.1 * 0.5 ** np.arange(12)[None, :]
    assert not _converging(settled, 1e-8)
    assert not _converging(wide, 1e-8)
    assert _converging(shrinking, 1e-8)


def test_cycles_on_different_sides_are_different_even_at_the_same_x():
    """A04: two cycles are one only if every point matches in side *and* x."""
    from throwmap.analysis.cycles import _same_points

    assert _same_points(((0, 0.3), (1, 0.5)), ((0, 0.3), (1, 0.5)), 1e-8)
    assert not _same_points(((0, 0.3), (1, 0.5)), ((1, 0.3), (0, 0.5)), 1e-8)
    assert not _same_points(((0, 0.3), (1, 0.5)), ((0, 0.3), (1, 0.6)), 1e-8)


def test_two_disjoint_chaotic_bands_on_one_side_stay_two_attractors():
    """A06: bands merge only where their intervals overlap; two tents on disjoint intervals are two bands."""
    s = 1.9

    def f(x, side):
        lo = x < 0.5
        u = np.where(lo, x / 0.5, (x - 0.5) / 0.5)  # local coordinate in (0, 1)
        t = s * np.minimum(u, 1.0 - u)
        return np.where(lo, 0.5 * t, 0.5 + 0.5 * t), side, _ok(x)

    ls = limit_set(FunctionMap(f, {0: (0.0, 1.0)}, name="two tents"), n_starts=64)
    assert ls.kind == "several" and len(ls.attractors) == 2, ls.summary()
    a, b = ls.attractors
    assert a.kind == b.kind == "band"
    assert a.interval(0)[1] < 0.5 < b.interval(0)[0]


def test_fixed_points_far_apart_are_different_attractors():
    """A19: two fixed points are the same attractor only if |x_a − x_b| ≤ tol (either order)."""
    from throwmap.analysis.cellmap import _same_attractor

    def fp(x):
        return Attractor(id=1, kind="fixed_point", period=1, points=((0, x),), bands=((0, x, x),), multiplier=0.5,
                         lyapunov=math.log(0.5), fraction=0.5, side_visits=((0, 1.0),))

    assert _same_attractor(fp(0.2), fp(0.2 + 1e-9), 1e-6)
    assert not _same_attractor(fp(0.2), fp(0.8), 1e-6)
    assert not _same_attractor(fp(0.8), fp(0.2), 1e-6)


def test_escape_step_counts_the_throw_that_escaped():
    """A08: fate_step is the number of throws made, the escaping one included (1-based)."""
    from throwmap.analysis.recurrence import run_orbits

    def walk(x, s):
        xn = x + 0.1
        return xn, s, np.where(xn > 1.0, OFF_END, OK)

    cmap = FunctionMap(walk, {0: (0.0, 1.0)}, name="walk")
    x0 = np.array([0.05, 0.55, 0.95])
    X, S, fate, step = run_orbits(cmap, x0, np.zeros(3, dtype=np.int64), 2, 20)
    # x0 + 0.1 n > 1 first at n = 10, 5, 1
    assert step.tolist() == [10, 5, 1]
    assert fate.tolist() == [OFF_END] * 3
    # recorded from throw 3 on: the first start rests after throws 3..9, i.e. 7 recorded states
    assert np.isfinite(X[0]).sum() == 7 and np.isfinite(X[1]).sum() == 2 and np.isfinite(X[2]).sum() == 0


def test_hull_lower_end_waits_for_the_upper_end_to_settle():
    """A16: the hull iteration stops only when both ends have settled. Here the first image of the whole
    domain already starts at ~0 (a transient branch x > 0.9 lands next to the joint) while its upper end
    is still moving; every orbit ends on the fixed point 0.4, so l = 0.4."""
    from throwmap.analysis import critical_points

    def f(x, s):
        return np.where(x > 0.9, (x - 0.9) * 1e-7, 0.4 + 0.2 * (x - 0.4)), s, _ok(x)

    cp = critical_points(FunctionMap(f, {0: (0.0, 1.0)}, name="transient branch"))
    assert cp.l[0] == pytest.approx(0.4, abs=1e-5)

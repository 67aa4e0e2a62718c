"""Every cycle a limit set reports is a cycle of the map; a drift is no attractor (issue 10, item 3).

A map with no periodic orbit (x → x − 1e-4) once came out with seven "fixed points"
when the recurrence test compared steps without their sign, and with three "bands" as
it stood. Here the cycles are re-checked by the test itself, applying the map p times
(independently of the library's own check), on synthetic maps whose answer is known:
a drift, an irrational and a rational rotation, a true 2-cycle and contractions.
The recurrence functions are also tested directly, so that a slip in either of the
two checks (the recorded tails, the map's confirmation) is caught on its own.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from throwmap.analysis import Attractor, FunctionMap, LimitSet, basins, limit_set
from throwmap.analysis.caps import DEFAULT_CAPS
from throwmap.analysis.cycles import closing, cycle_residual
from throwmap.analysis.recurrence import _periods
from throwmap.errors import InvalidStateError
from throwmap.records.outcome import Status

OK, BEHIND = int(Status.OK), int(Status.BEHIND_JOINT)
TOL = DEFAULT_CAPS["tol"]
GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0


def _ok(x):
    return np.zeros(x.size, dtype=np.int64)


def drift(step=1e-4):
    """x → x − step: no periodic orbit, no attractor; orbits move on for ever."""
    return FunctionMap(lambda x, s: (x - step, s, _ok(x)), {0: (0.0, 1.0)}, name="drift")


def drift_to_the_joint(step=1e-4):
    """x → x − step, behind the joint (status BEHIND_JOINT) once x ≤ 0."""
    return FunctionMap(lambda x, s: (x - step, s, np.where(x - step <= 0.0, BEHIND, OK)), {0: (0.0, 1.0)},
                       name="drift to the joint")


def rotation(alpha):
    """x → x + α mod 1: a band [0, 1) for irrational α (Lyapunov 0); every orbit a q-cycle for α = p/q."""
    return FunctionMap(lambda x, s: (np.mod(x + alpha, 1.0), s, _ok(x)), {0: (0.0, 1.0)}, name=f"rotation {alpha:g}")


def two_cycle():
    """Side 0 → side 1 at 0.6 + 0.5 (x − 0.3), side 1 → side 0 at 0.3 − 0.4 (x − 0.6): the 2-cycle (0.3, 0), (0.6, 1)."""
    def f(x, s):
        return np.where(s == 0, 0.6 + 0.5 * (x - 0.3), 0.3 - 0.4 * (x - 0.6)), 1 - s, _ok(x)
    return FunctionMap(f, {0: (0.0, 1.0), 1: (0.0, 1.0)}, name="two-cycle")


def contraction(a=0.4, k=0.5):
    return FunctionMap(lambda x, s: (a + k * (x - a), s, _ok(x)), {0: (0.0, 1.0)}, name=f"contraction k={k}")


def _closes(cmap, a: Attractor, tol: float) -> float:
    """The test's own check: apply the map p times from the first point; every image on the next point's side."""
    x = np.array([a.points[0][1]])
    s = np.array([a.points[0][0]])
    worst = 0.0
    for k in range(1, a.period + 1):
        x, s, st = cmap.f(x, s)
        want_s, want_x = a.points[k % a.period]
        assert int(st[0]) == OK and int(s[0]) == want_s, f"{a!r}: image {k} escapes or changes side"
        worst = max(worst, abs(float(x[0]) - want_x))
    assert worst <= tol, f"{a!r}: |T^p(x) − x| = {worst:.3g} m > tol"
    return worst


# --- through limit_set: the same code path as a throw map ---------------------------------------------------


@pytest.mark.parametrize("cmap", [drift(), drift_to_the_joint(), drift(1e-6)], ids=["drift", "to_joint", "slow"])
def test_a_drifting_map_reports_no_cycle_and_no_band(cmap):
    ls = limit_set(cmap, n_starts=32)
    assert ls.attractors == () and ls.kind == "escape", ls.summary()
    assert np.all(ls.labels == -1)
    assert set(ls.escapes) <= {"unresolved", "behind_joint"} and "unresolved" in ls.escapes
    assert sum(ls.escapes.values()) == pytest.approx(1.0)


def test_a_drifting_map_has_no_basin_either():
    b = basins(drift(), grid=40, n_seeds=8, max_throws=50)
    assert b.attractors == () and np.all(b.labels == -1)
    assert not b.certificate.unique and "not unique" in b.certificate.statement


@pytest.mark.parametrize("cmap, kind, period", [
    (two_cycle(), "cycle", 2),
    (contraction(0.4, 0.5), "fixed_point", 1),
    (contraction(0.4, -0.95), "fixed_point", 1),  # a 2-cycle whose points coincide: iterated to a fixed point
    (contraction(0.4, 0.95), "fixed_point", 1),
], ids=["two_cycle", "contraction", "flip_contraction", "slow_contraction"])
def test_every_reported_cycle_closes_under_the_map(cmap, kind, period):
    ls = limit_set(cmap, n_starts=16)
    (a,) = ls.attractors
    assert a.kind == kind and a.period == period
    got = _closes(cmap, a, TOL)
    assert a.residual <= TOL and a.residual == pytest.approx(got, abs=1e-15)
    assert np.all(ls.labels == 1)


def test_a_rational_rotation_gives_cycles_that_close():
    ls = limit_set(rotation(0.25), starts=(np.array([0.1, 0.35, 0.8]), 0))
    assert ls.attractors and all(a.kind == "cycle" and a.period == 4 for a in ls.attractors)
    for a in ls.attractors:
        _closes(rotation(0.25), a, TOL)


def test_an_irrational_rotation_is_one_band_and_no_cycle():
    ls = limit_set(rotation(GOLDEN), n_starts=16)
    (a,) = ls.attractors
    assert a.kind == "band" and a.period == 0 and a.points == ()
    assert a.interval(0)[0] < 0.01 and a.interval(0)[1] > 0.99
    assert abs(a.lyapunov) < 1e-6


# --- the two checks, each on its own ------------------------------------------------------------------------


def test_recorded_tail_periods_need_equal_states_not_a_smaller_one():
    """A tail stepping down by 1e-4 (or up) repeats with no period: ``_periods`` compares |x_{n+p} − x_n|."""
    n = 64
    down = 0.5 - 1e-4 * np.arange(n)
    up = 0.5 + 1e-4 * np.arange(n)
    fixed = np.full(n, 0.4)
    alternating = np.where(np.arange(n) % 2 == 0, 0.3, 0.6)
    X = np.vstack([down, up, fixed, alternating])
    S = np.zeros_like(X, dtype=np.int64)
    assert _periods(X, S, 8, TOL).tolist() == [0, 0, 1, 2]
    S2 = S.copy()
    S2[2, 1::2] = 1  # the same x, alternately on another side: period 2, not 1
    assert _periods(X, S2, 8, TOL).tolist()[2] == 2


def test_the_map_confirms_a_cycle_only_if_it_closes():
    m = drift()
    assert cycle_residual(m, ((0, 0.5),)) == pytest.approx(1e-4)
    assert cycle_residual(two_cycle(), ((0, 0.3), (1, 0.6))) <= 1e-15
    assert cycle_residual(two_cycle(), ((0, 0.3), (0, 0.6))) == math.inf  # wrong side
    assert cycle_residual(drift_to_the_joint(), ((0, 5e-5),)) == math.inf  # escapes
    X = np.vstack([0.5 - 1e-4 * np.arange(8), np.full(8, 0.4)])
    S = np.zeros_like(X, dtype=np.int64)
    per = np.array([1, 1])
    assert closing(m, X, S, np.array([0]), per, TOL).tolist() == [False]
    assert closing(contraction(), X, S, np.array([1]), per, TOL).tolist() == [True]
    swap = FunctionMap(lambda x, s: (x, 1 - s, _ok(x)), {0: (0.0, 1.0), 1: (0.0, 1.0)}, name="swap sides")
    assert closing(swap, X[1:], S[1:], np.array([0]), per[1:], TOL).tolist() == [False]  # same x, other side
    up = np.vstack([0.5 + 1e-4 * np.arange(8)])
    assert closing(FunctionMap(lambda x, s: (x + 1e-4, s, _ok(x)), {0: (0.0, 1.0)}), up, S[:1], np.array([0]),
                   per[:1], TOL).tolist() == [False]


# --- the result holds only cycles the map closes ------------------------------------------------------------


def _fixed_point(residual):
    return Attractor(id=1, kind="fixed_point", period=1, points=((0, 0.5),), bands=((0, 0.5, 0.5),),
                     multiplier=1.0, lyapunov=0.0, fraction=1.0, side_visits=((0, 1.0),), residual=residual)


@pytest.mark.parametrize("residual", [1e-4, math.nan, math.inf])
def test_a_limit_set_refuses_a_cycle_the_map_does_not_close(residual):
    with pytest.raises(InvalidStateError) as err:
        LimitSet(attractors=(_fixed_point(residual),), escapes={}, starts_x=np.array([0.5]),
                 starts_side=np.array([0]), labels=np.array([1]), caps=dict(DEFAULT_CAPS), map_info={})
    assert err.value.field == "attractors" and "#1" in str(err.value)


def test_a_residual_survives_the_json_round_trip():
    ls = limit_set(two_cycle(), n_starts=4)
    back = LimitSet.from_dict(ls.to_dict())
    assert back.attractors[0].residual == ls.attractors[0].residual <= TOL

"""Critical points r_i = sup S and l_i = inf S (paper Sec. III-D, Sec. V).

r_i is checked throw by throw at the ends of its bracket and against a dense independent
sweep of ``throw_batch``; l_i against the lowest configuration that long plain orbits
reach, against the invariance of S, and against :func:`limit_set` (a second method).
Synthetic maps with r and l known in closed form test the search without physics.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import throwmap as tm
from throwmap.analysis import CriticalPoints, FunctionMap, critical_points, limit_set
from throwmap.errors import InvalidStateError
from throwmap.records.outcome import Status

OMEGA = 4.0  # rad/s: one band on all three sides of the canonical triangle
MODELS = ["paper", "rigid_body"]
OK, OFF_END = int(Status.OK), int(Status.OFF_END)


@pytest.fixture(scope="module", params=MODELS)
def model(request):
    return request.param


@pytest.fixture(scope="module")
def cps(triangle, arm):
    """Critical points of the canonical triangle at 4 rad/s, per model (computed once)."""
    return {m: critical_points(triangle, arm, OMEGA, m) for m in MODELS}


def _is_jog(o, side):
    return o.status == Status.OK and o.side == side


# --- r_i: where jogs end -------------------------------------------------------------------------------------


def test_r_switches_from_jog_to_non_jog_within_the_tolerance(triangle, arm, cps, model):
    cp = cps[model]
    assert cp.sides == triangle.stable_sides == (0, 1, 2)
    for s in cp.sides:
        r = cp.r[s]
        lo, hi = cp.r_bracket[s]
        assert math.isfinite(r) and lo < hi and hi == r
        assert hi - lo <= cp.xtol == 1e-6
        assert _is_jog(tm.throw(triangle, arm, r - 2e-6, s, OMEGA, model), s)
        assert _is_jog(tm.throw(triangle, arm, lo, s, OMEGA, model), s)
        at_r = tm.throw(triangle, arm, r, s, OMEGA, model)
        assert not _is_jog(at_r, s)
        # next_kind says what the throw at r does
        assert cp.next_kind[s] == (f"flip to side {at_r.side}" if at_r.status == Status.OK else at_r.status.label)


def test_every_x_between_the_first_jog_and_r_jogs_dense_sweep(triangle, arm, cps, model):
    cp = cps[model]
    for s in cp.sides:
        x_lo = triangle.x_min(s)
        spacing = (cp.x_max - x_lo) / 128  # the default bracketing grid
        assert x_lo < cp.jog_start[s] <= x_lo + spacing + 1e-12
        x = np.linspace(cp.jog_start[s], cp.r_bracket[s][0], 20_001)
        r = tm.throw_batch(triangle, arm, x, s, OMEGA, model)
        jog = (r.status == OK) & (r.side == s)
        assert np.all(jog), x[~jog][:5]


def test_flips_beyond_agrees_with_a_dense_sweep(triangle, arm, cps, model):
    """``flips_beyond`` and ``non_flips`` against 20 000 throws per side from r_i to x_max."""
    cp = cps[model]
    for s in cp.sides:
        x = np.linspace(cp.r[s], cp.x_max, 20_001)
        r = tm.throw_batch(triangle, arm, x, s, OMEGA, model)
        flip = (r.status == OK) & (r.side != s)
        spacing = (cp.x_max - triangle.x_min(s)) / 128
        if cp.flips_beyond[s]:
            assert np.all(flip) and cp.non_flips[s] == ()
        else:
            assert not np.all(flip) and cp.non_flips[s]
            # the first reported non-flip run starts within one grid spacing of the first non-flip found densely
            first = x[np.flatnonzero(~flip)[0]]
            a, b, what = cp.non_flips[s][0]
            assert abs(a - first) <= spacing and a <= b
            i = np.flatnonzero(~flip)[0]
            kind = "jog" if r.status[i] == OK else Status(int(r.status[i])).label
            assert what == kind
    # canonical triangle at 4 rad/s: on side 1 a hard throw far out rocks back (a jog) — the paper's
    # "every x ≥ r_i flips" does not hold there, and the dense sweep confirms it
    assert not cp.flips_beyond[1]


def test_r_is_the_same_switch_on_a_finer_grid(triangle, arm, cps, model):
    fine = critical_points(triangle, arm, OMEGA, model, n_grid=512, xtol=1e-7)
    for s in fine.sides:
        assert fine.r_bracket[s][1] - fine.r_bracket[s][0] <= 1e-7
        assert fine.r[s] == pytest.approx(cps[model].r[s], abs=1.1e-6)


# --- l_i = inf S ---------------------------------------------------------------------------------------------


def _orbit_minima(triangle, arm, model, n_orbits, n_skip, n_record, seed=1):
    """Lowest x per side over long plain ``throw_batch`` orbits from random starts, after ``n_skip`` throws."""
    rng = np.random.default_rng(seed)
    s = rng.integers(0, 3, n_orbits)
    x = np.array([rng.uniform(triangle.x_min(k) + 1e-3, 0.6) for k in s])
    mins = {k: math.inf for k in (0, 1, 2)}
    for i in range(n_skip + n_record):
        r = tm.throw_batch(triangle, arm, x, s, OMEGA, model)
        assert np.all(r.status == OK)
        x, s = r.x, r.side
        if i >= n_skip:
            for k in mins:
                on = s == k
                if np.any(on):
                    mins[k] = min(mins[k], float(x[on].min()))
    return mins


@pytest.mark.parametrize("model, n_orbits, n_record", [("paper", 1000, 400), ("rigid_body", 200, 300)])
def test_l_is_the_lowest_configuration_long_orbits_reach(triangle, arm, cps, model, n_orbits, n_record):
    cp = cps[model]
    assert cp.l_method == "hull"
    mins = _orbit_minima(triangle, arm, model, n_orbits, 300, n_record)
    for s in cp.sides:
        assert mins[s] >= cp.l[s] - 1e-6, (s, mins[s], cp.l[s])  # no orbit goes below inf S
        assert mins[s] - cp.l[s] <= 1e-3, (s, mins[s], cp.l[s])  # and orbits come close to it


def test_the_image_of_each_l_is_in_S(triangle, arm, cps, model):
    """S is forward invariant, so T(l_i, i) = (y, j) lies in S: y ≥ l_j (to the hull tolerance)."""
    cp = cps[model]
    for s in cp.sides:
        o = tm.throw(triangle, arm, cp.l[s], s, OMEGA, model)
        assert o.status == Status.OK
        assert o.x >= cp.l[o.side] - cp.xtol, (s, o.side, o.x - cp.l[o.side])


def test_l_agrees_with_the_limit_set_found_from_orbits(triangle, arm, cps):
    cp = cps["paper"]
    ls = limit_set(triangle, arm, OMEGA, "paper")
    for s in cp.sides:
        assert ls.l(s) >= cp.l[s] - 1e-6  # recorded orbit points lie in S
        assert ls.l(s) == pytest.approx(cp.l[s], abs=1e-3)
    taken = critical_points(triangle, arm, OMEGA, "paper", limit=ls)
    assert taken.l_method == "orbits" and taken.l == {s: ls.l(s) for s in cp.sides}
    assert taken.r == cp.r  # r does not depend on where l comes from


def test_critical_points_of_an_escaping_map_have_no_l(triangle, arm):
    cp = critical_points(triangle, arm, 5.6, "paper")
    assert cp.l_method == "orbits"  # the hulls are not trapping: l comes from orbits, and there are none
    assert cp.sides == (0, 1, 2) and all(math.isnan(cp.l[s]) for s in cp.sides)
    with_r = [s for s in cp.sides if math.isfinite(cp.r[s])]
    assert with_r  # the check below is not empty
    for s in with_r:  # r is still where jogs end
        assert _is_jog(tm.throw(triangle, arm, cp.r_bracket[s][0], s, 5.6, "paper"), s)
        assert not _is_jog(tm.throw(triangle, arm, cp.r[s], s, 5.6, "paper"), s)


# --- synthetic maps: r and l in closed form ------------------------------------------------------------------


def jog_flip(R=0.5123, a0=0.3, a1=0.25, k=0.5):
    """Side 0 jogs (contracting to a0) below R and flips to side 1 at 0.2 + k (x − R) from R on;
    side 1 always jogs, contracting to a1. S = {(a0, 0)} ∪ {(a1, 1)}: l_0 = a0, l_1 = a1."""
    def f(x, s):
        flip = (s == 0) & (x >= R)
        xn = np.where(s == 0, np.where(flip, 0.2 + k * (x - R), a0 + k * (x - a0)), a1 + k * (x - a1))
        return xn, np.where(flip, 1, s), np.zeros(x.size, dtype=np.int64)
    return FunctionMap(f, {0: (0.0, 1.0), 1: (0.0, 1.0)}, name="jog-flip")


def jog_escape(R=0.5123, a0=0.3, k=0.5):
    """Jogs (contracting to a0) below R; from R on the part leaves the arm's end."""
    def f(x, s):
        return np.where(x < R, a0 + k * (x - a0), x), s, np.where(x < R, OK, OFF_END)
    return FunctionMap(f, {0: (0.0, 1.0)}, name="jog-escape")


def test_synthetic_jog_flip_map():
    R = 0.5123
    cp = critical_points(jog_flip(R))
    lo, hi = cp.r_bracket[0]
    assert lo < R <= hi and hi - lo <= cp.xtol and cp.r[0] == hi
    assert cp.next_kind[0] == "flip to side 1" and cp.flips_beyond[0] and cp.non_flips[0] == ()
    assert math.isnan(cp.r[1]) and cp.next_kind[1] == "jogs to x_max" and not cp.flips_beyond[1]
    assert cp.l_method == "hull"
    assert cp.l[0] == pytest.approx(0.3, abs=1e-6) and cp.l[1] == pytest.approx(0.25, abs=1e-6)


def test_synthetic_jog_escape_map():
    R = 0.5123
    cp = critical_points(jog_escape(R))
    lo, hi = cp.r_bracket[0]
    assert lo < R <= hi and hi - lo <= cp.xtol
    assert cp.next_kind[0] == "off_end" and not cp.flips_beyond[0]
    ((a, b, what),) = cp.non_flips[0]
    assert what == "off_end" and R <= a <= R + 1.0 / 128 and b == pytest.approx(1.0)
    assert cp.l_method == "orbits" and cp.l[0] == pytest.approx(0.3, abs=1e-8)


def test_side_without_jogs():
    """A map that flips everywhere has no r on either side."""
    def f(x, s):
        return 0.5 + 0.5 * (x - 0.5), 1 - s, np.zeros(x.size, dtype=np.int64)
    cp = critical_points(FunctionMap(f, {0: (0.0, 1.0), 1: (0.0, 1.0)}))
    for s in (0, 1):
        assert math.isnan(cp.r[s]) and math.isnan(cp.jog_start[s]) and cp.next_kind[s] == "no jog"
        assert cp.l[s] == pytest.approx(0.5, abs=1e-6)


@settings(max_examples=25, deadline=None)
@given(R=st.floats(0.05, 0.95), xtol=st.sampled_from([1e-5, 1e-6, 1e-8]))
def test_property_r_brackets_the_switch(R, xtol):
    cp = critical_points(jog_flip(R, a0=0.3 * R, a1=0.25), xtol=xtol)
    lo, hi = cp.r_bracket[0]
    assert lo < R <= hi and hi - lo <= xtol
    assert cp.l[0] == pytest.approx(0.3 * R, abs=max(xtol, 1e-9))


def test_n_throws_counts_map_evaluations():
    calls = []

    def f(x, s):
        calls.append(x.size)
        return jog_flip().f(x, s)

    cp = critical_points(FunctionMap(f, {0: (0.0, 1.0), 1: (0.0, 1.0)}))
    assert cp.n_throws == sum(calls) > 2 * 128


# --- input checking and records ------------------------------------------------------------------------------


@pytest.mark.parametrize("kwargs, field", [
    ({"n_grid": 1}, "n_grid"), ({"n_grid": 64.0}, "n_grid"), ({"n_split": 0}, "n_split"),
    ({"hull_samples": 1}, "hull_samples"), ({"hull_max_iter": 0}, "hull_max_iter"), ({"xtol": 0.0}, "xtol"),
    ({"xtol": -1e-6}, "xtol"), ({"xtol": math.inf}, "xtol"), ({"xtol": True}, "xtol"), ({"x_max": 0.01}, "x_max"),
])
def test_bad_arguments_raise_one_line_errors(triangle, arm, kwargs, field):
    with pytest.raises(InvalidStateError) as err:
        critical_points(triangle, arm, OMEGA, "paper", **kwargs)
    assert err.value.field == field and "\n" not in str(err.value)


def test_missing_omega_or_arm(triangle, arm):
    with pytest.raises(InvalidStateError) as err:
        critical_points(triangle, arm)
    assert err.value.field == "omega"
    with pytest.raises(InvalidStateError) as err:
        critical_points(triangle, None, OMEGA)
    assert err.value.field == "arm"


def test_critical_points_round_trip_through_json(triangle, arm, cps):
    for cp in (cps["paper"], critical_points(jog_escape()), critical_points(triangle, arm, 5.6, "paper")):
        d = json.loads(json.dumps(cp.to_dict()))
        back = CriticalPoints.from_dict(d)
        assert back.to_dict() == d
        for s in cp.sides:
            assert back.r[s] == cp.r[s] or (math.isnan(back.r[s]) and math.isnan(cp.r[s]))
            assert back.non_flips[s] == cp.non_flips[s]


def test_table_lists_every_side_in_cm(cps):
    text = cps["paper"].table()
    lines = text.splitlines()
    assert len(lines) == 5
    assert lines[0].startswith("searched: x ≤ 60.0 cm")  # the range r_i, l_i and flips_beyond hold in
    for s, line in zip((0, 1, 2), lines[2:]):
        assert line.split()[0] == str(s)
        assert f"{100 * cps['paper'].r[s]:.4f}" in line

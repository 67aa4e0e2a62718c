"""Basins of attraction, the uniqueness certificate, funnels and pushed sets (paper Sec. I-A, III-D, Fig. 2).

Synthetic maps give basins, throw counts and funnel orders in closed form; the two basin
methods ("orbits", exact, and "cells", Hsu's cell mapping) check each other; ``push``
is checked against ``throw_batch`` applied throw by throw.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import throwmap as tm
from throwmap.analysis import (
    LABEL_ESCAPE,
    Basins,
    ConfigSet,
    FunctionMap,
    FunnelGraph,
    ThrowMap,
    basins,
    funnels,
    push,
)
from throwmap.analysis.cellmap import map_to_attractors
from throwmap.errors import InvalidStateError
from throwmap.records.outcome import Status

OK, BEHIND, OFF_END = int(Status.OK), int(Status.BEHIND_JOINT), int(Status.OFF_END)


def _ok(x):
    return np.zeros(x.size, dtype=np.int64)


def contraction(a=0.4, k=0.5, name=None):
    return FunctionMap(lambda x, s: (a + k * (x - a), s, _ok(x)), {0: (0.0, 1.0)}, name=name or f"to {a}")


def bistable(p=0.2, q=0.7, m=0.37, k=0.5, name="bistable"):
    """x < m contracts to p, x ≥ m to q: basins (0, m) and [m, 1]."""
    return FunctionMap(lambda x, s: (np.where(x < m, p + k * (x - p), q + k * (x - q)), s, _ok(x)),
                       {0: (0.0, 1.0)}, name=name)


def doubling_escape():
    """x → 2x on (0.01, 1]; beyond 1 the part is off the arm's end."""
    return FunctionMap(lambda x, s: (2 * x, s, np.where(2 * x > 1.0, OFF_END, OK)), {0: (0.01, 1.0)}, name="escape")


def repeller(a=0.5):
    def f(x, s):
        xn = a + 2.0 * (x - a)
        return xn, s, np.where(xn > 1.0, OFF_END, np.where(xn <= 0.0, BEHIND, OK))
    return FunctionMap(f, {0: (0.0, 1.0)}, name="repeller")


def _expected_throws(x, a, k, tol):
    """Throws until |a + k^n (x − a) − a| ≤ tol; and whether n is safely away from a rounding tie."""
    d = np.abs(x - a)
    with np.errstate(divide="ignore", invalid="ignore"):
        v = np.where(d <= tol, 0.0, np.log(tol / np.maximum(d, tol)) / np.log(abs(k)))
    n = np.ceil(v).astype(int)
    clear = (d <= tol) | (np.abs(v - np.round(v)) > 1e-6)
    return n, clear


# --- basins of synthetic maps --------------------------------------------------------------------------------


def test_contraction_basin_is_everything_and_throws_follow_the_closed_form():
    a, k, tol = 0.4, 0.5, 1e-6
    b = basins(contraction(a, k), grid=300, method="orbits", reach_tol=tol)
    assert b.method == "orbits" and b.n_configs == 300
    assert np.all(b.labels == 1) and np.all(b.fates == 0) and b.fractions == {1: 1.0}
    n, clear = _expected_throws(b.x, a, k, tol)
    assert np.count_nonzero(clear) >= 0.9 * clear.size  # the exact comparison below covers most of the grid
    np.testing.assert_array_equal(b.throws[clear], n[clear])
    assert np.all(np.abs(b.throws - n) <= 1)
    cert = b.certificate
    assert cert.unique and cert.attractor == 1 and cert.n_configs == 300
    assert cert.max_throws_to_reach == b.throws.max() and cert.trap_excursion == 0.0
    assert cert.grid_spacing == {0: pytest.approx(1.0 / 300)}


def test_cells_throw_counts_use_half_a_cell_as_the_reach_tolerance():
    """On the cell graph an orbit has arrived once it is within half a cell of the attractor.

    (With |k| ≥ 1/2 the cells next to the fixed point map onto themselves and every chain
    is finished by exact orbits instead; k = 0.3 keeps the cell graph itself at work.)
    """
    a, k = 0.4, 0.3
    b = basins(contraction(a, k), grid=300, method="cells", n_check=50)
    assert np.all(b.labels == 1) and b.check["agreement"] == 1.0
    assert b.check["n_exact_finish"] == 0
    half_cell = 0.5 / 300
    n, _ = _expected_throws(b.x, a, k, half_cell)
    assert np.all(np.abs(b.throws - n) <= 1)


def test_escaping_map_labels_everything_minus_one_off_end():
    b = basins(doubling_escape(), grid=200, method="orbits")
    assert np.all(b.labels == LABEL_ESCAPE) and np.all(b.fates == OFF_END)
    assert b.escapes == {"off_end": 1.0} and b.fractions == {-1: 1.0} and not b.attractors
    # 2^n x > 1 first at n = floor(log2(1/x)) + 1
    n = np.floor(np.log2(1.0 / b.x)).astype(int) + 1
    clear = np.abs(np.log2(1.0 / b.x) - np.round(np.log2(1.0 / b.x))) > 1e-9
    assert np.count_nonzero(clear) >= 0.9 * clear.size
    np.testing.assert_array_equal(b.throws[clear], n[clear])
    assert not b.certificate.unique and b.certificate.attractor is None
    assert "off_end" in b.certificate.statement


def test_two_attractors_split_the_grid_where_their_basins_meet():
    m, n = 0.37, 300
    bo = basins(bistable(m=m), grid=n, method="orbits")
    bc = basins(bistable(m=m), grid=n, method="cells", n_check=100)
    for b in (bo, bc):
        np.testing.assert_array_equal(b.labels, np.where(b.x < m, 1, 2))
        assert b.fractions[1] == pytest.approx(m, abs=1.01 / n)
        assert sum(b.fractions.values()) == pytest.approx(1.0)
        assert sum(a.fraction for a in b.attractors) == pytest.approx(1.0)
        assert not b.certificate.unique
    assert bc.check["agreement"] == 1.0


def test_unstable_fixed_point_on_the_grid_is_found_and_everything_else_leaves():
    b = basins(repeller(0.5), grid=200, method="orbits")
    (fp,) = b.attractors
    assert fp.kind == "fixed_point" and fp.stable is False
    on = np.flatnonzero(b.labels == fp.id)
    assert b.x[on].tolist() == [0.5]  # the grid point 100/200 is the fixed point itself
    below, above = b.x < 0.5, b.x > 0.5
    assert np.all(b.fates[below] == BEHIND) and np.all(b.fates[above] == OFF_END)
    assert b.escapes == pytest.approx({"behind_joint": 99 / 200, "off_end": 100 / 200})


def test_map_to_attractors_without_attractors_is_unresolved():
    cmap = contraction()
    labels, fates, throws = map_to_attractors(cmap, np.array([0.1, 0.9]), np.array([0, 0]), (), 1e-6, 7)
    assert labels.tolist() == [-1, -1] and fates.tolist() == [-1, -1] and throws.tolist() == [7, 7]


def test_grid_given_per_side_and_label_at():
    grid = {0: np.linspace(0.05, 0.95, 40)}
    b = basins(bistable(m=0.37), grid=grid, method="orbits")
    np.testing.assert_array_equal(b.x, grid[0])
    np.testing.assert_array_equal(b.label_at(b.x, 0), b.labels)
    assert b.label_at([0.1, 0.6], 0).tolist() == [1, 2]
    assert b.label_at([5.0], 0).tolist() == [LABEL_ESCAPE]  # far outside the grid


@settings(max_examples=15, deadline=None)
@given(m=st.floats(0.1, 0.9), n=st.integers(20, 200), seed=st.integers(0, 2**16))
def test_property_fractions_sum_to_one_and_match_the_split(m, n, seed):
    b = basins(bistable(p=0.5 * m, q=0.5 + 0.5 * m, m=m), grid=n, method="auto", rng=seed, n_seeds=16)
    assert sum(b.fractions.values()) == pytest.approx(1.0)
    assert set(b.fractions) <= {1, 2}
    assert b.fractions.get(1, 0.0) == pytest.approx(m, abs=1.01 / n)


# --- the two methods and the seed ----------------------------------------------------------------------------


def test_orbits_and_cells_agree_on_the_canonical_triangle(triangle, arm):
    bo = basins(triangle, arm, 4.0, "paper", grid=150, method="orbits")
    bc = basins(triangle, arm, 4.0, "paper", grid=150, method="cells", n_check=150)
    np.testing.assert_array_equal(bo.x, bc.x)
    np.testing.assert_array_equal(bo.labels, bc.labels)
    assert bc.check["n"] == 150 and bc.check["agreement"] == 1.0
    assert bo.certificate.unique and bc.certificate.unique


def test_same_seed_same_basins_and_another_seed_changes_only_the_check_sample():
    cmap = bistable()
    a = basins(cmap, grid=400, method="cells", n_check=50, rng=3)
    b = basins(cmap, grid=400, method="cells", n_check=50, rng=3)
    c = basins(cmap, grid=400, method="cells", n_check=50, rng=4)
    for field in ("x", "side", "labels", "fates", "throws"):
        np.testing.assert_array_equal(getattr(a, field), getattr(b, field))
        np.testing.assert_array_equal(getattr(a, field), getattr(c, field))
    assert a.check == b.check and a.to_dict() == b.to_dict()
    assert c.check["n"] == a.check["n"] == 50 and c.check["agreement"] == 1.0
    assert a.caps["rng"] == 3 and c.caps["rng"] == 4


def test_same_seed_same_basins_on_the_canonical_triangle(triangle, arm):
    a = basins(triangle, arm, 4.0, "paper", grid=100, method="cells", n_check=30, rng=9)
    b = basins(triangle, arm, 4.0, "paper", grid=100, method="cells", n_check=30, rng=9)
    c = basins(triangle, arm, 4.0, "paper", grid=100, method="cells", n_check=30, rng=10)
    assert a.to_dict() == b.to_dict()
    np.testing.assert_array_equal(a.labels, c.labels)
    np.testing.assert_array_equal(a.fates, c.fates)


def test_auto_method_switches_to_cells_on_big_grids():
    assert basins(contraction(), grid=100).method == "orbits"
    assert basins(contraction(), grid=20_001, n_check=10).method == "cells"


# --- the certificate on the canonical triangle ---------------------------------------------------------------


def test_certificate_unique_at_4_rad_s(triangle, arm):
    b = basins(triangle, arm, 4.0, "paper", grid=500, method="cells", n_check=300)
    cert = b.certificate
    assert cert.unique and cert.attractor == 1 and cert.n_configs == 1500
    assert b.fractions == {1: 1.0} and not b.escapes
    assert cert.check_agreement == 1.0 and cert.trap_excursion <= cert.trap_tol
    assert max(cert.grid_spacing.values()) <= (0.6 - min(triangle.x_min(s) for s in (0, 1, 2))) / 500 + 1e-12
    assert cert.max_throws_to_reach == b.throws.max() > 0
    assert "unique" in cert.statement
    # second method: exact plain orbits from the grid points that took longest end inside the band
    (band,) = b.attractors
    slow = np.argsort(b.throws)[-20:]
    x, s = b.x[slow].copy(), b.side[slow].copy()
    for _ in range(int(b.throws.max()) + 5):
        r = tm.throw_batch(triangle, arm, x, s, 4.0, "paper")
        assert np.all(r.status == OK)
        x, s = r.x, r.side
    assert np.all(band.contains(x, s, 1e-3))


def test_certificate_not_unique_at_5_6_rad_s(triangle, arm):
    b = basins(triangle, arm, 5.6, "paper", grid=500)
    cert = b.certificate
    assert not cert.unique and cert.attractor is None
    assert np.all(b.labels == LABEL_ESCAPE) and np.all(b.fates == BEHIND)
    assert b.escapes == {"behind_joint": 1.0} and b.fractions == {-1: 1.0}
    assert "behind_joint" in cert.statement


# --- bad input -----------------------------------------------------------------------------------------------


@pytest.mark.parametrize("kwargs, field", [
    ({"grid": 1}, "grid"), ({"grid": 2.5}, "grid"), ({"grid": True}, "grid"), ({"grid": "100"}, "grid"),
    ({"grid": [0.1, 0.2]}, "grid"), ({"grid": {0: [0.3]}}, "grid"), ({"grid": {0: [0.0, 0.4]}}, "grid"),
    ({"grid": {0: [0.3, math.nan]}}, "grid"),
    ({"method": "cell"}, "method"), ({"method": None}, "method"),
    ({"reach_tol": 0.0}, "reach_tol"), ({"trap_tol": -1.0}, "trap_tol"), ({"max_throws": 0}, "max_throws"),
    ({"n_check": -1}, "n_check"), ({"n_seeds": 0}, "n_seeds"), ({"rng": -1}, "rng"),
    ({"transient": -5}, "transient"), ({"n_record": 10, "max_period": 6}, "n_record"), ({"tol": 0}, "tol"),
])
def test_bad_basin_arguments_raise_one_line_errors(kwargs, field):
    with pytest.raises(InvalidStateError) as err:
        basins(contraction(), **kwargs)
    assert err.value.field == field and "\n" not in str(err.value)


def test_grid_on_an_unknown_side_is_refused():
    with pytest.raises(InvalidStateError) as err:
        basins(contraction(), grid={3: [0.3, 0.4]})
    assert "3" in str(err.value) and "\n" not in str(err.value)


def test_grid_behind_the_joint_is_refused(triangle, arm):
    with pytest.raises(InvalidStateError) as err:
        basins(triangle, arm, 4.0, "paper", grid={0: [0.05, 0.3]})
    assert err.value.field == "grid" and "behind" in str(err.value)


# --- records -------------------------------------------------------------------------------------------------


def test_basins_round_trip_through_json(triangle, arm):
    for b in (basins(triangle, arm, 4.0, "paper", grid=40, method="cells", n_check=10),
              basins(bistable(), grid=50), basins(doubling_escape(), grid=20)):
        d = json.loads(json.dumps(b.to_dict(arrays=True)))
        back = Basins.from_dict(d)
        assert back.to_dict(arrays=True) == d
        for field in ("x", "side", "labels", "fates", "throws"):
            np.testing.assert_array_equal(getattr(back, field), getattr(b, field))
        assert back.certificate == b.certificate or math.isnan(b.certificate.trap_excursion)
    with pytest.raises(InvalidStateError) as err:
        Basins.from_dict(json.loads(json.dumps(b.to_dict(arrays=False))))
    assert err.value.field == "grid"


def test_summary_mentions_attractors_escapes_check_and_certificate(triangle, arm):
    b = basins(bistable(), grid=50, method="cells", n_check=10)
    text = b.summary()
    assert "#1" in text and "#2" in text and "exact-orbit check" in text and "certificate" in text
    assert "off_end" in basins(doubling_escape(), grid=20).summary()


# --- funnels -------------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def funnel_graph():
    """Three synthetic maps on one side of (0, 1]:

    A contracts to 0.6; B sends x < 0.5 to 0.2 and x ≥ 0.5 to 0.7; C contracts to 0.3.
    Goal around 0.7: B#2 (spout 0.7) is in it; A's spout 0.6 lies in B#2's mouth; C's spout
    0.3 and B#1's spout 0.2 lie in A's mouth (not in B#2's). So B#2 > A > {C, B#1}.
    """
    A = contraction(0.6, name="A")
    B = bistable(p=0.2, q=0.7, m=0.5, name="B")
    C = contraction(0.3, name="C")
    return funnels(None, maps=[A, B, C], goal="0:0.69-0.71", grid=200)


def test_funnel_priority_order_on_synthetic_maps(funnel_graph):
    fg = funnel_graph
    names = [f.name for f in fg.funnels]
    assert names == ["A #1", "B #1", "B #2", "C #1"]
    ia, ib1, ib2, ic = range(4)
    assert fg.rank == {ib2: 0, ia: 1, ib1: 2, ic: 2}
    # rank 2: the bigger mouth first (C's mouth is all of (0, 1], B#1's is (0, 0.5))
    assert fg.order == (ib2, ia, ic, ib1)
    edges = {(i, j) for i, j, _ in fg.edges}
    assert (ia, ib2) in edges and (ic, ib2) not in edges and (ib1, ib2) not in edges
    assert (ic, ib1) in edges and (ic, ia) in edges and (ib1, ia) in edges
    assert all(share == 1.0 for _, _, share in fg.edges)
    assert fg.funnels[ib1].mouth_fraction == pytest.approx(0.5, abs=1.01 / 200)
    assert fg.funnels[ib2].mouth.contains(0.6, 0) and not fg.funnels[ib2].mouth.contains(0.3, 0)
    assert fg.funnels[ib2].spout.intervals == ((0, pytest.approx(0.7), pytest.approx(0.7)),)


def test_two_funnels_a_leads_into_b():
    """A's fixed point (0.3) lies in B's basin (all of (0, 1]); the goal holds B's fixed point (0.7)."""
    A, B = contraction(0.3, name="A"), contraction(0.7, name="B")
    fg = funnels(None, maps=[A, B], goal=ConfigSet(((0, 0.69, 0.71),)), grid=100)
    assert fg.rank == {1: 0, 0: 1} and fg.order == (1, 0)
    assert fg.goal == ConfigSet.parse("0:0.69-0.71")


def test_funnel_policy_picks_the_highest_priority_mouth(triangle, arm):
    band = "0:0.17-0.53, 1:0.32-0.44, 2:0.27-0.40"  # the 4 rad/s band, with a margin
    fg = funnels(triangle, arm, [4.2, 4.0], "paper", grid=60, goal=band)
    i4 = next(i for i, f in enumerate(fg.funnels) if f.omegas == (4.0,))
    assert fg.rank[i4] == 0 and fg.order[0] == i4
    choose = fg.policy()
    for x, s in ((0.3, 0), (0.2, 1), (0.45, 2)):
        assert fg.funnels[i4].mouth.contains(x, s)
        assert choose(x, s) == (4.0,)
    assert choose(5.0, 0) is None  # in no mouth


def test_funnels_without_a_goal_rank_nothing():
    fg = funnels(None, maps=[contraction(0.6), contraction(0.3)], grid=50)
    assert fg.goal is None and fg.rank == {0: None, 1: None} and fg.order == ()
    assert {(i, j) for i, j, _ in fg.edges} == {(0, 1), (1, 0)}


def test_funnels_of_the_canonical_triangle_name_their_throws(triangle, arm):
    fg = funnels(triangle, arm, [4.0, 5.6], "paper", grid=60, goal="0:0.1-0.6, 1:0.1-0.6, 2:0.1-0.6")
    assert [f.omegas for f in fg.funnels] == [(4.0,)]  # nothing is attracted at 5.6 rad/s: no funnel
    assert fg.rank == {0: 0} and fg.order == (0,)
    assert "ω=4" in fg.table()


def test_funnel_graph_round_trips_through_json(funnel_graph, triangle, arm):
    for fg in (funnel_graph, funnels(triangle, arm, [4.0, 4.2], "paper", grid=30, goal="0:0.2-0.4")):
        d = json.loads(json.dumps(fg.to_dict()))
        back = FunnelGraph.from_dict(d)
        assert back.to_dict() == d
        assert back.order == fg.order and back.rank == fg.rank


@pytest.mark.parametrize("kwargs, field", [
    ({"goal": "zzz"}, "goal"), ({"goal": "0:0.3-0.2"}, "goal"), ({"goal": 3}, "goal"), ({"goal": ""}, "goal"),
    ({"containment": 0.0}, "containment"), ({"containment": 1.5}, "containment"),
    ({"spout_samples": 1}, "spout_samples"), ({"maps": []}, "maps"),
])
def test_bad_funnel_arguments(kwargs, field):
    kw = {"maps": [contraction()], "grid": 20}
    kw.update(kwargs)
    with pytest.raises(InvalidStateError) as err:
        funnels(None, **kw)
    assert err.value.field == field and "\n" not in str(err.value)


def test_funnels_need_throw_speeds(triangle, arm):
    with pytest.raises(InvalidStateError) as err:
        funnels(triangle, arm, None, "paper")
    assert err.value.field == "omegas"


# --- ConfigSet -----------------------------------------------------------------------------------------------


@pytest.mark.parametrize("spec", ["0:abc", "0.2-0.3", "", " , ", "-1:0.2-0.3", "0:0.3-0.2", "x:0.1-0.2",
                                  "0:0.1-0.2-0.3"])
def test_malformed_goal_specs_raise(spec):
    with pytest.raises(InvalidStateError) as err:
        ConfigSet.parse(spec)
    assert err.value.field == "goal" and "\n" not in str(err.value)


@pytest.mark.parametrize("intervals", [((0, 0.3),), ((0.5, 0.2, 0.3),), ((0, math.nan, 0.3),), ((True, 0.1, 0.2),),
                                       ((0, 0.4, 0.3),)])
def test_malformed_intervals_raise(intervals):
    with pytest.raises(InvalidStateError) as err:
        ConfigSet(intervals)
    assert err.value.field == "goal"


def test_config_set_parse_measure_and_points():
    cs = ConfigSet.parse("1:0.10-0.15, 0:0.20-0.30, 2:0.25")
    assert cs.intervals == ((0, 0.2, 0.3), (1, 0.1, 0.15), (2, 0.25, 0.25))  # sorted by side
    assert cs.sides == (0, 1, 2) and cs.measure() == pytest.approx(0.15)
    x, s = cs.sample(5)
    assert x.size == 11 and s.tolist() == [0] * 5 + [1] * 5 + [2]
    assert x[0] == 0.2 and x[4] == 0.3 and x[-1] == 0.25  # ends included
    assert "side 0: [20, 30] cm" in cs.describe("cm")


interval = st.tuples(st.integers(0, 4), st.floats(0.0, 1.0), st.floats(0.0, 0.5)).map(
    lambda t: (t[0], t[1], t[1] + t[2]))


@settings(max_examples=60, deadline=None)
@given(ivs=st.lists(interval, min_size=1, max_size=5), n=st.integers(2, 30),
       probe=st.tuples(st.integers(0, 5), st.floats(-0.5, 2.0)))
def test_property_config_set_contains_its_samples_and_nothing_else(ivs, n, probe):
    cs = ConfigSet(tuple(ivs))
    x, s = cs.sample(n)
    assert np.all(cs.contains(x, s))
    side, xp = probe
    inside = any(k == side and lo <= xp <= hi for k, lo, hi in cs.intervals)
    assert bool(cs.contains(xp, side)) == inside
    back = ConfigSet.from_dict(json.loads(json.dumps(cs.to_dict())))
    assert back == cs and back.to_dict() == cs.to_dict()


# --- push ----------------------------------------------------------------------------------------------------


def test_push_equals_throw_batch_applied_throw_by_throw(triangle, arm):
    omegas = [4.0, 5.6, 5.6, 3.5, 5.6]
    cs = ConfigSet(((0, 0.12, 0.5), (1, 0.06, 0.4), (2, 0.3, 0.35)))
    im = push(triangle, arm, omegas, cs, "paper", n=80)
    x, s = cs.sample(80)
    np.testing.assert_array_equal(im.x[0], x)
    status = np.zeros(x.size, dtype=np.int64)
    for k, w in enumerate(omegas, start=1):
        alive = status == OK
        r = tm.throw_batch(triangle, arm, x[alive], s[alive], w, "paper")
        ok = r.status == OK
        idx = np.flatnonzero(alive)
        x[idx[ok]], s[idx[ok]] = r.x[ok], r.side[ok]
        status[idx] = r.status
        np.testing.assert_array_equal(im.x[k], x)
        np.testing.assert_array_equal(im.side[k], s)
        np.testing.assert_array_equal(im.status[k], status)
        # the hull after each throw holds exactly the configurations still on the arm
        on = status == OK
        assert np.any(on) and np.all(im.hulls[k].contains(x[on], s[on]))
    assert 0 < im.escaped < 1 and im.escapes() == {"behind_joint": pytest.approx(im.escaped)}
    assert im.omegas == tuple(omegas) and im.final == im.hulls[-1]


def test_push_final_image_is_the_composed_map(triangle, arm):
    omegas = (4.0, 3.0, 4.5)
    x0 = np.linspace(0.12, 0.55, 50)
    s0 = np.zeros(50, dtype=np.int64)
    im = push(triangle, arm, omegas, (x0, s0), "paper")
    xn, sn, st_ = ThrowMap(triangle, arm, omegas, "paper")(x0, s0)
    np.testing.assert_array_equal(im.status[-1], st_)
    on = st_ == OK
    np.testing.assert_array_equal(im.x[-1][on], xn[on])
    np.testing.assert_array_equal(im.side[-1][on], sn[on])


def test_push_bad_input(triangle, arm):
    for omegas in ([], None):
        with pytest.raises(InvalidStateError) as err:
            push(triangle, arm, omegas, "0:0.2-0.3", "paper")
        assert err.value.field == "omegas"
    with pytest.raises(InvalidStateError) as err:
        push(triangle, arm, [4.0], "5:0.2-0.3", "paper")
    assert err.value.field == "configs"
    with pytest.raises(InvalidStateError) as err:
        push(triangle, arm, [4.0], ([0.05], [0]), "paper")  # behind the joint, given as arrays
    assert err.value.field == "configs"


# --- library bugs found while writing these tests (fail until fixed) -----------------------------------------


def test_push_refuses_a_function_map_naming_the_part():
    """BUG: push's own check ("push needs a part (or ThrowMap), not a function map", field
    ``part``) is unreachable: ``as_map(F, None, 1.0)`` raises first with field ``arm`` and
    "give either a map or (part, arm, omega), not both", though no arm was given."""
    with pytest.raises(InvalidStateError) as err:
        push(contraction(), omegas=[1.0], configs="0:0.2-0.3")
    assert err.value.field == "part"


def test_push_refuses_a_config_set_behind_the_joint(triangle, arm):
    """BUG: a ConfigSet reaching behind the joint is not validated (the same configurations as
    (x, side) arrays are refused, field ``starts``). The inadmissible samples get status
    ``invalid_start`` and the summary reports them as "off the arm"."""
    with pytest.raises(InvalidStateError) as err:
        push(triangle, arm, [4.0], "0:0.05-0.3", "paper")
    assert err.value.field in ("configs", "starts")

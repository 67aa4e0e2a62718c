"""The engine screen of the feeder search: the exact table is the exact model's own throws, and the recoil
feeder of the examples (found by hand before the search existed) scores as a feeder on the engine table."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import throwmap as tm
from throwmap.feeder import Variant, arrival
from throwmap.feeder.arrival import DROP_X, exact_table, screen_table
from throwmap.system.arm import Arm


def test_the_exact_table_is_the_exact_models_throws():
    tri = tm.triangle_30_60_90(0.17)
    arm = Arm(h=-0.01, mu=1.0)
    t = exact_table(tri, arm, 4.5, sigma=0.03)
    rng = np.random.default_rng(0)
    for _ in range(12):
        a, k, i = int(rng.integers(7)), int(rng.choice(tri.stable_sides)), int(rng.integers(0, t.x.size))
        if t.x[i] + tri.uL[k] <= 0.002:  # no rest there: not thrown
            assert t.status[a, k, i] == -1
            continue
        r = tm.throw(tri, arm, float(t.x[i]), k, 4.5 * (1 + 0.03 * t.z[a]), model="rigid_body")
        assert t.status[a, k, i] == int(r.status)
        if r.ok:
            assert t.x_next[a, k, i] == pytest.approx(r.x, abs=1e-12) and t.side_next[a, k, i] == r.side


def test_arrival_shares_are_bounded_and_stops_lie_beyond_the_drops():
    tri = tm.triangle_30_60_90(0.17)
    a = arrival(Variant(tri, None, None), 4.5, Arm(h=-0.02), chains=300,
                table=screen_table(tri, 4.5, Arm(h=-0.02), exact=True))
    assert set(a.best) == set(tri.stable_sides)
    for X, first, wrong, holds in a.best.values():
        assert 0 <= first <= 1 and 0 <= wrong <= 1 and first + wrong <= 1 + 1e-12
        assert X >= DROP_X[1] + float(np.max(tri.uR)) + 0.01 - 1e-9
        assert holds or first == 0


@pytest.mark.slow
def test_the_examples_recoil_feeder_arrives_first_on_its_side_in_the_engine():
    from throwmap.io.config import resolve_part

    part = resolve_part("examples/recoil_feeder.toml").part
    arm = Arm(h=-0.02042023480254783, mu=1.0)
    a = arrival(Variant(part, None, None), 4.559824565181344, arm, table=screen_table(part, 4.559824565181344, arm, workers=1))
    assert a.side == 0 and a.predicted >= 0.99 and a.wrong == 0 and 0.37 <= a.X <= 0.41


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_the_pocket_floor_covers_the_parts_footprint_on_its_side(seed):
    """Laid flat on side k, the part spans exactly ℓ_k + (clearance − 5 mm) along the arm: the floor a pocket needs."""
    from throwmap.feeder import random_plate
    from throwmap.feeder.arrival import lip_offset, pocket_clearance
    from throwmap.system.pose import pose_at_rest, world_vertices

    part = random_plate(np.random.default_rng(seed))
    for k in part.stable_sides:
        xs = world_vertices(part, pose_at_rest(part, 0.0, 0.2, k))[:, 0]
        assert float(xs.max() - xs.min()) == pytest.approx(part.length[k] + pocket_clearance(part, k) - 0.005, abs=1e-9)
        assert lip_offset(part, k, 0.0) == 0.0
        assert lip_offset(part, k, 0.01) == pytest.approx(xs.max() - xs.min() + 0.005 + 0.01 / np.tan(np.radians(60)))


def test_a_rectangle_needs_no_more_floor_than_its_side():
    from throwmap.feeder.arrival import pocket_clearance

    box = tm.Part.from_vertices([(0.0, 0.0), (0.0, 0.04), (0.1, 0.04), (0.1, 0.0)], mass=0.05, name="box")
    assert all(pocket_clearance(box, k) == pytest.approx(0.005) for k in range(4))


def test_a_chain_that_starts_past_a_stop_is_there_on_the_side_it_starts_on():
    """A stop every drop is already past: each chain counts on the side it was dropped on, whatever its throws do."""
    from throwmap.design.passage import first_passage

    tri = tm.triangle_30_60_90(0.17)
    t = exact_table(tri, Arm(h=-0.02), 5.5)
    sides = np.asarray(tri.stable_sides)
    p = first_passage(tri, t, 0, n=2000, throws=5, seed=3, x_range=(0.2, 0.25), X=np.array([0.05]))
    dropped = sides[np.random.default_rng(3).integers(0, sides.size, 2000)]  # the chains' first draw: their sides
    assert p.good[0] == pytest.approx(np.mean(dropped == 0), abs=1e-12) and p.good[0] + p.wrong[0] == 1.0


@settings(max_examples=8, deadline=None)
@given(seed=st.integers(0, 2**31 - 1), omega=st.sampled_from([3.5, 4.5, 5.5]), h=st.sampled_from([-0.03, -0.01]))
def test_one_run_of_the_chains_for_both_places_equals_a_run_per_side_and_place(seed, omega, h):
    """``arrivals`` shares one run of the chains between every side and both places of arrival; each side's shares
    equal those of its own ``first_passage`` run over its own stops (the chains do not depend on the stops)."""
    from throwmap.design.passage import first_passage
    from throwmap.feeder import random_plate
    from throwmap.feeder.arrival import TABLE_STEP, TABLE_X_MAX, _stops, arrivals, lip_offset

    part = random_plate(np.random.default_rng(seed))
    arm = Arm(h=h, mu=1.0)
    table = screen_table(part, omega, arm, exact=True)
    both = arrivals(Variant(part, None, None), omega, arm, chains=200, table=table, depths=(0.0, 0.01))
    for a, depth in zip(both, (0.0, 0.01)):
        assert a.lip == (depth > 0)
        for k in part.stable_sides:
            off = lip_offset(part, k, depth)
            lips = np.round(_stops(part) - off, 6)
            lips = lips[(lips > 0.02) & (lips <= TABLE_X_MAX - TABLE_STEP + 1e-9)]
            p = first_passage(part, table, k, n=200, X=lips, x_range=DROP_X)
            score = np.where(p.holds, p.good - 2.0 * p.wrong, -np.inf)
            i = int(np.argmax(score))
            want = (round(float(p.X[i]) + off, 6), float(p.good[i]) if p.holds[i] else 0.0, float(p.wrong[i]))
            assert a.best[k][:3] == pytest.approx(want, abs=1e-12)

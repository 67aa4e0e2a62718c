"""The engine screen of the feeder search: the exact table is the exact model's own throws, and the recoil
feeder of the examples (found by hand before the search existed) scores as a feeder on the engine table."""

from __future__ import annotations

import numpy as np
import pytest

import throwmap as tm
from throwmap.feeder import Variant, arrival
from throwmap.feeder.arrival import DROP_X, exact_table
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
    a = arrival(Variant(tri, None, None), 4.5, Arm(h=-0.02), exact=True, chains=300)
    assert set(a.best) == set(tri.stable_sides)
    for X, first, wrong, holds in a.best.values():
        assert 0 <= first <= 1 and 0 <= wrong <= 1 and first + wrong <= 1 + 1e-12
        assert X >= DROP_X[1] + float(np.max(tri.uR)) + 0.01 - 1e-9
        assert holds or first == 0


@pytest.mark.slow
def test_the_examples_recoil_feeder_arrives_first_on_its_side_in_the_engine():
    from throwmap.io.config import resolve_part

    part = resolve_part("examples/recoil_feeder.toml").part
    a = arrival(Variant(part, None, None), 4.559824565181344, Arm(h=-0.02042023480254783, mu=1.0), workers=1)
    assert a.side == 0 and a.predicted >= 0.99 and a.wrong == 0 and 0.37 <= a.X <= 0.41

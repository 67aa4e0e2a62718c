"""The work guard: large analyses are estimated and refused up front, and large grids go in chunks (issue 10)."""

from __future__ import annotations

import numpy as np
import pytest

import throwmap as tm
from throwmap.budget import Limits
from throwmap.analysis import FunctionMap, basins, critical_points, limit_set, push
from throwmap.analysis import cellmap
from throwmap.analysis.budget import guard_work
from throwmap.errors import InvalidStateError


def _ok(x):
    return np.zeros(x.size, dtype=np.int64)


def bistable():
    return FunctionMap(lambda x, s: (np.where(x < 0.37, 0.2 + 0.5 * (x - 0.2), 0.7 + 0.5 * (x - 0.7)), s, _ok(x)),
                       {0: (0.0, 1.0)}, name="bistable")


def test_a_huge_basin_grid_is_refused_before_it_is_built():
    part, arm = tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01)
    with pytest.raises(InvalidStateError) as err:
        basins(part, arm, 4.0, "paper", grid=100_000_000)
    msg = str(err.value)
    assert err.value.field == "grid" and "\n" not in msg
    assert "300,000,000 configurations" in msg and "48 GB" in msg and "max_memory" in msg and "force=True" in msg


def test_the_time_estimate_refuses_long_work_and_says_how_to_go_on():
    m = bistable()
    with pytest.raises(InvalidStateError) as err:
        basins(m, grid=50_000, limits=Limits(max_seconds=1e-6))
    assert err.value.field == "grid" and "measured now" in str(err.value) and "max_seconds" in str(err.value)
    with pytest.raises(InvalidStateError) as err:
        limit_set(m, n_starts=10_000, limits=Limits(max_seconds=1e-6))
    assert err.value.field == "n_starts"
    with pytest.raises(InvalidStateError) as err:
        critical_points(m, n_grid=200_000, limits=Limits(max_memory=1e6))
    assert err.value.field == "n_grid"
    part, arm = tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01)
    with pytest.raises(InvalidStateError) as err:
        push(part, arm, [4.0] * 10, "0:0.2-0.3", model="paper", n=10**8)
    assert err.value.field == "n" and "GB of memory" in str(err.value)
    b = basins(m, grid=50, limits=Limits(max_seconds=1e-9, max_memory=1.0, force=True))  # force: no estimate stops it
    assert b.n_configs == 50


@pytest.mark.parametrize("kwargs, field", [({"max_memory": 0}, "max_memory"), ({"max_seconds": float("nan")},
                                                                                "max_seconds"),
                                           ({"force": "yes"}, "force")])
def test_bad_limits_are_refused(kwargs, field):
    with pytest.raises(InvalidStateError) as err:
        basins(bistable(), grid=20, limits=Limits(**kwargs))
    assert err.value.field == field


def test_guard_returns_its_estimate():
    # timed_above=0: time it although 2,000 throws are below the size that is timed by default
    est = guard_work("x", "grid", 1000, 100, Limits(1e9, 1e9, False), throws_per_config=2.0, cmap=bistable(),
                     timed_above=0)
    assert est["memory_bytes"] == 1e5 and est["seconds"] == pytest.approx(2000 * est["seconds_per_throw"])


def test_chunked_cells_and_orbits_give_the_same_basins(monkeypatch):
    m = bistable()
    whole_cells = basins(m, grid=3000, method="cells", n_seeds=8)
    whole_orbits = basins(m, grid=300, method="orbits", n_seeds=8)
    monkeypatch.setattr(cellmap, "CHUNK", 97)
    cells = basins(m, grid=3000, method="cells", n_seeds=8)
    orbits = basins(m, grid=300, method="orbits", n_seeds=8)
    for a, b in ((whole_cells, cells), (whole_orbits, orbits)):
        np.testing.assert_array_equal(a.labels, b.labels)
        np.testing.assert_array_equal(a.throws, b.throws)
        np.testing.assert_array_equal(a.fates, b.fates)

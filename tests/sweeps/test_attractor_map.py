"""The two-parameter attractor map: each point is the limit set the library gives there, kept and resumed."""

from __future__ import annotations

import json

import numpy as np
import pytest

import throwmap as tm
from throwmap.analysis.limitset import limit_set
from throwmap.errors import InvalidStateError
from throwmap.sweeps.attractor_map import attractor_map, limit_set_config

PART = """[part]
vertices = [[0.14722431864335458, 0.0], [0.0, 0.085], [0.0, 0.0]]
mass = 0.04728
[[part.point_masses]]
mass = 0.03
at = [0.03, 0.02]
"""


@pytest.fixture
def client(dask_client):
    return dask_client


def test_each_point_is_the_limit_set_there_and_a_rerun_computes_nothing(tmp_path, client):
    part_file = tmp_path / "part.toml"
    part_file.write_text(PART)
    arm = tm.Arm(h=-0.01)
    cfg = limit_set_config(str(part_file), arm, omega=4.2, model="paper", n_starts=8)
    grid = {"omega": (4.0, 4.6, 2), "weight_x": (0.02, 0.04, 2)}
    m = attractor_map(grid, tmp_path / "map", cfg, client=client)
    assert m.count.shape == (2, 2) and not m.errors and np.all(np.isfinite(m.count))
    from throwmap.analysis.continuation import system_at
    from throwmap.io.config import resolve_part

    base = resolve_part(str(part_file)).part
    for i, w in enumerate(m.values[0]):
        for j, wx in enumerate(m.values[1]):
            p = system_at(base, arm, None, "weight_x", float(wx), {})[0]
            ls = limit_set(p, tm.Arm(h=-0.01, length=None), float(w), "paper", n_starts=8, rng=0)
            assert m.count[i, j] == len(ls.attractors)
            assert m.escape[i, j] == pytest.approx(sum(v for k, v in ls.escapes.items() if k != "unresolved"))
    stamp = sorted(p.stat().st_mtime_ns for p in (tmp_path / "map").iterdir())
    again = attractor_map(grid, tmp_path / "map", cfg, client=client)
    assert np.array_equal(again.count, m.count)
    assert sorted(p.stat().st_mtime_ns for p in (tmp_path / "map").iterdir()) == stamp  # nothing written again
    doc = json.loads(json.dumps(m.to_dict(), allow_nan=False))
    assert doc["params"] == ["omega", "weight_x"] and all(isinstance(c, int) for row in doc["attractors"] for c in row)
    with pytest.raises(InvalidStateError, match=r"^param: must be one of"):
        attractor_map({"omega": (4, 5, 2), "speed": (1, 2, 2)}, tmp_path / "x", cfg, client=client)

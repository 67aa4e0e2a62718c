"""First passage under the recoil arm (throwmap.design.passage): the table is the engine's map, and the
chain shares obey the inclusion order of first passage."""

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from throwmap.design.passage import first_passage, recoil_table
from throwmap.engine.api import engine_throw
from throwmap.system.motion import RecoilThrow
from throwmap.errors import InvalidStateError
from throwmap.io.config import load_config

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def feeder():
    cfg = load_config(ROOT / "examples" / "recoil_feeder.toml")
    run = tomllib.loads((ROOT / "examples" / "feed_recoil.toml").read_text())
    return cfg.part, cfg.arm, run["omega"]


@pytest.fixture(scope="module")
def table(feeder):
    part, arm, omega = feeder
    return recoil_table(part, arm, omega, step=0.04, x_max=0.44, workers=1)


@pytest.mark.slow
def test_table_entries_are_engine_throws(feeder, table):
    part, arm, omega = feeder
    rng = np.random.default_rng(3)
    for _ in range(3):
        a, k, i = int(rng.integers(len(table.z))), int(rng.integers(3)), int(rng.integers(table.x.size))
        if table.status[a, k, i] < 0:
            continue
        w = omega * (1 + table.sigma * table.z[a])
        out = engine_throw(part, arm, float(table.x[i]), k, w,
                           realisation=RecoilThrow.for_release_rate(w, recoil=math.radians(3), zeta=0.2))
        assert int(out.status) == table.status[a, k, i]
        assert out.side == table.side_next[a, k, i]
        assert out.x == pytest.approx(table.x_next[a, k, i], abs=1e-9)


@pytest.mark.slow
def test_first_passage_shares_are_ordered(feeder, table):
    part, _, _ = feeder
    p = first_passage(part, table, 0, n=400, throws=30, seed=1, X=np.arange(0.20, 0.44, 0.02))
    assert np.all(p.good + p.wrong <= 1 + 1e-12)
    passed = p.good + p.wrong
    assert np.all(np.diff(passed) <= 1e-12)  # passing a farther stop implies passing a nearer one
    assert passed[0] > 0.5  # most chains get 20 cm out
    again = first_passage(part, table, 0, n=400, throws=30, seed=1, X=p.X)
    assert np.array_equal(again.good, p.good)  # seeded
    assert set(p.window(0.0)) <= set(round(float(x), 9) for x in p.X[p.holds])


def test_first_passage_refuses_bad_input(feeder, table):
    part, _, _ = feeder
    with pytest.raises(InvalidStateError, match="n"):
        first_passage(part, table, 0, n=0)
    with pytest.raises(Exception, match="target"):
        first_passage(part, table, 7)

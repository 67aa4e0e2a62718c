"""Outcomes, batches and orbits say which system they were thrown in: the arm's rest angle α and the fixtures."""

import json
import math

import numpy as np
import pytest

import throwmap as tm
from throwmap import Wall
from throwmap.system.fixtures import Cavity, fixture_from_dict, fixture_to_dict
from throwmap.records.orbit import Orbit
from throwmap.throws.orbit import iterate
from throwmap.records.outcome import BatchOutcome, ThrowOutcome

SQUARE = tm.Part.from_vertices([(0, 0), (0.06, 0), (0.06, 0.06), (0, 0.06)], mass=0.05)
ARM = tm.Arm(h=-0.01, mu=1.0, length=0.30)
WALL = Wall(0.05, mu=0.0)


def test_level_bare_throw_keeps_the_defaults():
    o = tm.throw(SQUARE, ARM, 0.2, 0, 3.0, "rigid_body")
    assert o.alpha == 0.0 and o.fixtures == ()
    assert "α" not in repr(o) and "fixtures" not in repr(o)


def test_throw_records_alpha_and_fixtures_and_round_trips():
    a = math.radians(4.0)
    o = tm.throw(SQUARE, ARM, 0.2, 0, 3.0, "rigid_body", alpha=a, fixtures=(WALL,))
    assert o.alpha == pytest.approx(a) and o.fixtures == (WALL,)
    assert "α=4°" in repr(o) and "Wall" in repr(o) and "α=4°" in o.table()
    d = json.loads(json.dumps(o.to_dict()))
    assert d["fixtures"] == [{"kind": "wall", "height": 0.05, "thickness": 0.01, "mu": 0.0}]
    back = ThrowOutcome.from_dict(d)
    assert back.alpha == pytest.approx(a) and back.fixtures == (WALL,) and back.x == o.x


def test_batch_records_the_system():
    b = tm.throw_batch(SQUARE, ARM, np.array([0.1, 0.2]), 0, 3.0, "rigid_body", alpha=0.02, fixtures=(WALL,))
    assert b.alpha == pytest.approx(0.02) and b.fixtures == (WALL,)
    back = BatchOutcome.from_dict(json.loads(json.dumps(b.to_dict())))
    assert back.alpha == pytest.approx(0.02) and back.fixtures == (WALL,)
    assert np.array_equal(back.side, b.side)
    plain = tm.throw_batch(SQUARE, ARM, np.array([0.1]), 0, 3.0, "rigid_body")
    assert plain.alpha == 0.0 and plain.fixtures == ()


def test_orbit_records_the_system_and_round_trips():
    orb = iterate(SQUARE, ARM, (0.15, 0), 3.0, n=4, model="rigid_body", fixtures=(WALL,), alpha=0.01)
    assert orb.fixtures == (WALL,) and orb.alpha == pytest.approx(0.01)
    assert all(o.fixtures == (WALL,) for o in orb.outcomes)
    back = Orbit.from_dict(json.loads(json.dumps(orb.to_dict())))
    assert back.fixtures == (WALL,) and back.alpha == pytest.approx(0.01)
    assert "Wall" in repr(orb)


def test_fixture_dicts_round_trip_and_refuse_unknown():
    cav = Cavity(((0.06, 0.0), (0.06, -0.02), (0.0, -0.02)))
    for f in (WALL, Wall(0.1, 0.02), cav):
        assert fixture_from_dict(fixture_to_dict(f)) == f
    with pytest.raises(tm.InvalidStateError, match="fixtures"):
        fixture_from_dict({"kind": "ramp"})

"""One result vocabulary for throws: to_dict/from_dict round trips and text tables."""

import json

import numpy as np
import pytest

import throwmap as tm
from throwmap.records.outcome import Status

TRI = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01, mu=1.5)


def strict(d):
    return json.loads(json.dumps(d, allow_nan=False))


@pytest.mark.parametrize("model", ["paper", "small_angle", "rigid_body"])
def test_throw_outcome_round_trip(model):
    for x, s, om in [(0.2, 0, 4.0), (0.34, 1, 4.0), (0.08, 2, 7.0), (0.12, 0, 0.0)]:
        o = tm.throw(TRI, ARM, x, s, om, model=model)
        d = strict(o.to_dict())
        back = tm.ThrowOutcome.from_dict(d)
        assert back.to_dict() == o.to_dict()
        assert (back.x, back.side, back.status) == (o.x, o.side, o.status)
        text = o.table()
        assert model in text and (o.kind in text or o.status.label in text)


def test_batch_outcome_round_trip_and_counts():
    x = np.linspace(-0.02, 0.6, 12).reshape(3, 4)
    b = tm.throw_batch(TRI, ARM, x, 0, 5.0, on_invalid="status")
    back = tm.BatchOutcome.from_dict(strict(b.to_dict()))
    np.testing.assert_array_equal(back.x, b.x)
    np.testing.assert_array_equal(back.status, b.status)
    np.testing.assert_array_equal(back.records, b.records)
    counts = b.counts()
    assert sum(counts.values()) == 12 and counts.get("invalid_start", 0) >= 1
    assert all(label in b.table() for label in counts)


def test_orbit_round_trip_and_table():
    orbit = tm.iterate(TRI, ARM, (0.12, 0), [4.0, 3.0, 5.6, 5.6, 5.6], model="paper")
    back = tm.Orbit.from_dict(strict(orbit.to_dict()))
    np.testing.assert_array_equal(back.x, orbit.x)
    assert back.status == orbit.status and back.kinds == orbit.kinds and back.n_throws == orbit.n_throws
    lines = orbit.table().splitlines()
    assert len(lines) == 2 + orbit.n_throws


def test_status_labels_round_trip():
    for s in Status:
        assert Status.from_label(s.label) is s
    with pytest.raises(ValueError, match="status"):
        Status.from_label("flying")

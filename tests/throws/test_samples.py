"""Sampled maps (the data of paper Fig. 2): the grid, agreement with single throws, immutability, JSON."""

import dataclasses
import json

import numpy as np
import pytest

import throwmap as tm
from throwmap.analysis import FunctionMap, ThrowMap
from throwmap.errors import InvalidStateError
from throwmap.throws.samples import DEFAULT_X_MAX, MapSamples, sample_map, throw_map_samples

OMEGA = 4.0


@pytest.fixture(scope="module")
def samples(triangle, arm):
    return throw_map_samples(triangle, arm, OMEGA, model="paper", x_max=0.6, n=40)


def test_grid_per_side_excludes_the_lower_end(samples, triangle):
    assert samples.sides == triangle.stable_sides and samples.n == 40
    for i, s in enumerate(samples.sides):
        sl = samples.panel(s)
        x = samples.x[sl]
        assert np.all(samples.side[sl] == s)
        lo = triangle.x_min(s)
        assert samples.x_lo[i] == lo and samples.x_hi[i] == 0.6
        assert x[0] > lo and x[-1] == pytest.approx(0.6)
        np.testing.assert_allclose(np.diff(x), (0.6 - lo) / 40)


def test_each_sample_is_one_throw(samples, triangle, arm):
    """Independent check: the batch agrees with tm.throw one start at a time."""
    for j in (0, 17, 39, 45, 79, 100, 119):
        one = tm.throw(triangle, arm, float(samples.x[j]), int(samples.side[j]), OMEGA, model="paper")
        assert samples.status[j] == one.status
        if one.status == tm.Status.OK:
            assert samples.x_next[j] == pytest.approx(one.x, abs=1e-12)
            assert samples.side_next[j] == one.side
    assert np.array_equal(samples.ok, samples.status == 0)


def test_jogs_and_flips_both_appear(samples):
    """Fig. 2: near the joint the part jogs (same side), far out it flips."""
    ok = samples.ok
    assert np.any(ok & (samples.side_next == samples.side)) and np.any(ok & (samples.side_next != samples.side))


def test_sides_subset_and_default_x_max(triangle, arm):
    s = throw_map_samples(triangle, arm, OMEGA, sides=[2], n=5)
    assert s.sides == (2,) and s.x.size == 5
    assert s.x_hi == (DEFAULT_X_MAX,)  # unbounded arm
    bounded = throw_map_samples(triangle, tm.Arm(h=-0.01, length=0.4), OMEGA, sides=[0], n=5)
    assert bounded.x[-1] == pytest.approx(0.4)
    with pytest.raises(InvalidStateError, match="side"):
        throw_map_samples(triangle, arm, OMEGA, sides=[7], n=5)
    with pytest.raises(InvalidStateError, match="n"):
        throw_map_samples(triangle, arm, OMEGA, n=0)


def test_sample_map_matches_throw_map_samples(triangle, arm):
    cmap = ThrowMap(triangle, arm, OMEGA, "paper", 0.6)
    a = sample_map(cmap, 30)
    b = throw_map_samples(triangle, arm, OMEGA, model="paper", x_max=0.6, n=30)
    for name in ("x", "side", "x_next", "side_next", "status"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    assert a.label == cmap.label and a.info == cmap.describe()


def test_sample_map_of_a_function_map():
    f = FunctionMap(lambda x, s: (0.5 * x, 1 - s, np.where(x > 0.4, 2, 0)), {0: (0.0, 0.5), 1: (0.1, 0.3)},
                    name="halve")
    s = sample_map(f, 10)
    assert s.sides == (0, 1) and s.x_lo == (0.0, 0.1) and s.x_hi == (0.5, 0.3)
    np.testing.assert_allclose(s.x_next, 0.5 * s.x)
    np.testing.assert_array_equal(s.side_next, 1 - s.side)
    assert int(np.sum(~s.ok)) == 2  # x = 0.45, 0.5 on side 0
    with pytest.raises(InvalidStateError, match="n"):
        sample_map(f, 1)


def test_frozen_and_read_only(samples):
    with pytest.raises(dataclasses.FrozenInstanceError):
        samples.label = "other"
    with pytest.raises(ValueError):
        samples.x_next[0] = 1.0


def test_json_round_trip(samples):
    d = json.loads(json.dumps(samples.to_dict(), allow_nan=True))
    back = MapSamples.from_dict(d)
    for name in ("x", "side", "x_next", "side_next", "status"):
        np.testing.assert_array_equal(getattr(back, name), getattr(samples, name))
    assert (back.sides, back.x_lo, back.x_hi, back.label) == (samples.sides, samples.x_lo, samples.x_hi,
                                                              samples.label)


def test_inconsistent_samples_are_refused():
    kw = dict(x=[0.1, 0.2], side=[0, 0], x_next=[0.1, 0.2], side_next=[0, 0], status=[0, 0], sides=(0,),
              x_lo=(0.0,), x_hi=(0.2,))
    MapSamples(**kw)
    with pytest.raises(InvalidStateError, match="one length"):
        MapSamples(**{**kw, "status": [0]})
    with pytest.raises(InvalidStateError, match="side 1"):
        MapSamples(**{**kw, "sides": (0, 1), "x_lo": (0.0, 0.0), "x_hi": (0.2, 0.2)})
    with pytest.raises(InvalidStateError, match="sides"):
        MapSamples(**{**kw, "x_lo": ()})
    with pytest.raises(InvalidStateError, match="side"):
        MapSamples(**kw).panel(3)


def test_walled_map_stops_at_the_wall(triangle):
    """With a Wall (and no x_max) each side's samples end where its outer vertex meets the wall: every
    sample is an admissible rest, the last one exactly at x + u_R = L."""
    arm = tm.Arm(h=-0.01, mu=1.0, length=0.35)
    s = throw_map_samples(triangle, arm, OMEGA, model="rigid_body", n=12, fixtures=(tm.Wall(0.05, mu=0.0),))
    for i, k in enumerate(s.sides):
        sl = s.panel(k)
        assert s.x_hi[i] == pytest.approx(0.35 - float(triangle.uR[k]), abs=1e-12)
        assert s.x[sl][-1] == pytest.approx(s.x_hi[i])
        assert np.all(s.status[sl] != tm.Status.INVALID_START)
    open_ = throw_map_samples(triangle, arm, OMEGA, model="rigid_body", n=12)
    assert open_.x_hi == (0.35,) * len(open_.sides)  # no wall: the arm's length, as before

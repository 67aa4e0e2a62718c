"""One-bit sensors: every field validated with one line naming it; error rates measured (the Wilson
interval of the observed rate holds the set rate: 99.9 %, z = 3.29, since a 95 % interval misses one
time in 20 by design and a dozen are checked here); hysteresis and blur; the stream's use independent
of the settings."""

import math

import numpy as np
import pytest

from throwmap.control import BeyondSensor, PositionSensor, SideSensor, WithinSensor
from throwmap.errors import InvalidStateError
from throwmap.experiments.stats import wilson_interval as _wilson

N = 20_000


def wilson_interval(k, n):
    return _wilson(k, n, z=3.29)


def _rate(sensor, x, side, n=N, seed=0):
    rng = np.random.default_rng(seed)
    return sum(sensor.read(x, side, rng) for _ in range(n))


@pytest.mark.parametrize("fp, fn", [(0.0, 0.0), (0.01, 0.05), (0.05, 0.01), (0.2, 0.3)])
def test_side_sensor_error_rates(fp, fn):
    s = SideSensor(1, false_positive=fp, false_negative=fn)
    on = _rate(s, 0.3, 1, seed=1)  # truth 1: reads 1 with probability 1 − fn
    off = _rate(s, 0.3, 2, seed=2)  # truth 0: reads 1 with probability fp
    lo, hi = wilson_interval(N - on, N)
    assert lo <= fn <= hi or (fn == 0 and on == N)
    lo, hi = wilson_interval(off, N)
    assert lo <= fp <= hi or (fp == 0 and off == 0)


@pytest.mark.parametrize("sensor, inside, outside", [
    (BeyondSensor(0.40, false_positive=0.05, false_negative=0.01), 0.41, 0.39),
    (WithinSensor(0.45, 0.01, false_positive=0.01, false_negative=0.05), 0.455, 0.47),
])
def test_position_sensor_error_rates(sensor, inside, outside):
    on, off = _rate(sensor, inside, 1, seed=3), _rate(sensor, outside, 1, seed=4)
    lo, hi = wilson_interval(N - on, N)
    assert lo <= sensor.false_negative <= hi
    lo, hi = wilson_interval(off, N)
    assert lo <= sensor.false_positive <= hi


def test_hysteresis_keeps_a_reading_until_the_band_is_left():
    rng = np.random.default_rng(0)
    b = BeyondSensor(0.40, hysteresis=0.01)
    assert not b.read(0.395, 1, rng, last=False) and b.read(0.395, 1, rng, last=True)
    assert not b.read(0.389, 1, rng, last=True)
    w = WithinSensor(0.45, 0.01, hysteresis=0.002)
    assert not w.read(0.461, 1, rng, last=False) and w.read(0.461, 1, rng, last=True)
    assert not w.read(0.463, 1, rng, last=True)


def test_blur_thresholds_a_noisy_abscissa():
    b = BeyondSensor(0.40, sigma=0.001)
    share = _rate(b, 0.401, 1, n=4000, seed=5) / 4000  # P(x + σ z > X) = Φ(1) ≈ 0.841
    assert abs(share - 0.8413) < 0.03


def test_every_read_draws_the_same_numbers():
    # two draws a read whatever the sensor and its rates: a trial's stream does not depend on them
    for s in (SideSensor(0), SideSensor(0, 0.3, 0.2), BeyondSensor(0.1), WithinSensor(0.1, 0.01, sigma=0.01),
              PositionSensor(0.001, 0.1)):
        rng = np.random.default_rng(9)
        s.read(0.2, 0, rng)
        ref = np.random.default_rng(9)
        ref.random(), ref.standard_normal()
        assert rng.random() == ref.random()


def test_position_sensor_estimates_and_side_errors():
    rng = np.random.default_rng(1)
    p = PositionSensor(0.002, side_error=0.1, n_sides=3)
    reads = [p.read(0.3, 1, rng) for _ in range(N)]
    xs = np.array([r[0] for r in reads])
    assert abs(xs.mean() - 0.3) < 1e-4 and abs(xs.std() - 0.002) < 1e-4
    wrong = sum(r[1] != 1 for r in reads)
    lo, hi = wilson_interval(wrong, N)
    assert lo <= 0.1 <= hi and all(r[1] in (1, 2) for r in reads)


@pytest.mark.parametrize("make, field", [
    (lambda: SideSensor(-1), "sensor.side"),
    (lambda: SideSensor(True), "sensor.side"),
    (lambda: SideSensor(0, false_positive=1.0), "sensor.false_positive"),
    (lambda: SideSensor(0, false_negative=-0.1), "sensor.false_negative"),
    (lambda: BeyondSensor(math.nan), "sensor.x"),
    (lambda: BeyondSensor(0.1, hysteresis=-1e-3), "sensor.hysteresis"),
    (lambda: BeyondSensor(0.1, sigma=math.inf), "sensor.sigma"),
    (lambda: WithinSensor(0.1, 0.0), "sensor.eps"),
    (lambda: WithinSensor(0.1, 0.01, false_positive="0.1"), "sensor.false_positive"),
    (lambda: PositionSensor(side_error=1.5), "sensor.side_error"),
    (lambda: PositionSensor(n_sides=0), "sensor.n_sides"),
])
def test_bad_fields_are_one_line_naming_them(make, field):
    with pytest.raises(InvalidStateError) as err:
        make()
    assert err.value.field == field and "\n" not in str(err.value)


def test_sensors_are_immutable_values():
    s = SideSensor(1)
    with pytest.raises(AttributeError):
        s.side = 2
    assert SideSensor(1) == s and hash(SideSensor(1)) == hash(s)

"""Experiment configs take the ends of their ranges: a range (low, high) with low = high, a rate of exactly
100 rad/s; the serial experiment's wedge drop range is ordered like the others."""

import pytest

from throwmap.errors import ConfigError, ScaleWarning
from throwmap.experiments import get_experiment
from throwmap.experiments.base import config_of
from throwmap.io.spec import MAX_RATE


def test_a_range_with_low_equal_to_high_is_one_value():
    cfg = config_of(get_experiment("feed"), {"height": [0.05, 0.05], "x_range": [0.2, 0.2]})
    assert tuple(cfg.height) == (0.05, 0.05) and tuple(cfg.x_range) == (0.2, 0.2)


def test_the_largest_rate_is_taken_and_one_above_refused():
    assert MAX_RATE == 100.0
    with pytest.warns(ScaleWarning):  # taken, with the unit-slip warning any ω over 30 rad/s gets
        assert config_of(get_experiment("feed"), {"omega": MAX_RATE}).omega == MAX_RATE
    with pytest.raises(ConfigError, match=r"^config\.omega: "), pytest.warns(ScaleWarning):
        config_of(get_experiment("feed"), {"omega": MAX_RATE + 0.5})


def test_the_serial_wedge_drop_range_must_be_ordered():
    with pytest.raises(ConfigError, match=r"^config\.x_range_second: "):
        config_of(get_experiment("assemble-serial"), {"x_range_second": [0.18, 0.10]})

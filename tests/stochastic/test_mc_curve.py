"""The Monte Carlo curve P(goal by throw k) counts a trial that reached the goal at throw k at k, not after."""

import math

import numpy as np
import pytest

from throwmap.stochastic.compare import mc_curve


def test_a_hit_at_throw_k_counts_at_k():
    # hits at 0, 1, 1, 3 and two never: P(by 0) = 1/6, P(by 1) = 3/6, P(by 2) = 3/6, P(by 3) = 4/6
    p, lo, hi, n = mc_curve([0, 1, 1, 3, None, -1], 4)
    assert n == 6
    assert p.tolist() == pytest.approx([1 / 6, 3 / 6, 3 / 6, 4 / 6, 4 / 6])
    assert np.all(lo <= p) and np.all(p <= hi)


def test_the_curve_is_the_empirical_distribution_of_the_hitting_throw():
    rng = np.random.default_rng(3)
    hits = rng.integers(-1, 8, 500).astype(float)
    hits[rng.random(500) < 0.1] = math.nan
    p, _, _, n = mc_curve(hits.tolist(), 10)
    for k in range(11):
        assert p[k] == np.count_nonzero((hits >= 0) & (hits <= k)) / 500

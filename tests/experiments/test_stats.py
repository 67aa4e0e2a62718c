"""Wilson 95 % interval: against SciPy, at the edges, and its defining properties."""

import math

import pytest
from hypothesis import given, strategies as st
from scipy.stats import binomtest, norm

from throwmap.errors import InvalidStateError
from throwmap.experiments.stats import Z95, wilson_interval


def test_z_is_the_95_percent_quantile():
    assert Z95 == pytest.approx(norm.ppf(0.975), rel=1e-15)


@pytest.mark.parametrize("k,n", [(0, 1), (1, 1), (0, 10), (10, 10), (19, 20), (3, 7), (199, 200), (500, 1000),
                                 (1, 10000)])
def test_matches_scipy(k, n):
    ci = binomtest(k, n).proportion_ci(confidence_level=0.95, method="wilson")
    lo, hi = wilson_interval(k, n)
    assert lo == pytest.approx(ci.low, abs=1e-12) and hi == pytest.approx(ci.high, abs=1e-12)


@given(st.integers(1, 5000).flatmap(lambda n: st.tuples(st.integers(0, n), st.just(n))))
def test_properties(kn):
    k, n = kn
    lo, hi = wilson_interval(k, n)
    assert 0.0 <= lo <= k / n <= hi <= 1.0
    assert (lo == 0.0) == (k == 0) and (hi == 1.0) == (k == n)
    lo2, hi2 = wilson_interval(n - k, n)  # symmetric under success ↔ failure
    assert lo2 == pytest.approx(1 - hi, abs=1e-12) and hi2 == pytest.approx(1 - lo, abs=1e-12)
    # the Wilson ends are the two roots of |p̂ − p| = z·sqrt(p(1 − p)/n) (score test inversion)
    for p in (lo, hi):
        if 0 < p < 1:
            assert abs(k / n - p) == pytest.approx(Z95 * math.sqrt(p * (1 - p) / n), rel=1e-9, abs=1e-12)


def test_no_trials_is_no_information():
    assert wilson_interval(0, 0) == (0.0, 1.0)


@pytest.mark.parametrize("k,n", [(-1, 5), (6, 5), (1, -1)])
def test_refuses_impossible_counts(k, n):
    with pytest.raises(InvalidStateError, match="successes"):
        wilson_interval(k, n)


def test_mean_interval_is_the_large_sample_interval_of_a_mean():
    import math

    import numpy as np

    from throwmap.experiments.stats import Z95, mean_interval

    v = np.array([3.0, 5.0, 7.0, 9.0, math.nan])  # nan (a failed trial's throws) is left out
    m, lo, hi = mean_interval(v)
    half = Z95 * np.std([3.0, 5.0, 7.0, 9.0], ddof=1) / 2.0
    assert m == 6.0 and lo == pytest.approx(6.0 - half) and hi == pytest.approx(6.0 + half)
    one = mean_interval([4.0])
    assert one[0] == 4.0 and math.isnan(one[1]) and math.isnan(one[2])
    assert all(math.isnan(v) for v in mean_interval([]))
    with pytest.raises(Exception, match="^z"):
        mean_interval([1.0, 2.0], z=0.0)

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

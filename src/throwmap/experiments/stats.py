"""Interval estimates for Monte Carlo results.

Every success rate carries the Wilson score interval (Wilson 1927; Brown, Cai &
DasGupta, *Statist. Sci.* 16 (2001) 101, Eq. (4)) rather than the Wald interval, which
collapses to a point at 0 or n successes — the cases a feeder is designed for.
:func:`rerun_range` is where a *new* run of m trials will land: the Wilson interval bounds the rate, not a
second sample of it (a 200-trial rerun of a 200-trial result falls outside its Wilson interval about one time in six).
:func:`mean_interval` is the large-sample interval of a mean (e.g. throws to success).
"""

from __future__ import annotations

import math

from ..errors import InvalidStateError, shown

__all__ = ["Z95", "wilson_interval", "rerun_range", "mean_interval"]

Z95 = 1.959963984540054
"""The two-sided 95 % standard-normal quantile, Φ⁻¹(0.975)."""


def wilson_interval(successes: int, n: int, z: float = Z95) -> tuple[float, float]:
    """Wilson score interval ``(low, high)`` for ``successes`` out of ``n`` Bernoulli trials.

    With p̂ = k/n::

        centre = (p̂ + z²/(2n)) / (1 + z²/n)
        half   = z / (1 + z²/n) · sqrt(p̂(1 − p̂)/n + z²/(4n²))

    ``z`` = :data:`Z95` gives the 95 % interval. ``n = 0`` gives ``(0.0, 1.0)`` (no
    information); ``k = 0`` gives a low end of exactly 0 and ``k = n`` a high end of exactly 1.
    """
    for name, v in (("successes", successes), ("n", n)):
        if isinstance(v, bool) or not isinstance(v, int) and not hasattr(v, "__index__"):
            raise InvalidStateError(name, f"must be an integer, got {shown(v)}")
    k, n = int(successes), int(n)
    if n < 0 or not 0 <= k <= n:
        raise InvalidStateError("successes", f"must satisfy 0 ≤ successes ≤ n, got {k} of {n}")
    if not (isinstance(z, (int, float)) and math.isfinite(z) and z > 0):
        raise InvalidStateError("z", f"must be a positive finite number, got {shown(z)}")
    if n == 0:
        return 0.0, 1.0
    p = k / n
    z2 = z * z
    denom = 1.0 + z2 / n
    centre = (p + z2 / (2 * n)) / denom
    half = z / denom * math.sqrt(p * (1.0 - p) / n + z2 / (4.0 * n * n))
    low = 0.0 if k == 0 else max(0.0, centre - half)
    high = 1.0 if k == n else min(1.0, centre + half)
    return low, high


def rerun_range(successes: int, n: int, m: int, level: float = 0.95) -> tuple[int, int]:
    """The successes ``(low, high)`` a new run of ``m`` trials reaches with probability ≥ ``level`` (central), given
    ``successes`` of ``n`` so far: the posterior predictive of the rate under the Jeffreys prior Beta(½, ½), a
    beta-binomial(m, k + ½, n − k + ½) (Gelman et al., *Bayesian Data Analysis*, 3rd ed., Sec. 2.4 and 2.9).

    It holds both uncertainties — the rate's, from ``n`` trials, and the new run's own sampling — so it is wider
    than the Wilson interval scaled to ``m``: 390 of 400 gives 189–199 of 200 (94.5–99.5 %), against Wilson's
    95.5–98.6 %.
    """
    from scipy.stats import betabinom

    wilson_interval(successes, n)  # the same checks on successes and n
    check = m if not isinstance(m, bool) and hasattr(m, "__index__") else None
    if check is None or int(m) < 1:
        raise InvalidStateError("m", f"must be an integer ≥ 1 (trials in the new run), got {shown(m)}")
    if not (isinstance(level, (int, float)) and 0.0 < level < 1.0):
        raise InvalidStateError("level", f"must be a probability in (0, 1), got {shown(level)}")
    k, n, m = int(successes), int(n), int(m)
    d = betabinom(m, k + 0.5, n - k + 0.5)
    tail = (1.0 - level) / 2.0
    return int(d.ppf(tail)), int(d.ppf(1.0 - tail))


def mean_interval(values, z: float = Z95) -> tuple[float, float, float]:
    """``(mean, low, high)`` of the finite ``values`` with the large-sample interval mean ± z·s/√n
    (s the sample standard deviation, ddof = 1; ``z`` = :data:`Z95`: 95 %). Fewer than two values give nan
    bounds (no spread to estimate); none gives nan throughout."""
    import numpy as np

    if not (isinstance(z, (int, float)) and math.isfinite(z) and z > 0):
        raise InvalidStateError("z", f"must be a positive finite number, got {shown(z)}")
    v = np.asarray(values, dtype=float).ravel()
    v = v[np.isfinite(v)]
    if v.size == 0:
        return math.nan, math.nan, math.nan
    m = float(v.mean())
    if v.size < 2:
        return m, math.nan, math.nan
    half = z * float(v.std(ddof=1)) / math.sqrt(v.size)
    return m, m - half, m + half

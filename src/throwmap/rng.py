"""The one seeding helper: every stochastic function takes ``rng`` through :func:`as_generator`."""

from __future__ import annotations

import numpy as np

from .errors import InvalidStateError, shown

__all__ = ["as_generator"]


def as_generator(rng=None, field: str = "rng") -> np.random.Generator:
    """A :class:`numpy.random.Generator` from a Generator, an integer seed or None (fresh entropy).

    The same integer seed always gives the same stream, so the same seed gives the same result.
    """
    if isinstance(rng, np.random.Generator):
        return rng
    if rng is None:
        return np.random.default_rng()
    if isinstance(rng, bool) or not isinstance(rng, (int, np.integer)) or int(rng) < 0:
        raise InvalidStateError(field, f"must be a non-negative integer seed, a numpy Generator or None, got {shown(rng)}")
    return np.random.default_rng(int(rng))

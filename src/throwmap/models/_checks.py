"""Validation helpers shared by the models' options dataclasses (one-line errors naming the field)."""

from __future__ import annotations

import math

import numpy as np

from ..errors import InvalidStateError, shown


def finite_float(value, field: str) -> float:
    """A finite number (an int, a float or a NumPy scalar; booleans and text refused) as a float."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) or not math.isfinite(value):
        raise InvalidStateError(field, f"must be a finite number, got {shown(value)}")
    return float(value)


def positive_float(value, field: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
        raise InvalidStateError(field, f"must be a positive finite number, got {shown(value)}")
    return float(value)


TOL_MAX = 1e-6
"""Largest contact tolerance (dimensionless, relative to the gap's terms) the analytic models accept: a
looser one stops the first-contact search visibly early and silently moves the result."""


def tolerance(value, field: str = "tol") -> float:
    """A dimensionless relative tolerance, 0 < value ≤ :data:`TOL_MAX`."""
    v = positive_float(value, field)
    if v > TOL_MAX:
        raise InvalidStateError(field, f"must be ≤ {TOL_MAX:g} (a relative tolerance; the default is 1e-14), "
                                       f"got {shown(value)}")
    return v


def int_at_least(value, field: str, lo: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < lo:
        raise InvalidStateError(field, f"must be an integer ≥ {lo}, got {shown(value)}")
    return int(value)

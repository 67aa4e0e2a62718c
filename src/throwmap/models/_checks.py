"""Validation helpers shared by the models' options dataclasses (one-line errors naming the field)."""

from __future__ import annotations

import math

from ..errors import InvalidStateError, shown


def positive_float(value, field: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
        raise InvalidStateError(field, f"must be a positive finite number, got {shown(value)}")
    return float(value)


def int_at_least(value, field: str, lo: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < lo:
        raise InvalidStateError(field, f"must be an integer ≥ {lo}, got {shown(value)}")
    return int(value)

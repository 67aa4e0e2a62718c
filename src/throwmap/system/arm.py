"""The one-joint throwing arm (paper Sec. III-A, Fig. 6)."""

from __future__ import annotations

import math
import numbers
import warnings
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass

import numpy as np

from ..conventions import G
from ..errors import InvalidArmError, RegimeWarning, shown

__all__ = ["Arm", "check_back", "check_g", "check_length", "check_mu", "regime_problems", "regime_warnings_once",
           "warn_if_outside_regime"]


def _is_real(value) -> bool:
    """A real number (Python or NumPy, e.g. ``np.int64``, ``np.float32``), not a bool."""
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def check_mu(value, field: str = "arm.mu") -> float:
    """Coulomb friction μ as a float: a number ≥ 0, ``inf`` for a contact that never slips (the one rule for μ
    everywhere: the Arm, walls, configs); else :class:`~throwmap.errors.InvalidArmError` on ``field``."""
    if not _is_real(value) or math.isnan(value) or value < 0:
        raise InvalidArmError(field, f"must be a number ≥ 0 (inf: no slip), got {shown(value)}")
    return float(value)


def check_g(value, field: str = "arm.g") -> float:
    """Gravitational acceleration (m/s², along −y) as a float: a positive finite number."""
    if not _is_real(value):
        raise InvalidArmError(field, f"must be a number, got {shown(value)}")
    if not math.isfinite(value):
        raise InvalidArmError(field, f"must be finite, got {value}")
    if value <= 0:
        raise InvalidArmError(field, f"must be positive (gravity acts along -y), got {value}")
    return float(value)


def check_back(value, field: str = "arm.back") -> float:
    """The arm's surface behind the joint (m) as a float: a finite number ≥ 0."""
    if not _is_real(value):
        raise InvalidArmError(field, f"must be a number, got {shown(value)}")
    if not math.isfinite(value) or value < 0:
        raise InvalidArmError(field, f"must be a finite number ≥ 0, got {shown(value)}")
    return float(value)


def check_length(value, field: str = "arm.length"):
    """An arm length (m) as a float, or None (unbounded): a positive number; ``inf`` and None both mean an
    unbounded arm (the one spelling of config files); else :class:`~throwmap.errors.InvalidArmError` on ``field``."""
    if value is None:
        return None
    if _is_real(value) and value == math.inf:
        return None
    if not _is_real(value) or not math.isfinite(value) or value <= 0:
        raise InvalidArmError(field, f"must be a positive number in m (inf: unbounded), got {shown(value)}")
    return float(value)


@dataclass(frozen=True, slots=True)
class Arm:
    """A one-joint arm whose surface is the line y = h when horizontal.

    Attributes
    ----------
    h : float
        Height of the surface at rest, m (h < 0: below the joint axis). Any finite h
        is valid; outside the paper's regime 0 > h > -min_i d_i a
        :class:`~throwmap.errors.RegimeWarning` says which guarantee is lost.
    g : float
        Gravitational acceleration along −y, m/s² (> 0).
    length : float or None
        The arm spans 0 ≤ x ≤ length, m; ``None`` means unbounded.
    mu : float
        Coulomb friction coefficient between the arm and a part (≥ 0; ``inf``: the
        contact never slips, the paper's assumption). Used by the "rigid_body"
        model and the engines; "paper" and the small-angle models assume no slip
        and only report the friction ratio a throw needs.
    back : float
        Extent of the arm's surface behind the joint, m (≥ 0, finite): the surface
        spans −back ≤ x along the arm, and a contact at x ≤ −back is
        ``behind_joint``. With the default 0 any contact at x ≤ 0 is
        ``behind_joint`` (a contact exactly at the joint included), as in the
        paper, where the part must stay on the arm's outer side.
    """

    h: float
    g: float = G
    length: float | None = None
    mu: float = math.inf
    back: float = 0.0

    def __post_init__(self):
        h = self.h
        if not _is_real(h):
            raise InvalidArmError("arm.h", f"must be a number, got {shown(h)}")
        if not math.isfinite(h):
            raise InvalidArmError("arm.h", f"must be finite, got {h}")
        object.__setattr__(self, "h", float(h))
        object.__setattr__(self, "g", check_g(self.g))
        object.__setattr__(self, "length", check_length(self.length))
        object.__setattr__(self, "mu", check_mu(self.mu))
        object.__setattr__(self, "back", check_back(self.back))

    @property
    def no_slip(self) -> bool:
        """Whether the arm contact can never slip (μ = ∞)."""
        return math.isinf(self.mu)

    @property
    def length_or_inf(self) -> float:
        return math.inf if self.length is None else self.length


def regime_problems(part, arm: Arm) -> list[str]:
    """Which of the paper's guarantees (Sec. III-D) fail for this part on this arm.

    The paper requires 0 > h > -min_i d_i: h < 0 makes jogs outward (the left
    support vertex starts with an outward velocity), h > -min d makes the CM's
    flight velocity inward so flips move the part toward the joint.
    """
    out = []
    if arm.h >= 0:
        out.append(f"h = {arm.h:g} m ≥ 0: jogs are no longer guaranteed to move outward")
    min_d = part.min_d
    if arm.h <= -min_d:
        out.append(f"h = {arm.h:g} m ≤ -min d = {-min_d:g} m: flips are no longer guaranteed to move inward")
    return out


_WARNED: ContextVar[tuple] = ContextVar("throwmap_regime_warned", default=())
"""The registries of the :func:`regime_warnings_once` blocks open now (innermost last): the messages warned in each."""


@contextmanager
def regime_warnings_once():
    """Within the block each lost guarantee (each distinct :class:`RegimeWarning` message) is warned once: the
    first throw that loses it warns, the rest of the block's throws do not. Works as a decorator too, a fresh
    registry per call, so a function that throws in a loop (a limit set, basins, an experiment's trials) warns once
    per call, and a later call warns again. Blocks nest (what an outer block warned, an inner one does not warn
    again); the registry is the context's (threads and tasks each have their own), never global."""
    token = _WARNED.set(_WARNED.get() + (set(),))
    try:
        yield
    finally:
        _WARNED.reset(token)


def warn_if_outside_regime(part, arm: Arm, stacklevel: int = 3) -> None:
    """Issue a :class:`RegimeWarning` per lost guarantee (see :func:`regime_problems`), once per
    :func:`regime_warnings_once` block where one is open."""
    if arm.h < 0 and arm.h > -part.min_d:
        return
    seen = _WARNED.get()
    for msg in regime_problems(part, arm):
        if any(msg in s for s in seen):
            continue
        for s in seen:
            s.add(msg)
        warnings.warn(msg, RegimeWarning, stacklevel=stacklevel)

"""The one-joint throwing arm (paper Sec. III-A, Fig. 6)."""

from __future__ import annotations

import math
import numbers
import warnings
from dataclasses import dataclass

import numpy as np

from ..conventions import G
from ..errors import InvalidArmError, RegimeWarning, shown

__all__ = ["Arm", "regime_problems", "warn_if_outside_regime"]


def _is_real(value) -> bool:
    """A real number (Python or NumPy, e.g. ``np.int64``, ``np.float32``), not a bool."""
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


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
        for name in ("h", "g"):
            val = getattr(self, name)
            if not _is_real(val):
                raise InvalidArmError(f"arm.{name}", f"must be a number, got {shown(val)}")
            if not math.isfinite(val):
                raise InvalidArmError(f"arm.{name}", f"must be finite, got {val}")
        if self.g <= 0:
            raise InvalidArmError("arm.g", f"must be positive (gravity acts along -y), got {self.g}")
        if self.length is not None:
            L = self.length
            if not _is_real(L) or not math.isfinite(L) or L <= 0:
                raise InvalidArmError("arm.length", f"must be a positive finite number or None, got {shown(L)}")
        mu = self.mu
        if not _is_real(mu) or math.isnan(mu) or mu < 0:
            raise InvalidArmError("arm.mu", f"must be a number ≥ 0 (inf: no slip), got {shown(mu)}")
        object.__setattr__(self, "mu", float(mu))
        back = self.back
        if not _is_real(back):
            raise InvalidArmError("arm.back", f"must be a number, got {shown(back)}")
        if not math.isfinite(back) or back < 0:
            raise InvalidArmError("arm.back", f"must be a finite number ≥ 0, got {shown(back)}")
        object.__setattr__(self, "back", float(back))
        object.__setattr__(self, "h", float(self.h))
        object.__setattr__(self, "g", float(self.g))
        if self.length is not None:
            object.__setattr__(self, "length", float(self.length))

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


def warn_if_outside_regime(part, arm: Arm, stacklevel: int = 3) -> None:
    """Issue a :class:`RegimeWarning` per lost guarantee (see :func:`regime_problems`)."""
    if arm.h < 0 and arm.h > -part.min_d:
        return
    for msg in regime_problems(part, arm):
        warnings.warn(msg, RegimeWarning, stacklevel=stacklevel)

"""The system a part is thrown on: the arm, its fixtures and its rest angle α.

Models take a :class:`System` besides the part (see :mod:`throwmap.models`).
Each model states which features of it it supports (:class:`throwmap.models.Features`)
and refuses the rest with a one-line error naming the field; ``throw``,
``throw_batch`` and ``iterate`` build the System from their ``arm``,
``fixtures=`` and ``alpha=`` keywords.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InvalidStateError, shown, warn_scale
from .arm import Arm
from .fixtures import Cavity, Wall

__all__ = ["System", "check_alpha"]


def check_alpha(value, field: str = "alpha") -> float:
    """The arm's rest angle α (rad, counter-clockwise from horizontal) as a float: finite, |α| < π/2 (the arm
    below vertical; draft Sec. VI); else :class:`~throwmap.errors.InvalidStateError` on ``field``."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InvalidStateError(field, f"must be a finite angle in rad, got {shown(value)}")
    if not abs(value) < 0.5 * math.pi:
        # a value of a few units was likely meant in degrees: say how to write it; at ±π/2 (90° already) it was not
        hint = f"; for degrees write e.g. {value:g}deg" if abs(abs(value) - 0.5 * math.pi) > 1e-9 else ""
        raise InvalidStateError(field, f"must be an angle with |α| < π/2 rad (the arm below vertical), got {value} "
                                       f"(= {math.degrees(value):.4g}°{hint})")
    warn_scale(field, value, "alpha")
    return float(value)


@dataclass(frozen=True, slots=True)
class System:
    """An arm with fixtures, resting at angle ``alpha`` (rad, counter-clockwise from horizontal).

    ``fixtures`` is a tuple of :class:`~throwmap.system.fixtures.Wall` /
    :class:`~throwmap.system.fixtures.Cavity` in the arm frame. The paper's analytic
    models (Sec. III) assume a plain horizontal arm: ``fixtures=()``, ``alpha=0``.
    """

    arm: Arm
    fixtures: tuple = ()
    alpha: float = 0.0

    def __post_init__(self):
        if not isinstance(self.arm, Arm):
            raise InvalidStateError("arm", f"must be an Arm, got {type(self.arm).__name__}")
        fx = self.fixtures
        if fx is None:
            fx = ()
        if isinstance(fx, (Wall, Cavity)):
            fx = (fx,)
        try:
            fx = tuple(fx)
        except TypeError:
            raise InvalidStateError("fixtures", f"must be a sequence of Wall/Cavity, got {shown(fx)}") from None
        for i, f in enumerate(fx):
            if not isinstance(f, (Wall, Cavity)):
                raise InvalidStateError(f"fixtures[{i}]", f"must be a Wall or a Cavity, got {type(f).__name__}")
        for kind in (Wall, Cavity):  # one arm end: one wall, one cavity (engine.scene and rigid_body take one)
            if sum(isinstance(f, kind) for f in fx) > 1:
                raise InvalidStateError("fixtures", f"at most one {kind.__name__} (the arm has one end), got "
                                                    f"{sum(isinstance(f, kind) for f in fx)}")
        object.__setattr__(self, "fixtures", fx)
        object.__setattr__(self, "alpha", check_alpha(self.alpha))

    @property
    def plain(self) -> bool:
        """True for the paper's arm: no fixtures, horizontal at rest."""
        return not self.fixtures and self.alpha == 0.0

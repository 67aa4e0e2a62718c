"""How far a design may drift: the distance along a parameter to the nearest change of its limit set.

:func:`margin` runs a short :func:`~throwmap.analysis.continuation.continuation` centred on the design's value
(``n`` values over ± ``span``, the value itself one of them) and reports the nearest event of any kind and the
nearest edge of escape — where starts begin (or stop) leaving the arm — on either side; a design whose own value
already lets starts escape has escape margin 0. Events beyond the span are not seen: a margin is then "more than
the span", never a number it did not measure.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InvalidStateError, shown
from .continuation import PARAMS, Continuation, Event, Resolution, continuation

__all__ = ["Margin", "margin", "MARGIN_RESOLUTION"]

MARGIN_RESOLUTION = Resolution(starts=40, horizon=300, tol=2e-3)
"""The continuation a margin runs: 40 starts per side, 300 throws, events to 2e-3 of the parameter's unit."""


@dataclass(frozen=True)
class Margin:
    """The margin of ``value`` along ``param``: ``span`` (lo, hi) searched; ``nearest`` event (or None) at
    ``distance``; ``escape`` the nearest escape edge (or None) at ``escape_distance`` (0 when starts already escape
    at ``value``; inf when none in the span); ``continuation`` the run it rests on."""

    param: str
    unit: str
    value: float
    span: tuple
    nearest: Event | None
    distance: float
    escape: Event | None
    escape_distance: float
    continuation: Continuation

    def text(self) -> str:
        u = f" {self.unit}" if self.unit else ""
        lo, hi = self.span

        def dist(d, e):
            if e is None and math.isinf(d):
                return f"none within [{lo:.4g}, {hi:.4g}]{u}"
            if e is None:
                return "0 (starts escape at the value itself)"
            return f"{d:.3g}{u} ({e.kind} at {e.value:.4g}{u})"

        return (f"margin along {self.param} from {self.value:.4g}{u}: nearest event {dist(self.distance, self.nearest)}; "
                f"escape {dist(self.escape_distance, self.escape)}")

    def to_dict(self) -> dict:
        def num(v):
            return None if math.isinf(v) else v

        return {"param": self.param, "unit": self.unit, "value": self.value, "span": list(self.span),
                "nearest": None if self.nearest is None else self.nearest.to_dict(), "distance": num(self.distance),
                "escape": None if self.escape is None else self.escape.to_dict(),
                "escape_distance": num(self.escape_distance), "text": self.text()}


def margin(part, arm, param: str, value: float, *, span: float, omega=None, model: str = "rigid_body", n: int = 9,
           resolution: Resolution = MARGIN_RESOLUTION, **throw_options) -> Margin:
    """The margin of ``part`` on ``arm`` at ``param`` = ``value`` (module docstring): a continuation over
    ``value`` ± ``span`` (in the parameter's unit; ω kept above 0) at ``n`` values (odd: ``value`` is one),
    ``omega`` (rad/s) where ω is not the parameter, ``model``, ``resolution``, ``throw_options`` as for
    :func:`~throwmap.analysis.continuation.continuation`."""
    import numpy as np

    if param not in PARAMS:
        raise InvalidStateError("param", f"must be one of {', '.join(PARAMS)}, got {shown(param)}")
    if not (isinstance(span, (int, float)) and math.isfinite(span) and span > 0):
        raise InvalidStateError("span", f"must be a number > 0, got {shown(span)}")
    if isinstance(n, bool) or not isinstance(n, int) or n < 3:
        raise InvalidStateError("n", f"must be an integer ≥ 3, got {shown(n)}")
    half = n // 2
    lo = value - span
    if param in ("omega", "mu"):
        lo = max(lo, value * 0.05 if param == "omega" else 0.0)
    values = np.concatenate([np.linspace(lo, value, half + 1), np.linspace(value, value + span, half + 1)[1:]])
    c = continuation(part, arm, param, values, omega=omega, model=model, resolution=resolution, **throw_options)
    d, e = c.margin(value)
    here = next(p for p in c.points if p.value == float(value))
    if here.escape_fraction > 0:
        de, ee = 0.0, None
    else:
        de, ee = c.margin(value, kinds=("escape_onset", "escape_end"))
    return Margin(param, c.unit, float(value), (float(values[0]), float(values[-1])), e, d, ee, de, c)

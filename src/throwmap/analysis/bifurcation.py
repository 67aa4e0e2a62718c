"""The results of a continuation (:func:`throwmap.analysis.continuation.continuation`): how finely it looked
(:class:`Resolution`), the attractors at every value (:class:`ContinuationPoint`), the events located
(:class:`Event`) and the whole curve (:class:`Continuation`: JSON, table, the bifurcation diagram)."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidStateError, shown
from .attractors import Attractor

__all__ = ["EVENT_KINDS", "Resolution", "Event", "ContinuationPoint", "Continuation"]

EVENT_KINDS = ("appear", "vanish", "merge", "split", "jump", "period_doubling", "fold", "escape_onset", "escape_end")


@dataclass(frozen=True, slots=True)
class Resolution:
    """How finely a continuation looks.

    ``starts``: starts per stable side (evenly over (x_lo, x_max], m; ``x_max`` None: the arm's length, else
    0.6 m); ``horizon``: throws an orbit is followed before it is called unresolved (an escape later than this is
    not seen); ``tol``: the width, in the parameter's unit, to which events are located; ``match_tol``: the
    largest distance (m) between two attractors' sets at neighbouring values for them to be one attractor;
    ``max_refine``: the most values evaluated while locating events; ``critical``: also r_i (where jogs end,
    :func:`~throwmap.analysis.critical.critical_points`) at every value of the grid.
    """

    starts: int = 200
    x_max: float | None = None
    horizon: int = 500
    tol: float = 1e-3
    match_tol: float = 0.03
    max_refine: int = 400
    critical: bool = False

    def __post_init__(self):
        for name, lo in (("starts", 2), ("horizon", 1), ("max_refine", 0)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < lo:
                raise InvalidStateError(name, f"must be an integer ≥ {lo}, got {shown(v)}")
        for name in ("tol", "match_tol"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v > 0):
                raise InvalidStateError(name, f"must be a number > 0, got {shown(v)}")
        if self.x_max is not None and not (isinstance(self.x_max, (int, float)) and math.isfinite(self.x_max)
                                           and self.x_max > 0):
            raise InvalidStateError("x_max", f"must be a length > 0 m, got {shown(self.x_max)}")


@dataclass(frozen=True, slots=True)
class Event:
    """A change located on the parameter: ``kind`` (one of ``appear``, ``vanish``, ``merge``, ``split``, ``jump``,
    ``period_doubling``, ``fold``, ``escape_onset``, ``escape_end``), ``value`` (the middle of the final interval,
    in the parameter's unit) ± ``tol`` (half its width), ``ids`` (the attractors concerned) and ``detail``."""

    kind: str
    value: float
    tol: float
    ids: tuple = ()
    detail: str = ""

    def to_dict(self) -> dict:
        return {"kind": self.kind, "value": self.value, "tol": self.tol, "ids": list(self.ids), "detail": self.detail}


@dataclass(frozen=True, slots=True)
class ContinuationPoint:
    """The attractors at one value: ``attractors`` (:class:`~throwmap.analysis.attractors.Attractor`, ids
    continued along the curve, ``fraction`` the share of the starts ending on each), ``escape_fraction`` (share
    of the starts that left the arm within the horizon), ``unresolved_fraction`` (still undecided at the
    horizon), ``escapes`` (share by fate), ``r`` (r_i per side, m, when asked for), ``refined`` (True for a value
    added while locating an event)."""

    value: float
    attractors: tuple
    escape_fraction: float
    unresolved_fraction: float
    escapes: dict
    r: dict = field(default_factory=dict)
    refined: bool = False

    def l_points(self) -> dict:
        """l_i per side: the lowest x of the attractors on that side, m (paper Sec. III-D: l_i = inf S)."""
        out: dict = {}
        for a in self.attractors:
            for s, lo, _ in a.bands:
                out[int(s)] = min(out.get(int(s), math.inf), float(lo))
        return out

    def to_dict(self) -> dict:
        def att(a: Attractor) -> dict:
            lo = min(b[1] for b in a.bands)
            hi = max(b[2] for b in a.bands)
            return {"id": a.id, "kind": a.kind, "period": a.period, "sides": list(a.sides), "x": [lo, hi],
                    "bands": [[int(s), float(b0), float(b1)] for s, b0, b1 in a.bands], "fraction": a.fraction,
                    "multiplier": None if not math.isfinite(a.multiplier) else a.multiplier}

        return {"value": self.value, "escape_fraction": self.escape_fraction,
                "unresolved_fraction": self.unresolved_fraction, "escapes": dict(self.escapes),
                "attractors": [att(a) for a in self.attractors],
                "l": {str(s): v for s, v in sorted(self.l_points().items())},
                **({"r": {str(s): (None if not math.isfinite(v) else v) for s, v in sorted(self.r.items())}}
                   if self.r else {}),
                "refined": self.refined}


@dataclass(frozen=True)
class Continuation:
    """Attractors along one parameter (module docstring): ``param`` and its ``unit``; ``points`` (every value
    evaluated, ascending; ``grid`` the values asked for); ``events``; ``range`` (the starts, in words and
    numbers); ``system`` (what is fixed); ``model``; ``resolution``; ``warnings`` (each distinct one, once);
    ``time_s``; ``evaluations``."""

    param: str
    unit: str
    grid: tuple
    points: tuple
    events: tuple
    range: dict
    system: dict
    model: str
    resolution: Resolution
    warnings: tuple
    time_s: float
    evaluations: int

    @property
    def ids(self) -> tuple:
        return tuple(sorted({a.id for p in self.points for a in p.attractors}))

    def at_grid(self) -> tuple:
        """The points at the values asked for (without those added while locating events)."""
        return tuple(p for p in self.points if not p.refined)

    def margin(self, value: float, kinds=None) -> tuple:
        """``(distance, event)`` to the nearest event from ``value`` (of ``kinds``, default all), in the parameter's
        unit; ``(inf, None)`` when there is none."""
        best = (math.inf, None)
        for e in self.events:
            if kinds is None or e.kind in kinds:
                d = abs(e.value - value)
                if d < best[0]:
                    best = (d, e)
        return best

    def to_dict(self) -> dict:
        return {"param": self.param, "unit": self.unit, "model": self.model,
                "points": [p.to_dict() for p in self.points], "events": [e.to_dict() for e in self.events],
                "range": dict(self.range), "system": dict(self.system),
                "resolution": dataclasses.asdict(self.resolution), "warnings": list(self.warnings),
                "time_s": self.time_s, "evaluations": self.evaluations}

    def table(self) -> str:
        """One row per value asked for (attractors as ``#id kind sides x-range share``), then the events."""
        u = f" {self.unit}" if self.unit else ""
        lines = [f"continuation along {self.param}{u} ({self.model}); starts: {self.range['text']}"]
        for p in self.at_grid():
            atts = "; ".join(f"#{a.id} {a.kind}{'' if a.kind != 'cycle' else f'/{a.period}'} s{','.join(map(str, a.sides))} "
                             f"[{100 * min(b[1] for b in a.bands):.2f}, {100 * max(b[2] for b in a.bands):.2f}] cm "
                             f"{100 * a.fraction:.1f} %" for a in p.attractors) or "none"
            un = f"  unresolved {100 * p.unresolved_fraction:.1f} %" if p.unresolved_fraction > 0 else ""
            lines.append(f"  {p.value:10.5g}  escape {100 * p.escape_fraction:5.1f} %{un}  {atts}")
        if self.events:
            lines.append("events:")
            for e in self.events:
                ids = f" (#{', #'.join(map(str, e.ids))})" if e.ids else ""
                lines.append(f"  {e.kind:<16} at {e.value:.6g} ± {e.tol:.2g}{u}{ids}  {e.detail}")
        else:
            lines.append("events: none between the values evaluated")
        for w in self.warnings:
            lines.append(f"note: {w}")
        return "\n".join(lines)

    def plot(self, path=None, **kwargs):
        """The bifurcation diagram over the basin fractions (:func:`throwmap.viz.continuation.plot_continuation`)."""
        from ..viz.continuation import plot_continuation

        return plot_continuation(self, path=path, **kwargs)



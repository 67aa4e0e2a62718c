"""What a design aims at: features of the limit set and their targets (paper Sec. V).

Three kinds of target, each on one stable side (sides numbered as in
:mod:`throwmap.conventions`):

``Target("r", side, value)``       the critical point r_i (m): jogs for x < r_i, not from r_i on —
                                   the draft's sup S (Sec. V-A), from
                                   :func:`throwmap.analysis.critical_points` on the exact map, to ``xtol``.
``Target("top", side, value)``     the band top u_i of the forward limit set on the side (m):
``Target("bottom", side, value)``  its bottom l_i = inf S; both from
                                   :func:`throwmap.analysis.limit_set` (orbits; noisier than r_i:
                                   found to the band sampling, so use larger FD steps).
``WallWindow(side, jitter, width)`` an end wall at the arm's end L holds side k and no other, for every
                                   ω within ±jitter: with u_R(i) the CM → outer support vertex,
                                   S = [r_k + u_R(k)](ω(1 + jitter)) − max_{j≠k} [r_j + u_R(j)](ω(1 − jitter))
                                   is the width of the usable L; the residual max(0, width − S) is zero
                                   once S ≥ width (a part against the wall at L jogs back to it iff
                                   L − u_R(i) < r_i, and r_i falls as ω rises).
``Separation(side, x, margin)``    "x beyond X is reached only on side k, with margin m":
                                   every point of the limit set on a side j ≠ k lies below X − m
                                   (u_j ≤ X − m) and the limit set on side k reaches X + m
                                   (u_k ≥ X + m). Its residuals are the hinges
                                   max(0, u_j − (X − m)) for j ≠ k and max(0, X + m − u_k): zero
                                   exactly when the objective holds.

Every target becomes one or more rows of the residual vector (achieved − target, m).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, shown

__all__ = ["Target", "Separation", "WallWindow", "as_targets", "Evaluation", "evaluate"]

KINDS = ("r", "top", "bottom")


@dataclass(frozen=True, slots=True)
class Target:
    """A feature of the limit set (``kind`` r | top | bottom) on ``side`` to bring to ``value`` (m)."""

    kind: str
    side: int
    value: float

    def __post_init__(self):
        if self.kind not in KINDS:
            raise InvalidStateError("target", f"unknown kind {shown(self.kind)} (choose from {', '.join(KINDS)})")
        if isinstance(self.side, bool) or not isinstance(self.side, (int, np.integer)) or self.side < 0:
            raise InvalidStateError("target", f"side must be a side index ≥ 0, got {shown(self.side)}")
        object.__setattr__(self, "side", int(self.side))
        v = self.value
        if isinstance(v, bool) or not isinstance(v, (int, float, np.floating)) or not math.isfinite(v):
            raise InvalidStateError("target", f"{self.kind}_{self.side}: must be a finite position in m, got {shown(v)}")
        object.__setattr__(self, "value", float(v))

    @property
    def label(self) -> str:
        return f"{self.kind}_{self.side}"

    @property
    def rows(self) -> tuple:
        return (self.label,)


@dataclass(frozen=True, slots=True)
class Separation:
    """x ≥ ``x`` + ``margin`` is reached by the limit set on ``side`` and no other side passes ``x`` − ``margin`` (m)."""

    side: int
    x: float
    margin: float = 0.01

    def __post_init__(self):
        if isinstance(self.side, bool) or not isinstance(self.side, (int, np.integer)) or self.side < 0:
            raise InvalidStateError("separation.side", f"must be a side index ≥ 0, got {shown(self.side)}")
        object.__setattr__(self, "side", int(self.side))
        for nm in ("x", "margin"):
            v = getattr(self, nm)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.floating)) or not math.isfinite(v):
                raise InvalidStateError(f"separation.{nm}", f"must be a finite length in m, got {shown(v)}")
        if self.margin < 0:
            raise InvalidStateError("separation.margin", f"must be ≥ 0, got {self.margin}")
        object.__setattr__(self, "x", float(self.x))
        object.__setattr__(self, "margin", float(self.margin))

    label = property(lambda self: f"only side {self.side} beyond {100 * self.x:.4g} cm (±{100 * self.margin:.3g})")

    def residual(self, tops: dict) -> dict:
        """Hinge residuals per side (m), keyed ``sep_j``; nan where a side's top is unknown."""
        out = {}
        for j, u in sorted(tops.items()):
            if j == self.side:
                out[f"sep_{j}"] = max(0.0, self.x + self.margin - u) if math.isfinite(u) else math.nan
            else:
                # a side the limit set never rests on (nan) cannot reach X: satisfied
                out[f"sep_{j}"] = max(0.0, u - (self.x - self.margin)) if math.isfinite(u) else 0.0
        return out

    def holds(self, tops: dict) -> bool:
        r = self.residual(tops)
        return all(math.isfinite(v) and v == 0.0 for v in r.values())


@dataclass(frozen=True, slots=True)
class WallWindow:
    """An end wall holds ``side`` only for ω within ±``jitter`` (fraction), with a window ≥ ``width`` (m)."""

    side: int
    jitter: float = 0.06
    width: float = 0.02

    def __post_init__(self):
        if isinstance(self.side, bool) or not isinstance(self.side, (int, np.integer)) or self.side < 0:
            raise InvalidStateError("wall_window.side", f"must be a side index ≥ 0, got {shown(self.side)}")
        object.__setattr__(self, "side", int(self.side))
        for nm, lo, hi in (("jitter", 0.0, 0.5), ("width", 0.0, math.inf)):
            v = getattr(self, nm)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.floating)) or not (lo <= v < hi):
                raise InvalidStateError(f"wall_window.{nm}", f"must be a number in [{lo}, {hi}), got {shown(v)}")
            object.__setattr__(self, nm, float(v))

    @property
    def label(self) -> str:
        return f"wall_{self.side}"

    def width_of(self, part, r_lo: dict, r_hi: dict) -> float:
        """S (m) from r_i at ω(1 − jitter) and ω(1 + jitter); nan where an r_i is missing."""
        k = self.side
        others = [r_lo.get(j, math.nan) + float(part.uR[j]) for j in part.stable_sides if j != k]
        if k not in part.stable_sides or not others:
            return math.nan
        return r_hi.get(k, math.nan) + float(part.uR[k]) - max(others)


def as_targets(target) -> tuple:
    """A dict ``{side: r_i}`` (m), or Target/Separation objects, as a tuple of targets."""
    if isinstance(target, (Target, Separation, WallWindow)):
        return (target,)
    if isinstance(target, dict):
        if not target:
            raise InvalidStateError("target", "give at least one target")
        return tuple(Target("r", s, v) for s, v in sorted(target.items(), key=lambda kv: str(kv[0])))
    try:
        items = tuple(target)
    except TypeError:
        raise InvalidStateError("target", f"must be a dict {{side: r_i}} or targets, got {shown(target)}") from None
    if not items or not all(isinstance(t, (Target, Separation, WallWindow)) for t in items):
        raise InvalidStateError("target", "must be a dict {side: r_i in m} or a sequence of Target/Separation/"
                                          "WallWindow")
    if sum(isinstance(t, Separation) for t in items) > 1:
        raise InvalidStateError("target", "at most one separation objective")
    labels = [t.label for t in items if not isinstance(t, Separation)]
    if len(set(labels)) != len(labels):
        raise InvalidStateError("target", f"a feature is targeted twice: {labels}")
    return items


@dataclass(frozen=True, slots=True)
class Evaluation:
    """Features of one design point: r_i, band tops/bottoms (m), and the residual rows."""

    r: dict
    top: dict
    bottom: dict
    residual: dict
    next_kind: dict
    wall: dict = None

    @property
    def vector(self) -> np.ndarray:
        return np.array(list(self.residual.values()), dtype=float)

    @property
    def finite(self) -> bool:
        return bool(np.all(np.isfinite(self.vector)))


class _NoLimit:
    """Stands in for a LimitSet in :func:`critical_points` so that only r_i is computed (l_i nan)."""

    def l(self, side):  # noqa: E741 - the paper's l_i
        return math.nan


def evaluate(setup, targets, model: str, *, x_max=None, xtol: float = 1e-7, n_grid: int = 128,
             limit_options=None) -> Evaluation:
    """The features ``targets`` need at one design point (an :class:`~throwmap.design.space.Setup`).

    r_i by :func:`throwmap.analysis.critical_points` (``n_grid``, ``xtol``; l_i skipped); band
    tops/bottoms by :func:`throwmap.analysis.limit_set` (``limit_options``, default 32 starts per
    side, seed 0) only when a target needs them. A side that is no longer stable, or has no
    such feature, gives nan.
    """
    from ..analysis.critical import critical_points
    from ..analysis.limitset import limit_set

    part, arm, omega, opts = setup.part, setup.arm, setup.omega, setup.throw_options
    need_r = any(isinstance(t, Target) and t.kind == "r" for t in targets)
    need_ls = any(isinstance(t, Separation) or (isinstance(t, Target) and t.kind != "r") for t in targets)
    r, top, bottom, nxt = {}, {}, {}, {}
    if need_r:
        cp = critical_points(part, arm, omega, model, x_max=x_max, xtol=xtol, n_grid=n_grid, limit=_NoLimit(), **opts)
        r, nxt = dict(cp.r), dict(cp.next_kind)
    if need_ls:
        lo = {"n_starts": 32, "rng": 0}
        lo.update(limit_options or {})
        ls = limit_set(part, arm, omega, model, x_max=x_max, **lo, **opts)
        top = {s: ls.u(s) for s in part.stable_sides}
        bottom = {s: ls.l(s) for s in part.stable_sides}
    wall = {}
    for t in targets:
        if isinstance(t, WallWindow):
            rr = [critical_points(part, arm, omega * f, model, x_max=x_max, xtol=xtol, n_grid=n_grid, limit=_NoLimit(),
                                  **opts).r for f in (1 - t.jitter, 1 + t.jitter)]
            wall[t.label] = t.width_of(part, rr[0], rr[1])
    res = {}
    for t in targets:
        if isinstance(t, WallWindow):
            S = wall[t.label]
            res[t.label] = max(0.0, t.width - S) if math.isfinite(S) else math.nan
        elif isinstance(t, Separation):
            res.update(t.residual(top))
        else:
            src = {"r": r, "top": top, "bottom": bottom}[t.kind]
            res[t.label] = src.get(t.side, math.nan) - t.value
    return Evaluation(r=r, top=top, bottom=bottom, residual=res, next_kind=nxt, wall=wall)

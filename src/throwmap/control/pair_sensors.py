"""One-bit sensors for two parts on the arm (paper Sec. VI: self-assembly of two triangles).

The draft's assembly switches from randomising to assembling throws when its camera sees the pair
"in the basin of attraction of the assembled state": part *a* resting on its intermediate-length
edge (the longer leg) wholly to the left of part *b*, which rests on its hypotenuse. The parts are
identical (same-handed), so either may play *a*.

* :func:`pair_ready` — that predicate on the parts' arm-frame poses (the truth a sensor reads);
* :func:`assembled_error` / :func:`is_assembled` — how far the pair is from the assembled rectangle
  of :func:`throwmap.statics.assembly.assembled_pair` (position of each CM, m; angle, rad), over both
  labellings;
* :class:`PairSensor` — the one-bit sensor: reads :func:`pair_ready` with a false-positive and a
  false-negative rate, independently at every read (a fresh look of the camera). Every read draws
  exactly one uniform, whatever the rates, so a trial's stream does not depend on them.

Sides are those of :func:`throwmap.triangle_30_60_90`: 0 the hypotenuse, 1 the longer leg, 2 the
shorter. Units: m, rad, arm frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, shown

__all__ = ["PairSensor", "pair_ready", "assembled_error", "is_assembled", "rectangle_error", "is_rectangle", "READY_TILT", "HYPOTENUSE", "LONG_LEG"]

READY_TILT = 0.02
"""rad: a part within this angle of a side rests flat on it (the engine's :data:`~throwmap.engine.rest.FLAT_TILT`)."""
HYPOTENUSE = 0
"""Side index of the hypotenuse of :func:`throwmap.triangle_30_60_90` (part *b* rests on it)."""
LONG_LEG = 1
"""Side index of the longer leg, the "intermediate-length edge" (part *a* rests on it)."""


def _wrap(a: float) -> float:
    return (a + math.pi) % (2.0 * math.pi) - math.pi


def pair_ready(part, poses, *, tilt: float = READY_TILT, side_a: int = LONG_LEG, side_b: int = HYPOTENUSE,
               a_min_x: float = 0.0):
    """``(i, j)`` (the indices playing *a* and *b*) when part *i* rests flat on ``side_a`` wholly left of part
    *j* flat on ``side_b`` (every vertex of *i* at smaller x than every vertex of *j*) and *i*'s CM is at
    least ``a_min_x`` (m) from the joint, else None. ``poses``: the two arm-frame poses ``(x, y, φ)``
    (m, m, rad)."""
    from ..system.pose import state_from_pose, world_vertices

    if len(poses) != 2:
        raise InvalidStateError("poses", f"a pair sensor looks at two parts, got {len(poses)}")
    st = [state_from_pose(part, q) for q in poses]
    xs = [world_vertices(part, q)[:, 0] for q in poses]
    for i, j in ((0, 1), (1, 0)):
        if (st[i][1] == side_a and st[j][1] == side_b and abs(st[i][2]) < tilt and abs(st[j][2]) < tilt
                and float(xs[i].max()) < float(xs[j].min()) and st[i][0] >= a_min_x):
            return i, j
    return None


def assembled_error(part, poses, *, length: float, h: float) -> tuple[float, float]:
    """``(position error, angle error)``: the larger CM distance (m) and the larger angle difference (rad)
    of the two parts from the assembled pair against the wall at x = ``length``, for the better labelling."""
    from ..statics.assembly import assembled_pair

    a, b = assembled_pair(part, length=length, h=h)
    best = (math.inf, math.inf)
    for i, j in ((0, 1), (1, 0)):
        d = max(math.hypot(poses[i][0] - a.x, poses[i][1] - a.y), math.hypot(poses[j][0] - b.x, poses[j][1] - b.y))
        e = max(abs(_wrap(poses[i][2] - a.phi)), abs(_wrap(poses[j][2] - b.phi)))
        if (d, e) < best:
            best = (d, e)
    return float(best[0]), float(best[1])


def rectangle_error(part, poses, *, h: float) -> tuple[float, float, float]:
    """``(position error, angle error, x of a)``: as :func:`assembled_error`, but of the assembled pair shifted
    along the arm to wherever *a* is (the rectangle formed away from the wall), for the better labelling."""
    from ..statics.assembly import assembled_pair

    a, b = assembled_pair(part, length=1.0, h=h)
    best = (math.inf, math.inf, math.nan)
    for i, j in ((0, 1), (1, 0)):
        dx = poses[i][0] - a.x
        d = max(abs(poses[i][1] - a.y), math.hypot(poses[j][0] - b.x - dx, poses[j][1] - b.y))
        e = max(abs(_wrap(poses[i][2] - a.phi)), abs(_wrap(poses[j][2] - b.phi)))
        if (d, e) < best[:2]:
            best = (d, e, poses[i][0])
    return float(best[0]), float(best[1]), float(best[2])


def is_rectangle(part, poses, *, h: float, pos_tol: float = 0.005, ang_tol: float = 0.05,
                 a_min_x: float = 0.0) -> bool:
    """The pair assembled anywhere on the arm (:func:`rectangle_error` within ``pos_tol``, ``ang_tol``), *a*'s
    CM at least ``a_min_x`` from the joint."""
    d, e, x = rectangle_error(part, poses, h=h)
    return d <= pos_tol and e <= ang_tol and x >= a_min_x


def is_assembled(part, poses, *, length: float, h: float, pos_tol: float = 0.005, ang_tol: float = 0.05) -> bool:
    """Both parts within ``pos_tol`` (m) and ``ang_tol`` (rad) of the assembled pair (:func:`assembled_error`)."""
    d, e = assembled_error(part, poses, length=length, h=h)
    return d <= pos_tol and e <= ang_tol


def _rate(value, field: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not math.isfinite(value) or not 0.0 <= value < 1.0:
        raise InvalidStateError(field, f"must be a probability in [0, 1), got {shown(value)}")
    return float(value)


@dataclass(frozen=True, slots=True)
class PairSensor:
    """The draft's one-bit "ready to assemble" sensor (:func:`pair_ready`) with error rates per read:
    ``false_positive`` P(reads 1 | not ready), ``false_negative`` P(reads 0 | ready); ``a_min_x`` (m) the
    least CM abscissa of *a* (:func:`pair_ready`); with ``rectangle_h`` (the arm's h, m) "ready" also when the
    pair is already a rectangle anywhere on the arm (:func:`is_rectangle`)."""

    false_positive: float = 0.0
    false_negative: float = 0.0
    a_min_x: float = 0.0
    rectangle_h: float | None = None

    def __post_init__(self):
        object.__setattr__(self, "false_positive", _rate(self.false_positive, "sensor.false_positive"))
        object.__setattr__(self, "false_negative", _rate(self.false_negative, "sensor.false_negative"))
        if isinstance(self.a_min_x, bool) or not isinstance(self.a_min_x, (int, float)) \
                or not math.isfinite(self.a_min_x) or self.a_min_x < 0:
            raise InvalidStateError("sensor.a_min_x", f"must be a finite length >= 0 m, got {shown(self.a_min_x)}")

    def truth(self, part, poses) -> bool:
        if pair_ready(part, poses, a_min_x=self.a_min_x) is not None:
            return True
        return self.rectangle_h is not None and is_rectangle(part, poses, h=self.rectangle_h, a_min_x=self.a_min_x)

    def read(self, part, poses, rng) -> bool:
        """One reading (draws one uniform from ``rng``)."""
        u = float(rng.random())
        if self.truth(part, poses):
            return u >= self.false_negative
        return u < self.false_positive

    def to_dict(self) -> dict:
        return {"kind": "pair_ready", "false_positive": self.false_positive, "false_negative": self.false_negative,
                "flat_within_rad": READY_TILT,
                "a_min_x_m": self.a_min_x, "or_rectangle": self.rectangle_h is not None}

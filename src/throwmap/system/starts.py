"""Where a part may start a throw: the arm's admissible rests and the rules that refuse a start.

One statement of each rule, used by every model, the dispatcher and the engines:
a rest has both support vertices on the arm (:func:`start_interval`, :func:`check_start`), a
finite ω ≥ 0 (:func:`check_omega`), does not reach into a wall (:func:`wall_start_reason`) and,
on a tilted arm, is at rest there (:func:`tilted_rest_reason`, draft Sec. VI).
"""

from __future__ import annotations

import math

from ..errors import InvalidStateError, shown, warn_scale
from .arm import Arm
from .part import Part

__all__ = ["check_omega", "check_start", "start_interval", "tilted_rest_reason", "wall_reach", "wall_start_reason"]


def _check_scalar(value, field: str) -> float:
    if isinstance(value, (bool, str, bytes)):
        raise InvalidStateError(field, f"must be a number, got {shown(value)}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InvalidStateError(field, f"must be a number, got {shown(value)}") from None
    if not math.isfinite(v):
        raise InvalidStateError(field, f"must be finite, got {v}")
    return v


def check_omega(omega, field: str = "omega") -> float:
    """A release rate ω (rad/s) as a float: a finite number ≥ 0 (the arm throws upward), else
    :class:`InvalidStateError` on ``field``."""
    w = _check_scalar(omega, field)
    if w < 0:
        raise InvalidStateError(field, f"must be ≥ 0 (the arm throws upward), got {w}")
    warn_scale(field, w, "omega")
    return w


def _last_at_most(u: float, bound: float) -> float:
    """The largest double ``x`` with ``x + u <= bound`` in floating point (``bound`` finite)."""
    x = bound - u
    while x + u > bound:
        x = math.nextafter(x, -math.inf)
    while math.nextafter(x, math.inf) + u <= bound:
        x = math.nextafter(x, math.inf)
    return x


def start_interval(part: Part, arm: Arm, side: int) -> tuple[float, float]:
    """The admissible starts (rests) on ``side``: ``x`` (m, CM) with ``lo < x <= hi``.

    The rule (docs/explanation/conventions.md; :func:`throwmap.engine.rest.rest_status` for the engines' rests):
    a part rests on the arm iff both support vertices are on it, −back < x + u_L and
    x + u_R ≤ length. ``lo`` is the largest double with ``lo + u_L ≤ −back`` and ``hi``
    the largest with ``hi + u_R ≤ length`` (``inf`` on an unbounded arm), so that
    ``lo < x <= hi`` holds exactly for the x that :func:`check_start` accepts. The
    interval is empty (``hi <= lo``) when the part is longer on this side than the arm.
    ``side`` must be a stable side (:meth:`Part.check_side`).
    """
    if not isinstance(part, Part):
        raise InvalidStateError("part", f"must be a Part (e.g. throwmap.triangle_30_60_90()), got {type(part).__name__}")
    if not isinstance(arm, Arm):
        raise InvalidStateError("arm", f"must be an Arm, got {type(arm).__name__}")
    k = part.check_side(side)
    lo = _last_at_most(float(part.uL[k]), -arm.back)
    hi = math.inf if arm.length is None else _last_at_most(float(part.uR[k]), float(arm.length))
    return lo, hi


def check_start(part: Part, arm: Arm, x: float, side: int, omega: float) -> tuple[float, int, float]:
    """Validate a throw's start; returns ``(x, side, omega)`` as Python scalars.

    Admissible: a stable side, finite ω ≥ 0 and both support vertices on the arm,
    −back < x + u_L and x + u_R ≤ length (:func:`start_interval`).
    """
    if not isinstance(part, Part):
        raise InvalidStateError("part", f"must be a Part (e.g. throwmap.triangle_30_60_90()), got {type(part).__name__}")
    if not isinstance(arm, Arm):
        raise InvalidStateError("arm", f"must be an Arm, got {type(arm).__name__}")
    k = part.check_side(side)
    x = _check_scalar(x, "x")
    warn_scale("x", x, "length")
    omega = check_omega(omega)
    if not x + float(part.uL[k]) > -arm.back:
        x_min = -float(part.uL[k]) - arm.back
        edge = "the joint" if arm.back == 0.0 else f"the arm's edge behind the joint (arm.back = {arm.back:g} m)"
        raise InvalidStateError(
            "x", f"the left support vertex is behind {edge}: on side {k} x must exceed {x_min:.6g} m, got {x:.6g}"
        )
    if arm.length is not None and not x + float(part.uR[k]) <= arm.length:
        x_max = float(arm.length) - float(part.uR[k])
        raise InvalidStateError(
            "x", f"the right support vertex is beyond the arm's end ({arm.length:g} m): on side {k} x must be "
                 f"≤ {x_max:.6g} m, got {x:.6g}"
        )
    return x, k, omega


def wall_reach(part: Part, side: int, height: float) -> float:
    """How far (m) the part resting flat on ``side`` reaches beyond its CM along the arm up to ``height`` above it.

    The largest x-offset from the CM of the part's outline clipped to y ≤ h + ``height`` (a vertex, or an edge
    crossing that height): a :class:`~throwmap.system.fixtures.Wall` of that height at the arm's end x = L
    overlaps the resting part iff x + reach > L (an outline that rises above the wall's top may overhang it).
    """
    pts = part.vertices_at_rest(0.0, side, 0.0)
    best = -math.inf
    n = len(pts)
    for j in range(n):
        (ax, ay), (bx, by) = pts[j], pts[(j + 1) % n]
        if ay <= height:
            best = max(best, ax)
        if (ay - height) * (by - height) < 0.0:
            best = max(best, ax + (height - ay) * (bx - ax) / (by - ay))
    return best


def wall_start_reason(part: Part, arm: Arm, side: int, x: float, fixtures) -> str:
    """Why the part resting at ``(x, side)`` cannot start there because it overlaps a wall; ``""`` if it does not.

    A start whose outline reaches into a :class:`~throwmap.system.fixtures.Wall` (beyond x = length below its top,
    :func:`wall_reach`, by more than 1e-9 m) is inadmissible: no model can throw a part that is inside a solid.
    """
    from .fixtures import Wall

    for f in fixtures:
        if isinstance(f, Wall) and arm.length is not None:
            reach = wall_reach(part, side, f.height)
            if x + reach > arm.length + 1e-9:
                return (f"the part at x = {x:.6g} m on side {side} reaches {x + reach - arm.length:.3g} m into the "
                        f"wall at length = {arm.length:.6g} m (below its top, {f.height:.3g} m): the start must have "
                        f"x ≤ {arm.length - reach:.6g} m")
    return ""


def tilted_rest_reason(part: Part, arm: Arm, side: int, alpha: float, friction: bool = True) -> str:
    """Why a part flat on ``side`` is NOT at rest on an arm resting at ``alpha`` (rad, CCW +); ``""`` if it is.

    Draft Sec. VI (the tilted arm), gravity (−g sin α, −g cos α) in the arm frame. A part
    flat on side k rests iff (a) it stands: the vertical through its CM meets the arm at
    −d_k tan α from the CM along the arm, strictly between the support vertices,
    u_L < −d_k tan α < u_R (else it tips over the vertex its CM overhangs), and (b)
    friction holds it: |tan α| ≤ μ (``Arm.mu``; checked only where the model uses
    friction, ``friction=True``; model "paper" assumes no slip). Independent of x.
    """
    k = part.check_side(side)
    if alpha == 0.0:
        return ""
    d, uL, uR = float(part.d[k]), float(part.uL[k]), float(part.uR[k])
    p = -d * math.tan(alpha)
    if not uL < p < uR:
        j = (k + 1) % part.n_sides if uL >= p else k
        return (f"tips over vertex {part.user_vertex(j)}: at α = {math.degrees(alpha):.4g}° the vertical through the "
                f"CM meets side {k} {100 * p:+.4g} cm from the CM, outside its support "
                f"[{100 * uL:+.4g}, {100 * uR:+.4g}] cm")
    if friction and abs(math.tan(alpha)) > arm.mu:
        return f"slides: |tan α| = {abs(math.tan(alpha)):.4g} > μ = {arm.mu:g} (α = {math.degrees(alpha):.4g}°)"
    return ""

"""Checks of a run between steps: penetration, clearance (for exact flight), escape, flips and settling.

* penetration: each part vertex is tested against the arm, fixtures and other
  parts; deeper than ``penetration_tol`` means pymunk lost the contact (it can
  lose grazing high-friction contacts: zero impulse, a vertex sinking
  millimetres into the arm) and the run's result is refused.
* clearance: a lower bound of the distance from a part to everything else,
  which bounds how long it may fly on the exact parabola (:mod:`.stepping`).
* escape: a part whose CM drops below the arm's underside has left the arm:
  ``behind_joint`` behind the joint's half of the arm, else ``off_end``.
* settling: every part slower than ``settle_speed`` and ``settle_spin``.
"""

from __future__ import annotations

import math

from ...throws.outcome import Status
from .world import World

__all__ = ["inspect", "clearance", "escape", "all_slow"]


def inspect(w: World, i: int, arm_angle: float, ca: float, sa: float):
    """Part i against the arm at ``arm_angle`` (rad; ``ca``, ``sa`` its cos and sin).

    Returns ``(depth, x, y, phi)``: the deepest penetration (m) of part i's
    vertices into the arm, fixtures or other parts, and its CM ``(x, y)`` (m)
    and angle ``phi`` (rad) in the arm frame (``phi`` unwrapped).
    """
    cp = w.cp
    b = w.bodies_h[i]
    a = cp.angle(b)
    p = cp.position(b)
    px, py = p.x, p.y
    deepest = 0.0
    if w.plain_arm:  # fast path: depth below the flat surface line, in the arm frame
        c, s = math.cos(a), math.sin(a)
        L, h = w.L, w.h
        for wx, wy in w.wlists[i]:
            X = px + c * wx - s * wy
            Y = py + s * wx + c * wy
            xa = ca * X + sa * Y
            if 0.0 <= xa <= L:
                d = h - (-sa * X + ca * Y)
                if d > deepest:
                    deepest = d
    else:
        distance, NULL, to_world = cp.distance, cp.NULL, cp.to_world
        others = w.others_h[i]
        for v in [to_world(b, v) for v in w.wlists[i]]:
            for s in others:
                d = distance(s, v, NULL)
                if d < -deepest:
                    deepest = -d
    return deepest, ca * px + sa * py, -sa * px + ca * py, a - arm_angle


def clearance(w: World, i: int) -> float:
    """Lower bound of the distance (m) from part i to every other shape."""
    cp = w.cp
    distance, NULL, to_world = cp.distance, cp.NULL, cp.to_world
    b = w.bodies_h[i]
    best = math.inf
    others = w.others_h[i]
    for v in [to_world(b, v) for v in w.wlists[i]]:
        for s in others:
            d = distance(s, v, NULL)
            if d < best:
                best = d
    aa = cp.angle(w.arm_h)
    ca, sa = math.cos(aa), math.sin(aa)
    shp = w.shapes_h[i]
    for cx, cy in w.corners:
        d = distance(shp, (ca * cx - sa * cy, sa * cx + ca * cy), NULL)
        if d < best:
            best = d
    for j in range(w.n):
        if j != i:
            bj = w.bodies_h[j]
            for v in [to_world(bj, v) for v in w.wlists[j]]:
                d = distance(shp, v, NULL)
                if d < best:
                    best = d
    return best


def escape(w: World, i: int, xa: float, ya: float, arm_thickness: float):
    """Status of part i if its CM ``(xa, ya)`` (m, arm frame) has left the arm, else None.

    Left: below the arm's underside (less 3 × the part's radius), or below its
    top beyond either end; ``behind_joint`` on the joint's half of the arm, else ``off_end``.
    """
    R, L, h = w.R[i], w.L, w.h
    if ya < h - arm_thickness - 3.0 * R or (ya < h and (xa < -R or xa > L + R)):
        return Status.BEHIND_JOINT if xa < 0.5 * L else Status.OFF_END
    return None


def all_slow(w: World, tracks, speed: float, spin: float) -> bool:
    """Every part still on the arm is slower than ``speed`` (m/s) and spins slower than ``spin`` (rad/s)."""
    cp = w.cp
    for b, tr in zip(w.bodies_h, tracks):
        if tr.fell is not None:
            continue
        v = cp.velocity(b)
        if not (math.hypot(v.x, v.y) < speed and abs(cp.spin(b)) < spin):
            return False
    return True

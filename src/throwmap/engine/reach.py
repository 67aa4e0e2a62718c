"""How long an engine makes an unbounded arm (``Arm.length`` None): long enough for the throw it simulates.

An engine needs a finite arm. For an unbounded arm both backends (pymunk, MuJoCo)
size it from a bound on where the throw can take a part (:func:`reach_bound`):
the farthest x the CM can reach in free flight from its release state (the
parabola in the arm frame, gravity resolved along and across the arm at its rest
angle α, until the CM is a part radius below the surface line, where every
vertex would be under it), plus a margin for the bounces and slides after the
landing (``margin``, m). A part that still reaches the simulated end is rerun on
a longer arm (:func:`lengths`: the margin × 4, × 16, …, up to the distance the
part could travel in ``t_max`` at the speed its energy allows); if it reaches
the end of the longest, the result is refused as ``unresolved`` with a message
that says so — never ``off_end``, which means leaving a real arm's end.
"""

from __future__ import annotations

import math

__all__ = ["EXTENSIONS", "GROWTH", "flight_reach", "lengths", "reach_bound", "travel_bound", "unbounded_message"]

GROWTH = 4.0
"""Factor by which the margin beyond the flight bound grows on each rerun."""
EXTENSIONS = 3
"""Reruns on a longer arm before a part that reaches the simulated end is refused."""


def flight_reach(x: float, y: float, vx: float, vy: float, g: float, h: float, radius: float, alpha: float = 0.0,
                 alpha_end: float | None = None, speed: float | None = None) -> tuple[float, float]:
    """``(x_far, v_max)``: the farthest arm-frame x (m) the CM reaches in free flight from ``(x, y)`` (m)
    and a bound on its speed (m/s) anywhere on the arm.

    Velocity ``(vx, vy)`` (m/s, arm frame); ``g`` (m/s²); ``h`` the surface line (m);
    ``radius`` the part's largest vertex distance from its CM (m: the flight ends
    before the CM is ``radius`` below the line). The arm's angle lies between
    ``alpha`` and ``alpha_end`` (rad; gravity along the arm −g sin α). With ``speed``
    (m/s) the direction is unknown: the bound holds for any velocity of that size.
    """
    alpha_end = alpha if alpha_end is None else alpha_end
    along = (-g * math.sin(alpha), -g * math.sin(alpha_end))  # acceleration along the arm, m/s²
    a_hi, a_lo = max(along), min(along)
    gn = max(g * min(math.cos(alpha), math.cos(alpha_end)), 1e-3 * g)  # least acceleration towards the surface
    drop = max(y - h, 0.0) + radius
    if speed is not None:  # any direction: as fast as possible outward, upward (longest flight) and inward
        vx = vy = speed
    t_end = (vy + math.sqrt(vy * vy + 2.0 * gn * drop)) / gn  # CM `radius` below the line: flight over

    def extreme(v, a, pick):  # the largest (pick=max) or smallest (min) of v t + a t²/2 over [0, t_end]
        best = pick(0.0, v * t_end + 0.5 * a * t_end * t_end)
        if a != 0.0 and 0.0 < -v / a < t_end:  # turning point inside the flight
            best = pick(best, -0.5 * v * v / a)
        return best

    far = x + extreme(vx, a_hi, max)
    near = x + (extreme(vx, a_lo, min) if speed is None else -(speed * t_end + 0.5 * abs(a_lo) * t_end * t_end))
    # energy: the CM falls at most `drop` across the arm and moves along it at most |Δx| against g |sin α|
    slope = max(abs(a_hi), abs(a_lo))
    v2 = speed * speed if speed is not None else vx * vx + vy * vy
    v_max = math.sqrt(v2 + 2.0 * g * drop + 2.0 * slope * max(far - x, x - near))
    return far, v_max


def travel_bound(x: float, v_max: float, g: float, alpha: float, alpha_end: float, t_max: float) -> float:
    """Farthest arm-frame x (m) a CM at ``x`` (m) can reach in ``t_max`` (s) at speed ``v_max`` (m/s),
    speeding up along an arm tilted down by at most its lowest angle (rad)."""
    a = max(-g * math.sin(alpha), -g * math.sin(alpha_end), 0.0)
    return x + v_max * t_max + 0.5 * a * t_max * t_max


def reach_bound(scene, realisation, margin: float, t_max: float) -> tuple[float, float]:
    """``(base, cap)`` for an unbounded arm: the flight bound over every part (:func:`flight_reach`), m,
    and the farthest x any part can get in ``t_max`` (s) at its speed bound plus ``margin`` (m)."""
    arm = scene.arm
    h, g = arm.h, arm.g
    alpha = scene.alpha
    alpha_end = alpha + getattr(realisation, "delta", 0.0)
    arm_rate = abs(getattr(realisation, "omega", 0.0)) + abs(getattr(realisation, "peak_rate", 0.0)) \
        + abs(getattr(realisation, "rate_", 0.0))
    base, cap = 0.0, 0.0
    for pl in scene.placements:
        part = pl.part
        R = float(max(math.hypot(wx, wy) for wx, wy in part.w.tolist()))
        x, y, _ = pl.arm_pose(h)
        vx, vy, _ = pl.velocity
        if getattr(realisation, "impulsive", False):  # ω × r of the arm point at the CM (Sec. III-B)
            w = getattr(realisation, "omega", 0.0)
            far, vmax = flight_reach(x, y, vx - w * y, vy + w * x, g, h, R, alpha, alpha_end)
        else:  # the arm moves for a while: only the speed is bounded
            speed = math.hypot(vx, vy) + arm_rate * (math.hypot(x, y) + R)
            far, vmax = flight_reach(x, y, vx, vy, g, h, R, alpha, alpha_end, speed=speed)
        base = max(base, far + R)
        cap = max(cap, travel_bound(x, vmax, g, alpha, alpha_end, t_max) + R)
    return max(base, 0.0), max(cap, base) + margin


def lengths(scene, realisation, margin: float, t_max: float) -> list[float]:
    """Simulated lengths (m) to try for ``scene``'s arm, shortest first: ``[arm.length]`` for a
    bounded arm, else the flight bound plus ``margin`` × 1, 4, 16, … (:data:`GROWTH`,
    :data:`EXTENSIONS` reruns), none beyond the travel cap of :func:`reach_bound`."""
    if scene.arm.length is not None:
        return [float(scene.arm.length)]
    base, cap = reach_bound(scene, realisation, margin, t_max)
    out = []
    for k in range(EXTENSIONS + 1):
        L = min(base + margin * GROWTH**k, cap)
        if out and L <= out[-1]:
            break
        out.append(L)
    return out


def unbounded_message(L: float, tried: list[float]) -> str:
    """Why a throw on an unbounded arm was refused: a part reached the end of the longest simulated arm."""
    shown = ", ".join(f"{v:.4g}" for v in tried)
    return (f"a part reached the end of the simulated arm at x = {L:.4g} m; the arm is unbounded "
            f"(Arm.length None) and the engine simulates it as a finite one (lengths tried: {shown} m): "
            f"result refused")

"""Advancing a run: exact ballistic leaps while every part is clear, fixed pymunk steps otherwise.

pymunk's symplectic Euler drifts by g·t·dt/2 in free flight. While every part
is clear of everything by more than ``flight_margin``, the parts are instead
moved along their exact parabolas, in leaps short enough that no vertex can
reach any shape: with ``v`` a bound on every vertex's speed relative to the
shapes and ``d`` the usable gap, the leap τ solves v τ + g τ² = d (the g term
bounds the speed gained during the leap). Near contacts, the space advances by
the fixed step ``dt``; the arm's kinematic body follows the realisation θ(t)
with the rate that takes it to θ(t + step) in one step.
"""

from __future__ import annotations

import math

from .interrupt import check as check_interrupt
from .world import World

__all__ = ["leap_length", "vertex_speed_bound", "leap", "fixed_steps"]


def leap_length(w: World, gap: float, vmax: float, margin: float) -> float:
    """Longest safe exact-flight leap (s) for clearance ``gap`` (m) and vertex speed bound ``vmax`` (m/s)."""
    usable = gap - 0.5 * margin
    g = w.g
    # vmax τ + g τ² ≤ usable (the g term bounds the speed gained during the leap)
    return 2.0 * usable / (vmax + math.sqrt(vmax * vmax + 4.0 * g * usable))


def vertex_speed_bound(w: World, tracks) -> float:
    """Largest CM speed plus spin × reach over the parts still on the arm, m/s."""
    if w.native is not None:
        return w.native.vertex_speed_bound()
    cp = w.cp
    vmax = 0.0
    for i, b in enumerate(w.bodies_h):
        if tracks[i].fell is None:
            v = cp.velocity(b)
            vmax = max(vmax, math.hypot(v.x, v.y) + abs(cp.spin(b)) * w.R[i])
    return vmax


def leap(w: World, tau: float, arm_angle: float):
    """Move every part along its exact parabola for ``tau`` (s); put the arm at ``arm_angle`` (rad), at rest."""
    w.arm_w = 0.0
    if w.native is not None:
        w.native.leap(tau, arm_angle)
        return
    cp, g = w.cp, w.g
    for b in w.bodies_h:
        p, v = cp.position(b), cp.velocity(b)
        px, py, vx, vy = p.x, p.y, v.x, v.y
        cp.set_position(b, (px + vx * tau, py + vy * tau - 0.5 * g * tau * tau))
        cp.set_velocity(b, (vx, vy - g * tau))
        cp.set_angle(b, cp.angle(b) + cp.spin(b) * tau)
    cp.set_angle(w.arm_h, arm_angle)
    cp.set_spin(w.arm_h, 0.0)
    w.space.reindex_shapes_for_body(w.arm)
    # and the parts' shapes: Chipmunk caches a shape's world vertices at each step, and the clearance measures the
    # arm's and the fixtures' corners and the other parts' vertices against them. Stale through a run of leaps, a
    # part was measured where its last step left it: two parts flying at each other passed into each other (a
    # vertex 3.6 mm deep, refused), and a wall's top corner passed 10.7 mm into a part flying over it (a wrong
    # ``ok``, 11 mm from the converged rest)
    for body in w.bodies:
        w.space.reindex_shapes_for_body(body)


def fixed_steps(w: World, contacts, t: float, n: int, step: float, angle, alpha: float, arm_stop: float,
                end_alpha: float) -> float:
    """Take ``n`` pymunk steps of ``step`` (s) from time ``t`` (s); return the new time.

    While t < ``arm_stop`` the arm follows α + θ(t) (``alpha``, rad; ``angle`` is θ, e.g.
    :func:`throwmap.system.motion.angle_function`); after it, it is parked at ``end_alpha`` once.
    θ(t + step) of one step is reused as θ(t) of the next (the same float: t advances by ``t += step``).
    First impacts get their post-impact record after the step they happened in.
    """
    cp = w.cp
    space_step, space_h, arm_h = cp.step, w.space_h, w.arm_h
    clock = contacts.clock  # (contacts.now, set once per step)
    arm_moving = t < arm_stop
    wa = w.arm_w  # the arm's rate as last set (kept here, stored back once)
    if not arm_moving and wa == 0.0:  # the arm is parked: only the space moves
        if w.native is not None:
            t = w.native.steps(contacts, t, n, step)
            check_interrupt()
            return t
        for _ in range(n):
            t_next = t + step
            clock.now = t_next
            space_step(space_h, step)
            t = t_next
            if contacts.need_post:
                contacts.record_post(step)
        check_interrupt()
        return t
    set_angle, set_spin = cp.set_angle, cp.set_spin
    a_next = None  # α + θ(t) for the current t, carried over from the previous step
    for _ in range(n):
        t_next = t + step
        if arm_moving:
            a_now = alpha + angle(t) if a_next is None else a_next
            a_next = alpha + angle(t_next)
            set_angle(arm_h, a_now)
            wa = (a_next - a_now) / step
            set_spin(arm_h, wa)
            arm_moving = t_next < arm_stop
        elif wa != 0.0:
            set_angle(arm_h, end_alpha)
            set_spin(arm_h, 0.0)
            wa = 0.0
        clock.now = t_next
        space_step(space_h, step)
        t = t_next
        if contacts.need_post:
            contacts.record_post(step)
    w.arm_w = wa
    check_interrupt()
    return t

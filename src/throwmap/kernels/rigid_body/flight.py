"""Mode FLIGHT of model "rigid_body": guards ``touch`` and ``leave_arm``, reset ``lift``.

Ballistic motion from an arbitrary state (paper Sec. III-B, Eqs. 1–3), with the
shared kernels of :mod:`~throwmap.kernels.flight`: reset ``release`` (Eq. 1) is
:func:`~throwmap.kernels.flight.release_state`, guard ``touch`` is
:func:`~throwmap.kernels.flight.first_contact` from the flight frame
(ru_j, rv_j) = R(φ0) w_j, c0_j = y0 − h + rv_j (:func:`flight_frame`).

On an arm at rest angle α (:mod:`~.tilt`) gravity in the arm frame is (−g_t, −g_n):
``touch`` sees the normal component g_n only (the gaps are normal distances), and
the CM's x gets −½ g_t t² (:func:`fly` with ``gt``).
"""

import math

from numba import njit

from .. import codes as C
from ..flight import SNAP, departure_window, first_contact, separating_window
from .trajectory import _put


@njit(cache=True)
def flight_frame(phi, y, h, w, ru, rv, c0, j_on):
    """Flight frame at orientation φ and CM height y: vertex offsets R(φ) w_j and gaps; vertex ``j_on`` is on the line."""
    cp = math.cos(phi)
    sp = math.sin(phi)
    for j in range(w.shape[0]):
        ru[j] = cp * w[j, 0] - sp * w[j, 1]
        rv[j] = sp * w[j, 0] + cp * w[j, 1]
        c0[j] = (y - h) + rv[j]
    c0[j_on] = 0.0


@njit(cache=True)
def refresh_frame(phi, y, h, w, ell, ru, rv, c0):
    """Flight frame at orientation φ and CM height y (m): offsets R(φ) w_j and arm gaps (tiny ones snapped to 0)."""
    cp = math.cos(phi)
    sp = math.sin(phi)
    for j in range(w.shape[0]):
        ru[j] = cp * w[j, 0] - sp * w[j, 1]
        rv[j] = sp * w[j, 0] + cp * w[j, 1]
        c = (y - h) + rv[j]
        c0[j] = 0.0 if abs(c) <= SNAP * ell[j] else c


@njit(cache=True)
def leave_arm(px, back, length):
    """Guard ``leave_arm`` for a contact at world x = ``px`` (m): BEHIND_JOINT (x ≤ −back, ``Arm.back``),
    OFF_END (x > length), else OK."""
    if px <= -back:
        return C.BEHIND_JOINT
    if px > length:
        return C.OFF_END
    return C.OK


@njit(cache=True)
def fly(t, x, y, vx, vy, phi, om, c0, ru, rv, g, ell, excl_j, excl_t, tol, max_iter, traj, ts, gt=0.0):
    """Mode FLIGHT until guard ``touch``; samples the trajectory on the way.

    Gravity (−gt, −g) in the arm frame (m/s²: ``g`` normal to the arm, ``gt`` along it,
    0 on a horizontal arm). ``excl_j`` (−1: none) is a vertex that just left the line,
    known to stay above it for ``excl_t`` s. Returns ``(j, t, x, y, v_y, φ, r_x, r_y, v_x)``
    at contact: vertex j (−1 if the search hit ``max_iter``; ``UNRESOLVED_J`` past the spin
    angle the search resolves), its offset (r_x, r_y) from the CM (m) and the CM's v_x.
    """
    tc, jc = first_contact(c0, ru, rv, vy, om, g, ell, excl_j, excl_t, tol, max_iter)
    if jc < 0:
        return jc, t, x, y, vy, phi, 0.0, 0.0, vx
    if traj.shape[0] > 0:
        while ts[1] <= t + tc:
            tq = ts[1] - t
            _put(traj, ts, ts[1], x + vx * tq - 0.5 * gt * tq * tq, y + vy * tq - 0.5 * g * tq * tq, phi + om * tq)
            ts[1] += ts[2]
    if gt != 0.0:
        x -= 0.5 * gt * tc * tc
        x += vx * tc
        vx -= gt * tc
    else:
        x += vx * tc
    y += vy * tc - 0.5 * g * tc * tc
    vy -= g * tc
    phi += om * tc
    t += tc
    cp = math.cos(om * tc)
    sp = math.sin(om * tc)
    rx = cp * ru[jc] - sp * rv[jc]
    ry = sp * ru[jc] + cp * rv[jc]
    if traj.shape[0] > 0:
        _put(traj, ts, t, x, y, phi)
    return jc, t, x, y, vy, phi, rx, ry, vx


@njit(cache=True)
def lift(px, h, lj, theta, thdot, va, phi, g, w, ru, rv, c0, jp):
    """Reset ``lift``: pivot vertex ``jp`` at (px, h) leaves the line (PIVOT_* → FLIGHT) with the contact's velocity.

    Fills the flight frame and returns ``(x, y, v_x, v_y, ω, excl_t)``: vertex jp is
    excluded from ``touch`` for ``excl_t`` s (:func:`~throwmap.kernels.flight.departure_window`); ``excl_t`` ≤ 0
    means the free motion would sink it (no consistent contact: INCONSISTENT).
    """
    c = math.cos(theta)
    s = math.sin(theta)
    x = px + lj * c
    y = h + lj * s
    vx = va - thdot * lj * s
    vy = thdot * lj * c
    rx = -lj * c
    excl_t = departure_window(rx, -lj * s, thdot, g, lj, g)  # leaves with normal rate v_y + θ̇ r_x = 0
    if excl_t > 0.0:
        flight_frame(phi, y, h, w, ru, rv, c0, jp)
    return x, y, vx, vy, thdot, excl_t


@njit(cache=True)
def rearm_window(y, vx, vy, phi, om, w, j, h, gn, gx, tol):
    """The exclusion window (s) of arm vertex ``j`` after an impact elsewhere (on the wall) changed the velocity.

    The window a vertex got when it left the arm holds for the free flight it was computed on; an impulse
    from the wall invalidates it. From the new state (CM height y, velocity (v_x, v_y), orientation φ,
    spin ω; SI): 0 when the vertex is more than ``tol`` (m) above the line (the flight's own touch search
    watches it), the departure or separating window when it is on the line and leaving, −1 when it is on
    the line and not leaving (the wall's impulse pressed it back: a second contact at the same instant)."""
    c = math.cos(phi)
    s = math.sin(phi)
    rx = c * w[j, 0] - s * w[j, 1]
    ry = s * w[j, 0] + c * w[j, 1]
    if y + ry - h > tol:
        return 0.0
    lj = math.hypot(rx, ry)
    un = vy + om * rx
    if un > 1e-12 * (abs(vx) + abs(vy) + abs(om) * lj):
        return separating_window(un, gn + abs(gx) + om * om * lj)
    win = departure_window(rx, ry, om, gn, lj, gn)
    return win if win > 0.0 else -1.0

"""WALL_CONTACT in the automaton: entering it, its sub-mode changes, and the events that end it.

:func:`wall_contact` follows a part whose vertex P is pressed on the wall's face
(:mod:`.wall_slide`) from the flight state right after the wall impact to the first event the
automaton continues from: P lets go (FLIGHT, P excluded from the wall guards for the exact
departure window :func:`~.wall_contact.wall_departure`), or another vertex A reaches the arm
(the automaton then applies the arm's impact, and where that alone would drive P into the wall,
the two-contact impact of :mod:`.wall_lean`).
"""

import math

import numpy as np
from numba import njit

from .modes import EV_INCONSISTENT, EV_LIFT_OFF, EV_SLIP, EV_STEP_CAP, EV_STICK
from .wall_contact import (WHY_CORNER, WHY_CORNER_VERTEX, WHY_NONE, WHY_WALL_EDGE, WHY_WALL_SLIDE, WHY_WALL_TOP,
                           corner_departure, wall_departure)
from .wall_corner import EV_CARM, EV_FACE, corner_phase, corner_select, edge_body
from .wall_guards import fill_wall_vertices
from .wall_slide import EV_ARM, EV_EDGE, EV_TOP, W_STICK, wall_phase, wall_select

WC_FLIGHT = 0
WC_ARM = 1
WC_REFUSE = 2
WC_INCONSISTENT = 3
WC_CAP = 4
WC_FACE = 5
"""Outcomes of :func:`wall_contact` and :func:`corner_contact` (WC_FACE: a vertex reached the face, corner only)."""


@njit(cache=True)
def wall_contact(j, t, x, y, vx, vy, phi, om, w, rho2, gx, gn, mu_w, h, top, L, arm_skip, arm_skip_until, max_steps,
                 max_events, wv, traj, ts, rec):
    """Mode WALL_CONTACT from the flight state (CM (x, y), velocity (v_x, v_y), φ, ω; SI) with vertex ``j``
    (body offsets ``w``) on the face x = ``L`` after a plastic impact.

    Sub-modes slide/stick (:func:`~.wall_slide.wall_select`, :func:`~.wall_slide.wall_phase`) until:
    ``lift_off`` (N = 0): FLIGHT, with the departure window of P; ``arm``: vertex k reaches the arm
    (WC_ARM, the caller applies the landing; k = j, P at the wall's foot, is refused: WHY_CORNER);
    ``top``: WHY_WALL_TOP; ``edge``: WHY_WALL_EDGE; Painlevé (D ≤ 0) or no consistent sub-mode:
    WC_INCONSISTENT; ``max_steps`` steps in one sub-mode or ``max_events`` sub-mode changes: WC_CAP.
    ``wv`` (n, 2) is scratch. Returns ``(outcome, k, t, x, y, v_x, v_y, φ, ω, r_x, r_y, window, why)``:
    the flight state at the event, (r_x, r_y) the CM → vertex k offset (WC_ARM), ``window`` (s) P's
    departure window (WC_FLIGHT), ``why`` the reason of WC_REFUSE.
    """
    cp = math.cos(phi)
    sp = math.sin(phi)
    rx = cp * w[j, 0] - sp * w[j, 1]
    ry = sp * w[j, 0] + cp * w[j, 1]
    lj = math.hypot(rx, ry)
    th = math.atan2(-ry, -rx)
    phi_off = phi - th
    yp = y + ry
    vp = vy + om * rx
    thd = om
    fill_wall_vertices(th, phi, w, j, wv)
    from_slip = False
    ev = EV_LIFT_OFF
    k = -1
    for _ in range(max_events):
        mode, sig = wall_select(th, thd, vp, lj, rho2, gx, gn, mu_w, from_slip)
        if mode == -2:
            return _out(WC_INCONSISTENT, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_NONE)
        if mode == -1:
            ev = EV_LIFT_OFF
            break
        ev, k, yp, th, vp, thd, t = wall_phase(yp, th, vp, thd, mode == W_STICK, sig, t, lj, rho2, gx, gn, mu_w, h,
                                               top, wv, arm_skip, arm_skip_until, L, phi_off, max_steps, traj, ts, rec)
        if ev == EV_STICK:
            from_slip = False
            continue
        if ev == EV_SLIP:
            from_slip = True
            continue
        break
    else:
        return _out(WC_CAP, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_NONE)
    if ev == EV_LIFT_OFF:
        c = math.cos(th)
        s = math.sin(th)
        win = wall_departure(0.0, -lj * c, -lj * s, thd, gx, -gn, lj)
        if win <= 0.0:  # N = 0 with no strict departure: a tangency this mode cannot resolve
            return _out(WC_REFUSE, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_WALL_SLIDE)
        return _out(WC_FLIGHT, -1, t, L, yp, th, vp, thd, lj, phi_off, w, win, WHY_NONE)
    if ev == EV_ARM:
        if k == j:
            return _out(WC_REFUSE, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_CORNER)
        return _out(WC_ARM, k, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_NONE)
    if ev == EV_TOP:
        return _out(WC_REFUSE, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_WALL_TOP)
    if ev == EV_EDGE:
        return _out(WC_REFUSE, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_WALL_EDGE)
    if ev == EV_INCONSISTENT:
        return _out(WC_INCONSISTENT, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_NONE)
    return _out(WC_CAP, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_NONE)  # EV_STEP_CAP


@njit(cache=True)
def _out(res, k, t, L, yp, th, vp, thd, lj, phi_off, w, win, why):
    """The flight state of P on the face at (y_P, θ, ẏ_P, θ̇), and vertex k's offset from the CM."""
    c = math.cos(th)
    s = math.sin(th)
    phi = th + phi_off
    rx = 0.0
    ry = 0.0
    if k >= 0:
        cp = math.cos(phi)
        sp = math.sin(phi)
        rx = cp * w[k, 0] - sp * w[k, 1]
        ry = sp * w[k, 0] + cp * w[k, 1]
    return (res, k, t, L + lj * c, yp + lj * s, -lj * s * thd, vp + lj * c * thd, phi, thd, rx, ry, win, why)


@njit(cache=True)
def corner_contact(e, t, x, y, vx, vy, phi, om, w, rho2, gx, gn, mu_w, h, top, L, arm_skip, arm_skip_until,
                   max_steps, max_events, traj, ts):
    """Mode CORNER (:mod:`.wall_corner`) from the flight state with edge ``e`` pressed on the wall's top corner after a
    plastic impact, until: ``lift_off`` (WC_FLIGHT, with the edge's departure window
    :func:`~.wall_contact.corner_departure`); a vertex k reaches the arm (WC_ARM) or the face below the top (WC_FACE);
    a vertex reaches the corner or the wall's top beyond the face (WHY_CORNER_VERTEX); Painlevé or no consistent
    sub-mode (WC_INCONSISTENT); the step or event caps (WC_CAP). Returns as :func:`wall_contact`.
    """
    s = np.array([x, y, phi, vx, vy, om])
    from_slip = False
    for _ in range(max_events):
        mode, sig = corner_select(s, e, w, rho2, gx, gn, mu_w, L, h, top, from_slip)
        if mode == -2:
            return _cout(WC_INCONSISTENT, -1, t, s, w, 0.0, WHY_NONE)
        if mode == -1:
            return _corner_lift(e, t, s, w, gx, gn, h, top, L)
        ev, k, s, t = corner_phase(s, e, mode == 1, sig, t, w, rho2, gx, gn, mu_w, h, L, top, arm_skip,
                                   arm_skip_until, max_steps, traj, ts)
        if ev == EV_STICK:
            from_slip = False
            continue
        if ev == EV_SLIP:
            from_slip = True
            continue
        if ev == EV_LIFT_OFF:
            return _corner_lift(e, t, s, w, gx, gn, h, top, L)
        if ev == EV_CARM:
            return _cout(WC_ARM, k, t, s, w, 0.0, WHY_NONE)
        if ev == EV_FACE:
            return _cout(WC_FACE, k, t, s, w, 0.0, WHY_NONE)
        if ev == EV_INCONSISTENT:
            return _cout(WC_INCONSISTENT, -1, t, s, w, 0.0, WHY_NONE)
        if ev == EV_STEP_CAP:
            return _cout(WC_CAP, -1, t, s, w, 0.0, WHY_NONE)
        return _cout(WC_REFUSE, -1, t, s, w, 0.0, WHY_CORNER_VERTEX)  # EV_END, EV_TOPS
    return _cout(WC_CAP, -1, t, s, w, 0.0, WHY_NONE)


@njit(cache=True)
def _cout(res, k, t, s, w, win, why):
    rx = 0.0
    ry = 0.0
    if k >= 0:
        c = math.cos(s[2])
        sn = math.sin(s[2])
        rx = c * w[k, 0] - sn * w[k, 1]
        ry = sn * w[k, 0] + c * w[k, 1]
    return (res, k, t, s[0], s[1], s[3], s[4], s[2], s[5], rx, ry, win, why)


@njit(cache=True)
def _corner_lift(e, t, s, w, gx, gn, h, top, L):
    """The edge lets go of the corner (λ = 0): FLIGHT with its departure window, or refused at a tangency, or
    refused (WHY_CORNER_VERTEX) when the CM is past the face: the part tips over the wall, whose top (its
    thickness) rigid_body does not model."""
    if s[0] >= L:
        return _cout(WC_REFUSE, -1, t, s, w, 0.0, WHY_CORNER_VERTEX)
    nx, ny, _tx, _ty, _le = edge_body(w, e)
    c = math.cos(s[2])
    sn = math.sin(s[2])
    win = corner_departure(L - s[0], h + top - s[1], s[3], s[4], s[5], gx, gn, c * nx - sn * ny, sn * nx + c * ny,
                           1.0)
    if win <= 0.0:
        return _cout(WC_REFUSE, -1, t, s, w, 0.0, WHY_WALL_SLIDE)
    return _cout(WC_FLIGHT, -1, t, s, w, win, WHY_NONE)


@njit(cache=True)
def follow(wj, ce, t, x, y, vx, vy, phi, om, w, rho2, gx, gn, mu_w, h, top, L, arm_skip, arm_skip_until, max_steps,
           max_events, wv, traj, ts, rec):
    """:func:`wall_contact` for face vertex ``wj`` ≥ 0, else :func:`corner_contact` for corner edge ``ce``."""
    if wj >= 0:
        return wall_contact(wj, t, x, y, vx, vy, phi, om, w, rho2, gx, gn, mu_w, h, top, L, arm_skip, arm_skip_until,
                            max_steps, max_events, wv, traj, ts, rec)
    return corner_contact(ce, t, x, y, vx, vy, phi, om, w, rho2, gx, gn, mu_w, h, top, L, arm_skip, arm_skip_until,
                          max_steps, max_events, traj, ts)

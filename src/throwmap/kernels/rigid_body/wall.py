"""A wall at the arm's end in model "rigid_body": its guards, resets and statics (issue 11, item 2).

The wall (:class:`throwmap.system.fixtures.Wall`) is the face x = L (the arm's
``length``, arm frame) from the arm surface y = h up to y = h + H; its normal
into the part is −x̂, its Coulomb coefficient μ_w (``inf``: no slip), and every
impact with it is plastic (zero restitution), as on the arm. Gravity is a
general vector (g_x, g_y) in the arm frame; an arm at rest angle α gives
(g_x, g_y) = (−g sin α, −g cos α) (α < 0 tilts the end down: g_x > 0 pushes the
part towards the wall). Unit mass, inertia ρ² about the CM, as the rest of the
automaton (:mod:`throwmap.kernels.rigid_body`).

Guards
------
``wall_touch``   FLIGHT: the earliest time a vertex reaches x = L moving outward
                 (:func:`wall_touch_time`, the lower-bound stepping of
                 :func:`throwmap.kernels.flight.touch_time` applied to the wall
                 gap; it cannot miss a crossing). A vertex crossing x = L above
                 the wall top has passed over it: an edge then meets the wall's
                 top corner, which is not modelled (refused, :data:`WHY_WALL_TOP`).
``wall_reach``   PIVOT_* about A = (p_x, h): every vertex above the line moves
                 outward as θ decreases, so the wall is a lower bound θ ≥ θ_w on the
                 pivot angle (:func:`wall_theta`, closed form); the swinging part
                 touches the wall when θ reaches θ_w.
``slide_hit``    FLAT_SLIDE at constant acceleration: the leading vertex reaches the
                 wall (:func:`slide_hit`, closed form).

Resets
------
``wall_impact``  one vertex against the wall: the impact law of the arm
                 (:func:`~.impact.coulomb_impact`: Eq. 4 inside the friction cone,
                 else Routh's process or the velocity-level law) in a frame turned by
                 −90° so that the wall's normal −x̂ is that law's normal ŷ
                 (:func:`wall_impact`). The normal velocity after it is 0.
``all_stop``     several contacts (arm vertices and wall vertices) at once: the part
                 stops if the impulse that removes its whole momentum is a sum of
                 impulses inside the contacts' friction cones
                 (:func:`cone_contains`, exact: Carathéodory's theorem, every basis of
                 ≤ 3 cone edges is tried).

Statics
-------
``rest_against_wall`` a part at rest touching the arm and the wall stays if gravity
                 is balanced by forces inside the contacts' cones (:func:`cone_contains`
                 with the gravity wrench), the same exact test.

Modules: :mod:`.wall_contact` (reason codes, the impact along any normal, departure windows),
:mod:`.wall_guards` (``wall_touch``, ``corner_touch``, ``wall_reach``), :mod:`.wall_statics`
(cone tests, the flat slide into the wall), :mod:`.wall_slide` / :mod:`.wall_corner` /
:mod:`.wall_ladder` (the modes WALL_CONTACT, CORNER, LADDER), :mod:`.wall_follow` and
:mod:`.wall_lean` (their entries and exits, the multi-contact impact); this module holds FLIGHT
with a wall and the impact of a flight on it, and re-exports the rest. A pivot that meets the
wall is resolved with one impact at both contacts (:func:`~.wall_lean.lean`).

What is still refused (status UNRESOLVED, reason code ``WHY_*``) is listed in
:data:`~.wall_contact.WHY_MESSAGES`.
"""

import math

from numba import njit

from ..flight import SNAP, first_contact
from .modes import IMP_INCONSISTENT
from .trajectory import _put
from .wall_contact import (CONE_TOL, EV_WALL, WHY_COL,
                           WHY_CORNER, WHY_LADDER, WHY_MESSAGES, WHY_NONE, WHY_SLIDE_WALL, WHY_TWO_CONTACT,
                           WHY_WALL_SLIDE, WHY_WALL_TOP, contact_impact, corner_departure, refuse, separating_window,
                           wall_departure,
                           wall_impact)
from .wall_guards import (_edge_frame, corner_inside, corner_touch_time, fill_wall_vertices, wall_contact_angle,
                          wall_theta, wall_touch_time)
from .wall_statics import (cone_contains, contacts_can_supply, corner_pivot_rate, flat_contacts, rest_flat_at_wall,
                           settle_walled, slide_hit, wall_reach_at_rest)

__all__ = ["CONE_TOL", "EV_WALL", "WHY_COL",
           "WHY_CORNER", "WHY_LADDER", "WHY_MESSAGES", "WHY_NONE", "WHY_SLIDE_WALL", "WHY_TWO_CONTACT",
           "WHY_WALL_SLIDE", "WHY_WALL_TOP", "cone_contains", "contact_impact", "contacts_can_supply",
           "corner_departure", "corner_inside", "corner_pivot_rate", "corner_touch_time", "fill_wall_vertices",
           "flat_contacts", "fly_walled", "nearest_side", "refresh_frame", "refuse",
           "rest_flat_at_wall", "settle_walled", "slide_hit", "wall_contact_angle", "wall_departure",
           "wall_hit_in_flight", "wall_impact", "wall_reach_at_rest", "wall_theta", "wall_touch_time"]


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
def fly_walled(t, x, y, vx, vy, phi, om, c0, ru, rv, gx, g, ell, excl_j, excl_t, wexcl_j, wexcl_t, cexcl_e, cexcl_t, L,
               top, h, tol, max_iter, cw, off, traj, ts):
    """Mode FLIGHT with a wall: until guard ``touch`` (the arm), ``wall_touch`` (the face) or ``corner_touch``
    (the top corner), whichever comes first.

    Gravity (g_x, −g) (m/s²; g the component normal to the arm, as
    :func:`~throwmap.kernels.flight.first_contact` takes it). The arm's vertex ``excl_j`` is
    excluded for ``excl_t`` s, the face's ``wexcl_j`` for ``wexcl_t`` s, the corner's edge ``cexcl_e``
    for ``cexcl_t`` s (all from now). A vertex that reaches the face's plane above the top
    (``top`` m above the line y = ``h``) passes over it and is marked in ``off`` (n,), no longer
    watched by the face. ``cw`` (n,) is scratch. Returns ``(where, j, t, x, y, v_x, v_y, φ, r_x, r_y,
    n_x, n_y)``: where = 0 the arm (vertex j), 1 the face (vertex j), 2 the corner (edge j), −1 the
    arm search failed (j its code, as :func:`fly`), −2 a wall search hit ``max_iter``; (r_x, r_y)
    the contact point's offset from the CM (m) and (n_x, n_y) the contact's normal into the part.
    """
    n = ru.shape[0]
    tc, jc = first_contact(c0, ru, rv, vy, om, g, ell, excl_j, excl_t, tol, max_iter)
    where = 0 if jc >= 0 else -1
    nx = 0.0
    ny = 1.0
    for j in range(n):
        cj = L - x - ru[j]
        cw[j] = 0.0 if abs(cj) <= SNAP * ell[j] else cj
    for _ in range(n + 1):
        tw, jw = wall_touch_time(cw, ru, rv, vx, om, gx, ell, wexcl_j, wexcl_t, tc, tol, max_iter, off)
        if jw == -3:
            return -2, jw, t, x, y, vx, vy, phi, 0.0, 0.0, 0.0, 0.0
        if jw < 0:
            break
        yj = y + vy * tw - 0.5 * g * tw * tw + math.sin(om * tw) * ru[jw] + math.cos(om * tw) * rv[jw]
        if yj - h < top:
            if tw < tc or jc < 0:
                where = 1
                jc = jw
                tc = tw
                nx = -1.0
                ny = 0.0
            break
        off[jw] = 1.0  # over the top: the corner guard watches its edges
    tq, eq = corner_touch_time(L - x, h + top - y, vx, vy, om, gx, g, ru, rv, cexcl_e, cexcl_t, tc, tol, max_iter)
    if eq == -3:
        return -2, eq, t, x, y, vx, vy, phi, 0.0, 0.0, 0.0, 0.0
    if eq >= 0 and (tq < tc or where == -1):
        where = 2
        jc = eq
        tc = tq
        nx0, ny0, _ce = _edge_frame(ru, rv, eq)
        nx = -(math.cos(om * tq) * nx0 - math.sin(om * tq) * ny0)
        ny = -(math.sin(om * tq) * nx0 + math.cos(om * tq) * ny0)
    if where == -1:
        return -1, jc, t, x, y, vx, vy, phi, 0.0, 0.0, 0.0, 0.0
    if traj.shape[0] > 0:
        while ts[1] <= t + tc:
            tq_ = ts[1] - t
            _put(traj, ts, ts[1], x + vx * tq_ + 0.5 * gx * tq_ * tq_, y + vy * tq_ - 0.5 * g * tq_ * tq_, phi + om * tq_)
            ts[1] += ts[2]
    if gx != 0.0:  # the same arithmetic as the plain arm's fly(): a flight that meets no wall is the same
        x += 0.5 * gx * tc * tc
        x += vx * tc
        vx += gx * tc
    else:
        x += vx * tc
    y += vy * tc - 0.5 * g * tc * tc
    vy -= g * tc
    phi += om * tc
    t += tc
    if where == 2:
        rx = L - x
        ry = h + top - y
    else:
        cp = math.cos(om * tc)
        sp = math.sin(om * tc)
        rx = cp * ru[jc] - sp * rv[jc]
        ry = sp * ru[jc] + cp * rv[jc]
    if traj.shape[0] > 0:
        _put(traj, ts, t, x, y, phi)
    return where, jc, t, x, y, vx, vy, phi, rx, ry, nx, ny


@njit(cache=True)
def wall_hit_in_flight(vx, vy, om, rx, ry, nx, ny, corner, rho2, mu_w, law, gx, g, lj):
    """Reset ``wall_impact`` in FLIGHT at the contact (r_x, r_y) from the CM (m) with normal (n_x, n_y) into the part:
    a vertex on the face (−x̂), or the top corner on an edge (``corner``: the edge's inward normal).

    Refuses (``why`` = :data:`WHY_WALL_SLIDE`) a contact the impact leaves pressed on the wall (no
    departure window: it would slide along it). Returns ``(vx⁺, vy⁺, ω⁺, P_t, P_n, kind, excl_t, why)``:
    ``excl_t`` (s) how long the contact provably stays open afterwards (:func:`wall_departure`,
    :func:`corner_departure`); kind IMP_INCONSISTENT: no consistent impulse.
    """
    vxp, vyp, wp, pt, pn, kind, _jt0, _jn0 = contact_impact(vx, vy, om, rx, ry, nx, ny, rho2, mu_w, law)
    if kind == IMP_INCONSISTENT:
        return vx, vy, om, 0.0, 0.0, kind, 0.0, WHY_NONE
    if corner:
        excl = corner_departure(rx, ry, vxp, vyp, wp, gx, g, -nx, -ny, 1.0)
    else:
        un = -(vxp - wp * ry)  # the wall gap's rate: 0 after a plastic impact (> 0 if it was leaving)
        vscale = max(1.0, abs(vxp) + abs(vyp) + abs(wp) * lj)
        excl = wall_departure(un if un > 0.0 else 0.0, rx, ry, wp, gx, -g, lj) if un <= 1e-12 * vscale else \
            separating_window(un, abs(gx) + wp * wp * lj)
    if excl <= 0.0:
        return vxp, vyp, wp, pt, pn, kind, 0.0, WHY_WALL_SLIDE
    return vxp, vyp, wp, pt, pn, kind, excl, WHY_NONE


@njit(cache=True)
def nearest_side(phi, beta):
    """The side whose rest orientation β_k is nearest to φ (rad), as the engines read a tilted rest."""
    best = 0
    dmin = math.inf
    for k in range(beta.shape[0]):
        dd = abs((phi - beta[k] + math.pi) % (2.0 * math.pi) - math.pi)
        if dd < dmin:
            dmin = dd
            best = k
    return best

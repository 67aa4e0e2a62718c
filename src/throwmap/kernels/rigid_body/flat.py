"""Modes FLAT_SLIDE and REST of model "rigid_body": a side flat on the arm slides, rests, leaves, or tips.

Flat on side k (CM at height d_k above the line, support vertices at u_L ≤ u_R from the CM along the
arm; paper Sec. III-C) the part rests (:func:`rest`: status OK, or BEHIND_JOINT / OFF_END if a support
vertex is off the arm, the rest rule of :func:`throwmap.system.starts.start_interval`), or, on an
unstable side, tips from rest over the vertex its CM overhangs (:func:`tip_from_rest`).

Horizontal arm: a flat slide decelerates at μ g and stops (:func:`flat_slide`, closed form; tipping
over the leading edge is not checked). Frictionless arm (μ = 0): no contact force has a horizontal
component, so the CM's horizontal velocity never changes; a part landing flat keeps sliding
(:func:`slide_away`: behind the joint inward, off the end outward, NO_REST outward on an unbounded arm).

Tilted arm (rest angle α, rad, CCW +; draft Sec. VI; gravity (−g sin α, −g cos α) in the arm frame):
a side is statically stable against tipping iff the line of gravity through the CM meets the support
segment inside, u_L < −d_k tan α < u_R (:func:`~.tilt.tilted_stable`; else it tips about the vertex its
CM overhangs, :func:`~.tilt.tip_vertex`), and is held by friction iff |tan α| ≤ μ. A flat slide
(:func:`settle`) moves at acceleration −g_t − μ g_n sgn v: it stops where it decelerates (then rests,
or slides downhill at once if |tan α| > μ), or runs down for ever: it leaves the arm behind the joint
(BEHIND_JOINT), off the end (OFF_END), or slides on for ever on an unbounded arm (NO_REST). As for
α = 0, tipping over the leading edge while sliding is not checked.

With a wall at the arm's end (:mod:`.wall`): a slide that reaches it (:func:`reaches_wall`) is followed
by :func:`settle_walled` (guard ``slide_hit``, closed form; the plastic impact at the wall stops the
part dead, turns it about the corner vertex, or hands an edge on the wall's top corner to
:mod:`.wall_lean`; a rest against the wall holds if :func:`~.wall_statics.rest_flat_at_wall`), any
other as without it, to the last bit (:func:`settle_at_wall`). A part that leans on the arm and the
wall reports the side nearest its orientation (:func:`nearest_side`), as the engines do.
"""

import math

import numpy as np
from numba import njit

from .. import codes as C
from ..roll import theta_a, theta_b
from .impact import record_impact
from .modes import MODE_LEAN, MODE_REST, MODE_SELECT, TWO_PI, WHY_LADDER, WHY_NONE, WHY_TWO_CONTACT, refuse
from .tilt import tip_vertex
from .trajectory import _put, _put_final
from .wall_statics import contacts_can_supply, flat_contacts, rest_flat_at_wall


@njit(cache=True)
def rest(x, k, t, h, g, d, uL, uR, beta, length, back, phi, traj, ts, rec):
    """Terminal mode REST flat on side k with the CM at x (m): status BEHIND_JOINT if the left support
    vertex is at x ≤ −back, OFF_END if the right one is beyond ``length`` (x + u_R > length), else OK
    (the rest rule of :func:`throwmap.system.starts.start_interval`)."""
    rec[C.E_FINAL] = g * d[k]
    rec[C.T_REST] = t
    m = round((phi - beta[k]) / TWO_PI)
    _put_final(traj, ts, t, x, h + d[k], beta[k] + TWO_PI * m)
    if x + uL[k] <= -back:
        return x, k, C.BEHIND_JOINT
    if x + uR[k] > length:
        return x, k, C.OFF_END
    return x, k, C.OK


@njit(cache=True)
def flat_slide(x_cm, vx, t, mu, g, y, phi, traj, ts, rec):
    """Mode FLAT_SLIDE: a side flat on the line slides from speed ``vx`` (m/s) at deceleration μ g to rest.

    Closed form (tipping over the leading edge is not checked). Returns ``(x_cm, t)`` at rest.
    """
    rec[C.N_SLIPS] += 1.0
    sgn = 1.0 if vx > 0.0 else -1.0
    dec = mu * g
    t_slide = abs(vx) / dec
    dist = 0.5 * vx * vx / dec
    if traj.shape[0] > 0:
        while ts[1] <= t + t_slide:
            tq = ts[1] - t
            _put(traj, ts, ts[1], x_cm + vx * tq - 0.5 * sgn * dec * tq * tq, y, phi)
            ts[1] += ts[2]
    rec[C.SLIP_DISTANCE] += dist
    return x_cm + sgn * dist, t + t_slide


@njit(cache=True)
def slide_away(x_cm, vx, t, k, uL, uR, length, back, y, phi, traj, ts, rec):
    """Mode FLAT_SLIDE on a frictionless arm (μ = 0): flat on side k at speed ``vx`` ≠ 0 (m/s), for ever.

    Moving inward it reaches the arm's edge behind the joint (left support vertex at
    x = −back): BEHIND_JOINT; outward it passes the arm's end: OFF_END; on an unbounded
    arm it never comes to rest: NO_REST (CM where the slide began). Returns ``(x, status, t)``
    with the CM x (m) and time (s) at the edge.
    """
    rec[C.N_SLIPS] += 1.0
    if vx < 0.0:
        x_end = -back - uL[k]
        status = C.BEHIND_JOINT
    elif length < math.inf:
        x_end = length - uR[k]
        status = C.OFF_END
    else:
        return x_cm, C.NO_REST, t
    dist = abs(x_end - x_cm)
    t_end = t + dist / abs(vx)
    rec[C.SLIP_DISTANCE] += dist
    if traj.shape[0] > 0:
        while ts[1] <= t_end:
            _put(traj, ts, ts[1], x_cm + vx * (ts[1] - t), y, phi)
            ts[1] += ts[2]
        _put_final(traj, ts, t_end, x_end, y, phi)
    return x_end, status, t_end


@njit(cache=True)
def tip_from_rest(k, x_cm, n, d, uL, uR, alpha=0.0):
    """Flat on an unstable side k: the pivot the part tips over from rest (the vertex its CM overhangs).

    On an arm at rest angle ``alpha`` the CM overhangs along gravity
    (:func:`~.tilt.tip_vertex`). Returns ``(j, x_j, θ)``: the pivot vertex, its
    world x (m) and the angle of pivot→CM.
    """
    left = uL[k] >= 0.0
    if alpha != 0.0:
        left = tip_vertex(k, n, uL, d, alpha)
    if left:
        j = (k + 1) % n
        return j, x_cm + uL[k], theta_a(j, n, d, uL)
    return k, x_cm + uR[k], theta_b(k, d, uR)


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


@njit(cache=True)
def _edge(direction, k, uL, uR, length, back):
    """The CM x (m) at which a part flat on side k sliding in ``direction`` leaves the arm, and the status."""
    if direction < 0.0:
        return -back - uL[k], C.BEHIND_JOINT
    if length < math.inf:
        return length - uR[k], C.OFF_END
    return math.inf, C.NO_REST


@njit(cache=True)
def _slide_rows(x0, v0, a, t0, t1, y, phi, traj, ts):
    while ts[1] <= t1:
        tq = ts[1] - t0
        _put(traj, ts, ts[1], x0 + v0 * tq + 0.5 * a * tq * tq, y, phi)
        ts[1] += ts[2]


@njit(cache=True)
def settle(x, v, t, k, mu, g, alpha, h, d, uL, uR, beta, length, back, phi, traj, ts, rec):
    """Flat on side k (statically stable), the CM at x moving at v (m/s) along a tilted arm: slide, then rest or leave.

    Mode FLAT_SLIDE under gravity (−g sin α, −g cos α): acceleration −g_t − μ g_n sgn v
    while sliding. A slide that decelerates stops after |v|/|a|; a part at rest stays
    iff |tan α| ≤ μ, else it slides downhill at g_t ∓ μ g_n for ever. Leaving the arm:
    the left support vertex at x ≤ −back (BEHIND_JOINT) or the right one beyond the
    length (OFF_END); on an unbounded arm an outward slide for ever is NO_REST (CM where
    the endless slide began). Returns ``(x, side, status, t)``.
    """
    gt = g * math.sin(alpha)
    gn = g * math.cos(alpha)
    fr = mu * gn  # largest friction deceleration
    y = h + d[k]
    sample = traj.shape[0] > 0
    slid = False
    for _ in range(2):
        if v != 0.0:
            slid = True
            sv = 1.0 if v > 0.0 else -1.0
            a = -gt - fr * sv
            if a * sv < 0.0:  # decelerates: stops after |v|/|a| unless it leaves the arm first
                t_stop = -v / a
                x_stop = x - 0.5 * v * v / a
                x_edge, st_edge = _edge(sv, k, uL, uR, length, back)
                past = (x_stop + uL[k] <= -back) if sv < 0.0 else (x_stop + uR[k] > length)
                if past:
                    dist = abs(x_edge - x)
                    disc = v * v + 2.0 * a * (x_edge - x)
                    t_e = (-v + sv * math.sqrt(disc if disc > 0.0 else 0.0)) / a if a != 0.0 else dist / abs(v)
                    if sample:
                        _slide_rows(x, v, a, t, t + t_e, y, phi, traj, ts)
                        _put_final(traj, ts, t + t_e, x_edge, y, phi)
                    rec[C.SLIP_DISTANCE] += dist
                    rec[C.N_SLIPS] += 1.0
                    return x_edge, k, st_edge, t + t_e
                if sample:
                    _slide_rows(x, v, a, t, t + t_stop, y, phi, traj, ts)
                rec[C.SLIP_DISTANCE] += abs(x_stop - x)
                x = x_stop
                t += t_stop
                v = 0.0
                continue
            # accelerates (or keeps its speed) for ever: leaves the arm in the sense of v
            x_edge, st_edge = _edge(sv, k, uL, uR, length, back)
            rec[C.N_SLIPS] += 1.0
            if st_edge == C.NO_REST:
                return x, k, C.NO_REST, t
            dist = abs(x_edge - x)
            disc = v * v + 2.0 * a * (x_edge - x)
            t_e = (-v + sv * math.sqrt(disc if disc > 0.0 else 0.0)) / a if a != 0.0 else dist / abs(v)
            if sample:
                _slide_rows(x, v, a, t, t + t_e, y, phi, traj, ts)
                _put_final(traj, ts, t + t_e, x_edge, y, phi)
            rec[C.SLIP_DISTANCE] += dist
            return x_edge, k, st_edge, t + t_e
        # at rest: does friction hold it?
        if abs(gt) <= fr:
            if slid:
                rec[C.N_SLIPS] += 1.0
            rec[C.E_FINAL] = gn * d[k] + gt * x
            rec[C.T_REST] = t
            m = round((phi - beta[k]) / TWO_PI)
            _put_final(traj, ts, t, x, y, beta[k] + TWO_PI * m)
            if x + uL[k] <= -back:
                return x, k, C.BEHIND_JOINT, t
            if x + uR[k] > length:
                return x, k, C.OFF_END, t
            return x, k, C.OK, t
        # slides downhill from rest, for ever
        sv = -1.0 if gt > 0.0 else 1.0
        a = -gt + fr * (1.0 if gt > 0.0 else -1.0)
        x_edge, st_edge = _edge(sv, k, uL, uR, length, back)
        rec[C.N_SLIPS] += 1.0
        if st_edge == C.NO_REST:
            return x, k, C.NO_REST, t
        dist = abs(x_edge - x)
        t_e = math.sqrt(2.0 * dist / abs(a))
        if sample:
            _slide_rows(x, 0.0, a, t, t + t_e, y, phi, traj, ts)
            _put_final(traj, ts, t + t_e, x_edge, y, phi)
        rec[C.SLIP_DISTANCE] += dist
        return x_edge, k, st_edge, t + t_e
    return x, k, C.NO_REST, t  # not reached


@njit(cache=True)
def slide_hit(v, a, gap):
    """Guard ``slide_hit``: a flat slide at speed ``v`` > 0 (m/s, towards the wall) with constant
    acceleration ``a`` (m/s²) and ``gap`` (m) between its leading vertex and the wall.

    Returns ``(hit, t, v_hit)``: whether it reaches the wall, when (s) and how fast (m/s);
    without a hit ``t`` is the time it stops (a < 0) and v_hit = 0.
    """
    if gap <= 0.0:
        return True, 0.0, v
    disc = v * v + 2.0 * a * gap
    if disc < 0.0:
        return False, -v / a, 0.0
    vh = math.sqrt(disc)
    if a == 0.0:
        return True, gap / v, v
    return True, 2.0 * gap / (v + vh), vh


@njit(cache=True)
def wall_reach_at_rest(u, vh, top):
    """The leading vertex of a part flat on a side sliding towards the wall.

    ``u`` the vertices' x offsets from the CM (m), ``vh`` their heights above the arm line (m),
    ``top`` the wall's height (m). Returns ``(u_w, j_w, above)``: the largest offset, its vertex,
    and whether that vertex is above the wall's top (it would pass over the wall: an edge then
    meets the top corner).
    """
    jb = 0
    for j in range(u.shape[0]):
        if u[j] > u[jb]:
            jb = j
    umax = u[jb]
    tie = 1e-12 * (abs(umax) + abs(vh[jb]))
    for j in range(u.shape[0]):  # a flush (vertical) leading side: its lowest vertex meets the wall
        if u[j] >= umax - tie and vh[j] < vh[jb]:
            jb = j
    return umax, jb, vh[jb] >= top


@njit(cache=True)
def reach_below(u, vh, top):
    """The outline's largest x offset from the CM (m) at heights ≤ ``top`` above the arm: a vertex that low, or an
    edge crossing that height (vertex offsets ``u``, heights ``vh``, in order around the part)."""
    n = u.shape[0]
    best = -math.inf
    for j in range(n):
        j2 = (j + 1) % n
        if vh[j] <= top:
            best = max(best, u[j])
        if (vh[j] - top) * (vh[j2] - top) < 0.0:
            best = max(best, u[j] + (top - vh[j]) * (u[j2] - u[j]) / (vh[j2] - vh[j]))
    return best


@njit(cache=True)
def flat_offsets(k, w, beta):
    """Vertex offsets (u_j, v_j) from the CM (m) of a part flat on side k."""
    cb = math.cos(beta[k])
    sb = math.sin(beta[k])
    n = w.shape[0]
    u = np.empty(n)
    v = np.empty(n)
    for j in range(n):
        u[j] = cb * w[j, 0] - sb * w[j, 1]
        v[j] = sb * w[j, 0] + cb * w[j, 1]
    return u, v


@njit(cache=True)
def corner_pivot_rate(v, u_r, d, rho2):
    """Spin (rad/s) just after a part sliding flat at ``v`` (m/s) hits the wall with its right support vertex.

    That vertex sits in the corner of arm and wall (offset (u_R, −d) from the CM, m) and stops;
    the part turns about it, conserving angular momentum about it: ω⁺ = −d v/(ρ² + u_R² + d²)
    (clockwise for v > 0: it tips towards the wall).
    """
    return -d * v / (rho2 + u_r * u_r + d * d)


@njit(cache=True)
def reaches_wall(x, v, gx, fr, x_wall):
    """Whether a part flat on a side, CM at x (m) moving at v (m/s), ever gets its leading vertex to the wall (CM at
    ``x_wall``, m) under acceleration g_x − fr sgn v while sliding (fr = μ g_n: friction's largest deceleration)."""
    if x >= x_wall:
        return True
    if v > 0.0:
        a = gx - fr
        if a >= 0.0:
            return True
        if x - 0.5 * v * v / a >= x_wall:
            return True
        return gx > fr  # stopped short: slides on outward only if downhill beats friction
    if v < 0.0 and gx + fr <= 0.0:
        return False  # runs inward for ever: leaves behind the joint
    return gx > fr


@njit(cache=True)
def settle_at_wall(x_cm, v, t, k, phi, last_side, h, g, alpha, length, back, rho2, mu, w, beta, d, uL, uR, wall_h,
                   wall_mu, traj, ts, rec):
    """Flat on side k moving at v (m/s) on an arm with a wall, as ``land_side`` returns it: at rest or gone
    (MODE_REST), refused (MODE_REST, UNRESOLVED), or turning about the corner vertex k at (length, h) (MODE_SELECT).

    A slide that never reaches the wall (:func:`reaches_wall`) is the plain arm's (:func:`flat_slide` and
    :func:`rest`, or :func:`settle`), to the last bit; one that does is :func:`settle_walled`."""
    dk = d[k]
    gx = -g * math.sin(alpha)
    gn = g * math.cos(alpha)
    u, _v = flat_offsets(k, w, beta)
    if not reaches_wall(x_cm, v, gx, mu * gn, length - u.max()):
        if alpha != 0.0:
            x, k, status, t = settle(x_cm, v, t, k, mu, g, alpha, h, d, uL, uR, beta, length, back, phi, traj, ts,
                                     rec)
        elif v != 0.0 and mu == 0.0:  # frictionless, inward (outward reaches the wall)
            x, status, t = slide_away(x_cm, v, t, k, uL, uR, length, back, h + dk, phi, traj, ts, rec)
        else:
            if v != 0.0:
                x_cm, t = flat_slide(x_cm, v, t, mu, g, h + dk, phi, traj, ts, rec)
            x, k, status = rest(x_cm, k, t, h, g, d, uL, uR, beta, length, back, phi, traj, ts, rec)
        return MODE_REST, status, x, h + dk, 0.0, 0.0, 0.0, phi, t, k, length, 0.0, 0.0, 0.0, 0.0, -1, 0.0, last_side
    st, x, t, wc, why = settle_walled(x_cm, v, t, k, mu, gx, gn, h, length, wall_h, wall_mu, back, rho2, w, beta, d,
                                      uL, uR, phi, traj, ts, rec)
    if st == -2:  # an edge met the wall's top corner (wc: the speed then): the multi-contact impact of wall_lean
        return MODE_LEAN, C.OK, x, h + dk, wc, 0.0, 0.0, phi, t, k, length, 0.0, 0.0, 0.0, 0.0, -1, 0.0, last_side
    if st == -1:
        th = theta_b(k, d, uR)
        return (MODE_SELECT, C.OK, x, h + dk, 0.0, 0.0, wc, phi, t, k, length, th, wc, 0.0, phi - th, -1, 0.0,
                last_side)
    if st == C.UNRESOLVED:
        refuse(rec, why)
    return MODE_REST, st, x, h + dk, 0.0, 0.0, 0.0, phi, t, k, length, 0.0, 0.0, 0.0, 0.0, -1, 0.0, last_side


@njit(cache=True)
def settle_walled(x, v, t, k, mu, gx, gn, h, L, top, mu_w, back, rho2, w, beta, d, uL, uR, phi, traj, ts, rec):
    """Mode FLAT_SLIDE on side k with a wall at x = L: slide, then rest, hit the wall, or leave behind the joint.

    The CM at x (m) moves at v (m/s) with acceleration g_x − μ g_n sgn v while sliding (g_x
    gravity along the arm, g_n > 0 normal to it; μ = 0 slides on until something stops it).
    Stopped away from the wall it rests if |g_x| ≤ μ g_n, else slides downhill. Outward, the
    leading vertex (:func:`wall_reach_at_rest`) reaches the wall with the CM at x = L − u_w
    (:func:`slide_hit`); the plastic impact there stops the part if the impulse lies in the
    contacts' cones (the arm at both support vertices, the wall at the leading vertices: a
    flush side stops dead); a part whose only wall contact is its right support vertex turns
    about that corner instead (:func:`corner_pivot_rate`); anything else is refused
    (:data:`~.modes.WHY_TWO_CONTACT`); a leading vertex above the wall's top hands over to :mod:`.wall_lean`
    where its edge meets the top corner. At rest against the wall it stays if arm and wall hold gravity
    (:func:`~.wall_statics.rest_flat_at_wall`): x = L − u_w (rounded down where needed so that x + u_R ≤ L, the start
    rule of :func:`throwmap.system.starts.start_interval`); pulled away it slides back; pushed
    into the wall and not held it is refused (:data:`~.modes.WHY_LADDER`).

    Returns ``(status, x, t, ω_corner, why)``: status OK or BEHIND_JOINT (at rest or leaving
    behind the joint, x the CM), −1: the part turns about its corner vertex k at (L, h) with
    spin ω_corner (rad/s), −2: an edge meets the wall's top corner (a leading vertex above the top:
    the outline's reach below the top, :func:`reach_below`, touches it), the CM at x moving at
    ω_corner (m/s) — :mod:`.wall_lean`'s impact decides — UNRESOLVED with ``why``.
    """
    n = w.shape[0]
    u, vv = flat_offsets(k, w, beta)
    dk = d[k]
    u_w, _j_w, above = wall_reach_at_rest(u, vv + dk, top)
    if above:  # the leading vertex passes over the wall: an edge meets its top corner when the outline's reach
        u_w = reach_below(u, vv + dk, top)  # below the top does
    jl = (k + 1) % n
    jr = k
    fr = mu * gn
    lref = math.sqrt(rho2) + dk
    x_wall = L - u_w
    while x_wall + uR[k] > L:  # resting against the wall is a start throw() accepts: x + u_R ≤ L in floating point
        x_wall = np.nextafter(x_wall, -math.inf)
    y = h + dk
    sample = traj.shape[0] > 0
    for _ in range(8):
        if v == 0.0:
            if x >= x_wall - 1e-12 * (abs(L) + lref):  # against the wall
                x = x_wall
                if above:  # at rest on an edge against the top corner: the contacts of wall_lean decide
                    return -2, x, t, 0.0, WHY_NONE
                if rest_flat_at_wall(u, vv, jl, jr, u_w, top - dk, mu, mu_w, gx, -gn, lref):
                    return _rest_walled(x, k, t, gx, gn, dk, y, phi, beta, uL, back, traj, ts, rec)
                if gx >= 0.0:
                    return C.UNRESOLVED, x, t, 0.0, WHY_LADDER
            elif abs(gx) <= fr:
                return _rest_walled(x, k, t, gx, gn, dk, y, phi, beta, uL, back, traj, ts, rec)
            sv = 1.0 if gx > 0.0 else -1.0  # slides downhill from rest
        else:
            sv = 1.0 if v > 0.0 else -1.0
        a = gx - fr * sv
        rec[C.N_SLIPS] += 1.0
        if sv > 0.0:
            hit, th, vh = slide_hit(v, a, x_wall - x)
            if not hit:  # stops short of the wall
                x_stop = x - 0.5 * v * v / a
                if sample:
                    _slide_rows(x, v, a, t, t + th, y, phi, traj, ts)
                rec[C.SLIP_DISTANCE] += x_stop - x
                x = x_stop
                t += th
                v = 0.0
                continue
            if sample:
                _slide_rows(x, v, a, t, t + th, y, phi, traj, ts)
            rec[C.SLIP_DISTANCE] += x_wall - x
            t += th
            x = x_wall
            if above:  # an edge meets the wall's top corner at speed vh: the multi-contact impact of wall_lean
                return -2, x, t, vh, WHY_NONE
            pts = np.empty((4, 2))
            nrm = np.empty((4, 2))
            mus = np.empty(4)
            m, nw = flat_contacts(u, vv, jl, jr, mu, mu_w, top - dk, u_w, 1e-9 * lref, pts, nrm, mus)
            k_before = 0.5 * vh * vh
            if contacts_can_supply(pts, nrm, mus, m, -vh, 0.0, 0.0, lref):
                record_impact(0.0, vh, k_before, 0.0, rec)
                v = 0.0
                continue
            if nw == 1 and u_w - u[jr] <= 1e-9 * lref:
                wp = corner_pivot_rate(vh, u[jr], dk, rho2)
                l2 = u[jr] * u[jr] + dk * dk
                record_impact(-wp * dk - vh, -wp * u[jr], k_before, 0.5 * (rho2 + l2) * wp * wp, rec)
                return -1, x, t, wp, WHY_NONE
            return C.UNRESOLVED, x, t, 0.0, WHY_TWO_CONTACT
        # inward
        if a > 0.0 and v < 0.0:  # decelerates: stops unless it leaves behind the joint first
            x_stop = x - 0.5 * v * v / a
            if x_stop + uL[k] > -back:
                t_stop = -v / a
                if sample:
                    _slide_rows(x, v, a, t, t + t_stop, y, phi, traj, ts)
                rec[C.SLIP_DISTANCE] += x - x_stop
                x = x_stop
                t += t_stop
                v = 0.0
                continue
        x_edge = -back - uL[k]
        dist = x - x_edge
        if a != 0.0:
            disc = v * v - 2.0 * a * dist
            t_e = (-v - math.sqrt(disc if disc > 0.0 else 0.0)) / a
        else:
            t_e = dist / abs(v)
        if sample:
            _slide_rows(x, v, a, t, t + t_e, y, phi, traj, ts)
            _put_final(traj, ts, t + t_e, x_edge, y, phi)
        rec[C.SLIP_DISTANCE] += dist
        return C.BEHIND_JOINT, x_edge, t + t_e, 0.0, WHY_NONE
    return C.UNRESOLVED, x, t, 0.0, WHY_LADDER


@njit(cache=True)
def _rest_walled(x, k, t, gx, gn, dk, y, phi, beta, uL, back, traj, ts, rec):
    rec[C.E_FINAL] = gn * dk - gx * x
    rec[C.T_REST] = t
    m = round((phi - beta[k]) / (2.0 * math.pi))
    _put_final(traj, ts, t, x, y, beta[k] + 2.0 * math.pi * m)
    if x + uL[k] <= -back:
        return C.BEHIND_JOINT, x, t, 0.0, WHY_NONE
    return C.OK, x, t, 0.0, WHY_NONE

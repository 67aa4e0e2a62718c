"""Mode LEAN of model "rigid_body": a part touching the arm and the wall's face at once, and its LADDER.

:func:`lean` takes the part from the moment a vertex A on the arm and a vertex P on the face
touch together (a landing while P slides on the face, a swinging pivot that meets the face) to the
first state the automaton continues from. In order: the plastic impact at every touching vertex
(:func:`~.impact.multi_contact_impact`, velocity-level); then, with the contacts it leaves
closed (:func:`_dispatch`): one arm vertex and one face vertex moving — LADDER
(:func:`ladder_phase`); only one arm vertex — a pivot (the automaton's PIVOT modes);
only one face vertex — WALL_CONTACT (:mod:`.wall_slide`); only an edge on the wall's top corner —
CORNER (:mod:`.wall_corner`); none — FLIGHT; the part stopped — at rest
if its contacts hold gravity inside their cones (:func:`~.wall_statics.contacts_can_supply`), else
it starts from rest as a ladder (the sense with σ ω̇ > 0 and both normal forces > 0) or swings back
about A (gravity turns it away from the wall). A third vertex meeting the arm or the face during
LADDER is another impact of the same kind. What is refused (UNRESOLVED with a reason code): a
motion with two closed contacts on one surface (an edge flat on the arm or on the face sliding:
WHY_TWO_CONTACT), the corner and another contact moving together (WHY_WALL_SLIDE), a stopped
part that none of the motions above can start (WHY_LADDER), P at the wall's top (WHY_WALL_TOP),
a vertex at the wall's foot (WHY_CORNER).

LADDER (A on the line y = h, P on the face x = L, both sliding): one degree of freedom, the
orientation φ; with the CM offsets r_A = R(φ) w_A and r_P = R(φ) w_P the CM is
(L − r_Px, h − r_Ay). With d = P − A, A slips at d_y φ̇ along +x̂ and P at d_x φ̇ along +ŷ, so
both slip senses are σ = sgn φ̇ (d_x, d_y > 0). Forces (F_A, N_A) at A with F_A = −μσ N_A and
(−N_P, F_P) at P with F_P = −μ_w σ N_P; unit mass, inertia ρ², gravity (g_x, −g_n)::

    r_Py ω̇ + μσ N_A + N_P                           = g_x − r_Px ω²
   −r_Ax ω̇ − N_A + μ_w σ N_P                        = −g_n − r_Ay ω²
    ρ² ω̇ − (r_Ax + μσ r_Ay) N_A − (r_Py − μ_w σ r_Px) N_P = 0

(:func:`ladder_rhs`, Cramer's rule; a non-positive determinant of the normal-force block —
Painlevé — is INCONSISTENT). Integration: RK4 in (φ, ω), step DTH/(|ω| + Ω); guards (:func:`_lguards`:
A's own as any Coulomb contact's, :func:`~.coulomb.cone_guard`, then P's lift-off and the geometric
ones) located in the step by :func:`~.bracket.locate_guard`.
"""

import math

import numpy as np
from numba import njit

from ..flight import departure_window, separating_window
from .bracket import locate_guard
from .coulomb import cone_guard, cone_guard_value
from .impact import C_OPEN, multi_contact_impact
from .modes import (DTH, EV_INCONSISTENT, EV_LIFT_OFF, EV_STEP_CAP, EV_STICK, MU_SKID, WHY_CORNER, WHY_LADDER,
                    WHY_NONE, WHY_TWO_CONTACT, WHY_WALL_SLIDE, WHY_WALL_TOP)
from .trajectory import _put
from .wall import corner_bounds, corner_departure
from .wall_statics import contacts_can_supply

LN_REST = 0
LN_PIVOT = 1
LN_WALL = 2
LN_REFUSE = 3
LN_INCONSISTENT = 4
LN_CAP = 5
LN_BEHIND = 6
LN_FLIGHT = 7
LN_CORNER = 8
"""Outcomes of :func:`lean`."""

_GO = -1  # internal: go on as a ladder
V_STOP = 1e-6
"""A part whose speeds (|v_x| + |v_y| + |ω| ℓ) after an impact are below V_STOP √(|g| ℓ) (≈ 1 µm/s) is stopped: the
limit of a Zeno sequence of ever smaller impacts against the arm and the wall (measured: such sequences decay by
≈ 0.57 per impact, then stall near 1e-8 m/s, where gravity between impacts adds what each impact removes). A stop
that its contacts cannot hold starts again from rest (a ladder, a swing back)."""


EV_A_OFF = EV_LIFT_OFF
"""LADDER guard: N_A = 0 (A lifts off the arm)."""
EV_P_OFF = 20
"""LADDER guard: N_P = 0 (P leaves the wall)."""
EV_STOP = EV_STICK
"""LADDER guard: ω = 0 (both slips stop together)."""
EV_LAND = 21
"""LADDER guard: another vertex (returned) reaches the arm."""
EV_PLANE = 22
"""LADDER guard: another vertex reaches the wall's plane."""
EV_P_TOP = 23
"""LADDER guard: P reaches the wall's top."""
EV_FOOT = 24
"""LADDER guard: A reaches the wall or P the arm (a vertex at the wall's foot)."""
EV_BEHIND = 25
"""LADDER guard: A slides behind the joint (x ≤ −back)."""


@njit(cache=True)
def offsets(phi, w, j):
    """CM → vertex j (m) at orientation φ."""
    c = math.cos(phi)
    s = math.sin(phi)
    return c * w[j, 0] - s * w[j, 1], s * w[j, 0] + c * w[j, 1]


@njit(cache=True)
def _collect(x, y, phi, w, h, L, top, tol, mu, mu_w, ja, jp, pts, nrm, mus, idx, kind):
    """Contacts of the part at (x, y, φ): every vertex within ``tol`` (m) of the arm (kind 0, cone μ) or of the
    face below its top (kind 1, cone μ_w), and always ``ja`` on the arm and ``jp`` on the face (≥ 0); the
    wall's top corner within ``tol`` of an edge (kind 2, the edge's inward normal, cone μ_w, ``idx`` the
    edge's first vertex). Returns m."""
    m = 0
    n = w.shape[0]
    for k in range(n):
        rkx, rky = offsets(phi, w, k)
        for kd in range(2):
            if kd == 0:
                near = k == ja or y + rky - h <= tol
            else:
                near = k == jp or (L - (x + rkx) <= tol and y + rky <= h + top)
            if near:
                pts[m, 0] = rkx
                pts[m, 1] = rky
                nrm[m, 0] = 0.0 if kd == 0 else -1.0
                nrm[m, 1] = 1.0 if kd == 0 else 0.0
                mus[m] = mu if kd == 0 else mu_w
                idx[m] = k
                kind[m] = kd
                m += 1
    qx = L - x  # the top corner from the CM
    qy = h + top - y
    for k in range(n):
        ax, ay = offsets(phi, w, k)
        bx, by = offsets(phi, w, (k + 1) % n)
        ex = bx - ax
        ey = by - ay
        le = math.hypot(ex, ey)
        s = ((qx - ax) * ex + (qy - ay) * ey) / (le * le)
        if s <= 0.0 or s >= 1.0:
            continue
        nx = ey / le  # the edge's outward normal (n·a > 0: the CM is inside), as _edge_frame
        ny = -ex / le
        if nx * ax + ny * ay < 0.0:
            nx = -nx
            ny = -ny
        if abs(nx * (qx - ax) + ny * (qy - ay)) <= tol:
            pts[m, 0] = qx
            pts[m, 1] = qy
            nrm[m, 0] = -nx  # the contact's normal into the part
            nrm[m, 1] = -ny
            mus[m] = mu_w
            idx[m] = k
            kind[m] = 2
            m += 1
    return m


@njit(cache=True)
def _dispatch(x, y, vx, vy, phi, om, w, rho2, mu, mu_w, gx, gn, lref, m, pts, nrm, mus, idx, kind, st):
    """What follows an impact that left the contacts in states ``st``: ``(code, ka, kp, win_a, win_p, v_a, kc, win_c)`` with
    code an LN_* outcome or _GO (a ladder on arm vertex ka and face vertex kp, or ka/kp = −1 with ω = 0:
    stopped, to be started by :func:`_from_rest`); ``win_a``/``win_p`` (s) exclusion windows of the arm / face
    vertex that just opened (FLIGHT, WALL), ``v_a`` the slip velocity of a pivot (PIVOT), ``kc``/``win_c`` the edge that
    just left the wall's top corner and its window."""
    scale = abs(vx) + abs(vy) + abs(om) * lref + 1e-300
    moving = scale > V_STOP * math.sqrt((abs(gx) + gn) * lref)
    na = 0
    nw = 0
    ka = -1
    kp = -1
    nc = 0
    kc = -1
    for i in range(m):
        if st[i] != C_OPEN:
            if kind[i] == 0:
                na += 1
                ka = idx[i]
            elif kind[i] == 1:
                nw += 1
                kp = idx[i]
            else:
                nc += 1
                kc = idx[i]
    if not moving:
        if contacts_can_supply(pts, nrm, mus, m, -gx, gn, 0.0, lref):
            return LN_REST, -1, -1, 0.0, 0.0, 0.0, -1, 0.0
        # stopped and not held: a ladder on one arm and one face contact may start
        ka = -1
        kp = -1
        for i in range(m):
            if kind[i] == 0 and ka < 0:
                ka = idx[i]
            if kind[i] == 1 and kp < 0:
                kp = idx[i]
        if ka >= 0 and kp >= 0 and ka != kp:
            return _GO, ka, kp, 0.0, 0.0, 0.0, -1, 0.0
        return LN_REFUSE, WHY_LADDER, -1, 0.0, 0.0, 0.0, -1, 0.0
    if nc > 0 and (nc > 1 or na > 0 or nw > 0):
        return LN_REFUSE, WHY_WALL_SLIDE, -1, 0.0, 0.0, 0.0, -1, 0.0  # the corner and another contact, moving
    if na > 1 or nw > 1:
        return LN_REFUSE, WHY_TWO_CONTACT, -1, 0.0, 0.0, 0.0, -1, 0.0
    if na == 1 and nw == 1 and ka == kp:
        return LN_REFUSE, WHY_CORNER, -1, 0.0, 0.0, 0.0, -1, 0.0  # one vertex at the wall's foot
    # windows of the contacts that opened (the slowest of each kind)
    win_a = math.inf
    win_p = math.inf
    win_c = math.inf
    oa = -1
    op = -1
    oc = -1
    for i in range(m):
        if st[i] == C_OPEN:
            rx = pts[i, 0]
            ry = pts[i, 1]
            lj = math.hypot(rx, ry)
            if kind[i] == 0:
                un = vy + om * rx
                wv = departure_window(rx, ry, om, gn, lj, gn) if un <= 1e-12 * scale else \
                    separating_window(un, gn + abs(gx) + om * om * lj)
                if wv < win_a:
                    win_a = wv
                    oa = idx[i]
            elif kind[i] == 1:
                un = -(vx - om * ry)
                wv = departure_window(ry, -rx, om, gx, lj, abs(gx) + gn) if un <= 1e-12 * scale else \
                    separating_window(un, abs(gx) + gn + om * om * lj)
                if wv < win_p:
                    win_p = wv
                    op = idx[i]
            else:  # the corner let go of edge idx[i] (outward normal −nrm[i])
                qx = pts[i, 0]
                qy = pts[i, 1]
                un = nrm[i, 0] * (vx - om * qy) + nrm[i, 1] * (vy + om * qx)  # the gap's rate, > 0: opening
                if un <= 1e-12 * scale:
                    wv = corner_departure(qx, qy, vx, vy, om, gx, gn, -nrm[i, 0], -nrm[i, 1], 1.0)
                else:
                    m2, _m3 = corner_bounds(qx, qy, vx, vy, om, gx, gn, 1.0)
                    wv = separating_window(un, m2)
                if wv < win_c:
                    win_c = wv
                    oc = idx[i]
    if (oa >= 0 and win_a <= 0.0) or (op >= 0 and win_p <= 0.0) or (oc >= 0 and win_c <= 0.0):
        # a contact that can neither stay closed nor open
        return LN_REFUSE, WHY_TWO_CONTACT, -1, 0.0, 0.0, 0.0, oc, win_c
    if na == 1 and nw == 1:
        return _GO, ka, kp, 0.0, 0.0, 0.0, oc, win_c
    if na == 1:
        rax, ray = offsets(phi, w, ka)
        return LN_PIVOT, ka, op, 0.0, win_p, vx - om * ray, oc, win_c
    if nw == 1:
        return LN_WALL, oa, kp, win_a, 0.0, 0.0, oc, win_c
    if nc == 1:
        return LN_CORNER, oa, kc, win_a, 0.0, 0.0, oc, win_c  # ``kp``: the edge on the corner
    return LN_FLIGHT, oa, op, win_a, win_p, 0.0, oc, win_c


@njit(cache=True)
def lean(ja, jp, impact, t, x, y, vx, vy, phi, om, w, rho2, mu, mu_w, gx, gn, h, top, L, back, lref, max_steps,
         max_events, traj, ts):
    """Mode LEAN (module docstring) from the flight state (CM (x, y), (v_x, v_y), φ, ω; SI) with vertex ``ja`` on the
    arm and ``jp`` on the face: the impact first if ``impact`` (else the part moves as a ladder with σ = sgn ω,
    or is stopped if ω = 0).

    Returns ``(outcome, why, t, x, y, v_x, v_y, φ, ω, ka, kp, win_a, win_p, v_a, kc, win_c)``: LN_REST (pose),
    LN_PIVOT on arm vertex ``ka`` with slip velocity ``v_a`` (m/s), LN_WALL on face vertex ``kp`` (arm vertex
    ``ka`` excluded for ``win_a`` s), LN_CORNER with edge ``kp`` on the wall's top corner (:mod:`.wall_corner`;
    ``ka`` as LN_WALL), LN_FLIGHT (arm vertex ``ka`` excluded ``win_a`` s, face vertex ``kp`` ``win_p`` s),
    LN_REFUSE with ``why``, LN_INCONSISTENT, LN_CAP, LN_BEHIND (A slid behind the joint); ``kc`` an edge that
    just left the wall's top corner, excluded from its guard for ``win_c`` s (−1: none).
    """
    n = w.shape[0]
    pts = np.empty((2 * n, 2))
    nrm = np.empty((2 * n, 2))
    mus = np.empty(2 * n)
    idx = np.empty(2 * n, dtype=np.int64)
    kind = np.empty(2 * n, dtype=np.int64)
    st = np.empty(2 * n, dtype=np.int64)
    tol = 1e-9 * lref
    stopped = False
    pending = impact or ja < 0 or jp < 0  # (a stopped part on the corner and the arm: its contacts are collected)
    if not pending:
        stopped = om == 0.0
    for _ in range(max_events):
        if pending:
            m = _collect(x, y, phi, w, h, L, top, tol, mu, mu_w, ja, jp, pts, nrm, mus, idx, kind)
            ok, vx1, vy1, om1 = multi_contact_impact(vx, vy, om, pts, nrm, mus, m, rho2, st)
            if not ok:  # infinite friction at two contacts can leave no consistent impulse: its μ → ∞ limit
                for i in range(m):
                    mus[i] = min(mus[i], MU_SKID)
                ok, vx1, vy1, om1 = multi_contact_impact(vx, vy, om, pts, nrm, mus, m, rho2, st)
            vx, vy, om = vx1, vy1, om1
            if not ok:
                return LN_INCONSISTENT, WHY_NONE, t, x, y, vx, vy, phi, om, -1, -1, 0.0, 0.0, 0.0, -1, 0.0
            code, ka, kp, win_a, win_p, v_a, kc, win_c = _dispatch(x, y, vx, vy, phi, om, w, rho2, mu, mu_w, gx, gn,
                                                                   lref, m, pts, nrm, mus, idx, kind, st)
            if code != _GO:
                if code == LN_REFUSE:
                    return code, ka, t, x, y, vx, vy, phi, om, -1, -1, 0.0, 0.0, 0.0, -1, 0.0
                if code == LN_REST:
                    return code, WHY_NONE, t, x, y, 0.0, 0.0, phi, 0.0, -1, -1, 0.0, 0.0, 0.0, -1, 0.0
                return code, WHY_NONE, t, x, y, vx, vy, phi, om, ka, kp, win_a, win_p, v_a, kc, win_c
            ja = ka
            jp = kp
            pending = False
            stopped = om == 0.0 or not (abs(vx) + abs(vy) + abs(om) * lref
                                        > V_STOP * math.sqrt((abs(gx) + gn) * lref))
        if stopped:
            act, sig = _from_rest(phi, w, ja, jp, rho2, mu, mu_w, gx, gn, lref)
            x, y = ladder_pose(phi, w, ja, jp, h, L)
            if act == 0:
                return LN_REST, WHY_NONE, t, x, y, 0.0, 0.0, phi, 0.0, -1, -1, 0.0, 0.0, 0.0, -1, 0.0
            if act == 2:
                return LN_PIVOT, WHY_NONE, t, x, y, 0.0, 0.0, phi, 0.0, ja, -1, 0.0, 0.0, 0.0, -1, 0.0
            if act == 3:
                return LN_REFUSE, WHY_LADDER, t, x, y, 0.0, 0.0, phi, 0.0, -1, -1, 0.0, 0.0, 0.0, -1, 0.0
            om = 0.0
            stopped = False
        else:
            sig = 1.0 if om > 0.0 else -1.0
        ev, k, phi, om, t = ladder_phase(phi, om, sig, t, w, ja, jp, rho2, mu, mu_w, gx, gn, h, L, top, back,
                                         max_steps, traj, ts)
        x, y = ladder_pose(phi, w, ja, jp, h, L)
        rax, ray = offsets(phi, w, ja)
        rpx, rpy = offsets(phi, w, jp)
        vx = rpy * om
        vy = -rax * om
        if ev == EV_STOP:
            stopped = True
            continue
        if ev == EV_P_OFF:
            return LN_PIVOT, WHY_NONE, t, x, y, vx, vy, phi, om, ja, jp, 0.0, 0.0, vx - om * ray, -1, 0.0
        if ev == EV_A_OFF:
            win = departure_window(rax, ray, om, gn, math.hypot(rax, ray), gn)
            if win <= 0.0:
                return LN_INCONSISTENT, WHY_NONE, t, x, y, vx, vy, phi, om, -1, -1, 0.0, 0.0, 0.0, -1, 0.0
            return LN_WALL, WHY_NONE, t, x, y, vx, vy, phi, om, ja, jp, win, 0.0, 0.0, -1, 0.0
        if ev == EV_LAND or ev == EV_PLANE:
            pending = True  # a third vertex meets the arm or the face: another impact
            continue
        if ev == EV_P_TOP:
            return LN_REFUSE, WHY_WALL_TOP, t, x, y, vx, vy, phi, om, -1, -1, 0.0, 0.0, 0.0, -1, 0.0
        if ev == EV_FOOT:
            return LN_REFUSE, WHY_CORNER, t, x, y, vx, vy, phi, om, -1, -1, 0.0, 0.0, 0.0, -1, 0.0
        if ev == EV_BEHIND:
            return LN_BEHIND, WHY_NONE, t, x, y, vx, vy, phi, om, -1, -1, 0.0, 0.0, 0.0, -1, 0.0
        if ev == EV_INCONSISTENT:
            return LN_INCONSISTENT, WHY_NONE, t, x, y, vx, vy, phi, om, -1, -1, 0.0, 0.0, 0.0, -1, 0.0
        return LN_CAP, WHY_NONE, t, x, y, vx, vy, phi, om, -1, -1, 0.0, 0.0, 0.0, -1, 0.0
    return LN_CAP, WHY_NONE, t, x, y, vx, vy, phi, om, -1, -1, 0.0, 0.0, 0.0, -1, 0.0


@njit(cache=True)
def _from_rest(phi, w, ja, jp, rho2, mu, mu_w, gx, gn, lref):
    """What a part leaning at rest on A (arm) and P (face) does: ``(0, _)`` rests, ``(1, σ)`` slides as a ladder
    with sense σ, ``(2, _)`` swings back about A (P leaves the wall), ``(3, _)`` none of these (refused)."""
    rax, ray = offsets(phi, w, ja)
    rpx, rpy = offsets(phi, w, jp)
    pts = np.empty((2, 2))
    nrm = np.empty((2, 2))
    mus = np.empty(2)
    pts[0, 0] = rax
    pts[0, 1] = ray
    nrm[0, 0] = 0.0
    nrm[0, 1] = 1.0
    mus[0] = mu
    pts[1, 0] = rpx
    pts[1, 1] = rpy
    nrm[1, 0] = -1.0
    nrm[1, 1] = 0.0
    mus[1] = mu_w
    if contacts_can_supply(pts, nrm, mus, 2, -gx, gn, 0.0, lref):
        return 0, 0.0
    for sig in (1.0, -1.0):
        wd, na, npw, D = ladder_rhs(phi, 0.0, w[ja], w[jp], rho2, mu, mu_w, sig, gx, gn)
        if D > 0.0 and na > 0.0 and npw > 0.0 and sig * wd > 0.0:
            return 1, sig
    lj = math.hypot(rax, ray)
    if (rax * gn + ray * gx) / lj > 0.0:  # (CM − A) × g / ℓ = (−r_A) × (g_x, −g_n) / ℓ: θ̈ about A
        return 2, 0.0
    return 3, 0.0


@njit(cache=True)
def ladder_rhs(phi, om, wa, wp, rho2, mu, mu_w, sig, gx, gn):
    """LADDER dynamics (module docstring) at orientation φ and rate ω with body offsets ``wa`` = w_A, ``wp`` = w_P.

    Returns ``(ω̇, N_A, N_P, D)``: D the determinant of the normal-force block (≤ 0: Painlevé,
    ``(nan, nan, nan, D)``).
    """
    c = math.cos(phi)
    s = math.sin(phi)
    rax = c * wa[0] - s * wa[1]
    ray = s * wa[0] + c * wa[1]
    rpx = c * wp[0] - s * wp[1]
    rpy = s * wp[0] + c * wp[1]
    ms = mu * sig
    mws = mu_w * sig
    # unknowns (ω̇, N_A, N_P)
    a11, a12, a13, b1 = rpy, ms, 1.0, gx - rpx * om * om
    a21, a22, a23, b2 = -rax, -1.0, mws, -gn - ray * om * om
    a31, a32, a33, b3 = rho2, -(rax + ms * ray), -(rpy - mws * rpx), 0.0
    det = a11 * (a22 * a33 - a23 * a32) - a12 * (a21 * a33 - a23 * a31) + a13 * (a21 * a32 - a22 * a31)
    # frictionless: det = ρ² + r_Ax² + r_Py² > 0; friction that drives det to 0 makes the forces unbounded
    D = det / rho2
    if not D > 0.0:
        return math.nan, math.nan, math.nan, D
    wd = (b1 * (a22 * a33 - a23 * a32) - a12 * (b2 * a33 - a23 * b3) + a13 * (b2 * a32 - a22 * b3)) / det
    na = (a11 * (b2 * a33 - a23 * b3) - b1 * (a21 * a33 - a23 * a31) + a13 * (a21 * b3 - b2 * a31)) / det
    npw = (a11 * (a22 * b3 - b2 * a32) - a12 * (a21 * b3 - b2 * a31) + b1 * (a21 * a32 - a22 * a31)) / det
    return wd, na, npw, D


@njit(cache=True)
def ladder_pose(phi, w, ja, jp, h, L):
    """CM (x, y) (m) of the part with vertex ``ja`` on the line y = h and ``jp`` on the face x = L at orientation φ."""
    c = math.cos(phi)
    s = math.sin(phi)
    return L - (c * w[jp, 0] - s * w[jp, 1]), h - (s * w[ja, 0] + c * w[ja, 1])


@njit(cache=True)
def _rk4(phi, om, dt, wa, wp, rho2, mu, mu_w, sig, gx, gn):
    a1, _n, _m, _d = ladder_rhs(phi, om, wa, wp, rho2, mu, mu_w, sig, gx, gn)
    a2, _n, _m, _d = ladder_rhs(phi + 0.5 * dt * om, om + 0.5 * dt * a1, wa, wp, rho2, mu, mu_w, sig, gx, gn)
    w2 = om + 0.5 * dt * a1
    a3, _n, _m, _d = ladder_rhs(phi + 0.5 * dt * w2, om + 0.5 * dt * a2, wa, wp, rho2, mu, mu_w, sig, gx, gn)
    w3 = om + 0.5 * dt * a2
    a4, _n, _m, _d = ladder_rhs(phi + dt * w3, om + dt * a3, wa, wp, rho2, mu, mu_w, sig, gx, gn)
    w4 = om + dt * a3
    return (phi + dt * (om + 2.0 * w2 + 2.0 * w3 + w4) / 6.0,
            om + dt * (a1 + 2.0 * a2 + 2.0 * a3 + a4) / 6.0)


@njit(cache=True, inline="always")
def _advance(s, tau, p):
    """The RK4 step of length ``tau`` (s) from ``s`` = (φ, ω) (parameters ``p`` of :func:`ladder_phase`)."""
    w, ja, jp, rho2, mu, mu_w, sig, gx, gn, h, L, top, back, ga, wa, wpv = p
    return _rk4(s[0], s[1], tau, wa, wpv, rho2, mu, mu_w, sig, gx, gn)


@njit(cache=True)
def _lguard(which, k, s, p):
    """Value of one LADDER guard (> 0: not fired) at ``s`` = (φ, ω); see :func:`_lguards`."""
    phi, om = s
    w, ja, jp, rho2, mu, mu_w, sig, gx, gn, h, L, top, back, ga, wa, wpv = p
    if which == EV_STOP or which == EV_A_OFF or which == EV_P_OFF:
        _a, na, npw, _d = ladder_rhs(phi, om, w[ja], w[jp], rho2, mu, mu_w, sig, gx, gn)
        if which == EV_P_OFF:
            return cone_guard_value(EV_LIFT_OFF, npw, 0.0, om, sig, mu_w, ga)
        return cone_guard_value(which, na, 0.0, om, sig, mu, ga)
    x, y = ladder_pose(phi, w, ja, jp, h, L)
    c = math.cos(phi)
    s = math.sin(phi)
    if which == EV_P_TOP:
        return h + top - (y + s * w[jp, 0] + c * w[jp, 1])
    if which == EV_BEHIND:
        return x + c * w[ja, 0] - s * w[ja, 1] + back
    if which == EV_LAND or (which == EV_FOOT and k == jp):
        return y + s * w[k, 0] + c * w[k, 1] - h
    if which == EV_PLANE or which == EV_FOOT:
        return L - (x + c * w[k, 0] - s * w[k, 1])
    return math.nan


@njit(cache=True)
def _lguards(s, p):
    """Least LADDER guard at ``s`` = (φ, ω): ``(value, which, k)``; ``(-1, EV_INCONSISTENT, -1)`` at D ≤ 0 (Painlevé).

    Guards: A's own as a Coulomb contact (:func:`~.coulomb.cone_guard`: ``a_off`` N_A/|g|, ``stop`` σω, both
    slips stop together); ``p_off`` N_P/|g|; ``land`` y_k − h (k ≠ A, P); ``plane`` L − x_k (k ≠ A, P);
    ``foot`` y_P − h or L − x_A; ``p_top`` h + H − y_P; ``behind`` x_A + back.
    """
    phi, om = s
    w, ja, jp, rho2, mu, mu_w, sig, gx, gn, h, L, top, back, ga, wa, wpv = p
    _a, na, npw, D = ladder_rhs(phi, om, w[ja], w[jp], rho2, mu, mu_w, sig, gx, gn)
    if not D > 0.0:
        return -1.0, EV_INCONSISTENT, -1
    gmin, which = cone_guard(na, 0.0, om, False, sig, mu, ga, True)
    kk = -1
    if npw / ga < gmin:
        gmin = npw / ga
        which = EV_P_OFF
    x, y = ladder_pose(phi, w, ja, jp, h, L)
    c = math.cos(phi)
    s = math.sin(phi)
    for k in range(w.shape[0]):
        xk = x + c * w[k, 0] - s * w[k, 1]
        yk = y + s * w[k, 0] + c * w[k, 1]
        if k == jp:
            if yk - h < gmin:
                gmin = yk - h
                which = EV_FOOT
                kk = k
            if h + top - yk < gmin:
                gmin = h + top - yk
                which = EV_P_TOP
                kk = k
        elif k == ja:
            if L - xk < gmin:
                gmin = L - xk
                which = EV_FOOT
                kk = k
            if xk + back < gmin:
                gmin = xk + back
                which = EV_BEHIND
                kk = k
        else:
            if yk - h < gmin:
                gmin = yk - h
                which = EV_LAND
                kk = k
            if L - xk < gmin:
                gmin = L - xk
                which = EV_PLANE
                kk = k
    return gmin, which, kk


@njit(cache=True)
def ladder_phase(phi, om, sig, t, w, ja, jp, rho2, mu, mu_w, gx, gn, h, L, top, back, max_steps, traj, ts):
    """Mode LADDER from orientation φ and rate ω (slip sense σ = sgn ω) until a guard fires (:func:`_lguards`).

    Returns ``(event, k, φ, ω, t)`` (k: the vertex of ``land``/``plane``/``foot``, else −1).
    """
    ga = abs(gx) + gn
    lmax = 0.0
    for k in range(w.shape[0]):
        lmax = max(lmax, math.hypot(w[k, 0], w[k, 1]))
    om0 = math.sqrt(ga / lmax)
    wa = w[ja]
    wpv = w[jp]
    sample = traj.shape[0] > 0
    p = (w, ja, jp, rho2, mu, mu_w, sig, gx, gn, h, L, top, back, ga, wa, wpv)
    for _ in range(max_steps):
        dt = DTH / (abs(om) + om0)
        s0 = (phi, om)
        s1 = _advance(s0, dt, p)
        gm, which, k = _lguards(s1, p)
        if which == EV_INCONSISTENT:
            return EV_INCONSISTENT, -1, phi, om, t
        step = dt
        if gm <= 0.0:
            step, which, k, s1 = locate_guard(_advance, _lguards, _lguard, s0, s1, dt, which, k, t, p)
        p1, w1 = s1
        if sample:
            while ts[1] <= t + step:
                pq, _wq = _rk4(phi, om, ts[1] - t, wa, wpv, rho2, mu, mu_w, sig, gx, gn)
                xq, yq = ladder_pose(pq, w, ja, jp, h, L)
                _put(traj, ts, ts[1], xq, yq, pq)
                ts[1] += ts[2]
        phi, om = p1, w1
        t += step
        if gm <= 0.0:
            if which == EV_STOP:
                om = 0.0
            if sample:
                xq, yq = ladder_pose(phi, w, ja, jp, h, L)
                _put(traj, ts, t, xq, yq, phi)
            return which, k, phi, om, t
    return EV_STEP_CAP, -1, phi, om, t

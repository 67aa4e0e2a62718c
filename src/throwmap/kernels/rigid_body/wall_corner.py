"""Mode CORNER of model "rigid_body": an edge of the part pressed on the wall's top corner, the part otherwise free.

The corner Q = (L, h + H) (arm frame, m) touches edge e (vertex e → e + 1, outward unit normal n,
unit tangent t along it, support d = n·(a − X) for its vertex a and CM X). The gap is
g = n·(Q − X) − d; with r = Q − X (CM → contact), J the turn by +90° and V the CM velocity,

    g' = ω (Jn)·r − n·V,   g'' = ω̇ (Jn)·r − ω² n·r − 2ω (Jn)·V − n·A.

The corner pushes with λ ≥ 0 along −n and rubs with f along t (Coulomb μ_w of the wall); unit mass,
inertia ρ², gravity (g_x, −g_n). Sliding (the part's material point at Q slips at s = t·(V + ω J r),
f = −μ_w σ λ, σ = sgn s): g'' = 0 gives λ D = −f₂ with f₂ = −ω² n·r − 2ω (Jn)·V − n·g and
D = 1 + ((r × n)² + μ_w σ (r × n)(r × t))/ρ² (D ≤ 0: Painlevé, INCONSISTENT). Sticking (s = 0: the
part turns about Q, p = X − Q): (ρ² + |p|²) ω̇ = p × g, A = ω̇ J p − ω² p, and the contact force is
A − g, valid while λ ≥ 0 and |f| ≤ μ_w λ. f₂ ≤ 0 is exactly the condition under which
:func:`~.wall.corner_departure` finds no departure window (the edge stays pressed).

Integration: classical RK4 in (x, y, φ, v_x, v_y, ω), step DTH/(|ω| + Ω), after every step the pose
and velocity projected back onto g = 0, g' = 0 (along n); guards located inside the step by
:func:`~.bracket.locate_guard`. Guards: the contact's own (:func:`~.coulomb.cone_guard`: ``lift_off``
λ = 0, ``stick``/``slip`` for μ_w > 0), ``end`` (Q at an end of the edge: a vertex on the corner),
``arm`` (a vertex reaches y = h), ``wall`` (a vertex reaches the wall's solid: its face x = L below the
top, or its top y = h + H beyond the face).

The automaton enters the mode through :func:`corner_contact`, which follows the sub-mode changes
(:func:`corner_select`, :func:`corner_phase`) to the first event it continues from: the edge lets go
(FLIGHT, the edge excluded from ``corner_touch`` for its departure window :func:`~.wall.corner_departure`),
or another vertex reaches the arm or the face (the multi-contact impact of :mod:`.wall_lean`).
"""

import math

import numpy as np
from numba import njit

from .bracket import locate_guard
from .coulomb import cone_guard
from .modes import (DTH, EV_INCONSISTENT, EV_LIFT_OFF, EV_SLIP, EV_STEP_CAP, EV_STICK, WC_ARM, WC_CAP, WC_FACE,
                    WC_FLIGHT, WC_INCONSISTENT, WC_REFUSE, WHY_CORNER_VERTEX, WHY_NONE, WHY_WALL_SLIDE)
from .trajectory import _put
from .wall import corner_departure, sink_slack

EV_END = 30
"""Guard ``end``: the corner reached an end of the edge (a vertex on the corner)."""
EV_CARM = 31
"""Guard ``arm``: a vertex (returned) reaches the arm's line."""
EV_FACE = 32
"""Guard ``wall``: a vertex (returned) reaches the wall's face below its top."""
EV_TOPS = 33
"""Guard ``wall``: a vertex reaches the wall's top surface beyond the face."""


@njit(cache=True)
def edge_body(w, e):
    """Body-frame outward normal (n_x, n_y), unit tangent (t_x, t_y) and length (m) of edge e (vertex e → e + 1)."""
    n = w.shape[0]
    ax, ay = w[e, 0], w[e, 1]
    bx, by = w[(e + 1) % n, 0], w[(e + 1) % n, 1]
    le = math.hypot(bx - ax, by - ay)
    tx = (bx - ax) / le
    ty = (by - ay) / le
    nx = ty
    ny = -tx
    if nx * ax + ny * ay < 0.0:
        nx = -nx
        ny = -ny
    return nx, ny, tx, ty, le


@njit(cache=True)
def corner_rhs(s, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, stick):
    """CORNER dynamics (module docstring) at state ``s`` = (x, y, φ, v_x, v_y, ω) with the corner at (q_x, q_y) and
    the edge's body normal ``nb`` and tangent ``tb``. Returns ``(a_x, a_y, ω̇, λ, f, D, slip)`` (per unit mass)."""
    x, y, phi, vx, vy, om = s[0], s[1], s[2], s[3], s[4], s[5]
    c = math.cos(phi)
    sn = math.sin(phi)
    nx = c * nb[0] - sn * nb[1]
    ny = sn * nb[0] + c * nb[1]
    tx = c * tb[0] - sn * tb[1]
    ty = sn * tb[0] + c * tb[1]
    rx = qx - x
    ry = qy - y
    slip = tx * (vx - om * ry) + ty * (vy + om * rx)
    if stick:
        px = -rx
        py = -ry
        wd = (px * (-gn) - py * gx) / (rho2 + px * px + py * py)
        ax = -wd * py - om * om * px
        ay = wd * px - om * om * py
        fx = ax - gx
        fy = ay + gn
        return ax, ay, wd, -(nx * fx + ny * fy), tx * fx + ty * fy, 1.0, slip
    rxn = rx * ny - ry * nx
    rxt = rx * ty - ry * tx
    ms = mu_w * sig
    D = 1.0 + (rxn * rxn + ms * rxn * rxt) / rho2
    if not D > 0.0:
        return math.nan, math.nan, math.nan, math.nan, math.nan, D, slip
    jnx = -ny
    jny = nx
    f2 = -om * om * (nx * rx + ny * ry) - 2.0 * om * (jnx * vx + jny * vy) - (nx * gx - ny * gn)
    lam = -f2 / D
    f = -ms * lam
    fx = -lam * nx + f * tx
    fy = -lam * ny + f * ty
    return gx + fx, -gn + fy, (rx * fy - ry * fx) / rho2, lam, f, D, slip


@njit(cache=True)
def _deriv(s, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, stick):
    ax, ay, wd, _l, _f, _d, _s = corner_rhs(s, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, stick)
    out = np.empty(6)
    out[0] = s[3]
    out[1] = s[4]
    out[2] = s[5]
    out[3] = ax
    out[4] = ay
    out[5] = wd
    return out


@njit(cache=True)
def _project(s, qx, qy, nb, db):
    """Put the pose back on the edge through the corner (g = 0) and its velocity on g' = 0, moving along n."""
    c = math.cos(s[2])
    sn = math.sin(s[2])
    nx = c * nb[0] - sn * nb[1]
    ny = sn * nb[0] + c * nb[1]
    g = nx * (qx - s[0]) + ny * (qy - s[1]) - db
    s[0] += g * nx
    s[1] += g * ny
    rx = qx - s[0]
    ry = qy - s[1]
    gd = s[5] * (-ny * rx + nx * ry) - (nx * s[3] + ny * s[4])
    s[3] += gd * nx
    s[4] += gd * ny


@njit(cache=True)
def _rk4(s, dt, qx, qy, nb, tb, db, rho2, gx, gn, mu_w, sig, stick):
    k1 = _deriv(s, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, stick)
    k2 = _deriv(s + 0.5 * dt * k1, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, stick)
    k3 = _deriv(s + 0.5 * dt * k2, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, stick)
    k4 = _deriv(s + dt * k3, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, stick)
    out = s + dt * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0
    _project(out, qx, qy, nb, db)
    return out


@njit(cache=True)
def _cguards(s, p):
    """Least CORNER guard ``(value, which, k)`` (module docstring) at the state ``s`` (6,); ``(-1, EV_INCONSISTENT, -1)``
    at D ≤ 0. The contact's own guards are :func:`~.coulomb.cone_guard`'s; ``p`` the parameters of :func:`corner_phase`."""
    w, e, le, qx, qy, nb, tb, db, rho2, gx, gn, mu_w, sig, stick, h, L, top, ga, arm_skip, slack = p
    _ax, _ay, _wd, lam, f, D, slip = corner_rhs(s, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, stick)
    if not D > 0.0:
        return -1.0, EV_INCONSISTENT, -1
    gmin, which = cone_guard(lam, f, slip, stick, sig, mu_w, ga, mu_w > 0.0)
    kk = -1
    c = math.cos(s[2])
    sn = math.sin(s[2])
    tx = c * tb[0] - sn * tb[1]
    ty = sn * tb[0] + c * tb[1]
    ax = s[0] + c * w[e, 0] - sn * w[e, 1]
    ay = s[1] + sn * w[e, 0] + c * w[e, 1]
    u = tx * (qx - ax) + ty * (qy - ay)
    if u < gmin:
        gmin = u
        which = EV_END
    if le - u < gmin:
        gmin = le - u
        which = EV_END
    n = w.shape[0]
    for k in range(n):
        xk = s[0] + c * w[k, 0] - sn * w[k, 1]
        yk = s[1] + sn * w[k, 0] + c * w[k, 1]
        v = yk - h + slack if k == arm_skip else yk - h
        if v < gmin:
            gmin = v
            which = EV_CARM
            kk = k
        if k != e and k != (e + 1) % n:
            v = max(L - xk, yk - (h + top))  # outside the wall's solid quadrant x ≥ L, y ≤ h + H
            if v < gmin:
                gmin = v
                which = EV_FACE if L - xk >= yk - (h + top) else EV_TOPS
                kk = k
    return gmin, which, kk


@njit(cache=True, inline="always")
def _advance(s, tau, p):
    """The RK4 step of length ``tau`` (s) from the state ``s`` (6,), projected back onto the corner (:func:`_rk4`)."""
    w, e, le, qx, qy, nb, tb, db, rho2, gx, gn, mu_w, sig, stick, h, L, top, ga, arm_skip, slack = p
    return _rk4(s, tau, qx, qy, nb, tb, db, rho2, gx, gn, mu_w, sig, stick)


@njit(cache=True, inline="always")
def _least_guard(which, k, s, p):
    """The least guard's value at ``s``: the value :func:`~.bracket.locate_guard` narrows in CORNER (its guards are
    located on their minimum, whose pieces switch as the projected state moves)."""
    return _cguards(s, p)[0]


@njit(cache=True)
def corner_phase(s, e, stick, sig, t, w, rho2, gx, gn, mu_w, h, L, top, arm_skip, arm_skip_until, arm_slack,
                 max_steps, traj, ts):
    """Integrate one sub-mode of CORNER (``stick``, or sliding with sense ``sig``) from state ``s`` (6,) until a
    guard fires. Returns ``(event, k, s, t)`` (k: the vertex of ``arm``/``wall``, else −1). Vertex ``arm_skip``
    just left the arm: until ``arm_skip_until`` (s) its arm guard fires only ``arm_slack`` (m) below the line
    (:func:`~.wall.sink_slack`)."""
    nx, ny, tx, ty, le = edge_body(w, e)
    nb = np.array([nx, ny])
    tb = np.array([tx, ty])
    db = nx * w[e, 0] + ny * w[e, 1]
    qx = L
    qy = h + top
    ga = abs(gx) + gn
    lmax = 0.0
    for k in range(w.shape[0]):
        lmax = max(lmax, math.hypot(w[k, 0], w[k, 1]))
    om0 = math.sqrt(ga / lmax)
    sample = traj.shape[0] > 0
    s = s.copy()
    _project(s, qx, qy, nb, db)
    for _ in range(max_steps):
        skip = arm_skip if t < arm_skip_until else -1
        p = (w, e, le, qx, qy, nb, tb, db, rho2, gx, gn, mu_w, sig, stick, h, L, top, ga, skip, arm_slack)
        dt = DTH / (abs(s[5]) + om0)
        s1 = _advance(s, dt, p)
        gm, which, k = _cguards(s1, p)
        if which == EV_INCONSISTENT:
            return EV_INCONSISTENT, -1, s, t
        step = dt
        if gm <= 0.0:
            step, which, k, s1 = locate_guard(_advance, _cguards, _least_guard, s, s1, dt, which, k, t, p)
        if sample:
            while ts[1] <= t + step:
                sq = _rk4(s, ts[1] - t, qx, qy, nb, tb, db, rho2, gx, gn, mu_w, sig, stick)
                _put(traj, ts, ts[1], sq[0], sq[1], sq[2])
                ts[1] += ts[2]
        s = s1
        t += step
        if gm <= 0.0:
            if sample:
                _put(traj, ts, t, s[0], s[1], s[2])
            return which, k, s, t
    return EV_STEP_CAP, -1, s, t


@njit(cache=True)
def corner_select(s, e, w, rho2, gx, gn, mu_w, L, h, top, from_slip):
    """Which sub-mode continues from edge ``e`` on the corner at state ``s`` (as :func:`~.wall_slide.wall_select`):
    ``(mode, σ)`` with mode 1 stick, 0 slide, −1 not pressed (λ ≤ 0: let go), −2 no consistent motion."""
    nx, ny, tx, ty, _le = edge_body(w, e)
    nb = np.array([nx, ny])
    tb = np.array([tx, ty])
    qx = L
    qy = h + top
    _a, _b, _w, lam0, _f, D0, slip = corner_rhs(s, qx, qy, nb, tb, rho2, gx, gn, 0.0, 0.0, False)
    if mu_w == 0.0:
        if not D0 > 0.0:
            return -2, 0.0
        return (0, 0.0) if lam0 > 0.0 else (-1, 0.0)
    scale = max(1.0, abs(s[3]) + abs(s[4]))
    if abs(slip) > 1e-12 * scale:
        sig = 1.0 if slip > 0.0 else -1.0
        if math.isinf(mu_w):
            return -2, 0.0
        _a, _b, _w, lam, _f, D, _s = corner_rhs(s, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, False)
        if not D > 0.0:
            return -2, 0.0
        return (0, sig) if lam > 0.0 else (-1, 0.0)
    _a, _b, _w, lam, f, _d, _s = corner_rhs(s, qx, qy, nb, tb, rho2, gx, gn, mu_w, 0.0, True)
    if lam <= 0.0:
        return -1, 0.0
    if not from_slip and abs(f) <= mu_w * lam:
        return 1, 0.0
    sig = -1.0 if f > 0.0 else 1.0
    if not math.isinf(mu_w):
        _a, _b, _w, lam2, _f, D, _s = corner_rhs(s, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, False)
        if D > 0.0 and lam2 > 0.0:
            return 0, sig
    # neither sticking nor sliding keeps it pressed: it lets go if the free motion opens the gap
    c = math.cos(s[2])
    sn = math.sin(s[2])
    if corner_departure(qx - s[0], qy - s[1], s[3], s[4], s[5], gx, gn, c * nx - sn * ny, sn * nx + c * ny,
                        1.0) > 0.0:
        return -1, 0.0
    return -2, 0.0


@njit(cache=True)
def corner_contact(e, t, x, y, vx, vy, phi, om, w, rho2, gx, gn, mu_w, h, top, L, arm_skip, arm_skip_until,
                   max_steps, max_events, traj, ts):
    """Mode CORNER (:mod:`.wall_corner`) from the flight state with edge ``e`` pressed on the wall's top corner after a
    plastic impact, until: ``lift_off`` (WC_FLIGHT, with the edge's departure window
    :func:`~.wall.corner_departure`); a vertex k reaches the arm (WC_ARM) or the face below the top (WC_FACE);
    a vertex reaches the corner or the wall's top beyond the face (WHY_CORNER_VERTEX); Painlevé or no consistent
    sub-mode (WC_INCONSISTENT); the step or event caps (WC_CAP). Returns as :func:`wall_contact`.
    """
    s = np.array([x, y, phi, vx, vy, om])
    slack = sink_slack(x, y, phi, w, arm_skip, h)
    from_slip = False
    for _ in range(max_events):
        mode, sig = corner_select(s, e, w, rho2, gx, gn, mu_w, L, h, top, from_slip)
        if mode == -2:
            return _cout(WC_INCONSISTENT, -1, t, s, w, 0.0, WHY_NONE)
        if mode == -1:
            return _corner_lift(e, t, s, w, gx, gn, h, top, L)
        ev, k, s, t = corner_phase(s, e, mode == 1, sig, t, w, rho2, gx, gn, mu_w, h, L, top, arm_skip,
                                   arm_skip_until, slack, max_steps, traj, ts)
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

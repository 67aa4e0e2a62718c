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
:func:`~.wall_contact.corner_departure` finds no departure window (the edge stays pressed).

Integration: classical RK4 in (x, y, φ, v_x, v_y, ω), step DTH/(|ω| + Ω), after every step the pose and
velocity projected back onto g = 0, g' = 0 (along n); guards located inside the step by bracketing as
:func:`~.slide._locate_guard`. Guards: ``lift_off`` (λ = 0), ``stick``/``slip`` (μ_w > 0), ``end`` (Q at
an end of the edge: a vertex on the corner), ``arm`` (a vertex reaches y = h), ``wall`` (a vertex reaches
the wall's solid: its face x = L below the top, or its top y = h + H beyond the face).
"""

import math

import numpy as np
from numba import njit

from .modes import DTH, EV_INCONSISTENT, EV_LIFT_OFF, EV_SLIP, EV_STEP_CAP, EV_STICK, N_BISECT
from .bracket import falsi_point
from .trajectory import _put
from .wall_contact import corner_departure

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
def _cguards(s, w, e, le, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, stick, h, L, top, ga, arm_skip):
    """Least CORNER guard ``(value, which, k)`` (module docstring); ``(-1, EV_INCONSISTENT, -1)`` at D ≤ 0."""
    _ax, _ay, _wd, lam, f, D, slip = corner_rhs(s, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, stick)
    if not D > 0.0:
        return -1.0, EV_INCONSISTENT, -1
    gmin = lam / ga
    which = EV_LIFT_OFF
    kk = -1
    if stick:
        if math.isfinite(mu_w):
            v = (mu_w * lam - abs(f)) / ga
            if v < gmin:
                gmin = v
                which = EV_SLIP
    elif mu_w > 0.0 and sig * slip < gmin:
        gmin = sig * slip
        which = EV_STICK
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
        if k != arm_skip and yk - h < gmin:
            gmin = yk - h
            which = EV_CARM
            kk = k
        if k != e and k != (e + 1) % n:
            v = max(L - xk, yk - (h + top))  # outside the wall's solid quadrant x ≥ L, y ≤ h + H
            if v < gmin:
                gmin = v
                which = EV_FACE if L - xk >= yk - (h + top) else EV_TOPS
                kk = k
    return gmin, which, kk


@njit(cache=True)
def corner_phase(s, e, stick, sig, t, w, rho2, gx, gn, mu_w, h, L, top, arm_skip, arm_skip_until, max_steps, traj,
                 ts):
    """Integrate one sub-mode of CORNER (``stick``, or sliding with sense ``sig``) from state ``s`` (6,) until a
    guard fires. Returns ``(event, k, s, t)`` (k: the vertex of ``arm``/``wall``, else −1)."""
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
        dt = DTH / (abs(s[5]) + om0)
        s1 = _rk4(s, dt, qx, qy, nb, tb, db, rho2, gx, gn, mu_w, sig, stick)
        gm, which, k = _cguards(s1, w, e, le, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, stick, h, L, top, ga, skip)
        if which == EV_INCONSISTENT:
            return EV_INCONSISTENT, -1, s, t
        step = dt
        if gm <= 0.0:
            lo = 0.0
            hi = dt
            s_lo = s
            s_hi = s1
            falsi = True
            for _i in range(4 * N_BISECT):
                width = hi - lo
                tol = 1e-16 * (t + hi)
                if width <= tol:
                    break
                mid = lo + 0.5 * width
                if falsi:
                    c_lo = _cguards(s_lo, w, e, le, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, stick, h, L, top, ga,
                                    skip)[0]
                    c_hi = _cguards(s_hi, w, e, le, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, stick, h, L, top, ga,
                                    skip)[0]
                    mid = falsi_point(lo, hi, tol, c_lo, c_hi)
                sm = _rk4(s, mid, qx, qy, nb, tb, db, rho2, gx, gn, mu_w, sig, stick)
                gmid, wh, km = _cguards(sm, w, e, le, qx, qy, nb, tb, rho2, gx, gn, mu_w, sig, stick, h, L, top, ga,
                                        skip)
                if gmid <= 0.0:
                    hi = mid
                    which = wh
                    k = km
                    s_hi = sm
                else:
                    lo = mid
                    s_lo = sm
                falsi = hi - lo <= 0.5 * width
            step = hi
            s1 = s_hi
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

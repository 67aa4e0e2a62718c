"""Mode PIVOT_SLIDE of model "rigid_body" and the contact-mode selection (resets slip_start / stick_start / lift).

One vertex A on the line sliding with slip velocity v_A ≠ 0: 2 DOF (x_A, θ) with
friction −μσN, σ = sgn v_A (:func:`slide_rhs`), integrated with classical RK4,
step Δt = DTH/(|θ̇| + Ω); guards ``stick`` (v_A = 0), ``land`` (θa, θb),
``lift_off`` (N = 0), ``painleve`` (D ≤ 0) and ``leave_arm`` are checked at step
ends and located on the step length (:func:`~.bracket.locate_guard`). μ = ∞ slides with ``MU_SKID``.

On an arm at rest angle α (rad; :mod:`~.tilt`) gravity in the arm frame is
(−g_t, −g_n) = (−g sin α, −g cos α): ``g`` below is the normal component g_n and
``gt`` the one along the arm (0 for α = 0, the horizontal equations unchanged).
"""

import math

import numpy as np
from numba import njit

from .. import codes as C
from ..flight import departure_window
from .bracket import locate_guard
from .coulomb import cone_guard, cone_guard_value
from .modes import (DTH, EV_BEHIND_JOINT, EV_INCONSISTENT, EV_LAND_A, EV_LAND_B, EV_LIFT_OFF, EV_OFF_END,
                    EV_STEP_CAP, EV_STICK, EV_WALL, MODE_FLIGHT, MODE_SLIDE, MODE_STICK)
from .stick import stick_forces
from .trajectory import _put

NO_WALL = np.zeros((0, 2))
"""No vertex watched for a wall."""


@njit(cache=True)
def slide_rhs(th, w, lj, rho2, g, musig, gt=0.0):
    """PIVOT_SLIDE dynamics with friction −μσN (musig = μσ), gravity (−gt, −g) in the arm frame (m/s²).

    With c = cos θ, s = sin θ and A → CM = ℓ(c, s):
    ÿ_A = 0 gives N D = g − ℓ s θ̇², D = 1 + ℓ² c (c + μσ s)/ρ²;
    ρ² θ̈ = −ℓ N (c + μσ s);  ẍ_A = −μσ N − g_t + ℓ (s θ̈ + c θ̇²).
    Returns ``(θ̈, ẍ_A, N, D)`` (N per unit mass, m/s²); at D = 0 exactly ``(nan, nan, nan, 0)``
    (compiled code would raise ZeroDivisionError there).
    """
    c = math.cos(th)
    s = math.sin(th)
    q = c + musig * s
    D = 1.0 + lj * lj * c * q / rho2
    if D == 0.0:  # the Painlevé boundary: no finite normal force (callers refuse D ≤ 0 as inconsistent)
        return math.nan, math.nan, math.nan, 0.0
    N = (g - lj * s * w * w) / D
    thdd = -lj * q * N / rho2
    xdd = -musig * N - gt + lj * (s * thdd + c * w * w)
    return thdd, xdd, N, D


@njit(cache=True)
def _rk4_slide(xa, th, va, w, dt, lj, rho2, g, musig, gt):
    a1, b1, _n, _d = slide_rhs(th, w, lj, rho2, g, musig, gt)
    th2 = th + 0.5 * dt * w
    w2 = w + 0.5 * dt * a1
    a2, b2, _n, _d = slide_rhs(th2, w2, lj, rho2, g, musig, gt)
    th3 = th + 0.5 * dt * w2
    w3 = w + 0.5 * dt * a2
    a3, b3, _n, _d = slide_rhs(th3, w3, lj, rho2, g, musig, gt)
    th4 = th + dt * w3
    w4 = w + dt * a3
    a4, b4, _n, _d = slide_rhs(th4, w4, lj, rho2, g, musig, gt)
    va2 = va + 0.5 * dt * b1
    va3 = va + 0.5 * dt * b2
    va4 = va + dt * b3
    xa1 = xa + dt * (va + 2.0 * va2 + 2.0 * va3 + va4) / 6.0
    th1 = th + dt * (w + 2.0 * w2 + 2.0 * w3 + w4) / 6.0
    va1 = va + dt * (b1 + 2.0 * b2 + 2.0 * b3 + b4) / 6.0
    w1 = w + dt * (a1 + 2.0 * a2 + 2.0 * a3 + a4) / 6.0
    return xa1, th1, va1, w1


@njit(cache=True)
def _wall_gap(xa, th, wall, wv):
    """Guard ``wall_reach`` while the pivot slides: the least gap (m) of the part to the wall x = ``wall``.

    ``wv`` rows (ℓ_j, δ_j[, H]): vertex j at A + ℓ_j (cos(θ + δ_j), sin(θ + δ_j)) (ℓ_j = 0: the pivot, not watched on
    the face), in order around the part; a third column holds the wall's height H above the arm (m). Without it:
    L − x_j over the vertices. With it: L − x_j over the vertices below the top (one above it passes over the wall),
    and the top corner Q = (L, h + H)'s signed distance outside the part (max over the edges of n_e·(Q − v_e), n_e
    the outward unit normal): 0 where an edge meets the corner.
    """
    gmin = math.inf
    top = wv[0, 2] if wv.shape[1] > 2 and wv.shape[0] > 0 else math.inf
    n = wv.shape[0]
    area2 = 0.0
    for j in range(n):
        if wv[j, 0] > 0.0:
            c = math.cos(th + wv[j, 1])
            sn = math.sin(th + wv[j, 1])
            if wv[j, 0] * sn < top:
                gj = wall - xa - wv[j, 0] * c
                if gj < gmin:
                    gmin = gj
        j2 = (j + 1) % n
        ax = wv[j, 0] * math.cos(th + wv[j, 1])
        ay = wv[j, 0] * math.sin(th + wv[j, 1])
        bx = wv[j2, 0] * math.cos(th + wv[j2, 1])
        by = wv[j2, 0] * math.sin(th + wv[j2, 1])
        area2 += ax * by - bx * ay
    if top < math.inf:
        qx = wall - xa
        qy = top
        dmax = -math.inf
        o = 1.0 if area2 > 0.0 else -1.0  # counter-clockwise: the outward normal is the edge turned by −90°
        for j in range(n):
            j2 = (j + 1) % n
            ax = wv[j, 0] * math.cos(th + wv[j, 1])
            ay = wv[j, 0] * math.sin(th + wv[j, 1])
            ex = wv[j2, 0] * math.cos(th + wv[j2, 1]) - ax
            ey = wv[j2, 0] * math.sin(th + wv[j2, 1]) - ay
            le = math.hypot(ex, ey)
            d = o * (ey * (qx - ax) - ex * (qy - ay)) / le
            if d > dmax:
                dmax = d
        if dmax < gmin:
            gmin = dmax
    return gmin


@njit(cache=True)
def _slide_guards(s, p):
    """Least guard of PIVOT_SLIDE at the state ``s`` = (x_A, θ, v_A, θ̇) and which it is: ``(value, event, −1)``.

    The contact's own guards (:func:`~.coulomb.cone_guard`: ``lift_off`` N/g, ``stick`` σ v_A), then
    ``land`` (θ − θa, θb − θ), ``leave_arm`` (x_A + back, length − x_A) and ``wall_reach``; ``(-1,
    EV_INCONSISTENT, -1)`` where D ≤ 0 (``painleve``). ``p``: the phase's parameters (:func:`pivot_slide_walled`).
    """
    xa, th, va, w = s
    sig, ta, tb, lj, rho2, g, musig, length, back, gt, wall, wv = p
    _a, _b, N, D = slide_rhs(th, w, lj, rho2, g, musig, gt)
    if D <= 0.0:
        return -1.0, EV_INCONSISTENT, -1
    gmin, which = cone_guard(N, 0.0, va, False, sig, abs(musig), g, True)
    if th - ta < gmin:
        gmin = th - ta
        which = EV_LAND_A
    if tb - th < gmin:
        gmin = tb - th
        which = EV_LAND_B
    if xa + back < gmin:
        gmin = xa + back
        which = EV_BEHIND_JOINT
    if length - xa < gmin:
        gmin = length - xa
        which = EV_OFF_END
    if wall < math.inf:
        gw = _wall_gap(xa, th, wall, wv)
        if gw < gmin:
            gmin = gw
            which = EV_WALL
    return gmin, which, -1


@njit(cache=True)
def _guard_value(which, k, s, p):
    """The value of one guard of :func:`_slide_guards` (a smooth function of the state)."""
    xa, th, va, w = s
    sig, ta, tb, lj, rho2, g, musig, length, back, gt, wall, wv = p
    if which == EV_STICK or which == EV_LIFT_OFF:
        _a, _b, N, _D = slide_rhs(th, w, lj, rho2, g, musig, gt)
        return cone_guard_value(which, N, 0.0, va, sig, abs(musig), g)
    if which == EV_LAND_A:
        return th - ta
    if which == EV_LAND_B:
        return tb - th
    if which == EV_BEHIND_JOINT:
        return xa + back
    if which == EV_OFF_END:
        return length - xa
    if which == EV_WALL:
        return _wall_gap(xa, th, wall, wv)
    return math.nan


@njit(cache=True, inline="always")
def _advance(s, tau, p):
    """The RK4 step of length ``tau`` (s) from ``s`` = (x_A, θ, v_A, θ̇) (:func:`_slide_guards`' ``p``)."""
    sig, ta, tb, lj, rho2, g, musig, length, back, gt, wall, wv = p
    return _rk4_slide(s[0], s[1], s[2], s[3], tau, lj, rho2, g, musig, gt)


@njit(cache=True)
def pivot_slide(xa, theta, va, thdot, sig, ta, tb, lj, rho2, g, mu, length, back, t, max_steps, h, phi_off, traj, ts,
                rec, alpha=0.0):
    """Mode PIVOT_SLIDE on vertex A at (x_A, h), slip sense σ = sgn v_A, until a guard fires; see
    :func:`pivot_slide_walled` (this is it without a wall)."""
    return pivot_slide_walled(xa, theta, va, thdot, sig, ta, tb, lj, rho2, g, mu, length, back, t, max_steps, h,
                              phi_off, traj, ts, rec, alpha, math.inf, NO_WALL)


@njit(cache=True)
def pivot_slide_walled(xa, theta, va, thdot, sig, ta, tb, lj, rho2, g, mu, length, back, t, max_steps, h, phi_off, traj,
                       ts, rec, alpha, wall, wv):
    """Mode PIVOT_SLIDE on vertex A at (x_A, h), slip sense σ = sgn v_A, until a guard fires.

    ``g`` (m/s²) is gravity's magnitude and ``alpha`` the arm's rest angle (rad):
    the dynamics use g cos α normal to the arm and −g sin α along it (:func:`slide_rhs`).

    Guards ``stick`` (σ v_A = 0), ``land`` (θa, θb), ``lift_off`` (N = 0),
    ``painleve`` (D ≤ 0), ``leave_arm`` (x_A ≤ −back or > length), and with a wall at x = ``wall``
    (:mod:`~.wall`) ``wall_reach``: a vertex of ``wv`` (rows ℓ_j, δ_j relative to A) reaches it
    (``EV_WALL``). RK4, the guard located inside a step by :func:`~.bracket.locate_guard`.
    Updates N_MIN, MU_MAX, SLIP_DISTANCE. Returns ``(event, x_A, θ, v_A, θ̇, t)``.
    """
    musig = mu * sig
    gt = g * math.sin(alpha)
    g = g * math.cos(alpha)
    om = math.sqrt(g / lj)
    x_start = xa
    if mu > rec[C.MU_MAX]:
        rec[C.MU_MAX] = mu
    sample = traj.shape[0] > 0
    p = (sig, ta, tb, lj, rho2, g, musig, length, back, gt, wall, wv)
    for _ in range(max_steps):
        dt = DTH / (abs(thdot) + om)
        s0 = (xa, theta, va, thdot)
        s1 = _advance(s0, dt, p)
        gm, which, _k = _slide_guards(s1, p)
        step = dt
        if gm <= 0.0:
            hi, _w, _k, _s = locate_guard(_advance, _slide_guards, _guard_value, s0, s1, dt, which, -1, t, p)
            step = hi
            s1 = _advance(s0, hi, p)
            gm, which, _k = _slide_guards(s1, p)
        x1, th1, v1, w1 = s1
        if sample:
            while ts[1] <= t + step:
                xq, thq, _v, _w = _rk4_slide(xa, theta, va, thdot, ts[1] - t, lj, rho2, g, musig, gt)
                _put(traj, ts, ts[1], xq + lj * math.cos(thq), h + lj * math.sin(thq), thq + phi_off)
                ts[1] += ts[2]
        _a, _b, N, _D = slide_rhs(th1, w1, lj, rho2, g, musig, gt)
        if N / g < rec[C.N_MIN]:
            rec[C.N_MIN] = N / g
        xa, theta, va, thdot = x1, th1, v1, w1
        t += step
        if gm <= 0.0:
            if which == EV_STICK:
                va = 0.0
            elif which == EV_LAND_A:
                theta = ta
            elif which == EV_LAND_B:
                theta = tb
            elif which == EV_LIFT_OFF:
                if rec[C.N_MIN] > 0.0:
                    rec[C.N_MIN] = 0.0
            rec[C.SLIP_DISTANCE] += abs(xa - x_start)
            if sample:
                _put(traj, ts, t, xa + lj * math.cos(theta), h + lj * math.sin(theta), theta + phi_off)
            return which, xa, theta, va, thdot, t
    rec[C.SLIP_DISTANCE] += abs(xa - x_start)
    return EV_STEP_CAP, xa, theta, va, thdot, t


@njit(cache=True)
def slide_sense(theta, thdot, va, f_stick, lj, rho2, g, mu, alpha=0.0):
    """Reset ``slip_start``: the slip sense σ (±1) of a consistent sliding motion, 0 if none.

    v_A ≠ 0 fixes σ = sgn v_A (needs D > 0). From v_A = 0 the slip starts against
    the friction that sticking would need (σ = −sgn F); it must satisfy σ ẍ_A > 0
    and D > 0, else the other sense is tried. ``alpha``: the arm's rest angle (rad).
    """
    gt = g * math.sin(alpha)
    g = g * math.cos(alpha)
    if va != 0.0:
        sig = 1.0 if va > 0.0 else -1.0
        _a, _x, _n, D = slide_rhs(theta, thdot, lj, rho2, g, mu * sig, gt)
        return sig if D > 0.0 else 0.0
    sig = -1.0 if f_stick > 0.0 else 1.0
    for _ in range(2):
        _a, xdd, _n, D = slide_rhs(theta, thdot, lj, rho2, g, mu * sig, gt)
        if D > 0.0 and sig * xdd > 0.0:
            return sig
        sig = -sig
    return 0.0


@njit(cache=True)
def select_contact_mode(theta, thdot, va, lj, rho2, g, mu, mu_s, from_slip, alpha=0.0):
    """Which mode continues from a one-vertex contact state (the single-contact Coulomb LCP).

    In order: ``PIVOT_STICK`` (v_A = 0, N > 0, |F| ≤ μN; not offered right after a
    ``slip``/``lift_off`` guard fired); ``FLIGHT`` if the free motion separates
    (:func:`~throwmap.kernels.flight.departure_window` > 0); ``PIVOT_SLIDE`` with a consistent sense
    (D > 0, N > 0, and σ ẍ_A > 0 when starting from v_A = 0 — right after ``slip``
    ẍ_A = 0 exactly, so σ = −sgn F is taken); else no consistent motion.
    ``mu_s`` is the coefficient used for sliding (μ, or MU_SKID for μ = ∞).
    ``alpha`` is the arm's rest angle (rad): normal gravity g cos α, along the arm
    −g sin α, sticking forces as :func:`~.stick.stick_forces`.
    Returns ``(mode, σ)`` with mode −1 for INCONSISTENT.
    """
    gt = g * math.sin(alpha)
    gn = g * math.cos(alpha)
    I = rho2 + lj * lj
    c = math.cos(theta)
    s = math.sin(theta)
    if va != 0.0:
        sig = 1.0 if va > 0.0 else -1.0
        _a, _x, N, D = slide_rhs(theta, thdot, lj, rho2, gn, mu_s * sig, gt)
        if D > 0.0 and N > 0.0:
            return MODE_SLIDE, sig
        if departure_window(-lj * c, -lj * s, thdot, gn, lj, gn) > 0.0:
            return MODE_FLIGHT, 0.0
        return -1, 0.0
    nf, ff = stick_forces(theta, thdot, lj, I, g, alpha)
    if not from_slip and nf > 0.0 and abs(ff) <= mu * nf:
        return MODE_STICK, 0.0
    if departure_window(-lj * c, -lj * s, thdot, gn, lj, gn) > 0.0:
        return MODE_FLIGHT, 0.0
    sig = -1.0 if ff > 0.0 else 1.0
    for _ in range(2):
        _a, xdd, N, D = slide_rhs(theta, thdot, lj, rho2, gn, mu_s * sig, gt)
        if D > 0.0 and N > 0.0 and (sig * xdd > 0.0 or from_slip):
            return MODE_SLIDE, sig
        if from_slip:
            break
        sig = -sig
    if from_slip:
        sig = -sig
        _a, xdd, N, D = slide_rhs(theta, thdot, lj, rho2, gn, mu_s * sig, gt)
        if D > 0.0 and N > 0.0 and sig * xdd > 0.0:
            return MODE_SLIDE, sig
    return -1, 0.0

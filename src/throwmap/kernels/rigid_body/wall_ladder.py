"""Two contacts at once in model "rigid_body": a vertex A on the arm and a vertex P on the wall's face.

The part leans on the arm and the wall like a ladder. Its impact there (:func:`multi_contact_impact`)
and its motion while both contacts slide (mode LADDER, :func:`ladder_phase`) are modelled here;
:mod:`.wall_follow` strings them into the automaton.

Impact (velocity-level, Moreau): one impulse per contact with Coulomb's law on the *post-impact*
velocities — at each contact either open (no impulse, normal velocity ≥ 0), sticking (normal and
tangential velocity 0, impulse inside the cone) or sliding (normal velocity 0, impulse on the cone's
edge against the slip). The 2-contact linear complementarity problem is solved exactly by trying
every combination (:func:`multi_contact_impact`); this is the law of time-stepping engines
(pymunk, Siconos' Moreau–Jean). For one contact the automaton keeps Routh's law
(:mod:`~.impact`); where both meet, a two-contact process in impulse space has no unique form.

LADDER (A on the line y = h, P on the face x = L, both sliding): one degree of freedom, the
orientation φ; with the CM offsets r_A = R(φ) w_A and r_P = R(φ) w_P the CM is
(L − r_Px, h − r_Ay). With d = P − A, A slips at d_y φ̇ along +x̂ and P at d_x φ̇ along +ŷ, so
both slip senses are σ = sgn φ̇ (d_x, d_y > 0). Forces (F_A, N_A) at A with F_A = −μ σ N_A and
(−N_P, F_P) at P with F_P = −μ_w σ N_P; unit mass, inertia ρ², gravity (g_x, −g_n)::

    r_Py ω̇ + μσ N_A + N_P                           = g_x − r_Px ω²
   −r_Ax ω̇ − N_A + μ_w σ N_P                        = −g_n − r_Ay ω²
    ρ² ω̇ − (r_Ax + μσ r_Ay) N_A − (r_Py − μ_w σ r_Px) N_P = 0

(:func:`ladder_rhs`, Cramer's rule; a non-positive determinant of the normal-force block —
Painlevé — is INCONSISTENT). Integration: RK4 in (φ, ω), step DTH/(|ω| + Ω); guards located in the
step as :func:`~.slide._locate_guard`.
"""

import math

import numpy as np
from numba import njit

from .modes import DTH, EV_INCONSISTENT, EV_LIFT_OFF, EV_STEP_CAP, EV_STICK, N_BISECT
from .bracket import falsi_point
from .trajectory import _put

C_OPEN = 0
C_STICK = 1
C_SLIDE = 2
"""Contact states after :func:`multi_contact_impact`."""

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
def multi_contact_impact(vx, vy, om, pts, nrm, mus, m, rho2, st):
    """Velocity-level plastic impact at ``m`` contacts (module docstring): CM → contact i = ``pts[i]`` (m), unit
    normal ``nrm[i]`` into the part, Coulomb ``mus[i]`` (``inf``: no slip, 0: frictionless).

    Every assignment of the contacts to open / sticking / sliding (each sense) is tried, those with the
    fewest open contacts first and sticking before sliding, and the first whose impulses and post-impact
    velocities satisfy every condition to 1e-10 of the velocity scale is returned: ``(ok, vx⁺, vy⁺, ω⁺)``,
    with the states in ``st`` (m,) (C_OPEN, C_STICK, C_SLIDE); ok False: none is consistent.
    """
    rows = np.empty((2 * m, 3))  # normal and tangent (t = n turned by −90°) rows in (v_x, v_y, ω)
    u = np.empty(2 * m)
    scale = abs(vx) + abs(vy) + 1e-300
    for i in range(m):
        nx = nrm[i, 0]
        ny = nrm[i, 1]
        rx = pts[i, 0]
        ry = pts[i, 1]
        rows[2 * i, 0] = nx
        rows[2 * i, 1] = ny
        rows[2 * i, 2] = rx * ny - ry * nx
        rows[2 * i + 1, 0] = ny
        rows[2 * i + 1, 1] = -nx
        rows[2 * i + 1, 2] = -rx * nx - ry * ny
        scale += abs(om) * math.hypot(rx, ry)
    for q in range(2 * m):
        u[q] = rows[q, 0] * vx + rows[q, 1] * vy + rows[q, 2] * om
    tol = 1e-10 * scale
    code = np.empty(m, dtype=np.int64)
    total = 4 ** m
    for n_open in range(m + 1):
        for n_slide in range(m - n_open + 1):
            for c in range(total):
                r = c
                no = 0
                ns = 0
                for i in range(m):
                    code[i] = r % 4  # 0 open, 1 stick, 2 slide +, 3 slide −
                    r //= 4
                    if code[i] == 0:
                        no += 1
                    elif code[i] >= 2:
                        ns += 1
                if no != n_open or ns != n_slide:
                    continue
                ok, vxp, vyp, wp = _try(rows, u, vx, vy, om, rho2, code, mus, m, tol)
                if ok:
                    for i in range(m):
                        st[i] = C_OPEN if code[i] == 0 else (C_STICK if code[i] == 1 else C_SLIDE)
                    return True, vxp, vyp, wp
    return False, vx, vy, om


@njit(cache=True)
def _try(rows, u, vx, vy, om, rho2, code, mus, m, tol):  # noqa: C901
    """One assignment ``code`` (0 open, 1 stick, 2/3 sliding with post-impact slip +/−) of
    :func:`multi_contact_impact`. Returns ``(ok, vx⁺, vy⁺, ω⁺)``."""
    dirs = np.empty((2 * m, 3))
    eqs = np.empty(2 * m, dtype=np.int64)
    k = 0
    for i in range(m):
        ci = code[i]
        mu = mus[i]
        if ci == 0:
            continue
        if ci == 1 and mu == 0.0:
            return False, vx, vy, om
        if ci >= 2 and math.isinf(mu):
            return False, vx, vy, om
        if ci == 1:
            for q in range(2):
                dirs[k, 0] = rows[2 * i + q, 0]
                dirs[k, 1] = rows[2 * i + q, 1]
                dirs[k, 2] = rows[2 * i + q, 2] / rho2
                eqs[k] = 2 * i + q
                k += 1
        else:
            f = -(1.0 if ci == 2 else -1.0) * mu
            dirs[k, 0] = rows[2 * i, 0] + f * rows[2 * i + 1, 0]
            dirs[k, 1] = rows[2 * i, 1] + f * rows[2 * i + 1, 1]
            dirs[k, 2] = (rows[2 * i, 2] + f * rows[2 * i + 1, 2]) / rho2
            eqs[k] = 2 * i
            k += 1
    A = np.empty((k, k))
    b = np.empty(k)
    for a in range(k):
        e = eqs[a]
        for c in range(k):
            A[a, c] = rows[e, 0] * dirs[c, 0] + rows[e, 1] * dirs[c, 1] + rows[e, 2] * dirs[c, 2]
        b[a] = -u[e]
    p = _solve(A, b, k) if k > 0 else np.empty(0)
    if k > 0 and p.shape[0] == 0:
        return False, vx, vy, om
    vxp = vx
    vyp = vy
    wp = om
    for c in range(k):
        vxp += p[c] * dirs[c, 0]
        vyp += p[c] * dirs[c, 1]
        wp += p[c] * dirs[c, 2]
    j = 0
    for i in range(m):
        ci = code[i]
        un = rows[2 * i, 0] * vxp + rows[2 * i, 1] * vyp + rows[2 * i, 2] * wp
        ut = rows[2 * i + 1, 0] * vxp + rows[2 * i + 1, 1] * vyp + rows[2 * i + 1, 2] * wp
        if ci == 0:
            if un < -tol:
                return False, vx, vy, om
            continue
        pn = p[j]
        if pn < -tol:
            return False, vx, vy, om
        if ci == 1:
            if abs(p[j + 1]) > mus[i] * max(pn, 0.0) + tol:
                return False, vx, vy, om
            j += 2
        else:
            if (1.0 if ci == 2 else -1.0) * ut < -tol:
                return False, vx, vy, om
            j += 1
    return True, vxp, vyp, wp


@njit(cache=True)
def _solve(A, b, k):
    """Gaussian elimination with partial pivoting of the k × k system; an empty array if it is singular."""
    M = np.empty((k, k + 1))
    M[:, :k] = A
    M[:, k] = b
    big = 0.0
    for i in range(k):
        for j in range(k):
            big = max(big, abs(A[i, j]))
    for c in range(k):
        piv = c
        for r in range(c + 1, k):
            if abs(M[r, c]) > abs(M[piv, c]):
                piv = r
        if abs(M[piv, c]) <= 1e-13 * big:
            return np.empty(0)
        if piv != c:
            for q in range(k + 1):
                tmp = M[c, q]
                M[c, q] = M[piv, q]
                M[piv, q] = tmp
        for r in range(c + 1, k):
            f = M[r, c] / M[c, c]
            for q in range(c, k + 1):
                M[r, q] -= f * M[c, q]
    x = np.empty(k)
    for c in range(k - 1, -1, -1):
        sacc = M[c, k]
        for q in range(c + 1, k):
            sacc -= M[c, q] * x[q]
        x[c] = sacc / M[c, c]
    return x


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


@njit(cache=True)
def _lguard(which, k, phi, om, w, ja, jp, rho2, mu, mu_w, sig, gx, gn, h, L, top, back, ga):
    """Value of one LADDER guard (> 0: not fired); see :func:`_lguards`."""
    if which == EV_STOP:
        return sig * om
    if which == EV_A_OFF or which == EV_P_OFF:
        _a, na, npw, _d = ladder_rhs(phi, om, w[ja], w[jp], rho2, mu, mu_w, sig, gx, gn)
        return (na if which == EV_A_OFF else npw) / ga
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
def _lguards(phi, om, w, ja, jp, rho2, mu, mu_w, sig, gx, gn, h, L, top, back, ga):
    """Least LADDER guard: ``(value, which, k)``; ``(-1, EV_INCONSISTENT, -1)`` at D ≤ 0 (Painlevé).

    Guards: ``stop`` σω; ``a_off`` N_A/|g|; ``p_off`` N_P/|g|; ``land`` y_k − h (k ≠ A, P); ``plane``
    L − x_k (k ≠ A, P); ``foot`` y_P − h or L − x_A; ``p_top`` h + H − y_P; ``behind`` x_A + back.
    """
    _a, na, npw, D = ladder_rhs(phi, om, w[ja], w[jp], rho2, mu, mu_w, sig, gx, gn)
    if not D > 0.0:
        return -1.0, EV_INCONSISTENT, -1
    gmin = sig * om
    which = EV_STOP
    kk = -1
    if na / ga < gmin:
        gmin = na / ga
        which = EV_A_OFF
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
    for _ in range(max_steps):
        dt = DTH / (abs(om) + om0)
        p1, w1 = _rk4(phi, om, dt, wa, wpv, rho2, mu, mu_w, sig, gx, gn)
        gm, which, k = _lguards(p1, w1, w, ja, jp, rho2, mu, mu_w, sig, gx, gn, h, L, top, back, ga)
        if which == EV_INCONSISTENT:
            return EV_INCONSISTENT, -1, phi, om, t
        step = dt
        if gm <= 0.0:
            lo = 0.0
            hi = dt
            ph_lo, w_lo = phi, om
            ph_hi, w_hi = p1, w1
            falsi = True
            for _i in range(4 * N_BISECT):
                width = hi - lo
                tol = 1e-16 * (t + hi)
                if width <= tol:
                    break
                mid = lo + 0.5 * width
                if falsi:
                    c_lo = _lguard(which, k, ph_lo, w_lo, w, ja, jp, rho2, mu, mu_w, sig, gx, gn, h, L, top, back, ga)
                    c_hi = _lguard(which, k, ph_hi, w_hi, w, ja, jp, rho2, mu, mu_w, sig, gx, gn, h, L, top, back, ga)
                    mid = falsi_point(lo, hi, tol, c_lo, c_hi)
                pm, wm = _rk4(phi, om, mid, wa, wpv, rho2, mu, mu_w, sig, gx, gn)
                gmid, wh, km = _lguards(pm, wm, w, ja, jp, rho2, mu, mu_w, sig, gx, gn, h, L, top, back, ga)
                if gmid <= 0.0:
                    hi = mid
                    which = wh
                    k = km
                    ph_hi, w_hi = pm, wm
                else:
                    lo = mid
                    ph_lo, w_lo = pm, wm
                falsi = hi - lo <= 0.5 * width
            step = hi
            p1, w1 = ph_hi, w_hi
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

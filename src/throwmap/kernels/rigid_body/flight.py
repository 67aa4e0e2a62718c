"""Mode FLIGHT of model "rigid_body": reset ``release`` (Eq. 1), guards ``touch`` and ``leave_arm``.

Ballistic motion from an arbitrary state (paper Sec. III-B, Eqs. 1–3): with
(ru_j, rv_j) = R(φ0) w_j and c0_j = y0 − h + rv_j, vertex j's gap above the line
after a flight time t is G_j(t) = c0_j + (v_y + ω ru_j) t − ½ g t² − 2 rv_j sin²(ωt/2)
+ ru_j (sin ωt − ωt) (:func:`first_contact_state`).
"""

import math

from numba import njit

from .. import codes as C
from .trajectory import _put


@njit(cache=True)
def release(x0, dk, beta_k, omega, h, w, ell, ru, rv, c0):
    """Reset ``release`` (Eq. 1): rest on a side at height ``dk`` (m) and x0, the arm turning at ω (rad/s).

    CM velocity ω × (x0, h + d) = (−(h + d) ω, x0 ω), spin ω. Fills the flight frame
    (``ru``, ``rv``, ``c0``; the support vertices' gaps snapped to exactly 0) and
    returns ``(x, y, φ, v_x, v_y, ω)``.
    """
    cb = math.cos(beta_k)
    sb = math.sin(beta_k)
    for j in range(w.shape[0]):
        ru[j] = cb * w[j, 0] - sb * w[j, 1]
        rv[j] = sb * w[j, 0] + cb * w[j, 1]
        c0[j] = dk + rv[j]
        if abs(c0[j]) <= 1e-15 * ell[j]:
            c0[j] = 0.0
    return x0, h + dk, beta_k, -(h + dk) * omega, x0 * omega, omega


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
def leave_arm(px, length):
    """Guard ``leave_arm`` for a contact at world x = ``px``: BEHIND_JOINT (x ≤ 0), OFF_END (x > length), else OK."""
    if px <= 0.0:
        return C.BEHIND_JOINT
    if px > length:
        return C.OFF_END
    return C.OK


@njit(cache=True)
def fly(t, x, y, vx, vy, phi, om, c0, ru, rv, g, ell, excl_j, excl_t, tol, max_iter, traj, ts):
    """Mode FLIGHT until guard ``touch``; samples the trajectory on the way.

    Returns ``(j, t, x, y, v_y, φ, r_x, r_y)`` at contact: vertex j (−1 if the
    search hit ``max_iter``) and its offset (r_x, r_y) from the CM (m).
    """
    tc, jc = first_contact_state(c0, ru, rv, vy, om, g, ell, excl_j, excl_t, tol, max_iter)
    if jc < 0:
        return jc, t, x, y, vy, phi, 0.0, 0.0
    if traj.shape[0] > 0:
        while ts[1] <= t + tc:
            tq = ts[1] - t
            _put(traj, ts, ts[1], x + vx * tq, y + vy * tq - 0.5 * g * tq * tq, phi + om * tq)
            ts[1] += ts[2]
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
    return jc, t, x, y, vy, phi, rx, ry


@njit(cache=True)
def _gap_state(t, j, c0, ru, rv, vy, w, g):
    """Gap of vertex j above the line at flight time t (cancellation-free) and its rate."""
    wt = w * t
    hs = math.sin(0.5 * wt)
    s = math.sin(wt)
    c = math.cos(wt)
    gap = c0[j] + (vy + w * ru[j]) * t - 0.5 * g * t * t - 2.0 * rv[j] * hs * hs + ru[j] * (s - wt)
    dg = vy - g * t + w * (ru[j] * c - rv[j] * s)
    return gap, dg


@njit(cache=True)
def first_contact_state(c0, ru, rv, vy, w, g, ell, excl_j, excl_t, tol, max_iter):
    """Guard ``touch``: earliest t ≥ 0 at which a vertex reaches y = h, from any flight state.

    Vertex j's gap is G_j(t) = c0_j + (v_y + ω ru_j) t − ½ g t² − 2 rv_j sin²(ωt/2)
    + ru_j (sin ωt − ωt), with (ru_j, rv_j) = R(φ0) w_j and c0_j = y0 − h + rv_j its gap
    at t = 0 (exactly 0 for a vertex on the line). As in
    :func:`~throwmap.kernels.flight.first_contact`, G_j'' ≥ −(g + ω² ℓ_j) makes each
    step the smallest positive root of a quadratic lower bound, so no crossing is
    missed; a Newton polish removes the stopping error. Vertex ``excl_j`` (one that
    just left the line) is known to stay above it for t < ``excl_t``.
    Returns ``(t, j)``, j = −1 when ``max_iter`` steps did not reach contact.
    """
    n = ru.shape[0]
    t = 0.0
    for _ in range(max_iter):
        wt = w * t
        s = math.sin(wt)
        c = math.cos(wt)
        hs = math.sin(0.5 * wt)
        cm1 = -2.0 * hs * hs
        smw = s - wt
        base = -0.5 * g * t * t
        dbase = vy - g * t
        step = math.inf
        jmin = -1
        gmin = math.inf
        for j in range(n):
            gap = c0[j] + (vy + w * ru[j]) * t + base + rv[j] * cm1 + ru[j] * smw
            dg = dbase + w * (ru[j] * c - rv[j] * s)
            if j == excl_j and t < excl_t:
                sj = excl_t - t
                gp = gap if gap > 0.0 else 0.0
                M = g + w * w * ell[j]
                disc = math.sqrt(dg * dg + 2.0 * M * gp)
                if gp > 0.0 or dg > 0.0:
                    sq = (dg + disc) / M if dg >= 0.0 else 2.0 * gp / (disc - dg)
                    if sq > sj:
                        sj = sq
                if sj < step:
                    step = sj
                continue
            if gap <= tol and (t > 0.0 or dg <= 0.0):
                if gap < gmin:
                    gmin = gap
                    jmin = j
                continue
            gp = gap if gap > 0.0 else 0.0
            M = g + w * w * ell[j]
            disc = math.sqrt(dg * dg + 2.0 * M * gp)
            if dg >= 0.0:
                sj = (dg + disc) / M
            else:
                sj = 2.0 * gp / (disc - dg)
            if sj < step:
                step = sj
        if jmin >= 0:
            if t > 0.0 and gmin > 0.0:
                for _ in range(3):
                    gap, dg = _gap_state(t, jmin, c0, ru, rv, vy, w, g)
                    if dg >= 0.0:
                        break
                    st = -gap / dg
                    if abs(st) > 0.05 * t:
                        break
                    t += st
                    if abs(st) <= 1e-15 * t:
                        break
            return t, jmin
        t += step
    return t, -1


@njit(cache=True)
def departure_window(un, rx, ry, w, g, lj):
    """Time for which a vertex that just left the line (gap 0, rate un ≥ 0) stays above it.

    Exact Taylor bound of its gap G(s) ≥ G' s + ½G'' s² + G''' s³/6 − ω⁴ℓ s⁴/24
    with G' = un, G'' = −g − ω² r_y, G''' = −ω³ r_x; returns 0.9 × the positive
    root of ½G'' + G''' s/6 − ω⁴ℓ s²/24 (G' ≥ 0 only helps), or 0 if none.
    """
    g2 = -g - w * w * ry
    g3 = -w * w * w * rx
    if g2 < 0.0 and g2 > -1e-9 * g:
        g2 = 0.0
    if g2 < 0.0:
        return 0.0
    a = w * w * w * w * lj / 24.0
    b = g3 / 6.0
    c = 0.5 * g2
    if a <= 0.0:
        if b > 0.0 or c > 0.0:
            return 1.0
        return 0.0
    disc = b * b + 4.0 * a * c
    root = (b + math.sqrt(disc)) / (2.0 * a)
    if root <= 0.0:
        return 0.0
    return 0.9 * root


@njit(cache=True)
def lift(px, h, lj, theta, thdot, va, phi, g, w, ru, rv, c0, jp):
    """Reset ``lift``: pivot vertex ``jp`` at (px, h) leaves the line (PIVOT_* → FLIGHT) with the contact's velocity.

    Fills the flight frame and returns ``(x, y, v_x, v_y, ω, excl_t)``: vertex jp is
    excluded from ``touch`` for ``excl_t`` s (:func:`departure_window`); ``excl_t`` ≤ 0
    means the free motion would sink it (no consistent contact: INCONSISTENT).
    """
    c = math.cos(theta)
    s = math.sin(theta)
    x = px + lj * c
    y = h + lj * s
    vx = va - thdot * lj * s
    vy = thdot * lj * c
    rx = -lj * c
    un = vy + thdot * rx
    excl_t = departure_window(un if un > 0.0 else 0.0, rx, -lj * s, thdot, g, lj)
    if excl_t > 0.0:
        flight_frame(phi, y, h, w, ru, rv, c0, jp)
    return x, y, vx, vy, thdot, excl_t

"""Ballistic flight after an impulsive release and the first contact (paper Sec. III-B, Eqs. 1–3).

Release (Eq. 1, with g > 0 along −y: the draft's ``+½gt²`` needs a signed g):
the part leaves the arm moving rigidly with it, CM velocity ω × r = ω(−(h+d), x0),
spin ω. Then

    x(t) = x0 − (h + d) ω t,   y(t) = h + d + x0 ω t − ½ g t²,   φ(t) = ω t.

First contact (Eq. 3, for every vertex, not only the left support vertex): the
gap of vertex j above the line y = h is

    G_j(t) = d + x0 ω t − ½ g t² + u_j sin ωt + v_j cos ωt,

with (u_j, v_j) the vertex relative to the CM at the rest orientation. It is
evaluated in the cancellation-free form

    G_j(t) = (d + v_j) + (x0 + u_j) ω t − ½ g t² − 2 v_j sin²(ωt/2) + u_j (sin ωt − ωt),

where d + v_j is exactly 0 for the support vertices, so the tiny flights of starts
just in front of the joint keep their relative accuracy.
"""

import math

from numba import njit


@njit(cache=True)
def _gap(t, j, x0, d, omega, g, pu, pv, ell):
    """Gap G_j(t) (m) in the cancellation-free form, and its derivative (m/s)."""
    wt = omega * t
    hs = math.sin(0.5 * wt)
    s = math.sin(wt)
    c = math.cos(wt)
    c0 = d + pv[j]
    if abs(c0) <= 1e-15 * ell[j]:
        c0 = 0.0
    gap = c0 + (x0 + pu[j]) * wt - 0.5 * g * t * t - 2.0 * pv[j] * hs * hs + pu[j] * (s - wt)
    dg = omega * x0 - g * t + omega * (pu[j] * c - pv[j] * s)
    return gap, dg


@njit(cache=True)
def _polish(t, j, x0, d, omega, g, pu, pv, ell):
    """A few Newton steps on G_j from the safe side; each step is capped at 0.05 t."""
    for _ in range(3):
        gap, dg = _gap(t, j, x0, d, omega, g, pu, pv, ell)
        if dg >= 0.0:
            break
        step = -gap / dg
        if abs(step) > 0.05 * t:
            break
        t += step
        if abs(step) <= 1e-15 * t:
            break
    return t


@njit(cache=True)
def first_contact(x0, d, omega, g, pu, pv, ell, tol, max_iter):
    """Earliest t > 0 at which any vertex reaches the line y = h.

    Guarantee: no crossing before the returned time is missed. Since
    ``G_j'' = −g − ω²(u_j sin ωt + v_j cos ωt) ≥ −(g + ω² |p_j|) =: −M_j``, every
    gap obeys ``G_j(t+s) ≥ G_j + G_j' s − ½ M_j s²``; each step is the smallest
    positive root of that lower bound over all vertices, so all gaps stay ≥ 0
    (up to rounding) and the iteration approaches the first root from below in
    time, quadratically once near a transversal crossing. It stops when the
    smallest gap is ≤ ``tol`` (m).

    A short Newton polish on the touching vertex's gap then removes the time error
    ``tol / |G_j'|`` left by stopping at a positive gap.

    Returns ``(t, j)``; ``j = -1`` if ``max_iter`` steps did not reach contact.
    """
    n = pu.shape[0]
    t = 0.0
    for _ in range(max_iter):
        wt = omega * t
        s = math.sin(wt)
        c = math.cos(wt)
        hs = math.sin(0.5 * wt)
        cm1 = -2.0 * hs * hs  # cos ωt − 1 without cancellation
        smw = s - wt  # sin ωt − ωt
        base = -0.5 * g * t * t
        dbase = omega * x0 - g * t
        step = math.inf
        jmin = -1
        gmin = math.inf
        for j in range(n):
            c0 = d + pv[j]
            if abs(c0) <= 1e-15 * ell[j]:
                c0 = 0.0  # a support vertex: exactly on the arm at rest
            gap = c0 + (x0 + pu[j]) * wt + base + pv[j] * cm1 + pu[j] * smw
            dg = dbase + omega * (pu[j] * c - pv[j] * s)
            if gap <= tol and (t > 0.0 or dg <= 0.0):
                if gap < gmin:
                    gmin = gap
                    jmin = j
                continue
            gp = gap if gap > 0.0 else 0.0
            M = g + omega * omega * ell[j]
            disc = math.sqrt(dg * dg + 2.0 * M * gp)
            if dg >= 0.0:
                sj = (dg + disc) / M
            else:
                sj = 2.0 * gp / (disc - dg)
            if sj < step:
                step = sj
        if jmin >= 0:
            if t > 0.0 and gmin > 0.0:
                t = _polish(t, jmin, x0, d, omega, g, pu, pv, ell)
            return t, jmin
        t += step
    return t, -1

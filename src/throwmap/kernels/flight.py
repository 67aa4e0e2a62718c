"""Ballistic flight after an impulsive release and the first contact (paper Sec. III-B, Eqs. 1–3).

Release (Eq. 1, with g > 0 along −y: the draft's ``+½gt²`` needs a signed g):
the part leaves the arm moving rigidly with it, CM velocity ω × r = ω(−(h+d), x0),
spin ω. Then

    x(t) = x0 − (h + d) ω t,   y(t) = h + d + x0 ω t − ½ g t²,   φ(t) = ω t.

First contact (Eq. 3, for every vertex, not only the left support vertex): the
gap of vertex j above the line y = h is

    G_j(t) = d + x0 ω t − ½ g t² + u_j sin ωt + v_j cos ωt,

with (u_j, v_j) the vertex relative to the CM at the rest orientation.
"""

import math

from numba import njit


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

    Returns ``(t, j)``; ``j = -1`` if ``max_iter`` steps did not reach contact.
    """
    n = pu.shape[0]
    t = 0.0
    for _ in range(max_iter):
        wt = omega * t
        s = math.sin(wt)
        c = math.cos(wt)
        base = d + omega * x0 * t - 0.5 * g * t * t
        dbase = omega * x0 - g * t
        step = math.inf
        jmin = -1
        gmin = math.inf
        for j in range(n):
            gap = base + pu[j] * s + pv[j] * c
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
            return t, jmin
        t += step
    return t, -1

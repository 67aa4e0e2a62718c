"""Release and ballistic flight up to the first contact (paper Sec. III-B, Eqs. 1–3).

Shared by every analytic model ("paper", "small_angle", "rigid_body").

Release (Eq. 1, with g > 0 along −y: the draft's ``+½gt²`` needs a signed g):
the part leaves the arm moving rigidly with it, CM velocity ω × r = ω(−(h+d), x0),
spin ω (:func:`release_state`). Then

    x(t) = x0 − (h + d) ω t,   y(t) = h + d + x0 ω t − ½ g t²,   φ(t) = ω t.

First contact (Eq. 3, for every vertex, not only the left support vertex), from
any flight state: with (u_j, v_j) = R(φ0) w_j the vertex relative to the CM
(:func:`rest_offsets` at a rest orientation) and c0_j = y0 − h + v_j its gap at
t = 0 (:func:`gap_constants`), the gap of vertex j above the line y = h is

    G_j(t) = c0_j + (v_y + ω u_j) t − ½ g t² − 2 v_j sin²(ωt/2) + u_j (sin ωt − ωt),

a cancellation-free form of c0_j + v_y t − ½ g t² + u_j (sin ωt − ωt) + … in which
c0_j is exactly 0 for a vertex on the line (the support vertices at release), so
the tiny flights of starts just in front of the joint keep their relative accuracy.
After the release of model "paper", v_y = x0 ω and c0_j = d + v_j.
"""

import math

import numpy as np
from numba import njit

SNAP = 1e-15
"""Relative size (of ℓ_j) below which a gap constant c0_j is snapped to exactly 0."""

MAX_SPIN_ANGLE = 1e9
"""Largest spin angle ω t (rad) a flight may reach before its first contact.

Beyond it double precision no longer resolves the orientation (ulp(1e9) ≈ 1.2e-7 rad),
so the contact vertex and the impact are not determined by the inputs: the search
stops with :data:`UNRESOLVED_J` and the models report status UNRESOLVED, never a
number. (Such flights need launch speeds far beyond any arm: e.g. ω = 1e6 rad/s at
x = 2e8 m.)"""

UNRESOLVED_J = -2
"""Vertex returned by :func:`touch_time` when the flight passed :data:`MAX_SPIN_ANGLE`."""


@njit(cache=True, inline="always")
def release_state(x0, d, h, omega):
    """CM velocity (m/s) and spin (rad/s) just after release from rest at ``x0`` on a side at ``d`` (Eq. 1).

    The part moves rigidly with the arm turning at ``omega`` about the joint:
    v = ω × (x0, h + d) = (−(h + d) ω, x0 ω), spin ω. Returns ``(vx, vy, w)``.
    """
    return -(h + d) * omega, x0 * omega, omega


@njit(cache=True)
def rest_offsets(w, beta_k):
    """Vertices relative to the CM at orientation ``beta_k`` (rad): ``(u, v)`` with (u_j, v_j) = R(β_k) w_j (m)."""
    n = w.shape[0]
    cb = math.cos(beta_k)
    sb = math.sin(beta_k)
    u = np.empty(n)
    v = np.empty(n)
    for j in range(n):
        u[j] = cb * w[j, 0] - sb * w[j, 1]
        v[j] = sb * w[j, 0] + cb * w[j, 1]
    return u, v


@njit(cache=True, inline="always")
def gap_constants(dy, rv, ell, c0):
    """Fill ``c0`` with the gaps c0_j = dy + v_j (m) of the vertices above the line at t = 0.

    ``dy`` = y0 − h is the CM height above the arm line. A gap below ``SNAP`` ℓ_j
    is set to exactly 0: that vertex is on the line (a support vertex at rest).
    """
    for j in range(rv.shape[0]):
        c = dy + rv[j]
        if abs(c) <= SNAP * ell[j]:
            c = 0.0
        c0[j] = c


@njit(cache=True, inline="always")
def gap(t, j, c0, b, ru, rv, vy, w, g):
    """Gap G_j(t) (m) of vertex j above the line at flight time ``t`` (s), and its rate (m/s).

    ``b[j]`` = v_y + ω u_j is the gap's rate at t = 0 (see :func:`touch_time`).
    """
    wt = w * t
    hs = math.sin(0.5 * wt)
    hc = math.cos(0.5 * wt)
    s = 2.0 * hs * hc  # sin ωt
    cm1 = -2.0 * hs * hs  # cos ωt − 1
    gj = c0[j] + b[j] * t - 0.5 * g * t * t + rv[j] * cm1 + ru[j] * (s - wt)
    dg = vy - g * t + w * (ru[j] * (1.0 + cm1) - rv[j] * s)
    return gj, dg


@njit(cache=True, inline="always")
def _polish(t, gj, dg, j, c0, b, ru, rv, vy, w, g):
    """A few Newton steps on G_j from the safe side, starting from its value ``gj`` and rate ``dg`` at t.

    Each step is capped at 0.05 t.
    """
    for it in range(3):
        if it > 0:
            gj, dg = gap(t, j, c0, b, ru, rv, vy, w, g)
        if dg >= 0.0:
            break
        st = -gj / dg
        if abs(st) > 0.05 * t:
            break
        t += st
        if abs(st) <= 1e-15 * t:
            break
    return t


@njit(cache=True, inline="always")
def _lower_bound_step(gj, dg, M):
    """Smallest positive root s of gj + dg s − ½ M s² (gj clipped at 0): a step that cannot pass a root."""
    gp = gj if gj > 0.0 else 0.0
    disc = math.sqrt(dg * dg + 2.0 * M * gp)
    if dg >= 0.0:
        return (dg + disc) / M
    return 2.0 * gp / (disc - dg)


@njit(cache=True, inline="always")
def touch_time(c0, b, ru, rv, vy, w, g, ell, excl_j, excl_t, tol, max_iter):
    """Guard ``touch``: earliest t ≥ 0 (s) at which any vertex reaches the line y = h (Eq. 3).

    As :func:`first_contact`, with the gaps' initial rates b_j = v_y + ω u_j (m/s)
    given by the caller: after a release (v_y = x0 ω) b_j = ω (x0 + u_j) is free of
    the cancellation that v_y + ω u_j suffers for a support vertex just in front
    of the joint (x0 + u_L → 0), so those tiny flights keep their relative accuracy.

    ``c0`` gaps at t = 0 (m, :func:`gap_constants`), ``(ru, rv)`` vertex offsets
    at t = 0 (m), ``vy`` CM vertical velocity (m/s), ``w`` spin (rad/s), ``ell``
    vertex distances |w_j| (m). Vertex ``excl_j`` (one that just left the line;
    −1: none) is known to stay above it for t < ``excl_t``.

    Guarantee: no crossing before the returned time is missed. Since
    G_j'' = −g − ω²(u_j sin ωt + v_j cos ωt) ≥ −(g + ω² ℓ_j) =: −M_j, every gap
    obeys G_j(t+s) ≥ G_j + G_j' s − ½ M_j s²; each step is the smallest positive
    root of that lower bound over all vertices, so all gaps stay ≥ 0 (up to
    rounding) and the iteration approaches the first root from below in time,
    quadratically once near a transversal crossing.

    Stopping is relative to the scale of the flight: it stops when the smallest
    gap is ≤ ``tol`` × S_j(t) with S_j(t) = |c0_j| + (|b_j| + ω|u_j|) t + ½ g t²
    + |v_j| |cos ωt − 1|, the size of the terms G_j is summed from (its rounding
    error is a few ulp of S_j; ``tol`` is dimensionless, default 1e-14 ≈ 45 ulp).
    An absolute tolerance fails both ways: on long flights (metres, tens of m/s) the
    gap's rounding noise exceeds 1e-14 m and the search never stops; on the tiny
    flights of starts δ above x_min the whole gap excursion (≈ ω²δ²/g) is far
    below it and the search stopped at its first step, with t_flight ~25 % short.
    If a step no longer advances t in floating point, the vertex of smallest gap
    is taken (the contact is resolved to rounding). A short Newton polish on the
    touching vertex's gap then removes the time error gap / |G_j'| left by
    stopping at a positive gap. A flight whose spin angle ω t passes
    :data:`MAX_SPIN_ANGLE` is not resolved.

    Returns ``(t, j)``; ``j = -1`` if ``max_iter`` steps did not reach contact,
    ``j = UNRESOLVED_J`` (−2) past :data:`MAX_SPIN_ANGLE`.
    """
    n = ru.shape[0]
    t = 0.0
    aw = abs(w)
    for _ in range(max_iter):
        wt = w * t
        if aw * t > MAX_SPIN_ANGLE:
            return t, UNRESOLVED_J
        if t > 0.0:
            hs = math.sin(0.5 * wt)  # half-angle: two trig calls per step
            hc = math.cos(0.5 * wt)
        else:
            hs = 0.0
            hc = 1.0
        s = 2.0 * hs * hc  # sin ωt
        cm1 = -2.0 * hs * hs  # cos ωt − 1 without cancellation
        c = 1.0 + cm1
        smw = s - wt  # sin ωt − ωt
        base = -0.5 * g * t * t
        dbase = vy - g * t
        step = math.inf
        jmin = -1
        gmin = math.inf
        dgmin = 0.0
        jlow = -1  # the vertex of smallest gap, in case t can no longer advance
        glow = math.inf
        dglow = 0.0
        half_gt2 = -base
        for j in range(n):
            gj = c0[j] + b[j] * t + base + rv[j] * cm1 + ru[j] * smw
            dg = dbase + w * (ru[j] * c - rv[j] * s)
            M = g + w * w * ell[j]
            scale = abs(c0[j]) + (abs(b[j]) + aw * abs(ru[j])) * t + half_gt2 + abs(rv[j] * cm1)
            tol_j = tol * scale
            if j == excl_j and t < excl_t:
                sj = excl_t - t
                if gj > 0.0 or dg > 0.0:
                    sq = _lower_bound_step(gj, dg, M)
                    if sq > sj:
                        sj = sq
                if sj < step:
                    step = sj
                continue
            if gj <= tol_j and (t > 0.0 or dg <= 0.0):
                if gj < gmin:
                    gmin = gj
                    dgmin = dg
                    jmin = j
                continue
            if gj < glow and t > 0.0:
                glow = gj
                dglow = dg
                jlow = j
            sj = _lower_bound_step(gj, dg, M)
            if sj < step:
                step = sj
        if jmin < 0 and t + step == t and jlow >= 0:
            # the step is below the resolution of t: the contact is resolved to rounding
            jmin = jlow
            gmin = glow
            dgmin = dglow
        if jmin >= 0:
            if t > 0.0 and gmin > 0.0:
                t = _polish(t, gmin, dgmin, jmin, c0, b, ru, rv, vy, w, g)
            return t, jmin
        t += step
    return t, -1


@njit(cache=True)
def first_contact(c0, ru, rv, vy, w, g, ell, excl_j, excl_t, tol, max_iter):
    """Guard ``touch``: earliest t ≥ 0 (s) at which any vertex reaches the line y = h (Eq. 3), from any flight state.

    ``c0`` gaps at t = 0 (m, :func:`gap_constants`), ``(ru, rv)`` vertex offsets
    at t = 0 (m), ``vy`` CM vertical velocity (m/s), ``w`` spin (rad/s), ``ell``
    vertex distances |w_j| (m). Vertex ``excl_j`` (one that just left the line;
    −1: none) is known to stay above it for t < ``excl_t`` (s). ``tol`` (dimensionless)
    is the gap, relative to the size of its terms, at which the search stops,
    ``max_iter`` its step cap. Returns ``(t, j)``; ``j = -1`` if ``max_iter`` steps
    did not reach contact, ``UNRESOLVED_J`` past :data:`MAX_SPIN_ANGLE`.
    See :func:`touch_time` (this computes b_j = v_y + ω u_j).
    """
    n = ru.shape[0]
    b = np.empty(n)
    for j in range(n):
        b[j] = vy + w * ru[j]
    return touch_time(c0, b, ru, rv, vy, w, g, ell, excl_j, excl_t, tol, max_iter)

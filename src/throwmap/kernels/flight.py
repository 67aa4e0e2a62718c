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

The same search finds the first contact with any line (:func:`line_touch`): written in the
line's frame (tangent t̂, normal n̂ into the part) the gap has this form with (u_j, v_j) the
offsets along t̂ and n̂ and g gravity's component against n̂. The arm is t̂ = x̂, n̂ = ŷ
(:func:`touch_time`, with a Newton polish); the end wall's face x = L is t̂ = ŷ, n̂ = −x̂, so
(u_j, v_j) = (r_y, −r_x), v_n = −v_x and g = g_x (:func:`throwmap.kernels.rigid_body.wall.wall_touch_time`).
A vertex that has just left a line stays off it for :func:`departure_window`, in the same frame.
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

NO_CONTACT = -1
"""Vertex returned by :func:`line_touch` when no vertex reaches the line up to its horizon ``t_max``."""
UNRESOLVED_J = -2
"""Vertex returned by :func:`line_touch` (and :func:`touch_time`) when the flight passed :data:`MAX_SPIN_ANGLE`."""
SEARCH_CAP = -3
"""Vertex returned by :func:`line_touch` after ``max_iter`` steps, or a step that no longer advances t, undecided."""
WATCH_ALL = np.zeros(0)
"""``off`` of :func:`line_touch` that watches every vertex."""


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
def lower_bound_step(gj, dg, M):
    """Smallest positive root s of gj + dg s − ½ M s² (gj clipped at 0; M ≥ 0): a step that cannot pass a root.

    With M = 0 (no curvature to bound) the linear bound's root, or ``inf`` if the gap is not closing."""
    gp = gj if gj > 0.0 else 0.0
    if M <= 0.0:
        if dg >= 0.0:
            return math.inf
        return gp / (-dg)
    disc = math.sqrt(dg * dg + 2.0 * M * gp)
    if dg >= 0.0:
        return (dg + disc) / M
    return 2.0 * gp / (disc - dg)


@njit(cache=True, inline="always")
def departure_window(rt, rn, w, g, lj, g_ref):
    """Time (s) for which a vertex that just left a line (gap 0, normal rate ≥ 0) provably stays off it.

    The line is the arm (tangent x̂, normal ŷ into the part) or the wall's face (tangent ŷ, normal −x̂):
    ``(rt, rn)`` is the CM → vertex offset along the line's tangent and normal (m), ``w`` the spin (rad/s),
    ``g`` gravity's component against the normal (m/s²: g cos α on the arm, g_x on the face), ``lj``
    the vertex's distance from the CM (m). Exact Taylor bound of the gap (Sec. III-B, Eq. 1 from an
    arbitrary state) G(s) ≥ G′ s + ½G″ s² + G‴ s³/6 − ω⁴ℓ s⁴/24 with G″ = −g − ω² r_n and
    G‴ = −ω³ r_t: returns 0.9 × the positive root of ½G″ + G‴ s/6 − ω⁴ℓ s²/24 (G′ ≥ 0 only helps),
    or 0 if G″ < 0 (the vertex is pressed onto the line: it cannot leave). A G″ less than
    1e-9 ``g_ref`` (m/s², gravity's scale) below 0 is rounding and counts as 0.
    """
    g2 = -g - w * w * rn
    g3 = -w * w * w * rt
    if g2 < 0.0 and g2 > -1e-9 * g_ref:
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
def separating_window(un, acc):
    """Time (s) for which a contact that leaves at normal rate ``un`` > 0 (m/s) stays open when its gap's second
    derivative is bounded by ``acc`` (m/s²): 0.9 × 2 un/acc (at most 1 s), from gap(s) ≥ un s − ½ acc s²."""
    if acc <= 0.0:
        return 1.0
    return min(1.8 * un / acc, 1.0)


@njit(cache=True, inline="always")
def line_touch(c0, b, ru, rv, vn, w, g, ell, excl_j, excl_t, t_max, tol, max_iter, off, hold_ref):
    """Guard ``touch`` against any line: the earliest t ∈ [0, t_max] (s) at which a vertex of the flying
    polygon reaches the line moving into it (Eq. 3 on the arm; the wall's face is the same in its frame).

    Everything in the line's frame (tangent t̂, normal n̂ into the part: the arm x̂, ŷ; the face ŷ, −x̂):
    ``c0`` the gaps at t = 0 (m, :func:`gap_constants`: exactly 0 for a vertex on the line), ``b`` their
    rates at t = 0 (m/s, b_j = v_n + ω u_j or a cancellation-free form of it), ``(ru, rv)`` the vertex
    offsets (u_j, v_j) from the CM along t̂ and n̂ (m), ``vn`` the CM's velocity along n̂ (m/s), ``w``
    the spin (rad/s), ``g`` gravity's component against n̂ (m/s², either sign), ``ell`` the vertex
    distances from the CM (m). The gap of vertex j is

        G_j(t) = c0_j + b_j t − ½ g t² − 2 v_j sin²(ωt/2) + u_j (sin ωt − ωt).

    Vertex ``excl_j`` (one that just left the line; −1: none) is known to stay off it for
    t < ``excl_t``; vertices with ``off[j]`` ≠ 0 are not watched (:data:`WATCH_ALL`: every one is).
    ``hold_ref`` > 0 (m/s², gravity's scale for :func:`departure_window`): at t = 0 a vertex on the
    line at rest relative to it is held off for its departure window, a contact only if that is 0
    (the face, against which the part may rest); 0: it is a contact (on the arm the callers exclude
    the vertex that just left it, ``excl_j``).

    Guarantee: no crossing before the returned time is missed. Since
    G_j″ = −g − ω²(u_j sin ωt + v_j cos ωt) ≥ −(max(g, 0) + ω² ℓ_j) =: −M_j, every gap
    obeys G_j(t+s) ≥ G_j + G_j′ s − ½ M_j s²; each step is the smallest positive
    root of that lower bound over all vertices (:func:`lower_bound_step`), so all gaps stay
    ≥ 0 (up to rounding) and the iteration approaches the first root from below in time,
    quadratically once near a transversal crossing.

    Stopping is relative to the scale of the flight: it stops when the smallest
    gap is ≤ ``tol`` × S_j(t) with S_j(t) = |c0_j| + (|b_j| + ω|u_j|) t + ½ |g| t²
    + |v_j| |cos ωt − 1|, the size of the terms G_j is summed from (its rounding
    error is a few ulp of S_j; ``tol`` is dimensionless, default 1e-14 ≈ 45 ulp).
    An absolute tolerance fails both ways: on long flights (metres, tens of m/s) the
    gap's rounding noise exceeds 1e-14 m and the search never stops; on the tiny
    flights of starts δ above x_min the whole gap excursion (≈ ω²δ²/g) is far
    below it and the search stopped at its first step, with t_flight ~25 % short.
    If a step no longer advances t in floating point, the vertex of smallest gap
    is taken (the contact is resolved to rounding). A flight whose spin angle ω t
    passes :data:`MAX_SPIN_ANGLE` is not resolved.

    Returns ``(t, j, G_j, G_j′)``: the contact vertex j with its gap and rate at t (for a polish,
    :func:`touch_time`), or j = :data:`NO_CONTACT` (none up to ``t_max``; t = t_max),
    :data:`UNRESOLVED_J` (past :data:`MAX_SPIN_ANGLE`) or :data:`SEARCH_CAP` (``max_iter`` steps, or a
    step that no longer advances t, without a decision).
    """
    n = ru.shape[0]
    t = 0.0
    aw = abs(w)
    g_pos = g if g > 0.0 else 0.0
    watch_all = off.shape[0] == 0
    for _ in range(max_iter):
        if t > t_max:
            return t_max, NO_CONTACT, 0.0, 0.0
        wt = w * t
        if aw * t > MAX_SPIN_ANGLE:
            return t, UNRESOLVED_J, 0.0, 0.0
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
        dbase = vn - g * t
        half_gt2 = 0.5 * abs(g) * t * t
        step = math.inf
        jmin = -1
        gmin = math.inf
        dgmin = 0.0
        jlow = -1  # the vertex of smallest gap, in case t can no longer advance
        glow = math.inf
        dglow = 0.0
        for j in range(n):
            if not watch_all and off[j] != 0.0:
                continue
            gj = c0[j] + b[j] * t + base + rv[j] * cm1 + ru[j] * smw
            dg = dbase + w * (ru[j] * c - rv[j] * s)
            M = g_pos + w * w * ell[j]
            scale = abs(c0[j]) + (abs(b[j]) + aw * abs(ru[j])) * t + half_gt2 + abs(rv[j] * cm1)
            tol_j = tol * scale
            if j == excl_j and t < excl_t:
                sj = excl_t - t
                if gj > 0.0 or dg > 0.0:
                    sq = lower_bound_step(gj, dg, M)
                    if sq > sj:
                        sj = sq
                if sj < step:
                    step = sj
                continue
            if hold_ref > 0.0 and t == 0.0 and gj <= tol_j and (dg == 0.0 or abs(dg) < 1e-300):
                # on the line at rest relative to it: pressed (a contact now) unless it curves away
                win = departure_window(ru[j], rv[j], w, g, ell[j], hold_ref)
                if win > 0.0:
                    if win < step:
                        step = win
                    continue
                gj = 0.0
                dg = 0.0
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
            sj = lower_bound_step(gj, dg, M)
            if sj < step:
                step = sj
        if jmin < 0 and t + step == t and jlow >= 0:
            # the step is below the resolution of t: the contact is resolved to rounding
            jmin = jlow
            gmin = glow
            dgmin = dglow
        if jmin >= 0:
            return t, jmin, gmin, dgmin
        if t + step == t:
            return t, SEARCH_CAP, 0.0, 0.0
        t += step
    return t, SEARCH_CAP, 0.0, 0.0


@njit(cache=True, inline="always")
def touch_time(c0, b, ru, rv, vy, w, g, ell, excl_j, excl_t, tol, max_iter):
    """Guard ``touch`` on the arm: earliest t ≥ 0 (s) at which any vertex reaches the line y = h (Eq. 3).

    :func:`line_touch` in the arm's frame (``g`` > 0 the gravity normal to the arm, m/s²; no horizon),
    then a short Newton polish of the touching vertex's gap (:func:`_polish`), which removes the time
    error gap / |G_j′| left by stopping at a positive gap. The gaps' initial rates b_j = v_y + ω u_j
    (m/s) are given by the caller: after a release (v_y = x0 ω) b_j = ω (x0 + u_j) is free of the
    cancellation that v_y + ω u_j suffers for a support vertex just in front of the joint
    (x0 + u_L → 0), so those tiny flights keep their relative accuracy (:func:`first_contact`
    computes b_j from any flight state). Other arguments as :func:`line_touch`.

    Returns ``(t, j)``; ``j = -1`` if ``max_iter`` steps did not reach contact,
    ``j = UNRESOLVED_J`` (−2) past :data:`MAX_SPIN_ANGLE`.
    """
    t, j, gj, dg = line_touch(c0, b, ru, rv, vy, w, g, ell, excl_j, excl_t, math.inf, tol, max_iter, WATCH_ALL, 0.0)
    if j == SEARCH_CAP:
        return t, -1
    if j >= 0 and t > 0.0 and gj > 0.0:
        t = _polish(t, gj, dg, j, c0, b, ru, rv, vy, w, g)
    return t, j


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

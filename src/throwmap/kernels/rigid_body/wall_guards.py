"""The wall's guards for model "rigid_body": the face and the top corner in flight, the wall's bound on a pivot.

Part of :mod:`.wall`: ``wall_touch`` (a vertex reaches the face, lower-bound stepping as
:func:`throwmap.kernels.flight.touch_time`), ``corner_touch`` (the top corner enters the
flying part), ``wall_reach`` (the least pivot angle the wall allows, closed form, face or corner).
"""

import math

import numpy as np
from numba import njit

from .wall_contact import _step_lb, corner_bounds, wall_departure


@njit(cache=True, inline="always")
def wall_gap(t, j, c, b, ru, rv, vx, om, gx):
    """Gap W_j(t) = L − x_j(t) (m) of vertex j to the wall at flight time t (s), and its rate (m/s).

    W_j(t) = c_j + b_j t − ½ g_x t² − u_j (cos ωt − 1) + v_j (sin ωt − ωt), with c_j = L − x − u_j
    and b_j = −v_x + ω v_j its value and rate at t = 0, (u_j, v_j) the vertex offsets at t = 0.
    """
    wt = om * t
    hs = math.sin(0.5 * wt)
    hc = math.cos(0.5 * wt)
    s = 2.0 * hs * hc
    cm1 = -2.0 * hs * hs
    gj = c[j] + b[j] * t - 0.5 * gx * t * t - ru[j] * cm1 + rv[j] * (s - wt)
    dg = -vx - gx * t + om * (ru[j] * s + rv[j] * (1.0 + cm1))
    return gj, dg


@njit(cache=True)
def wall_touch_time(c, ru, rv, vx, om, gx, ell, excl_j, excl_t, t_max, tol, max_iter, off):
    """Guard ``wall_touch``: earliest t ∈ [0, t_max] (s) at which a vertex reaches the wall x = L moving outward.

    ``c`` the gaps L − x_j at t = 0 (m; exactly 0 for a vertex on the wall), ``(ru, rv)``
    the vertex offsets from the CM at t = 0 (m), ``vx`` the CM's velocity along the arm (m/s),
    ``om`` the spin (rad/s), ``gx`` gravity along the arm (m/s²), ``ell`` the vertex
    distances from the CM (m). Vertex ``excl_j`` (−1: none) just left the wall and stays
    off it for t < ``excl_t``; vertices with ``off[j]`` ≠ 0 are not watched (they passed above the top).

    Guarantee (as :func:`throwmap.kernels.flight.touch_time`): W_j'' = −g_x + ω²(…) ≥
    −(max(g_x, 0) + ω² ℓ_j) =: −M_j, so each step, the smallest positive root of the
    quadratic lower bound of every gap, cannot pass a crossing; it stops when the
    smallest gap is ≤ ``tol`` times the size of its terms, or past ``t_max`` (the
    arm's touch: the earlier event wins). Returns ``(t, j)``: j = −1 no wall contact
    before t_max, −3 ``max_iter`` steps without a decision.
    """
    n = ru.shape[0]
    b = np.empty(n)
    for j in range(n):
        b[j] = -vx + om * rv[j]
    aw = abs(om)
    t = 0.0
    for _ in range(max_iter):
        if t > t_max:
            return t_max, -1
        step = math.inf
        jmin = -1
        gmin = math.inf
        jlow = -1  # the vertex of smallest gap, in case t can no longer advance
        glow = math.inf
        for j in range(n):
            if off[j] != 0.0:
                continue
            gj, dg = wall_gap(t, j, c, b, ru, rv, vx, om, gx)
            M = max(gx, 0.0) + om * om * ell[j]
            scale = abs(c[j]) + (abs(b[j]) + aw * abs(rv[j])) * t + 0.5 * abs(gx) * t * t \
                + abs(ru[j]) * abs(math.cos(om * t) - 1.0)
            if j == excl_j and t < excl_t:
                sj = excl_t - t
                if gj > 0.0 or dg > 0.0:
                    sq = _step_lb(gj, dg, M)
                    if sq > sj:
                        sj = sq
                if sj < step:
                    step = sj
                continue
            if t == 0.0 and gj <= tol * scale and (dg == 0.0 or abs(dg) < 1e-300):
                # on the wall at rest relative to it: pressed (contact now) unless it curves away
                win = wall_departure(0.0, ru[j], rv[j], om, gx, 0.0, ell[j])
                if win > 0.0:
                    if win < step:
                        step = win
                    continue
                gj = 0.0
                dg = 0.0
            if gj <= tol * scale and (t > 0.0 or dg <= 0.0):
                if gj < gmin:
                    gmin = gj
                    jmin = j
                continue
            if gj < glow and t > 0.0:
                glow = gj
                jlow = j
            sj = _step_lb(gj, dg, M)
            if sj < step:
                step = sj
        if jmin < 0 and t + step == t and jlow >= 0:
            jmin = jlow  # the step is below the resolution of t: the contact is resolved to rounding
        if jmin >= 0:
            return t, jmin
        if t + step == t:
            return t, -3
        t += step
    return t, -3


@njit(cache=True)
def _edge_frame(ru, rv, e):
    """Outward unit normal (n_x, n_y) of edge e (vertex e → e + 1, offsets from the CM at t = 0) and its support c_e (m)."""
    n = ru.shape[0]
    e2 = (e + 1) % n
    ex = ru[e2] - ru[e]
    ey = rv[e2] - rv[e]
    le = math.hypot(ex, ey)
    nx = ey / le
    ny = -ex / le
    c = nx * ru[e] + ny * rv[e]
    if c < 0.0:  # the CM (origin) is inside: the outward normal has n·a > 0
        nx = -nx
        ny = -ny
        c = -c
    return nx, ny, c


@njit(cache=True)
def corner_touch_time(qx, qy, vx, vy, om, gx, gn, ru, rv, excl_e, excl_t, t_max, tol, max_iter):
    """Guard ``corner_touch``: earliest t ∈ [0, t_max] (s) at which the wall's top corner Q enters the flying part.

    ``(q_x, q_y)`` = Q − CM at t = 0 (m), CM velocity (v_x, v_y), spin ω, gravity (g_x, −g_n);
    ``(ru, rv)`` the vertex offsets at t = 0. Edge e (outward normal n_e, support c_e) has the
    signed distance f_e(t) = R(ωt) n_e · (Q − X(t)) − c_e of Q beyond it; Q is inside the convex
    part iff every f_e < 0, so the part stays clear while some f_e > 0, and a step is safe if
    it is safe for one positive edge: the largest of the edges' lower-bound steps (the second
    derivatives are bounded by M2 of :func:`corner_bounds`) is taken. Edge ``excl_e`` stays
    positive for t < ``excl_t``. Returns ``(t, e)``: e the edge Q meets, −1 none before t_max,
    −3 ``max_iter`` steps.
    """
    n = ru.shape[0]
    M2, _m3 = corner_bounds(qx, qy, vx, vy, om, gx, gn, t_max)
    t = 0.0
    for _ in range(max_iter):
        if t > t_max:
            return t_max, -1
        c = math.cos(om * t)
        s = math.sin(om * t)
        px = qx - vx * t - 0.5 * gx * t * t  # Q − X(t)
        py = qy - vy * t + 0.5 * gn * t * t
        wx = vx + gx * t
        wy = vy - gn * t
        scale = math.hypot(px, py) + math.hypot(ru[0], rv[0])
        fmax = -math.inf
        emax = -1
        dfmax = 0.0
        step = 0.0
        clear = False  # the excluded edge still provably keeps Q out
        for e in range(n):
            nx0, ny0, ce = _edge_frame(ru, rv, e)
            nx = c * nx0 - s * ny0
            ny = s * nx0 + c * ny0
            f = nx * px + ny * py - ce
            df = om * (-ny * px + nx * py) - (nx * wx + ny * wy)
            if e == excl_e and t < excl_t:
                se = excl_t - t
                if f > 0.0 or df > 0.0:
                    se = max(se, _step_lb(f, df, M2))
                step = max(step, se)
                clear = True
                continue
            if f > fmax:
                fmax = f
                emax = e
                dfmax = df
            if f > 0.0 or (t == 0.0 and df > 0.0 and f >= -tol * scale):
                step = max(step, _step_lb(f, df, M2))
        if not clear and fmax <= tol * scale and (t > 0.0 or dfmax <= 0.0):
            return t, emax  # (at t = 0 only if Q is closing in: an edge through Q that opens is no contact)
        if t + step == t:
            return t, emax if not clear else -3
        t += step
    return t, -3


@njit(cache=True)
def wall_theta(px, L, top, theta, phi, w, jp):
    """Guard ``wall_reach`` of a pivot on vertex ``jp`` at (p_x, h): the least pivot angle θ_w the wall allows.

    Vertex j sits at A + ℓ_j (cos ψ_j, sin ψ_j), ψ_j = θ + δ_j, with ψ_j ∈ [0, π] while the
    part pivots (every vertex above the line), so x_j decreases with θ and x_j ≤ L ⟺
    θ ≥ arccos((L − p_x)/ℓ_j) − δ_j. ``theta``/``phi`` (rad) are the current pivot angle and
    orientation (δ_j follows from them), ``w`` the body vertices (m), ``top`` = H the wall's
    height above the line (m). Returns ``(θ_w, j_w, y_w)``: the bound (−inf: none), the vertex
    that sets it and its height above the line there (m; > ``top``: it passes above the wall).
    """
    cp = math.cos(phi)
    sp = math.sin(phi)
    ax = cp * w[jp, 0] - sp * w[jp, 1]
    ay = sp * w[jp, 0] + cp * w[jp, 1]
    gap = L - px
    best = -math.inf
    jb = -1
    yb = 0.0
    for j in range(w.shape[0]):
        if j == jp:
            continue
        ex = cp * w[j, 0] - sp * w[j, 1] - ax
        ey = sp * w[j, 0] + cp * w[j, 1] - ay
        lj = math.hypot(ex, ey)
        if lj <= gap:
            continue
        delta = math.atan2(ey, ex) - theta
        psi_w = math.acos(max(-1.0, min(1.0, gap / lj)))
        th = psi_w - delta
        if th > best:
            best = th
            jb = j
            yb = lj * math.sin(psi_w)
    return best, jb, yb


@njit(cache=True)
def wall_contact_angle(px, L, top, theta, phi, w, jp):
    """Guard ``wall_reach`` with the wall's top corner: the least pivot angle θ_c at which the part meets the wall.

    Pivoting on vertex ``jp`` at (p_x, h), the part meets the wall either with a vertex on its face
    below the top (:func:`wall_theta`'s bound, for the vertices that cross x = L below ``top``) or
    with an edge on the top corner Q = (L, h + H): turned by Δ about A an edge with outward normal
    n_e and support c_e = n_e·(a − A) touches Q when |q| cos(∠n_e + Δ − ∠q) = c_e, q = Q − A, with
    the touching point inside the edge. The largest such angle θ ≤ θ (the part moves outward as θ
    decreases) is the bound. Returns ``(θ_c, corner, j, c_x, c_y, n_x, n_y)``: the bound (−inf: none),
    whether it is the corner, the vertex on the face or the edge (vertex j → j + 1) on the corner, the contact point relative to A (m) and the unit normal of the contact
    into the part (world frame at θ_c): −x̂ on the face, the edge's inward normal on the corner.
    """
    cp = math.cos(phi)
    sp = math.sin(phi)
    n = w.shape[0]
    ax = cp * w[jp, 0] - sp * w[jp, 1]
    ay = sp * w[jp, 0] + cp * w[jp, 1]
    gap = L - px
    best = -math.inf
    corner = False
    jb = -1
    cx = 0.0
    cy = 0.0
    nx = -1.0
    ny = 0.0
    # vertices on the face, below the top
    for j in range(n):
        if j == jp:
            continue
        ex = cp * w[j, 0] - sp * w[j, 1] - ax
        ey = sp * w[j, 0] + cp * w[j, 1] - ay
        lj = math.hypot(ex, ey)
        if lj <= gap:
            continue
        psi_w = math.acos(max(-1.0, min(1.0, gap / lj)))
        yw = lj * math.sin(psi_w)
        if yw >= top:
            continue  # passes above the top: the corner decides
        th = psi_w - (math.atan2(ey, ex) - theta)
        if th > best:
            best = th
            corner = False
            jb = j
            cx = gap
            cy = yw
            nx = -1.0
            ny = 0.0
    # edges on the top corner
    qx = gap
    qy = top
    rq = math.hypot(qx, qy)
    aq = math.atan2(qy, qx)
    gx_ = -ax  # the CM relative to A (for the outward sense of the normals)
    gy_ = -ay
    for j in range(n):
        j2 = (j + 1) % n
        pax = cp * w[j, 0] - sp * w[j, 1] - ax
        pay = sp * w[j, 0] + cp * w[j, 1] - ay
        pbx = cp * w[j2, 0] - sp * w[j2, 1] - ax
        pby = sp * w[j2, 0] + cp * w[j2, 1] - ay
        ex = pbx - pax
        ey = pby - pay
        le = math.hypot(ex, ey)
        if le == 0.0:
            continue
        enx = ey / le
        eny = -ex / le
        if enx * (gx_ - pax) + eny * (gy_ - pay) > 0.0:  # make it outward
            enx = -enx
            eny = -eny
        ce = enx * pax + eny * pay
        if abs(ce) > rq:
            continue
        an = math.atan2(eny, enx)
        base = math.acos(ce / rq)
        for sgn in (1.0, -1.0):
            dlt = aq - an + sgn * base
            dlt = (dlt + math.pi) % (2.0 * math.pi) - math.pi  # (−π, π]
            if dlt > 1e-15:
                dlt -= 2.0 * math.pi
            th = theta + dlt
            if th <= best:
                continue
            # the edge at that angle: is Q inside the segment?
            c = math.cos(dlt)
            s = math.sin(dlt)
            rax = c * pax - s * pay
            ray = s * pax + c * pay
            rex = c * ex - s * ey
            rey = s * ex + c * ey
            u = ((qx - rax) * rex + (qy - ray) * rey) / (le * le)
            if u < 0.0 or u > 1.0:
                continue
            best = th
            corner = True
            jb = j
            cx = qx
            cy = qy
            nx = -(c * enx - s * eny)
            ny = -(s * enx + c * eny)
    return best, corner, jb, cx, cy, nx, ny


@njit(cache=True)
def fill_wall_vertices(theta, phi, w, jp, wv):
    """Rows (ℓ_j, δ_j) of ``wv`` (n, 2): vertex j at A + ℓ_j (cos(θ + δ_j), sin(θ + δ_j)) while pivoting on ``jp``
    (ℓ = 0 for jp itself), for the sliding phase's guard ``wall_reach``."""
    cp = math.cos(phi)
    sp = math.sin(phi)
    for j in range(w.shape[0]):
        ex = cp * (w[j, 0] - w[jp, 0]) - sp * (w[j, 1] - w[jp, 1])
        ey = sp * (w[j, 0] - w[jp, 0]) + cp * (w[j, 1] - w[jp, 1])
        wv[j, 0] = 0.0 if j == jp else math.hypot(ex, ey)
        wv[j, 1] = math.atan2(ey, ex) - theta


@njit(cache=True)
def corner_inside(px, h, theta, phi, w, jp, L, top):
    """Whether the wall's top corner (L, h + top) lies inside the part pivoting on ``jp`` at (p_x, h) (by more than
    1e-12 of its size): an edge has passed it."""
    cp = math.cos(phi)
    sp = math.sin(phi)
    n = w.shape[0]
    qx = L - px
    qy = top
    sgn = 0.0
    size = 0.0
    for j in range(n):
        size = max(size, abs(w[j, 0]) + abs(w[j, 1]))
    for j in range(n):
        j2 = (j + 1) % n
        ax = cp * (w[j, 0] - w[jp, 0]) - sp * (w[j, 1] - w[jp, 1])
        ay = sp * (w[j, 0] - w[jp, 0]) + cp * (w[j, 1] - w[jp, 1])
        bx = cp * (w[j2, 0] - w[jp, 0]) - sp * (w[j2, 1] - w[jp, 1])
        by = sp * (w[j2, 0] - w[jp, 0]) + cp * (w[j2, 1] - w[jp, 1])
        cr = (bx - ax) * (qy - ay) - (by - ay) * (qx - ax)
        le = math.hypot(bx - ax, by - ay)
        if abs(cr) <= 1e-12 * size * le:
            return False
        s = 1.0 if cr > 0.0 else -1.0
        if sgn == 0.0:
            sgn = s
        elif s != sgn:
            return False
    return True

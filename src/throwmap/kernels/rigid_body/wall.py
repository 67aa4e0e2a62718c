"""A wall at the arm's end in model "rigid_body": its guards, resets and statics (issue 11, item 2).

The wall (:class:`throwmap.system.fixtures.Wall`) is the face x = L (the arm's
``length``, arm frame) from the arm surface y = h up to y = h + H; its normal
into the part is −x̂, its Coulomb coefficient μ_w (``inf``: no slip), and every
impact with it is plastic (zero restitution), as on the arm. Gravity is a
general vector (g_x, g_y) in the arm frame; an arm at rest angle α gives
(g_x, g_y) = (−g sin α, −g cos α) (α < 0 tilts the end down: g_x > 0 pushes the
part towards the wall). Unit mass, inertia ρ² about the CM, as the rest of the
automaton (:mod:`throwmap.kernels.rigid_body`).

Guards
------
``wall_touch``   FLIGHT: the earliest time a vertex reaches x = L moving outward
                 (:func:`wall_touch_time`, the lower-bound stepping of
                 :func:`throwmap.kernels.flight.touch_time` applied to the wall
                 gap; it cannot miss a crossing). A vertex crossing x = L above
                 the wall top has passed over it: an edge then meets the wall's
                 top corner, which is not modelled (refused, :data:`WHY_WALL_TOP`).
``wall_reach``   PIVOT_* about A = (p_x, h): every vertex above the line moves
                 outward as θ decreases, so the wall is a lower bound θ ≥ θ_w on the
                 pivot angle (:func:`wall_theta`, closed form); the swinging part
                 touches the wall when θ reaches θ_w.
``slide_hit``    FLAT_SLIDE at constant acceleration: the leading vertex reaches the
                 wall (:func:`slide_hit`, closed form).

Resets
------
``wall_impact``  one vertex against the wall: the impact law of the arm
                 (:func:`~.impact.coulomb_impact`: Eq. 4 inside the friction cone,
                 else Routh's process or the velocity-level law) in a frame turned by
                 −90° so that the wall's normal −x̂ is that law's normal ŷ
                 (:func:`wall_impact`). The normal velocity after it is 0.
``all_stop``     several contacts (arm vertices and wall vertices) at once: the part
                 stops if the impulse that removes its whole momentum is a sum of
                 impulses inside the contacts' friction cones
                 (:func:`cone_contains`, exact: Carathéodory's theorem, every basis of
                 ≤ 3 cone edges is tried).

Statics
-------
``rest_against_wall`` a part at rest touching the arm and the wall stays if gravity
                 is balanced by forces inside the contacts' cones (:func:`cone_contains`
                 with the gravity wrench), the same exact test.

What is refused (status UNRESOLVED, reason code ``WHY_*`` below) is every state
the automaton cannot follow exactly: an edge on the wall's top corner, a vertex
pressed against the wall during flight (it would slide along the wall), a
two-contact impact with slip, a two-contact slide (a ladder sliding at both
ends), and a pivot at the wall's foot driven into the wall.
"""

import math

import numpy as np
from numba import njit

from .. import codes as C
from ..flight import SNAP, first_contact
from .impact import coulomb_impact, record_impact
from .modes import IMP_INCONSISTENT, IMP_SEPARATE
from .trajectory import _put, _put_final

WHY_NONE = 0
WHY_WALL_TOP = 1
WHY_WALL_SLIDE = 2
WHY_TWO_CONTACT = 3
WHY_LADDER = 4
WHY_CORNER = 5
WHY_SLIDE_WALL = 6
WHY_MESSAGES = {
    WHY_WALL_TOP: ("a vertex passed the wall's plane above its top: an edge meets the wall's top corner, "
                   "which rigid_body does not model (use model 'engine', or a taller Wall)"),
    WHY_WALL_SLIDE: ("a vertex stays pressed against the wall in flight (it would slide along the wall face), "
                     "which rigid_body does not model"),
    WHY_TWO_CONTACT: ("an impact at the arm and the wall at once needs slip at a contact: this two-contact "
                      "impact is not modelled by rigid_body"),
    WHY_LADDER: ("the part leans on the arm and the wall and slides at both (a ladder-like slide): this "
                 "two-contact motion is not modelled by rigid_body"),
    WHY_CORNER: ("the pivot at the wall's foot is driven into the wall while the part swings: this "
                 "two-contact motion is not modelled by rigid_body"),
    WHY_SLIDE_WALL: ("a pivot sliding along the arm brought the part to the wall: this contact is not located "
                     "by rigid_body's sliding phase"),
}
"""Why a walled throw was refused (status UNRESOLVED), by reason code."""

EV_WALL = 10
"""Event code of guard ``wall_reach`` (after the codes of :mod:`.modes`): a vertex is on the wall and the part turns into it."""
WHY_COL = getattr(C, "WHY", -1)
"""Record column receiving the reason code of a refusal (``kernels.codes.WHY``), if the record has one."""

CONE_TOL = 1e-11
"""Relative tolerance of :func:`cone_contains` (residual and negative coefficients, relative to |b|)."""
MU_BIG = 1e12
"""μ standing in for ∞ where a cone needs a finite edge (never in the impact law: μ = ∞ is exact there)."""


@njit(cache=True)
def refuse(rec, why):
    """Status UNRESOLVED for a walled throw the automaton cannot follow; the reason ``why`` goes to the record."""
    if WHY_COL >= 0:
        rec[WHY_COL] = why
    return C.UNRESOLVED


# ---------------------------------------------------------------------------------------- reset wall_impact
@njit(cache=True)
def wall_impact(vx, vy, om, rx, ry, rho2, mu_w, law):
    """Reset ``wall_impact``: plastic Coulomb impact of the vertex at (r_x, r_y) from the CM (m) on the wall x = L.

    The arm's law :func:`~.impact.coulomb_impact` in the frame (x', y') = (y, −x), a proper
    rotation by −90° in which the wall's inward normal −x̂ is ŷ' and its tangent ŷ is x̂';
    ω is unchanged. ``mu_w`` is the wall's μ (``inf``: no slip), ``law`` the impact law.
    Returns ``(vx⁺, vy⁺, ω⁺, P_t, P_n, kind, jt0, jn0)``: P_n (m/s, ≥ 0) the impulse along −x̂,
    P_t along +ŷ, kind as :func:`~.impact.coulomb_impact` (IMP_SEPARATE if the vertex is not
    moving into the wall).
    """
    vxp, vyp, wp, pt, pn, kind, jt0, jn0 = coulomb_impact(vy, -vx, om, ry, -rx, rho2, mu_w, law)
    return -vyp, vxp, wp, pt, pn, kind, jt0, jn0


# ---------------------------------------------------------------------------------------- guard wall_touch
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


@njit(cache=True, inline="always")
def _step_lb(gj, dg, M):
    """Smallest positive root of gj + dg s − ½ M s² (gj clipped at 0; M ≥ 0): a step that cannot pass a root."""
    gp = gj if gj > 0.0 else 0.0
    if M <= 0.0:
        if dg >= 0.0:
            return math.inf
        return gp / (-dg)
    disc = math.sqrt(dg * dg + 2.0 * M * gp)
    if dg >= 0.0:
        return (dg + disc) / M
    return 2.0 * gp / (disc - dg)


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
            if t == 0.0 and gj <= tol * scale and dg == 0.0:
                # on the wall at rest relative to it: pressed (contact now) unless it curves away
                win = wall_departure(0.0, ru[j], rv[j], om, gx, 0.0, ell[j])
                if win > 0.0:
                    if win < step:
                        step = win
                    continue
                gj = 0.0
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
def wall_departure(un, rx, ry, om, gx, gy, lj):
    """Time (s) for which a vertex that just left the wall (gap 0, outward rate ``un`` ≥ 0) stays off it.

    Exact Taylor bound of its gap W(s) ≥ W' s + ½W'' s² + W''' s³/6 − ω⁴ℓ s⁴/24 with
    W'' = −g_x + ω² r_x and W''' = −ω³ r_y ((r_x, r_y): CM → vertex, m): returns 0.9 × the
    positive root of ½W'' + W''' s/6 − ω⁴ℓ s²/24, or 0 if W'' < 0 (the vertex is pressed
    against the wall: it cannot leave). ``gy`` does not enter (the wall is vertical).
    """
    g2 = -gx + om * om * rx
    g3 = -om * om * om * ry
    if g2 < 0.0 and g2 > -1e-9 * (abs(gx) + abs(gy) + 1e-300):
        g2 = 0.0
    if g2 < 0.0:
        return 0.0
    a = om * om * om * om * lj / 24.0
    bb = g3 / 6.0
    cc = 0.5 * g2
    if a <= 0.0:
        if bb > 0.0 or cc > 0.0:
            return 1.0
        return 0.0
    root = (bb + math.sqrt(bb * bb + 4.0 * a * cc)) / (2.0 * a)
    if root <= 0.0:
        return 0.0
    return 0.9 * root


# ---------------------------------------------------------------------------------------- guard wall_reach (pivots)
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
def contact_impact(vx, vy, om, rx, ry, nx, ny, rho2, mu_c, law):
    """Reset ``impact`` at a contact with unit normal (n_x, n_y) into the part: the arm's law in the frame (t, n),
    t = n turned by −90° (a proper rotation). Returns as :func:`wall_impact`, with P_n along n and P_t along t."""
    tx = ny
    ty = -nx
    vxp, vyp, wp, pt, pn, kind, jt0, jn0 = coulomb_impact(vx * tx + vy * ty, vx * nx + vy * ny, om,
                                                          rx * tx + ry * ty, rx * nx + ry * ny, rho2, mu_c, law)
    return vxp * tx + vyp * nx, vxp * ty + vyp * ny, wp, pt, pn, kind, jt0, jn0


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


# ---------------------------------------------------------------------------------------- guard corner_touch (flight)
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
def corner_bounds(qx, qy, vx, vy, om, gx, gn, t_max):
    """Bounds (M2, M3) on the second and third time derivatives of every edge's corner distance f_e
    (:func:`corner_touch_time`) over a flight of ``t_max`` s from Q − CM = (q_x, q_y) (m) and CM velocity (v_x, v_y)."""
    ga = math.hypot(gx, gn)
    v0 = math.hypot(vx, vy)
    D = math.hypot(qx, qy) + v0 * t_max + 0.5 * ga * t_max * t_max
    vm = v0 + ga * t_max
    aw = abs(om)
    return om * om * D + 2.0 * aw * vm + ga, aw * aw * aw * D + 3.0 * om * om * vm + 3.0 * aw * ga


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
        fmax = -math.inf
        emax = -1
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
            if f > 0.0:
                step = max(step, _step_lb(f, df, M2))
        scale = math.hypot(px, py) + math.hypot(ru[0], rv[0])
        if not clear and fmax <= tol * scale:
            return t, emax
        if t + step == t:
            return t, emax if not clear else -3
        t += step
    return t, -3


@njit(cache=True)
def corner_departure(qx, qy, vx, vy, om, gx, gn, nx, ny, t_max):
    """Time (s) for which an edge that just stopped on the wall's top corner (normal velocity 0) stays off it.

    With Q − CM = (q_x, q_y) (m) and the edge's outward normal (n_x, n_y) now: f(s) ≥ ½ f2 s² − M3 s³/6 with
    f2 = −ω² n·(Q − X) − 2ω (Jn)·V − n·g (J: +90°, M3 of :func:`corner_bounds`); returns 0.9 · 3 f2/M3
    (``t_max`` if M3 = 0), or 0 if f2 ≤ 0 (the edge is pressed on the corner: it would slide over it).
    """
    jx = -ny
    jy = nx
    f2 = -om * om * (nx * qx + ny * qy) - 2.0 * om * (jx * vx + jy * vy) - (nx * gx - ny * gn)
    if f2 <= 0.0:
        return 0.0
    _m2, M3 = corner_bounds(qx, qy, vx, vy, om, gx, gn, t_max)
    if M3 <= 0.0:
        return t_max
    return min(0.9 * 3.0 * f2 / M3, t_max)


# ---------------------------------------------------------------------------------------- FLAT_SLIDE into the wall
@njit(cache=True)
def slide_hit(v, a, gap):
    """Guard ``slide_hit``: a flat slide at speed ``v`` > 0 (m/s, towards the wall) with constant
    acceleration ``a`` (m/s²) and ``gap`` (m) between its leading vertex and the wall.

    Returns ``(hit, t, v_hit)``: whether it reaches the wall, when (s) and how fast (m/s);
    without a hit ``t`` is the time it stops (a < 0) and v_hit = 0.
    """
    if gap <= 0.0:
        return True, 0.0, v
    disc = v * v + 2.0 * a * gap
    if disc < 0.0:
        return False, -v / a, 0.0
    vh = math.sqrt(disc)
    if a == 0.0:
        return True, gap / v, v
    return True, 2.0 * gap / (v + vh), vh


@njit(cache=True)
def wall_reach_at_rest(u, vh, top):
    """The leading vertex of a part flat on a side sliding towards the wall.

    ``u`` the vertices' x offsets from the CM (m), ``vh`` their heights above the arm line (m),
    ``top`` the wall's height (m). Returns ``(u_w, j_w, above)``: the largest offset, its vertex,
    and whether that vertex is above the wall's top (it would pass over the wall: an edge then
    meets the top corner).
    """
    jb = 0
    for j in range(u.shape[0]):
        if u[j] > u[jb]:
            jb = j
    umax = u[jb]
    tie = 1e-12 * (abs(umax) + abs(vh[jb]))
    for j in range(u.shape[0]):  # a flush (vertical) leading side: its lowest vertex meets the wall
        if u[j] >= umax - tie and vh[j] < vh[jb]:
            jb = j
    return umax, jb, vh[jb] >= top


# ---------------------------------------------------------------------------------------- cones: impacts and statics
@njit(cache=True)
def _solve3(A, b, x):
    """Solve the 3×3 system A x = b by Gaussian elimination with partial pivoting; False if singular."""
    M = np.empty((3, 4))
    for i in range(3):
        for k in range(3):
            M[i, k] = A[i, k]
        M[i, 3] = b[i]
    amax = 0.0
    for i in range(3):
        for k in range(3):
            amax = max(amax, abs(A[i, k]))
    if amax == 0.0:
        return False
    for col in range(3):
        p = col
        for i in range(col + 1, 3):
            if abs(M[i, col]) > abs(M[p, col]):
                p = i
        if abs(M[p, col]) <= 1e-13 * amax:
            return False
        if p != col:
            for k in range(4):
                tmp = M[col, k]
                M[col, k] = M[p, k]
                M[p, k] = tmp
        for i in range(col + 1, 3):
            f = M[i, col] / M[col, col]
            for k in range(col, 4):
                M[i, k] -= f * M[col, k]
    for i in range(2, -1, -1):
        s = M[i, 3]
        for k in range(i + 1, 3):
            s -= M[i, k] * x[k]
        x[i] = s / M[i, i]
    return True


@njit(cache=True)
def cone_contains(G, m, b):
    """Whether ``b`` (3,) is a nonnegative combination of the first ``m`` columns of ``G`` (3, ≥ m).

    Exact by Carathéodory's theorem: if b is in the cone it is a nonnegative combination of
    at most 3 linearly independent columns, so every set of 1, 2 and 3 columns is tried
    (least squares on 1 and 2, a solve on 3), accepting coefficients ≥ −tol and residual ≤ tol,
    tol = :data:`CONE_TOL` |b| (columns normalised first).
    """
    nb = math.sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2])
    if nb == 0.0:
        return True
    tol = CONE_TOL
    bn = b / nb
    Gn = np.empty((3, m))
    for k in range(m):
        c = math.sqrt(G[0, k] ** 2 + G[1, k] ** 2 + G[2, k] ** 2)
        for i in range(3):
            Gn[i, k] = G[i, k] / c if c > 0.0 else 0.0
    # one column
    for k in range(m):
        a = Gn[0, k] * bn[0] + Gn[1, k] * bn[1] + Gn[2, k] * bn[2]
        if a > 0.0:
            r = 0.0
            for i in range(3):
                r += (bn[i] - a * Gn[i, k]) ** 2
            if math.sqrt(r) <= tol:
                return True
    # two columns: least squares
    for k1 in range(m):
        for k2 in range(k1 + 1, m):
            a11 = 0.0
            a12 = 0.0
            a22 = 0.0
            r1 = 0.0
            r2 = 0.0
            for i in range(3):
                a11 += Gn[i, k1] * Gn[i, k1]
                a12 += Gn[i, k1] * Gn[i, k2]
                a22 += Gn[i, k2] * Gn[i, k2]
                r1 += Gn[i, k1] * bn[i]
                r2 += Gn[i, k2] * bn[i]
            det = a11 * a22 - a12 * a12
            if det <= 1e-14:
                continue
            c1 = (a22 * r1 - a12 * r2) / det
            c2 = (a11 * r2 - a12 * r1) / det
            if c1 < -tol or c2 < -tol:
                continue
            r = 0.0
            for i in range(3):
                r += (bn[i] - c1 * Gn[i, k1] - c2 * Gn[i, k2]) ** 2
            if math.sqrt(r) <= tol:
                return True
    # three columns
    A = np.empty((3, 3))
    x = np.empty(3)
    for k1 in range(m):
        for k2 in range(k1 + 1, m):
            for k3 in range(k2 + 1, m):
                for i in range(3):
                    A[i, 0] = Gn[i, k1]
                    A[i, 1] = Gn[i, k2]
                    A[i, 2] = Gn[i, k3]
                if not _solve3(A, bn, x):
                    continue
                if x[0] >= -tol and x[1] >= -tol and x[2] >= -tol:
                    return True
    return False


@njit(cache=True)
def contact_wrenches(pts, nrm, mus, m, lref, G):
    """Fill ``G`` (3, ≥ 3m) with the edges of the contacts' friction cones as wrenches; returns their number.

    Contact i at ``pts[i]`` (CM → contact point, m) with inward unit normal ``nrm[i]`` and
    Coulomb μ ``mus[i]``: edges n ± μ t (t = n turned by −90°), just n if μ = 0, and n, t, −t if
    μ = ∞. A force f at r gives the wrench (f_x, f_y, (r × f)/``lref``) (``lref`` m: torques in
    force units).
    """
    k = 0
    for i in range(m):
        nx = nrm[i, 0]
        ny = nrm[i, 1]
        tx = ny
        ty = -nx
        rx = pts[i, 0]
        ry = pts[i, 1]
        mu = mus[i]
        if mu == 0.0:
            dirs = ((nx, ny), (nx, ny), (nx, ny))
            nd = 1
        elif math.isinf(mu):
            dirs = ((nx, ny), (tx, ty), (-tx, -ty))
            nd = 3
        else:
            dirs = ((nx + mu * tx, ny + mu * ty), (nx - mu * tx, ny - mu * ty), (nx, ny))
            nd = 2
        for q in range(nd):
            fx, fy = dirs[q]
            G[0, k] = fx
            G[1, k] = fy
            G[2, k] = (rx * fy - ry * fx) / lref
            k += 1
    return k


@njit(cache=True)
def contacts_can_supply(pts, nrm, mus, m, fx, fy, tau, lref):
    """Whether contact forces (or impulses) inside the contacts' cones sum to the wrench (f_x, f_y, τ).

    ``tau`` is the torque about the CM (m · force). Statics of a part touching the arm and the
    wall: (f_x, f_y, τ) = (−g_x, −g_y, 0); a plastic impact that stops the part: −(v_x, v_y, ρ²ω).
    """
    G = np.empty((3, 3 * m))
    k = contact_wrenches(pts, nrm, mus, m, lref, G)
    b = np.empty(3)
    b[0] = fx
    b[1] = fy
    b[2] = tau / lref
    return cone_contains(G, k, b)


@njit(cache=True)
def flat_contacts(u, vh, k_left, k_right, mu, mu_w, top, x_gap, tol, pts, nrm, mus):
    """The contacts of a part flat on a side, its vertices' offsets ``u`` (along the arm) and ``vh`` (normal) from the CM (m).

    Arm contacts at the two support vertices ``k_left``, ``k_right`` (normal ŷ, μ); wall
    contacts (normal −x̂, μ_w) where the part meets the wall face x_cm + ``x_gap``: the
    vertices within ``tol`` (m) of it span a segment (one point, or a flush side) whose ends
    below ``top`` (the wall top's height above the CM, m) are the contacts — a flush side
    reaching above the top touches up to the wall's top corner. Fills ``pts``/``nrm``/``mus``
    (≥ 4 rows) and returns the number of contacts and of wall contacts.
    """
    m = 0
    for j in (k_left, k_right):
        pts[m, 0] = u[j]
        pts[m, 1] = vh[j]
        nrm[m, 0] = 0.0
        nrm[m, 1] = 1.0
        mus[m] = mu
        m += 1
    lo = math.inf
    hi = -math.inf
    for j in range(u.shape[0]):
        if u[j] >= x_gap - tol:
            lo = min(lo, vh[j])
            hi = max(hi, vh[j])
    if not lo < top:
        return m, 0
    hi = min(hi, top)
    nw = 0
    for yc in (lo, hi):
        if nw == 1 and yc <= lo + tol:
            break
        pts[m, 0] = x_gap
        pts[m, 1] = yc
        nrm[m, 0] = -1.0
        nrm[m, 1] = 0.0
        mus[m] = mu_w
        m += 1
        nw += 1
    return m, nw


@njit(cache=True)
def corner_pivot_rate(v, u_r, d, rho2):
    """Spin (rad/s) just after a part sliding flat at ``v`` (m/s) hits the wall with its right support vertex.

    That vertex sits in the corner of arm and wall (offset (u_R, −d) from the CM, m) and stops;
    the part turns about it, conserving angular momentum about it: ω⁺ = −d v/(ρ² + u_R² + d²)
    (clockwise for v > 0: it tips towards the wall).
    """
    return -d * v / (rho2 + u_r * u_r + d * d)


@njit(cache=True)
def rest_flat_at_wall(u, vh, k_left, k_right, x_gap, top, mu, mu_w, gx, gy, lref):
    """Rest ``rest_against_wall`` of a part flat on a side touching the wall: whether gravity is held.

    Contacts from :func:`flat_contacts`; gravity (g_x, g_y) (m/s²). True if arm and wall forces
    inside their cones can balance it (:func:`contacts_can_supply`).
    """
    pts = np.empty((4, 2))
    nrm = np.empty((4, 2))
    mus = np.empty(4)
    m, _nw = flat_contacts(u, vh, k_left, k_right, mu, mu_w, top, x_gap, 1e-9 * lref, pts, nrm, mus)
    return contacts_can_supply(pts, nrm, mus, m, -gx, -gy, 0.0, lref)


@njit(cache=True)
def separates(kind):
    """Whether a wall impact of this kind left the vertex moving away (it was not moving in)."""
    return kind == IMP_SEPARATE


# ---------------------------------------------------------------------------------------- FLIGHT with a wall
@njit(cache=True)
def refresh_frame(phi, y, h, w, ell, ru, rv, c0):
    """Flight frame at orientation φ and CM height y (m): offsets R(φ) w_j and arm gaps (tiny ones snapped to 0)."""
    cp = math.cos(phi)
    sp = math.sin(phi)
    for j in range(w.shape[0]):
        ru[j] = cp * w[j, 0] - sp * w[j, 1]
        rv[j] = sp * w[j, 0] + cp * w[j, 1]
        c = (y - h) + rv[j]
        c0[j] = 0.0 if abs(c) <= SNAP * ell[j] else c


@njit(cache=True)
def fly_walled(t, x, y, vx, vy, phi, om, c0, ru, rv, gx, g, ell, excl_j, excl_t, wexcl_j, wexcl_t, cexcl_e, cexcl_t, L,
               top, h, tol, max_iter, cw, off, traj, ts):
    """Mode FLIGHT with a wall: until guard ``touch`` (the arm), ``wall_touch`` (the face) or ``corner_touch``
    (the top corner), whichever comes first.

    Gravity (g_x, −g) (m/s²; g the component normal to the arm, as
    :func:`~throwmap.kernels.flight.first_contact` takes it). The arm's vertex ``excl_j`` is
    excluded for ``excl_t`` s, the face's ``wexcl_j`` for ``wexcl_t`` s, the corner's edge ``cexcl_e``
    for ``cexcl_t`` s (all from now). A vertex that reaches the face's plane above the top
    (``top`` m above the line y = ``h``) passes over it and is marked in ``off`` (n,), no longer
    watched by the face. ``cw`` (n,) is scratch. Returns ``(where, j, t, x, y, v_x, v_y, φ, r_x, r_y,
    n_x, n_y)``: where = 0 the arm (vertex j), 1 the face (vertex j), 2 the corner (edge j), −1 the
    arm search failed (j its code, as :func:`fly`), −2 a wall search hit ``max_iter``; (r_x, r_y)
    the contact point's offset from the CM (m) and (n_x, n_y) the contact's normal into the part.
    """
    n = ru.shape[0]
    tc, jc = first_contact(c0, ru, rv, vy, om, g, ell, excl_j, excl_t, tol, max_iter)
    where = 0 if jc >= 0 else -1
    nx = 0.0
    ny = 1.0
    for j in range(n):
        cj = L - x - ru[j]
        cw[j] = 0.0 if abs(cj) <= SNAP * ell[j] else cj
    for _ in range(n + 1):
        tw, jw = wall_touch_time(cw, ru, rv, vx, om, gx, ell, wexcl_j, wexcl_t, tc, tol, max_iter, off)
        if jw == -3:
            return -2, jw, t, x, y, vx, vy, phi, 0.0, 0.0, 0.0, 0.0
        if jw < 0:
            break
        yj = y + vy * tw - 0.5 * g * tw * tw + math.sin(om * tw) * ru[jw] + math.cos(om * tw) * rv[jw]
        if yj - h < top:
            if tw < tc or jc < 0:
                where = 1
                jc = jw
                tc = tw
                nx = -1.0
                ny = 0.0
            break
        off[jw] = 1.0  # over the top: the corner guard watches its edges
    tq, eq = corner_touch_time(L - x, h + top - y, vx, vy, om, gx, g, ru, rv, cexcl_e, cexcl_t, tc, tol, max_iter)
    if eq == -3:
        return -2, eq, t, x, y, vx, vy, phi, 0.0, 0.0, 0.0, 0.0
    if eq >= 0 and (tq < tc or where == -1):
        where = 2
        jc = eq
        tc = tq
        nx0, ny0, _ce = _edge_frame(ru, rv, eq)
        nx = -(math.cos(om * tq) * nx0 - math.sin(om * tq) * ny0)
        ny = -(math.sin(om * tq) * nx0 + math.cos(om * tq) * ny0)
    if where == -1:
        return -1, jc, t, x, y, vx, vy, phi, 0.0, 0.0, 0.0, 0.0
    if traj.shape[0] > 0:
        while ts[1] <= t + tc:
            tq_ = ts[1] - t
            _put(traj, ts, ts[1], x + vx * tq_ + 0.5 * gx * tq_ * tq_, y + vy * tq_ - 0.5 * g * tq_ * tq_, phi + om * tq_)
            ts[1] += ts[2]
    x += vx * tc + 0.5 * gx * tc * tc
    vx += gx * tc
    y += vy * tc - 0.5 * g * tc * tc
    vy -= g * tc
    phi += om * tc
    t += tc
    if where == 2:
        rx = L - x
        ry = h + top - y
    else:
        cp = math.cos(om * tc)
        sp = math.sin(om * tc)
        rx = cp * ru[jc] - sp * rv[jc]
        ry = sp * ru[jc] + cp * rv[jc]
    if traj.shape[0] > 0:
        _put(traj, ts, t, x, y, phi)
    return where, jc, t, x, y, vx, vy, phi, rx, ry, nx, ny


@njit(cache=True)
def wall_hit_in_flight(vx, vy, om, rx, ry, nx, ny, corner, rho2, mu_w, law, gx, g, lj):
    """Reset ``wall_impact`` in FLIGHT at the contact (r_x, r_y) from the CM (m) with normal (n_x, n_y) into the part:
    a vertex on the face (−x̂), or the top corner on an edge (``corner``: the edge's inward normal).

    Refuses (``why`` = :data:`WHY_WALL_SLIDE`) a contact the impact leaves pressed on the wall (no
    departure window: it would slide along it). Returns ``(vx⁺, vy⁺, ω⁺, P_t, P_n, kind, excl_t, why)``:
    ``excl_t`` (s) how long the contact provably stays open afterwards (:func:`wall_departure`,
    :func:`corner_departure`); kind IMP_INCONSISTENT: no consistent impulse.
    """
    vxp, vyp, wp, pt, pn, kind, _jt0, _jn0 = contact_impact(vx, vy, om, rx, ry, nx, ny, rho2, mu_w, law)
    if kind == IMP_INCONSISTENT:
        return vx, vy, om, 0.0, 0.0, kind, 0.0, WHY_NONE
    if corner:
        excl = corner_departure(rx, ry, vxp, vyp, wp, gx, g, -nx, -ny, 1.0)
    else:
        un = -(vxp - wp * ry)  # the wall gap's rate: 0 after a plastic impact (> 0 if it was leaving)
        vscale = max(1.0, abs(vxp) + abs(vyp) + abs(wp) * lj)
        excl = wall_departure(un if un > 0.0 else 0.0, rx, ry, wp, gx, -g, lj) if un <= 1e-12 * vscale else 1.0
    if excl <= 0.0:
        return vxp, vyp, wp, pt, pn, kind, 0.0, WHY_WALL_SLIDE
    return vxp, vyp, wp, pt, pn, kind, excl, WHY_NONE


# ---------------------------------------------------------------------------------------- PIVOT_* reaching the wall
ACT_FLIGHT = 0
ACT_REST = 1
ACT_SWING = 2
ACT_REFUSE = 3
ACT_INCONSISTENT = 4
ACT_CORNER = 5


@njit(cache=True)
def pivot_wall_hit(px, h, lj, theta, thdot, va, cqx, cqy, nx, ny, corner, rho2, mu, mu_w, law, gx, gy, lref):
    """Reset at guard ``wall_reach``: pivoting on A = (p_x, h), the part meets the wall at A + (c_x, c_y)
    (:func:`wall_contact_angle`) with the contact's normal (n_x, n_y) into the part (−x̂ on the face, an
    edge's inward normal on the top corner, ``corner``).

    In order, as the arm's ``land_side``: (1) the impulse at the wall contact alone (A free,
    :func:`contact_impact`); accepted if A then moves up (lifts): FLIGHT, the wall
    contact kept from the flight's wall guards for ``excl_t`` s. (2) Else both contacts stop
    their normal motion; A on the arm and the wall contact leave the part one degree of freedom that
    moves the contact along its normal, so the part stops — if the impulse that removes its momentum
    lies in the sum of the two friction cones (:func:`contacts_can_supply`); else the impact needs
    slip at both: refused (:data:`WHY_TWO_CONTACT`). (3) Stopped, it rests leaning on arm and wall if
    gravity is held inside both cones (``rest_against_wall``); else it swings back about A from rest
    if gravity turns it away from the wall (θ̈ > 0), else it would slide at both (refused,
    :data:`WHY_LADDER`).

    Returns ``(action, x, y, v_x, v_y, ω, excl_t, why)``: ``ACT_FLIGHT`` with the flight state
    (the wall contact to be excluded from ``wall_touch``/``corner_touch`` for excl_t s), ``ACT_REST`` (x, y the CM),
    ``ACT_SWING`` (pivot state unchanged, at rest), ``ACT_REFUSE`` with ``why``, ``ACT_INCONSISTENT``.
    """
    c = math.cos(theta)
    s = math.sin(theta)
    x = px + lj * c
    y = h + lj * s
    vx = va - thdot * lj * s
    vy = thdot * lj * c
    om = thdot
    rx = cqx - lj * c  # CM → contact
    ry = cqy - lj * s
    # (1) the impulse at the wall contact alone
    vxp, vyp, wp, pt, pn, kind, _j0, _j1 = contact_impact(vx, vy, om, rx, ry, nx, ny, rho2, mu_w, law)
    if kind == IMP_INCONSISTENT:
        return ACT_INCONSISTENT, x, y, vx, vy, om, 0.0, WHY_NONE
    ax = -lj * c  # CM → A
    ay = -lj * s
    un_a = vyp + wp * ax
    if un_a > 0.0:
        if corner:
            excl = corner_departure(rx, ry, vxp, vyp, wp, gx, -gy, -nx, -ny, 1.0)
            if excl <= 0.0:
                return ACT_REFUSE, x, y, vxp, vyp, wp, 0.0, WHY_WALL_SLIDE
            return ACT_FLIGHT, x, y, vxp, vyp, wp, excl, WHY_NONE
        vscale = max(1.0, abs(vxp) + abs(vyp) + abs(wp) * lj)
        un = -(vxp - wp * ry)
        lc = math.hypot(rx, ry)
        excl = wall_departure(un if un > 0.0 else 0.0, rx, ry, wp, gx, gy, lc) if un <= 1e-12 * vscale else 1.0
        if excl <= 0.0:
            return ACT_REFUSE, x, y, vxp, vyp, wp, 0.0, WHY_WALL_SLIDE
        return ACT_FLIGHT, x, y, vxp, vyp, wp, excl, WHY_NONE
    # (2) both stop
    pts = np.empty((2, 2))
    nrm = np.empty((2, 2))
    mus = np.empty(2)
    pts[0, 0] = ax
    pts[0, 1] = ay
    nrm[0, 0] = 0.0
    nrm[0, 1] = 1.0
    mus[0] = mu
    pts[1, 0] = rx
    pts[1, 1] = ry
    nrm[1, 0] = nx
    nrm[1, 1] = ny
    mus[1] = mu_w
    if not contacts_can_supply(pts, nrm, mus, 2, -vx, -vy, -rho2 * om, lref):
        return ACT_REFUSE, x, y, vx, vy, om, 0.0, WHY_TWO_CONTACT
    # (3) at rest leaning on arm and wall, or swinging back, or a ladder
    if contacts_can_supply(pts, nrm, mus, 2, -gx, -gy, 0.0, lref):
        return ACT_REST, x, y, 0.0, 0.0, 0.0, 0.0, WHY_NONE
    torque = c * gy - s * gx  # (CM − A) × g / ℓ: θ̈ has its sign
    if torque > 0.0:
        return ACT_SWING, x, y, 0.0, 0.0, 0.0, 0.0, WHY_NONE
    return ACT_REFUSE, x, y, 0.0, 0.0, 0.0, 0.0, WHY_LADDER


@njit(cache=True)
def nearest_side(phi, beta):
    """The side whose rest orientation β_k is nearest to φ (rad), as the engines read a tilted rest."""
    best = 0
    dmin = math.inf
    for k in range(beta.shape[0]):
        dd = abs((phi - beta[k] + math.pi) % (2.0 * math.pi) - math.pi)
        if dd < dmin:
            dmin = dd
            best = k
    return best


# ---------------------------------------------------------------------------------------- FLAT_SLIDE with a wall
@njit(cache=True)
def _rows(x0, v0, a, t0, t1, y, phi, traj, ts):
    while ts[1] <= t1:
        tq = ts[1] - t0
        _put(traj, ts, ts[1], x0 + v0 * tq + 0.5 * a * tq * tq, y, phi)
        ts[1] += ts[2]


@njit(cache=True)
def flat_offsets(k, w, beta):
    """Vertex offsets (u_j, v_j) from the CM (m) of a part flat on side k."""
    cb = math.cos(beta[k])
    sb = math.sin(beta[k])
    n = w.shape[0]
    u = np.empty(n)
    v = np.empty(n)
    for j in range(n):
        u[j] = cb * w[j, 0] - sb * w[j, 1]
        v[j] = sb * w[j, 0] + cb * w[j, 1]
    return u, v


@njit(cache=True)
def settle_walled(x, v, t, k, mu, gx, gn, h, L, top, mu_w, back, rho2, w, beta, d, uL, phi, traj, ts, rec):
    """Mode FLAT_SLIDE on side k with a wall at x = L: slide, then rest, hit the wall, or leave behind the joint.

    The CM at x (m) moves at v (m/s) with acceleration g_x − μ g_n sgn v while sliding (g_x
    gravity along the arm, g_n > 0 normal to it; μ = 0 slides on until something stops it).
    Stopped away from the wall it rests if |g_x| ≤ μ g_n, else slides downhill. Outward, the
    leading vertex (:func:`wall_reach_at_rest`) reaches the wall with the CM at x = L − u_w
    (:func:`slide_hit`); the plastic impact there stops the part if the impulse lies in the
    contacts' cones (the arm at both support vertices, the wall at the leading vertices: a
    flush side stops dead); a part whose only wall contact is its right support vertex turns
    about that corner instead (:func:`corner_pivot_rate`); anything else is refused
    (:data:`WHY_TWO_CONTACT`), as is a leading vertex above the wall's top
    (:data:`WHY_WALL_TOP`). At rest against the wall it stays if arm and wall hold gravity
    (:func:`rest_flat_at_wall`): x = L − u_w, exactly; pulled away it slides back; pushed
    into the wall and not held it is refused (:data:`WHY_LADDER`).

    Returns ``(status, x, t, ω_corner, why)``: status OK or BEHIND_JOINT (at rest or leaving
    behind the joint, x the CM), −1: the part turns about its corner vertex k at (L, h) with
    spin ω_corner (rad/s), UNRESOLVED with ``why``.
    """
    n = w.shape[0]
    u, vv = flat_offsets(k, w, beta)
    dk = d[k]
    u_w, _j_w, above = wall_reach_at_rest(u, vv + dk, top)
    jl = (k + 1) % n
    jr = k
    fr = mu * gn
    lref = math.sqrt(rho2) + dk
    x_wall = L - u_w
    y = h + dk
    sample = traj.shape[0] > 0
    for _ in range(8):
        if v == 0.0:
            if x >= x_wall - 1e-12 * (abs(L) + lref):  # against the wall
                x = x_wall
                if rest_flat_at_wall(u, vv, jl, jr, u_w, top - dk, mu, mu_w, gx, -gn, lref):
                    return _rest_walled(x, k, t, gx, gn, dk, y, phi, beta, uL, back, traj, ts, rec)
                if gx >= 0.0:
                    return C.UNRESOLVED, x, t, 0.0, WHY_LADDER
            elif abs(gx) <= fr:
                return _rest_walled(x, k, t, gx, gn, dk, y, phi, beta, uL, back, traj, ts, rec)
            sv = 1.0 if gx > 0.0 else -1.0  # slides downhill from rest
        else:
            sv = 1.0 if v > 0.0 else -1.0
        a = gx - fr * sv
        rec[C.N_SLIPS] += 1.0
        if sv > 0.0:
            hit, th, vh = slide_hit(v, a, x_wall - x)
            if not hit:  # stops short of the wall
                x_stop = x - 0.5 * v * v / a
                if sample:
                    _rows(x, v, a, t, t + th, y, phi, traj, ts)
                rec[C.SLIP_DISTANCE] += x_stop - x
                x = x_stop
                t += th
                v = 0.0
                continue
            if above:
                return C.UNRESOLVED, x, t, 0.0, WHY_WALL_TOP
            if sample:
                _rows(x, v, a, t, t + th, y, phi, traj, ts)
            rec[C.SLIP_DISTANCE] += x_wall - x
            t += th
            x = x_wall
            pts = np.empty((4, 2))
            nrm = np.empty((4, 2))
            mus = np.empty(4)
            m, nw = flat_contacts(u, vv, jl, jr, mu, mu_w, top - dk, u_w, 1e-9 * lref, pts, nrm, mus)
            k_before = 0.5 * vh * vh
            if contacts_can_supply(pts, nrm, mus, m, -vh, 0.0, 0.0, lref):
                record_impact(0.0, vh, k_before, 0.0, rec)
                v = 0.0
                continue
            if nw == 1 and u_w - u[jr] <= 1e-9 * lref:
                wp = corner_pivot_rate(vh, u[jr], dk, rho2)
                l2 = u[jr] * u[jr] + dk * dk
                record_impact(-wp * dk - vh, -wp * u[jr], k_before, 0.5 * (rho2 + l2) * wp * wp, rec)
                return -1, x, t, wp, WHY_NONE
            return C.UNRESOLVED, x, t, 0.0, WHY_TWO_CONTACT
        # inward
        if a > 0.0 and v < 0.0:  # decelerates: stops unless it leaves behind the joint first
            x_stop = x - 0.5 * v * v / a
            if x_stop + uL[k] > -back:
                t_stop = -v / a
                if sample:
                    _rows(x, v, a, t, t + t_stop, y, phi, traj, ts)
                rec[C.SLIP_DISTANCE] += x - x_stop
                x = x_stop
                t += t_stop
                v = 0.0
                continue
        x_edge = -back - uL[k]
        dist = x - x_edge
        if a != 0.0:
            disc = v * v - 2.0 * a * dist
            t_e = (-v - math.sqrt(disc if disc > 0.0 else 0.0)) / a
        else:
            t_e = dist / abs(v)
        if sample:
            _rows(x, v, a, t, t + t_e, y, phi, traj, ts)
            _put_final(traj, ts, t + t_e, x_edge, y, phi)
        rec[C.SLIP_DISTANCE] += dist
        return C.BEHIND_JOINT, x_edge, t + t_e, 0.0, WHY_NONE
    return C.UNRESOLVED, x, t, 0.0, WHY_LADDER


@njit(cache=True)
def _rest_walled(x, k, t, gx, gn, dk, y, phi, beta, uL, back, traj, ts, rec):
    rec[C.E_FINAL] = gn * dk - gx * x
    rec[C.T_REST] = t
    m = round((phi - beta[k]) / (2.0 * math.pi))
    _put_final(traj, ts, t, x, y, beta[k] + 2.0 * math.pi * m)
    if x + uL[k] <= -back:
        return C.BEHIND_JOINT, x, t, 0.0, WHY_NONE
    return C.OK, x, t, 0.0, WHY_NONE

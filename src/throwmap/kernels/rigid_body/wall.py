"""The end wall in model "rigid_body": its geometry and its guards and resets in FLIGHT and for a pivot.

The wall (:class:`throwmap.system.fixtures.Wall`) is the face x = L (the arm's
``length``, arm frame) from the arm surface y = h up to y = h + H, with its top corner
Q = (L, h + H); its normal into the part is −x̂, its Coulomb coefficient μ_w (``inf``: no
slip), and every impact with it is plastic (zero restitution), as on the arm. Gravity is a
general vector (g_x, g_y) in the arm frame; an arm at rest angle α gives
(g_x, g_y) = (−g sin α, −g cos α) (α < 0 tilts the end down: g_x > 0 pushes the
part towards the wall). Unit mass, inertia ρ² about the CM, as the rest of the
automaton (:mod:`throwmap.kernels.rigid_body`).

Guards
------
``wall_touch``   FLIGHT: the earliest time a vertex reaches x = L moving outward
                 (:func:`wall_touch_time`: the first contact with a line,
                 :func:`throwmap.kernels.flight.line_touch`, in the face's frame; it cannot
                 miss a crossing). A vertex crossing x = L above the top passes over the wall
                 and is watched no more: its edges meet the top corner.
``corner_touch`` FLIGHT: the top corner enters the flying part through an edge
                 (:func:`corner_touch_time`, lower-bound stepping on the edges' distances).
``wall_reach``   PIVOT_* about A = (p_x, h): every vertex above the line moves
                 outward as θ decreases, so the wall is a lower bound θ ≥ θ_w on the
                 pivot angle, face or corner (:func:`wall_theta`, :func:`wall_contact_angle`,
                 closed form); a sliding pivot watches the gap of :func:`fill_wall_vertices`'
                 vertices (:func:`~.slide.pivot_slide_walled`).

Resets
------
``wall_impact``  one vertex against the face, or the corner against an edge: the impact law of
                 the arm along the contact's normal (:func:`~.impact.contact_impact`) with μ_w;
                 the contact then stays open for its exact departure window
                 (:func:`throwmap.kernels.flight.departure_window` in the face's frame,
                 :func:`corner_departure`), or stays pressed (modes WALL_CONTACT, CORNER)
                 (:func:`wall_hit_in_flight`).

What follows on the wall: :mod:`.wall_slide` (WALL_CONTACT, a vertex pressed on the face),
:mod:`.wall_corner` (CORNER, an edge pressed on the top corner), :mod:`.wall_lean` (LEAN, the
arm and the wall at once, and its LADDER); statics against the wall: :mod:`.wall_statics`;
flat slides into the wall: :mod:`.flat`. What is still refused (status UNRESOLVED, reason code
``WHY_*``) is listed in :data:`~.modes.WHY_MESSAGES`.
"""

import math

import numpy as np
from numba import njit

from ..flight import SNAP, departure_window, first_contact, line_touch, lower_bound_step, separating_window
from .impact import contact_impact
from .modes import IMP_INCONSISTENT, SINK_TOL, WHY_NONE, WHY_WALL_SLIDE
from .trajectory import _put

@njit(cache=True)
def wall_touch_time(c, ru, rv, vx, om, gx, ell, excl_j, excl_t, t_max, tol, max_iter, off):
    """Guard ``wall_touch``: earliest t ∈ [0, t_max] (s) at which a vertex reaches the wall x = L moving outward.

    ``c`` the gaps L − x_j at t = 0 (m; exactly 0 for a vertex on the wall), ``(ru, rv)``
    the vertex offsets from the CM at t = 0 (m), ``vx`` the CM's velocity along the arm (m/s),
    ``om`` the spin (rad/s), ``gx`` gravity along the arm (m/s²), ``ell`` the vertex
    distances from the CM (m). Vertex ``excl_j`` (−1: none) just left the wall and stays
    off it for t < ``excl_t``; vertices with ``off[j]`` ≠ 0 are not watched (they passed above the top).

    The first contact with a line (:func:`throwmap.kernels.flight.line_touch`) in the face's frame:
    tangent ŷ, normal −x̂ into the part, so the offsets are (r_y, −r_x), the normal velocity −v_x and
    gravity against the normal g_x; a vertex resting on the face at t = 0 is held off for its departure
    window (a part may rest against the wall). Not polished (the arm's search is). Returns ``(t, j)``:
    j = −1 no wall contact before t_max, −3 ``max_iter`` steps without a decision, −2 past the spin
    angle the search resolves.
    """
    n = ru.shape[0]
    rt = np.empty(n)
    rn = np.empty(n)
    b = np.empty(n)
    for j in range(n):
        rt[j] = rv[j]
        rn[j] = -ru[j]
        b[j] = -vx + om * rv[j]
    t, j, _g, _dg = line_touch(c, b, rt, rn, -vx, om, gx, ell, excl_j, excl_t, t_max, tol, max_iter, off,
                               abs(gx) + 1e-300)
    return t, j


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
                    se = max(se, lower_bound_step(f, df, M2))
                step = max(step, se)
                clear = True
                continue
            if f > fmax:
                fmax = f
                emax = e
                dfmax = df
            if f > 0.0 or (t == 0.0 and df > 0.0 and f >= -tol * scale):
                step = max(step, lower_bound_step(f, df, M2))
        if not clear and fmax <= tol * scale and (t > 0.0 or dfmax <= 0.0):
            return t, emax  # (at t = 0 only if Q is closing in: an edge through Q that opens is no contact)
        if t + step == t:
            return t, emax if not clear else -3
        t += step
    return t, -3


@njit(cache=True)
def corner_departure(qx, qy, vx, vy, om, gx, gn, nx, ny, t_max):
    """Time (s) for which an edge that just stopped on the wall's top corner (normal velocity 0) stays off it.

    With Q − CM = (q_x, q_y) (m), CM velocity V, gravity g = (g_x, −g_n) and the edge's outward normal n
    (J: turn by +90°), the gap's Taylor bound f(s) ≥ ½ f2 s² + f3 s³/6 − M4 s⁴/24 holds for s ≤ ``t_max`` with
    f2 = −ω² n·(Q − X) − 2ω (Jn)·V − n·g, f3 = −ω³ (Jn)·(Q − X) + 3ω² n·V − 3ω (Jn)·g and
    M4 = ω⁴ D + 4|ω|³ v + 6ω² |g| (D, v: bounds on |Q − X| and |V| over ``t_max``). Returns 0.9 × the positive
    root of ½ f2 + f3 s/6 − M4 s²/24 (at most ``t_max``), or 0 if f2 < 0 (the edge is pressed on the corner) or
    f2 = 0 with f3 ≤ 0 (a tangency that does not open). f3 matters where the edge just let go of the corner
    (CORNER's lift-off, λ = 0: f2 = 0).
    """
    jx = -ny
    jy = nx
    ga = math.hypot(gx, gn)
    f2 = -om * om * (nx * qx + ny * qy) - 2.0 * om * (jx * vx + jy * vy) - (nx * gx - ny * gn)
    if f2 < 0.0 and f2 > -1e-9 * ga:
        f2 = 0.0
    if f2 < 0.0:
        return 0.0
    f3 = -om * om * om * (jx * qx + jy * qy) + 3.0 * om * om * (nx * vx + ny * vy) - 3.0 * om * (jx * gx - jy * gn)
    if f2 == 0.0 and f3 <= 0.0:
        return 0.0
    v0 = math.hypot(vx, vy)
    D = math.hypot(qx, qy) + v0 * t_max + 0.5 * ga * t_max * t_max
    vm = v0 + ga * t_max
    aw = abs(om)
    M4 = om * om * om * om * D + 4.0 * aw * aw * aw * vm + 6.0 * om * om * ga
    if M4 <= 0.0:
        return t_max
    a = M4 / 24.0
    b = f3 / 6.0
    c = 0.5 * f2
    root = (b + math.sqrt(b * b + 4.0 * a * c)) / (2.0 * a)
    return min(0.9 * root, t_max) if root > 0.0 else 0.0


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
def rearm_wall_window(corner, x, y, vx, vy, phi, om, w, k, L, h, top, gx, gn, tol):
    """The exclusion window (s) of face vertex ``k`` (``corner`` False) or of edge ``k`` on the wall's top corner
    (``corner`` True) after an impact on the arm changed the velocity (the window it got when it left the wall
    holds only for the free flight it was computed on). From the new state (CM (x, y), velocity (v_x, v_y),
    orientation φ, spin ω; SI): 0 when the vertex (edge) is more than ``tol`` (m) off the wall, the separating or
    departure window when it touches and leaves, −1 when it touches and does not leave (pressed back on the wall:
    a second contact at the same instant)."""
    c = math.cos(phi)
    s = math.sin(phi)
    ax = c * w[k, 0] - s * w[k, 1]
    ay = s * w[k, 0] + c * w[k, 1]
    ga = abs(gx) + gn
    if not corner:
        if L - (x + ax) > tol:
            return 0.0
        lj = math.hypot(ax, ay)
        un = -(vx - om * ay)  # the vertex's velocity away from the face
        if un > 1e-12 * (abs(vx) + abs(vy) + abs(om) * lj):
            return separating_window(un, ga + om * om * lj)
        win = departure_window(ay, -ax, om, gx, lj, ga)
        return win if win > 0.0 else -1.0
    n = w.shape[0]
    bx = c * w[(k + 1) % n, 0] - s * w[(k + 1) % n, 1]
    by = s * w[(k + 1) % n, 0] + c * w[(k + 1) % n, 1]
    le = math.hypot(bx - ax, by - ay)
    nx = (by - ay) / le  # the edge's outward normal (n·a > 0)
    ny = -(bx - ax) / le
    if nx * ax + ny * ay < 0.0:
        nx = -nx
        ny = -ny
    qx = L - x
    qy = h + top - y
    if nx * (qx - ax) + ny * (qy - ay) > tol:
        return 0.0
    un = -(nx * (vx - om * qy) + ny * (vy + om * qx))  # the gap's rate: the part's point at Q moving along −n
    if un > 1e-12 * (abs(vx) + abs(vy) + abs(om) * math.hypot(qx, qy)):
        m2, _m3 = corner_bounds(qx, qy, vx, vy, om, gx, gn, 1.0)
        return separating_window(un, m2)
    win = corner_departure(qx, qy, vx, vy, om, gx, gn, nx, ny, 1.0)
    return win if win > 0.0 else -1.0


@njit(cache=True)
def sink_slack(x, y, phi, w, k, h):
    """How far (m) below the arm's line y = ``h`` vertex ``k`` (body offsets ``w``, CM (x, y), orientation φ) may
    sink before its arm guard fires in a wall mode it enters just after leaving the arm: its depth now (0 when
    above) plus :data:`~.modes.SINK_TOL` of the part's size. The vertex's departure window is estimated for free
    flight; on the wall's face or corner the wall's force can press it back into the arm, which this guard
    catches (the mode then ends as a second contact, never a vertex inside the arm). 0 for ``k`` < 0: none."""
    if k < 0:
        return 0.0
    c = math.cos(phi)
    s = math.sin(phi)
    yk = y + s * w[k, 0] + c * w[k, 1]
    size = 0.0
    for i in range(w.shape[0]):
        size = max(size, math.hypot(w[i, 0], w[i, 1]))
    return max(h - yk, 0.0) + SINK_TOL * size


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
    if gx != 0.0:  # the same arithmetic as the plain arm's fly(): a flight that meets no wall is the same
        x += 0.5 * gx * tc * tc
        x += vx * tc
        vx += gx * tc
    else:
        x += vx * tc
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

    Refuses (``why`` = :data:`~.modes.WHY_WALL_SLIDE`) a contact the impact leaves pressed on the wall (no
    departure window: it would slide along it). Returns ``(vx⁺, vy⁺, ω⁺, P_t, P_n, kind, excl_t, why)``:
    ``excl_t`` (s) how long the contact provably stays open afterwards (:func:`~throwmap.kernels.flight.departure_window`,
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
        excl = departure_window(ry, -rx, wp, gx, lj, abs(gx) + g) if un <= 1e-12 * vscale else \
            separating_window(un, abs(gx) + wp * wp * lj)
    if excl <= 0.0:
        return vxp, vyp, wp, pt, pn, kind, 0.0, WHY_WALL_SLIDE
    return vxp, vyp, wp, pt, pn, kind, excl, WHY_NONE

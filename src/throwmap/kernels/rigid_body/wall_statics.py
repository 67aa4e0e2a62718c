"""Statics and flat slides against the wall for model "rigid_body": exact cone tests, FLAT_SLIDE into the wall.

Part of :mod:`.wall`: whether contact forces (or impulses) inside the contacts' friction
cones can supply a wrench (:func:`cone_contains`, exact by Carathéodory's theorem), the
contacts of a part flat on a side against the wall, and the flat slide that reaches it
(:func:`settle_walled`: stop dead, turn about the corner vertex, rest at x = L − u_w).
"""

import math

import numpy as np
from numba import njit

from .. import codes as C
from .impact import record_impact
from .trajectory import _put, _put_final
from .wall_contact import CONE_TOL, WHY_LADDER, WHY_NONE, WHY_TWO_CONTACT


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


@njit(cache=True)
def reach_below(u, vh, top):
    """The outline's largest x offset from the CM (m) at heights ≤ ``top`` above the arm: a vertex that low, or an
    edge crossing that height (vertex offsets ``u``, heights ``vh``, in order around the part)."""
    n = u.shape[0]
    best = -math.inf
    for j in range(n):
        j2 = (j + 1) % n
        if vh[j] <= top:
            best = max(best, u[j])
        if (vh[j] - top) * (vh[j2] - top) < 0.0:
            best = max(best, u[j] + (top - vh[j]) * (u[j2] - u[j]) / (vh[j2] - vh[j]))
    return best


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
def _rows(x0, v0, a, t0, t1, y, phi, traj, ts):
    while ts[1] <= t1:
        tq = ts[1] - t0
        _put(traj, ts, ts[1], x0 + v0 * tq + 0.5 * a * tq * tq, y, phi)
        ts[1] += ts[2]


@njit(cache=True)
def settle_walled(x, v, t, k, mu, gx, gn, h, L, top, mu_w, back, rho2, w, beta, d, uL, uR, phi, traj, ts, rec):
    """Mode FLAT_SLIDE on side k with a wall at x = L: slide, then rest, hit the wall, or leave behind the joint.

    The CM at x (m) moves at v (m/s) with acceleration g_x − μ g_n sgn v while sliding (g_x
    gravity along the arm, g_n > 0 normal to it; μ = 0 slides on until something stops it).
    Stopped away from the wall it rests if |g_x| ≤ μ g_n, else slides downhill. Outward, the
    leading vertex (:func:`wall_reach_at_rest`) reaches the wall with the CM at x = L − u_w
    (:func:`slide_hit`); the plastic impact there stops the part if the impulse lies in the
    contacts' cones (the arm at both support vertices, the wall at the leading vertices: a
    flush side stops dead); a part whose only wall contact is its right support vertex turns
    about that corner instead (:func:`corner_pivot_rate`); anything else is refused
    (:data:`WHY_TWO_CONTACT`); a leading vertex above the wall's top hands over to :mod:`.wall_lean`
    where its edge meets the top corner. At rest against the wall it stays if arm and wall hold gravity
    (:func:`rest_flat_at_wall`): x = L − u_w (rounded down where needed so that x + u_R ≤ L, the start
    rule of :func:`throwmap.system.starts.start_interval`); pulled away it slides back; pushed
    into the wall and not held it is refused (:data:`WHY_LADDER`).

    Returns ``(status, x, t, ω_corner, why)``: status OK or BEHIND_JOINT (at rest or leaving
    behind the joint, x the CM), −1: the part turns about its corner vertex k at (L, h) with
    spin ω_corner (rad/s), −2: an edge meets the wall's top corner (a leading vertex above the top:
    the outline's reach below the top, :func:`reach_below`, touches it), the CM at x moving at
    ω_corner (m/s) — :mod:`.wall_lean`'s impact decides — UNRESOLVED with ``why``.
    """
    n = w.shape[0]
    u, vv = flat_offsets(k, w, beta)
    dk = d[k]
    u_w, _j_w, above = wall_reach_at_rest(u, vv + dk, top)
    if above:  # the leading vertex passes over the wall: an edge meets its top corner when the outline's reach
        u_w = reach_below(u, vv + dk, top)  # below the top does
    jl = (k + 1) % n
    jr = k
    fr = mu * gn
    lref = math.sqrt(rho2) + dk
    x_wall = L - u_w
    while x_wall + uR[k] > L:  # resting against the wall is a start throw() accepts: x + u_R ≤ L in floating point
        x_wall = np.nextafter(x_wall, -math.inf)
    y = h + dk
    sample = traj.shape[0] > 0
    for _ in range(8):
        if v == 0.0:
            if x >= x_wall - 1e-12 * (abs(L) + lref):  # against the wall
                x = x_wall
                if above:  # at rest on an edge against the top corner: the contacts of wall_lean decide
                    return -2, x, t, 0.0, WHY_NONE
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
            if sample:
                _rows(x, v, a, t, t + th, y, phi, traj, ts)
            rec[C.SLIP_DISTANCE] += x_wall - x
            t += th
            x = x_wall
            if above:  # an edge meets the wall's top corner at speed vh: the multi-contact impact of wall_lean
                return -2, x, t, vh, WHY_NONE
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

"""Statics against the wall for model "rigid_body": exact friction-cone tests of a part touching the arm and the wall.

Whether contact forces (or impulses) inside the contacts' friction cones can supply a wrench
(:func:`contacts_can_supply`, exact by Carathéodory's theorem, :func:`cone_contains`): a part at rest
touching the arm and the wall stays if they balance gravity (rest ``rest_against_wall``,
:func:`rest_flat_at_wall` for a part flat on a side, with its contacts :func:`flat_contacts`); a
plastic impact that stops the part is one whose impulse they can supply (the flat slide into the
wall, :func:`~.flat.settle_walled`; a stop in LEAN, :mod:`.wall_lean`).
"""

import math

import numpy as np
from numba import njit

CONE_TOL = 1e-11
"""Relative tolerance of :func:`cone_contains` (residual and negative coefficients, relative to |b|)."""


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

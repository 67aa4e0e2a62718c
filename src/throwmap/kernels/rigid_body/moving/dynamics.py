"""Constrained Newton–Euler equations of one polygon on a moving arm, in the arm frame.

Arm frame: origin at the joint, x along the arm, the arm's surface the line y = h; it turns
with the arm at angle ψ = α + θ(t) about the joint (rate Ω = θ̇, Ω̇ = θ̈; :mod:`.profile`).
State s = (x, y, φ, v_x, v_y, ω): the CM's position (m) and velocity (m/s) and the part's
orientation (rad) and spin (rad/s), all relative to the arm. Unit mass, inertia ρ² (m²).

Applied field per unit mass (the arm's motion enters only here; d'Alembert):

    f = g(ψ) + Ω² r − Ω̇ ẑ × r − 2 Ω ẑ × v,   g(ψ) = (−g sin ψ, −g cos ψ)
      = (−g sin ψ + Ω² x + Ω̇ y + 2Ω v_y,  −g cos ψ + Ω² y − Ω̇ x − 2Ω v_x),
    angular:  ω̇ = τ/ρ² − Ω̇      (gravity and the fictitious forces act at the CM: no torque).

Contacts: vertex j at offset r_j = R(φ) w_j (m) from the CM, on the line (gap y + r_jy − h = 0).
A force (T, N) at vertex j adds (T, N) to the CM and r_jx N − r_jy T to the torque. A contact set
``act`` (1 vertex: a pivot; 2 adjacent vertices: a side flat) with ``tmode`` 0 (sticking: one
tangential constraint, the total friction T applied at act[0] — both vertices of a flat side lie
on the line, so T's moment does not depend on where it acts) or σ = ±1 (sliding with slip
velocity sign σ, T_j = −μσN_j) gives the linear system (M = diag(1, 1, ρ²), a = (a_x, a_y, ω̇))

    M a − Σ_j N_j (n_j − μσ t_j) − T t_c = M f,     n_j = (0, 1, r_jx),  t_j = (1, 0, −r_jy)
    n_j · a = ω² r_jy   (the vertex's normal acceleration is 0)
    t_c · a = ω² r_cx   (sticking: the tangential acceleration is 0)

solved by :func:`solve` (numpy, a 4×4 to 6×6 system). Painlevé: a sliding vertex whose normal
effective mass A = n · M⁻¹ (n − μσ t) is ≤ 0 has no consistent Coulomb solution (the static
automaton's D ≤ 0); a flat side sliding is accepted wherever its 2×2 system is regular and its
forces are ≥ 0 (existence; A need not be a P-matrix).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["Body", "applied", "solve", "offsets", "gaps", "vertex_velocity"]


class Body:
    """The part's data the equations need: body-frame vertices ``w`` (n, 2) about the CM (m), ``rho2`` (m²),
    the sides' CM distances ``d`` and orientations ``beta`` (side k joins vertices k and k+1)."""

    def __init__(self, w, rho2, d, beta):
        self.w = np.asarray(w, dtype=float)
        self.n = self.w.shape[0]
        self.rho2 = float(rho2)
        self.d = np.asarray(d, dtype=float)
        self.beta = np.asarray(beta, dtype=float)
        self.lmax = float(np.max(np.hypot(self.w[:, 0], self.w[:, 1])))

    def side_of(self, i: int, j: int) -> int:
        """The side joining vertices i and j (adjacent), or −1."""
        if (i + 1) % self.n == j:
            return i
        if (j + 1) % self.n == i:
            return j
        return -1


def offsets(body: Body, phi: float):
    """Vertex offsets r_j = R(φ) w_j (m), as arrays (rx, ry)."""
    c, s = math.cos(phi), math.sin(phi)
    w = body.w
    return c * w[:, 0] - s * w[:, 1], s * w[:, 0] + c * w[:, 1]


def gaps(body: Body, s, h: float):
    """Heights of the vertices above the arm line y = h (m), and the offsets (rx, ry)."""
    rx, ry = offsets(body, s[2])
    return s[1] + ry - h, rx, ry


def vertex_velocity(s, rx, ry):
    """Velocity (tangential, normal) of the vertex at offset (rx, ry) (m/s): v + ω ẑ × r."""
    return s[3] - s[5] * ry, s[4] + s[5] * rx


def applied(s, g: float, psi: float, Om: float, Omd: float):
    """The applied field per unit mass (m/s², m/s², rad/s²) at state ``s`` for arm angle ψ = α + θ (rad),
    rate Ω (rad/s) and acceleration Ω̇ (rad/s²): gravity, centrifugal, Euler and Coriolis terms."""
    x, y, vx, vy = s[0], s[1], s[3], s[4]
    fx = -g * math.sin(psi) + Om * Om * x + Omd * y + 2.0 * Om * vy
    fy = -g * math.cos(psi) + Om * Om * y - Omd * x - 2.0 * Om * vx
    return fx, fy, -Omd


def solve(body: Body, s, f, act, tmode: int, mu: float):
    """Accelerations and contact forces of contact set ``act`` in mode ``tmode`` (0 stick, ±1 slide σ).

    Returns ``(a, N, T, ok)``: a = (a_x, a_y, ω̇), N the normal forces (per unit mass, m/s²) of ``act``,
    T the total tangential force, ``ok`` False when the system is singular or (sliding) not a
    P-matrix (Painlevé)."""
    rho2 = body.rho2
    if not act:
        return np.array([f[0], f[1], f[2]]), np.zeros(0), 0.0, True
    rx, ry = offsets(body, s[2])
    om = s[5]
    k = len(act)
    nt = 1 if tmode == 0 else 0
    m = 3 + k + nt
    A = np.zeros((m, m))
    b = np.zeros(m)
    A[0, 0] = 1.0
    A[1, 1] = 1.0
    A[2, 2] = rho2
    b[0], b[1], b[2] = f[0], f[1], rho2 * f[2]
    for i, j in enumerate(act):
        col = 3 + i
        # force column: n_j − μσ t_j (sliding) or n_j
        cx, cy, cw = 0.0, 1.0, rx[j]
        if tmode != 0:
            cx -= mu * tmode
            cw += mu * tmode * ry[j]
        A[0, col] = -cx
        A[1, col] = -cy
        A[2, col] = -cw
        # constraint row: n_j · a = ω² r_jy
        A[col, 1] = 1.0
        A[col, 2] = rx[j]
        b[col] = om * om * ry[j]
    if nt:
        c = act[0]
        col = 3 + k
        A[0, col] = -1.0
        A[2, col] = ry[c]
        A[col, 0] = 1.0
        A[col, 2] = -ry[c]
        b[col] = om * om * rx[c]
    try:
        z = np.linalg.solve(A, b)
    except np.linalg.LinAlgError:
        return np.zeros(3), np.zeros(k), 0.0, False
    if not np.all(np.isfinite(z)):
        return np.zeros(3), np.zeros(k), 0.0, False
    N = z[3:3 + k]
    T = z[3 + k] if nt else -mu * tmode * float(np.sum(N))
    ok = True
    if tmode != 0:
        ok = _p_matrix(rx, ry, act, tmode, mu, rho2)
    return z[:3], N, float(T), ok


def _p_matrix(rx, ry, act, sig, mu, rho2) -> bool:
    """Whether the sliding contacts' normal effective-mass matrix A_ij = n_i · M⁻¹ (n_j − μσ t_j) is a
    P-matrix (positive principal minors): the Painlevé consistency of Coulomb sliding."""
    k = len(act)
    A = np.empty((k, k))
    for a, i in enumerate(act):
        for b, j in enumerate(act):
            # n_i · M⁻¹ c_j with c_j = (−μσ, 1, r_jx + μσ r_jy)
            A[a, b] = 1.0 + rx[i] * (rx[j] + mu * sig * ry[j]) / rho2
    if k == 1:
        return A[0, 0] > 0.0
    # a flat side sliding: A need not be a P-matrix for a solution to exist (only for it to be unique); the
    # solve's forces are accepted where they are ≥ 0 (checked by the caller) and A is not singular
    return abs(A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0]) > 1e-12 * (abs(A[0, 0] * A[1, 1]) + abs(A[0, 1] * A[1, 0]))

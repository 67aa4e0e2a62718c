"""Independent reference implementation of model "paper" (Sec. III, Eqs. 1–4), plain Python + SciPy.

A deliberately straightforward, per-throw second method for the compiled kernels
of :mod:`throwmap.kernels.paper`. It shares *no code* with them: it reads only the
part's clockwise CM-centred vertices ``part.w``, the rest rotations ``part.beta``
and ``part.radius_of_gyration``, and recomputes every other quantity itself. Each
step uses a different numerical method from the kernels:

==================  ===============================================  ==============================
phase               reference (here)                                 kernels
==================  ===============================================  ==============================
first contact       grid scan of every vertex gap (``dt``), then     safeguarded Newton-like
(Eqs. 1–3)          :func:`scipy.optimize.brentq` in the first       lower-bound stepping
                    bracket (every vertex, earliest root wins)
plastic impact      5×5 linear system (momentum, angular momentum,   closed form, Eq. (4)
(Eq. 4)             contact velocity = 0), :func:`numpy.linalg.solve`
pivoting            :func:`scipy.integrate.solve_ivp` of             energy / barrier algebra
                    I_P ψ̈ = torque of gravity, terminal events
                    "adjacent side flat"
side landings       the same 5×5 linear system about the side's      closed-form ratio
                    other vertex
==================  ===============================================  ==============================

Model (paper Sec. III, with the corrections the kernels document)
-----------------------------------------------------------------
Release from rest at ``(x0, side)`` on the line y = h with arm rate ω: CM velocity
ω(−(h+d), x0), spin ω; ballistic flight under g along −y. First contact is the
first t > 0 at which *any* vertex reaches y = h. The impact is plastic and
no-slip about that vertex. Afterwards the part pivots about its contact vertex
(no slip, no lift-off) until one of the two sides adjacent to that vertex lies
flat, which is again a plastic no-slip impact, about the side's other vertex B.
If the post-landing rotation about B would push the first vertex into the arm,
both vertices stay down: the part rests (stable side) or tips, from rest, about
the vertex its CM overhangs (unstable side). If it lifts and the side is stable
with kinetic energy below both topple barriers g(ℓ_A − d) and g(ℓ_B − d) (per
unit mass), it rocks to rest there (every later swing has less energy);
otherwise the pivoting continues about B.

Status strings: ``"ok"``; ``"behind_joint"`` (a contact vertex — first contact,
a landing vertex or a pivot — or the resting left support vertex at x ≤ 0);
``"off_end"`` (a contact beyond ``arm.length``, or at rest with the right support vertex beyond it);
``"no_rest"`` (``max_impacts`` reached, or a pivot swing that never ends within
``pivot_t_max``); ``"no_contact"`` (no contact within ``t_max``).

Conditioning
------------
Every discrete decision is recorded with its margin (``margins`` in the result):
the energy of a swing against the potential peak ahead (flip or fall back), the
lift ratio at a landing (pivot on or stay down), the time to the second vertex
crossing and the depth of a near-grazing vertex (which vertex touches first), and
the distance of decisive positions from the joint and the arm's end.
``ill_conditioned`` says that some decision is within 1e-6 (relative) or 1e-9
(s, m) of flipping: there, a comparison with any other method is meaningless.

Notes
-----
The grid scan assumes a vertex gap cannot dip below the arm and re-emerge
within one grid step without its rate changing sign there (dips are found by
locating the minimum where the rate goes from − to +); with |G''| ≤ g + ω²ℓ this
holds for the sizes and rates used here. This module is slow on purpose (a few
ms per throw); it is the baseline the compiled batch is benchmarked against.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

__all__ = [
    "reference_throw",
    "reference_roll",
    "impact_linear_system",
    "rest_geometry",
    "DEFAULT_DT",
    "DEFAULT_T_MAX",
    "DEFAULT_MAX_IMPACTS",
    "DEFAULT_RTOL",
    "DEFAULT_ATOL",
    "DEFAULT_PIVOT_T_MAX",
    "ILL_CONDITIONED_BELOW",
]

DEFAULT_DT = 1e-4
"""Grid step of the first-contact scan, s."""
DEFAULT_T_MAX = 20.0
"""Longest flight searched, s (status ``"no_contact"`` beyond)."""
DEFAULT_MAX_IMPACTS = 1000
"""Cap on plastic impacts in one throw (status ``"no_rest"`` beyond)."""
DEFAULT_RTOL = 1e-11
"""Relative tolerance of the pivot integration (``solve_ivp``, DOP853)."""
DEFAULT_ATOL = 1e-13
"""Absolute tolerance of the pivot integration (rad, rad/s)."""
DEFAULT_PIVOT_T_MAX = 60.0
"""Longest single pivot swing integrated, s (a swing balancing on its peak)."""
ILL_CONDITIONED_BELOW = 1e-6
"""Relative decision margin below which a throw is flagged ill-conditioned."""

_BRENT_XTOL = 1e-15  # s
_BRENT_RTOL = 4.0 * np.finfo(float).eps  # the smallest brentq accepts
_CONTACT_TIE = 1e-9  # s: two vertex crossings closer than this are a tie
_GRAZE_DEPTH = 1e-9  # m: a vertex passing this close above the arm is a near-graze
_JOINT_NEAR = 1e-9  # m: contacts this close to x = 0 or the arm's end are ill-conditioned


# ---------------------------------------------------------------------------- geometry
def _rot(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s], [s, c]])


def rest_geometry(part, side: int) -> dict:
    """Rest geometry of ``side`` recomputed from ``part.w`` and ``part.beta`` (m).

    Returns ``p`` (vertices relative to the CM at the rest orientation, (n, 2)),
    ``d`` (CM height), ``uL``/``uR`` (x of the left/right support vertex relative
    to the CM), ``stable``.
    """
    n = len(part.w)
    p = np.asarray(part.w, dtype=float) @ _rot(float(part.beta[side])).T
    iR, iL = side, (side + 1) % n
    d = -0.5 * (p[iR, 1] + p[iL, 1])
    uR, uL = float(p[iR, 0]), float(p[iL, 0])
    return {"p": p, "d": float(d), "uL": uL, "uR": uR, "stable": uL < 0.0 < uR}


def impact_linear_system(vx: float, vy: float, w: float, rx: float, ry: float, rho2: float):
    """Plastic no-slip impact about a contact point, solved as a 5×5 linear system.

    Unknowns ``(ẋ⁺, ẏ⁺, φ̇⁺, J_x, J_y)`` (impulse per unit mass, m/s):
    ``ẋ⁺ − ẋ = J_x``, ``ẏ⁺ − ẏ = J_y``, ``ρ²(φ̇⁺ − φ̇) = r_x J_y − r_y J_x`` and
    the contact point at rest afterwards, ``ẋ⁺ − φ̇⁺ r_y = 0``, ``ẏ⁺ + φ̇⁺ r_x = 0``.
    ``(rx, ry)`` is CM → contact point (m), ``rho2`` = ρ² (m²).
    Returns ``(vx⁺, vy⁺, w⁺, Jx, Jy)``.
    """
    A = np.array(
        [
            [1.0, 0.0, 0.0, -1.0, 0.0],
            [0.0, 1.0, 0.0, 0.0, -1.0],
            [0.0, 0.0, rho2, ry, -rx],
            [1.0, 0.0, -ry, 0.0, 0.0],
            [0.0, 1.0, rx, 0.0, 0.0],
        ]
    )
    b = np.array([vx, vy, rho2 * w, 0.0, 0.0])
    sol = np.linalg.solve(A, b)
    return tuple(float(s) for s in sol)


# ---------------------------------------------------------------------- first contact
def _gap_functions(x0, d, omega, g, p, supports):
    """Vertex gaps above the arm line during flight and their rates.

    ``gap_j(t) = (d + v_j) + x0 ω t − ½ g t² + u_j sin ωt + v_j (cos ωt − 1)``
    (Eqs. 1–3 for every vertex). For the two support vertices ``d + v_j = 0``
    exactly and the *reduced* gap ``gap_j / t`` (limit ω(x0 + u_j) at t = 0) is
    used for sign tests and root finding, so that t = 0 is not a root.
    """
    u = p[:, 0]
    v = p[:, 1]
    c0 = d + v
    c0 = np.where(supports, 0.0, c0)

    def gap(j, t):
        wt = omega * t
        return c0[j] + x0 * omega * t - 0.5 * g * t * t + u[j] * math.sin(wt) - 2.0 * v[j] * math.sin(0.5 * wt) ** 2

    def reduced(j, t):
        if not supports[j]:
            return gap(j, t)
        if t == 0.0:
            return omega * (x0 + u[j])
        wt = omega * t
        return x0 * omega - 0.5 * g * t + u[j] * math.sin(wt) / t - 2.0 * v[j] * math.sin(0.5 * wt) ** 2 / t

    def rate(j, t):
        wt = omega * t
        return x0 * omega - g * t + omega * (u[j] * math.cos(wt) - v[j] * math.sin(wt))

    def grid(t):
        wt = omega * t[:, None]
        base = x0 * omega * t[:, None] - 0.5 * g * t[:, None] ** 2
        G = c0[None, :] + base + u[None, :] * np.sin(wt) - 2.0 * v[None, :] * np.sin(0.5 * wt) ** 2
        tt = np.where(t[:, None] > 0.0, t[:, None], 1.0)
        Gr = np.where(supports[None, :] & (t[:, None] > 0.0), G / tt, G)
        Gr = np.where(supports[None, :] & (t[:, None] == 0.0), omega * (x0 + u[None, :]), Gr)
        dG = x0 * omega - g * t[:, None] + omega * (u[None, :] * np.cos(wt) - v[None, :] * np.sin(wt))
        return G, Gr, dG

    return gap, reduced, rate, grid


def _first_contact(x0, d, omega, g, p, supports, dt, t_max):
    """Earliest t > 0 at which a vertex gap reaches 0; returns ``(t, j, margin_info)``.

    Scans a grid of step ``dt`` (in chunks) for the first interval where any
    (reduced) gap is negative at its right end or dips below zero inside it,
    then solves every vertex's crossing in that interval with ``brentq`` and
    keeps the earliest. ``j = -1`` if nothing within ``t_max``.
    """
    gap, reduced, rate, grid = _gap_functions(x0, d, omega, g, p, supports)
    n = p.shape[0]
    chunk = 4096
    graze = math.inf  # smallest positive local minimum of a gap before contact, m
    i0 = 0
    while i0 * dt < t_max:
        t = (i0 + np.arange(chunk + 1)) * dt
        G, Gr, dG = grid(t)
        neg = Gr[1:] < 0.0  # negative at the right end of [t_i, t_{i+1}]
        dip = (dG[:-1] < 0.0) & (dG[1:] > 0.0)  # a local minimum inside [t_i, t_{i+1}]
        for k in np.flatnonzero(np.any(neg | dip, axis=1)):
            ta, tb = float(t[k]), float(t[k + 1])
            roots = []
            for j in range(n):
                if neg[k, j]:
                    if Gr[k, j] <= 0.0:  # exactly on the arm at the grid point
                        roots.append((ta, j))
                    else:
                        roots.append((brentq(lambda s: reduced(j, s), ta, tb, xtol=_BRENT_XTOL, rtol=_BRENT_RTOL), j))
                elif dip[k, j]:
                    tm = brentq(lambda s: rate(j, s), ta, tb, xtol=_BRENT_XTOL, rtol=_BRENT_RTOL)
                    gm = gap(j, tm)
                    if gm < 0.0:  # dips below the arm and re-emerges inside the interval
                        roots.append((brentq(lambda s: reduced(j, s), ta, tm, xtol=_BRENT_XTOL, rtol=_BRENT_RTOL), j))
                    else:
                        graze = min(graze, gm)
            if not roots:
                continue
            roots.sort()
            t_c, jc = roots[0]
            tie = roots[1][0] - t_c if len(roots) > 1 else math.inf
            # re-check: no other vertex is below the arm at t_c (it would have crossed earlier)
            for j in range(n):
                if j != jc and reduced(j, t_c) < -1e-12:
                    raise RuntimeError(f"first-contact scan missed vertex {j} crossing before t = {t_c}")
            return t_c, jc, {"tie": tie, "graze": graze}
        i0 += chunk
    return t_max, -1, {"tie": math.inf, "graze": graze}


# --------------------------------------------------------------------------- pivoting
def _pivot_swing(part, j, psi0, psidot0, g, rtol, atol, t_max):
    """Integrate pivoting about vertex ``w_j`` from body angle ``psi0`` at rate ``psidot0``.

    Body angle ψ: world vertex = CM + R(ψ) w. With the pivot fixed, per unit mass
    ``I_P ψ̈ = g (R(ψ) w_j)_x`` (torque of gravity about the pivot), I_P = ρ² + |w_j|².
    Terminal events: side j (w_j → w_{j+1}) flat, side j−1 (w_{j−1} → w_j) flat.
    Returns ``(side_landed, other_vertex, psi, psidot, crossed_peak)`` or ``None``
    if neither side lands within ``t_max``.
    """
    w = np.asarray(part.w, dtype=float)
    n = len(w)
    wj = w[j]
    I_P = part.radius_of_gyration**2 + float(wj @ wj)
    e_next = w[(j + 1) % n] - wj
    e_prev = w[(j - 1) % n] - wj

    def rhs(_t, y):
        c, s = math.cos(y[0]), math.sin(y[0])
        return [y[1], g * (c * wj[0] - s * wj[1]) / I_P]

    def flat_next(_t, y):
        return math.sin(y[0]) * e_next[0] + math.cos(y[0]) * e_next[1]

    def flat_prev(_t, y):
        return math.sin(y[0]) * e_prev[0] + math.cos(y[0]) * e_prev[1]

    for ev in (flat_next, flat_prev):
        ev.terminal = True
        ev.direction = -1.0
    sol = solve_ivp(rhs, (0.0, t_max), [psi0, psidot0], method="DOP853", events=(flat_next, flat_prev),
                    rtol=rtol, atol=atol)
    hits = [(float(sol.t_events[i][0]), i) for i in range(2) if len(sol.t_events[i])]
    if not hits:
        return None
    _, which = min(hits)
    psi, psidot = (float(a) for a in sol.y_events[which][0])
    qx0 = -(math.cos(psi0) * wj[0] - math.sin(psi0) * wj[1])  # (CM − pivot)_x at start
    qx1 = -(math.cos(psi) * wj[0] - math.sin(psi) * wj[1])
    crossed = (qx0 > 0.0) != (qx1 > 0.0)
    if which == 0:
        return j, (j + 1) % n, psi, psidot, crossed
    return (j - 1) % n, (j - 1) % n, psi, psidot, crossed


def reference_roll(part, arm, j, psi, psidot, px, *, side0=-1, max_impacts=DEFAULT_MAX_IMPACTS,
                   rtol=DEFAULT_RTOL, atol=DEFAULT_ATOL, pivot_t_max=DEFAULT_PIVOT_T_MAX, n_impacts=0):
    """From pivoting on vertex ``w_j`` (world x ``px``) at body angle ``psi`` (rad) and rate
    ``psidot`` (rad/s, CCW +), follow swings and side landings until the part rests.

    ``side0`` is the side the part was thrown from (−1: none). The pivot's world
    x is tracked through every landing; the resting CM x follows from it.

    Returns a dict: ``x`` (resting CM x, m; for an escape the CM x flat on the
    side just landed on), ``side``, ``status``, ``escape`` (which contact decided
    a non-"ok" status: ``"landing_vertex"``, ``"rest_left_vertex"``, ``"rest_cm"``,
    ``"cap"`` or ``""``), ``n_impacts`` (``n_impacts`` given plus the landings),
    ``n_flips`` (side changes: landings on a side other than the last one landed
    on, starting from ``side0``), ``n_peaks`` (potential peaks crossed over a
    pivot), ``margins`` (see :func:`reference_throw`), ``max_impact_energy_gain``
    (J/kg, ≤ 0 for a physical impact).
    """
    w = np.asarray(part.w, dtype=float)
    g = arm.g
    L = math.inf if arm.length is None else float(arm.length)
    rho2 = part.radius_of_gyration**2
    ell = np.hypot(w[:, 0], w[:, 1])
    margins = {"energy": math.inf, "lift": math.inf, "position": math.inf}
    n_flips = n_peaks = 0
    last_side = side0
    gain = -math.inf

    def result(x, side, status, escape=""):
        return {"x": float(x), "side": int(side), "status": status, "escape": escape, "n_impacts": int(n_impacts),
                "n_flips": n_flips, "n_peaks": n_peaks, "margins": {key: float(val) for key, val in margins.items()},
                "max_impact_energy_gain": float(gain)}

    def near(*positions):  # distance of position tests from x = 0 and x = L, m
        for pos in positions:
            margins["position"] = min(margins["position"], abs(float(pos)), abs(float(pos) - L))

    while True:
        # ----------------------------------------------------------- swing about w_j
        q = -(_rot(psi) @ w[j])  # CM − pivot
        I_P = rho2 + ell[j] ** 2
        E = 0.5 * I_P * psidot**2 + g * q[1]
        if psidot * q[0] > 0.0 or abs(q[0]) < ILL_CONDITIONED_BELOW * ell[j]:  # heading for (or at) the peak
            margins["energy"] = min(margins["energy"], abs(E - g * ell[j]) / (g * ell[j]))
        swing = _pivot_swing(part, j, psi, psidot, g, rtol, atol, pivot_t_max)
        if swing is None:
            return result(math.nan, -1, "no_rest", "cap")
        k, jB, _psi_ev, psidot_ev, crossed = swing
        n_peaks += int(crossed)
        if k != last_side:
            n_flips += 1
            last_side = k
        # ----------------------------------------------------------- landing on side k
        n_impacts += 1
        geo = rest_geometry(part, k)
        qA = geo["p"][j]  # CM → A (the pivot), flat on side k
        qB = geo["p"][jB]  # CM → B (the landing vertex)
        x_cm = px - qA[0]
        xB = x_cm + qB[0]
        if n_impacts > max_impacts:
            return result(x_cm, k, "no_rest", "cap")
        near(xB)
        if xB <= 0.0:
            return result(x_cm, k, "behind_joint", "landing_vertex")
        if xB > L:
            return result(x_cm, k, "off_end", "landing_vertex")
        # plastic no-slip impact about B; pre-impact CM velocity psidot × (CM − A), CM − A = −qA
        vx, vy = psidot_ev * qA[1], -psidot_ev * qA[0]
        k_before = 0.5 * (vx * vx + vy * vy + rho2 * psidot_ev**2)
        vxp, vyp, wp, _, _ = impact_linear_system(vx, vy, psidot_ev, float(qB[0]), float(qB[1]), rho2)
        margins["lift"] = min(margins["lift"], abs(wp) / max(abs(psidot_ev), 1e-300))
        lifts = wp * (qA[0] - qB[0]) > 0.0  # A's y-velocity about B after the landing
        if lifts:
            k_after = 0.5 * (vxp * vxp + vyp * vyp + rho2 * wp * wp)
            gain = max(gain, k_after - k_before)
            below = k_after < g * (ell[j] - geo["d"]) and k_after < g * (ell[jB] - geo["d"])
            if not (geo["stable"] and below):
                j, px, psi, psidot = jB, xB, float(part.beta[k]), wp
                continue
        else:
            gain = max(gain, -k_before)
            if not geo["stable"]:  # tips from rest about the vertex its CM overhangs
                xs = {j: px, jB: xB}
                jT = min(xs, key=xs.get) if geo["uL"] >= 0.0 else max(xs, key=xs.get)
                j, px, psi, psidot = jT, xs[jT], float(part.beta[k]), 0.0
                continue
        # ----------------------------------------------------------- at rest on side k
        xL = x_cm + geo["uL"]
        near(xL, x_cm)
        if xL <= 0.0:
            return result(x_cm, k, "behind_joint", "rest_left_vertex")
        xR = x_cm + geo["uR"]
        if xR > L:  # the right support vertex past the end: the same rest rule as throw()'s starts
            return result(x_cm, k, "off_end", "rest_right_vertex")
        return result(x_cm, k, "ok")


# ---------------------------------------------------------------------------- a throw
def reference_throw(part, arm, x, side, omega, *, dt=DEFAULT_DT, t_max=DEFAULT_T_MAX,
                    max_impacts=DEFAULT_MAX_IMPACTS, rtol=DEFAULT_RTOL, atol=DEFAULT_ATOL,
                    pivot_t_max=DEFAULT_PIVOT_T_MAX, ill_conditioned_below=ILL_CONDITIONED_BELOW) -> dict:
    """One throw of ``part`` resting at ``(x, side)`` on ``arm`` at release rate ``omega`` (rad/s).

    Model "paper" computed independently of the kernels (see the module docstring).
    The start is only checked for a stable ``side`` and ``x + u_L > 0``.

    Returns a dict with keys

    ``x`` (m; the resting CM x, or the CM x when the part left the arm), ``side``,
    ``status`` (string, see the module docstring), ``escape`` (which contact
    decided a non-"ok" status: ``"first_contact"``, ``"landing_vertex"``,
    ``"rest_left_vertex"``, ``"rest_cm"``, ``"cap"``, else ``""``),
    ``t_flight`` (s), ``contact_vertex`` (clockwise index j into ``part.w``; map
    with ``part.user_vertex``), ``contact_x`` (m), ``v_pre``/``v_post`` ((ẋ, ẏ, φ̇)
    around the first impact; m/s, m/s, rad/s), ``impulse`` (first-impact impulse,
    **N·s**, for mass ``part.mass``), ``impulse_per_mass`` (m/s),
    ``kinetic_pre``/``kinetic_post`` (J/kg), ``n_impacts`` (first impact plus
    every side landing), ``n_flips`` (landings on a side other than the last one
    landed on), ``n_peaks`` (potential peaks crossed), ``max_impact_energy_gain``
    (J/kg, ≤ 0), ``margins`` and ``ill_conditioned``.

    ``margins``: ``energy`` — smallest |E − gℓ|/(gℓ) of a swing heading for its
    peak (flip or fall back); ``lift`` — smallest |φ̇⁺/φ̇⁻| at a landing (lift or
    stay down); ``contact_tie`` — time from the first vertex crossing to the
    next one in the same bracket (s); ``graze`` — smallest positive local minimum
    of a vertex gap before contact (m); ``position`` — smallest distance of a
    decisive contact/rest position from x = 0 or the arm's end (m).
    ``ill_conditioned`` is true when energy or lift < ``ill_conditioned_below``,
    contact_tie < 1e-9 s, graze < 1e-9 m or position < 1e-9 m.
    """
    geo = rest_geometry(part, side)
    if not geo["stable"]:
        raise ValueError(f"side: side {side} is unstable")
    if not x + geo["uL"] > 0.0:
        raise ValueError(f"x: the left support vertex is behind the joint (x = {x})")
    g, h = arm.g, arm.h
    L = math.inf if arm.length is None else float(arm.length)
    rho2 = part.radius_of_gyration**2
    d, p = geo["d"], geo["p"]
    n = len(p)
    margins = {"energy": math.inf, "lift": math.inf, "contact_tie": math.inf, "graze": math.inf,
               "position": math.inf}
    out = {"x": float(x), "side": int(side), "status": "ok", "escape": "", "t_flight": 0.0, "contact_vertex": -1,
           "contact_x": math.nan, "v_pre": (0.0, 0.0, 0.0), "v_post": (0.0, 0.0, 0.0), "impulse": (0.0, 0.0),
           "impulse_per_mass": (0.0, 0.0), "kinetic_pre": 0.0, "kinetic_post": 0.0, "n_impacts": 0,
           "n_flips": 0, "n_peaks": 0, "max_impact_energy_gain": -math.inf, "margins": margins,
           "ill_conditioned": False}
    if omega == 0.0:
        return out
    supports = np.zeros(n, dtype=bool)
    supports[side] = supports[(side + 1) % n] = True
    t_c, jc, info = _first_contact(float(x), d, float(omega), g, p, supports, dt, t_max)
    out["t_flight"] = t_c
    out["contact_vertex"] = int(jc)
    if jc < 0:
        out.update(status="no_contact", escape="cap")
        return out
    margins.update(contact_tie=info["tie"], graze=info["graze"])
    # state just before the impact (Eq. 1)
    xc = x - (h + d) * omega * t_c
    vx, vy, w0 = -(h + d) * omega, x * omega - g * t_c, float(omega)
    psi = float(part.beta[side]) + omega * t_c
    r = _rot(psi) @ np.asarray(part.w[jc], dtype=float)
    px = xc + r[0]
    vxp, vyp, wp, Jx, Jy = impact_linear_system(vx, vy, w0, float(r[0]), float(r[1]), rho2)
    k_pre = 0.5 * (vx * vx + vy * vy + rho2 * w0 * w0)
    k_post = 0.5 * (vxp * vxp + vyp * vyp + rho2 * wp * wp)
    out.update(contact_x=float(px), v_pre=(vx, vy, w0), v_post=(vxp, vyp, wp),
               impulse=(part.mass * Jx, part.mass * Jy), impulse_per_mass=(Jx, Jy), kinetic_pre=k_pre,
               kinetic_post=k_post, n_impacts=1, max_impact_energy_gain=k_post - k_pre)
    margins["position"] = min(abs(float(px)), abs(float(px) - L))
    if px <= 0.0 or px > L:
        out.update(x=float(xc), status="behind_joint" if px <= 0.0 else "off_end", escape="first_contact")
    else:
        roll = reference_roll(part, arm, jc, psi, wp, px, side0=int(side), max_impacts=max_impacts, rtol=rtol,
                              atol=atol, pivot_t_max=pivot_t_max, n_impacts=1)
        for key in ("energy", "lift", "position"):
            margins[key] = min(margins[key], roll["margins"][key])
        out.update({key: roll[key] for key in ("x", "side", "status", "escape", "n_impacts", "n_flips", "n_peaks")})
        out["max_impact_energy_gain"] = max(out["max_impact_energy_gain"], roll["max_impact_energy_gain"])
    out["ill_conditioned"] = bool(
        margins["energy"] < ill_conditioned_below
        or margins["lift"] < ill_conditioned_below
        or margins["contact_tie"] < _CONTACT_TIE
        or margins["graze"] < _GRAZE_DEPTH
        or margins["position"] < _JOINT_NEAR
    )
    return out

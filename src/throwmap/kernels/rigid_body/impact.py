"""The impact laws of model "rigid_body": plastic impacts with Coulomb friction (resets ``impact``,
``wall_impact`` and the multi-contact impact of LEAN).

One vertex on the arm (:func:`coulomb_impact`): the no-slip impulse is paper Eq. (4)
(:func:`~throwmap.kernels.impact.plastic_impact`); outside the friction cone, Routh's
compression-only process in impulse space (or the velocity-level law, below). One contact with
any normal — a vertex on the wall's face, the wall's top corner on an edge — is the same law in a
turned frame (:func:`contact_impact`). Several contacts at once (the arm and the wall): the
velocity-level law of time-stepping engines, solved exactly (:func:`multi_contact_impact`).

Which impact law, and when to trust it
--------------------------------------
With Coulomb friction a rigid-body impact is not decided by the rigid-body
equations alone; two laws are in use and they differ exactly when the contact's
slip *stops during the impact and cannot stay stopped* (|K_tn/K_tt| > μ, below):

* Routh's process (Darboux–Keller; Routh 1905, Stronge 2000 ch. 3–4), the
  default here: the impact is followed in normal impulse p and friction opposes
  the *current* slip all along, so a slip that stops and restarts the other way
  has been braked first. Preceded by one rule of the velocity-level law: the
  no-slip impulse of Eq. 4 is applied whenever it lies in the cone (as model
  "paper"), even where the pure process would reverse the slip — this keeps the
  model equal to "paper" wherever the paper's assumptions hold, and is closer to
  both laws than pure Routh (measured: pure Routh lands up to 9.6 mm from pymunk
  at μ = 0.3 and changes a side, this law up to 8.6 mm, no side).
* The one-step velocity-level law (Moreau; what time-stepping engines — pymunk,
  Siconos' Moreau–Jean, MuJoCo — compute): one impulse P with u_n⁺ = 0 and
  Coulomb's law on the *post-impact* slip u_t⁺ (:func:`coulomb_impact` with
  ``law=LAW_VELOCITY``). Its friction points against the final slip only.

Where no impact reverses its slip the two are the same law. Measured against
pymunk (``throwmap validate``, 628 throws, 5 parts; the table's μ rows): at
μ = 1, 1.5, 2 rigid_body is within 0.5 mm in 98–99.5 % of throws (max < 1 mm);
at μ = 0.6 in 97 % (max 5 mm) and at μ = 0.3 in 75 % (p90 3.5 mm, max 32 mm),
where reversing impacts are common. On the triangle grid of
tests/engine/test_low_mu_agreement.py, swapping only this reset for the
velocity-level law brings rigid_body from 8.6 mm to ≤ 0.45 mm of pymunk at
μ = 0.3 (6.1 → 0.21 mm at μ = 0.6), and on the whole validation set at μ = 0.3
from 75 % to 99 % within 0.5 mm (max 32 → 1.3 mm): the low-μ gap is the impact
law, not the rest of the automaton. (At μ ≳ 3 and μ = ∞ a smaller gap, ≤ 2.7 mm, 81 % within
0.5 mm at μ = ∞, is pymunk's: its friction cap, :mod:`throwmap.engine.pymunk.friction`,
freezes its results above μ ≈ 3 while rigid_body's still move towards μ = ∞.)

Which to trust: for a part whose contact is stiff in both directions and short
(the rigid-body idealisation), Routh's process is the one derived from the
dynamics during the impact; a time-stepping engine, and any comparison with
one, follows the velocity-level law; a real part with a compliant tangential
contact lies between. So at μ ≥ 1 either; at μ ≤ 0.6 read the difference
between rigid_body and the engine as the model's uncertainty in the final x
(mm, occasionally cm), and prefer the engine only when the question is what a
time-stepping simulator will do.

Several contacts at once
------------------------
Where the part meets the arm and the wall together (mode LEAN, :mod:`.wall_lean`) the impact is
velocity-level (Moreau): one impulse per contact with Coulomb's law on the *post-impact*
velocities — at each contact either open (no impulse, normal velocity ≥ 0), sticking (normal and
tangential velocity 0, impulse inside the cone) or sliding (normal velocity 0, impulse on the
cone's edge against the slip). The linear complementarity problem is solved exactly by trying
every combination (:func:`multi_contact_impact`); this is the law of time-stepping engines
(pymunk, Siconos' Moreau–Jean). For one contact the automaton keeps Routh's law; where several
meet, a process in impulse space has no unique form.
"""

import math

import numpy as np
from numba import njit

from .. import codes as C
from ..impact import plastic_impact
from .modes import IMP_INCONSISTENT, IMP_SEPARATE, IMP_SLIDE, IMP_STICK

LAW_ROUTH = 0
"""Impact law: Eq. 4 inside the cone, else Routh's compression-only process (the default)."""
LAW_VELOCITY = 1
"""Impact law: one-step velocity-level Coulomb impact (Moreau), as time-stepping engines."""


@njit(cache=True)
def coulomb_impact(vx, vy, w, rx, ry, rho2, mu, law=LAW_ROUTH):
    """Plastic single-vertex impact with Coulomb friction (reset ``impact``).

    Contact frame t = x̂, n = ŷ; contact velocity u = (v_x − ω r_y, v_y + ω r_x);
    an impulse P at the contact changes it by K P with the inverse-inertia matrix
    K = [[1 + r_y²/ρ², −r_x r_y/ρ²], [−r_x r_y/ρ², 1 + r_x²/ρ²]] (unit mass).

    1. The no-slip impulse J = −K⁻¹u (Eq. 4). If J_n ≥ 0 and |J_t| ≤ μ J_n it is
       applied (sticking impact, computed by :func:`plastic_impact` exactly as model
       "paper").
    2. Otherwise Routh's process, compression only (zero Poisson restitution),
       parametrised by the normal impulse p: while sliding with sense σ,
       dP = (−μσ, 1) dp; when u_t reaches 0 the part sticks if |K_tn/K_tt| ≤ μ
       (dP = (−K_tn/K_tt, 1) dp), else slides with σ = sgn K_tn; it ends when u_n = 0.
       μ = ∞ is the limit: a purely tangential impulse until u_t = 0 or u_n = 0.
       If the normal velocity cannot be stopped (du_n/dp ≤ 0 while sliding) there is
       no consistent impulse (``IMP_INCONSISTENT``). Once the slip has stopped and
       cannot stick (|K_tn/K_tt| > μ) it restarts with σ = sgn K_tn, the one sense in
       which friction −μσ opposes the slip it produces (σ du_t/dp = |K_tn| − μK_tt > 0);
       checked against an independent small-step integration of the process
       (tests/kernels/test_impact_process.py).

    With ``law=LAW_VELOCITY`` step 2 is instead the one-step velocity-level impact:
    P = p(−μσ, 1) with p = −u_n/(K_nn − μσK_tn) > 0 and the post-impact slip
    σ u_t⁺ ≥ 0, σ = sgn u_t tried first, then −σ; none: ``IMP_INCONSISTENT``.
    It differs from Routh's only where the slip would stop and reverse (module
    docstring). μ = ∞ is Routh's limit under both laws.

    ``(rx, ry)`` CM → contact vertex (m), ``rho2`` ρ² (m²).
    Returns ``(vx⁺, vy⁺, ω⁺, P_t, P_n, kind, jt0, jn0)``; kind is IMP_STICK,
    IMP_SLIDE (contact slides, u_n = 0), IMP_SEPARATE (u_n > 0, the vertex
    leaves) or IMP_INCONSISTENT; (jt0, jn0) is the no-slip impulse of step 1.
    """
    ut = vx - w * ry
    un = vy + w * rx
    Ktt = 1.0 + ry * ry / rho2
    Knn = 1.0 + rx * rx / rho2
    Ktn = -rx * ry / rho2
    det = Ktt * Knn - Ktn * Ktn
    jt0 = -(Knn * ut - Ktn * un) / det
    jn0 = -(-Ktn * ut + Ktt * un) / det
    if un >= 0.0:
        return vx, vy, w, 0.0, 0.0, IMP_SEPARATE, jt0, jn0
    if jn0 >= 0.0 and abs(jt0) <= mu * jn0:
        vxp, vyp, wp = plastic_impact(vx, vy, w, rx, ry, rho2)
        return vxp, vyp, wp, vxp - vx, vyp - vy, IMP_STICK, jt0, jn0
    if law == LAW_VELOCITY and not math.isinf(mu):
        s0 = 1.0 if ut > 0.0 else -1.0
        for sg in (s0, -s0):
            an = Knn - mu * sg * Ktn
            if an > 0.0:
                pn = -un / an
                if sg * (ut + (Ktn - mu * sg * Ktt) * pn) >= 0.0:
                    pt = -mu * sg * pn
                    return vx + pt, vy + pn, w + (rx * pn - ry * pt) / rho2, pt, pn, IMP_SLIDE, jt0, jn0
        return vx, vy, w, 0.0, 0.0, IMP_INCONSISTENT, jt0, jn0
    scale = abs(ut) + abs(un)
    Pt = 0.0
    Pn = 0.0
    kind = IMP_SLIDE
    for _ in range(4):
        if un >= 0.0:
            break
        if abs(ut) <= 1e-14 * scale:
            ut = 0.0
            lam = -Ktn / Ktt
            # Sticking here ends at the no-slip impulse J, a sum of impulses in the cone, so J is in
            # the cone and step 1 has taken it: this branch is reached only when rounding puts J
            # just outside the cone (a safety net; hand-made mutants of it are equivalent).
            if abs(lam) <= mu:
                dp = -un / (Knn + Ktn * lam)
                Pt += lam * dp
                Pn += dp
                un = 0.0
                kind = IMP_STICK
                break
            sig = 1.0 if Ktn > 0.0 else -1.0
        else:
            sig = 1.0 if ut > 0.0 else -1.0
        if math.isinf(mu):
            # limit mu -> inf: tangential impulse only, until u_t = 0 or u_n = 0
            pt_stop = -ut / Ktt
            un_stop = un + Ktn * pt_stop
            if un_stop >= 0.0 and Ktn != 0.0:
                pt = -un / Ktn
                Pt += pt
                ut += Ktt * pt
                un = 0.0
                kind = IMP_SLIDE if ut != 0.0 else IMP_STICK
                break
            Pt += pt_stop
            ut = 0.0
            un = un_stop
            continue
        at = Ktn - mu * sig * Ktt  # du_t/dp while sliding with sense sig
        an = Knn - mu * sig * Ktn  # du_n/dp
        p_n = -un / an if an > 0.0 else math.inf
        p_t = -ut / at if (sig * at < 0.0 and ut != 0.0) else math.inf
        if math.isinf(p_n) and math.isinf(p_t):
            return vx, vy, w, 0.0, 0.0, IMP_INCONSISTENT, jt0, jn0
        if p_n <= p_t:
            Pt += -mu * sig * p_n
            Pn += p_n
            ut += at * p_n
            un = 0.0
            kind = IMP_SLIDE
            break
        Pt += -mu * sig * p_t
        Pn += p_t
        un += an * p_t
        ut = 0.0
    if un > 0.0:  # defensive: every exit above leaves u_n = 0 or u_n < 0 (loop cap)
        kind = IMP_SEPARATE
    vxp = vx + Pt
    vyp = vy + Pn
    wp = w + (rx * Pn - ry * Pt) / rho2
    return vxp, vyp, wp, Pt, Pn, kind, jt0, jn0


@njit(cache=True)
def record_impact(pt, pn, k_before, k_after, rec):
    """Count an impact with impulse (P_t, P_n) (m/s) in ``rec``: N_IMPACTS, MU_MAX, K_MAX_IMPACT_GAIN."""
    rec[C.N_IMPACTS] += 1.0
    if pn > 0.0:
        r = abs(pt) / pn
        if r > rec[C.MU_MAX]:
            rec[C.MU_MAX] = r
    elif pt != 0.0:
        rec[C.MU_MAX] = math.inf
    gain = k_after - k_before
    if gain > rec[C.K_MAX_IMPACT_GAIN]:
        rec[C.K_MAX_IMPACT_GAIN] = gain


@njit(cache=True)
def record_first_contact(rec, t, j, px, vx, vy, w, k_pre, dy, g):
    """First-contact fields of ``rec``: time (s), vertex, x (m), velocities before impact, energies (J/kg)."""
    rec[C.T_FLIGHT] = t
    rec[C.CONTACT_VERTEX] = j
    rec[C.CONTACT_X] = px
    rec[C.VX_PRE] = vx
    rec[C.VY_PRE] = vy
    rec[C.W_PRE] = w
    rec[C.K_PRE] = k_pre
    rec[C.U_IMPACT] = g * dy


@njit(cache=True)
def record_first_impact(rec, vx, vy, w, pt, pn, jt0, jn0, k_post):
    """First-impact fields of ``rec``: velocities after it, impulse (m/s), the friction ratio the no-slip impulse needs."""
    rec[C.VX_POST] = vx
    rec[C.VY_POST] = vy
    rec[C.W_POST] = w
    rec[C.JX] = pt
    rec[C.JY] = pn
    if jn0 > 0.0:
        rec[C.MU_IMPACT] = abs(jt0) / jn0
    else:
        rec[C.MU_IMPACT] = math.inf if jt0 != 0.0 else 0.0
    rec[C.K_POST] = k_post


@njit(cache=True)
def contact_impact(vx, vy, om, rx, ry, nx, ny, rho2, mu_c, law):
    """Reset ``impact`` at a contact with unit normal (n_x, n_y) into the part: the arm's law in the frame (t, n),
    t = n turned by −90° (a proper rotation). Returns as :func:`coulomb_impact`, with P_n along n and P_t along t."""
    tx = ny
    ty = -nx
    vxp, vyp, wp, pt, pn, kind, jt0, jn0 = coulomb_impact(vx * tx + vy * ty, vx * nx + vy * ny, om,
                                                          rx * tx + ry * ty, rx * nx + ry * ny, rho2, mu_c, law)
    return vxp * tx + vyp * nx, vxp * ty + vyp * ny, wp, pt, pn, kind, jt0, jn0


C_OPEN = 0
C_STICK = 1
C_SLIDE = 2
"""Contact states after :func:`multi_contact_impact`."""


@njit(cache=True)
def multi_contact_impact(vx, vy, om, pts, nrm, mus, m, rho2, st):
    """Velocity-level plastic impact at ``m`` contacts (module docstring): CM → contact i = ``pts[i]`` (m), unit
    normal ``nrm[i]`` into the part, Coulomb ``mus[i]`` (``inf``: no slip, 0: frictionless).

    Every assignment of the contacts to open / sticking / sliding (each sense) is tried, those with the
    fewest open contacts first and sticking before sliding, and the first whose impulses and post-impact
    velocities satisfy every condition to 1e-10 of the velocity scale is returned: ``(ok, vx⁺, vy⁺, ω⁺)``,
    with the states in ``st`` (m,) (C_OPEN, C_STICK, C_SLIDE); ok False: none is consistent.
    """
    rows = np.empty((2 * m, 3))  # normal and tangent (t = n turned by −90°) rows in (v_x, v_y, ω)
    u = np.empty(2 * m)
    scale = abs(vx) + abs(vy) + 1e-300
    for i in range(m):
        nx = nrm[i, 0]
        ny = nrm[i, 1]
        rx = pts[i, 0]
        ry = pts[i, 1]
        rows[2 * i, 0] = nx
        rows[2 * i, 1] = ny
        rows[2 * i, 2] = rx * ny - ry * nx
        rows[2 * i + 1, 0] = ny
        rows[2 * i + 1, 1] = -nx
        rows[2 * i + 1, 2] = -rx * nx - ry * ny
        scale += abs(om) * math.hypot(rx, ry)
    for q in range(2 * m):
        u[q] = rows[q, 0] * vx + rows[q, 1] * vy + rows[q, 2] * om
    tol = 1e-10 * scale
    code = np.empty(m, dtype=np.int64)
    total = 4 ** m
    for n_open in range(m + 1):
        for n_slide in range(m - n_open + 1):
            for c in range(total):
                r = c
                no = 0
                ns = 0
                for i in range(m):
                    code[i] = r % 4  # 0 open, 1 stick, 2 slide +, 3 slide −
                    r //= 4
                    if code[i] == 0:
                        no += 1
                    elif code[i] >= 2:
                        ns += 1
                if no != n_open or ns != n_slide:
                    continue
                ok, vxp, vyp, wp = _try(rows, u, vx, vy, om, rho2, code, mus, m, tol)
                if ok:
                    for i in range(m):
                        st[i] = C_OPEN if code[i] == 0 else (C_STICK if code[i] == 1 else C_SLIDE)
                    return True, vxp, vyp, wp
    return False, vx, vy, om


@njit(cache=True)
def _try(rows, u, vx, vy, om, rho2, code, mus, m, tol):  # noqa: C901
    """One assignment ``code`` (0 open, 1 stick, 2/3 sliding with post-impact slip +/−) of
    :func:`multi_contact_impact`. Returns ``(ok, vx⁺, vy⁺, ω⁺)``."""
    dirs = np.empty((2 * m, 3))
    eqs = np.empty(2 * m, dtype=np.int64)
    k = 0
    for i in range(m):
        ci = code[i]
        mu = mus[i]
        if ci == 0:
            continue
        if ci == 1 and mu == 0.0:
            return False, vx, vy, om
        if ci >= 2 and math.isinf(mu):
            return False, vx, vy, om
        if ci == 1:
            for q in range(2):
                dirs[k, 0] = rows[2 * i + q, 0]
                dirs[k, 1] = rows[2 * i + q, 1]
                dirs[k, 2] = rows[2 * i + q, 2] / rho2
                eqs[k] = 2 * i + q
                k += 1
        else:
            f = -(1.0 if ci == 2 else -1.0) * mu
            dirs[k, 0] = rows[2 * i, 0] + f * rows[2 * i + 1, 0]
            dirs[k, 1] = rows[2 * i, 1] + f * rows[2 * i + 1, 1]
            dirs[k, 2] = (rows[2 * i, 2] + f * rows[2 * i + 1, 2]) / rho2
            eqs[k] = 2 * i
            k += 1
    A = np.empty((k, k))
    b = np.empty(k)
    for a in range(k):
        e = eqs[a]
        for c in range(k):
            A[a, c] = rows[e, 0] * dirs[c, 0] + rows[e, 1] * dirs[c, 1] + rows[e, 2] * dirs[c, 2]
        b[a] = -u[e]
    p = _solve(A, b, k) if k > 0 else np.empty(0)
    if k > 0 and p.shape[0] == 0:
        return False, vx, vy, om
    vxp = vx
    vyp = vy
    wp = om
    for c in range(k):
        vxp += p[c] * dirs[c, 0]
        vyp += p[c] * dirs[c, 1]
        wp += p[c] * dirs[c, 2]
    j = 0
    for i in range(m):
        ci = code[i]
        un = rows[2 * i, 0] * vxp + rows[2 * i, 1] * vyp + rows[2 * i, 2] * wp
        ut = rows[2 * i + 1, 0] * vxp + rows[2 * i + 1, 1] * vyp + rows[2 * i + 1, 2] * wp
        if ci == 0:
            if un < -tol:
                return False, vx, vy, om
            continue
        pn = p[j]
        if pn < -tol:
            return False, vx, vy, om
        if ci == 1:
            if abs(p[j + 1]) > mus[i] * max(pn, 0.0) + tol:
                return False, vx, vy, om
            j += 2
        else:
            if (1.0 if ci == 2 else -1.0) * ut < -tol:
                return False, vx, vy, om
            j += 1
    return True, vxp, vyp, wp


@njit(cache=True)
def _solve(A, b, k):
    """Gaussian elimination with partial pivoting of the k × k system; an empty array if it is singular."""
    M = np.empty((k, k + 1))
    M[:, :k] = A
    M[:, k] = b
    big = 0.0
    for i in range(k):
        for j in range(k):
            big = max(big, abs(A[i, j]))
    for c in range(k):
        piv = c
        for r in range(c + 1, k):
            if abs(M[r, c]) > abs(M[piv, c]):
                piv = r
        if abs(M[piv, c]) <= 1e-13 * big:
            return np.empty(0)
        if piv != c:
            for q in range(k + 1):
                tmp = M[c, q]
                M[c, q] = M[piv, q]
                M[piv, q] = tmp
        for r in range(c + 1, k):
            f = M[r, c] / M[c, c]
            for q in range(c, k + 1):
                M[r, q] -= f * M[c, q]
    x = np.empty(k)
    for c in range(k - 1, -1, -1):
        sacc = M[c, k]
        for q in range(c + 1, k):
            sacc -= M[c, q] * x[q]
        x[c] = sacc / M[c, c]
    return x

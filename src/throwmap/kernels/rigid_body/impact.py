"""Reset ``impact`` of model "rigid_body": a plastic one-vertex impact with Coulomb friction.

The no-slip impulse is paper Eq. (4) (:func:`~throwmap.kernels.impact.plastic_impact`);
outside the friction cone, Routh's compression-only process in impulse space.

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
"""

import math

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

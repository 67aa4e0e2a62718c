"""Reset ``land_side`` of model "rigid_body": a second vertex B touches while A is on the line.

Then, in order: the impulse at B alone (A free) if it makes A lift; the Zeno rule
``rocking_rest`` (decided on purpose, as :mod:`~throwmap.kernels.roll`); else both
vertices stop normal motion and friction removes what it can of the horizontal
velocity; what remains slides the part flat (mode FLAT_SLIDE, deceleration μ g,
closed form) to rest on a stable side, or it tips from rest about the vertex its
CM overhangs (unstable side).

Frictionless arm (μ = 0): no contact force has a horizontal component, so the CM's
horizontal velocity never changes (it stays −(h + d) ω from the release). A part
landing flat keeps sliding (:func:`slide_away`: behind the joint inward, off the end
outward, NO_REST outward on an unbounded arm); an unstable side tips while it slides
(pivot on the overhung vertex, sliding); the Zeno rule compares the kinetic energy
relative to the CM's horizontal motion with the topple barriers.
"""

import math

from numba import njit

from .. import codes as C
from ..flight import departure_window
from ..roll import theta_a, theta_b
from .flat import flat_slide, rest, settle, settle_at_wall, slide_away, tip_from_rest
from .flight import flight_frame, leave_arm
from .impact import coulomb_impact, record_impact
from .modes import HALF_PI, IMP_INCONSISTENT, IMP_SEPARATE, IMP_STICK, MODE_FLIGHT, MODE_REST, MODE_SELECT, MODE_STICK, N_ARC, TWO_PI
from .stick import _n_min_range, _n_stick
from .tilt import rocking_rest_tilted, topple_barrier


@njit(cache=True)
def arc_ok(th_from, E, lj, I, g, mu, towards_peak):
    """Whether a sticking swing from θ at energy E up to its turning point keeps N > 0, |F| ≤ μN."""
    k = lj * lj / I
    e = E / (g * lj)
    st = min(e, 1.0)
    if towards_peak > 0:
        tt = math.asin(st) if th_from < HALF_PI else HALF_PI
        if tt < th_from:
            tt = th_from
    else:
        tt = math.pi - math.asin(st) if th_from > HALF_PI else HALF_PI
        if tt > th_from:
            tt = th_from
    lo = min(th_from, tt)
    hi = max(th_from, tt)
    if _n_min_range(lo, hi, e, k) <= 0.0:
        return False
    if math.isinf(mu):
        return True
    for i in range(N_ARC):
        th = lo + (hi - lo) * i / (N_ARC - 1)
        s = math.sin(th)
        nf = _n_stick(s, e, k)
        if abs(k * math.cos(th) * (3.0 * s - 2.0 * e)) > mu * nf:
            return False
    return True


@njit(cache=True)
def rocking_rest(th_new, th_A, k_after, lA, lB, rho2, dk, g, mu, land_dir):
    """Guard ``rocking_rest`` (Zeno) after a sticking landing on a stable side, kinetic energy ``k_after`` (J/kg).

    Rest when K is below both topple barriers g(ℓ_A − d), g(ℓ_B − d) and the next
    swings at that energy about B (from ``th_new``) and back about A (from ``th_A``)
    keep N > 0 and |F| ≤ μN (:func:`arc_ok`).
    """
    if not k_after < min(g * (lA - dk), g * (lB - dk)):
        return False
    E_B = k_after + g * dk
    if not arc_ok(th_new, E_B, lB, rho2 + lB * lB, g, mu, land_dir):
        return False
    return arc_ok(th_A, E_B, lA, rho2 + lA * lA, g, mu, -land_dir)


@njit(cache=True)
def land_side(land_dir, jp, px, thdot, va, phi, t, last_side, part, arm, ta, tb, ru, rv, c0, traj, ts, rec):
    """Reset ``land_side``: pivoting on A = w_jp, θ reached θb (``land_dir`` +1) or θa (−1) and B touches.

    ``part`` and ``arm`` are the kernels' records (:class:`~.inputs.PartArrays`, :class:`~.inputs.ArmArrays`).

    On an arm at rest angle ``arm.alpha`` ≠ 0 (rad; :mod:`~.tilt`): the departure window
    sees the normal gravity g cos α, the Zeno rule uses the tilted topple barriers
    and swings (:func:`~.tilt.rocking_rest_tilted`), a flat part slides and settles
    under the tilted gravity (:func:`~.flat.settle`: rests only where |tan α| ≤ μ),
    an unstable side (``stable`` is the table for α) tips about the vertex its CM
    overhangs along gravity, at once, sliding if it still moves.

    With a wall (``arm.wall_h`` > 0, m; Coulomb ``arm.wall_mu``) every flat slide and rest goes to
    :func:`settle_at_wall` (:mod:`~.wall`).

    ``arm.law`` is the impact law of the impulse at B (:data:`~.impact.LAW_ROUTH` or
    :data:`~.impact.LAW_VELOCITY`, see :func:`~.impact.coulomb_impact`).

    Returns ``(mode, status, x, y, v_x, v_y, ω, φ, t, jp, px, θ, θ̇, v_A, phi_off, excl_j, excl_t, last_side)``:
    mode MODE_REST (``status`` decided, x the CM and ``last_side`` the side),
    MODE_FLIGHT (B bounced off: the flight state and frame ``ru``/``rv``/``c0``),
    MODE_SELECT (pivot on B) or MODE_STICK (tip from rest on an unstable side).
    """
    rho2, w, beta, d, uL, uR, ell, stable = part
    h, g, alpha, length, back, mu, law, wall_h, wall_mu = arm
    n = d.shape[0]
    if land_dir > 0:  # landed on side jp; A is its right vertex, B = w_{jp+1} its left
        k = jp
        uA = uR[k]
        uB = uL[k]
        jB = (jp + 1) % n
    else:  # landed on side jp − 1; A is its left vertex, B its right
        k = (jp - 1) % n
        uA = uL[k]
        uB = uR[k]
        jB = k
    dk = d[k]
    if k != last_side:
        rec[C.N_FLIPS] += 1.0
        last_side = k
    x_cm = px - uA
    vxm = va - thdot * dk
    vym = -thdot * uA
    k_before = 0.5 * (vxm * vxm + vym * vym + rho2 * thdot * thdot)
    pxB = x_cm + uB
    vxp, vyp, wp, pt, pn, kind, jt0, jn0 = coulomb_impact(vxm, vym, thdot, uB, -dk, rho2, mu, law)
    lifts = kind != IMP_INCONSISTENT and (vyp + wp * uA) > 0.0
    status = leave_arm(pxB, back, length)
    if status != C.OK:
        rec[C.N_IMPACTS] += 1.0
        return (MODE_REST, status, x_cm, h + dk, 0.0, 0.0, 0.0, phi, t, jp, px, 0.0, thdot, va, 0.0, -1, 0.0,
                last_side)
    if lifts:
        # ------------------------------------------------------------------ the impulse at B alone: A lifts
        if jn0 < 0.0:
            rec[C.N_PULL] += 1.0
        k_after = 0.5 * (vxp * vxp + vyp * vyp + rho2 * wp * wp)
        record_impact(pt, pn, k_before, k_after, rec)
        if kind != IMP_STICK:
            rec[C.N_SLIPS] += 1.0
        th_new = theta_a(jB, n, d, uL) if land_dir > 0 else theta_b(jB, d, uR)
        th_A = tb if land_dir > 0 else ta
        if alpha != 0.0:
            barrier = topple_barrier(th_A, th_new, ell[jp], ell[jB], g, alpha)
        else:
            barrier = min(g * (ell[jp] - dk), g * (ell[jB] - dk))
        if mu == 0.0 and stable[k] and k_after - 0.5 * vxp * vxp < barrier:
            if wall_h > 0.0:
                return settle_at_wall(x_cm, vxp, t, k, phi, last_side, h, g, alpha, length, back, rho2, mu, w, beta, d,
                                      uL, uR, wall_h, wall_mu, traj, ts, rec)
            if alpha != 0.0:
                x, k, status, t = settle(x_cm, vxp, t, k, mu, g, alpha, h, d, uL, uR, beta, length, back, phi, traj,
                                         ts, rec)
                return (MODE_REST, status, x, h + dk, 0.0, 0.0, 0.0, phi, t, jp, px, 0.0, 0.0, 0.0, 0.0, -1, 0.0,
                        last_side)
            # frictionless Zeno rule: the CM's horizontal motion is free (no friction), the rocking
            # relative to it is below both topple barriers and dies out: flat on side k, sliding at v_x
            if vxp == 0.0:
                x, k, status = rest(x_cm, k, t, h, g, d, uL, uR, beta, length, back, phi, traj, ts, rec)
            else:
                x, status, t = slide_away(x_cm, vxp, t, k, uL, uR, length, back, h + dk, phi, traj, ts, rec)
            return MODE_REST, status, x, h + dk, 0.0, 0.0, 0.0, phi, t, jp, px, 0.0, 0.0, 0.0, 0.0, -1, 0.0, last_side
        if kind == IMP_STICK and stable[k]:
            if alpha != 0.0:
                zeno = rocking_rest_tilted(th_new, th_A, k_after, ell[jp], ell[jB], rho2, g, mu, land_dir, alpha)
            else:
                zeno = rocking_rest(th_new, th_A, k_after, ell[jp], ell[jB], rho2, dk, g, mu, land_dir)
            if zeno and alpha != 0.0 and wall_h > 0.0:
                return settle_at_wall(x_cm, 0.0, t, k, phi, last_side, h, g, alpha, length, back, rho2, mu, w, beta, d,
                                      uL, uR, wall_h, wall_mu, traj, ts, rec)
            if zeno and alpha != 0.0:
                x, k, status, t = settle(x_cm, 0.0, t, k, mu, g, alpha, h, d, uL, uR, beta, length, back, phi, traj,
                                         ts, rec)
                return (MODE_REST, status, x, h + dk, 0.0, 0.0, 0.0, phi, t, jp, px, 0.0, 0.0, 0.0, 0.0, -1, 0.0,
                        last_side)
            if zeno:
                x, k, status = rest(x_cm, k, t, h, g, d, uL, uR, beta, length, back, phi, traj, ts, rec)
                return (MODE_REST, status, x, h + dk, 0.0, 0.0, 0.0, phi, t, jp, px, 0.0, 0.0, 0.0, 0.0, -1, 0.0,
                        last_side)
        phi_off = phi - th_new
        if kind == IMP_SEPARATE:
            # B bounced: flight again, B excluded from touch while it provably stays above the line
            un = vyp + wp * uB
            vscale = max(1.0, abs(vxp) + abs(vyp) + abs(wp) * ell[jB])
            g_n = g * math.cos(alpha)
            excl_t = departure_window(uB, -dk, wp, g_n, ell[jB], g_n) if un <= 1e-12 * vscale else 0.0
            flight_frame(phi, h + dk, h, w, ru, rv, c0, jB)
            return (MODE_FLIGHT, C.OK, x_cm, h + dk, vxp, vyp, wp, phi, t, jB, pxB, th_new, wp, 0.0, phi_off, jB,
                    excl_t, last_side)
        va_B = 0.0 if kind == IMP_STICK else vxp + wp * dk  # slip velocity of B
        return (MODE_SELECT, C.OK, x_cm, h + dk, vxp, vyp, wp, phi, t, jB, pxB, th_new, wp, va_B, phi_off, -1, 0.0,
                last_side)
    # ---------------------------------------------------------------------- both vertices stop: v_y = ω = 0
    jn = -vym if vym < 0.0 else 0.0
    jt = -vxm
    if abs(jt) > mu * jn:
        jt = -mu * jn if vxm > 0.0 else mu * jn
    vx_after = vxm + jt
    record_impact(jt, jn, k_before, 0.5 * vx_after * vx_after, rec)
    phi = beta[k] + TWO_PI * round((phi - beta[k]) / TWO_PI)
    if wall_h > 0.0 and stable[k]:
        return settle_at_wall(x_cm, vx_after, t, k, phi, last_side, h, g, alpha, length, back, rho2, mu, w, beta, d,
                              uL, uR, wall_h, wall_mu, traj, ts, rec)
    if alpha != 0.0:
        if stable[k]:
            x, k, status, t = settle(x_cm, vx_after, t, k, mu, g, alpha, h, d, uL, uR, beta, length, back, phi, traj,
                                     ts, rec)
            return MODE_REST, status, x, h + dk, 0.0, 0.0, 0.0, phi, t, jp, px, 0.0, 0.0, 0.0, 0.0, -1, 0.0, last_side
        # an unstable side tips at once over the vertex its CM overhangs along gravity (sliding if it moves)
        jt_, px_t, theta = tip_from_rest(k, x_cm, n, d, uL, uR, alpha)
        status = leave_arm(px_t, back, length)
        if status != C.OK:
            mode = MODE_REST
        else:
            mode = MODE_STICK if vx_after == 0.0 else MODE_SELECT
        return (mode, status, x_cm, h + dk, vx_after, 0.0, 0.0, phi, t, jt_, px_t, theta, 0.0, vx_after,
                phi - theta, -1, 0.0, last_side)
    if vx_after != 0.0 and mu == 0.0:
        # frictionless arm: nothing stops the horizontal motion
        if stable[k]:
            x, status, t = slide_away(x_cm, vx_after, t, k, uL, uR, length, back, h + dk, phi, traj, ts, rec)
            return MODE_REST, status, x, h + dk, 0.0, 0.0, 0.0, phi, t, jp, px, 0.0, 0.0, 0.0, 0.0, -1, 0.0, last_side
        # an unstable side tips over the vertex its CM overhangs while it slides on
        jt_, px_t, theta = tip_from_rest(k, x_cm, n, d, uL, uR)
        status = leave_arm(px_t, back, length)
        mode = MODE_SELECT if status == C.OK else MODE_REST
        return (mode, status, x_cm, h + dk, vx_after, 0.0, 0.0, phi, t, jt_, px_t, theta, 0.0, vx_after,
                phi - theta, -1, 0.0, last_side)
    if vx_after != 0.0:
        x_cm, t = flat_slide(x_cm, vx_after, t, mu, g, h + dk, phi, traj, ts, rec)
    if stable[k]:
        x, k, status = rest(x_cm, k, t, h, g, d, uL, uR, beta, length, back, phi, traj, ts, rec)
        return MODE_REST, status, x, h + dk, 0.0, 0.0, 0.0, phi, t, jp, px, 0.0, 0.0, 0.0, 0.0, -1, 0.0, last_side
    # flat on an unstable side: tips over the vertex its CM overhangs, from rest
    jt_, px_t, theta = tip_from_rest(k, x_cm, n, d, uL, uR)
    status = leave_arm(px_t, back, length)
    mode = MODE_STICK if status == C.OK else MODE_REST
    return mode, status, x_cm, h + dk, 0.0, 0.0, 0.0, phi, t, jt_, px_t, theta, 0.0, 0.0, phi - theta, -1, 0.0, last_side

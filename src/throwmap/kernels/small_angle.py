"""Model "small_angle": the paper's closed forms (Sec. IV Lemma 4.1, Sec. V-A), corrected.

Small-angle approximation around ω t* = 0, to first order (sin ωt → ωt, cos ωt → 1),
with contact on the left support vertex (u_L, v_L = −d) of the resting side i.
Write R for the resting x. Each line gives the corrected form and, after ``draft:``,
what the draft prints and why it is wrong.

1. Flight time from ``V_y(t*) = h``:  t* = 2 ω (R + u_L) / g.
   draft: t* = −2θ̇_r(R + u_L)/g — negative, from the draft's ``+½gt²`` (g signed).
2. CM at impact: x* = R − (h + d) ω t*,  y* = h + d − (2ω²/g)(R + u_L) u_L,  φ* = ω t*.
   draft: x* = R + (2/g)θ̇(Rθ̇ + θ̇u_L)(h − v_L) (sign, from 1.), y* drops h.
3. Contact vector at impact (rotated, first order): r = (u_L + d φ*, −d + u_L φ*);
   pre-impact velocity ẋ⁻ = −ω(h + d), ẏ⁻ = ωR − g t* = −ω(R + 2u_L), φ̇⁻ = ω.
4. Eq. (4): H = ρ²ω + r_y ẋ⁻ − r_x ẏ⁻ (angular momentum about the contact per unit
   mass), φ̇⁺ = H / (ρ² + |r|²).
   draft: φ̇⁺ carries an extra factor θ̇_r and uses the unrotated (u_L, v_L).
5. Kinetic energy after impact (pivoting about the contact):
   K = ½ m (ρ² + |r|²) φ̇⁺² = m H² / (2 (ρ² + |r|²)).
   draft: (ρ + m|r|²)/(2(ρ²+|r|²)²)·(…)² — adds ρ (m) to m|r|² (kg m²): a unit error.
6. Potential energy after impact, from the arm line: U = m g (−r_y) = m g (d − u_L φ*).
   draft: −gm(…)² — squared lengths, a term without g: unit errors and a missing g.
7. Flip test: flip iff φ̇⁺ > 0 (rotating toward side i+1) and
   F = K + U − U_crit > 0 with U_crit = m g sqrt(u_L² + v_L²).
   draft: F > 0 alone — blind to the sense of rotation.
8. New rest position. Jog: the part falls back and rests with its left vertex where it
   touched: x' = P_x − u_L = R − h ω t* = R − (2 h ω²/g)(R + u_L).
   draft (Lemma 4.1): x(t_impact), the CM at impact, is taken as the new rest position.
   Flip: it rolls over the contact vertex (at P_x = x* + r_x) onto side i+1 and on over
   unstable sides to the next stable side s: x' = P_x − Σ(lengths rolled over) − u_R^s.

The jog map is affine in R with slope 1 − 2hω²/g > 1 for h < 0: jogs stretch x.

Second order (model "small_angle2", ours)
-----------------------------------------
The first-order forms are inconsistent where it matters: the jog −hφ* has the small
coefficient |h|, while the dropped term −u_L φ*²/2 of u_L cos φ* has the large |u_L|,
so they compete once φ* ≳ 2|h/u_L| (about 0.2 rad for the canonical triangle,
and the jog length is off by ~20 % already at φ* = 0.035). With cos φ → 1 − φ²/2:
t* = 2ω(R + u_L)/(g − dω²) (no contact in the model if g ≤ dω²: status UNRESOLVED), the CM from Eq. (1)
exactly, r = (u_L(1 − φ*²/2) + dφ*, u_Lφ* − d(1 − φ*²/2)), and steps 4–8 unchanged.
"""

import math

from numba import njit, prange

from . import codes as C
from .flight import MAX_SPIN_ANGLE, release_state
from .rows import mark_invalid


PARALLEL_MIN = 16384
"""Smallest batch run on Numba's thread pool (:func:`throw_many_small_angle`); smaller batches
run on the calling thread (:func:`throw_many_small_angle_serial`, same results). A closed-form
throw takes well under a microsecond, so only large batches repay waking the pool."""


@njit(cache=True)
def throw_one_small_angle(x0, side, omega, h, g, length, back, rho2, d, uL, uR, ell, elen, stable, order, rec):
    """One throw with the corrected small-angle closed forms of ``order`` 1 or 2; returns ``(x, side, status)``.

    ``length`` (m, inf: unbounded) and ``back`` (m, ``Arm.back``) bound the arm's surface
    (a contact or resting support vertex at x ≤ −back is BEHIND_JOINT). Status UNRESOLVED
    where the closed forms give no answer: ``order`` 2 with g ≤ d ω² (no contact in the
    expansion), or a spin angle ω t* beyond
    :data:`~throwmap.kernels.flight.MAX_SPIN_ANGLE` (as the exact models).
    """
    n = d.shape[0]
    for i in range(C.NREC):
        rec[i] = math.nan
    rec[C.N_IMPACTS] = 0.0
    rec[C.N_FLIPS] = 0.0
    rec[C.N_PULL] = 0.0
    dk = d[side]
    u = uL[side]
    rec[C.E_RELEASE] = 0.5 * omega * omega * (x0 * x0 + (h + dk) * (h + dk) + rho2) + g * dk
    if omega == 0.0:
        rec[C.E_FINAL] = g * dk
        return x0, side, (C.BEHIND_JOINT if x0 + u <= -back else C.OK)
    if order == 1:
        t = 2.0 * omega * (x0 + u) / g  # 1.
    else:
        geff = g - dk * omega * omega
        if geff <= 0.0:
            return x0, side, C.UNRESOLVED
        t = 2.0 * omega * (x0 + u) / geff
    if t < 0.0:  # left support vertex behind the joint (arm.back > 0): it moves down at once
        t = 0.0
    if not omega * t <= MAX_SPIN_ANGLE:
        return x0, side, C.UNRESOLVED
    vx, vy0, _ = release_state(x0, dk, h, omega)  # Eq. (1)
    phi = omega * t
    xs = x0 + vx * t  # 2.
    ys = h + dk + vy0 * t - 0.5 * g * t * t
    cph = 1.0 if order == 1 else 1.0 - 0.5 * phi * phi
    rx = u * cph + dk * phi  # 3.
    ry = -dk * cph + u * phi
    vy = vy0 - g * t
    H = rho2 * omega + ry * vx - rx * vy  # 4.
    Ir = rho2 + rx * rx + ry * ry
    wp = H / Ir
    K = 0.5 * Ir * wp * wp  # 5. (per unit mass)
    U = g * (-ry)  # 6.
    U_crit = g * math.sqrt(u * u + dk * dk)
    px = xs + rx
    rec[C.T_FLIGHT] = t
    rec[C.CONTACT_VERTEX] = (side + 1) % n
    rec[C.CONTACT_X] = px
    rec[C.VX_PRE] = vx
    rec[C.VY_PRE] = vy
    rec[C.W_PRE] = omega
    rec[C.VX_POST] = ry * wp
    rec[C.VY_POST] = -rx * wp
    rec[C.W_POST] = wp
    rec[C.JX] = ry * wp - vx
    rec[C.JY] = -rx * wp - vy
    rec[C.K_PRE] = 0.5 * (vx * vx + vy * vy + rho2 * omega * omega)
    rec[C.K_POST] = K
    rec[C.U_IMPACT] = g * (ys - h)
    rec[C.N_IMPACTS] = 1.0
    if px <= -back:
        return xs, side, C.BEHIND_JOINT
    if px > length:
        return xs, side, C.OFF_END
    if wp > 0.0 and K + U - U_crit > 0.0:  # 7. flip
        rec[C.N_FLIPS] = 1.0
        k = (side + 1) % n
        p = px
        while not stable[k]:
            p -= elen[k]
            k = (k + 1) % n
            if k == side:
                break
        x = p - uR[k]
    else:  # jog, 8.: rests with the left vertex where it touched
        k = side
        x = px - u
    rec[C.E_FINAL] = g * d[k]
    if x + uL[k] <= -back:
        return x, k, C.BEHIND_JOINT
    if x + uR[k] > length:
        return x, k, C.OFF_END
    return x, k, C.OK


@njit(cache=True, parallel=True)
def throw_many_small_angle(x0, side, omega, valid, h, g, length, back, rho2, d, uL, uR, ell, elen, stable, order,
                           x_out, side_out, status_out, rec_out):
    """Batch of :func:`throw_one_small_angle` throws in parallel (flat arrays; invalid starts get INVALID_START)."""
    for i in prange(x0.shape[0]):
        if not valid[i]:
            mark_invalid(i, x0, side, x_out, side_out, status_out, rec_out)
            continue
        x, k, st = throw_one_small_angle(x0[i], side[i], omega[i], h, g, length, back, rho2, d, uL, uR, ell, elen,
                                         stable, order, rec_out[i])
        x_out[i] = x
        side_out[i] = k
        status_out[i] = st


@njit(cache=True)
def throw_many_small_angle_serial(x0, side, omega, valid, h, g, length, back, rho2, d, uL, uR, ell, elen, stable,
                                  order, x_out, side_out, status_out, rec_out):
    """:func:`throw_many_small_angle` on the calling thread (batches below :data:`PARALLEL_MIN`; same results)."""
    for i in range(x0.shape[0]):
        if not valid[i]:
            mark_invalid(i, x0, side, x_out, side_out, status_out, rec_out)
            continue
        x, k, st = throw_one_small_angle(x0[i], side[i], omega[i], h, g, length, back, rho2, d, uL, uR, ell, elen,
                                         stable, order, rec_out[i])
        x_out[i] = x
        side_out[i] = k
        status_out[i] = st

"""A pivot at the wall's foot: one vertex in the corner of the arm and the end wall, the part turning about it.

The vertex at (L, h) (arm frame) can move neither into the arm (−y) nor into the wall (+x). While it stays
there the part swings as the sticking pivot (:mod:`~.tilt`: the swing in ψ = θ + α, for any α) with the
contact force (F, N) of :func:`~.stick.stick_forces`, shared by the arm and the wall. The wall takes
every F < 0 (the vertex pressed towards the wall; a frictionless wall's normal force, the wall's friction
not relied on), the arm's Coulomb friction the rest: the pivot holds while N > 0 and F ≤ μN
(:func:`foot_holds`; ``slip`` at F = μN slides it back along the arm, away from the wall; ``lift_off`` at
N = 0). Guards: those of :func:`~.tilt.pivot_stick_tilted` with ``foot`` set.

Reset ``foot`` (:func:`foot_impact`): a pivot sliding along the arm (slip velocity v_A > 0) reaches the foot.
The wall stops the vertex (plastic); the vertex is pinned, so angular momentum about it is kept:
(ρ² + ℓ²) θ̇⁺ = (ρ² + ℓ²) θ̇ − ℓ sin θ v_A (unit mass; CM at A + ℓ (cos θ, sin θ)). The impulse is
(P_x, P_y) = (−v_A (1 − ℓ² sin²θ / I), ℓ cos θ (θ̇⁺ − θ̇)): P_x < 0 is the wall's; P_y must be ≥ 0 (the arm
pushes), else the vertex would leave both surfaces, which is refused.
"""

import math

from numba import njit

from .stick import stick_forces


@njit(cache=True)
def foot_holds(walled, px, length, va, theta, thdot, lj, I, g, mu, alpha):
    """Whether a pivot at ``px`` (m) at rest on the line (``va`` = 0) is at the wall's foot (``walled`` and
    px ≥ ``length``) and stays there: N > 0 and F ≤ μN (:func:`~.stick.stick_forces`, units m g)."""
    if not walled or px < length or va != 0.0:
        return False
    nf, ff = stick_forces(theta, thdot, lj, I, g, alpha)
    return nf > 0.0 and ff <= mu * nf


@njit(cache=True)
def foot_impact(theta, thdot, va, lj, rho2):
    """Reset ``foot`` (module docstring) for a pivot at θ (rad) turning at θ̇ (rad/s) that slides at v_A (m/s)
    into the wall's foot. Returns ``(ok, θ̇⁺, P_t, P_n, K⁻, K⁺)``: P_t = 0 is the arm's tangential impulse (the
    wall takes all of it), P_n the arm's normal impulse (m/s), K the kinetic energy per unit mass (J/kg) before
    and after; ``ok`` False where P_n < 0."""
    I = rho2 + lj * lj
    s = math.sin(theta)
    c = math.cos(theta)
    th1 = thdot - lj * s * va / I
    pn = lj * c * (th1 - thdot)
    vx = va - thdot * lj * s
    vy = thdot * lj * c
    k0 = 0.5 * (vx * vx + vy * vy + rho2 * thdot * thdot)
    k1 = 0.5 * I * th1 * th1
    scale = abs(va) + abs(thdot) * lj
    return pn >= -1e-12 * scale, th1, 0.0, max(pn, 0.0), k0, k1

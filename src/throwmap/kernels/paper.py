"""Model "paper": the exact throw map within the paper's assumptions (Sec. III, Eqs. 1–4).

No small-angle approximation: flight (Eq. 1, g > 0 along −y), first contact of
any vertex (Eq. 3, :func:`~throwmap.kernels.flight.first_contact`), plastic
no-slip impact with r at the impact orientation (Eq. 4), then the exact
pivot/landing/rocking sequence of :mod:`throwmap.kernels.roll`.
"""

import math

import numpy as np
from numba import njit, prange

from . import codes as C
from .flight import gap_constants, release_state, rest_offsets, touch_time
from .impact import plastic_impact
from .roll import roll_to_rest


@njit(cache=True)
def throw_one(x0, side, omega, h, g, length, rho2, w, beta, d, uL, uR, ell, stable, tol, max_iter, max_impacts,
              n_samples, rec):
    """One throw from rest at ``(x0, side)`` with release rate ``omega`` (rad/s).

    Fills ``rec`` (see :mod:`~throwmap.kernels.codes`) and returns ``(x, side, status)``.
    The caller has checked the start (stable side, x0 + u_L > 0, omega ≥ 0).
    """
    n = w.shape[0]
    for i in range(C.NREC):
        rec[i] = 0.0
    rec[C.N_MIN] = math.inf
    rec[C.T_REST] = math.nan
    rec[C.K_MAX_IMPACT_GAIN] = -math.inf
    rec[C.CONTACT_VERTEX] = -1.0
    dk = d[side]
    # release energy per unit mass (Eq. 1): |ω × r|² + ρ²ω², potential from the arm line
    rec[C.E_RELEASE] = 0.5 * omega * omega * (x0 * x0 + (h + dk) * (h + dk) + rho2) + g * dk
    if omega == 0.0:
        rec[C.E_FINAL] = g * dk
        rec[C.N_MIN] = 1.0
        return x0, side, C.OK
    # reset release (Eq. 1); vertices relative to the CM at the rest orientation on `side`
    vx, vy0, _ = release_state(x0, dk, h, omega)
    pu, pv = rest_offsets(w, beta[side])
    c0 = np.empty(n)
    b = np.empty(n)
    gap_constants(dk, pv, ell, c0)
    for j in range(n):
        b[j] = omega * (x0 + pu[j])  # the gaps' initial rates, cancellation-free
    t, jc = touch_time(c0, b, pu, pv, vy0, omega, g, ell, -1, 0.0, tol, max_iter)
    rec[C.T_FLIGHT] = t
    rec[C.CONTACT_VERTEX] = jc
    if jc < 0:
        return x0, side, C.NO_CONTACT
    # state just before impact (Eq. 1)
    phi = omega * t
    xc = x0 + vx * t
    yc = h + dk + vy0 * t - 0.5 * g * t * t
    vy = vy0 - g * t
    cp = math.cos(phi)
    sp = math.sin(phi)
    rx = cp * pu[jc] - sp * pv[jc]
    ry = sp * pu[jc] + cp * pv[jc]
    px = xc + rx
    rec[C.CONTACT_X] = px
    rec[C.VX_PRE] = vx
    rec[C.VY_PRE] = vy
    rec[C.W_PRE] = omega
    k_pre = 0.5 * (vx * vx + vy * vy + rho2 * omega * omega)
    rec[C.K_PRE] = k_pre
    rec[C.U_IMPACT] = g * (yc - h)
    # plastic no-slip impact about the contact vertex (Eq. 4)
    vxp, vyp, wp = plastic_impact(vx, vy, omega, rx, ry, rho2)
    rec[C.VX_POST] = vxp
    rec[C.VY_POST] = vyp
    rec[C.W_POST] = wp
    jx = vxp - vx
    jy = vyp - vy
    rec[C.JX] = jx
    rec[C.JY] = jy
    if jy > 0.0:
        rec[C.MU_IMPACT] = abs(jx) / jy
        rec[C.MU_MAX] = rec[C.MU_IMPACT]
    else:
        rec[C.MU_IMPACT] = math.inf if jx != 0.0 else 0.0
        if jy < 0.0:
            rec[C.N_PULL] += 1.0
    k_post = 0.5 * (rho2 + rx * rx + ry * ry) * wp * wp
    rec[C.K_POST] = k_post
    rec[C.K_MAX_IMPACT_GAIN] = k_post - k_pre
    rec[C.N_IMPACTS] = 1.0
    if px <= 0.0:
        return xc, side, C.BEHIND_JOINT
    if px > length:
        return xc, side, C.OFF_END
    theta = math.atan2(-ry, -rx)
    x, k, status = roll_to_rest(jc, theta, wp, px, side, rho2, d, uL, uR, ell, stable, g, length, max_impacts,
                                n_samples, rec)
    rec[C.E_FINAL] = g * d[k]
    if status == C.OK:
        if x + uL[k] <= 0.0:
            status = C.BEHIND_JOINT
        elif x > length:
            status = C.OFF_END
    return x, k, status


@njit(cache=True, parallel=True)
def throw_many(x0, side, omega, valid, h, g, length, rho2, w, beta, d, uL, uR, ell, stable, tol, max_iter,
               max_impacts, n_samples, x_out, side_out, status_out, rec_out):
    """Batch of independent throws (flat arrays); invalid starts get ``INVALID_START``."""
    for i in prange(x0.shape[0]):
        if not valid[i]:
            x_out[i] = x0[i]
            side_out[i] = side[i]
            status_out[i] = C.INVALID_START
            for q in range(C.NREC):
                rec_out[i, q] = math.nan
            continue
        x, k, st = throw_one(x0[i], side[i], omega[i], h, g, length, rho2, w, beta, d, uL, uR, ell, stable, tol,
                             max_iter, max_impacts, n_samples, rec_out[i])
        x_out[i] = x
        side_out[i] = k
        status_out[i] = st

"""Model "paper": the exact throw map within the paper's assumptions (Sec. III, Eqs. 1–4).

No small-angle approximation: release (Eq. 1, :func:`~throwmap.kernels.flight.release_state`),
flight and first contact of any vertex (Eq. 3, :func:`~throwmap.kernels.flight.touch_time`),
plastic no-slip impact with r at the impact orientation (Eq. 4,
:func:`~throwmap.kernels.impact.plastic_impact`), then the exact pivot/landing/rocking
sequence of :mod:`throwmap.kernels.roll`.

Entry points: :func:`throw_one` (one throw), :func:`throw_one_traj` (one throw with
its trajectory rows, :mod:`~throwmap.kernels.record`) and :func:`throw_many` (a
batch, in parallel; no trajectory cost: its buffers have zero rows) with its serial
twin :func:`throw_many_serial` for batches below :data:`PARALLEL_MIN`.

Tilted arm (``alpha``, rad, CCW +, |α| < π/2; draft Sec. VI): the arm rests at α and
the impulse throw gives the part ω × r with the arm itself not moving (as the engine's
:class:`~throwmap.system.motion.ImpulseThrow`). In the arm frame this is the
horizontal throw with gravity (−g sin α, −g cos α): the first-contact search sees the
normal component g cos α, the CM's x gets −½ g sin α t², and the cascade runs in
ψ = θ + α (:mod:`~throwmap.kernels.roll`). Energies use U = g cos α (y − h) + g sin α x.
``stable`` must be the table for α (:func:`throwmap.kernels.rigid_body.tilt.tilted_stable`).
α = 0 runs the horizontal code unchanged, bit for bit.
"""

import math

import numpy as np
from numba import njit, prange

from . import codes as C
from . import record as R
from .flight import UNRESOLVED_J, gap_constants, release_state, touch_time
from .impact import plastic_impact
from .roll import pivot_cascade, side_angles
from .rows import mark_invalid, start_record

CHUNK = 256
"""Throws per work unit of :func:`throw_many` (one scratch allocation per chunk)."""

PARALLEL_MIN = 4096
"""Smallest batch the "paper" model runs on Numba's thread pool (:func:`throw_many`); smaller
batches run on the calling thread (:func:`throw_many_serial`, same results). A throw takes
about 1–3 µs, while waking the pool costs tens of µs and, when the cores are busy, can
cost milliseconds (critical_points: 108 ms on two threads vs 3.7 ms on one)."""


@njit(cache=True, inline="always")
def _throw(x0, side, omega, h, g, alpha, length, back, rho2, w, beta, d, uL, uR, ell, stable, tol, max_iter,
           max_impacts, n_samples, ta_j, tb_j, work, rec, traj, tags, ts):
    """One throw; ``work`` is (4, n) scratch, ``traj``/``tags``/``ts`` the trajectory writer (0 rows: none)."""
    n = w.shape[0]
    start_record(rec)
    dk = d[side]
    record = traj.shape[0] > 0
    phi0 = beta[side]
    tilted = alpha != 0.0
    gt = g * math.sin(alpha)  # gravity along the arm (−gt) and normal to it (−gn)
    gn = g * math.cos(alpha)
    if record:
        R.put(traj, tags, ts, 0.0, x0, h + dk, phi0, n + side)
    # release energy per unit mass (Eq. 1): |ω × r|² + ρ²ω², potential from the arm line
    if tilted:
        rec[C.E_RELEASE] = 0.5 * omega * omega * (x0 * x0 + (h + dk) * (h + dk) + rho2) + gn * dk + gt * x0
    else:
        rec[C.E_RELEASE] = 0.5 * omega * omega * (x0 * x0 + (h + dk) * (h + dk) + rho2) + g * dk
    if omega == 0.0:
        rec[C.E_FINAL] = gn * dk + gt * x0 if tilted else g * dk
        rec[C.N_MIN] = 1.0
        if tilted:
            rec[C.MU_MAX] = abs(math.tan(alpha))  # the friction that holds it at rest
        return x0, side, (C.BEHIND_JOINT if x0 + uL[side] <= -back else C.OK)
    # reset release (Eq. 1); vertices relative to the CM at the rest orientation on `side`
    vx, vy0, _ = release_state(x0, dk, h, omega)
    pu = work[0]
    pv = work[1]
    c0 = work[2]
    b = work[3]
    cb = math.cos(phi0)
    sb = math.sin(phi0)
    for j in range(n):
        pu[j] = cb * w[j, 0] - sb * w[j, 1]
        pv[j] = sb * w[j, 0] + cb * w[j, 1]
        b[j] = omega * (x0 + pu[j])  # the gaps' initial rates, cancellation-free
    gap_constants(dk, pv, ell, c0)
    t, jc = touch_time(c0, b, pu, pv, vy0, omega, gn, ell, -1, 0.0, tol, max_iter)
    rec[C.T_FLIGHT] = t
    rec[C.CONTACT_VERTEX] = jc
    if jc < 0:
        if record:
            R.release_flight_rows(traj, tags, ts, R.ESCAPE_FALL_TIME, x0, dk, h, omega, gn, phi0, R.FLIGHT, gt)
        if jc != UNRESOLVED_J:
            rec[C.CAP_HIT] = 1.0  # max_iter steps without contact: not resolved, not a missed contact
        return x0, side, C.UNRESOLVED
    # state just before impact (Eq. 1)
    phi = omega * t
    if tilted:
        xc = x0 + vx * t - 0.5 * gt * t * t
        vx = vx - gt * t
    else:
        xc = x0 + vx * t
    yc = h + dk + vy0 * t - 0.5 * gn * t * t
    vy = vy0 - gn * t
    cp = math.cos(phi)
    sp = math.sin(phi)
    rx = cp * pu[jc] - sp * pv[jc]
    ry = sp * pu[jc] + cp * pv[jc]
    px = xc + rx
    if record:
        R.release_flight_rows(traj, tags, ts, t, x0, dk, h, omega, gn, phi0, jc, gt)
    rec[C.CONTACT_X] = px
    rec[C.VX_PRE] = vx
    rec[C.VY_PRE] = vy
    rec[C.W_PRE] = omega
    k_pre = 0.5 * (vx * vx + vy * vy + rho2 * omega * omega)
    rec[C.K_PRE] = k_pre
    rec[C.U_IMPACT] = gn * (yc - h) + gt * xc if tilted else g * (yc - h)
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
    if px <= -back or px > length:
        if record:  # nothing to land on there: the part falls on past the arm line
            R.flight_rows(traj, tags, ts, t, t + R.ESCAPE_FALL_TIME, xc, yc, phi0 + omega * t, vx, vy, omega, gn,
                          R.FLIGHT, gt)
        return xc, side, (C.BEHIND_JOINT if px <= -back else C.OFF_END)
    theta = math.atan2(-ry, -rx)
    x, k, status = pivot_cascade(jc, theta, wp, px, side, rho2, d, uL, uR, ell, stable, ta_j, tb_j, g, length,
                                 max_impacts, n_samples, rec, traj, tags, ts, h, w, beta, back, alpha)
    if tilted:
        rec[C.E_FINAL] = gn * d[k] + gt * x
        if status == C.OK and abs(math.tan(alpha)) > rec[C.MU_MAX]:
            rec[C.MU_MAX] = abs(math.tan(alpha))  # the friction that holds it at rest
    else:
        rec[C.E_FINAL] = g * d[k]
    if status == C.OK:
        if x + uL[k] <= -back:
            status = C.BEHIND_JOINT
        elif x + uR[k] > length:
            status = C.OFF_END
    return x, k, status


@njit(cache=True)
def throw_one(x0, side, omega, h, g, alpha, length, back, rho2, w, beta, d, uL, uR, ell, stable, tol, max_iter,
              max_impacts, n_samples, rec):
    """One throw from rest at ``(x0, side)`` with release rate ``omega`` (rad/s).

    ``length`` (m, inf: unbounded) and ``back`` (m, ``Arm.back``) bound the arm's
    surface: a contact at x ≤ −back is BEHIND_JOINT, beyond length OFF_END; ``tol``
    is the relative contact tolerance (:func:`~throwmap.kernels.flight.touch_time`).
    Fills ``rec`` (see :mod:`~throwmap.kernels.codes`) and returns ``(x, side, status)``.
    The caller has checked the start (stable side, x0 + u_L > −back, omega ≥ 0).
    """
    ta_j, tb_j = side_angles(d, uL, uR)
    work = np.empty((4, w.shape[0]))
    return _throw(x0, side, omega, h, g, alpha, length, back, rho2, w, beta, d, uL, uR, ell, stable, tol, max_iter,
                  max_impacts, n_samples, ta_j, tb_j, work, rec, np.empty((0, 4)), np.empty(0, np.int64),
                  np.zeros(R.NTS))


@njit(cache=True)
def throw_one_traj(x0, side, omega, h, g, alpha, length, back, rho2, w, beta, d, uL, uR, ell, stable, tol, max_iter,
                   max_impacts, n_samples, rec, traj, tags, dt):
    """:func:`throw_one` also recording its trajectory every ``dt`` s and at every event.

    ``traj`` (M, 4) gets rows (t, x_cm, y_cm, φ) and ``tags`` (M,) their contacts
    (:mod:`~throwmap.kernels.record`): the resting start at t = 0, the flight, the
    first contact, every pivot swing and landing, ending at the rest pose (or the
    escape). Returns ``(x, side, status, rows, dropped)``: ``dropped`` rows did
    not fit (call again with M ≥ rows + dropped).
    """
    ta_j, tb_j = side_angles(d, uL, uR)
    work = np.empty((4, w.shape[0]))
    ts = R.new_state(dt)
    x, k, st = _throw(x0, side, omega, h, g, alpha, length, back, rho2, w, beta, d, uL, uR, ell, stable, tol, max_iter,
                      max_impacts, n_samples, ta_j, tb_j, work, rec, traj, tags, ts)
    return x, k, st, int(ts[R.COUNT]), int(ts[R.DROPPED])


@njit(cache=True, inline="always")
def _chunk(c, x0, side, omega, valid, h, g, alpha, length, back, rho2, w, beta, d, uL, uR, ell, stable, tol, max_iter,
           max_impacts, n_samples, ta_j, tb_j, x_out, side_out, status_out, rec_out):
    """Throws ``c·CHUNK`` … ``(c+1)·CHUNK − 1`` of a batch (one scratch allocation)."""
    m = x0.shape[0]
    work = np.empty((4, w.shape[0]))
    traj = np.empty((0, 4))
    tags = np.empty(0, np.int64)
    ts = np.zeros(R.NTS)
    for i in range(c * CHUNK, min(m, (c + 1) * CHUNK)):
        if not valid[i]:
            mark_invalid(i, x0, side, x_out, side_out, status_out, rec_out)
            continue
        x, k, st = _throw(x0[i], side[i], omega[i], h, g, alpha, length, back, rho2, w, beta, d, uL, uR, ell, stable,
                          tol, max_iter, max_impacts, n_samples, ta_j, tb_j, work, rec_out[i], traj, tags, ts)
        x_out[i] = x
        side_out[i] = k
        status_out[i] = st


@njit(cache=True, parallel=True)
def throw_many(x0, side, omega, valid, h, g, alpha, length, back, rho2, w, beta, d, uL, uR, ell, stable, tol, max_iter,
               max_impacts, n_samples, x_out, side_out, status_out, rec_out):
    """Batch of independent throws (flat arrays), chunks in parallel; invalid starts get ``INVALID_START``.

    Arguments as :func:`throw_one`; fills ``x_out``, ``side_out``, ``status_out`` (m,)
    and ``rec_out`` (m, NREC). Same results as :func:`throw_many_serial`; the model
    picks this one for batches of at least :data:`PARALLEL_MIN` throws.
    """
    ta_j, tb_j = side_angles(d, uL, uR)
    n_chunks = (x0.shape[0] + CHUNK - 1) // CHUNK
    for c in prange(n_chunks):
        _chunk(c, x0, side, omega, valid, h, g, alpha, length, back, rho2, w, beta, d, uL, uR, ell, stable, tol,
               max_iter, max_impacts, n_samples, ta_j, tb_j, x_out, side_out, status_out, rec_out)


@njit(cache=True)
def throw_many_serial(x0, side, omega, valid, h, g, alpha, length, back, rho2, w, beta, d, uL, uR, ell, stable, tol,
                      max_iter, max_impacts, n_samples, x_out, side_out, status_out, rec_out):
    """:func:`throw_many` on the calling thread (no thread-pool wake-up): for batches below :data:`PARALLEL_MIN`."""
    ta_j, tb_j = side_angles(d, uL, uR)
    n_chunks = (x0.shape[0] + CHUNK - 1) // CHUNK
    for c in range(n_chunks):
        _chunk(c, x0, side, omega, valid, h, g, alpha, length, back, rho2, w, beta, d, uL, uR, ell, stable, tol,
               max_iter, max_impacts, n_samples, ta_j, tb_j, x_out, side_out, status_out, rec_out)

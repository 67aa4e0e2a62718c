"""Batches of independent "rigid_body" throws (flat arrays, Numba-parallel).

Two entries with one loop each (a jitted function passed into a parallel loop
cannot be cached): :func:`throw_many_rigid_body` (closed-form sticking phase)
and :func:`throw_many_rigid_body_rk4` (the RK4 reference). Batches smaller than
``SERIAL_BELOW`` run on the calling thread: the analysis layer asks for many
small batches, for which waking the thread pool costs more than the throws.
"""


import numpy as np
from numba import njit, prange

from ..rows import mark_invalid
from .automaton import throw_one_rigid_body, throw_one_rigid_body_rk4

SERIAL_BELOW = 128
"""Batches with fewer throws than this run serially (same results, no thread-pool wake-up)."""


@njit(cache=True)
def _serial(x0, side, omega, valid, h, g, length, rho2, mu, w, beta, d, uL, uR, ell, stable, tol, max_iter, max_events,
            x_out, side_out, status_out, rec_out):
    no_traj = np.empty((0, 4))
    for i in range(x0.shape[0]):
        if not valid[i]:
            mark_invalid(i, x0, side, x_out, side_out, status_out, rec_out)
            continue
        x, k, st = throw_one_rigid_body(x0[i], side[i], omega[i], h, g, length, rho2, mu, w, beta, d, uL, uR, ell,
                                        stable, tol, max_iter, max_events, rec_out[i], no_traj, 0.0)
        x_out[i] = x
        side_out[i] = k
        status_out[i] = st


@njit(cache=True, parallel=True)
def throw_many_rigid_body(x0, side, omega, valid, h, g, length, rho2, mu, w, beta, d, uL, uR, ell, stable, tol,
                          max_iter, max_events, x_out, side_out, status_out, rec_out):
    """Batch of independent throws (flat arrays), model "rigid_body"; invalid starts get INVALID_START.

    Fills ``x_out``, ``side_out``, ``status_out`` (n,) and ``rec_out`` (n, NREC) in
    place; each throw as :func:`~.automaton.throw_one_rigid_body`.
    """
    no_traj = np.empty((0, 4))
    for i in prange(x0.shape[0]):
        if not valid[i]:
            mark_invalid(i, x0, side, x_out, side_out, status_out, rec_out)
            continue
        x, k, st = throw_one_rigid_body(x0[i], side[i], omega[i], h, g, length, rho2, mu, w, beta, d, uL, uR, ell,
                                        stable, tol, max_iter, max_events, rec_out[i], no_traj, 0.0)
        x_out[i] = x
        side_out[i] = k
        status_out[i] = st


@njit(cache=True, parallel=True)
def throw_many_rigid_body_rk4(x0, side, omega, valid, h, g, length, rho2, mu, w, beta, d, uL, uR, ell, stable, tol,
                              max_iter, max_events, x_out, side_out, status_out, rec_out):
    """:func:`throw_many_rigid_body` with the RK4 sticking phase (:func:`~.automaton.throw_one_rigid_body_rk4`)."""
    no_traj = np.empty((0, 4))
    for i in prange(x0.shape[0]):
        if not valid[i]:
            mark_invalid(i, x0, side, x_out, side_out, status_out, rec_out)
            continue
        x, k, st = throw_one_rigid_body_rk4(x0[i], side[i], omega[i], h, g, length, rho2, mu, w, beta, d, uL, uR,
                                            ell, stable, tol, max_iter, max_events, rec_out[i], no_traj, 0.0)
        x_out[i] = x
        side_out[i] = k
        status_out[i] = st

"""Batches of independent "rigid_body" throws (flat arrays), in parallel or on the calling thread.

Each batch entry has a parallel kernel (Numba ``prange``) and a serial twin with the
same loop (a jitted function passed into a parallel loop cannot be cached, so each
sticking phase has its own pair): :func:`throw_many_rigid_body` /
:func:`throw_many_rigid_body_serial` (closed-form sticking phase) and
:func:`throw_many_rigid_body_rk4` / :func:`throw_many_rigid_body_rk4_serial` (the RK4
reference). :func:`pick` chooses by batch size: batches smaller than
:data:`PARALLEL_MIN` run serially, since the analysis layer asks for many small
batches, for which waking the thread pool costs more than the throws.
"""


import numpy as np
from numba import njit, prange

from ..rows import mark_invalid
from .automaton import throw_one_rigid_body, throw_one_rigid_body_rk4

PARALLEL_MIN = 1024
"""Smallest batch run on Numba's thread pool; smaller batches run serially (same results).

A "rigid_body" throw takes about 2–20 µs; waking the pool costs tens of µs and, when
the cores are busy, up to milliseconds per call (``critical_points`` took
108 ms on two threads and 3.7 ms on one under load)."""


@njit(cache=True)
def throw_many_rigid_body_serial(x0, side, omega, valid, part, arm, lim, x_out, side_out, status_out, rec_out):
    """:func:`throw_many_rigid_body` on the calling thread (batches below :data:`PARALLEL_MIN`)."""
    no_traj = np.empty((0, 4))
    for i in range(x0.shape[0]):
        if not valid[i]:
            mark_invalid(i, x0, side, x_out, side_out, status_out, rec_out)
            continue
        x, k, st = throw_one_rigid_body(x0[i], side[i], omega[i], part, arm, lim, rec_out[i], no_traj, 0.0)
        x_out[i] = x
        side_out[i] = k
        status_out[i] = st


@njit(cache=True, parallel=True)
def throw_many_rigid_body(x0, side, omega, valid, part, arm, lim, x_out, side_out, status_out, rec_out):
    """Batch of independent throws (flat arrays), model "rigid_body"; invalid starts get INVALID_START.

    Fills ``x_out``, ``side_out``, ``status_out`` (n,) and ``rec_out`` (n, NREC) in
    place; each throw as :func:`~.automaton.throw_one_rigid_body` with the records ``part``, ``arm`` and ``lim``
    (:mod:`~.inputs`).
    """
    no_traj = np.empty((0, 4))
    for i in prange(x0.shape[0]):
        if not valid[i]:
            mark_invalid(i, x0, side, x_out, side_out, status_out, rec_out)
            continue
        x, k, st = throw_one_rigid_body(x0[i], side[i], omega[i], part, arm, lim, rec_out[i], no_traj, 0.0)
        x_out[i] = x
        side_out[i] = k
        status_out[i] = st


@njit(cache=True, parallel=True)
def throw_many_rigid_body_rk4(x0, side, omega, valid, part, arm, lim, x_out, side_out, status_out, rec_out):
    """:func:`throw_many_rigid_body` with the RK4 sticking phase (:func:`~.automaton.throw_one_rigid_body_rk4`)."""
    no_traj = np.empty((0, 4))
    for i in prange(x0.shape[0]):
        if not valid[i]:
            mark_invalid(i, x0, side, x_out, side_out, status_out, rec_out)
            continue
        x, k, st = throw_one_rigid_body_rk4(x0[i], side[i], omega[i], part, arm, lim, rec_out[i], no_traj, 0.0)
        x_out[i] = x
        side_out[i] = k
        status_out[i] = st


@njit(cache=True)
def throw_many_rigid_body_rk4_serial(x0, side, omega, valid, part, arm, lim, x_out, side_out, status_out, rec_out):
    """:func:`throw_many_rigid_body_rk4` on the calling thread (batches below :data:`PARALLEL_MIN`)."""
    no_traj = np.empty((0, 4))
    for i in range(x0.shape[0]):
        if not valid[i]:
            mark_invalid(i, x0, side, x_out, side_out, status_out, rec_out)
            continue
        x, k, st = throw_one_rigid_body_rk4(x0[i], side[i], omega[i], part, arm, lim, rec_out[i], no_traj, 0.0)
        x_out[i] = x
        side_out[i] = k
        status_out[i] = st


def pick(n: int, rk4: bool = False):
    """The batch kernel for ``n`` throws: parallel from :data:`PARALLEL_MIN` throws on, else its serial twin."""
    if rk4:
        return throw_many_rigid_body_rk4 if n >= PARALLEL_MIN else throw_many_rigid_body_rk4_serial
    return throw_many_rigid_body if n >= PARALLEL_MIN else throw_many_rigid_body_serial

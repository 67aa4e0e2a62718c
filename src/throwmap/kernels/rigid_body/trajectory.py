"""Trajectory rows of model "rigid_body": (t, x_cm, y_cm, φ) every ``traj_dt`` s and at every event.

``traj`` (M, 4) is pre-filled with NaN; ``ts`` = [rows written, next sample
time, sample period] (s). Regular samples stop at M − 1 rows so that the last
row can still receive the final pose; M = 0 records nothing.
"""

import math

from numba import njit


@njit(cache=True)
def _write_row(traj, ts, i, t, x, y, phi):
    traj[i, 0] = t
    traj[i, 1] = x
    traj[i, 2] = y
    traj[i, 3] = phi
    ts[0] = i + 1


@njit(cache=True)
def _put(traj, ts, t, x, y, phi):
    """Append a row (regular samples keep the last row free for the final pose)."""
    i = int(ts[0])
    if i < traj.shape[0] - 1:
        _write_row(traj, ts, i, t, x, y, phi)


@njit(cache=True)
def _put_final(traj, ts, t, x, y, phi):
    """Write the final pose, into the last row if the regular samples filled the rest."""
    m = traj.shape[0]
    if m > 0:
        _write_row(traj, ts, min(int(ts[0]), m - 1), t, x, y, phi)


@njit(cache=True)
def clear(traj, ts, traj_dt):
    """Fill ``traj`` with NaN and set the sample clock ``ts`` (period ``traj_dt`` s, none if ≤ 0)."""
    for i in range(traj.shape[0]):
        for q in range(4):
            traj[i, q] = math.nan
    ts[0] = 0.0
    ts[1] = 0.0
    ts[2] = traj_dt if traj_dt > 0.0 else math.inf


@njit(cache=True)
def put_pivot(traj, ts, t, px, h, lj, theta, phi_off):
    """Row for a pose pivoting on the vertex at (px, h): CM = (px, h) + ℓ (cos θ, sin θ), φ = θ + phi_off."""
    _put(traj, ts, t, px + lj * math.cos(theta), h + lj * math.sin(theta), theta + phi_off)


@njit(cache=True)
def count_samples(traj):
    """Number of trajectory rows written (leading rows whose time is not NaN)."""
    for i in range(traj.shape[0]):
        if math.isnan(traj[i, 0]):
            return i
    return traj.shape[0]

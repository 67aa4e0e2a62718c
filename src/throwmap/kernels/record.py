"""Trajectory rows written by the analytic kernels (model "paper"): poses sampled in time.

``traj`` (M, 4) receives rows (t, x_cm, y_cm, φ) (s, m, m, rad): the world pose of
:mod:`throwmap.records.trajectory` (vertex_j = (x, y) + R(φ) w_j; φ continuous, not
wrapped). ``tags`` (M,) says what touches the arm at each row: ``FLIGHT`` (−1)
nothing, 0 ≤ j < n the pivot vertex w_j, n + k both support vertices of side k
(at rest or at a landing). ``ts`` (:data:`NTS`,) carries the writer's state:
rows written, sample interval, rows that did not fit, and the last row's φ and t.

Samples follow each phase's own grid: t0 + i dt from the phase's start t0 and
exactly its end (a flight from release, each pivot swing from its start), as
:func:`grid_count` says. A swing's time t(θ) = ∫ dθ / |θ̇(θ)|, θ̇² = 2(E − g ℓ_j sin θ)/I_j,
is tabulated by :func:`swing_table` (the substitution θ = θ0 + (θ1 − θ0)(1 − cos πu)/2
removes the inverse-square-root singularity at a turning point or a start from rest;
midpoint rule in u) and inverted by linear interpolation.

Rows that do not fit in ``traj`` are counted in ``ts[DROPPED]`` (the caller
retries with a larger buffer); M = 0 records nothing (the batch path).

On an arm at rest angle α the rows stay in the ARM frame (the model turns them into
the world): flights get −½ g_t t² along the arm (``gt`` = g sin α, ``g`` its normal
component g cos α), and a swing is tabulated in ψ = θ + α (``tilt`` = α), the
horizontal pendulum, and drawn at θ = ψ − α.
"""

import math

import numpy as np
from numba import njit

FLIGHT = -1
"""Tag of a row in flight (no contact)."""
COUNT = 0  # ts slots
DT = 1
DROPPED = 2
PHI = 3
T_NOW = 4
NTS = 5
QUADRATURE_NODES = 400
"""Nodes of the time quadrature per monotone piece of a pivot swing."""
ESCAPE_FALL_TIME = 0.3
"""After a first contact off the arm (or none), the free fall is drawn for this long, s."""


@njit(cache=True)
def new_state(dt):
    """A writer state for sample interval ``dt`` (s)."""
    ts = np.zeros(NTS)
    ts[DT] = dt
    return ts


@njit(cache=True)
def put(traj, tags, ts, t, x, y, phi, tag):
    """Append the row (t, x, y, φ) with its contact ``tag`` (counted in ``ts[DROPPED]`` when full)."""
    i = int(ts[COUNT])
    if i < traj.shape[0]:
        traj[i, 0] = t
        traj[i, 1] = x
        traj[i, 2] = y
        traj[i, 3] = phi
        tags[i] = tag
        ts[COUNT] = i + 1
    else:
        ts[DROPPED] += 1.0
    ts[PHI] = phi
    ts[T_NOW] = t


@njit(cache=True)
def grid_count(t0, t1, dt):
    """Rows of a phase from t0 to t1 after its first: t0 + i dt for i < n, and t1 as the n-th."""
    if t1 <= t0:
        return 1
    return max(1, int(math.ceil((t1 - t0) / dt - 1e-9)))


@njit(cache=True)
def continue_angle(phi, phi_prev):
    """``phi`` shifted by a multiple of 2π to continue ``phi_prev``."""
    return phi + 2.0 * math.pi * round((phi_prev - phi) / (2.0 * math.pi))


@njit(cache=True)
def flight_rows(traj, tags, ts, t0, t1, x0, y0, phi0, vx, vy, w, g, last_tag, gt=0.0):
    """Rows of a ballistic flight (Eq. 1) from the pose (x0, y0, φ0) at t0 with velocity (vx, vy, w) up to t1.

    Gravity (−gt, −g) (m/s²). The row at t1 gets ``last_tag`` (the touching vertex at a first contact).
    """
    dt = ts[DT]
    n = grid_count(t0, t1, dt)
    for i in range(1, n + 1):
        tq = t1 if i == n else t0 + dt * i
        if t1 <= t0:
            tq = t0
        s = tq - t0
        put(traj, tags, ts, tq, x0 + vx * s - 0.5 * gt * s * s, y0 + vy * s - 0.5 * g * s * s, phi0 + w * s,
            last_tag if i == n else FLIGHT)


@njit(cache=True)
def release_flight_rows(traj, tags, ts, t1, x0, dk, h, omega, g, phi0, last_tag, gt=0.0):
    """Rows of the flight from release (Eq. 1 in the form x0 − (h+d)ωt − ½g_t t², h + d + x0ωt − ½gt²) up to t1."""
    dt = ts[DT]
    n = grid_count(0.0, t1, dt)
    for i in range(1, n + 1):
        tq = t1 if i == n else dt * i
        if t1 <= 0.0:
            tq = 0.0
        put(traj, tags, ts, tq, x0 - (h + dk) * omega * tq - 0.5 * gt * tq * tq,
            h + dk + x0 * omega * tq - 0.5 * g * tq * tq,
            phi0 + omega * tq, last_tag if i == n else FLIGHT)


@njit(cache=True)
def swing_table(th0, th1, E, lj, I, g, nodes, t_tab, th_tab, k0, t_start):
    """Fill ``t_tab[k0 : k0 + nodes + 1]``, ``th_tab[…]`` with (t, θ) along a monotone swing θ0 → θ1.

    ``t(θ) = t_start + ∫ dθ / |θ̇|`` at energy E (J/kg) about a pivot at distance
    ℓ_j (m), I = ρ² + ℓ_j² (m²); |θ̇| is floored at 1e-6 √(g/ℓ_j) so a swing that
    creeps over a peak with (numerically) zero margin takes a finite time.
    """
    dth = th1 - th0
    for i in range(nodes + 1):
        u = i / nodes
        th_tab[k0 + i] = th0 + dth * 0.5 * (1.0 - math.cos(math.pi * u))
        t_tab[k0 + i] = t_start
    th_tab[k0 + nodes] = th1
    if th1 == th0:
        return
    floor = 1e-6 * math.sqrt(g / lj)
    acc = 0.0
    for i in range(nodes):
        um = 0.5 * (i / nodes + (i + 1) / nodes)
        thm = th0 + dth * 0.5 * (1.0 - math.cos(math.pi * um))
        dth_du = abs(dth) * 0.5 * math.pi * math.sin(math.pi * um)
        w2 = 2.0 * (E - g * lj * math.sin(thm)) / I
        acc += dth_du / math.sqrt(max(w2, floor * floor))
        t_tab[k0 + i + 1] = t_start + acc / nodes


@njit(cache=True)
def _interp(x, xp, fp, k):
    """np.interp(x, xp, fp) for non-decreasing x over successive calls; ``k`` the bracket to start from."""
    m = xp.shape[0]
    while k + 1 < m and xp[k + 1] <= x:
        k += 1
    if k + 1 >= m:
        return fp[m - 1], k
    if x <= xp[0]:
        return fp[0], k
    slope = (fp[k + 1] - fp[k]) / (xp[k + 1] - xp[k])
    return slope * (x - xp[k]) + fp[k], k


@njit(cache=True)
def swing_rows(traj, tags, ts, j, px, lj, alpha_j, h, th0, th_turn, end, E, I, g, tilt=0.0):
    """Rows of one pivot swing about w_j at x = ``px`` from θ0 (through ``th_turn`` unless NaN) to ``end``.

    Writes the rows strictly inside the swing; returns ``(t_end, φ_end)``, the
    time and continuous body angle on arrival (the caller writes the landing row).
    φ = θ + π − α_j with α_j the body angle of w_j. On a tilted arm the angles given
    are ψ = θ + ``tilt`` (the pendulum's, rad) and the rows are drawn at θ = ψ − tilt.
    """
    nodes = QUADRATURE_NODES
    two = not math.isnan(th_turn)
    m = 2 * nodes + 1 if two else nodes + 1
    t_tab = np.empty(m)
    th_tab = np.empty(m)
    if two:
        swing_table(th0, th_turn, E, lj, I, g, nodes, t_tab, th_tab, 0, 0.0)
        swing_table(th_turn, end, E, lj, I, g, nodes, t_tab, th_tab, nodes, t_tab[nodes])
    else:
        swing_table(th0, end, E, lj, I, g, nodes, t_tab, th_tab, 0, 0.0)
    t0 = ts[T_NOW]
    t1 = t0 + t_tab[m - 1]
    off = continue_angle(th0 - tilt + math.pi - alpha_j, ts[PHI]) - th0
    dt = ts[DT]
    n = grid_count(t0, t1, dt)
    k = 0
    for i in range(1, n):
        tq = t0 + dt * i
        th, k = _interp(tq - t0, t_tab, th_tab, k)
        thp = th - tilt
        put(traj, tags, ts, tq, px + lj * math.cos(thp), h + lj * math.sin(thp), th + off, j)
    return (t0 if t1 <= t0 else t1), end + off


@njit(cache=True)
def count_rows(ts):
    """Rows written."""
    return int(ts[COUNT])

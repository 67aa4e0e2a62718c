"""Mode PIVOT_STICK of model "rigid_body" in closed form (the default sticking phase).

Same guards, resets and signature as the RK4 phase :func:`~throwmap.kernels.rigid_body.stick.pivot_stick`,
with the swing followed exactly (:mod:`~throwmap.kernels.rigid_body.swing`):

1. the path: the swing's pieces with monotone s = sin θ (reach the end ahead, or
   turn back where sin θ = e and sweep to the end behind);
2. on each piece, in order: ``lift_off`` at the first root of N(s) (quadratic),
   ``slip`` at the first root of P(s) = μ²N² − F² (quartic, isolated exactly),
   else on to the next piece; no guard on the last piece: ``land`` at its end;
3. θ̇ at the event from the energy, with the sense of the piece; the time from
   the elliptic integral :func:`~throwmap.kernels.rigid_body.swing.swing_time`.

Records: N_MIN (the exact minimum of N over the swept arc), MU_MAX (|F|/N at
``N_ARC`` points of each piece swept, equally spaced in s, where N > 0).
Trajectory samples invert t(θ) on the piece by bisection.
"""

import math

from numba import njit

from .. import codes as C
from .modes import EV_LAND_A, EV_LAND_B, EV_LIFT_OFF, EV_SLIP, N_ARC
from .stick import _n_min_range, _n_stick
from ..roll import swing_sense
from .swing import first_quartic_root, n_roots, slip_quartic, swing_pieces, swing_time, theta_on_piece
from .trajectory import put_pivot


@njit(cache=True)
def _record_friction_ratio(s_a, s_b, e, k, rec):
    """MU_MAX ← max |F|/N at N_ARC points equally spaced in s between s_a and s_b (points with N > 0)."""
    best = rec[C.MU_MAX]
    for i in range(N_ARC):
        s = s_a + (s_b - s_a) * i / (N_ARC - 1)
        nf = _n_stick(s, e, k)
        if nf > 0.0:
            c2 = 1.0 - s * s
            f = 3.0 * s - 2.0 * e
            r = k * math.sqrt(c2 if c2 > 0.0 else 0.0) * abs(f) / nf
            if r > best:
                best = r
    rec[C.MU_MAX] = best


@njit(cache=True)
def _sample_piece(a, b, t0, t1, e, c, px, h, lj, phi_off, traj, ts):
    """Trajectory rows at the sample times in [t0, t1] of the piece a → b swept from time t0 (θ by bisection in t(θ))."""
    while ts[1] <= t1:
        tq = ts[1] - t0
        lo = a
        hi = b
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if mid == lo or mid == hi:
                break
            if swing_time(a, mid, e, c) < tq:
                lo = mid
            else:
                hi = mid
        put_pivot(traj, ts, ts[1], px, h, lj, 0.5 * (lo + hi), phi_off)
        ts[1] += ts[2]


@njit(cache=True)
def pivot_stick_exact(theta, thdot, ta, tb, lj, I, g, mu, t, max_steps, px, h, phi_off, traj, ts, rec):
    """Mode PIVOT_STICK on a vertex at (px, h) from (θ, θ̇) until a guard fires, in closed form.

    Guards ``land`` (θ = θa or θb), ``lift_off`` (N = 0), ``slip`` (|F| = μN), all
    located exactly; ``max_steps`` is unused (no steps). Updates N_MIN, MU_MAX in
    ``rec`` and the trajectory. Returns ``(event, θ, θ̇, t)``.
    """
    c = g * lj / I
    k = lj * lj / I
    E = 0.5 * I * thdot * thdot + g * lj * math.sin(theta)
    e = E / (g * lj)
    s = math.sin(theta)
    n0 = _n_stick(s, e, k)
    if n0 <= 0.0:
        if n0 < rec[C.N_MIN]:
            rec[C.N_MIN] = n0
        return EV_LIFT_OFF, theta, thdot, t
    if abs(k * math.cos(theta) * (3.0 * s - 2.0 * e)) > mu * n0:
        return EV_SLIP, theta, thdot, t
    finite_mu = not math.isinf(mu)
    if finite_mu:
        p0, p1, p2, p3, p4 = slip_quartic(e, k, mu)
    else:
        p0 = p1 = p2 = p3 = p4 = 0.0
    n_lo, n_hi = n_roots(e, k)
    sample = traj.shape[0] > 0
    npc, th0, th1, th2, d0, d1 = swing_pieces(theta, swing_sense(theta, thdot), ta, tb, E, g, lj)
    for i in range(npc):
        a = th0 if i == 0 else th1
        b = th1 if i == 0 else th2
        dirn = d0 if i == 0 else d1
        s_a = math.sin(a)
        s_b = math.sin(b)
        ev = EV_LAND_B if dirn > 0 else EV_LAND_A
        th_ev = b
        s_ev = s_b
        if i < npc - 1:
            ev = -1  # no landing inside the swing: on to the next piece
        # ---------------------------------------------------------- guard lift_off: first root of N
        n_min = _n_min_range(min(a, b), max(a, b), e, k)
        if n_min <= 0.0:
            s_r = max(n_lo, s_a) if s_b >= s_a else min(n_hi, s_a)
            s_ev = min(max(s_r, min(s_a, s_b)), max(s_a, s_b))
            th_ev = theta_on_piece(s_ev, a, b)
            ev = EV_LIFT_OFF
        # ---------------------------------------------------------- guard slip: first root of μ²N² − F²
        if finite_mu:
            s_sl = first_quartic_root(s_a, s_ev, p0, p1, p2, p3, p4)
            if not math.isnan(s_sl) and (ev != EV_LIFT_OFF or s_sl != s_ev):
                s_ev = s_sl
                th_ev = theta_on_piece(s_sl, a, b)
                ev = EV_SLIP
        # ---------------------------------------------------------- records and time up to th_ev
        gn = 0.0 if ev == EV_LIFT_OFF else _n_min_range(min(a, th_ev), max(a, th_ev), e, k)
        if gn < rec[C.N_MIN]:
            rec[C.N_MIN] = gn
        _record_friction_ratio(s_a, s_ev, e, k, rec)
        dt = swing_time(a, th_ev, e, c)
        if sample:
            _sample_piece(a, th_ev, t, t + dt, e, c, px, h, lj, phi_off, traj, ts)
        t += dt
        if ev >= 0:
            w2 = 2.0 * (E - g * lj * math.sin(th_ev)) / I
            w_ev = math.sqrt(w2) if w2 > 0.0 else 0.0
            if sample:
                put_pivot(traj, ts, t, px, h, lj, th_ev, phi_off)
            return ev, th_ev, (w_ev if dirn > 0 else -w_ev), t
    return EV_LAND_A, ta, 0.0, t  # not reached: the last piece ends in a landing

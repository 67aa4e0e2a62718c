"""Mode PIVOT_STICK of model "rigid_body": one vertex A fixed on the line, guards land / lift_off / slip.

The part is a compound pendulum about A (as :mod:`~throwmap.kernels.roll`):
I θ̈ = −g ℓ cos θ with θ the angle of A→CM, ℓ = |A − CM|, I = ρ² + ℓ², and the
energy E = ½ I θ̇² + g ℓ sin θ is conserved. With s = sin θ, k = ℓ²/I and
e = E/(g ℓ) the contact forces, in units of m g, are

    N = 1 − k + 3k s² − 2k e s,     F = k cos θ (3s − 2e)   (F along +x).

Two implementations of the phase, with one signature: :func:`pivot_stick`
integrates with RK4 and locates guards by bisection (the original method, kept as
the reference); :func:`~throwmap.kernels.rigid_body.stick_exact.pivot_stick_exact`
follows the swing in closed form (the default).
"""

import math

from numba import njit

from .. import codes as C
from .modes import DTH, EV_LAND_A, EV_LAND_B, EV_LIFT_OFF, EV_SLIP, EV_STEP_CAP, HALF_PI, N_BISECT
from .trajectory import _put


@njit(cache=True)
def _n_stick(s, e, k):
    """Normal force while sticking, in units of m g (roll.py)."""
    return 1.0 - k + 3.0 * k * s * s - 2.0 * k * e * s


@njit(cache=True)
def _n_min_range(th_lo, th_hi, e, k):
    """Exact minimum of N over θ ∈ [th_lo, th_hi] ⊂ (0, π) at normalised energy e."""
    s1 = math.sin(th_lo)
    s2 = math.sin(th_hi)
    s_lo = min(s1, s2)
    s_hi = 1.0 if (th_lo <= HALF_PI <= th_hi) else max(s1, s2)
    s_star = min(max(e / 3.0, s_lo), s_hi)
    return _n_stick(s_star, e, k)


@njit(cache=True)
def _rk4_pend(th, w, dt, c):
    k1t = w
    k1w = -c * math.cos(th)
    k2t = w + 0.5 * dt * k1w
    k2w = -c * math.cos(th + 0.5 * dt * k1t)
    k3t = w + 0.5 * dt * k2w
    k3w = -c * math.cos(th + 0.5 * dt * k2t)
    k4t = w + dt * k3w
    k4w = -c * math.cos(th + dt * k3t)
    return (th + dt * (k1t + 2.0 * k2t + 2.0 * k3t + k4t) / 6.0,
            w + dt * (k1w + 2.0 * k2w + 2.0 * k3w + k4w) / 6.0)


@njit(cache=True)
def _stick_guards(th0, w0, th1, w1, ta, tb, e, k, mu):
    """Smallest guard value at the end of a (sub)step and which guard it is."""
    gmin = th1 - ta
    which = EV_LAND_A
    gb = tb - th1
    if gb < gmin:
        gmin = gb
        which = EV_LAND_B
    lo = min(th0, th1)
    hi = max(th0, th1)
    if w0 * w1 < 0.0:  # turned back inside the step: the turning angle is swept too
        st = min(e, 1.0)
        tt = math.asin(st) if math.cos(th0) > 0.0 else math.pi - math.asin(st)
        lo = min(lo, tt)
        hi = max(hi, tt)
    gn = _n_min_range(lo, hi, e, k)
    if gn < gmin:
        gmin = gn
        which = EV_LIFT_OFF
    if not math.isinf(mu):
        s = math.sin(th1)
        nf = _n_stick(s, e, k)
        f = k * math.cos(th1) * (3.0 * s - 2.0 * e)
        gs = mu * nf - abs(f)
        if gs < gmin:
            gmin = gs
            which = EV_SLIP
    return gmin, which


@njit(cache=True)
def pivot_stick(theta, thdot, ta, tb, lj, I, g, mu, t, max_steps, px, h, phi_off, traj, ts, rec):
    """Mode PIVOT_STICK on a vertex at (px, h) from (θ, θ̇) until a guard fires.

    Guards ``land`` (θ = θa or θb), ``lift_off`` (N = 0, exact), ``slip``
    (|F| = μN). Energy E = ½ I θ̇² + g ℓ sin θ is conserved; at the event θ̇ is
    recomputed from E. Updates N_MIN, MU_MAX in ``rec`` and the trajectory.
    Returns ``(event, θ, θ̇, t)``.
    """
    c = g * lj / I
    k = lj * lj / I
    E = 0.5 * I * thdot * thdot + g * lj * math.sin(theta)
    e = E / (g * lj)
    om = math.sqrt(c)
    s = math.sin(theta)
    n0 = _n_stick(s, e, k)
    f0 = k * math.cos(theta) * (3.0 * s - 2.0 * e)
    if n0 <= 0.0:
        if n0 < rec[C.N_MIN]:
            rec[C.N_MIN] = n0
        return EV_LIFT_OFF, theta, thdot, t
    if abs(f0) > mu * n0:
        return EV_SLIP, theta, thdot, t
    sample = traj.shape[0] > 0
    for _ in range(max_steps):
        dt = DTH / (abs(thdot) + om)
        th1, w1 = _rk4_pend(theta, thdot, dt, c)
        gm, which = _stick_guards(theta, thdot, th1, w1, ta, tb, e, k, mu)
        if gm > 0.0:
            if sample:
                while ts[1] <= t + dt:
                    thq, _w = _rk4_pend(theta, thdot, ts[1] - t, c)
                    _put(traj, ts, ts[1], px + lj * math.cos(thq), h + lj * math.sin(thq), thq + phi_off)
                    ts[1] += ts[2]
            gn = _n_min_range(min(theta, th1), max(theta, th1), e, k)
            if gn < rec[C.N_MIN]:
                rec[C.N_MIN] = gn
            s1 = math.sin(th1)
            nf = _n_stick(s1, e, k)
            if nf > 0.0:
                r = abs(k * math.cos(th1) * (3.0 * s1 - 2.0 * e)) / nf
                if r > rec[C.MU_MAX]:
                    rec[C.MU_MAX] = r
            theta = th1
            thdot = w1
            t += dt
            continue
        # locate the first guard in (0, dt] by bisection on the RK4 step length
        lo = 0.0
        hi = dt
        for _ in range(N_BISECT):
            mid = 0.5 * (lo + hi)
            thm, wm = _rk4_pend(theta, thdot, mid, c)
            gmid, wh = _stick_guards(theta, thdot, thm, wm, ta, tb, e, k, mu)
            if gmid <= 0.0:
                hi = mid
                which = wh
            else:
                lo = mid
            if hi - lo <= 1e-16 * (t + hi):
                break
        th1, w1 = _rk4_pend(theta, thdot, hi, c)
        gm, which = _stick_guards(theta, thdot, th1, w1, ta, tb, e, k, mu)
        if sample:
            while ts[1] <= t + hi:
                thq, _w = _rk4_pend(theta, thdot, ts[1] - t, c)
                _put(traj, ts, ts[1], px + lj * math.cos(thq), h + lj * math.sin(thq), thq + phi_off)
                ts[1] += ts[2]
        gn = _n_min_range(min(theta, th1), max(theta, th1), e, k)
        t += hi
        sgn = 1.0 if w1 >= 0.0 else -1.0
        if which == EV_LAND_A:
            th1 = ta
            sgn = -1.0
        elif which == EV_LAND_B:
            th1 = tb
            sgn = 1.0
        elif which == EV_LIFT_OFF:
            # exact: the root of N(s) = 0 nearest the located angle
            disc = e * e - 3.0 * (1.0 - k) / k
            if disc < 0.0:
                disc = 0.0
            s_loc = math.sin(th1)
            r1 = (e - math.sqrt(disc)) / 3.0
            r2 = (e + math.sqrt(disc)) / 3.0
            sr = r1 if abs(r1 - s_loc) <= abs(r2 - s_loc) else r2
            if sr > 1.0:
                sr = 1.0
            if sr > 0.0 and abs(sr - s_loc) < 1e-6:
                th1 = math.asin(sr) if math.cos(th1) > 0.0 else math.pi - math.asin(sr)
            gn = 0.0
        if gn < rec[C.N_MIN]:
            rec[C.N_MIN] = gn
        w2 = 2.0 * (E - g * lj * math.sin(th1)) / I
        w1 = sgn * (math.sqrt(w2) if w2 > 0.0 else 0.0)
        if traj.shape[0] > 0:
            _put(traj, ts, t, px + lj * math.cos(th1), h + lj * math.sin(th1), th1 + phi_off)
        return which, th1, w1, t
    return EV_STEP_CAP, theta, thdot, t


@njit(cache=True)
def stick_forces(theta, thdot, lj, I, g, alpha=0.0):
    """Normal force N and friction F (units m g, F along +x) while sticking at (θ, θ̇).

    On an arm at rest angle ``alpha`` (rad, CCW +; draft Sec. VI) the pendulum is the
    horizontal one in ψ = θ + α (gravity (−g sin α, −g cos α) in the arm frame), whose
    contact force (F_w, N_w) in the gravity-aligned frame is given by the formulas above
    with s = sin ψ; the arm-frame components are N = cos α N_w − sin α F_w and
    F = cos α F_w + sin α N_w (:func:`tilted_forces`).
    """
    if alpha != 0.0:
        k = lj * lj / I
        psi = theta + alpha
        e = (0.5 * I * thdot * thdot + g * lj * math.sin(psi)) / (g * lj)
        s = math.sin(psi)
        return tilted_forces(s, math.cos(psi), e, k, math.cos(alpha), math.sin(alpha))
    k = lj * lj / I
    e = (0.5 * I * thdot * thdot + g * lj * math.sin(theta)) / (g * lj)
    s = math.sin(theta)
    return _n_stick(s, e, k), k * math.cos(theta) * (3.0 * s - 2.0 * e)


@njit(cache=True, inline="always")
def tilted_forces(s, c, e, k, ca, sa):
    """Arm-frame contact force ``(N, F)`` (units m g) of a sticking pivot at ψ = θ + α with sin ψ = s, cos ψ = c.

    (F_w, N_w) = (k c (3s − 2e), 1 − k + 3k s² − 2k e s) is the force in the frame of
    gravity (the horizontal-arm formulas in ψ); rotated by −α into the arm frame:
    N = cos α N_w − sin α F_w, F = cos α F_w + sin α N_w.
    """
    nw = _n_stick(s, e, k)
    fw = k * c * (3.0 * s - 2.0 * e)
    return ca * nw - sa * fw, ca * fw + sa * nw

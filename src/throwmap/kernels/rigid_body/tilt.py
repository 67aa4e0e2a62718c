"""Model "rigid_body" on an arm resting at angle α (draft Sec. VI: the tilted arm).

Frame and gravity
-----------------
Every kernel works in the ARM frame: x along the arm from the joint, y normal to it,
the arm line y = h. The arm rests at α (rad, counter-clockwise positive, |α| < π/2)
and the impulse throw gives the part the velocity ω × r of the arm point under its
CM while the arm itself stays put (as :class:`throwmap.system.motion.ImpulseThrow`),
so the release (Eq. 1) is unchanged and only gravity changes: in the arm frame it is

    g⃗ = (−g sin α, −g cos α) = (−g_t, −g_n),

and the potential per unit mass is U = g_n (y − h) + g_t x (zero at the joint on the
arm line). Flight: the normal motion (the first-contact search) sees g_n only, the CM's
x gets −½ g_t t². α = 0 runs the horizontal code unchanged, bit for bit.

Pivoting
--------
About a fixed vertex with θ the angle of pivot→CM in the arm frame, U = g ℓ sin(θ + α):
the compound pendulum of :mod:`~throwmap.kernels.roll` in ψ = θ + α (the angle in
the frame of gravity). Its path, turning points and time (:mod:`.swing`) are those of
the horizontal arm in ψ, with the landing angles shifted to θa + α, θb + α. Its
contact force is the horizontal one in ψ, rotated into the arm frame
(:func:`~.stick.tilted_forces`): N = cos α N_w − sin α F_w, F = cos α F_w + sin α N_w.
The guards ``lift_off`` (N = 0) and ``slip`` (F = ±μN) are each p N_w + q F_w = 0, and
since F_w = ± k √(1 − s²)(3s − 2e) on a piece of monotone s = sin ψ, each one's roots
are among the roots of the quartic p² N_w² − q² F_w² (:func:`_lin_quartic`): all roots
of the three quartics on the piece are isolated exactly (monotone between the roots of
the derivative, as :func:`~.swing.first_quartic_root`; those are breakpoints too, so a
double root is not lost), and between consecutive breakpoints the
contact state is feasible or not throughout, decided at the midpoint
(:func:`first_exit`). The first infeasible interval starts at the event. (A guard
function that only touches zero without changing sign is not an event, as for α = 0.)

Resting flat
------------
Flat on side k (CM at height d_k above the line, support vertices at u_L ≤ u_R from
the CM along the arm) the part is statically stable against tipping iff the line of
gravity through the CM meets the support segment inside: u_L < −d_k tan α < u_R (the
``stable`` table the model passes for α; :func:`tilted_stable`); else it tips from rest
about the vertex its CM overhangs (:func:`tip_vertex`). Flat slides and rests on the
tilted arm: :func:`~.flat.settle`.
"""

import math

import numpy as np
from numba import njit

from .. import codes as C
from .modes import EV_LAND_A, EV_LAND_B, EV_LIFT_OFF, EV_SLIP, HALF_PI, N_ARC
from .stick import tilted_forces
from .swing import _dpoly_roots, _poly4, swing_pieces, swing_time, theta_on_piece
from ..roll import swing_sense
from .trajectory import _put


@njit(cache=True)
def tilted_stable(d, uL, uR, alpha):
    """Sides statically stable on an arm at rest angle ``alpha`` (rad): u_L < −d tan α < u_R (boolean array).

    The vertical through the CM (at height d above the side, m) meets the arm at
    −d tan α from the CM along the arm; the side stands iff that point lies strictly
    between the support vertices. α = 0: u_L < 0 < u_R.
    """
    n = d.shape[0]
    out = np.empty(n, dtype=np.bool_)
    ta = math.tan(alpha)
    for k in range(n):
        p = -d[k] * ta
        out[k] = uL[k] < p < uR[k]
    return out


@njit(cache=True)
def tip_vertex(k, n, uL, d, alpha):
    """Whether an unstable side k tips over its LEFT support vertex w_{k+1} (True) or its right one w_k (False).

    The part tips about the support vertex its CM overhangs along gravity: the left
    one iff u_L ≥ −d tan α.
    """
    return uL[k] >= -d[k] * math.tan(alpha)


@njit(cache=True)
def _lin_quartic(e, k, p, q):
    """Coefficients (p0 … p4) of p² N_w(s)² − q² F_w(s)², F_w² = k² (1 − s²)(3s − 2e)²
    (as :func:`~.swing.slip_quartic`)."""
    a0 = 1.0 - k
    a1 = -2.0 * k * e
    a2 = 3.0 * k
    pp = p * p
    qq = q * q * k * k
    p0 = pp * a0 * a0 - qq * 4.0 * e * e
    p1 = pp * 2.0 * a0 * a1 + qq * 12.0 * e
    p2 = pp * (a1 * a1 + 2.0 * a0 * a2) - qq * (9.0 - 4.0 * e * e)
    p3 = pp * 2.0 * a1 * a2 - qq * 12.0 * e
    p4 = pp * a2 * a2 + qq * 9.0
    return p0, p1, p2, p3, p4


@njit(cache=True)
def _quartic_roots(lo, hi, p0, p1, p2, p3, p4, out, m):
    """Append to ``out`` (from index m) the breakpoints of the quartic in [lo, hi]; returns the new m.

    The quartic is monotone between consecutive roots of its derivative
    (:func:`~.swing._dpoly_roots`), which are appended too (a double root, where the
    squared guard only touches 0 while the guard itself changes sign — e.g. N = 0 as
    α → 0 — is one of them); each monotone piece with a sign change holds one root,
    found by bisection to rounding.
    """
    mc, r1, r2, r3 = _dpoly_roots(lo, hi, p1, p2, p3, p4)
    for i in range(mc):
        out[m] = r1 if i == 0 else (r2 if i == 1 else r3)
        m += 1
    u = lo
    pu = _poly4(u, p0, p1, p2, p3, p4)
    if pu == 0.0:
        out[m] = u
        m += 1
    for i in range(mc + 1):
        v = hi if i == mc else (r1 if i == 0 else (r2 if i == 1 else r3))
        pv = _poly4(v, p0, p1, p2, p3, p4)
        if pv == 0.0:
            out[m] = v
            m += 1
        elif (pu < 0.0 < pv) or (pv < 0.0 < pu):
            a = u
            b = v
            fa = pu
            for _ in range(200):
                mid = 0.5 * (a + b)
                if mid <= a or mid >= b:
                    break
                fm = _poly4(mid, p0, p1, p2, p3, p4)
                if (fm < 0.0) == (fa < 0.0):
                    a = mid
                    fa = fm
                else:
                    b = mid
            out[m] = 0.5 * (a + b)
            m += 1
        u = v
        pu = pv
    return m


@njit(cache=True)
def first_exit(s_a, s_b, sig_c, e, k, ca, sa, mu, foot=False):
    """First s from ``s_a`` towards ``s_b`` (a piece of monotone s = sin ψ, cos ψ of sign ``sig_c``) where the
    sticking contact stops being feasible (N > 0, |F| ≤ μN in the arm frame; at the wall's ``foot`` the wall
    holds any F < 0, so only F ≤ μN).

    Returns ``(s, event)``: EV_LIFT_OFF or EV_SLIP, or ``(nan, -1)`` if it stays feasible.
    Breakpoints: all roots on the piece of the quartics of the guards N = 0 and F = ±μN
    (:func:`_lin_quartic`); feasibility is constant between consecutive breakpoints
    and is tested at their midpoint.
    """
    if s_a == s_b:
        return math.nan, -1
    lo = min(s_a, s_b)
    hi = max(s_a, s_b)
    br = np.empty(32)
    p0, p1, p2, p3, p4 = _lin_quartic(e, k, ca, -sa)
    m = _quartic_roots(lo, hi, p0, p1, p2, p3, p4, br, 0)
    if not math.isinf(mu):
        p0, p1, p2, p3, p4 = _lin_quartic(e, k, mu * ca - sa, -mu * sa - ca)
        m = _quartic_roots(lo, hi, p0, p1, p2, p3, p4, br, m)
        p0, p1, p2, p3, p4 = _lin_quartic(e, k, mu * ca + sa, -mu * sa + ca)
        m = _quartic_roots(lo, hi, p0, p1, p2, p3, p4, br, m)
    pts = np.sort(br[:m])
    up = s_b > s_a
    prev = s_a
    for i in range(m + 1):
        if i == m:
            r = s_b
        else:
            r = pts[i] if up else pts[m - 1 - i]
        if (r <= prev) if up else (r >= prev):
            continue
        mid = 0.5 * (prev + r)
        c = 1.0 - mid * mid
        cps = sig_c * math.sqrt(max(c, 0.0))
        N, F = tilted_forces(mid, cps, e, k, ca, sa)
        if N <= 0.0:
            return prev, EV_LIFT_OFF
        if (F if foot else abs(F)) > mu * N:
            return prev, EV_SLIP
        prev = r
    return math.nan, -1


@njit(cache=True)
def _record_arc(s_a, s_b, sig_c, e, k, ca, sa, rec):
    """N_MIN and MU_MAX (arm frame) at N_ARC points equally spaced in s between s_a and s_b."""
    for i in range(N_ARC):
        s = s_a + (s_b - s_a) * i / (N_ARC - 1)
        c = 1.0 - s * s
        cps = sig_c * math.sqrt(max(c, 0.0))
        N, F = tilted_forces(s, cps, e, k, ca, sa)
        if N < rec[C.N_MIN]:
            rec[C.N_MIN] = N
        if N > 0.0:
            r = abs(F) / N
            if r > rec[C.MU_MAX]:
                rec[C.MU_MAX] = r


@njit(cache=True)
def _pivot_row(traj, ts, t, px, h, lj, psi, alpha, phi_off):
    """Row for a pose pivoting on (px, h) at ψ: CM = (px, h) + ℓ (cos θ, sin θ) with θ = ψ − α, φ = θ + phi_off."""
    th = psi - alpha
    _put(traj, ts, t, px + lj * math.cos(th), h + lj * math.sin(th), th + phi_off)


@njit(cache=True)
def _sample_piece(a, b, t0, t1, e, c, px, h, lj, alpha, phi_off, traj, ts):
    """Trajectory rows at the sample times in [t0, t1] of the piece ψ: a → b swept from time t0."""
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
        _pivot_row(traj, ts, ts[1], px, h, lj, 0.5 * (lo + hi), alpha, phi_off)
        ts[1] += ts[2]


@njit(cache=True)
def pivot_stick_tilted(theta, thdot, ta, tb, lj, I, g, mu, t, px, h, phi_off, traj, ts, rec, alpha, foot=False):
    """Mode PIVOT_STICK on a tilted arm (α ≠ 0), closed form: the swing in ψ = θ + α, guards as in the module docstring.

    Arguments as :func:`~.stick_exact.pivot_stick_exact` (θ, θa, θb in the arm frame,
    rad). Returns ``(event, θ, θ̇, t)`` with θ in the arm frame. ``foot``: the pivot is at the wall's foot
    (any α, 0 included), where the wall takes every friction force F < 0 (towards the wall's face is +x, so F < 0
    pushes the vertex back from it): ``slip`` only at F > μN.
    """
    ca = math.cos(alpha)
    sa = math.sin(alpha)
    psi = theta + alpha
    pa = ta + alpha
    pb = tb + alpha
    c = g * lj / I
    k = lj * lj / I
    E = 0.5 * I * thdot * thdot + g * lj * math.sin(psi)
    e = E / (g * lj)
    N0, F0 = tilted_forces(math.sin(psi), math.cos(psi), e, k, ca, sa)
    if N0 <= 0.0:
        if N0 < rec[C.N_MIN]:
            rec[C.N_MIN] = N0
        return EV_LIFT_OFF, theta, thdot, t
    if (F0 if foot else abs(F0)) > mu * N0:
        return EV_SLIP, theta, thdot, t
    sample = traj.shape[0] > 0
    npc, th0, th1, th2, d0, d1 = swing_pieces(psi, swing_sense(psi, thdot), pa, pb, E, g, lj)
    for i in range(npc):
        a = th0 if i == 0 else th1
        b = th1 if i == 0 else th2
        dirn = d0 if i == 0 else d1
        sig_c = 1.0 if 0.5 * (a + b) < HALF_PI else -1.0
        s_a = math.sin(a)
        s_b = math.sin(b)
        s_ev, ev = first_exit(s_a, s_b, sig_c, e, k, ca, sa, mu, foot)
        if ev < 0:
            th_ev = b
            s_ev = s_b
            if i == npc - 1:
                ev = EV_LAND_B if dirn > 0 else EV_LAND_A
        else:
            th_ev = theta_on_piece(s_ev, a, b)
        _record_arc(s_a, s_ev, sig_c, e, k, ca, sa, rec)
        if ev == EV_LIFT_OFF and rec[C.N_MIN] > 0.0:
            rec[C.N_MIN] = 0.0
        dt = swing_time(a, th_ev, e, c)
        if sample:
            _sample_piece(a, th_ev, t, t + dt, e, c, px, h, lj, alpha, phi_off, traj, ts)
        t += dt
        if ev >= 0:
            w2 = 2.0 * (E - g * lj * math.sin(th_ev)) / I
            w_ev = math.sqrt(w2) if w2 > 0.0 else 0.0
            if ev == EV_LAND_A:
                th_out = ta
            elif ev == EV_LAND_B:
                th_out = tb
            else:
                th_out = th_ev - alpha
            if sample:
                _pivot_row(traj, ts, t, px, h, lj, th_out + alpha, alpha, phi_off)
            return ev, th_out, (w_ev if dirn > 0 else -w_ev), t
    return EV_LAND_A, ta, 0.0, t  # not reached: the last piece ends in a landing


@njit(cache=True)
def arc_ok_tilted(psi_from, E, lj, I, g, mu, towards_peak, ca, sa):
    """:func:`~.landing.arc_ok` on a tilted arm: the sticking swing from ψ at energy E (J/kg, U = g ℓ sin ψ) up to
    its turning point keeps N > 0 and |F| ≤ μN (arm frame), checked at N_ARC points."""
    k = lj * lj / I
    e = E / (g * lj)
    st = min(e, 1.0)
    if towards_peak > 0:
        tt = math.asin(st) if psi_from < HALF_PI else HALF_PI
        if tt < psi_from:
            tt = psi_from
    else:
        tt = math.pi - math.asin(st) if psi_from > HALF_PI else HALF_PI
        if tt > psi_from:
            tt = psi_from
    lo = min(psi_from, tt)
    hi = max(psi_from, tt)
    for i in range(N_ARC):
        th = lo + (hi - lo) * i / (N_ARC - 1)
        N, F = tilted_forces(math.sin(th), math.cos(th), e, k, ca, sa)
        if N <= 0.0:
            return False
        if not math.isinf(mu) and abs(F) > mu * N:
            return False
    return True


@njit(cache=True)
def topple_barrier(th_A, th_B, lA, lB, g, alpha):
    """The lower of the two topple barriers (J/kg) of a part flat on a stable side of a tilted arm.

    About a support vertex at pivot angle θ (arm frame) the barrier is the rise of the CM
    to the top of its circle, g ℓ (1 − sin(θ + α)) (α = 0: g (ℓ − d)).
    """
    return min(g * lA * (1.0 - math.sin(th_A + alpha)), g * lB * (1.0 - math.sin(th_B + alpha)))


@njit(cache=True)
def rocking_rest_tilted(th_new, th_A, k_after, lA, lB, rho2, g, mu, land_dir, alpha):
    """Guard ``rocking_rest`` (Zeno) on a tilted arm: K below both topple barriers (:func:`topple_barrier`) and
    the next swings at that energy about B (from ``th_new``) and back about A (from ``th_A``) keep contact and
    stick (:func:`arc_ok_tilted`; their energies measured from each pivot)."""
    if not k_after < topple_barrier(th_A, th_new, lA, lB, g, alpha):
        return False
    ca = math.cos(alpha)
    sa = math.sin(alpha)
    pB = th_new + alpha
    pA = th_A + alpha
    if not arc_ok_tilted(pB, k_after + g * lB * math.sin(pB), lB, rho2 + lB * lB, g, mu, land_dir, ca, sa):
        return False
    return arc_ok_tilted(pA, k_after + g * lA * math.sin(pA), lA, rho2 + lA * lA, g, mu, -land_dir, ca, sa)

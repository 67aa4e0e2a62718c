"""Model "rigid_body": exact planar rigid-body dynamics of one polygon on the arm line.

Extends model "paper" (Sec. III, Eqs. 1–4; :mod:`~throwmap.kernels.paper`,
:mod:`~throwmap.kernels.roll`) by dropping its two contact assumptions: the
contact vertex may *lift off* (the normal force reaches zero, Sec. III-C's
"the part does not bounce" is no longer imposed) and it may *slip* (Coulomb
friction μ, Sec. III-C's "friction is high enough" is no longer imposed).
Unit mass, inertia ρ² about the CM, gravity −g ŷ, arm line y = h for
0 ≤ x ≤ length, plastic impacts (zero restitution).

Pose convention (as :mod:`throwmap.throws.trajectory`): world vertex_j = (x, y) + R(φ) w_j;
flat on side k, φ = β_k (mod 2π) and y = h + d_k.

Hybrid system
-------------
Modes

``FLIGHT``       ballistic motion (Eq. 1 from an arbitrary state).
``PIVOT_STICK``  one vertex A fixed on the line: compound pendulum
                 I_A θ̈ = −g ℓ_A cos θ (θ = angle of A→CM, I_A = ρ² + ℓ_A²), as roll.py.
``PIVOT_SLIDE``  one vertex A on the line, sliding with slip velocity v_A ≠ 0:
                 2 DOF (x_A, θ), friction −μ N sgn(v_A).
``FLAT_SLIDE``   a side flat on the line, sliding at deceleration μ g (closed form).
``REST``         terminal.

Guards (named as in the code, ``EV_*``)

``touch``        FLIGHT: the earliest time any vertex reaches y = h moving down
                 (:func:`first_contact_state`, the safe lower-bound stepping of
                 :func:`~throwmap.kernels.flight.first_contact` from any state).
``leave_arm``    a contact point at x ≤ 0 (BEHIND_JOINT) or x > length (OFF_END).
``land``         PIVOT_*: θ reaches θa (side j−1 flat) or θb (side j flat): the
                 second vertex B of that side touches (``EV_LAND_A``/``EV_LAND_B``).
``lift_off``     PIVOT_*: the normal force N reaches 0 (``EV_LIFT_OFF``). While
                 sticking, N/(m g) = 1 − k + 3k s² − 2k e s (s = sin θ, k = ℓ²/I,
                 e = E/(g ℓ)); the crossing is solved analytically in s.
``slip``         PIVOT_STICK: |F| = μ N, F/(m g) = k cos θ (3s − 2e) (``EV_SLIP``).
``stick``        PIVOT_SLIDE: the slip velocity reaches 0 (``EV_STICK``).
``painleve``     PIVOT_SLIDE: the normal-force equation's effective mass
                 D = 1 + ℓ² cos θ (cos θ + μσ sin θ)/ρ² reaches 0: no consistent
                 Coulomb solution (status INCONSISTENT).

Resets

``release``      rest on ``side`` at x0; CM velocity ω(−(h+d), x0), spin ω (Eq. 1).
``impact``       one vertex, plastic, Coulomb (:func:`coulomb_impact`): the no-slip
                 impulse of Eq. 4 if it lies in the friction cone (|J_t| ≤ μ J_n);
                 otherwise Routh's compression-only process in impulse space
                 (slide, slip may stop and stick or reverse, ends when the normal
                 velocity is 0). A no-slip impulse with J_n < 0 is counted in N_PULL.
``land_side``    B touches while A is on the line: first the impulse at B alone
                 (A free); accepted if A then moves up (lifts); otherwise both
                 vertices stop normal motion (v_y = ω = 0) and a friction impulse
                 ≤ μ J_n removes horizontal velocity; what remains slides the part
                 flat (FLAT_SLIDE) to rest. Then rest (stable side) or tip from rest
                 about the vertex the CM overhangs (unstable side), as roll.py.
``lift``         PIVOT_* → FLIGHT with the contact's velocity; the departed vertex is
                 excluded from ``touch`` for a window in which its exact 4th-order
                 Taylor lower bound (|G''''| ≤ ω⁴ℓ) stays positive.
``slip_start``   PIVOT_STICK → PIVOT_SLIDE; the sense σ is the one for which the
                 sliding dynamics is consistent (σ ẍ_A > 0, D > 0).
``stick_start``  PIVOT_SLIDE → PIVOT_STICK when static friction suffices, else
                 slide the other way.
``rocking_rest`` (Zeno, decided on purpose as roll.py): after a sticking landing on a
                 stable side with kinetic energy below both topple barriers, rest —
                 only if the next swings at that energy about both support vertices
                 keep N > 0 and |F| ≤ μN (checked at 16 points per arc).

Numerics and accuracy (plainly)
-------------------------------
* FLIGHT is closed form; ``touch`` cannot miss a crossing (lower-bound stepping)
  and is Newton-polished, as in model "paper".
* PIVOT_STICK and PIVOT_SLIDE are integrated with classical RK4, step
  Δt = DTH/(|θ̇| + Ω) (Ω = √(gℓ/I), DTH = 0.03 rad), global θ error ~1e-8 rad.
  Guards are checked at step ends and located by bisection on the RK4 step
  length (the RK4 step is the interpolant), to ~1e-15 of the step. In
  PIVOT_STICK the energy is exact: θ̇ at every event is recomputed from E, and the
  N guard uses the exact minimum of N over the angle range swept in the step,
  so a lift-off cannot be missed; the slip guard is sampled at step ends (an
  excursion of |F|/N above μ narrower than one step, ≤ 0.03 rad, can be missed).
* T_REST: when the Zeno rule decides rest, the (finite) remaining rocking time is
  not added: T_REST is the time of the deciding landing.
* FLAT_SLIDE assumes the part does not tip over its leading edge while it
  decelerates (not checked).

Trajectory output
-----------------
``traj`` (M, 4) receives rows (t, x_cm, y_cm, φ) every ``traj_dt`` s and at every
event; φ is continuous (not wrapped), the last row is the rest pose with
φ = β_k + 2π m. Rows not written are NaN: the number of samples is the number
of leading non-NaN rows (:func:`count_samples`). When M is too small, periodic
samples stop at M − 1 rows and the last row still receives the final pose.
M = 0 records nothing.
"""

import math

import numpy as np
from numba import njit, prange

from . import codes as C
from .impact import plastic_impact
from .roll import _theta_a, _theta_b

HALF_PI = 0.5 * math.pi
TWO_PI = 2.0 * math.pi

DTH = 0.03
"""Largest pivot-angle change of one RK4 step, rad (sets the integration accuracy)."""
N_BISECT = 56
"""Bisection steps locating a guard inside an RK4 step (≈ 1e-17 of the step)."""
N_ARC = 16
"""Points per arc at which the Zeno rule checks the friction demand."""
MU_SKID = 1e6
"""Friction coefficient standing in for μ = ∞ in PIVOT_SLIDE (the μ → ∞ limit, see Notes)."""

# guard / event codes returned by the contact phases
EV_NONE = 0
EV_LAND_A = 1  # theta reached theta_a: side j-1 flat
EV_LAND_B = 2  # theta reached theta_b: side j flat
EV_LIFT_OFF = 3  # normal force reached 0
EV_SLIP = 4  # |F| reached mu N while sticking
EV_STICK = 5  # slip velocity reached 0 while sliding
EV_BEHIND_JOINT = 6  # sliding contact reached x <= 0
EV_OFF_END = 7  # sliding contact passed x = length
EV_INCONSISTENT = 8  # Painlevé: effective mass D <= 0 while sliding
EV_STEP_CAP = 9  # max_iter integration steps without an event

# results of coulomb_impact
IMP_STICK = 0
IMP_SLIDE = 1
IMP_SEPARATE = 2
IMP_INCONSISTENT = -1

MODE_FLIGHT = 0
MODE_STICK = 1
MODE_SLIDE = 2
MODE_SELECT = 3  # a contact just began: choose stick / slide / flight (select_contact_mode)


# ============================================================================ trajectory samples
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
def _write_row(traj, ts, i, t, x, y, phi):
    traj[i, 0] = t
    traj[i, 1] = x
    traj[i, 2] = y
    traj[i, 3] = phi
    ts[0] = i + 1


@njit(cache=True)
def count_samples(traj):
    """Number of trajectory rows written (leading rows whose time is not NaN)."""
    for i in range(traj.shape[0]):
        if math.isnan(traj[i, 0]):
            return i
    return traj.shape[0]


# ============================================================================ reset: impact
@njit(cache=True)
def coulomb_impact(vx, vy, w, rx, ry, rho2, mu):
    """Plastic single-vertex impact with Coulomb friction (reset ``impact``).

    Contact frame t = x̂, n = ŷ; contact velocity u = (v_x − ω r_y, v_y + ω r_x);
    an impulse P at the contact changes it by K P with the inverse-inertia matrix
    K = [[1 + r_y²/ρ², −r_x r_y/ρ²], [−r_x r_y/ρ², 1 + r_x²/ρ²]] (unit mass).

    1. The no-slip impulse J = −K⁻¹u (Eq. 4). If J_n ≥ 0 and |J_t| ≤ μ J_n it is
       applied (sticking impact, computed by :func:`plastic_impact` exactly as model
       "paper").
    2. Otherwise Routh's process, compression only (zero Poisson restitution),
       parametrised by the normal impulse p: while sliding with sense σ,
       dP = (−μσ, 1) dp; when u_t reaches 0 the part sticks if |K_tn/K_tt| ≤ μ
       (dP = (−K_tn/K_tt, 1) dp), else slides with σ = sgn K_tn; it ends when u_n = 0.
       μ = ∞ is the limit: a purely tangential impulse until u_t = 0 or u_n = 0.
       If the normal velocity cannot be stopped (du_n/dp ≤ 0 while sliding) there is
       no consistent impulse (``IMP_INCONSISTENT``).

    ``(rx, ry)`` CM → contact vertex (m), ``rho2`` ρ² (m²).
    Returns ``(vx⁺, vy⁺, ω⁺, P_t, P_n, kind, jt0, jn0)``; kind is IMP_STICK,
    IMP_SLIDE (contact slides, u_n = 0), IMP_SEPARATE (u_n > 0, the vertex
    leaves) or IMP_INCONSISTENT; (jt0, jn0) is the no-slip impulse of step 1.
    """
    ut = vx - w * ry
    un = vy + w * rx
    Ktt = 1.0 + ry * ry / rho2
    Knn = 1.0 + rx * rx / rho2
    Ktn = -rx * ry / rho2
    det = Ktt * Knn - Ktn * Ktn
    jt0 = -(Knn * ut - Ktn * un) / det
    jn0 = -(-Ktn * ut + Ktt * un) / det
    if un >= 0.0:
        return vx, vy, w, 0.0, 0.0, IMP_SEPARATE, jt0, jn0
    if jn0 >= 0.0 and abs(jt0) <= mu * jn0:
        vxp, vyp, wp = plastic_impact(vx, vy, w, rx, ry, rho2)
        return vxp, vyp, wp, vxp - vx, vyp - vy, IMP_STICK, jt0, jn0
    scale = abs(ut) + abs(un)
    Pt = 0.0
    Pn = 0.0
    kind = IMP_SLIDE
    for _ in range(4):
        if un >= 0.0:
            break
        if abs(ut) <= 1e-14 * scale:
            ut = 0.0
            lam = -Ktn / Ktt
            if abs(lam) <= mu:
                dp = -un / (Knn + Ktn * lam)
                Pt += lam * dp
                Pn += dp
                un = 0.0
                kind = IMP_STICK
                break
            sig = 1.0 if Ktn > 0.0 else -1.0
        else:
            sig = 1.0 if ut > 0.0 else -1.0
        if math.isinf(mu):
            # limit mu -> inf: tangential impulse only, until u_t = 0 or u_n = 0
            pt_stop = -ut / Ktt
            un_stop = un + Ktn * pt_stop
            if un_stop >= 0.0 and Ktn != 0.0:
                pt = -un / Ktn
                Pt += pt
                ut += Ktt * pt
                un = 0.0
                kind = IMP_SLIDE if ut != 0.0 else IMP_STICK
                break
            Pt += pt_stop
            ut = 0.0
            un = un_stop
            continue
        at = Ktn - mu * sig * Ktt  # du_t/dp while sliding with sense sig
        an = Knn - mu * sig * Ktn  # du_n/dp
        p_n = -un / an if an > 0.0 else math.inf
        p_t = -ut / at if (sig * at < 0.0 and ut != 0.0) else math.inf
        if math.isinf(p_n) and math.isinf(p_t):
            return vx, vy, w, 0.0, 0.0, IMP_INCONSISTENT, jt0, jn0
        if p_n <= p_t:
            Pt += -mu * sig * p_n
            Pn += p_n
            ut += at * p_n
            un = 0.0
            kind = IMP_SLIDE
            break
        Pt += -mu * sig * p_t
        Pn += p_t
        un += an * p_t
        ut = 0.0
    if un > 0.0:
        kind = IMP_SEPARATE
    vxp = vx + Pt
    vyp = vy + Pn
    wp = w + (rx * Pn - ry * Pt) / rho2
    return vxp, vyp, wp, Pt, Pn, kind, jt0, jn0


@njit(cache=True)
def _record_impact(pt, pn, k_before, k_after, rec):
    rec[C.N_IMPACTS] += 1.0
    if pn > 0.0:
        r = abs(pt) / pn
        if r > rec[C.MU_MAX]:
            rec[C.MU_MAX] = r
    elif pt != 0.0:
        rec[C.MU_MAX] = math.inf
    gain = k_after - k_before
    if gain > rec[C.K_MAX_IMPACT_GAIN]:
        rec[C.K_MAX_IMPACT_GAIN] = gain


# ============================================================================ guard: touch (flight)
@njit(cache=True)
def _gap_state(t, j, c0, ru, rv, vy, w, g):
    """Gap of vertex j above the line at flight time t (cancellation-free) and its rate."""
    wt = w * t
    hs = math.sin(0.5 * wt)
    s = math.sin(wt)
    c = math.cos(wt)
    gap = c0[j] + (vy + w * ru[j]) * t - 0.5 * g * t * t - 2.0 * rv[j] * hs * hs + ru[j] * (s - wt)
    dg = vy - g * t + w * (ru[j] * c - rv[j] * s)
    return gap, dg


@njit(cache=True)
def first_contact_state(c0, ru, rv, vy, w, g, ell, excl_j, excl_t, tol, max_iter):
    """Guard ``touch``: earliest t ≥ 0 at which a vertex reaches y = h, from any flight state.

    Vertex j's gap is G_j(t) = c0_j + (v_y + ω ru_j) t − ½ g t² − 2 rv_j sin²(ωt/2)
    + ru_j (sin ωt − ωt), with (ru_j, rv_j) = R(φ0) w_j and c0_j = y0 − h + rv_j its gap
    at t = 0 (exactly 0 for a vertex on the line). As in
    :func:`~throwmap.kernels.flight.first_contact`, G_j'' ≥ −(g + ω² ℓ_j) makes each
    step the smallest positive root of a quadratic lower bound, so no crossing is
    missed; a Newton polish removes the stopping error. Vertex ``excl_j`` (one that
    just left the line) is known to stay above it for t < ``excl_t``.
    Returns ``(t, j)``, j = −1 when ``max_iter`` steps did not reach contact.
    """
    n = ru.shape[0]
    t = 0.0
    for _ in range(max_iter):
        wt = w * t
        s = math.sin(wt)
        c = math.cos(wt)
        hs = math.sin(0.5 * wt)
        cm1 = -2.0 * hs * hs
        smw = s - wt
        base = -0.5 * g * t * t
        dbase = vy - g * t
        step = math.inf
        jmin = -1
        gmin = math.inf
        for j in range(n):
            gap = c0[j] + (vy + w * ru[j]) * t + base + rv[j] * cm1 + ru[j] * smw
            dg = dbase + w * (ru[j] * c - rv[j] * s)
            if j == excl_j and t < excl_t:
                sj = excl_t - t
                gp = gap if gap > 0.0 else 0.0
                M = g + w * w * ell[j]
                disc = math.sqrt(dg * dg + 2.0 * M * gp)
                if gp > 0.0 or dg > 0.0:
                    sq = (dg + disc) / M if dg >= 0.0 else 2.0 * gp / (disc - dg)
                    if sq > sj:
                        sj = sq
                if sj < step:
                    step = sj
                continue
            if gap <= tol and (t > 0.0 or dg <= 0.0):
                if gap < gmin:
                    gmin = gap
                    jmin = j
                continue
            gp = gap if gap > 0.0 else 0.0
            M = g + w * w * ell[j]
            disc = math.sqrt(dg * dg + 2.0 * M * gp)
            if dg >= 0.0:
                sj = (dg + disc) / M
            else:
                sj = 2.0 * gp / (disc - dg)
            if sj < step:
                step = sj
        if jmin >= 0:
            if t > 0.0 and gmin > 0.0:
                for _ in range(3):
                    gap, dg = _gap_state(t, jmin, c0, ru, rv, vy, w, g)
                    if dg >= 0.0:
                        break
                    st = -gap / dg
                    if abs(st) > 0.05 * t:
                        break
                    t += st
                    if abs(st) <= 1e-15 * t:
                        break
            return t, jmin
        t += step
    return t, -1


@njit(cache=True)
def departure_window(un, rx, ry, w, g, lj):
    """Time for which a vertex that just left the line (gap 0, rate un ≥ 0) stays above it.

    Exact Taylor bound of its gap G(s) ≥ G' s + ½G'' s² + G''' s³/6 − ω⁴ℓ s⁴/24
    with G' = un, G'' = −g − ω² r_y, G''' = −ω³ r_x; returns 0.9 × the positive
    root of ½G'' + G''' s/6 − ω⁴ℓ s²/24 (G' ≥ 0 only helps), or 0 if none.
    """
    g2 = -g - w * w * ry
    g3 = -w * w * w * rx
    if g2 < 0.0 and g2 > -1e-9 * g:
        g2 = 0.0
    if g2 < 0.0:
        return 0.0
    a = w * w * w * w * lj / 24.0
    b = g3 / 6.0
    c = 0.5 * g2
    if a <= 0.0:
        if b > 0.0 or c > 0.0:
            return 1.0
        return 0.0
    disc = b * b + 4.0 * a * c
    root = (b + math.sqrt(disc)) / (2.0 * a)
    if root <= 0.0:
        return 0.0
    return 0.9 * root


# ============================================================================ PIVOT_STICK
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
def stick_forces(theta, thdot, lj, I, g):
    """Normal force N and friction F (units m g, F along +x) while sticking at (θ, θ̇)."""
    k = lj * lj / I
    e = (0.5 * I * thdot * thdot + g * lj * math.sin(theta)) / (g * lj)
    s = math.sin(theta)
    return _n_stick(s, e, k), k * math.cos(theta) * (3.0 * s - 2.0 * e)


# ============================================================================ PIVOT_SLIDE
@njit(cache=True)
def slide_rhs(th, w, lj, rho2, g, musig):
    """PIVOT_SLIDE dynamics with friction −μσN (musig = μσ).

    With c = cos θ, s = sin θ and A → CM = ℓ(c, s):
    ÿ_A = 0 gives N D = g − ℓ s θ̇², D = 1 + ℓ² c (c + μσ s)/ρ²;
    ρ² θ̈ = −ℓ N (c + μσ s);  ẍ_A = −μσ N + ℓ (s θ̈ + c θ̇²).
    Returns ``(θ̈, ẍ_A, N, D)`` (N per unit mass, m/s²).
    """
    c = math.cos(th)
    s = math.sin(th)
    q = c + musig * s
    D = 1.0 + lj * lj * c * q / rho2
    N = (g - lj * s * w * w) / D
    thdd = -lj * q * N / rho2
    xdd = -musig * N + lj * (s * thdd + c * w * w)
    return thdd, xdd, N, D


@njit(cache=True)
def _rk4_slide(xa, th, va, w, dt, lj, rho2, g, musig):
    a1, b1, _n, _d = slide_rhs(th, w, lj, rho2, g, musig)
    th2 = th + 0.5 * dt * w
    w2 = w + 0.5 * dt * a1
    a2, b2, _n, _d = slide_rhs(th2, w2, lj, rho2, g, musig)
    th3 = th + 0.5 * dt * w2
    w3 = w + 0.5 * dt * a2
    a3, b3, _n, _d = slide_rhs(th3, w3, lj, rho2, g, musig)
    th4 = th + dt * w3
    w4 = w + dt * a3
    a4, b4, _n, _d = slide_rhs(th4, w4, lj, rho2, g, musig)
    va2 = va + 0.5 * dt * b1
    va3 = va + 0.5 * dt * b2
    va4 = va + dt * b3
    xa1 = xa + dt * (va + 2.0 * va2 + 2.0 * va3 + va4) / 6.0
    th1 = th + dt * (w + 2.0 * w2 + 2.0 * w3 + w4) / 6.0
    va1 = va + dt * (b1 + 2.0 * b2 + 2.0 * b3 + b4) / 6.0
    w1 = w + dt * (a1 + 2.0 * a2 + 2.0 * a3 + a4) / 6.0
    return xa1, th1, va1, w1


@njit(cache=True)
def _slide_guards(xa, th, va, w, sig, ta, tb, lj, rho2, g, musig, length):
    _a, _b, N, D = slide_rhs(th, w, lj, rho2, g, musig)
    gmin = sig * va
    which = EV_STICK
    if th - ta < gmin:
        gmin = th - ta
        which = EV_LAND_A
    if tb - th < gmin:
        gmin = tb - th
        which = EV_LAND_B
    if D <= 0.0:
        return -1.0, EV_INCONSISTENT
    if N / g < gmin:
        gmin = N / g
        which = EV_LIFT_OFF
    if xa < gmin:
        gmin = xa
        which = EV_BEHIND_JOINT
    if length - xa < gmin:
        gmin = length - xa
        which = EV_OFF_END
    return gmin, which


@njit(cache=True)
def pivot_slide(xa, theta, va, thdot, sig, ta, tb, lj, rho2, g, mu, length, t, max_steps, h, phi_off, traj, ts,
                rec):
    """Mode PIVOT_SLIDE on vertex A at (x_A, h), slip sense σ = sgn v_A, until a guard fires.

    Guards ``stick`` (σ v_A = 0), ``land`` (θa, θb), ``lift_off`` (N = 0),
    ``painleve`` (D ≤ 0), ``leave_arm`` (x_A ≤ 0 or > length). RK4 with bisection
    event location. Updates N_MIN, MU_MAX, SLIP_DISTANCE. Returns
    ``(event, x_A, θ, v_A, θ̇, t)``.
    """
    musig = mu * sig
    om = math.sqrt(g / lj)
    x_start = xa
    if mu > rec[C.MU_MAX]:
        rec[C.MU_MAX] = mu
    sample = traj.shape[0] > 0
    for _ in range(max_steps):
        dt = DTH / (abs(thdot) + om)
        x1, th1, v1, w1 = _rk4_slide(xa, theta, va, thdot, dt, lj, rho2, g, musig)
        gm, which = _slide_guards(x1, th1, v1, w1, sig, ta, tb, lj, rho2, g, musig, length)
        step = dt
        if gm <= 0.0:
            lo = 0.0
            hi = dt
            for _ in range(N_BISECT):
                mid = 0.5 * (lo + hi)
                xm, thm, vm, wm = _rk4_slide(xa, theta, va, thdot, mid, lj, rho2, g, musig)
                gmid, wh = _slide_guards(xm, thm, vm, wm, sig, ta, tb, lj, rho2, g, musig, length)
                if gmid <= 0.0:
                    hi = mid
                else:
                    lo = mid
                if hi - lo <= 1e-16 * (t + hi):
                    break
            step = hi
            x1, th1, v1, w1 = _rk4_slide(xa, theta, va, thdot, hi, lj, rho2, g, musig)
            gm, which = _slide_guards(x1, th1, v1, w1, sig, ta, tb, lj, rho2, g, musig, length)
        if sample:
            while ts[1] <= t + step:
                xq, thq, _v, _w = _rk4_slide(xa, theta, va, thdot, ts[1] - t, lj, rho2, g, musig)
                _put(traj, ts, ts[1], xq + lj * math.cos(thq), h + lj * math.sin(thq), thq + phi_off)
                ts[1] += ts[2]
        _a, _b, N, _D = slide_rhs(th1, w1, lj, rho2, g, musig)
        if N / g < rec[C.N_MIN]:
            rec[C.N_MIN] = N / g
        xa, theta, va, thdot = x1, th1, v1, w1
        t += step
        if gm <= 0.0:
            if which == EV_STICK:
                va = 0.0
            elif which == EV_LAND_A:
                theta = ta
            elif which == EV_LAND_B:
                theta = tb
            elif which == EV_LIFT_OFF:
                if rec[C.N_MIN] > 0.0:
                    rec[C.N_MIN] = 0.0
            rec[C.SLIP_DISTANCE] += abs(xa - x_start)
            if sample:
                _put(traj, ts, t, xa + lj * math.cos(theta), h + lj * math.sin(theta), theta + phi_off)
            return which, xa, theta, va, thdot, t
    rec[C.SLIP_DISTANCE] += abs(xa - x_start)
    return EV_STEP_CAP, xa, theta, va, thdot, t


@njit(cache=True)
def slide_sense(theta, thdot, va, f_stick, lj, rho2, g, mu):
    """Reset ``slip_start``: the slip sense σ (±1) of a consistent sliding motion, 0 if none.

    v_A ≠ 0 fixes σ = sgn v_A (needs D > 0). From v_A = 0 the slip starts against
    the friction that sticking would need (σ = −sgn F); it must satisfy σ ẍ_A > 0
    and D > 0, else the other sense is tried.
    """
    if va != 0.0:
        sig = 1.0 if va > 0.0 else -1.0
        _a, _x, _n, D = slide_rhs(theta, thdot, lj, rho2, g, mu * sig)
        return sig if D > 0.0 else 0.0
    sig = -1.0 if f_stick > 0.0 else 1.0
    for _ in range(2):
        _a, xdd, _n, D = slide_rhs(theta, thdot, lj, rho2, g, mu * sig)
        if D > 0.0 and sig * xdd > 0.0:
            return sig
        sig = -sig
    return 0.0


@njit(cache=True)
def select_contact_mode(theta, thdot, va, lj, rho2, g, mu, mu_s, from_slip):
    """Which mode continues from a one-vertex contact state (the single-contact Coulomb LCP).

    In order: ``PIVOT_STICK`` (v_A = 0, N > 0, |F| ≤ μN; not offered right after a
    ``slip``/``lift_off`` guard fired); ``FLIGHT`` if the free motion separates
    (:func:`departure_window` > 0); ``PIVOT_SLIDE`` with a consistent sense
    (D > 0, N > 0, and σ ẍ_A > 0 when starting from v_A = 0 — right after ``slip``
    ẍ_A = 0 exactly, so σ = −sgn F is taken); else no consistent motion.
    ``mu_s`` is the coefficient used for sliding (μ, or MU_SKID for μ = ∞).
    Returns ``(mode, σ)`` with mode −1 for INCONSISTENT.
    """
    I = rho2 + lj * lj
    c = math.cos(theta)
    s = math.sin(theta)
    if va != 0.0:
        sig = 1.0 if va > 0.0 else -1.0
        _a, _x, N, D = slide_rhs(theta, thdot, lj, rho2, g, mu_s * sig)
        if D > 0.0 and N > 0.0:
            return MODE_SLIDE, sig
        if departure_window(0.0, -lj * c, -lj * s, thdot, g, lj) > 0.0:
            return MODE_FLIGHT, 0.0
        return -1, 0.0
    nf, ff = stick_forces(theta, thdot, lj, I, g)
    if not from_slip and nf > 0.0 and abs(ff) <= mu * nf:
        return MODE_STICK, 0.0
    if departure_window(0.0, -lj * c, -lj * s, thdot, g, lj) > 0.0:
        return MODE_FLIGHT, 0.0
    sig = -1.0 if ff > 0.0 else 1.0
    for _ in range(2):
        _a, xdd, N, D = slide_rhs(theta, thdot, lj, rho2, g, mu_s * sig)
        if D > 0.0 and N > 0.0 and (sig * xdd > 0.0 or from_slip):
            return MODE_SLIDE, sig
        if from_slip:
            break
        sig = -sig
    if from_slip:
        sig = -sig
        _a, xdd, N, D = slide_rhs(theta, thdot, lj, rho2, g, mu_s * sig)
        if D > 0.0 and N > 0.0 and sig * xdd > 0.0:
            return MODE_SLIDE, sig
    return -1, 0.0


# ============================================================================ helpers
@njit(cache=True)
def _arc_ok(th_from, E, lj, I, g, mu, towards_peak):
    """Whether a sticking swing from θ at energy E up to its turning point keeps N > 0, |F| ≤ μN."""
    k = lj * lj / I
    e = E / (g * lj)
    st = min(e, 1.0)
    if towards_peak > 0:
        tt = math.asin(st) if th_from < HALF_PI else HALF_PI
        if tt < th_from:
            tt = th_from
    else:
        tt = math.pi - math.asin(st) if th_from > HALF_PI else HALF_PI
        if tt > th_from:
            tt = th_from
    lo = min(th_from, tt)
    hi = max(th_from, tt)
    if _n_min_range(lo, hi, e, k) <= 0.0:
        return False
    if math.isinf(mu):
        return True
    for i in range(N_ARC):
        th = lo + (hi - lo) * i / (N_ARC - 1)
        s = math.sin(th)
        nf = _n_stick(s, e, k)
        if abs(k * math.cos(th) * (3.0 * s - 2.0 * e)) > mu * nf:
            return False
    return True


@njit(cache=True)
def _rest(x, k, t, h, g, d, uL, beta, length, phi, traj, ts, rec):
    rec[C.E_FINAL] = g * d[k]
    rec[C.T_REST] = t
    m = round((phi - beta[k]) / TWO_PI)
    _put_final(traj, ts, t, x, h + d[k], beta[k] + TWO_PI * m)
    if x + uL[k] <= 0.0:
        return x, k, C.BEHIND_JOINT
    if x > length:
        return x, k, C.OFF_END
    return x, k, C.OK


# ============================================================================ the throw
@njit(cache=True)
def throw_one_rigid_body(x0, side, omega, h, g, length, rho2, mu, w, beta, d, uL, uR, ell, stable, tol, max_iter,
                         max_events, rec, traj, traj_dt):
    """One throw from rest at ``(x0, side)`` with release rate ``omega`` (rad/s), model "rigid_body".

    Fills ``rec`` (layout :mod:`~throwmap.kernels.codes`) and ``traj`` (see the
    module docstring; rows not written are NaN) and returns ``(x, side, status)``.
    ``mu`` is the Coulomb coefficient (``inf``: no slip), ``max_iter`` caps the
    contact-search and integration steps of one mode, ``max_events`` the mode
    changes (status NO_REST beyond). The caller has checked the start.
    """
    n = w.shape[0]
    for i in range(C.NREC):
        rec[i] = 0.0
    rec[C.N_MIN] = math.inf
    rec[C.T_REST] = math.nan
    rec[C.K_MAX_IMPACT_GAIN] = -math.inf
    rec[C.CONTACT_VERTEX] = -1.0
    rec[C.PENETRATION_MAX] = 0.0
    for i in range(traj.shape[0]):
        for q in range(4):
            traj[i, q] = math.nan
    ts = np.zeros(3)
    ts[2] = traj_dt if traj_dt > 0.0 else math.inf
    dk = d[side]
    rec[C.E_RELEASE] = 0.5 * omega * omega * (x0 * x0 + (h + dk) * (h + dk) + rho2) + g * dk
    if traj.shape[0] > 0:
        _put(traj, ts, 0.0, x0, h + dk, beta[side])
        ts[1] = ts[2]
    if omega == 0.0:
        rec[C.N_MIN] = 1.0
        return _rest(x0, side, 0.0, h, g, d, uL, beta, length, beta[side], traj, ts, rec)
    # ------------------------------------------------------------------ reset release (Eq. 1)
    t = 0.0
    x = x0
    y = h + dk
    phi = beta[side]
    vx = -(h + dk) * omega
    vy = x0 * omega
    om = omega
    cb = math.cos(phi)
    sb = math.sin(phi)
    ru = np.empty(n)
    rv = np.empty(n)
    c0 = np.empty(n)
    for j in range(n):
        ru[j] = cb * w[j, 0] - sb * w[j, 1]
        rv[j] = sb * w[j, 0] + cb * w[j, 1]
        c0[j] = dk + rv[j]
        if abs(c0[j]) <= 1e-15 * ell[j]:
            c0[j] = 0.0
    excl_j = -1
    excl_t = 0.0
    mode = MODE_FLIGHT
    last_side = side
    first = True
    n_events = 0
    # contact-mode state: pivot vertex j at x_A = px, angle θ of A→CM, rates
    jp = -1
    px = 0.0
    theta = 0.0
    thdot = 0.0
    va = 0.0
    phi_off = 0.0
    sig = 0.0
    sample = traj.shape[0] > 0
    mu_s = MU_SKID if math.isinf(mu) else mu
    ev = EV_NONE
    while True:
        n_events += 1
        if n_events > max_events:
            return x, last_side, C.NO_REST
        if mode == MODE_FLIGHT:
            # ---------------------------------------------------------- guard touch
            tc, jc = first_contact_state(c0, ru, rv, vy, om, g, ell, excl_j, excl_t, tol, max_iter)
            if jc < 0:
                return x, last_side, C.NO_CONTACT
            if sample:
                while ts[1] <= t + tc:
                    tq = ts[1] - t
                    _put(traj, ts, ts[1], x + vx * tq, y + vy * tq - 0.5 * g * tq * tq, phi + om * tq)
                    ts[1] += ts[2]
            x += vx * tc
            y += vy * tc - 0.5 * g * tc * tc
            vy -= g * tc
            phi += om * tc
            t += tc
            cp = math.cos(om * tc)
            sp = math.sin(om * tc)
            rx = cp * ru[jc] - sp * rv[jc]
            ry = sp * ru[jc] + cp * rv[jc]
            pxc = x + rx
            if sample:
                _put(traj, ts, t, x, y, phi)
            k_pre = 0.5 * (vx * vx + vy * vy + rho2 * om * om)
            if first:
                rec[C.T_FLIGHT] = t
                rec[C.CONTACT_VERTEX] = jc
                rec[C.CONTACT_X] = pxc
                rec[C.VX_PRE] = vx
                rec[C.VY_PRE] = vy
                rec[C.W_PRE] = om
                rec[C.K_PRE] = k_pre
                rec[C.U_IMPACT] = g * (y - h)
            # ---------------------------------------------------------- guard leave_arm
            if pxc <= 0.0:
                return x, last_side, C.BEHIND_JOINT
            if pxc > length:
                return x, last_side, C.OFF_END
            # ---------------------------------------------------------- reset impact
            vxp, vyp, wp, pt, pn, kind, jt0, jn0 = coulomb_impact(vx, vy, om, rx, ry, rho2, mu)
            if jn0 < 0.0:
                rec[C.N_PULL] += 1.0
            if kind == IMP_INCONSISTENT:
                rec[C.N_IMPACTS] += 1.0
                return x, last_side, C.INCONSISTENT
            k_post = 0.5 * (vxp * vxp + vyp * vyp + rho2 * wp * wp)
            _record_impact(pt, pn, k_pre, k_post, rec)
            if kind != IMP_STICK:
                rec[C.N_SLIPS] += 1.0
            if first:
                first = False
                rec[C.VX_POST] = vxp
                rec[C.VY_POST] = vyp
                rec[C.W_POST] = wp
                rec[C.JX] = pt
                rec[C.JY] = pn
                if jn0 > 0.0:
                    rec[C.MU_IMPACT] = abs(jt0) / jn0
                else:
                    rec[C.MU_IMPACT] = math.inf if jt0 != 0.0 else 0.0
                rec[C.K_POST] = k_post
            vx, vy, om = vxp, vyp, wp
            if kind == IMP_SEPARATE:
                # the vertex leaves at once: flight again, this vertex excluded for a while
                un = vy + om * rx
                excl_j = jc
                excl_t = departure_window(un, rx, ry, om, g, ell[jc]) if un <= 1e-12 else 0.0
                cp = math.cos(phi)
                sp = math.sin(phi)
                for j in range(n):
                    ru[j] = cp * w[j, 0] - sp * w[j, 1]
                    rv[j] = sp * w[j, 0] + cp * w[j, 1]
                    c0[j] = (y - h) + rv[j]
                c0[jc] = 0.0
                continue
            jp = jc
            px = pxc
            theta = math.atan2(-ry, -rx)
            thdot = om
            phi_off = phi - theta
            va = vx - om * ry  # contact slip velocity
            if kind == IMP_STICK:
                va = 0.0
            mode = MODE_SELECT
            continue
        # ====================================================== contact modes on vertex jp
        lj = ell[jp]
        I = rho2 + lj * lj
        ta = _theta_a(jp, n, d, uL)
        tb = _theta_b(jp, d, uR)
        if theta < ta:
            theta = ta
        elif theta > tb:
            theta = tb
        if mode == MODE_SELECT:
            new_mode, sig = select_contact_mode(theta, thdot, va, lj, rho2, g, mu, mu_s, False)
            if new_mode < 0:
                return px + lj * math.cos(theta), last_side, C.INCONSISTENT
            if new_mode == MODE_SLIDE:
                rec[C.N_SLIPS] += 1.0 if va == 0.0 else 0.0  # a sliding impact was counted already
            mode = new_mode
            if mode == MODE_FLIGHT:
                ev = EV_LIFT_OFF
        if mode == MODE_FLIGHT:
            pass
        elif mode == MODE_STICK:
            ev, theta, thdot, t = pivot_stick(theta, thdot, ta, tb, lj, I, g, mu, t, max_iter, px, h, phi_off, traj,
                                              ts, rec)
            va = 0.0
        else:
            ev, px, theta, va, thdot, t = pivot_slide(px, theta, va, thdot, sig, ta, tb, lj, rho2, g, mu_s, length,
                                                      t, max_iter, h, phi_off, traj, ts, rec)
            if ev == EV_INCONSISTENT:
                return px + lj * math.cos(theta), last_side, C.INCONSISTENT
            if ev == EV_BEHIND_JOINT:
                return px + lj * math.cos(theta), last_side, C.BEHIND_JOINT
            if ev == EV_OFF_END:
                return px + lj * math.cos(theta), last_side, C.OFF_END
        if ev == EV_SLIP or ev == EV_LIFT_OFF or ev == EV_STICK:
            # ---------------------------------------------------------- resets slip_start / stick_start / lift
            new_mode, sig = select_contact_mode(theta, thdot, va, lj, rho2, g, mu, mu_s, ev != EV_STICK)
            if new_mode < 0:
                return px + lj * math.cos(theta), last_side, C.INCONSISTENT
            if new_mode == MODE_SLIDE:
                rec[C.N_SLIPS] += 1.0
                mode = MODE_SLIDE
                continue
            if new_mode == MODE_STICK:
                mode = MODE_STICK
                continue
            ev = EV_LIFT_OFF
        if ev == EV_STEP_CAP:
            return px + lj * math.cos(theta), last_side, C.NO_REST
        c = math.cos(theta)
        s = math.sin(theta)
        phi = theta + phi_off
        if ev == EV_LIFT_OFF:
            # ---------------------------------------------------------- reset lift
            rec[C.N_LIFTOFFS] += 1.0
            x = px + lj * c
            y = h + lj * s
            vx = va - thdot * lj * s
            vy = thdot * lj * c
            om = thdot
            rx = -lj * c
            ry = -lj * s
            un = vy + om * rx
            excl_j = jp
            excl_t = departure_window(un if un > 0.0 else 0.0, rx, ry, om, g, lj)
            if excl_t <= 0.0:
                # N = 0 with a friction force that only infinite friction supplies and a free
                # motion that would sink the vertex: no consistent contact (mu = inf only)
                return x, last_side, C.INCONSISTENT
            cp = math.cos(phi)
            sp = math.sin(phi)
            for j in range(n):
                ru[j] = cp * w[j, 0] - sp * w[j, 1]
                rv[j] = sp * w[j, 0] + cp * w[j, 1]
                c0[j] = (y - h) + rv[j]
            c0[jp] = 0.0
            sig = 0.0
            mode = MODE_FLIGHT
            continue
        # -------------------------------------------------------------- reset land_side
        land_dir = 1 if ev == EV_LAND_B else -1
        if land_dir > 0:
            k = jp
            uA = uR[k]
            uB = uL[k]
            jB = (jp + 1) % n
        else:
            k = (jp - 1) % n
            uA = uL[k]
            uB = uR[k]
            jB = k
        dk = d[k]
        if k != last_side:
            rec[C.N_FLIPS] += 1.0
            last_side = k
        x_cm = px - uA
        x = x_cm
        vxm = va - thdot * dk
        vym = -thdot * uA
        k_before = 0.5 * (vxm * vxm + vym * vym + rho2 * thdot * thdot)
        pxB = x_cm + uB
        vxp, vyp, wp, pt, pn, kind, jt0, jn0 = coulomb_impact(vxm, vym, thdot, uB, -dk, rho2, mu)
        lifts = kind != IMP_INCONSISTENT and (vyp + wp * uA) > 0.0
        if pxB <= 0.0:
            rec[C.N_IMPACTS] += 1.0
            return x_cm, k, C.BEHIND_JOINT
        if pxB > length:
            rec[C.N_IMPACTS] += 1.0
            return x_cm, k, C.OFF_END
        if lifts:
            if jn0 < 0.0:
                rec[C.N_PULL] += 1.0
            k_after = 0.5 * (vxp * vxp + vyp * vyp + rho2 * wp * wp)
            _record_impact(pt, pn, k_before, k_after, rec)
            if kind != IMP_STICK:
                rec[C.N_SLIPS] += 1.0
            th_new = _theta_a(jB, n, d, uL) if land_dir > 0 else _theta_b(jB, d, uR)
            lB = ell[jB]
            if kind == IMP_STICK and stable[k]:
                barrier_A = g * (ell[jp] - dk)
                barrier_B = g * (lB - dk)
                if k_after < min(barrier_A, barrier_B):
                    IB = rho2 + lB * lB
                    EB = k_after + g * dk
                    ok = _arc_ok(th_new, EB, lB, IB, g, mu, land_dir)
                    if ok:
                        th_A = tb if land_dir > 0 else ta
                        ok = _arc_ok(th_A, EB, ell[jp], rho2 + ell[jp] * ell[jp], g, mu, -land_dir)
                    if ok:
                        return _rest(x_cm, k, t, h, g, d, uL, beta, length, phi, traj, ts, rec)
            phi_off = phi - th_new
            if kind == IMP_SEPARATE:
                x = x_cm
                y = h + dk
                vx, vy, om = vxp, vyp, wp
                rx = uB
                ry = -dk
                excl_j = jB
                un = vy + om * rx
                excl_t = departure_window(un if un > 0.0 else 0.0, rx, ry, om, g, lB) if un <= 1e-12 else 0.0
                cp = math.cos(phi)
                sp = math.sin(phi)
                for j in range(n):
                    ru[j] = cp * w[j, 0] - sp * w[j, 1]
                    rv[j] = sp * w[j, 0] + cp * w[j, 1]
                    c0[j] = (y - h) + rv[j]
                c0[jB] = 0.0
                mode = MODE_FLIGHT
                continue
            jp = jB
            px = pxB
            theta = th_new
            thdot = wp
            va = 0.0 if kind == IMP_STICK else vxp + wp * dk  # slip velocity of B
            mode = MODE_SELECT
            continue
        # both vertices stop normal motion: v_y = ω = 0, friction removes what it can of v_x
        jn = -vym if vym < 0.0 else 0.0
        jt = -vxm
        if abs(jt) > mu * jn:
            jt = -mu * jn if vxm > 0.0 else mu * jn
        vx_after = vxm + jt
        k_after = 0.5 * vx_after * vx_after
        _record_impact(jt, jn, k_before, k_after, rec)
        m2 = round((phi - beta[k]) / TWO_PI)
        phi = beta[k] + TWO_PI * m2
        if vx_after != 0.0:
            # FLAT_SLIDE at deceleration mu g
            rec[C.N_SLIPS] += 1.0
            sgn = 1.0 if vx_after > 0.0 else -1.0
            dec = mu * g
            t_slide = abs(vx_after) / dec
            dist = 0.5 * vx_after * vx_after / dec
            if sample:
                while ts[1] <= t + t_slide:
                    tq = ts[1] - t
                    _put(traj, ts, ts[1], x_cm + vx_after * tq - 0.5 * sgn * dec * tq * tq, h + dk, phi)
                    ts[1] += ts[2]
            x_cm += sgn * dist
            t += t_slide
            rec[C.SLIP_DISTANCE] += dist
        x = x_cm
        if stable[k]:
            return _rest(x_cm, k, t, h, g, d, uL, beta, length, phi, traj, ts, rec)
        # flat on an unstable side: tips over the vertex its CM overhangs, from rest
        thdot = 0.0
        va = 0.0
        if uL[k] >= 0.0:
            jp = (k + 1) % n
            px = x_cm + uL[k]
            theta = _theta_a(jp, n, d, uL)
        else:
            jp = k
            px = x_cm + uR[k]
            theta = _theta_b(jp, d, uR)
        phi_off = phi - theta
        if px <= 0.0:
            return x_cm, k, C.BEHIND_JOINT
        if px > length:
            return x_cm, k, C.OFF_END
        mode = MODE_STICK


@njit(cache=True, parallel=True)
def throw_many_rigid_body(x0, side, omega, valid, h, g, length, rho2, mu, w, beta, d, uL, uR, ell, stable, tol,
                          max_iter, max_events, x_out, side_out, status_out, rec_out):
    """Batch of independent throws (flat arrays), model "rigid_body"; invalid starts get INVALID_START."""
    no_traj = np.empty((0, 4))
    for i in prange(x0.shape[0]):
        if not valid[i]:
            x_out[i] = x0[i]
            side_out[i] = side[i]
            status_out[i] = C.INVALID_START
            for q in range(C.NREC):
                rec_out[i, q] = math.nan
            continue
        x, k, st = throw_one_rigid_body(x0[i], side[i], omega[i], h, g, length, rho2, mu, w, beta, d, uL, uR, ell,
                                        stable, tol, max_iter, max_events, rec_out[i], no_traj, 0.0)
        x_out[i] = x
        side_out[i] = k
        status_out[i] = st

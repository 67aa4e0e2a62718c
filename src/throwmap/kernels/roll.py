"""After the first impact: pivoting, side landings, flips, rocking and rest.

Implements the post-impact phase of paper Sec. III-C, exactly within the
paper's assumptions (plastic impacts, no slip, the pivot never lifts) and with
the corrections listed in the draft's errata (``throwmap/data/errata.md``).

Pivot phase (guard/reset pairs)
-------------------------------
While pivoting on vertex w_j the part is a compound pendulum. Let θ be the angle
of the vector from the pivot to the CM (length ℓ_j = |w_j|), so the CM height
is ℓ_j sin θ, and I_j = ρ² + ℓ_j² (per unit mass). θ ranges over
[θa_j, θb_j]: θa_j is the part resting on side j−1 (w_j its left vertex),
θb_j resting on side j (w_j its right vertex). U = g ℓ_j sin θ has one peak
(θ = π/2), so energy E = ½ I_j θ̇² + g ℓ_j sin θ *and the sense of θ̇* decide
which end is reached (the draft's Sec. III-C test ignores the sense):

* guard ``reach_end``: no barrier ahead in the direction of motion, or E above it;
  reset ``land_side``: the side at that end slams flat.
* otherwise the part turns back (E below the peak, unimodal U) and lands on the
  side behind it.

Landing (reset ``land_side``)
-----------------------------
A side landing is a plastic impact about the side's *other* vertex B (angular
momentum about B conserved). With A the vertex it pivoted on and c the CM,
ω⁺ = ω⁻ (ρ² + (c−A)·(c−B)) / (ρ² + |c−B|²). If ω⁺ lifts the edge about B the
part pivots on B; otherwise both vertices stay down and it rests (stable side)
or tips about the vertex its CM overhangs (unstable side). Kinetic energy never
increases: (ρ² + a·b)² ≤ (ρ² + |a|²)(ρ² + |b|²) by Cauchy–Schwarz.

Rocking to rest (Zeno, decided on purpose): after a landing on a stable side
with kinetic energy K below *both* topple barriers g(ℓ_A − d) and g(ℓ_B − d),
every later swing has less energy, so the part rests there. The pivot never
slips, so a part that falls back rests with its impact vertex where it touched.

Forces while pivoting are checked, not imposed: the normal force in units of
m g is N = 1 − k + 3k s² − 2k e s (s = sin θ, k = ℓ²/I, e = E/(g ℓ)), whose
minimum over the swept arc is exact; the friction force is k cos θ (3s − 2e).
A negative minimum flags lift-off (the part would hop); it does not change the
dynamics of this model.

Tilted arm (rest angle α, rad, CCW +; draft Sec. VI)
----------------------------------------------------
Gravity in the arm frame is (−g sin α, −g cos α), so about a pivot U = g ℓ_j sin(θ + α):
the pendulum above in ψ = θ + α, the angle in the frame of gravity. The cascade runs
every guard and reset above in ψ (the landing angles become θa_j + α, θb_j + α; the peak
stays at ψ = π/2), so jog and flip barriers change with α; landings are impulsive and
unchanged. A side is stable iff its CM's vertical meets the support segment inside
(u_L < −d tan α < u_R, the ``stable`` table passed for α), the Zeno barriers are
g ℓ (1 − sin ψ) about each support vertex, and an unstable side tips over the vertex
its CM overhangs along gravity. The paper's no-slip assumption holds the part at any α
(the record reports the friction demand, now including |tan α| at rest). The force
record of a swing is then the horizontal force in ψ rotated into the arm frame,
N = cos α N_w − sin α F_w, F = cos α F_w + sin α N_w, sampled at ``n_samples`` angles
(its exact minimum is only exact for α = 0).
"""

import math

import numpy as np
from numba import njit

from . import codes as C
from .record import continue_angle, put, swing_rows

HALF_PI = 0.5 * math.pi
N_EXACT = 1e-2
"""Below this normal force (units of m g) an arc sample's friction ratio uses exact trig, not the recurrence."""


@njit(cache=True)
def theta_a(j, n, d, uL):
    """Angle (rad) of pivot→CM when resting on side j−1 with w_j its left vertex."""
    k = (j - 1) % n
    return math.atan2(d[k], -uL[k])


@njit(cache=True)
def theta_b(j, d, uR):
    """Angle (rad) of pivot→CM when resting on side j with w_j its right vertex."""
    return math.atan2(d[j], -uR[j])


_theta_a = theta_a  # names rigid_body imports
_theta_b = theta_b


@njit(cache=True, inline="always")
def _check_arc(th1, th2, E, ell, I, g, n_samples, rec):
    """Record the normal/friction demand of a pivot swing over θ ∈ [th1, th2] ⊂ (0, π).

    N_MIN gets the exact minimum of N over the arc. MU_MAX gets the largest
    |F|/N (where N > 0) at ``n_samples`` equally spaced angles, skipped when the
    bound k √(1 − s_lo²) max|3s − 2e| / min N over the arc cannot beat the record;
    the angles' sines and cosines follow a rotation recurrence (two trig calls per
    arc; rounding ~n_samples ulp), except where N < ``N_EXACT`` (there |F|/N
    amplifies that rounding, so the sample's own sine and cosine are used).
    """
    if th2 < th1:
        th1, th2 = th2, th1
    s1 = math.sin(th1)
    s2 = math.sin(th2)
    s_lo = min(s1, s2)
    s_hi = 1.0 if (th1 <= HALF_PI <= th2) else max(s1, s2)
    k = ell * ell / I
    e = E / (g * ell)
    s_star = min(max(e / 3.0, s_lo), s_hi)
    n_min = 1.0 - k + 3.0 * k * s_star * s_star - 2.0 * k * e * s_star
    if n_min < rec[C.N_MIN]:
        rec[C.N_MIN] = n_min
    if n_min > 0.0:
        f_max = k * math.sqrt(max(1.0 - s_lo * s_lo, 0.0)) * max(abs(3.0 * s_lo - 2.0 * e), abs(3.0 * s_hi - 2.0 * e))
        if f_max <= n_min * rec[C.MU_MAX] * (1.0 - 1e-12):
            return  # no sample can raise the record
    dth = (th2 - th1) / (n_samples - 1)
    cd = math.cos(dth)
    sd = math.sin(dth)
    s = s1
    c = math.cos(th1)
    for i in range(n_samples):
        N = 1.0 - k + 3.0 * k * s * s - 2.0 * k * e * s
        if N < N_EXACT:  # |F|/N is ill-conditioned here: the sample's own sine and cosine
            th = th1 + (th2 - th1) * i / (n_samples - 1)
            s_i = math.sin(th)
            c_i = math.cos(th)
            N = 1.0 - k + 3.0 * k * s_i * s_i - 2.0 * k * e * s_i
            if N > 0.0:
                r = abs(k * c_i * (3.0 * s_i - 2.0 * e)) / N
                if r > rec[C.MU_MAX]:
                    rec[C.MU_MAX] = r
        elif N > 0.0:
            F = k * c * (3.0 * s - 2.0 * e)
            r = abs(F) / N
            if r > rec[C.MU_MAX]:
                rec[C.MU_MAX] = r
        s, c = s * cd + c * sd, c * cd - s * sd


@njit(cache=True)
def _check_arc_tilted(th1, th2, E, ell, I, g, n_samples, rec, alpha):
    """:func:`_check_arc` on a tilted arm: ψ ∈ [th1, th2] (ψ = θ + α), arm-frame N and |F|/N at ``n_samples`` angles."""
    k = ell * ell / I
    e = E / (g * ell)
    ca = math.cos(alpha)
    sa = math.sin(alpha)
    for i in range(n_samples):
        th = th1 + (th2 - th1) * i / (n_samples - 1)
        s = math.sin(th)
        nw = 1.0 - k + 3.0 * k * s * s - 2.0 * k * e * s
        fw = k * math.cos(th) * (3.0 * s - 2.0 * e)
        N = ca * nw - sa * fw
        F = ca * fw + sa * nw
        if N < rec[C.N_MIN]:
            rec[C.N_MIN] = N
        if N > 0.0:
            r = abs(F) / N
            if r > rec[C.MU_MAX]:
                rec[C.MU_MAX] = r


@njit(cache=True, inline="always")
def _record_impulse(jx, jy, rec):
    if jy < 0.0:
        rec[C.N_PULL] += 1.0
    elif jy > 0.0:
        r = abs(jx) / jy
        if r > rec[C.MU_MAX]:
            rec[C.MU_MAX] = r


@njit(cache=True, inline="always")
def swing_sense(theta, thdot):
    """Sense (+1 CCW, −1 CW) of a swing at θ̇; from rest, the sense gravity pulls (down, away from the peak)."""
    if thdot > 0.0:
        return 1
    if thdot < 0.0:
        return -1
    return 1 if math.cos(theta) < 0.0 else -1


@njit(cache=True, inline="always")
def reach_end(theta, dirn, ta, tb, E, g, lj):
    """Guard ``reach_end``: the swing from θ in sense ``dirn`` at energy E (J/kg) reaches the end ahead.

    True when no barrier lies ahead (downhill to the end) or E is above it (the
    peak g ℓ_j at θ = π/2 if it lies ahead, else the end's own height).
    """
    if dirn > 0:
        end = tb
        peak_ahead = theta < HALF_PI < tb
    else:
        end = ta
        peak_ahead = ta < HALF_PI < theta
    if peak_ahead:
        barrier = g * lj
    elif math.sin(end) > math.sin(theta):
        barrier = g * lj * math.sin(end)
    else:
        barrier = -math.inf
    return E > barrier


@njit(cache=True, inline="always")
def turn_back(E, g, lj, dirn):
    """Guard ``turn_back``: the angle (rad) at which a swing in sense ``dirn`` below its barrier stops (θ̇ = 0)."""
    s_turn = min(E / (g * lj), 1.0)
    return math.asin(s_turn) if dirn > 0 else math.pi - math.asin(s_turn)


@njit(cache=True, inline="always")
def pivot_swing(theta, thdot, ta, tb, lj, I, g, n_samples, rec, alpha=0.0):
    """One swing about a pivot vertex (compound pendulum), from θ at rate θ̇ (rad/s) to a landing.

    On a tilted arm (``alpha`` ≠ 0) the angles θ, θa, θb are ψ = θ + α (see the module
    docstring) and the force record is :func:`_check_arc_tilted`.

    Returns ``(E, end, land_dir, th_turn, thdot_end)``: the energy (J/kg), the end
    angle reached (θa or θb), the sense of the landing, the turning angle (NaN when
    the guard ``reach_end`` held) and θ̇ on arrival. Records the force demand.
    """
    E = 0.5 * I * thdot * thdot + g * lj * math.sin(theta)
    dirn = swing_sense(theta, thdot)
    if reach_end(theta, dirn, ta, tb, E, g, lj):
        end = tb if dirn > 0 else ta
        a1 = theta  # the arc swept
        a2 = end
        land_dir = dirn
        th_turn = math.nan
    else:
        # turns back below the barrier and lands on the side behind
        th_turn = turn_back(E, g, lj, dirn)
        a1 = ta if dirn > 0 else th_turn
        a2 = th_turn if dirn > 0 else tb
        end = ta if dirn > 0 else tb
        land_dir = -dirn
    if alpha != 0.0:
        _check_arc_tilted(a1, a2, E, lj, I, g, n_samples, rec, alpha)
    else:
        _check_arc(a1, a2, E, lj, I, g, n_samples, rec)
    w2 = 2.0 * (E - g * lj * math.sin(end)) / I
    speed = math.sqrt(w2) if w2 > 0.0 else 0.0
    return E, end, land_dir, th_turn, (speed if land_dir > 0 else -speed)


@njit(cache=True, inline="always")
def land_side(j, land_dir, thdot, rho2, n, d, uL, uR, rec):
    """Reset ``land_side``: side k slams flat while pivoting on w_j at θ̇ (plastic impact about its other vertex B).

    Returns ``(k, uA, uB, jB, w_new, lifts)``: the side, the CM-frame abscissae of
    the pivot A and of B on it (m), B's index, the spin after the impact about B
    (rad/s) and whether it lifts the edge (the part then pivots on B). Records the
    impulse and the kinetic-energy change.
    """
    if land_dir > 0:
        k = j  # landed on side j; pivot A = its right vertex, B = left vertex w_{j+1}
        uA = uR[k]
        uB = uL[k]
        jB = (j + 1) % n
    else:
        k = (j - 1) % n  # landed on side j−1; A = its left vertex w_j, B = right vertex
        uA = uL[k]
        uB = uR[k]
        jB = k
    dk = d[k]
    IA = rho2 + uA * uA + dk * dk
    IB = rho2 + uB * uB + dk * dk
    w_new = thdot * (rho2 + uA * uB + dk * dk) / IB
    # CM velocity relative to the pivot: w × (c − P) with c − P = (−u, d)
    vx_m = -thdot * dk
    vy_m = -thdot * uA
    lifts = (w_new > 0.0) if land_dir > 0 else (w_new < 0.0)
    k_before = 0.5 * IA * thdot * thdot
    if lifts:
        vx_p = -w_new * dk
        vy_p = -w_new * uB
        _record_impulse(vx_p - vx_m, vy_p - vy_m, rec)
        k_after = 0.5 * IB * w_new * w_new
    else:
        _record_impulse(-vx_m, -vy_m, rec)  # both vertices stop the part
        k_after = 0.0
    if k_after - k_before > rec[C.K_MAX_IMPACT_GAIN]:
        rec[C.K_MAX_IMPACT_GAIN] = k_after - k_before
    return k, uA, uB, jB, w_new, lifts


@njit(cache=True, inline="always")
def rocking_rest(k_after, lA, lB, dk, g):
    """Guard ``rocking_rest`` (Zeno, decided on purpose): kinetic energy (J/kg) below both topple barriers g(ℓ − d)."""
    return k_after < min(g * (lA - dk), g * (lB - dk))


@njit(cache=True)
def tip_over(k, x_cm, n, d, uL, uR, alpha=0.0):
    """Reset ``tip_over``: flat on unstable side k, the part tips from rest over the vertex its CM overhangs.

    On an arm at rest angle ``alpha`` it overhangs along gravity: the left vertex iff
    u_L ≥ −d tan α. Returns ``(j, px, theta)``: the pivot vertex, its x (m) and the
    angle of pivot→CM (arm frame).
    """
    left = uL[k] >= 0.0
    if alpha != 0.0:
        left = uL[k] >= -d[k] * math.tan(alpha)
    if left:
        j = (k + 1) % n
        return j, x_cm + uL[k], theta_a(j, n, d, uL)
    return k, x_cm + uR[k], theta_b(k, d, uR)


@njit(cache=True)
def side_angles(d, uL, uR):
    """Tables ``(ta, tb)`` of θa_j and θb_j (rad) for every vertex j (:func:`theta_a`, :func:`theta_b`)."""
    n = d.shape[0]
    ta = np.empty(n)
    tb = np.empty(n)
    for j in range(n):
        ta[j] = theta_a(j, n, d, uL)
        tb[j] = theta_b(j, d, uR)
    return ta, tb


@njit(cache=True)
def roll_to_rest(j, theta, thdot, px, side0, rho2, d, uL, uR, ell, stable, g, length, max_impacts, n_samples, rec,
                 back=0.0):
    """Pivot on vertex ``w_j`` from angle ``theta`` at rate ``thdot`` (rad/s, CCW +) until rest.

    ``px`` is the pivot's world x (m), ``side0`` the side thrown from, ``length``
    the arm length (inf: unbounded), ``back`` its extent behind the joint (m,
    ``Arm.back``). Returns ``(x, side, status)``; ``rec`` counters are updated in
    place. :func:`pivot_cascade` without its tables and trajectory.
    """
    ta_j, tb_j = side_angles(d, uL, uR)
    return pivot_cascade(j, theta, thdot, px, side0, rho2, d, uL, uR, ell, stable, ta_j, tb_j, g, length,
                         max_impacts, n_samples, rec, np.empty((0, 4)), np.empty(0, np.int64), np.zeros(5), 0.0,
                         np.empty((0, 2)), d, back)


@njit(cache=True, inline="always")
def pivot_cascade(j, theta, thdot, px, side0, rho2, d, uL, uR, ell, stable, ta_j, tb_j, g, length, max_impacts,
                  n_samples, rec, traj, tags, ts, h, w, beta, back, alpha=0.0):
    """Pivot on vertex ``w_j`` from angle ``theta`` at rate ``thdot`` (rad/s, CCW +) until rest.

    ``px`` is the pivot's world x (m), ``side0`` the side thrown from (flips are
    counted as landings on a side other than the last one landed on), ``length``
    the arm length (inf: unbounded), ``back`` its extent behind the joint (m; a
    contact at x ≤ −back is BEHIND_JOINT), ``ta_j``/``tb_j`` the tables of
    :func:`side_angles`. Per-side/vertex arrays as in
    :func:`throwmap.system.geometry.side_table`.
    Returns ``(x, side, status)``; ``rec`` counters are updated in place.
    With a non-empty ``traj`` the swings and landings are recorded
    (:mod:`~throwmap.kernels.record`; ``h`` the arm height, ``w`` the vertices and
    ``beta`` the resting orientations give the poses). ``alpha``: the arm's rest angle
    (rad; ``stable`` must be the table for it): every swing runs in ψ = θ + α.
    """
    n = d.shape[0]
    last_side = side0
    record = traj.shape[0] > 0
    while True:
        # ---------------------------------------------------------- pivot phase on w_j
        lj = ell[j]
        I = rho2 + lj * lj
        ta = ta_j[j]
        tb = tb_j[j]
        if theta < ta:
            theta = ta
        elif theta > tb:
            theta = tb
        theta0 = theta
        # the swing in ψ = θ + α (α = 0: θ itself, bit for bit)
        E, end, land_dir, th_turn, thdot = pivot_swing(theta + alpha, thdot, ta + alpha, tb + alpha, lj, I, g,
                                                       n_samples, rec, alpha)
        # ---------------------------------------------------------- reset land_side
        k = j if land_dir > 0 else (j - 1) % n
        uA = uR[k] if land_dir > 0 else uL[k]
        if record:
            t_end, phi_end = swing_rows(traj, tags, ts, j, px, lj, math.atan2(w[j, 1], w[j, 0]), h, theta0 + alpha,
                                        th_turn, end, E, I, g, alpha)
            put(traj, tags, ts, t_end, px - uA, h + d[k], continue_angle(beta[k], phi_end), n + k)
        if k != last_side:
            rec[C.N_FLIPS] += 1.0
            last_side = k
        rec[C.N_IMPACTS] += 1.0
        if rec[C.N_IMPACTS] > max_impacts:
            return px - uA, k, C.NO_REST
        k, uA, uB, jB, w_new, lifts = land_side(j, land_dir, thdot, rho2, n, d, uL, uR, rec)
        dk = d[k]
        x_cm = px - uA  # CM x with the part flat on side k
        pxB = x_cm + uB
        # guard leave_arm: the landing vertex B must hit the arm, not the air beyond its span
        if pxB <= -back:
            return x_cm, k, C.BEHIND_JOINT
        if pxB > length:
            return x_cm, k, C.OFF_END
        if lifts:
            k_after = 0.5 * (rho2 + uB * uB + dk * dk) * w_new * w_new
            if alpha != 0.0:
                th_A = tb_j[j] if land_dir > 0 else ta_j[j]  # A's and B's pivot angles flat on side k
                th_B = ta_j[jB] if land_dir > 0 else tb_j[jB]
                zeno = k_after < min(g * ell[j] * (1.0 - math.sin(th_A + alpha)),
                                     g * ell[jB] * (1.0 - math.sin(th_B + alpha)))
            else:
                zeno = rocking_rest(k_after, ell[j], ell[jB], dk, g)
            if stable[k] and zeno:
                return x_cm, k, C.OK  # rocks to rest (Zeno), energy below both barriers
            j = jB
            px = pxB
            thdot = w_new
            theta = ta_j[j] if land_dir > 0 else tb_j[j]
        elif stable[k]:
            return x_cm, k, C.OK
        else:
            thdot = 0.0
            j, px, theta = tip_over(k, x_cm, n, d, uL, uR, alpha)
        if px <= -back:
            return x_cm, k, C.BEHIND_JOINT
        if px > length:
            return x_cm, k, C.OFF_END

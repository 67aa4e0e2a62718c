"""Mode WALL_CONTACT of model "rigid_body": one vertex pressed on the wall's face, the part otherwise free.

After a plastic impact with the wall (:func:`~.wall.wall_hit_in_flight`, or a swinging pivot
that meets the wall, :func:`~.wall_lean.lean`), a vertex P can stay pressed on the face x = L:
the motion that gravity and the part's rotation impose would carry it into the wall (G″ < 0 in
:func:`~throwmap.kernels.flight.departure_window`, in the face's frame). The part then moves with P
on the face — sliding along it (the wall's Coulomb μ_w, 0 included) or sticking to it — until P lets
go (N = 0), another vertex reaches the arm (a landing with P still on the wall), P reaches the
arm or the wall's top, or another vertex reaches the wall's plane (an edge flush on the face).

Coordinates (arm frame, m, rad): P = (L, y_P) and θ the angle of P → CM, so that
CM = P + ℓ (cos θ, sin θ) (ℓ the vertex's distance from the CM) and φ = θ + φ_off. Unit mass,
inertia ρ² about the CM, gravity (g_x, −g_n) (:mod:`~.wall`). The contact force on the part is
(−N, F): N ≥ 0 along the face's normal −x̂, F along +ŷ. Newton–Euler with the constraint
ẍ_P = 0 (c = cos θ, s = sin θ):

    ẍ = −ℓ s θ̈ − ℓ c θ̇² = g_x − N,   ÿ = ÿ_P + ℓ c θ̈ − ℓ s θ̇² = −g_n + F,
    ρ² θ̈ = −ℓ (c F + s N).

Sliding (ẏ_P ≠ 0, F = −μ_w σ N, σ = sgn ẏ_P; μ_w = 0: F = 0)::

    N D = g_x + ℓ c θ̇²,   D = 1 + ℓ² s (s − μ_w σ c)/ρ²,   ρ² θ̈ = ℓ N (μ_w σ c − s),
    ÿ_P = −g_n − μ_w σ N − ℓ c θ̈ + ℓ s θ̇²

(D ≤ 0: Painlevé's paradox, no consistent force: INCONSISTENT). Sticking (ẏ_P = 0, a pivot on the
face): (ρ² + ℓ²) θ̈ = −ℓ (c g_n + s g_x), N = g_x + ℓ s θ̈ + ℓ c θ̇², F = g_n + ℓ c θ̈ − ℓ s θ̇²,
valid while |F| ≤ μ_w N. The same equations as the arm's PIVOT_SLIDE / PIVOT_STICK
(:func:`~.slide.slide_rhs`) in a frame turned by −90°; they are written out here because
gravity's component normal to the wall (g_x) may be of either sign or zero.

Integration: classical RK4 in (y_P, θ, ẏ_P, θ̇), step Δt = DTH/(|θ̇| + Ω), Ω² = (|g_x| + g_n)/ℓ;
guards checked at step ends and located inside the step by bracketing (false position kept
inside the bracket, bisection otherwise; :func:`~.bracket.locate_guard`), the contact's guards those of any
Coulomb contact (:func:`~.coulomb.cone_guard`).

The automaton enters the mode through :func:`wall_contact`, which follows the sub-mode changes from the
flight state right after the wall impact to the first event it continues from: P lets go (FLIGHT, P
excluded from the wall guards for its exact departure window), or another vertex A reaches the arm (the
automaton then applies the arm's impact, and where that alone would drive P into the wall, the
two-contact impact of :mod:`.wall_lean`).
"""

import math

from numba import njit

from .. import codes as C
from ..flight import departure_window
from .bracket import locate_guard
from .coulomb import cone_guard, cone_guard_value
from .modes import (DTH, EV_INCONSISTENT, EV_LIFT_OFF, EV_SLIP, EV_STEP_CAP, EV_STICK, WC_ARM, WC_CAP, WC_FLIGHT,
                    WC_INCONSISTENT, WC_REFUSE, WHY_CORNER, WHY_NONE, WHY_WALL_EDGE, WHY_WALL_SLIDE, WHY_WALL_TOP)
from .trajectory import _put
from .wall import fill_wall_vertices, sink_slack

EV_ARM = 11
"""Guard ``arm``: a vertex (returned) reaches the arm's line y = h while P is on the face."""
EV_TOP = 12
"""Guard ``top``: P slides up to the wall's top corner."""
EV_EDGE = 13
"""Guard ``edge``: another vertex reaches the wall's plane x = L (an edge flush on it, or on its top corner)."""

W_SLIDE = 0
W_STICK = 1
"""Sub-modes of WALL_CONTACT (μ_w = 0 always slides)."""


@njit(cache=True)
def wall_rhs(th, thd, lj, rho2, gx, gn, musig, stick):
    """WALL_CONTACT dynamics (module docstring). ``musig`` = μ_w σ while sliding; ``stick``: P fixed on the face.

    Returns ``(θ̈, ÿ_P, N, F, D)`` (per unit mass, m/s² and rad/s²; D = 1 while sticking). At D = 0
    exactly ``(nan, nan, nan, nan, 0)``.
    """
    c = math.cos(th)
    s = math.sin(th)
    if stick:
        thdd = -lj * (c * gn + s * gx) / (rho2 + lj * lj)
        N = gx + lj * s * thdd + lj * c * thd * thd
        F = gn + lj * c * thdd - lj * s * thd * thd
        return thdd, 0.0, N, F, 1.0
    D = 1.0 + lj * lj * s * (s - musig * c) / rho2
    if D == 0.0:
        return math.nan, math.nan, math.nan, math.nan, 0.0
    N = (gx + lj * c * thd * thd) / D
    thdd = lj * N * (musig * c - s) / rho2
    F = -musig * N
    ypdd = -gn + F - lj * c * thdd + lj * s * thd * thd
    return thdd, ypdd, N, F, D


@njit(cache=True)
def _rk4(yp, th, vp, thd, dt, lj, rho2, gx, gn, musig, stick):
    a1, b1, _n, _f, _d = wall_rhs(th, thd, lj, rho2, gx, gn, musig, stick)
    th2 = th + 0.5 * dt * thd
    w2 = thd + 0.5 * dt * a1
    a2, b2, _n, _f, _d = wall_rhs(th2, w2, lj, rho2, gx, gn, musig, stick)
    th3 = th + 0.5 * dt * w2
    w3 = thd + 0.5 * dt * a2
    a3, b3, _n, _f, _d = wall_rhs(th3, w3, lj, rho2, gx, gn, musig, stick)
    th4 = th + dt * w3
    w4 = thd + dt * a3
    a4, b4, _n, _f, _d = wall_rhs(th4, w4, lj, rho2, gx, gn, musig, stick)
    v2 = vp + 0.5 * dt * b1
    v3 = vp + 0.5 * dt * b2
    v4 = vp + dt * b3
    yp1 = yp + dt * (vp + 2.0 * v2 + 2.0 * v3 + v4) / 6.0
    th1 = th + dt * (thd + 2.0 * w2 + 2.0 * w3 + w4) / 6.0
    vp1 = vp + dt * (b1 + 2.0 * b2 + 2.0 * b3 + b4) / 6.0
    w1 = thd + dt * (a1 + 2.0 * a2 + 2.0 * a3 + a4) / 6.0
    return yp1, th1, vp1, w1


@njit(cache=True, inline="always")
def _advance(s, tau, p):
    """The RK4 step of length ``tau`` (s) from ``s`` = (y_P, θ, ẏ_P, θ̇) (parameters ``p`` of :func:`wall_phase`)."""
    lj, rho2, gx, gn, mu_w, musig, stick, sig, h, top, wv, ga, arm_skip, slack = p
    return _rk4(s[0], s[1], s[2], s[3], tau, lj, rho2, gx, gn, musig, stick)


@njit(cache=True)
def _guard_value(which, k, s, p):
    """One guard's value (> 0: not fired): see :func:`_guards`."""
    yp, th, vp, thd = s
    lj, rho2, gx, gn, mu_w, musig, stick, sig, h, top, wv, ga, arm_skip, slack = p
    if which == EV_STICK or which == EV_SLIP or which == EV_LIFT_OFF:
        _a, _b, N, F, _D = wall_rhs(th, thd, lj, rho2, gx, gn, musig, stick)
        return cone_guard_value(which, N, F, vp, sig, mu_w, ga)
    if which == EV_TOP:
        return h + top - yp
    if which == EV_ARM:
        v = yp - h if wv[k, 0] == 0.0 else yp + wv[k, 0] * math.sin(th + wv[k, 1]) - h
        return v + slack if k == arm_skip else v
    if which == EV_EDGE:
        return -wv[k, 0] * math.cos(th + wv[k, 1])
    return math.nan


@njit(cache=True)
def _guards(s, p):
    """Least guard value and which guard (and vertex) it is; ``(-1, EV_INCONSISTENT, -1)`` if D ≤ 0.

    Guards: the contact's own (:func:`~.coulomb.cone_guard`: ``lift_off`` N/|g|, ``slip`` (μ_w N − |F|)/|g|
    while sticking with finite μ_w, ``stick`` σ ẏ_P while sliding with μ_w > 0), ``top`` h + H − y_P,
    ``arm`` y_k − h (every vertex but ``arm_skip``; P's own row in ``wv`` has ℓ = 0), ``edge`` L − x_k
    (every other vertex). ``s`` = (y_P, θ, ẏ_P, θ̇), ``p`` the parameters of :func:`wall_phase`.
    """
    yp, th, vp, thd = s
    lj, rho2, gx, gn, mu_w, musig, stick, sig, h, top, wv, ga, arm_skip, slack = p
    _a, _b, N, F, D = wall_rhs(th, thd, lj, rho2, gx, gn, musig, stick)
    if D <= 0.0:
        return -1.0, EV_INCONSISTENT, -1
    gmin, which = cone_guard(N, F, vp, stick, sig, mu_w, ga, mu_w > 0.0)
    kk = -1
    if h + top - yp < gmin:
        gmin = h + top - yp
        which = EV_TOP
    for k in range(wv.shape[0]):
        v = yp - h if wv[k, 0] == 0.0 else yp + wv[k, 0] * math.sin(th + wv[k, 1]) - h
        if k == arm_skip:
            v += slack
        if v < gmin:
            gmin = v
            which = EV_ARM
            kk = k
        if wv[k, 0] > 0.0:
            v = -wv[k, 0] * math.cos(th + wv[k, 1])
            if v < gmin:
                gmin = v
                which = EV_EDGE
                kk = k
    return gmin, which, kk


@njit(cache=True)
def wall_phase(yp, th, vp, thd, stick, sig, t, lj, rho2, gx, gn, mu_w, h, top, wv, arm_skip, arm_skip_until,
               arm_slack, L, phi_off, max_steps, traj, ts, rec):
    """Integrate one sub-mode of WALL_CONTACT (``stick``, or sliding with sense ``sig``) until a guard fires.

    ``wv`` (n, 2) rows (ℓ_k, δ_k): vertex k at P + ℓ_k (cos(θ + δ_k), sin(θ + δ_k)) (ℓ = 0: P itself,
    :func:`~.wall.fill_wall_vertices`); ``arm_skip`` a vertex that just left the arm: until
    ``arm_skip_until`` (s, absolute) its arm guard fires only once it sinks ``arm_slack`` (m) below the line
    (:func:`~.wall.sink_slack`: the departure window was estimated for free flight, and the wall's force can
    press the vertex back).
    Guards located inside a step by :func:`~.bracket.locate_guard`.
    Updates N_MIN (the wall's N/|g| is not the arm's: only MU_MAX), samples ``traj``.
    Returns ``(event, k, y_P, θ, ẏ_P, θ̇, t)`` with k the vertex of ``arm``/``edge`` (else −1).
    """
    musig = 0.0 if stick else mu_w * sig
    ga = abs(gx) + gn
    om0 = math.sqrt(ga / lj)
    sample = traj.shape[0] > 0
    if mu_w > rec[C.MU_MAX] and math.isfinite(mu_w):
        rec[C.MU_MAX] = mu_w
    for _ in range(max_steps):
        skip = arm_skip if t < arm_skip_until else -1
        p = (lj, rho2, gx, gn, mu_w, musig, stick, sig, h, top, wv, ga, skip, arm_slack)
        dt = DTH / (abs(thd) + om0)
        s0 = (yp, th, vp, thd)
        s1 = _advance(s0, dt, p)
        gm, which, k = _guards(s1, p)
        if which == EV_INCONSISTENT:
            return EV_INCONSISTENT, -1, yp, th, vp, thd, t
        step = dt
        if gm <= 0.0:
            step, which, k, _s = locate_guard(_advance, _guards, _guard_value, s0, s1, dt, which, k, t, p)
            s1 = _advance(s0, step, p)
        if sample:
            while ts[1] <= t + step:
                q = _rk4(yp, th, vp, thd, ts[1] - t, lj, rho2, gx, gn, musig, stick)
                _put(traj, ts, ts[1], L + lj * math.cos(q[1]), q[0] + lj * math.sin(q[1]), q[1] + phi_off)
                ts[1] += ts[2]
        yp, th, vp, thd = s1
        t += step
        if gm <= 0.0:
            if which == EV_STICK:
                vp = 0.0
            if sample:
                _put(traj, ts, t, L + lj * math.cos(th), yp + lj * math.sin(th), th + phi_off)
            return which, k, yp, th, vp, thd, t
    return EV_STEP_CAP, -1, yp, th, vp, thd, t


@njit(cache=True)
def wall_select(th, thd, vp, lj, rho2, gx, gn, mu_w, from_slip):
    """Which sub-mode continues from P on the face at (θ, θ̇, ẏ_P) (the one-contact Coulomb choice, as
    :func:`~.slide.select_contact_mode`): returns ``(mode, σ)`` with mode W_STICK, W_SLIDE, −1 (the
    contact is not pressed: N ≤ 0 — the caller lets it go) or −2 (no consistent motion).
    μ_w = 0 always slides; μ_w = ∞ sticks (ẏ_P is 0 after its impact). Where neither sticking (|F| > μ_w N) nor
    sliding (N ≤ 0 in the sense friction allows) keeps the vertex pressed, it lets go (−1) if the free motion
    leaves the face (:func:`~throwmap.kernels.flight.departure_window` > 0), as the arm's contact-mode selection does."""
    if mu_w == 0.0:
        _a, _b, N, _f, D = wall_rhs(th, thd, lj, rho2, gx, gn, 0.0, False)
        if D <= 0.0:
            return -2, 0.0
        return (W_SLIDE, 0.0) if N > 0.0 else (-1, 0.0)
    scale = max(1.0, abs(thd) * lj)
    if abs(vp) > 1e-12 * scale:
        sig = 1.0 if vp > 0.0 else -1.0
        if math.isinf(mu_w):
            return -2, 0.0
        _a, _b, N, _f, D = wall_rhs(th, thd, lj, rho2, gx, gn, mu_w * sig, False)
        if D <= 0.0:
            return -2, 0.0
        return (W_SLIDE, sig) if N > 0.0 else (-1, 0.0)
    _a, _b, N, F, _d = wall_rhs(th, thd, lj, rho2, gx, gn, 0.0, True)
    if N <= 0.0:
        return -1, 0.0
    if not from_slip and abs(F) <= mu_w * N:
        return W_STICK, 0.0
    sig = -1.0 if F > 0.0 else 1.0
    for _ in range(2):
        _a, ypdd, N2, _f, D = wall_rhs(th, thd, lj, rho2, gx, gn, mu_w * sig, False)
        if D > 0.0 and N2 > 0.0 and (sig * ypdd > 0.0 or from_slip):
            return W_SLIDE, sig
        if from_slip:
            break
        sig = -sig
    # neither sticking nor sliding keeps it pressed: it lets go if the free motion leaves the face
    c = math.cos(th)
    s = math.sin(th)
    if departure_window(-lj * s, lj * c, thd, gx, lj, abs(gx) + gn) > 0.0:
        return -1, 0.0
    return -2, 0.0


@njit(cache=True)
def wall_contact(j, t, x, y, vx, vy, phi, om, w, rho2, gx, gn, mu_w, h, top, L, arm_skip, arm_skip_until, max_steps,
                 max_events, wv, traj, ts, rec):
    """Mode WALL_CONTACT from the flight state (CM (x, y), velocity (v_x, v_y), φ, ω; SI) with vertex ``j``
    (body offsets ``w``) on the face x = ``L`` after a plastic impact.

    Sub-modes slide/stick (:func:`wall_select`, :func:`wall_phase`) until:
    ``lift_off`` (N = 0): FLIGHT, with the departure window of P; ``arm``: vertex k reaches the arm
    (WC_ARM, the caller applies the landing; k = j, P at the wall's foot, is refused: WHY_CORNER);
    ``top``: WHY_WALL_TOP; ``edge``: WHY_WALL_EDGE; Painlevé (D ≤ 0) or no consistent sub-mode:
    WC_INCONSISTENT; ``max_steps`` steps in one sub-mode or ``max_events`` sub-mode changes: WC_CAP.
    ``wv`` (n, 2) is scratch. Returns ``(outcome, k, t, x, y, v_x, v_y, φ, ω, r_x, r_y, window, why)``:
    the flight state at the event, (r_x, r_y) the CM → vertex k offset (WC_ARM), ``window`` (s) P's
    departure window (WC_FLIGHT), ``why`` the reason of WC_REFUSE.
    """
    cp = math.cos(phi)
    sp = math.sin(phi)
    rx = cp * w[j, 0] - sp * w[j, 1]
    ry = sp * w[j, 0] + cp * w[j, 1]
    lj = math.hypot(rx, ry)
    th = math.atan2(-ry, -rx)
    phi_off = phi - th
    yp = y + ry
    vp = vy + om * rx
    thd = om
    fill_wall_vertices(th, phi, w, j, wv)
    slack = sink_slack(x, y, phi, w, arm_skip, h)
    from_slip = False
    ev = EV_LIFT_OFF
    k = -1
    for _ in range(max_events):
        mode, sig = wall_select(th, thd, vp, lj, rho2, gx, gn, mu_w, from_slip)
        if mode == -2:
            return _out(WC_INCONSISTENT, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_NONE)
        if mode == -1:
            ev = EV_LIFT_OFF
            break
        ev, k, yp, th, vp, thd, t = wall_phase(yp, th, vp, thd, mode == W_STICK, sig, t, lj, rho2, gx, gn, mu_w, h,
                                               top, wv, arm_skip, arm_skip_until, slack, L, phi_off, max_steps, traj,
                                               ts, rec)
        if ev == EV_STICK:
            from_slip = False
            continue
        if ev == EV_SLIP:
            from_slip = True
            continue
        break
    else:
        return _out(WC_CAP, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_NONE)
    if ev == EV_LIFT_OFF:
        c = math.cos(th)
        s = math.sin(th)
        win = departure_window(-lj * s, lj * c, thd, gx, lj, abs(gx) + gn)
        if win <= 0.0:  # N = 0 with no strict departure: a tangency this mode cannot resolve
            return _out(WC_REFUSE, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_WALL_SLIDE)
        return _out(WC_FLIGHT, -1, t, L, yp, th, vp, thd, lj, phi_off, w, win, WHY_NONE)
    if ev == EV_ARM:
        if k == j:
            return _out(WC_REFUSE, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_CORNER)
        return _out(WC_ARM, k, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_NONE)
    if ev == EV_TOP:
        return _out(WC_REFUSE, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_WALL_TOP)
    if ev == EV_EDGE:
        return _out(WC_REFUSE, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_WALL_EDGE)
    if ev == EV_INCONSISTENT:
        return _out(WC_INCONSISTENT, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_NONE)
    return _out(WC_CAP, -1, t, L, yp, th, vp, thd, lj, phi_off, w, 0.0, WHY_NONE)  # EV_STEP_CAP


@njit(cache=True)
def _out(res, k, t, L, yp, th, vp, thd, lj, phi_off, w, win, why):
    """The flight state of P on the face at (y_P, θ, ẏ_P, θ̇), and vertex k's offset from the CM."""
    c = math.cos(th)
    s = math.sin(th)
    phi = th + phi_off
    rx = 0.0
    ry = 0.0
    if k >= 0:
        cp = math.cos(phi)
        sp = math.sin(phi)
        rx = cp * w[k, 0] - sp * w[k, 1]
        ry = sp * w[k, 0] + cp * w[k, 1]
    return (res, k, t, L + lj * c, yp + lj * s, -lj * s * thd, vp + lj * c * thd, phi, thd, rx, ry, win, why)

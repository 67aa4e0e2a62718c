"""The moving-arm phase: one polygon on an arm that follows θ(t), integrated in the arm frame.

Modes (a contact set and its tangential mode, :mod:`.dynamics`): FLIGHT (no contact), a PIVOT on
one vertex and a side FLAT on two, each sticking (tmode 0) or sliding (σ = ±1, the slip
velocity's sign). Every mode is integrated by classical RK4 on the full state (x, y, φ, v_x, v_y, ω)
with the mode's constrained accelerations (:func:`.dynamics.solve`), then projected back onto the
contact constraints (gap 0, normal velocity 0; sticking: the contact point fixed) — the projection
only removes the integrator's drift. Steps are at most ``dt`` (s) and never straddle a break of
θ̈ (:attr:`.profile.ArmMotion.breaks`; the arm is evaluated at the left limit there).

Guards, checked at each step's end and located by bisection on the RK4 step length (the RK4
step is the interpolant) to 2⁻⁶⁰ of the step (≲ 1e-19 s):

``lift``   an active contact's normal force N_j reaches 0;
``slip``   sticking: |T| reaches μ ΣN;
``stick``  sliding: the slip velocity reaches 0;
``touch``  an inactive vertex reaches the line (gap < −1e-12 m);
``leave``  a contact passes x ≤ −back or x > length (BEHIND_JOINT / OFF_END).

Resets: ``touch`` in FLIGHT — the single-vertex impact law of the static automaton
(:func:`~throwmap.kernels.rigid_body.impact.coulomb_impact`, option ``impact_law``); ``touch`` of the
second vertex of a side while pivoting — the static automaton's ``land_side`` law (the impulse at the
landing vertex alone if the pivot then lifts, else both vertices stop: v_y = ω = 0, a friction
impulse ≤ μ J_n on v_x; below :data:`V_ZENO` both stop at once, the Zeno limit of rocking); a jump of the arm's rate at a break (FiniteThrow's start and stop,
RecoilThrow's return) changes the arm-frame velocity by −Δθ̇ ẑ × r and the spin by −Δθ̇, and a contact
then driven into the line takes the same impact laws. Impacts are instantaneous, so the laws apply
in the arm frame unchanged (the arm is kinematic: its velocity field is continuous through them).

After every event the next mode is selected (:func:`select`): the first consistent one of flat
stick, flat slide, pivot stick, pivot slide, flight (normal forces ≥ 0, sticking inside the cone,
a starting slide accelerating in its sense, vertices on the line not pulled into it, a sliding vertex's
effective mass D > 0); none: status INCONSISTENT where a sliding vertex had D ≤ 0 (Painlevé), else
UNRESOLVED. μ = ∞ is taken as :data:`~..modes.MU_SKID` in the contact modes (as the static automaton's
sliding pivot: a contact slips only as its normal force vanishes), μ itself in the impact laws.

The phase ends (:func:`run_phase` returns) once the arm is at rest (t ≥ duration) and the part is
in a state the static automaton starts from: FLIGHT with every vertex ≥ 1 nm above the line, a
PIVOT, or FLAT, sticking at rest or sliding (:mod:`.handover`).
"""

from __future__ import annotations

import math

import numpy as np

from .. import impact as _impact
from ...codes import BEHIND_JOINT, INCONSISTENT, OFF_END, OK, UNRESOLVED
from ..modes import MU_SKID
from .dynamics import applied, gaps, offsets, solve

__all__ = ["Phase", "run_phase", "select", "N_BISECT", "WHY_EVENTS", "WHY_STEPS", "WHY_NO_MODE", "WHY_LAND"]

N_BISECT = 60
"""Bisection steps locating a guard inside one RK4 step."""
GAP_TOUCH = 1e-12
"""A vertex touches when its gap falls below −GAP_TOUCH (m)."""
ON_GAP = 1e-9
"""A vertex within ON_GAP (m) of the line whose normal velocity is within ±ON_VEL (m/s) is on the line (one
approaching faster touches later: guard ``touch``)."""
ON_VEL = 1e-7
CLEAR_GAP = 1e-9
"""FLIGHT is handed over once every vertex is CLEAR_GAP (m) above the line."""
SLIP_ZERO = 1e-12
"""|slip velocity| (m/s) below which a contact may stick."""
N_TOL = 1e-9
"""Tolerance (m/s²) of the consistency tests on forces and accelerations."""
V_ZENO = 1e-4
"""A side landing whose rocking speeds |v_y| + |ω| ℓ (relative to the arm; a slide along it, v_x, is kept) are below
V_ZENO √(g ℓ) (≈ 50 µm/s) stops both vertices
(the Zeno limit of rocking on the moving arm: measured, the B-alone impacts decay by ≈ 0.25 per landing and then
stall near 3 µm/s, where the arm's drive between landings adds what each landing removes)."""

# reasons of an UNRESOLVED throw (record WHY), moving-arm phase
WHY_EVENTS = 101  # more than max_events events while the arm moves (e.g. rocking on the moving arm)
WHY_STEPS = 102  # more than max_steps integration steps
WHY_NO_MODE = 103  # no consistent contact mode (after an event)
WHY_LAND = 104  # a vertex not adjacent to the pivot touched (degenerate polygon)


class Phase:
    """The moving-arm phase's state: time ``t`` (s), state ``s`` (6,), contact set ``act`` and ``tmode``,
    the sticking anchor (m), the last side, counts of impacts/lift-offs/slips, and the end result."""

    def __init__(self, t, s, side):
        self.t = float(t)
        self.s = np.array(s, dtype=float)
        self.act = ()
        self.tmode = 0
        self.anchor = 0.0
        self.side = int(side)
        self.flown = False
        self.n_impacts = 0
        self.n_lift = 0
        self.n_slips = 0
        self.status = OK
        self.why = 0
        self.log = []  # (t, act, tmode, state) at every mode selection
        self.trace = None  # a list: (t, state) after every step is appended to it


class _Ctx:
    def __init__(self, body, motion, g, alpha, h, mu, law, length, back):
        self.body, self.motion, self.g, self.alpha, self.h = body, motion, g, alpha, h
        self.mu, self.law, self.length, self.back = mu, law, length, back
        # the contact modes take μ = ∞ as MU_SKID (a contact slips only as N → 0); impacts take μ itself
        self.mu_s = MU_SKID if math.isinf(mu) else mu
        self.painleve = False  # the last selection rejected a sliding vertex for D ≤ 0


def _field(c: _Ctx, t, s, t_clip):
    th, thd, thdd = c.motion.state(min(t, t_clip))
    return applied(s, c.g, c.alpha + th, thd, thdd)


def _deriv(c, t, s, act, tmode, t_clip):
    a, _N, _T, _ok = solve(c.body, s, _field(c, t, s, t_clip), act, tmode, c.mu_s)
    return np.array([s[3], s[4], s[5], a[0], a[1], a[2]])


def _rk4(c, t, s, dt, act, tmode, anchor, t_clip):
    if len(act) == 2 and tmode == 0:  # flat and sticking: the part rides the arm, nothing moves in its frame
        return s.copy()
    k1 = _deriv(c, t, s, act, tmode, t_clip)
    k2 = _deriv(c, t + 0.5 * dt, s + 0.5 * dt * k1, act, tmode, t_clip)
    k3 = _deriv(c, t + 0.5 * dt, s + 0.5 * dt * k2, act, tmode, t_clip)
    k4 = _deriv(c, t + dt, s + dt * k3, act, tmode, t_clip)
    out = s + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    _project(c, out, act, tmode, anchor)
    return out


def _project(c, s, act, tmode, anchor):
    """Put ``s`` back on the constraints of ``act``: the integrator's drift only (m, rad)."""
    body = c.body
    if len(act) == 2:
        k = body.side_of(act[0], act[1])
        b = body.beta[k]
        s[2] = b + 2.0 * math.pi * round((s[2] - b) / (2.0 * math.pi))
        s[1] = c.h + body.d[k]
        s[4] = 0.0
        s[5] = 0.0
        if tmode == 0:
            s[0] = anchor
            s[3] = 0.0
    elif len(act) == 1:
        j = act[0]
        rx, ry = offsets(body, s[2])
        s[1] = c.h - ry[j]
        s[4] = -s[5] * rx[j]
        if tmode == 0:
            s[0] = anchor - rx[j]
            s[3] = s[5] * ry[j]


def _slip(s, ry, j):
    return s[3] - s[5] * ry[j]


def _guards(c, t, s, act, tmode, t_clip):
    """Guard values (≥ 0 while the mode holds) and their events: ('lift', j), ('slip',), ('stick',),
    ('touch', j), ('leave', status)."""
    out = []
    g, rx, ry = gaps(c.body, s, c.h)
    if act:
        _a, N, T, _ok = solve(c.body, s, _field(c, t, s, t_clip), act, tmode, c.mu_s)
        for i, j in enumerate(act):
            out.append((N[i], ("lift", j)))
            px = s[0] + rx[j]
            out.append((px + c.back, ("leave", BEHIND_JOINT)))
            out.append((c.length - px, ("leave", OFF_END)))
        if tmode == 0:
            out.append((c.mu_s * float(np.sum(N)) - abs(T), ("slip",)))
        if tmode != 0:
            out.append((tmode * _slip(s, ry, act[0]), ("stick",)))
    for j in range(c.body.n):
        if j not in act:
            out.append((g[j] + GAP_TOUCH, ("touch", j)))
    return out


def _fired(gs):
    return [ev for v, ev in gs if v < 0.0]


def _consistent(c, t, s, act, tmode, on, t_clip):
    a, N, T, ok = solve(c.body, s, _field(c, t, s, t_clip), act, tmode, c.mu_s)
    if not ok:
        c.painleve = c.painleve or (tmode != 0 and len(act) == 1)
        return False
    if np.any(N < -N_TOL):
        return False
    rx, ry = offsets(c.body, s[2])
    om = s[5]
    if act:
        if tmode == 0 and abs(T) > c.mu_s * float(np.sum(N)) + N_TOL:
            return False
        j = act[0]
        if tmode != 0 and abs(_slip(s, ry, j)) <= SLIP_ZERO:
            at = a[0] - a[2] * ry[j] - om * om * rx[j]
            if tmode * at < -N_TOL:
                return False
    for j in on:
        if j not in act and a[1] + a[2] * rx[j] - om * om * ry[j] < -N_TOL:
            return False
    return True


def select(c, p: Phase, t_clip, exclude=None) -> bool:
    """Choose the contact mode at ``p``'s state (module docstring), other than ``exclude`` (the mode whose
    guard just fired); False: none is consistent."""
    body, s = c.body, p.s
    g, rx, ry = gaps(body, s, c.h)
    on = [j for j in range(body.n) if g[j] <= ON_GAP and abs(s[4] + s[5] * rx[j]) <= ON_VEL]
    cands = []
    if len(on) >= 2:
        for a_ in range(len(on)):
            for b_ in range(a_ + 1, len(on)):
                k = body.side_of(on[a_], on[b_])
                if k >= 0 and abs(s[5]) <= 1e-9:
                    u = s[3]
                    modes = (0, 1, -1) if abs(u) <= SLIP_ZERO else (1 if u > 0 else -1,)
                    cands += [((on[a_], on[b_]), m) for m in modes]
    for j in on:
        u = _slip(s, ry, j)
        modes = (0, 1, -1) if abs(u) <= SLIP_ZERO else (1 if u > 0 else -1,)
        cands += [((j,), m) for m in modes]
    cands.append(((), 0))
    c.painleve = False
    for act, tm in cands:
        if exclude is not None and (act, tm) == exclude:
            continue
        trial = s.copy()
        anchor = s[0] if len(act) == 2 else (s[0] + rx[act[0]] if act else 0.0)
        if tm == 0 and act:
            if len(act) == 1:
                trial[3] = trial[5] * ry[act[0]]
            else:
                trial[3] = 0.0
        _project(c, trial, act, tm, anchor)
        if _consistent(c, p.t, trial, act, tm, on, t_clip):
            if tm != 0 and (p.tmode == 0 or p.act != act):
                p.n_slips += 1
            if len(act) == 2:
                p.side = body.side_of(act[0], act[1])
            p.s, p.act, p.tmode, p.anchor = trial, act, tm, anchor
            p.log.append((p.t, act, tm, trial.copy()))
            return True
    return False


def _impact_vertex(c, p: Phase, j):
    """Single-vertex plastic impact at vertex ``j`` (the static automaton's law)."""
    s = p.s
    rx, ry = offsets(c.body, s[2])
    vx, vy, w, *_rest = _impact.coulomb_impact(s[3], s[4], s[5], rx[j], ry[j], c.body.rho2, c.mu, c.law)
    kind = _rest[2]
    p.n_impacts += 1
    if kind == _impact.IMP_INCONSISTENT:
        return False
    s[3], s[4], s[5] = vx, vy, w
    return True


def _impact_flat(c, p: Phase, side):
    """Both vertices of ``side`` stop normal motion: v_y = ω = 0, then a friction impulse ≤ μ J_n on v_x
    (the static automaton's land_side law)."""
    s = p.s
    jn = -s[4] if s[4] < 0.0 else 0.0
    jt = -s[3]
    if abs(jt) > c.mu * jn:
        jt = -c.mu * jn if s[3] > 0.0 else c.mu * jn
    s[3] += jt
    s[4] = 0.0
    s[5] = 0.0
    p.side = side
    p.n_impacts += 1


def _land(c, p: Phase, j) -> bool:
    """Reset ``touch`` of vertex ``j``: from FLIGHT the single-vertex impact, while pivoting on A (or in
    FLIGHT with a neighbour A of ``j`` still on the line) the land_side law. False: the throw ends."""
    body = c.body
    if not p.act:
        g, _rx, _ry = gaps(body, p.s, c.h)
        near = [a for a in ((j + 1) % body.n, (j - 1) % body.n) if g[a] <= ON_GAP]
        if not near:
            if not _impact_vertex(c, p, j):
                p.status = INCONSISTENT
                return False
            return True
        a = near[0]  # a neighbour is (still) on the line: the side lands, as while pivoting on it
    else:
        a = p.act[0]
    k = body.side_of(a, j)
    if len(p.act) > 1 or k < 0:
        p.status, p.why = UNRESOLVED, WHY_LAND
        return False
    keep = p.s.copy()
    sv = p.s
    if abs(sv[4]) + abs(sv[5]) * body.lmax < V_ZENO * math.sqrt(c.g * body.lmax):
        _impact_flat(c, p, k)  # rocking at a stall: both vertices stop (Zeno limit)
        return True
    if _impact_vertex(c, p, j):
        rx, _ry = offsets(body, p.s[2])
        if p.s[4] + p.s[5] * rx[a] > 0.0:  # the impulse at B alone lifts A
            return True
        p.n_impacts -= 1
    p.s = keep
    _impact_flat(c, p, k)
    return True


def _rate_jump(c, p: Phase, dW) -> bool:
    """The arm's rate jumps by ``dW`` (rad/s): arm-frame velocity −dW ẑ × r, spin −dW; contacts driven into
    the line take the impact laws. False: the throw ends."""
    s = p.s
    s[3] += dW * s[1]
    s[4] -= dW * s[0]
    s[5] -= dW
    g, rx, _ry = gaps(c.body, s, c.h)
    on = tuple(j for j in range(c.body.n) if g[j] <= ON_GAP)
    if not on:
        return True
    into = [j for j in on if s[4] + s[5] * rx[j] < 0.0]
    if len(on) == 2 and len(into) == 2:
        _impact_flat(c, p, c.body.side_of(*on))
    elif into:
        # one vertex driven in (a pivot, or a flat side whose other vertex leaves): its impact
        if not _impact_vertex(c, p, into[0]):
            p.status = INCONSISTENT
            return False
        rx, _ry = offsets(c.body, s[2])
        other = [j for j in on if j != into[0]]
        if other and p.s[4] + p.s[5] * rx[other[0]] < 0.0:
            _impact_flat(c, p, c.body.side_of(*on))
    return True


def run_phase(p: Phase, body, motion, g, alpha, h, mu, law, length, back, dt=5e-5, max_events=2000,
              max_steps=400_000):
    """Integrate ``p`` (a part at rest relative to the arm at t = 0, or any state) until the handover
    (module docstring) or a terminal status. Returns ``p`` with ``status`` OK when handed over."""
    c = _Ctx(body, motion, g, alpha, h, mu, law, length, back)
    T = motion.duration
    breaks = [b for b in motion.breaks]
    ib = 0
    events = 0
    steps = 0
    # the jump at t = 0 (e.g. FiniteThrow) and the first mode
    while ib < len(breaks) and breaks[ib] <= p.t:
        dW = motion.rate_jump(breaks[ib])
        if dW != 0.0 and not _rate_jump(c, p, dW):
            return p
        ib += 1
    t_next = breaks[ib] if ib < len(breaks) else math.inf
    if not select(c, p, math.nextafter(t_next, -math.inf)):
        return _no_mode(c, p)
    while True:
        if p.t >= T and _handover_ready(c, p):
            return p
        steps += 1
        if steps > max_steps:
            p.status, p.why = UNRESOLVED, WHY_STEPS
            return p
        t_next = breaks[ib] if ib < len(breaks) else math.inf
        t_clip = math.nextafter(t_next, -math.inf)
        rate = abs(p.s[5]) + abs(motion.state(p.t)[1]) + 1.0
        h_step = min(dt, 0.02 / rate, t_next - p.t)
        s1 = _rk4(c, p.t, p.s, h_step, p.act, p.tmode, p.anchor, t_clip)
        fired = _fired(_guards(c, p.t + h_step, s1, p.act, p.tmode, t_clip))
        if not fired:
            p.t += h_step
            p.s = s1
            if p.trace is not None:
                p.trace.append((p.t, s1))
            if p.t >= t_next:
                p.t = t_next
                dW = motion.rate_jump(t_next)
                ib += 1
                if dW != 0.0:
                    if not _rate_jump(c, p, dW):
                        return p
                    if not select(c, p, _clip(breaks, ib)):
                        return _no_mode(c, p)
            continue
        # locate the first guard by bisection on the step length
        lo, hi = 0.0, h_step
        s_hi = s1
        for _ in range(N_BISECT):
            mid = 0.5 * (lo + hi)
            sm = _rk4(c, p.t, p.s, mid, p.act, p.tmode, p.anchor, t_clip)
            f = _fired(_guards(c, p.t + mid, sm, p.act, p.tmode, t_clip))
            if f:
                hi, s_hi, fired = mid, sm, f
            else:
                lo = mid
        p.t += hi
        p.s = s_hi
        events += 1
        if events > max_events:
            p.status, p.why = UNRESOLVED, WHY_EVENTS
            return p
        old = (p.act, p.tmode)
        ev = fired[0]
        for e in fired:  # an exit or an impact first
            if e[0] == "leave":
                ev = e
                break
            if e[0] == "touch":
                ev = e
        if ev[0] == "leave":
            p.status = ev[1]
            return p
        if ev[0] == "touch":
            if not _land(c, p, ev[1]):
                return p
        elif ev[0] == "lift":
            p.n_lift += 1
        elif ev[0] == "stick":
            rx, ry = offsets(body, p.s[2])
            p.s[3] = p.s[5] * ry[p.act[0]] if len(p.act) == 1 else 0.0
        if not select(c, p, t_clip, None if ev[0] == "touch" else old):
            return _no_mode(c, p)
        if not p.act:
            p.flown = True


def _no_mode(c, p: Phase) -> Phase:
    """No consistent mode: INCONSISTENT where a sliding vertex had D ≤ 0 (Painlevé, as the static automaton),
    else UNRESOLVED (WHY_NO_MODE)."""
    if c.painleve:
        p.status = INCONSISTENT
    else:
        p.status, p.why = UNRESOLVED, WHY_NO_MODE
    return p


def _clip(breaks, ib):
    return math.nextafter(breaks[ib], -math.inf) if ib < len(breaks) else math.inf


def _handover_ready(c, p: Phase) -> bool:
    """Arm at rest: FLIGHT clear of the line, a PIVOT, or FLAT (module docstring)."""
    if not p.act:
        g, _rx, _ry = gaps(c.body, p.s, c.h)
        return bool(np.all(g >= CLEAR_GAP))
    return True  # a pivot, or a side flat (sticking at rest or sliding)

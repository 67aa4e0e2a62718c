"""One "rigid_body" throw by a moving arm: the moving-arm phase, then the static automaton.

:func:`throw_moving` starts the part at rest on the arm (flat on ``side`` at x0, at the arm's
angle α + θ(0)), runs :func:`.phase.run_phase` while the arm moves, and once the arm is at rest
at α hands the state to the validated static automaton (:mod:`throwmap.kernels.rigid_body.automaton`):

* FLIGHT clear of the line → :func:`~..automaton.throw_from_state` (kind 0), the first contact's
  record written there if the part had not yet touched the arm since it left it;
* a PIVOT → :func:`~..automaton.throw_from_state` (kind 1): θ = angle of pivot → CM, its slip velocity;
  the automaton selects stick / slide / lift as after an impact;
* FLAT sticking at rest → :func:`~..automaton.throw_one_rigid_body` with ω = 0 (rest, or the tip of
  an unstable side, exactly as a throw with ω = 0);
* FLAT sliding → the static flat slide (:func:`~..flat.settle` on a tilted arm, :func:`~..flat.slide_away`
  at μ = 0, else :func:`~..flat.flat_slide` and :func:`~..flat.rest`), as ``land_side`` ends a landing.

What the handover cannot take ends the throw as status UNRESOLVED with a reason (record WHY,
:data:`~..modes.WHY_MESSAGES`); the moving phase's own terminal statuses (BEHIND_JOINT,
OFF_END, INCONSISTENT) are returned as they are. Records: the static automaton's, with the moving
phase's impacts, lift-offs and slips added to N_IMPACTS, N_LIFTOFFS, N_SLIPS; T_REST is from t = 0.
"""

from __future__ import annotations

import math

import numpy as np

from ... import codes as C
from ...rows import start_record
from ..automaton import throw_from_state, throw_one_rigid_body
from ..flat import flat_slide, rest, settle, slide_away
from ..inputs import arm_arrays, part_arrays, run_limits
from ..trajectory import clear
from .dynamics import Body, offsets
from .phase import Phase, run_phase
from .profile import arm_motion

__all__ = ["throw_moving", "start_pose"]


def start_pose(part, h, x0, side):
    """The arm-frame state (x, y, φ, 0, 0, 0) of ``part`` flat on ``side`` with its CM at ``x0`` (m)."""
    return np.array([x0, h + part.d[side], part.beta[side], 0.0, 0.0, 0.0])


def throw_moving(part, arm, x0, side, realisation, *, alpha=0.0, law=0, stable=None, tol=1e-14, max_iter=100_000,
                 max_events=10_000, dt=5e-5):
    """One throw of ``part`` resting at ``(x0, side)`` by the arm motion of ``realisation`` (not an impulse).

    ``alpha`` (rad) the arm's rest angle, ``law`` the impact-law code, ``stable`` the stable-side table
    at α; ``dt`` (s) the moving phase's largest RK4 step. Returns ``(x, side, status, record)`` as the
    model's kernels."""
    motion = arm_motion(realisation)
    rho2 = part.radius_of_gyration ** 2
    body = Body(part.w, rho2, part.d, part.beta)
    length = arm.length_or_inf
    rec = np.full(C.NREC, np.nan)
    p = Phase(0.0, start_pose(part, arm.h, x0, side), side)
    run_phase(p, body, motion, arm.g, float(alpha), arm.h, arm.mu, law, length, arm.back, dt=dt)
    if p.status != C.OK:
        rec[:] = np.nan
        rec[C.WHY] = p.why
        rec[C.CAP_HIT] = 0.0
        _counts(rec, p)
        return float(p.s[0]), p.side, int(p.status), rec
    args = (part_arrays(part, stable), arm_arrays(arm.h, arm.g, alpha, length, arm.back, arm.mu, law),
            run_limits(tol, max_iter, max_events))
    no_traj = np.empty((0, 4))
    s = p.s
    if len(p.act) == 2 and p.tmode == 0:  # flat, sticking, at rest: the static automaton's rest (or tip) from ω = 0
        xn, kn, st = throw_one_rigid_body(float(s[0]), p.side, 0.0, *args, rec, no_traj, 0.0)
        rec[C.T_REST] = p.t + (0.0 if math.isnan(rec[C.T_REST]) else rec[C.T_REST])
    elif len(p.act) == 2:  # flat, sliding: the static automaton's flat slide (land_side's, after both vertices stop)
        xn, kn, st = _flat_slide(part, arm, p, float(alpha), length, rec)
    else:
        start = np.zeros(14)
        start[1:8] = p.t, s[0], s[1], s[3], s[4], s[5], s[2]
        start[8] = p.side
        start[13] = 0.0 if p.n_impacts else 1.0
        if p.act:
            j = p.act[0]
            rx, ry = offsets(body, s[2])
            start[0] = 1.0
            start[9] = j
            start[10] = s[0] + rx[j]
            start[11] = math.atan2(-ry[j], -rx[j])
            start[12] = 0.0 if p.tmode == 0 else s[3] - s[5] * ry[j]
        xn, kn, st = throw_from_state(start, *args, rec, no_traj, 0.0)
    _counts(rec, p)
    rec[C.E_RELEASE] = math.nan  # (the automaton's release energy is not this throw's)
    return float(xn), int(kn), int(st), rec


def _flat_slide(part, arm, p, alpha, length, rec):
    """A side sliding flat on the arm at rest: :func:`~..flat.settle` (α ≠ 0), :func:`~..flat.slide_away` (μ = 0,
    for ever) or :func:`~..flat.flat_slide` and :func:`~..flat.rest`, as land_side ends a landing."""
    start_record(rec)
    traj = np.empty((0, 4))
    ts = np.zeros(3)
    clear(traj, ts, 0.0)
    s, k = p.s, p.side
    if alpha != 0.0:
        x, k, st, t = settle(float(s[0]), float(s[3]), p.t, k, arm.mu, arm.g, alpha, arm.h, part.d, part.uL, part.uR,
                             part.beta, length, arm.back, float(s[2]), traj, ts, rec)
        return x, k, st
    if arm.mu == 0.0:
        x, st, t = slide_away(float(s[0]), float(s[3]), p.t, k, part.uL, part.uR, length, arm.back, float(s[1]),
                              float(s[2]), traj, ts, rec)
        return x, k, st
    x, t = flat_slide(float(s[0]), float(s[3]), p.t, arm.mu, arm.g, float(s[1]), float(s[2]), traj, ts, rec)
    return rest(x, k, t, arm.h, arm.g, part.d, part.uL, part.uR, part.beta, length, arm.back, float(s[2]), traj, ts, rec)


def _counts(rec, p):
    for col, v in ((C.N_IMPACTS, p.n_impacts), (C.N_LIFTOFFS, p.n_lift), (C.N_SLIPS, p.n_slips)):
        rec[col] = (0.0 if math.isnan(rec[col]) else rec[col]) + v

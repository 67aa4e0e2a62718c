"""Animatable time histories of throws: one throw, or successive throws (an orbit), as a :class:`Trajectory`.

:func:`throw_trajectory` asks the model (from the registry, :mod:`throwmap.models`) for
the recorded motion of one throw — the analytic kernels record their own rows, the
engines sample their simulation — and :func:`orbit_trajectory` strings successive
throws together with a short still pause between them. Any model whose
``features.trajectory`` is set can be drawn; the others are refused naming ``model``.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InvalidStateError, shown
from ..models import DEFAULT_MODEL, model_names
from ..system.arm import Arm
from ..system.part import Part
from ..budget import Limits
from .orbit import ThrowGuard, planned_throws, throw_rates
from ..records.outcome import ThrowOutcome
from ..system.starts import check_start, tilted_rest_reason
from .throw import prepare
from ..records.trajectory import DEFAULT_DT, Trajectory, check_dt, drawn_length

__all__ = ["throw_trajectory", "paper_trajectory", "paper_throw_trajectory", "orbit_trajectory", "trajectory_models",
           "DEFAULT_DT", "TRAJECTORY_BYTES_PER_THROW"]

TRAJECTORY_BYTES_PER_THROW = 48_000
"""Memory an orbit's trajectory needs per throw, bytes: ≈ 130 samples (the throw at ``dt`` = 1/240 s and its
pause) of ≈ 120 bytes kept (≈ 16 kB measured), doubled while successive throws are joined, plus one throw's work."""


def trajectory_models() -> tuple[str, ...]:
    """The registered models that can record a throw's motion."""
    from ..models import get_model

    return tuple(n for n in model_names() if get_model(n).features.trajectory)


def _grid(t0: float, t1: float, dt: float) -> np.ndarray:
    """Times t0, t0 + dt, … and exactly t1 (at least the two ends)."""
    if t1 <= t0:
        return np.array([t0, t0])
    n = max(1, int(math.ceil((t1 - t0) / dt - 1e-9)))
    g = t0 + dt * np.arange(n + 1)
    g[-1] = t1
    return g


def throw_trajectory(part: Part, arm: Arm, x: float, side: int, omega: float, model: str = DEFAULT_MODEL, *,
                     dt: float = DEFAULT_DT, fixtures=(), alpha: float = 0.0, options=None,
                     **option_kw) -> tuple[ThrowOutcome, Trajectory]:
    """One throw of ``model`` with its motion sampled every ``dt`` s (and at every event).

    Returns ``(ThrowOutcome, Trajectory)``; the outcome equals :func:`throwmap.throw` with the
    same arguments. Keywords as :func:`throwmap.throw`; the engines sample at their own
    ``record_dt`` (:class:`throwmap.engine.EngineSettings`) instead of ``dt``. A start that is not
    at rest on a tilted arm (:func:`~throwmap.system.starts.tilted_rest_reason`) is refused naming ``side``.
    """
    m, system, opts = prepare(model, arm, fixtures, alpha, options, option_kw)
    if not m.features.trajectory:
        raise InvalidStateError("model", f"model {m.name!r} records no trajectory "
                                         f"(choose from {', '.join(trajectory_models())})")
    dt = check_dt(dt)
    x0, k0, om = check_start(part, arm, x, side, omega)
    if system.alpha != 0.0:  # throw() returns INVALID_START there; a trajectory has nothing to show
        reason = tilted_rest_reason(part, arm, k0, system.alpha, m.features.friction)
        if reason:
            raise InvalidStateError("side", f"not at rest on the tilted arm: {reason}")
    return m.trajectory(part, system, x0, k0, om, opts, dt)


def paper_throw_trajectory(part: Part, arm: Arm, x: float, side: int, omega: float, *, dt: float = DEFAULT_DT,
                           max_impacts: int | None = None) -> tuple[ThrowOutcome, Trajectory]:
    """:func:`throw_trajectory` of model "paper" (``max_impacts``: None for its default)."""
    kw = {} if max_impacts is None else {"max_impacts": max_impacts}
    return throw_trajectory(part, arm, x, side, omega, "paper", dt=dt, **kw)


def paper_trajectory(part: Part, arm: Arm, x: float, side: int, omega: float, *, dt: float = DEFAULT_DT,
                     max_impacts: int | None = None) -> Trajectory:
    """Time history of one "paper"-model throw (paper Sec. III-B–C) from rest at ``(x, side)``.

    One part, ``source="paper"``; the first sample is the resting start at t = 0 (the
    release), the last the kernel's resting configuration (or the escape). The arm stays
    horizontal (an impulsive throw); an unbounded arm is drawn a little longer than the
    part's reach. ``meta["outcomes"]`` holds the :class:`ThrowOutcome` of
    ``throw(..., model="paper")``; events and contacts as
    :func:`throwmap.models.paper.record_trajectory`.
    """
    return paper_throw_trajectory(part, arm, x, side, omega, dt=dt, max_impacts=max_impacts)[1]


def _pause(traj: Trajectory, seconds: float, dt: float) -> Trajectory:
    """The last sample of ``traj`` held still for ``seconds`` (starting at t = 0)."""
    ts = _grid(0.0, seconds, dt)
    m = ts.size
    return Trajectory(
        t=ts,
        arm_angle=np.full(m, traj.arm_angle[-1]),
        poses=np.repeat(traj.poses[-1:], m, axis=0),
        parts=traj.parts, h=traj.h, length=traj.length, fixtures=traj.fixtures,
        contacts=(traj.contacts[-1],) * m if traj.contacts else (),
        events=(), source=traj.source,
    )


def _dedupe(traj: Trajectory) -> Trajectory:
    """Drop samples whose time repeats the previous one (the joints :meth:`Trajectory.concat` makes)."""
    keep = np.ones(traj.n_samples, dtype=bool)
    keep[1:] = np.diff(traj.t) > 0.0
    if keep.all():
        return traj
    # keep the later of two samples at one time (the start of the next piece)
    keep = np.ones(traj.n_samples, dtype=bool)
    keep[:-1] = np.diff(traj.t) > 0.0
    idx = np.flatnonzero(keep)
    contacts = tuple(traj.contacts[i] for i in idx) if len(traj.contacts) == traj.n_samples else traj.contacts
    return Trajectory(traj.t[idx], traj.arm_angle[idx], traj.poses[idx], traj.parts, traj.h, traj.length,
                      traj.fixtures, contacts, traj.events, traj.source, dict(traj.meta))


def orbit_trajectory(part: Part, arm: Arm, x: float, side: int, omegas, n: int | None = None,
                     model: str = DEFAULT_MODEL, pause: float = 0.3, *, dt: float = DEFAULT_DT, progress=None,
                     limits: Limits | None = None, **throw_kw) -> Trajectory:
    """Successive throws from ``(x, side)`` as one trajectory, with a still ``pause`` (s) between throws.

    ``omegas`` is one release rate (then ``n`` throws) or one per throw (as
    :func:`throwmap.iterate`). Stops after a throw that escapes (leaves the arm or
    does not come to rest); that throw is drawn. ``model`` is any model that records
    trajectories (:func:`trajectory_models`); ``throw_kw`` go to :func:`throw_trajectory`
    (``fixtures``, ``alpha``, model options). ``progress``, if given, is called with the number
    of throws done after each. ``meta["outcomes"]`` holds each throw's
    :class:`ThrowOutcome`; ``meta["throw_starts"]`` each release time (s).

    Work guard (:mod:`throwmap.budget`, as :func:`throwmap.iterate`): the memory
    (:data:`TRAJECTORY_BYTES_PER_THROW` per throw at the default ``dt``) is checked
    before any throw, the time from the first throws; above ``limits`` (:class:`~throwmap.budget.Limits`)
    it is refused with one line on ``n``, unless ``limits.force``.
    """
    planned = planned_throws(omegas, n, min_n=1)
    per_throw = TRAJECTORY_BYTES_PER_THROW * max(1.0, DEFAULT_DT / float(dt)) if isinstance(dt, (int, float)) \
        and math.isfinite(dt) and dt > 0 else TRAJECTORY_BYTES_PER_THROW
    gd = ThrowGuard("orbit trajectory", "n", planned, per_throw, limits,
                    hint="fewer throws (-n)")
    om = throw_rates(omegas, n, min_n=1)
    pause = float(pause)
    if not (math.isfinite(pause) and pause >= 0):
        raise InvalidStateError("pause", f"must be a finite time ≥ 0 (s), got {shown(pause)}")
    dt = check_dt(dt)
    from .session import open_session

    m, _, _ = prepare(model, arm, throw_kw.get("fixtures", ()), throw_kw.get("alpha", 0.0), throw_kw.get("options"),
                      {k: v for k, v in throw_kw.items() if k not in ("fixtures", "alpha", "options")})
    if not m.features.trajectory:
        raise InvalidStateError("model", f"model {m.name!r} records no trajectory "
                                         f"(choose from {', '.join(trajectory_models())})")
    session = open_session(part, arm, (x, side), model, **throw_kw)
    alpha = session.system.alpha
    if alpha != 0.0:  # a throw from there is INVALID_START; a trajectory has nothing to show
        reason = tilted_rest_reason(part, arm, session.states[0].side, alpha, m.features.friction)
        if reason:
            raise InvalidStateError("side", f"not at rest on the tilted arm: {reason}")
    traj = None
    outcomes = []
    starts = []
    for w in om:
        step = session.throw(float(w), record=dt)
        outcomes.append(step.outcome)
        gd.tick()
        piece = step.trajectory
        if piece is None:  # the rest left by the last throw is no start (it leans on a wall): nothing to draw
            if traj is None:
                raise InvalidStateError("x", step.message or "the start is not a rest of the map")
            break
        if traj is None:
            starts.append(0.0)
            traj = piece
        else:
            if pause > 0:
                traj = traj.concat(_pause(traj, pause, dt))
            starts.append(float(traj.t[-1]))
            traj = traj.concat(piece)
        if progress is not None:
            progress(len(outcomes))
        if not step.ok:
            break
    traj = _dedupe(traj)
    length = traj.length
    if arm.length is None and not traj.fixtures:  # an unbounded arm: draw it just past the part's reach
        length = drawn_length(arm, traj.poses, traj.parts)
    meta = dict(traj.meta)
    meta.update(outcomes=tuple(outcomes), throw_starts=tuple(starts), arm=arm, arm_unbounded=arm.length is None)
    return Trajectory(traj.t, traj.arm_angle, traj.poses, traj.parts, traj.h, length, traj.fixtures, traj.contacts,
                      traj.events, traj.source if len(om) == 1 else f"{traj.source} orbit", meta)

"""Animatable time histories of throws: one throw, or successive throws (an orbit), as a :class:`Trajectory`.

:func:`paper_trajectory` / :func:`paper_throw_trajectory` (model "paper") and
:func:`rigid_trajectory` (model "rigid_body") check the start and call
:func:`throwmap.throws.trajectories.kernel_trajectory` (the kernels record their own
rows); :func:`orbit_trajectory` strings successive throws of any model that
provides a trajectory together with a short still pause between them.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InvalidStateError
from ..models.paper import PaperOptions
from ..models.rigid_body import RigidBodyOptions
from ..system.arm import Arm
from ..system.part import Part
from .outcome import Status, ThrowOutcome
from .orbit import throw_rates
from .throw import check_start
from .trajectories import DEFAULT_DT, check_dt, drawn_length, kernel_trajectory
from .trajectory import Trajectory

__all__ = ["paper_trajectory", "paper_throw_trajectory", "rigid_trajectory", "orbit_trajectory",
           "trajectory_function", "DEFAULT_DT", "TRAJECTORY_MODELS"]

TRAJECTORY_MODELS = ("paper", "rigid_body", "engine")
"""Models :func:`orbit_trajectory` can render."""


def _grid(t0: float, t1: float, dt: float) -> np.ndarray:
    """Times t0, t0 + dt, … and exactly t1 (at least the two ends)."""
    if t1 <= t0:
        return np.array([t0, t0])
    n = max(1, int(math.ceil((t1 - t0) / dt - 1e-9)))
    g = t0 + dt * np.arange(n + 1)
    g[-1] = t1
    return g


def paper_throw_trajectory(part: Part, arm: Arm, x: float, side: int, omega: float, *, dt: float = DEFAULT_DT,
                           max_impacts: int | None = None) -> tuple[ThrowOutcome, Trajectory]:
    """Like :func:`paper_trajectory`, also returning the kernel's :class:`ThrowOutcome`."""
    dt = check_dt(dt)
    x0, k0, om = check_start(part, arm, x, side, omega)
    o = PaperOptions() if max_impacts is None else PaperOptions(max_impacts=max_impacts)
    return kernel_trajectory(part, arm, x0, k0, om, "paper", dt=dt, options=o)


def paper_trajectory(part: Part, arm: Arm, x: float, side: int, omega: float, *, dt: float = DEFAULT_DT,
                     max_impacts: int | None = None) -> Trajectory:
    """Time history of one "paper"-model throw from rest at ``(x, side)`` with release rate ``omega``.

    Parameters
    ----------
    part, arm : Part, Arm
        The arm stays horizontal (an impulsive throw); ``arm.length=None`` is drawn
        a little longer than the part's reach.
    x : float, m
        Resting CM position along the arm; ``side`` the stable side it rests on.
    omega : float, rad/s
        Release angular velocity (≥ 0).
    dt : float, s
        Sample interval (phase changes are sampled exactly in addition).
    max_impacts : int
        Impact cap (default: :class:`~throwmap.models.paper.PaperOptions`'s).

    Returns
    -------
    Trajectory
        One part, ``source="paper"``; the first sample is the resting start at t = 0
        (the release), the last the kernel's resting configuration (or the escape).
        ``meta["outcomes"]`` holds the :class:`ThrowOutcome` of
        ``throw(..., model="paper")``. Events and contacts as in
        :mod:`throwmap.throws.trajectories`.
    """
    return paper_throw_trajectory(part, arm, x, side, omega, dt=dt, max_impacts=max_impacts)[1]


def rigid_trajectory(part: Part, arm: Arm, x: float, side: int, omega: float, *,
                     dt: float = DEFAULT_DT) -> tuple[ThrowOutcome, Trajectory]:
    """One "rigid_body" throw with its motion sampled every ``dt`` s and at every event.

    Returns ``(ThrowOutcome, Trajectory)``; contacts are the vertices within 1 µm of
    the arm line at each sample. The outcome equals ``throw(..., model="rigid_body")``.
    """
    x0, k, om = check_start(part, arm, x, side, omega)
    return kernel_trajectory(part, arm, x0, k, om, "rigid_body", dt=dt, options=RigidBodyOptions())


# ------------------------------------------------------------------ orbits
def trajectory_function(model: str):
    """``f(part, arm, x, side, omega) -> (ThrowOutcome, Trajectory)`` for a model name.

    ``"paper"`` and ``"rigid_body"`` record their kernels' rows; ``"engine"``
    (:func:`throwmap.engine.engine_trajectory`) is imported on demand and raises
    :class:`ImportError` where it is not installed.
    """
    if model == "paper":
        return paper_throw_trajectory
    if model == "engine":
        from ..engine import engine_trajectory

        return engine_trajectory
    if model == "rigid_body":
        return rigid_trajectory
    raise InvalidStateError("model", f"cannot animate model {model!r} (choose from {', '.join(TRAJECTORY_MODELS)})")


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


def orbit_trajectory(part: Part, arm: Arm, x: float, side: int, omegas, n: int | None = None, model: str = "paper",
                     pause: float = 0.3, *, dt: float = DEFAULT_DT, progress=None) -> Trajectory:
    """Successive throws from ``(x, side)`` as one trajectory, with a still ``pause`` (s) between throws.

    ``omegas`` is one release rate (then ``n`` throws) or one per throw (as
    :func:`throwmap.iterate`). Stops after a throw that escapes (leaves the arm or
    does not come to rest); that throw is drawn. ``model`` is ``"paper"``
    (:func:`paper_trajectory`), ``"rigid_body"`` or ``"engine"`` (see
    :func:`trajectory_function`). ``progress``, if given, is called with the number
    of throws done after each. ``meta["outcomes"]`` holds each throw's
    :class:`ThrowOutcome`; ``meta["throw_starts"]`` each release time (s).
    """
    om = throw_rates(omegas, n, min_n=1)
    pause = float(pause)
    if not (math.isfinite(pause) and pause >= 0):
        raise InvalidStateError("pause", f"must be a finite time ≥ 0 (s), got {pause!r}")
    dt = check_dt(dt)
    fn = trajectory_function(model)
    kwargs = {"dt": dt} if model == "paper" else {}
    traj = None
    outcomes = []
    starts = []
    xs, ss = float(x), side
    for w in om:
        out, piece = fn(part, arm, xs, ss, float(w), **kwargs)
        outcomes.append(out)
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
        if out.status != Status.OK:
            break
        xs, ss = out.x, out.side
    traj = _dedupe(traj)
    length = traj.length
    if arm.length is None and not traj.fixtures:  # an unbounded arm: draw it just past the part's reach
        length = drawn_length(arm, traj.poses, traj.parts)
    meta = dict(traj.meta)
    meta.update(outcomes=tuple(outcomes), throw_starts=tuple(starts), arm=arm, arm_unbounded=arm.length is None)
    return Trajectory(traj.t, traj.arm_angle, traj.poses, traj.parts, traj.h, length, traj.fixtures, traj.contacts,
                      traj.events, traj.source if len(om) == 1 else f"{traj.source} orbit", meta)

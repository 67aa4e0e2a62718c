"""Trajectories recorded by the analytic kernels ("paper", "rigid_body"), as :class:`Trajectory` values.

:func:`kernel_trajectory` runs a model's kernel with a trajectory buffer
(:mod:`throwmap.kernels.record` for "paper", the ``traj`` rows of
:mod:`throwmap.kernels.rigid_body` for "rigid_body") and turns its rows into a
:class:`~throwmap.throws.trajectory.Trajectory` with contacts and named events.
The start must already be checked (:func:`throwmap.throws.throw.check_start`);
``options`` is the model's options value (``tol``, ``max_iter``, ``max_impacts``,
and ``n_samples`` for "paper").

Model "paper" (paper Sec. III-B–C, Eqs. 1–4): the first sample is the resting start
at t = 0 (the release), then the flight (Eq. 1) to the first contact (Eq. 3), the
pivot swings (compound pendulum, time by quadrature, see
:mod:`~throwmap.kernels.record`) and side landings, ending at the kernel's resting
configuration exactly (or the escape; after a first contact off the arm the fall is
drawn for :data:`~throwmap.kernels.record.ESCAPE_FALL_TIME`). The arm stays
horizontal (an impulsive throw). Events ``(t, label)``: ``"release"``,
``"impact v<j>"`` (j the user's vertex index), ``"land side <k>"``, ``"flip <a>→<b>"``,
``"rest"`` or ``"escape: <status>"``. Contacts per sample: both support vertices at
rest and at a landing, the pivot while swinging, none in flight.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InvalidStateError
from ..kernels import codes as C
from ..kernels.paper import throw_one_traj
from ..kernels.record import FLIGHT
from ..system.arm import Arm
from ..system.part import Part
from .outcome import Status, ThrowOutcome
from .trajectory import Trajectory, world_vertices

__all__ = ["kernel_trajectory", "check_dt", "drawn_length", "DEFAULT_DT", "KERNEL_TRAJECTORY_MODELS"]

DEFAULT_DT = 1.0 / 240.0
"""Default sample interval, s."""
KERNEL_TRAJECTORY_MODELS = ("paper", "rigid_body")
"""Models whose kernels record trajectories."""
_NO_CONTACT = np.zeros((0, 2))
_NO_CONTACT.setflags(write=False)


def _contact(*points) -> np.ndarray:
    a = np.array(points, dtype=float).reshape(-1, 2)
    a.setflags(write=False)
    return a


def check_dt(dt) -> float:
    """A positive finite sample interval (s), or :class:`InvalidStateError` naming ``dt``."""
    if isinstance(dt, bool):
        raise InvalidStateError("dt", f"must be a number, got {dt!r}")
    try:
        v = float(dt)
    except (TypeError, ValueError):
        raise InvalidStateError("dt", f"must be a number, got {dt!r}") from None
    if not (math.isfinite(v) and v > 0):
        raise InvalidStateError("dt", f"must be a positive finite time step (s), got {dt!r}")
    return v


def drawn_length(arm: Arm, poses: np.ndarray, parts) -> float:
    """The arm's length (m), or for an unbounded arm one reaching a little past every vertex."""
    if arm.length is not None:
        return float(arm.length)
    reach = 0.0
    for p, part in enumerate(parts):
        r = float(np.max(part.ell))
        reach = max(reach, float(np.max(poses[:, p, 0])) + r)
    return max(1.15 * reach, reach + 0.03)


def kernel_trajectory(part: Part, arm: Arm, x: float, side: int, omega: float, model: str, *,
                      dt: float = DEFAULT_DT, options) -> tuple[ThrowOutcome, Trajectory]:
    """One throw of ``model`` ("paper" or "rigid_body") from a checked start, sampled every ``dt`` s and at events.

    Returns ``(ThrowOutcome, Trajectory)``; the outcome equals
    ``throw(part, arm, x, side, omega, model=model)`` with the same options.
    """
    dt = check_dt(dt)
    if model == "paper":
        return _paper(part, arm, float(x), int(side), float(omega), dt, options)
    if model == "rigid_body":
        return _rigid_body(part, arm, float(x), int(side), float(omega), dt, options)
    raise InvalidStateError("model", f"no kernel trajectory for model {model!r} "
                                     f"(choose from {', '.join(KERNEL_TRAJECTORY_MODELS)})")


def _paper(part, arm, x0, k0, om, dt, o):
    rec = np.empty(C.NREC)
    m = 2048
    while True:
        rows = np.full((m, 4), np.nan)
        tags = np.full(m, FLIGHT, dtype=np.int64)
        xn, kn, st, count, dropped = throw_one_traj(
            x0, k0, om, arm.h, arm.g, arm.length_or_inf, part.radius_of_gyration**2, part.w, part.beta, part.d,
            part.uL, part.uR, part.ell, part.stable, o.tol, o.max_iter, o.max_impacts, o.n_samples, rec, rows, tags,
            dt)
        if dropped == 0:
            break
        m = count + dropped + 1
    out = ThrowOutcome.from_record(part, x0, k0, om, "paper", xn, kn, st, rec)
    rows, tags = rows[:count], tags[:count]
    n, h = part.n_sides, arm.h
    contacts = []
    for r, tag in zip(rows, tags):
        if tag == FLIGHT:
            contacts.append(_NO_CONTACT)
        elif tag < n:  # the pivot (or the touching vertex at the first contact), on the arm line
            contacts.append(_contact((world_vertices(part, r[1:4])[tag, 0], h)))
        else:  # flat on side k: both support vertices
            k = tag - n
            contacts.append(_contact((r[1] + part.uR[k], h), (r[1] + part.uL[k], h)))
    t = rows[:, 0]
    events = [(0.0, "release")]
    status = Status(int(st))
    if om != 0.0 and status != Status.NO_CONTACT:
        t_f = float(rec[C.T_FLIGHT])
        events.append((t_f, f"impact v{part.user_vertex(int(rec[C.CONTACT_VERTEX]))}"))
        if int(rec[C.N_IMPACTS]) == 1 and status in (Status.BEHIND_JOINT, Status.OFF_END):
            events.append((t_f, f"escape: {status.label}"))  # first contact off the arm
        else:
            last = k0
            for i in np.flatnonzero(tags[1:] >= n) + 1:
                k = int(tags[i]) - n
                events.append((float(t[i]), f"land side {k}"))
                if k != last:
                    events.append((float(t[i]), f"flip {last}→{k}"))
                    last = k
            events.append((float(t[-1]), "rest" if status == Status.OK else f"escape: {status.label}"))
    else:
        events.append((float(t[-1]), "rest" if status == Status.OK else f"escape: {status.label}"))
    poses = rows[:, None, 1:4]
    traj = Trajectory(t=t, arm_angle=np.zeros_like(t), poses=poses, parts=(part,), h=h,
                      length=drawn_length(arm, poses, (part,)), fixtures=(), contacts=tuple(contacts),
                      events=tuple(events), source="paper",
                      meta={"outcomes": (out,), "arm": arm, "arm_unbounded": arm.length is None})
    return out, traj


def _rigid_body(part, arm, x0, k, om, dt, o, max_samples: int = 200_000):
    from ..kernels.rigid_body import count_samples, throw_one_rigid_body

    rec = np.empty(C.NREC)
    traj = np.full((max_samples, 4), np.nan)
    xn, kn, st = throw_one_rigid_body(x0, k, om, arm.h, arm.g, arm.length_or_inf, part.radius_of_gyration**2,
                                      arm.mu, part.w, part.beta, part.d, part.uL, part.uR, part.ell, part.stable,
                                      o.tol, o.max_iter, o.max_impacts, rec, traj, float(dt))
    out = ThrowOutcome.from_record(part, x0, k, om, "rigid_body", xn, kn, st, rec)
    m = count_samples(traj)
    rows = traj[:m]
    order = np.argsort(rows[:, 0], kind="stable")
    rows = rows[order]
    poses = rows[:, None, 1:4]
    contacts = []
    for p in rows:
        v = world_vertices(part, p[1:4])
        contacts.append(v[np.abs(v[:, 1] - arm.h) < 1e-6])
    reach = float(np.nanmax(rows[:, 1])) + float(np.max(part.ell)) if m else x0
    length = arm.length if arm.length is not None else max(reach, x0) + 0.05
    events = [(0.0, "release")]
    if out.t_flight == out.t_flight:
        events.append((out.t_flight, f"impact v{out.contact_vertex}"))
    if out.ok:
        events.append((float(rows[-1, 0]) if m else 0.0, "rest"))
    traj_obj = Trajectory(rows[:, 0], np.zeros(m), poses, (part,), arm.h, length, (), tuple(contacts),
                          tuple(events), "rigid_body", {"outcomes": (out,)})
    return out, traj_obj

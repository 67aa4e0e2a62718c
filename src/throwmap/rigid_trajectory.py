"""Sampled motion of the "rigid_body" model (for ``throwmap animate`` and inspection)."""

from __future__ import annotations

import numpy as np

from .system.arm import Arm
from .kernels import codes as C
from .kernels.rigid_body import count_samples, throw_one_rigid_body
from .throws.outcome import ThrowOutcome
from .system.part import Part
from .throws.throw import DEFAULT_MAX_IMPACTS, DEFAULT_MAX_ITER, DEFAULT_TOL, check_start
from .throws.trajectory import Trajectory, world_vertices

__all__ = ["rigid_trajectory"]


def rigid_trajectory(part: Part, arm: Arm, x: float, side: int, omega: float, *, dt: float = 1.0 / 240.0,
                     max_samples: int = 200_000) -> tuple[ThrowOutcome, Trajectory]:
    """One "rigid_body" throw with its motion sampled every ``dt`` s and at every event.

    Returns ``(ThrowOutcome, Trajectory)``; contacts are the vertices within 1 µm of
    the arm line at each sample. The outcome equals ``throw(..., model="rigid_body")``.
    """
    x0, k, om = check_start(part, arm, x, side, omega)
    rec = np.empty(C.NREC)
    traj = np.full((max_samples, 4), np.nan)
    xn, kn, st = throw_one_rigid_body(x0, k, om, arm.h, arm.g, arm.length_or_inf, part.radius_of_gyration**2,
                                      arm.mu, part.w, part.beta, part.d, part.uL, part.uR, part.ell, part.stable,
                                      DEFAULT_TOL, DEFAULT_MAX_ITER, DEFAULT_MAX_IMPACTS, rec, traj, float(dt))
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

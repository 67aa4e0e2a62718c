"""Model "paper": the exact throw map within the paper's assumptions (Sec. III, Eqs. 1–4).

No small-angle approximation: release (Eq. 1), first contact of any vertex (Eq. 3),
plastic no-slip impact (Eq. 4), then the exact pivot/landing/rocking cascade
(:mod:`throwmap.kernels.paper`). No fixtures; the arm may rest at an angle α
(``alpha=``, rad, CCW +; draft Sec. VI): gravity (−g sin α, −g cos α) in the arm
frame. Friction is not modelled (the record reports the friction the throw needs,
at rest on a tilted arm at least |tan α|).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kernels import codes as C
from ..kernels.paper import PARALLEL_MIN, throw_many, throw_many_serial, throw_one, throw_one_traj
from ..kernels.record import FLIGHT
from .rigid_body import stable_at
from ..records.outcome import Status, ThrowOutcome
from ..records.trajectory import NO_CONTACT, Trajectory, contact_points, drawn_length
from ..system.pose import world_vertices
from ._checks import int_at_least, tolerance
from .base import BatchArrays, Features
from .registry import register

__all__ = ["PaperOptions", "PaperModel", "MODEL"]


@dataclass(frozen=True, slots=True)
class PaperOptions:
    """Numerical options of the "paper" kernel.

    ``tol`` (dimensionless, 0 < tol ≤ 1e-6): contact tolerance of the first-contact search, relative to
    the size of the gap's terms (:func:`~throwmap.kernels.flight.touch_time`), so that
    tiny flights near x_min and long flights at high ω are both resolved to rounding;
    ``max_iter``: cap on its steps (beyond: status UNRESOLVED, record ``CAP_HIT`` = 1); ``max_impacts``: cap on plastic impacts in one
    throw (status NO_REST beyond); ``n_samples``: points per pivot swing at which the
    friction demand (record ``friction_ratio_max``) is sampled.
    """

    tol: float = 1e-14
    max_iter: int = 100_000
    max_impacts: int = 10_000
    n_samples: int = 16

    def __post_init__(self):
        object.__setattr__(self, "tol", tolerance(self.tol, "tol"))
        object.__setattr__(self, "max_iter", int_at_least(self.max_iter, "max_iter", 1))
        object.__setattr__(self, "max_impacts", int_at_least(self.max_impacts, "max_impacts", 1))
        object.__setattr__(self, "n_samples", int_at_least(self.n_samples, "n_samples", 2))


class PaperModel:
    name = "paper"
    summary = ("exact within the paper's assumptions (Sec. III, Eqs. 1–4): first contact of any vertex, "
               "plastic no-slip impact, exact pivoting, landings, flips and rocking; lift-off and pulling "
               "impulses flagged, not modelled")
    options_type = PaperOptions
    features = Features(trajectory=True, tilt=True)
    assumes = ("no lift-off", "no slip")
    """The contact assumptions of Sec. III (the pivot never lifts, the contact never slips)."""

    def throw_one(self, part, system, x, side, omega, o: PaperOptions):
        arm = system.arm
        rec = np.empty(C.NREC)
        xn, kn, st = throw_one(x, side, omega, arm.h, arm.g, system.alpha, arm.length_or_inf, arm.back,
                               part.radius_of_gyration**2, part.w, part.beta, part.d, part.uL, part.uR, part.ell,
                               stable_at(part, system.alpha), o.tol, o.max_iter, o.max_impacts, o.n_samples, rec)
        return xn, kn, st, rec

    def throw_batch(self, part, system, x, side, omega, valid, o: PaperOptions, progress=None):
        arm = system.arm
        m = x.size
        out = BatchArrays(np.empty(m), np.empty(m, dtype=np.int64), np.empty(m, dtype=np.int64), np.empty((m, C.NREC)))
        kernel = throw_many if m >= PARALLEL_MIN else throw_many_serial
        kernel(x, side, omega, valid, arm.h, arm.g, system.alpha, arm.length_or_inf, arm.back,
               part.radius_of_gyration**2, part.w, part.beta, part.d, part.uL, part.uR, part.ell,
               stable_at(part, system.alpha), o.tol, o.max_iter, o.max_impacts, o.n_samples, out.x, out.side,
               out.status, out.records)
        return out

    def assumptions(self, records, mu, status) -> str:
        """How often the paper's contact assumptions failed over a batch's records (validation table)."""
        lift = np.nan_to_num(records[:, C.N_MIN], nan=1.0) < 0
        slip = np.nan_to_num(records[:, C.MU_MAX], nan=0.0) > mu
        imp = np.nan_to_num(records[:, C.MU_IMPACT], nan=0.0) > mu
        return (f"lift-off {100 * lift.mean():.0f} %, impact outside cone {100 * imp.mean():.0f} %, "
                f"needs μ > arm μ {100 * slip.mean():.0f} %")

    def assumptions_hold(self, records, mu):
        """Where the paper's contact assumptions held over a batch's records (a boolean mask): no lift-off (the
        pivot's normal force never pulls) and no friction demand above the arm's ``mu``."""
        return (np.nan_to_num(records[:, C.N_MIN], nan=1.0) >= 0) & (np.nan_to_num(records[:, C.MU_MAX], nan=0.0) <= mu)

    def trajectory(self, part, system, x, side, omega, o: PaperOptions, dt):
        return record_trajectory(part, system.arm, x, side, omega, dt, o, alpha=system.alpha)


def record_trajectory(part, arm, x0, k0, om, dt, o: PaperOptions, alpha: float = 0.0):
    """The kernel's recorded motion of one throw as ``(ThrowOutcome, Trajectory)``.

    Model "paper" (paper Sec. III-B–C, Eqs. 1–4): the first sample is the resting start
    at t = 0 (the release), then the flight (Eq. 1) to the first contact (Eq. 3), the
    pivot swings (compound pendulum, time by quadrature, see
    :mod:`~throwmap.kernels.record`) and side landings, ending at the kernel's resting
    configuration exactly (or the escape; after a first contact off the arm the fall is
    drawn for :data:`~throwmap.kernels.record.ESCAPE_FALL_TIME`). The arm stays
    horizontal (an impulsive throw). Events ``(t, label)``: ``"release"``,
    ``"impact v<j>"`` (j the user's vertex index), ``"land side <k>"``, ``"flip <a>→<b>"``,
    ``"rest"`` or ``"escape: <status>"``. Contacts per sample: both support vertices at
    rest and at a landing, the pivot while swinging, none in flight. On an arm at rest
    angle ``alpha`` (rad) the kernel's arm-frame rows are turned into the world by α and
    ``arm_angle`` is α at every sample.
    """
    rec = np.empty(C.NREC)
    m = 2048
    while True:
        rows = np.full((m, 4), np.nan)
        tags = np.full(m, FLIGHT, dtype=np.int64)
        xn, kn, st, count, dropped = throw_one_traj(
            x0, k0, om, arm.h, arm.g, float(alpha), arm.length_or_inf, arm.back, part.radius_of_gyration**2, part.w,
            part.beta, part.d, part.uL, part.uR, part.ell, stable_at(part, alpha), o.tol, o.max_iter, o.max_impacts,
            o.n_samples, rec, rows, tags, dt)
        if dropped == 0:
            break
        m = count + dropped + 1
    out = ThrowOutcome.from_record(part, x0, k0, om, "paper", xn, kn, st, rec)
    rows, tags = rows[:count], tags[:count]
    n, h = part.n_sides, arm.h
    contacts = []
    for r, tag in zip(rows, tags):
        if tag == FLIGHT:
            contacts.append(NO_CONTACT)
        elif tag < n:  # the pivot (or the touching vertex at the first contact), on the arm line
            contacts.append(contact_points((world_vertices(part, r[1:4])[tag, 0], h)))
        else:  # flat on side k: both support vertices
            k = tag - n
            contacts.append(contact_points((r[1] + part.uR[k], h), (r[1] + part.uL[k], h)))
    t = rows[:, 0]
    events = [(0.0, "release")]
    status = Status(int(st))
    if om != 0.0 and int(rec[C.CONTACT_VERTEX]) >= 0:  # a first contact was found
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
    if alpha != 0.0:  # arm frame → world: turn by the rest angle
        ca, sa = np.cos(alpha), np.sin(alpha)
        rot = np.array([[ca, -sa], [sa, ca]])
        poses = np.concatenate((rows[:, 1:3] @ rot.T, rows[:, 3:4] + alpha), axis=1)[:, None, :]
        contacts = [c @ rot.T if len(c) else c for c in contacts]
    traj = Trajectory(t=t, arm_angle=np.full_like(t, float(alpha)), poses=poses, parts=(part,), h=h,
                      length=drawn_length(arm, poses, (part,)), fixtures=(), contacts=tuple(contacts),
                      events=tuple(events), source="paper",
                      meta={"outcomes": (out,), "arm": arm, "arm_unbounded": arm.length is None})
    return out, traj


MODEL = register(PaperModel())

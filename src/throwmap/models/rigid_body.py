"""Model "rigid_body": exact rigid-body dynamics of one polygon on the arm line (the default model).

Drops the paper's two contact assumptions: the pivot may lift off and may slip
(Coulomb friction ``Arm.mu``); Routh impacts (or, with option ``impact_law="velocity"``,
the one-step velocity-level impacts of time-stepping engines), sticking and sliding pivots, flat
slides and the Zeno rocking rule, as a hybrid automaton
(:mod:`throwmap.kernels.rigid_body`). Validated against pymunk and MuJoCo
(docs/explanation/validation.md). The arm may rest at an angle α (``alpha=``, rad, CCW +;
draft Sec. VI): gravity (−g sin α, −g cos α) in the arm frame, :mod:`throwmap.kernels.rigid_body.tilt`.
A :class:`~throwmap.system.fixtures.Wall` at the arm's end (``fixtures=(Wall(),)``, finite arm length)
is modelled exactly where it can be (:mod:`throwmap.kernels.rigid_body.wall`: impacts against the wall
with its own μ, a jog that slides or hops into it stops there, resting flat or leaning against it);
what it cannot follow is refused as status UNRESOLVED with the reason. A Cavity needs model "engine".
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kernels import codes as C
from ..errors import InvalidStateError, shown
from ..kernels.rigid_body import LAW_ROUTH, LAW_VELOCITY, count_samples, pick, throw_one_rigid_body
from ..kernels.rigid_body.inputs import arm_record, part_arrays, run_limits
from ..kernels.rigid_body.tilt import tilted_stable
from ..system.fixtures import Cavity, Wall
from ..records.outcome import ThrowOutcome
from ..records.trajectory import Trajectory
from ..system.pose import world_vertices
from ._checks import int_at_least, tolerance
from .base import BatchArrays, Features
from .registry import register

__all__ = ["RigidBodyOptions", "RigidBodyModel", "MODEL", "NO_TRAJ"]

NO_TRAJ = np.empty((0, 4))
"""An empty trajectory buffer: the kernel records nothing."""

IMPACT_LAWS = {"routh": LAW_ROUTH, "velocity": LAW_VELOCITY}
"""Option ``impact_law`` → the kernel's integer code (:mod:`throwmap.kernels.rigid_body.impact`)."""


@dataclass(frozen=True, slots=True)
class RigidBodyOptions:
    """Numerical options of the "rigid_body" kernel.

    ``tol`` (dimensionless, 0 < tol ≤ 1e-6): contact tolerance of the first-contact search, relative to
    the size of the gap's terms (:func:`~throwmap.kernels.flight.touch_time`); ``max_iter``: cap on the
    contact-search and integration steps of one mode (beyond: status UNRESOLVED, record ``CAP_HIT`` = 1); ``max_impacts``: cap on mode
    changes (events) in one throw (beyond: status UNRESOLVED, the contacts chatter). ``impact_law``: the law of
    the resets ``impact`` and ``land_side`` outside the friction cone (docstring of
    :mod:`throwmap.kernels.rigid_body.impact`): ``"routh"`` (default; Routh's
    compression-only process in impulse space, Stronge 2000 ch. 3–4) or ``"velocity"``
    (the one-step velocity-level Coulomb impulse of Moreau, as time-stepping engines
    such as pymunk compute it). The two differ only on impacts whose slip stops and
    reverses, common at μ ≤ 0.6; with "velocity" rigid_body lands within about
    0.5 mm of the pymunk engine at μ = 0.3 where "routh" differs by up to ~1 cm.
    ``realisation``: how the arm moves (as model "engine"): None, the paper's impulse at the throw's ω
    (:class:`~throwmap.engine.ImpulseThrow` likewise, at its own ω); a
    :class:`~throwmap.engine.FiniteThrow`, :class:`~throwmap.engine.RecoilThrow` or
    :class:`~throwmap.system.motion.SampledThrow`: the part rides the moving arm in the arm frame
    (:mod:`throwmap.kernels.rigid_body.moving`), the static automaton takes over once the arm stops;
    or a callable ``omega -> realisation`` (one per throw, e.g. ``RecoilThrow.for_release_rate``).
    """

    tol: float = 1e-14
    max_iter: int = 100_000
    max_impacts: int = 10_000
    impact_law: str = "routh"
    realisation: object = None

    def __post_init__(self):
        r = self.realisation
        if r is not None and not (callable(r) and not hasattr(r, "angle")):
            from ..system.motion import TiltTo, check_realisation  # no pymunk import

            check_realisation(r)
            if isinstance(r, TiltTo):
                raise InvalidStateError("realisation", "TiltTo is no throw: rigid_body takes ImpulseThrow, FiniteThrow, "
                                                       "RecoilThrow or SampledThrow")
        object.__setattr__(self, "tol", tolerance(self.tol, "tol"))
        object.__setattr__(self, "max_iter", int_at_least(self.max_iter, "max_iter", 1))
        object.__setattr__(self, "max_impacts", int_at_least(self.max_impacts, "max_impacts", 1))
        if not isinstance(self.impact_law, str) or self.impact_law not in IMPACT_LAWS:
            raise InvalidStateError("impact_law", f"must be one of {', '.join(map(repr, IMPACT_LAWS))}, "
                                                  f"got {shown(self.impact_law)}")

    @property
    def law_code(self) -> int:
        """``impact_law`` as the kernel's integer code."""
        return IMPACT_LAWS[self.impact_law]


def stable_at(part, alpha: float) -> np.ndarray:
    """The sides of ``part`` that stand on an arm at rest angle ``alpha`` (rad): u_L < −d tan α < u_R
    (:func:`~throwmap.kernels.rigid_body.tilt.tilted_stable`); ``part.stable`` for α = 0. Read-only either way."""
    if alpha == 0.0:
        return part.stable
    table = tilted_stable(part.d, part.uL, part.uR, float(alpha))
    table.flags.writeable = False  # read-only, as part.stable: one type, hence one compiled kernel, for both
    return table


def wall_args(arm, fixtures) -> tuple[float, float]:
    """The kernel's wall arguments ``(wall_h, wall_mu)`` from a System's fixtures: the wall's height (m; 0: no
    wall) and its μ, ``Wall.mu`` or, where that is None, the arm's μ."""
    for f in fixtures:
        if isinstance(f, Wall):
            return float(f.height), float(arm.mu if f.mu is None else f.mu)
    return 0.0, 0.0


def run_kernel(part, arm, x, side, omega, o: RigidBodyOptions, traj=NO_TRAJ, dt: float = 1.0, alpha: float = 0.0,
               fixtures=()):
    """One kernel call: ``(x', side', status, record)``; ``traj`` (M, 4) receives the sampled motion;
    ``alpha`` the arm's rest angle (rad), ``fixtures`` at most one Wall."""
    rec = np.empty(C.NREC)
    xn, kn, st = throw_one_rigid_body(x, side, omega, *records(part, arm, alpha, fixtures, o), rec, traj, dt)
    if st == C.OFF_END and wall_args(arm, fixtures)[0] > 0.0:
        xs, ss = at_the_wall(part, arm, np.array([xn]), np.array([kn]), np.array([st]))
        xn, st = float(xs[0]), int(ss[0])
    return xn, kn, st, rec


def at_the_wall(part, arm, x, side, status):
    """Rests against an end wall read back onto the arm. A side landing at the wall's foot (the kernel's
    ``land_side``: its second vertex touches at x = L, computed as the pivot's x plus the side's length) can put that
    vertex a few ulps past L, and ``leave_arm`` then calls the rest ``off_end`` at a wall nothing passes. Those —
    ``off_end`` with x + u_R within 8 ulps of L — become ``ok`` at the last start :func:`start_interval` accepts;
    every other throw is returned as it is. Arrays ``x`` (m), ``side``, ``status`` (codes); new arrays. (The kernel
    itself is left as it is: moving the rule there changes its compiled code, checked bit for bit elsewhere.)"""
    from ..system.starts import start_interval

    x, status = np.array(x, dtype=float), np.array(status)
    L = float(arm.length_or_inf)
    for i in np.flatnonzero(status == C.OFF_END):
        k = int(side[i])
        excess = x[i] + float(part.uR[k]) - L
        if 0.0 < excess <= 8.0 * np.spacing(L):
            x[i] = start_interval(part, arm, k)[1]
            status[i] = C.OK
    return x, status


def records(part, arm, alpha, fixtures, o: RigidBodyOptions):
    """The kernels' three records (:mod:`throwmap.kernels.rigid_body.inputs`): the part with its stable sides at
    ``alpha`` (rad), the arm with the impact law and the wall of ``fixtures``, and the options' limits."""
    return (part_arrays(part, stable_at(part, alpha)), arm_record(arm, alpha, o.law_code, *wall_args(arm, fixtures)),
            run_limits(o.tol, o.max_iter, o.max_impacts))


class RigidBodyModel:
    name = "rigid_body"
    summary = ("the exact rigid-body dynamics of one polygon on the arm line with plastic impacts and Coulomb "
               "friction Arm.mu: lift-off, sliding impacts and pivots, flat slides, Painlevé status")
    options_type = RigidBodyOptions
    features = Features(trajectory=True, friction=True, tilt=True, fixtures=True, realisation=True)

    def check_system(self, system) -> None:
        """Refuse what this model cannot take: a Cavity (model "engine" can), a Wall on an unbounded arm."""
        for f in system.fixtures:
            if isinstance(f, Cavity):
                raise InvalidStateError("fixtures", "rigid_body takes a Wall; a Cavity needs model 'engine'")
        if any(isinstance(f, Wall) for f in system.fixtures) and system.arm.length is None:
            raise InvalidStateError("arm.length", "a Wall stands at the arm's end: give the arm a finite length")

    def throw_one(self, part, system, x, side, omega, o: RigidBodyOptions):
        self.check_system(system)
        r, omega = realisation_for(o, omega, system)
        if r is not None:
            return run_moving(part, system, x, side, r, o)
        return run_kernel(part, system.arm, x, side, omega, o, alpha=system.alpha, fixtures=system.fixtures)

    def throw_batch(self, part, system, x, side, omega, valid, o: RigidBodyOptions, progress=None):
        self.check_system(system)
        arm = system.arm
        if o.realisation is not None:
            return moving_batch(part, system, x, side, omega, valid, o, progress)
        m = x.size
        out = BatchArrays(np.empty(m), np.empty(m, dtype=np.int64), np.empty(m, dtype=np.int64), np.empty((m, C.NREC)))
        pick(m)(x, side, omega, valid, *records(part, arm, system.alpha, system.fixtures, o), out.x, out.side,
                out.status, out.records)
        if wall_args(arm, system.fixtures)[0] > 0.0:
            out.x[:], out.status[:] = at_the_wall(part, arm, out.x, out.side, out.status)
        return out

    def assumptions(self, records, mu, status) -> str:
        """Nothing is assumed; how often the contact lifted, slipped or had no Coulomb solution (validation table)."""
        lo = np.nan_to_num(records[:, C.N_LIFTOFFS]) > 0
        sl = np.nan_to_num(records[:, C.N_SLIPS]) > 0
        inc = status == C.INCONSISTENT
        return (f"none assumed; lift-offs in {100 * lo.mean():.0f} %, slips in {100 * sl.mean():.0f} %, "
                f"inconsistent (Painlevé) {100 * inc.mean():.1f} %")

    def trajectory(self, part, system, x, side, omega, o: RigidBodyOptions, dt):
        self.check_system(system)
        if o.realisation is not None:
            raise InvalidStateError("realisation", "rigid_body records no trajectory of a moving arm yet: use model "
                                                   "'engine' for its animation")
        return record_trajectory(part, system.arm, x, side, omega, dt, o, alpha=system.alpha,
                                 fixtures=system.fixtures)


def realisation_for(o: RigidBodyOptions, omega: float, system):
    """``(realisation, ω)`` of one throw: (None, ω) for the impulse (None, or an ImpulseThrow at its own ω),
    else the finite realisation (a callable option is called with ω)."""
    r = o.realisation
    if r is None:
        return None, omega
    if callable(r) and not hasattr(r, "angle"):  # a factory ω → realisation (as iterate's engine chain)
        from ..system.motion import check_realisation

        r = check_realisation(r(float(omega)))
    from ..system.motion import ImpulseThrow, TiltTo

    if isinstance(r, ImpulseThrow):
        return None, r.omega
    if isinstance(r, TiltTo):
        raise InvalidStateError("realisation", "TiltTo is no throw")
    if system.fixtures:
        raise InvalidStateError("realisation", "rigid_body takes a moving arm without fixtures: use model 'engine'")
    return r, omega


def run_moving(part, system, x, side, r, o: RigidBodyOptions):
    """One throw by the moving arm of realisation ``r`` (:func:`throwmap.kernels.rigid_body.moving.throw_moving`)."""
    from ..kernels.rigid_body.moving import throw_moving

    return throw_moving(part, system.arm, float(x), int(side), r, alpha=system.alpha, law=o.law_code,
                        stable=stable_at(part, system.alpha), tol=o.tol, max_iter=o.max_iter, max_events=o.max_impacts)


def moving_batch(part, system, x, side, omega, valid, o: RigidBodyOptions, progress=None) -> BatchArrays:
    """:meth:`RigidBodyModel.throw_batch` with a realisation: the throws one by one (the moving phase is
    Python, ~0.1–0.5 s a throw); invalid starts get INVALID_START."""
    from ..kernels.rows import mark_invalid

    m = x.size
    out = BatchArrays(np.empty(m), np.empty(m, dtype=np.int64), np.empty(m, dtype=np.int64), np.empty((m, C.NREC)))
    for i in range(m):
        if not valid[i]:
            mark_invalid(i, x, side, out.x, out.side, out.status, out.records)
        else:
            r, om = realisation_for(o, float(omega[i]), system)
            if r is None:
                res = run_kernel(part, system.arm, float(x[i]), int(side[i]), om, o, alpha=system.alpha,
                                 fixtures=system.fixtures)
            else:
                res = run_moving(part, system, x[i], side[i], r, o)
            out.x[i], out.side[i], out.status[i], out.records[i] = res
        if progress is not None:
            progress(i + 1, m)
    return out


def record_trajectory(part, arm, x0, k, om, dt, o: RigidBodyOptions, max_samples: int = 200_000, alpha: float = 0.0,
                      fixtures=()):
    """The kernel's rows (t, x, y, φ) every ``dt`` s and at every event, as ``(ThrowOutcome, Trajectory)``;
    contacts are the vertices within 1 µm of the arm line at each sample. The kernel's rows are in the
    arm frame; on an arm at rest angle ``alpha`` (rad) poses and contacts are turned into the world by
    α, and the trajectory's ``arm_angle`` is α at every sample."""
    traj = np.full((max_samples, 4), np.nan)
    xn, kn, st, rec = run_kernel(part, arm, x0, k, om, o, traj, float(dt), alpha=alpha, fixtures=fixtures)
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
    if alpha != 0.0:  # the kernel's arm-frame rows, turned into the world by the rest angle
        ca, sa = np.cos(alpha), np.sin(alpha)
        rot = np.array([[ca, -sa], [sa, ca]])
        poses = np.concatenate((rows[:, 1:3] @ rot.T, rows[:, 3:4] + alpha), axis=1)[:, None, :]
        contacts = [c @ rot.T for c in contacts]
    reach = float(np.nanmax(rows[:, 1])) + float(np.max(part.ell)) if m else x0
    length = arm.length if arm.length is not None else max(reach, x0) + 0.05
    events = [(0.0, "release")]
    if out.t_flight == out.t_flight:
        events.append((out.t_flight, f"impact v{out.contact_vertex}"))
    if out.ok:
        events.append((float(rows[-1, 0]) if m else 0.0, "rest"))
    traj_obj = Trajectory(rows[:, 0], np.full(m, float(alpha)), poses, (part,), arm.h, length, tuple(fixtures), tuple(contacts),
                          tuple(events), "rigid_body", {"outcomes": (out,)})
    return out, traj_obj


MODEL = register(RigidBodyModel())

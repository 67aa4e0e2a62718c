"""Records of a throwing session: where each part is between throws, and what one step did.

A *throwing session* (:class:`~throwmap.models.base.ThrowSession`) is a scene — one or several
parts on an arm with its fixtures — thrown again and again, keeping its state. Each step (a
throw, or an arm move such as a tilt) returns a :class:`SessionStep`; the state between steps is
one :class:`PartState` per part. SI units, arm frame (:mod:`throwmap.system.pose`).
"""

from __future__ import annotations

from dataclasses import dataclass

from .outcome import Status

__all__ = ["PartState", "SessionStep"]


@dataclass(frozen=True, slots=True)
class PartState:
    """Where one part rests between throws.

    ``x`` (m): its CM abscissa along the arm; ``side``: the side it lies on (the nearest one where it is
    tilted); ``tilt`` (rad): how far it is turned from lying flat on that side (0 for the analytic
    models, which keep only rests); ``pose``: its arm-frame pose ``(x, y, φ)`` (m, m, rad) where the
    session keeps full poses (``Features.pose``), else None.
    """

    x: float
    side: int
    tilt: float = 0.0
    pose: tuple | None = None


@dataclass(frozen=True, slots=True)
class SessionStep:
    """One step of a session.

    ``kind``: ``"throw"`` or ``"move"`` (the arm turned to a new rest angle without a throw);
    ``omega`` (rad/s): the release rate thrown (0 for a move); ``motion``: the arm's motion (None: the
    paper's impulse at ``omega``); ``status``: ``ok`` when every part ended at rest on the arm, else the
    first part's failure; ``outcomes``: one :class:`~throwmap.records.outcome.ThrowOutcome` per part;
    ``states``: one :class:`PartState` per part after the step; ``alpha`` (rad): the arm's rest angle
    after it; ``message``: why a step was refused, if it was; ``run``: the engine's own record of the step
    (:class:`~throwmap.engine.EngineRun`) where the session has one; ``trajectory``: the step's sampled
    motion (:class:`~throwmap.records.trajectory.Trajectory`) where it was recorded, else None.
    """

    kind: str
    omega: float
    motion: object
    status: Status
    outcomes: tuple
    states: tuple
    alpha: float
    message: str = ""
    run: object = None
    trajectory: object = None

    @property
    def ok(self) -> bool:
        return self.status == Status.OK

    @property
    def outcome(self):
        """The first (for one part: the only) part's outcome."""
        return self.outcomes[0]

    @property
    def statuses(self) -> tuple:
        """Each part's status."""
        return tuple(o.status for o in self.outcomes)

    @property
    def poses(self) -> tuple:
        """Each part's arm-frame pose after the step (None where the session keeps no poses)."""
        return tuple(s.pose for s in self.states)

    def __repr__(self) -> str:
        where = ", ".join(f"(x={s.x:.4g} m, side {s.side})" for s in self.states)
        return f"SessionStep({self.kind}, omega={self.omega:g} rad/s, {self.status.label}, {where})"

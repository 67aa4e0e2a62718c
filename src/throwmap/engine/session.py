"""The engine's throwing session: a scene of parts thrown again and again, each run starting where the last ended.

The state between throws is the whole scene (:class:`~throwmap.engine.Scene`): every part's pose —
a part held tilted by a fixture, or leaning on the wall or on another part, stays so — and the arm's
rest angle, which :class:`~throwmap.system.motion.TiltTo` moves change. Each step is one
:func:`~throwmap.engine.simulate` run from the scene the previous run ended in
(:meth:`~throwmap.engine.EngineRun.next_scene`).
"""

from __future__ import annotations


from ..errors import InvalidStateError
from ..records.outcome import Status
from ..records.session import PartState, SessionStep
from ..system.motion import ImpulseThrow, TiltTo, check_realisation
from ..system.pose import state_from_pose
from ..system.starts import check_omega
from ..system.system import System
from .pymunk import simulate
from .scene import Scene
from .settings import EngineSettings

__all__ = ["EngineSession"]


class EngineSession:
    """Parts of ``scene`` thrown again and again in pymunk (:class:`~throwmap.models.base.ThrowSession`).

    ``settings``: the :class:`~throwmap.engine.EngineSettings` of every run (None: the defaults; a step
    may pass its own); ``features``: the engine model's :class:`~throwmap.models.base.Features`;
    ``options``: the model's options value the session was opened with (its ``realisation``, if any, is
    the arm's motion of a throw given none); ``states``: one
    :class:`~throwmap.records.session.PartState` per part (with its pose); ``scene``: where the next
    run starts; ``last``: the last step's :class:`~throwmap.engine.EngineRun` (None before the first).
    """

    def __init__(self, scene: Scene, settings: EngineSettings | None = None, *, features=None, options=None,
                 model: str = "engine"):
        if not isinstance(scene, Scene):
            raise InvalidStateError("scene", f"must be a throwmap.engine.Scene, got {type(scene).__name__}")
        self.scene = scene
        self.settings = settings
        self.features = features
        self.options = options
        self.model = model
        self.parts = scene.parts
        self.status = Status.OK
        self.n_throws = 0
        self.last = None
        h = scene.arm.h
        self.states = tuple(PartState(*state_from_pose(p.part, p.arm_pose(h)), pose=tuple(p.arm_pose(h)))
                            for p in scene.placements)
        self._system = None

    @property
    def system(self) -> System:
        """The arm, its fixtures and its current rest angle α (rad)."""
        if self._system is None or self._system.alpha != self.scene.alpha:
            self._system = System(self.scene.arm, self.scene.fixtures, self.scene.alpha)
        return self._system

    @property
    def ended(self) -> bool:
        return self.status != Status.OK

    def throw(self, omega: float, motion=None, *, options=None, record: bool = False,
              settings: EngineSettings | None = None) -> SessionStep:
        """One throw at ``omega`` (rad/s): the impulse, or the arm's ``motion`` (a finite throw, the recoil
        arm); ``settings`` (or ``options.settings``) for this run only; ``record`` keeps its trajectory."""
        w = check_omega(omega)
        if motion is None:
            motion = getattr(options if options is not None else self.options, "realisation", None)
        real = ImpulseThrow(w) if motion is None else check_realisation(motion)
        if isinstance(real, TiltTo):
            raise InvalidStateError("motion", "a TiltTo turns the arm without a throw: use move()")
        self.n_throws += 1
        return self._step("throw", w, real, self._settings(options, settings), record)

    def move(self, motion, *, options=None, record: bool = False,
             settings: EngineSettings | None = None) -> SessionStep:
        """The arm turns to a new rest angle without a throw (``motion`` a :class:`~throwmap.system.motion.TiltTo`)."""
        if not isinstance(motion, TiltTo):
            raise InvalidStateError("motion", f"an arm move is a TiltTo, got {type(motion).__name__}")
        return self._step("move", 0.0, motion, self._settings(options, settings), record)

    def _settings(self, options, settings):
        if settings is not None:
            return settings
        if options is not None:
            return getattr(options, "settings", None)
        return self.settings

    def _step(self, kind: str, omega: float, real, settings, record: bool) -> SessionStep:
        if self.ended:
            raise InvalidStateError("session", f"the scene has ended ({self.status.label}): it takes no more steps")
        before = self.states
        system = self.system
        run = simulate(self.scene, real, settings, record=record)
        outcomes = []
        for i, s in enumerate(before):
            o = run.outcome(i, x0=s.x, side0=s.side, omega=omega, model=self.model)
            if system.alpha != 0.0 or system.fixtures:
                o = o.replace(alpha=float(system.alpha), fixtures=tuple(system.fixtures))
            outcomes.append(o)
        self.states = tuple(PartState(float(x), int(k), float(t), tuple(float(c) for c in q))
                            for (x, k, t), q in zip(run.states, run.poses))
        self.last = run
        status = Status(run.status)
        if status == Status.OK:
            self.scene = run.next_scene()
        else:
            self.status = status
        return SessionStep(kind, omega, None if kind == "throw" and real.impulsive else real, status,
                           tuple(outcomes), self.states, float(run.alpha), run.message, run, run.trajectory)

    def __repr__(self) -> str:
        where = ", ".join(f"(x={s.x:.4g} m, side {s.side})" for s in self.states)
        return (f"EngineSession({len(self.parts)} part{'s' if len(self.parts) != 1 else ''}, "
                f"α={self.scene.alpha:.4g} rad, {self.n_throws} throws, {self.status.label}: {where})")

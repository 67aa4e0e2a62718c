"""Model "engine": a full pymunk simulation of the throw (:mod:`throwmap.engine`).

The only model with fixtures (walls, cavities), an arm rest angle α and finite arm
motions (:class:`~throwmap.engine.FiniteThrow`, :class:`~throwmap.engine.RecoilThrow`).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import InvalidStateError, shown
from ..kernels import codes as C
from .base import BatchArrays, Features
from .registry import register

__all__ = ["EngineOptions", "EngineModel", "MODEL"]


@dataclass(frozen=True, slots=True)
class EngineOptions:
    """Options of the pymunk engine.

    ``settings``: :class:`~throwmap.engine.EngineSettings` (None: the defaults);
    ``realisation``: how the arm moves (None: the paper's impulse at the throw's ω;
    else :class:`~throwmap.engine.ImpulseThrow`, ``FiniteThrow``, ``RecoilThrow``, ``TiltTo``);
    ``friction``: :class:`~throwmap.engine.Friction` per pair of bodies (None: from the arm
    and fixtures); ``workers``: processes for a batch (1: this process, 0: all cores).
    """

    settings: object = None
    realisation: object = None
    friction: object = None
    workers: int | None = 1

    def __post_init__(self):
        w = self.workers
        if w is not None and (isinstance(w, bool) or not isinstance(w, int) or w < 0):
            raise InvalidStateError("workers", f"must be an integer ≥ 0 (0: all cores) or None, got {shown(w)}")
        if self.settings is not None or self.friction is not None:
            from ..engine.settings import EngineSettings, Friction  # no pymunk import

            for name, kind in (("settings", EngineSettings), ("friction", Friction)):
                v = getattr(self, name)
                if v is not None and not isinstance(v, kind):
                    raise InvalidStateError(
                        name, f"must be a throwmap.engine.{kind.__name__} (or None: the defaults), got {type(v).__name__}")

    def engine_keywords(self) -> dict:
        return {"settings": self.settings, "realisation": self.realisation, "friction": self.friction}


def engine_failures(status) -> str:
    """``"timeouts a/n, penetration refused b/n, unconverged refused c/n"`` over a batch's status codes,
    and ``", unresolved refused d/n"`` where throws reached the end of a simulated unbounded arm."""
    n = max(len(status), 1)
    text = (f"timeouts {int((status == C.TIMEOUT).sum())}/{n}, penetration refused {int((status == C.PENETRATION).sum())}/{n}, "
            f"unconverged refused {int((status == C.UNCONVERGED).sum())}/{n}")
    unresolved = int((status == C.UNRESOLVED).sum())
    return text + (f", unresolved refused {unresolved}/{n}" if unresolved else "")


class EngineModel:
    name = "engine"
    summary = ("a full pymunk simulation (throwmap.engine): any number of parts, fixtures (Wall, Cavity), an arm "
               "rest angle α that may change at a rate (TiltTo), and throw realisations (ImpulseThrow, FiniteThrow, "
               "RecoilThrow)")
    options_type = EngineOptions
    features = Features(fixtures=True, tilt=True, realisation=True, trajectory=True, friction=True, parallel=True,
                        pose=True, parts=0, moves=True, ensemble=False)

    @staticmethod
    def _keywords(system, o: EngineOptions) -> dict:
        return {"fixtures": system.fixtures, "alpha": system.alpha, **o.engine_keywords()}

    def throw_one(self, part, system, x, side, omega, o: EngineOptions):
        from ..engine import engine_run

        run = engine_run(part, system.arm, x, side, omega, **self._keywords(system, o))
        return run.states[0][0], run.states[0][1], int(run.statuses[0]), run.records[0]

    def outcome(self, part, system, x, side, omega, o: EngineOptions):
        """The engine's own :class:`~throwmap.ThrowOutcome` (its record carries engine-only fields)."""
        from ..engine import engine_throw

        return engine_throw(part, system.arm, x, side, omega, **self._keywords(system, o))

    def throw_batch(self, part, system, x, side, omega, valid, o: EngineOptions, progress=None):
        from ..engine import engine_batch

        res = engine_batch(part, system.arm, x, side, omega, valid=valid, workers=o.workers, progress=progress,
                           **self._keywords(system, o))
        return BatchArrays(res.x, res.side, res.status, res.records)

    def session(self, parts, system, states, o: EngineOptions):
        """An :class:`~throwmap.engine.session.EngineSession`: ``states`` are rests ``(x, side)`` (one per part) or
        an engine :class:`~throwmap.engine.Scene` on this system (parts, arm, fixtures and α as given)."""
        from ..engine import Friction, Placement, Scene
        from ..engine.session import EngineSession

        if isinstance(states, Scene):
            scene = states
        else:
            friction = Friction() if o.friction is None else o.friction
            scene = Scene(system.arm, tuple(Placement(p, x=x, side=k) for p, (x, k) in zip(parts, states)),
                          system.fixtures, system.alpha, friction)
        return EngineSession(scene, o.settings, features=self.features, options=o, model=self.name)

    def assumptions(self, records, mu, status) -> str:
        """Runs that did not finish: timeouts and refused penetrations (validation table)."""
        return engine_failures(status)

    def trajectory(self, part, system, x, side, omega, o: EngineOptions, dt):
        from ..engine import engine_trajectory

        # the engine samples at its own EngineSettings.record_dt, not at dt
        return engine_trajectory(part, system.arm, x, side, omega, **self._keywords(system, o))


MODEL = register(EngineModel())

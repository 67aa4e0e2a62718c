"""Model "engine": a full pymunk simulation of the throw (:mod:`throwmap.engine`).

The only model with fixtures (walls, cavities), an arm rest angle α and finite arm
motions (:class:`~throwmap.engine.FiniteThrow`, :class:`~throwmap.engine.RecoilThrow`).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import InvalidStateError, shown
from ..kernels import codes as C
from ..records.outcome import Status
from .base import BatchArrays, Features
from .engine_oracle import ENDED, ORACLE_TOL, disagrees, engine_settings_at, oracle_options, settle_disagreement
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
        out = self.outcome(part, system, x, side, omega, o)
        return out.x, out.side, int(out.status), out.record

    def outcome(self, part, system, x, side, omega, o: EngineOptions):
        """The engine's own :class:`~throwmap.ThrowOutcome` (its record carries engine-only fields), checked
        against the exact model where it applies (:mod:`.engine_oracle`)."""
        from ..engine import engine_run

        run = engine_run(part, system.arm, x, side, omega, **self._keywords(system, o))
        out = run.outcome(0, x0=x, side0=side, omega=omega)
        oracle = oracle_options(system, o)
        if oracle is None or run.verified or int(out.status) not in ENDED:
            return out
        xr, kr, sr, _rr = oracle[0].throw_one(part, system, x, side, omega, oracle[1])
        first = (out.x, out.side, int(out.status), run)
        if int(sr) not in ENDED or not disagrees(first[:3], (xr, kr, sr), ORACLE_TOL):
            return out
        xs, ks, ss, chosen, why = settle_disagreement(first, self._rerun(part, system, x, side, omega, o),
                                                      o.settings)
        if not why:
            return out
        return chosen.outcome(0, x0=x, side0=side, omega=omega).replace(status=Status(ss), message=why)

    def _rerun(self, part, system, x, side, omega, o: EngineOptions):
        """``(dt, coarse_dt) → (x, side, status, run)``: the same engine throw at another step."""
        from ..engine import engine_run

        def rerun(dt, coarse_dt):
            kw = self._keywords(system, o)
            kw["settings"] = engine_settings_at(o.settings, dt, coarse_dt)
            r = engine_run(part, system.arm, x, side, omega, **kw)
            return r.states[0][0], r.states[0][1], int(r.statuses[0]), r

        return rerun

    def throw_batch(self, part, system, x, side, omega, valid, o: EngineOptions, progress=None):
        from ..engine import engine_batch

        res = engine_batch(part, system.arm, x, side, omega, valid=valid, workers=o.workers, progress=progress,
                           **self._keywords(system, o))
        out = BatchArrays(res.x, res.side, res.status, res.records)
        oracle = oracle_options(system, o)
        if oracle is not None:
            self._check_batch(part, system, x, side, omega, valid, o, oracle, out)
        return out

    def _check_batch(self, part, system, x, side, omega, valid, o, oracle, out):
        """:meth:`outcome`'s check for every throw of a batch: the exact model's batch at once, the engine's reruns
        one by one where it disagrees (in place on ``out``)."""
        import numpy as np

        rb, ro = oracle
        ex = rb.throw_batch(part, system, x, side, omega, valid, ro)
        for i in np.flatnonzero(np.asarray(valid, dtype=bool)):
            first = (out.x[i], out.side[i], int(out.status[i]), None)
            if first[2] not in ENDED or int(ex.status[i]) not in ENDED:
                continue
            if not disagrees(first[:3], (ex.x[i], ex.side[i], ex.status[i]), ORACLE_TOL):
                continue
            xs, ks, ss, chosen, why = settle_disagreement(
                first, self._rerun(part, system, float(x[i]), int(side[i]), float(omega[i]), o), o.settings)
            out.x[i], out.side[i], out.status[i] = xs, ks, ss
            if why and chosen is not None:
                out.records[i] = chosen.records[0]

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
